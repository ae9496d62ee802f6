"""Specialised closed forms, each written from its own printed equation.

* Case A, flat centre (``R -> inf``): eqs. (pressure_distribution_compact_1),
  (consistency_cond_A), (vertical_equilibrium_A) and the rotational condition
  that follows it;
* Case C, no central segment (``b -> 0``): eqs. (pressure_distribution_compact_2),
  (consistency_cond_2), (vertical_equilibrium_2) and its rotational companion;
* Hertz: eqs. (pressure_distribution_Hertz) and (contact_law_Hertz);
* lift-off: eq. (Pctob) and the lever arm ``s_lift-off``.

The equilibrium equations are printed with the sign of ``P`` reversed (they
evaluate ``int p dx`` with ``p < 0``); here they return the compressive load
and moment. ``s_lift_off`` uses the corrected coefficient ``3a^2 - 4ab + b^2``.
See ``docs/ERRATA.md``. The tests check each against the general form
(:mod:`closedform.formulas`) in the limit, and against quadrature.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import xlogy

from .formulas import on_contact

__all__ = ["case_a_pressure", "case_a_tilt", "case_a_load", "case_a_moment",
           "case_c_pressure", "case_c_tilt", "case_c_load", "case_c_moment",
           "hertz_pressure", "hertz_half_width", "P_lift_off", "s_lift_off"]


def _arccos_pair(a: ArrayLike, c: ArrayLike, b: float) -> tuple[np.ndarray, np.ndarray]:
    a, c = np.asarray(a, float), np.asarray(c, float)
    return (np.arccos(np.clip((-a + 2 * b + c) / (a + c), -1, 1)),
            np.arccos(np.clip((a + 2 * b - c) / (a + c), -1, 1)))


def _xlog_ratio(g: np.ndarray, ratio_rest: np.ndarray) -> np.ndarray:
    """``g ln|g * ratio_rest|`` continuous at ``g = 0``."""
    return xlogy(g, np.abs(g)) + g * np.log(np.abs(ratio_rest))


# -- case A: R -> inf ------------------------------------------------------------
def case_a_pressure(a: ArrayLike, c: ArrayLike, b: float, R1: float, R2: float, A: float,
                    x: ArrayLike) -> np.ndarray:
    """Compressive pressure of case A, eq. (pressure_distribution_compact_1), 0 outside."""
    a, c, inside, x, w = on_contact(x, a, c)
    t1, t2 = _arccos_pair(a, c, b)
    d1 = (c - a) * (x - b) + 2 * (a * c + b * x) + 2 * np.sqrt((a - b) * (c + b) * (c - x) * (a + x))
    d2 = (c - a) * (x + b) + 2 * (a * c - b * x) + 2 * np.sqrt((a + b) * (c - b) * (c - x) * (a + x))
    val = (w * (t1 / R1 + t2 / R2)
           + _xlog_ratio(b + x, (a + c) / d1) / R1
           + _xlog_ratio(b - x, (a + c) / d2) / R2) / (np.pi * A)
    return np.where(inside, val, 0.0)


def case_a_tilt(a: ArrayLike, c: ArrayLike, b: float, R1: float, R2: float) -> np.ndarray:
    """Tilt of case A, eq. (consistency_cond_A)."""
    a, c = np.asarray(a, float), np.asarray(c, float)
    t1, t2 = _arccos_pair(a, c, b)
    return (np.sqrt((a - b) * (b + c)) / R1 + (a - 2 * b - c) / (2 * R1) * t1
            - np.sqrt((a + b) * (c - b)) / R2 + (a + 2 * b - c) / (2 * R2) * t2) / np.pi


def case_a_load(a: ArrayLike, c: ArrayLike, b: float, R1: float, R2: float, A: float) -> np.ndarray:
    """Compressive load of case A: eq. (vertical_equilibrium_A) with its sign corrected."""
    a, c = np.asarray(a, float), np.asarray(c, float)
    t1, t2 = _arccos_pair(a, c, b)
    rhs = (t1 / (2 * R1) + t2 / (2 * R2)
           - (-a + 2 * b + c) * np.sqrt((a - b) * (c + b)) / ((a + c) ** 2 * R1)
           - (a + 2 * b - c) * np.sqrt((a + b) * (c - b)) / ((a + c) ** 2 * R2))
    return rhs * (a + c) ** 2 / (4 * A)


def case_a_moment(a: ArrayLike, c: ArrayLike, b: float, R1: float, R2: float,
                  A: float) -> np.ndarray:
    """Moment ``P s`` of case A: the rotational condition after eq. (vertical_equilibrium_A).

    Sign corrected; ``(a-c) (a^2-2b^2+c^2)/(a-c)`` is written as ``a^2-2b^2+c^2``
    (the printed removable singularity at ``a = c``).
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    t1, t2 = _arccos_pair(a, c, b)
    X = a**2 - 2 * b**2 + c**2
    rhs = ((a - c) * (t1 / (4 * R1) + t2 / (4 * R2))
           + (X + (a - c) * (a - 2 * b - c) / 2) * np.sqrt((a - b) * (c + b)) / (3 * (a + c) ** 2 * R1)
           - (X + (a - c) * (a + 2 * b - c) / 2) * np.sqrt((a + b) * (c - b)) / (3 * (a + c) ** 2 * R2))
    return -rhs * (a + c) ** 2 / (4 * A)


# -- case C: b -> 0 ---------------------------------------------------------------
def case_c_pressure(a: ArrayLike, c: ArrayLike, R1: float, R2: float, A: float,
                    x: ArrayLike) -> np.ndarray:
    """Compressive pressure of case C, eq. (pressure_distribution_compact_2), 0 outside."""
    a, c, inside, x, w = on_contact(x, a, c)
    den = 2 * a * c + (c - a) * x + 2 * np.sqrt(a * c * (c - x) * (a + x))
    val = (w * ((1 / R1 + 1 / R2) * np.pi / 2 + (1 / R1 - 1 / R2) * np.arcsin((a - c) / (a + c)))
           + (1 / R1 - 1 / R2) * _xlog_ratio(x, (a + c) / den)) / (np.pi * A)
    return np.where(inside, val, 0.0)


def case_c_tilt(a: ArrayLike, c: ArrayLike, R1: float, R2: float) -> np.ndarray:
    """Tilt of case C, eq. (consistency_cond_2)."""
    a, c = np.asarray(a, float), np.asarray(c, float)
    g = np.arcsin((a - c) / (a + c))
    return ((1 / R1 - 1 / R2) * np.sqrt(a * c) / np.pi
            + (1 / R1 - 1 / R2) * (a - c) / (2 * np.pi) * g + (1 / R1 + 1 / R2) * (a - c) / 4)


def case_c_load(a: ArrayLike, c: ArrayLike, R1: float, R2: float, A: float) -> np.ndarray:
    """Compressive load of case C: eq. (vertical_equilibrium_2) with its sign corrected."""
    a, c = np.asarray(a, float), np.asarray(c, float)
    g = np.arcsin((a - c) / (a + c))
    rhs = ((1 / R1 - 1 / R2) * (c - a) * np.sqrt(a * c) / (a + c) ** 2
           - 0.5 * (1 / R1 - 1 / R2) * g - (1 / R1 + 1 / R2) * np.pi / 4)
    return -rhs * (a + c) ** 2 / (4 * A)


def case_c_moment(a: ArrayLike, c: ArrayLike, R1: float, R2: float, A: float) -> np.ndarray:
    """Moment ``P s`` of case C: the rotational condition after eq. (vertical_equilibrium_2).

    Sign corrected; ``(a-c)(a^2+c^2)/(a-c)`` is written as ``a^2+c^2``.
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    g = np.arcsin((a - c) / (a + c))
    rhs = ((1 / R1 - 1 / R2) * 4 * np.sqrt(a * c) / (a + c) ** 2
           * (a**2 + c**2 + (a - c) ** 2 / 2)
           + (a - c) * ((1 / R1 - 1 / R2) * 3 * g + (1 / R1 + 1 / R2) * 3 * np.pi / 2)) / 12
    return -rhs * (a + c) ** 2 / (4 * A)


# -- Hertz ------------------------------------------------------------------------
def hertz_pressure(a: float, R1: float, A: float, x: ArrayLike) -> np.ndarray:
    """Compressive Hertz pressure ``sqrt(a^2 - x^2)/(A R1)``, eq. (pressure_distribution_Hertz)."""
    x = np.asarray(x, float)
    return np.sqrt(np.clip(a**2 - x**2, 0, None)) / (A * R1)


def hertz_half_width(P: ArrayLike, R1: float, A: float) -> np.ndarray:
    """``a = sqrt(2PAR1/pi)`` from eq. (contact_law_Hertz), sign corrected."""
    return np.sqrt(2 * np.asarray(P, float) * A * R1 / np.pi)


# -- lift-off -----------------------------------------------------------------------
def P_lift_off(a: ArrayLike, b: float, R1: float, R: float, A: float) -> np.ndarray:
    """Load at lift-off ``c = b``, eq. (Pctob) with its sign corrected."""
    a = np.asarray(a, float)
    k1 = 1 - R1 / R
    t = np.arccos(np.clip((3 * b - a) / (a + b), -1, 1))
    return ((a + b) ** 2 * (k1 / R1 * t + np.pi / R)
            + k1 / R1 * 2 * (a - 3 * b) * np.sqrt(2 * b * (a - b))) / (8 * A)


def s_lift_off(a: ArrayLike, b: float, R1: float, R: float) -> np.ndarray:
    """Lever arm at lift-off ``c = b`` (eq. after Pctob), corrected.

    The printed coefficient ``3a^2 - 4ab + 3b^2`` is ``3a^2 - 4ab + b^2``; the
    printed ``arccos[-(a-3b)/(a+c)]`` has ``c = b``. Written with ``1/R`` so
    that ``R = inf`` is allowed.
    """
    a = np.asarray(a, float)
    k1 = 1 - R1 / R
    t = np.arccos(np.clip((3 * b - a) / (a + b), -1, 1))
    root = np.sqrt(b * (a - b))
    num = (a - b) * (2 * np.sqrt(2) * b * k1 / root * (3 * a**2 - 4 * a * b + b**2)
                     + 3 * (a + b) ** 2 * (k1 * t + np.pi * R1 / R))
    den = 6 * ((a + b) ** 2 * (k1 * t + np.pi * R1 / R) + 2 * np.sqrt(2) * k1 * (a - 3 * b) * root)
    return -num / den

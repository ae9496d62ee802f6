"""Pressure as a sine series in θ, with optional closed-form kink terms.

The bounded solution on ``[m - h, m + h]`` is ``p = Σ_{k≥1} g_k sin kθ`` with
``x = m + h cos θ`` (:mod:`sie.projection`). A slope kink at ``s_b = cos θ_b``
contributes coefficients whose leading part is
``-(2/π) sin θ_b cos kθ_b / (k^2 - 1)``; its sum is the log-singular function

    Σ_{k≥2} cos kθ_b sin kθ / (k^2 - 1) = [S(θ + θ_b) + S(θ - θ_b)] / 2,
    S(φ) = Σ_{k≥2} sin kφ / (k^2 - 1) = sin φ (1/4 - ln|2 sin(φ/2)|),

which carries the ``(x ∓ b) ln|x ∓ b|`` terms of the pressure. The identity
follows from ``Σ cos jφ / j = -ln|2 sin(φ/2)|``; it is checked against direct
summation in the tests.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["sine_series", "log_kink", "ChebyshevPressure"]


def sine_series(g: ArrayLike, theta: ArrayLike) -> np.ndarray:
    """``Σ_{k=1}^{n} g_k sin kθ`` by Clenshaw's recurrence for ``sin θ Σ g_k U_{k-1}(cos θ)``.

    Parameters
    ----------
    g
        Coefficients ``g_1..g_n`` (``g[0]`` multiplies ``sin θ``).
    theta
        Angles, any shape.
    """
    g = np.asarray(g, dtype=float)
    theta = np.asarray(theta, dtype=float)
    x2 = 2.0 * np.cos(theta)
    b1 = np.zeros_like(theta)
    b2 = np.zeros_like(theta)
    for gk in g[::-1]:
        b1, b2 = gk + x2 * b1 - b2, b1
    return np.sin(theta) * b1


def log_kink(phi: ArrayLike) -> np.ndarray:
    """``S(φ) = Σ_{k≥2} sin kφ/(k^2 - 1) = sin φ (1/4 - ln|2 sin(φ/2)|)``, with ``S(2πj) = 0``."""
    phi = np.asarray(phi, dtype=float)
    s = np.abs(2.0 * np.sin(0.5 * phi))
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.sin(phi) * (0.25 - np.log(s))
    return np.where(s > 0, out, 0.0)


@dataclass(frozen=True)
class ChebyshevPressure:
    """A bounded pressure ``p(x)`` on ``[m - h, m + h]``, zero outside.

    ``p = Σ g_k sin kθ + Σ_j w_j [S(θ + θ_j) + S(θ - θ_j)]`` with ``x = m + h cos θ``.

    Attributes
    ----------
    m, h
        Centre and half-width of the loaded interval.
    g
        Sine coefficients ``g_1..g_n`` (pressure units).
    kinks
        Pairs ``(w_j, θ_j)`` of closed-form kink terms (empty for plain collocation).
    """

    m: float
    h: float
    g: np.ndarray = field(repr=False, compare=False)
    kinks: tuple[tuple[float, float], ...] = ()

    def __call__(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        s = (x - self.m) / self.h
        # the open interval by its ends, as the result reports them (a = h - m, c = h + m):
        # exactly 0 at and beyond them, whatever the rounding of (x - m)/h
        inside = (x > self.m - self.h) & (x < self.m + self.h) & (np.abs(s) < 1.0)
        theta = np.arccos(np.clip(s, -1.0, 1.0))
        p = sine_series(self.g, theta)
        for w, tb in self.kinks:
            p = p + w * (log_kink(theta + tb) + log_kink(theta - tb))
        return np.where(inside, p, 0.0)

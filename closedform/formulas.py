"""Forward closed forms of the general three-part punch for a given contact ``[-a, c]``.

Every function is pure and vectorised over ``a``, ``c`` (and ``x``). They are the
paper's equations written in the angles of the join points, which makes them
free of cancellation near lift-off and of the removable singularities at
``a = c``, ``x = ±b`` and ``R -> inf``:

* ``h = (a+c)/2`` and ``m = (c-a)/2`` are the half-width and centre of the contact;
* ``beta1 = arccos[(2b+c-a)/(a+c)]`` and ``beta2 = arccos[(2b+a-c)/(a+c)]`` are the
  arccos arguments of eq. (f0), so that ``sqrt((a-b)(b+c)) = h sin(beta1)`` and
  ``sqrt((a+b)(c-b)) = h sin(beta2)``;
* ``kappa1 = k1/R1``, ``kappa2 = k2/R2`` and ``kappa0 = 1/R`` (see :class:`Punch`).

Signs follow the README: ``P > 0`` compressive, pressure positive in compression,
``s`` the pressure centroid. The paper's printed equilibrium expressions carry
the opposite sign of ``P`` (see ``docs/ERRATA.md``).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from threepart.problem.punch import Punch

from .kernel import chi_v as _chi
from .kernel import f0_v as _f0
from .kernel import pressure_v as _pressure
from .kernel import psi_v as _psi

__all__ = ["beta", "F0", "load", "tilt", "moment", "lever_arm", "pressure",
           "F1", "F2", "F3"]


def beta(a: ArrayLike, c: ArrayLike, b: float) -> tuple[np.ndarray, np.ndarray]:
    """``beta1 = arccos[(2b-(a-c))/(a+c)]``, ``beta2 = arccos[((a-c)+2b)/(a+c)]`` (eq. f0).

    Evaluated as ``2 arctan2(sqrt(a-b), sqrt(c+b))``, exact to rounding also
    when the contact edge is at the join (``a -> b``).
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    # an edge at the join may sit a rounding error inside it: clipped, never NaN
    return (2 * np.arctan2(np.sqrt(np.maximum(a - b, 0.0)), np.sqrt(c + b)),
            2 * np.arctan2(np.sqrt(np.maximum(c - b, 0.0)), np.sqrt(a + b)))


def F0(punch: Punch, a: ArrayLike, c: ArrayLike) -> np.ndarray:
    """``F0 = k1/R1 beta1 + k2/R2 beta2 + pi/R`` (eq. f0), the angles of :func:`beta`.

    Compiled point by point (:data:`closedform.kernel.f0_v`): a microsecond on floats.
    """
    return np.asarray(_f0(punch.b, punch.kappa0, punch.kappa1, punch.kappa2, a, c))


def load(punch: Punch, a: ArrayLike, c: ArrayLike, A: ArrayLike) -> np.ndarray:
    """Compressive load ``P = -int p dx`` (eq. equilibrium_condition_1, sign corrected).

    ``8AP = (a+c)^2 F0 + 2 k1/R1 (a-2b-c) sqrt((a-b)(b+c))
    - 2 k2/R2 (a+2b-c) sqrt((a+b)(c-b))``, which in the angles reads
    ``AP = h^2/4 [k1/R1 (2 beta1 - sin 2beta1) + k2/R2 (2 beta2 - sin 2beta2) + 2pi/R]``.
    The printed equation has the opposite overall sign.
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    h = 0.5 * (a + c)
    b1, b2 = beta(a, c, punch.b)
    return (0.25 * h**2 * (punch.kappa1 * _psi(b1) + punch.kappa2 * _psi(b2)
                           + 2 * np.pi * punch.kappa0)) / np.asarray(A, float)


def tilt(punch: Punch, a: ArrayLike, c: ArrayLike) -> np.ndarray:
    """Tilt ``alpha`` from the consistency condition (eq. consistency_condition).

    ``2 pi alpha = k1/R1 [(a-2b-c) beta1 + 2 sqrt((a-b)(b+c))]
    + k2/R2 [(a+2b-c) beta2 - 2 sqrt((a+b)(c-b))] + pi (a-c)/R``, i.e.
    ``pi alpha = h [k1/R1 (sin b1 - b1 cos b1) - k2/R2 (sin b2 - b2 cos b2)] - pi m/R``.
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    b1, b2 = beta(a, c, punch.b)
    return h * (punch.kappa1 * _chi(b1) - punch.kappa2 * _chi(b2)) / np.pi - m * punch.kappa0


def moment(punch: Punch, a: ArrayLike, c: ArrayLike, A: ArrayLike) -> np.ndarray:
    """Moment ``P s = -int p x dx`` of the compressive pressure (eq. equilibrium_condition_2).

    Equivalent to the printed equation with the sign of ``P`` corrected, and
    free of its removable ``1/(a-c)``::

        6A P (s - m) = k2/R2 ((a+b)(c-b))^(3/2) - k1/R1 ((a-b)(b+c))^(3/2)
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    b1, b2 = beta(a, c, punch.b)
    A = np.asarray(A, float)
    lever = h**3 * (punch.kappa2 * np.sin(b2) ** 3 - punch.kappa1 * np.sin(b1) ** 3) / 6
    return m * load(punch, a, c, A) + lever / A


def lever_arm(punch: Punch, a: ArrayLike, c: ArrayLike) -> np.ndarray:
    """Lever arm ``s = moment/load`` (independent of ``A``)."""
    return moment(punch, a, c, 1.0) / load(punch, a, c, 1.0)


def on_contact(x: ArrayLike, a: ArrayLike, c: ArrayLike
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(a, c, inside, x_clipped, w)`` for evaluating a pressure at ``x`` on ``[-a, c]``.

    ``inside`` is the open contact (the pressure is exactly 0 at and beyond the
    edges); ``w = sqrt((x+a)(c-x))`` at the clipped ``x``.
    """
    x = np.asarray(x, float)
    a, c = np.asarray(a, float), np.asarray(c, float)
    xi = np.clip(x, -a, c)
    return a, c, (x > -a) & (x < c), xi, np.sqrt((xi + a) * (c - xi))


def pressure(punch: Punch, a: ArrayLike, c: ArrayLike, A: ArrayLike, x: ArrayLike) -> np.ndarray:
    """Compressive pressure ``-p(x)`` of eq. (pressure_abbreviated); 0 outside ``[-a, c]``.

    Collecting the terms of F1, F2 and F3 (appendix) by their logarithms, the
    coefficients of ``alpha`` and F2 cancel identically and

    ``-p(x) = [w F0 + k1/R1 (x+b) F1(x) + k2/R2 (x-b) F3(x)] / (pi A)``,

    where ``(x±b) ln|x±b|`` is continuous at the joins. ``a``, ``c`` (and ``A``)
    broadcast against ``x``. Evaluated point by point, compiled
    (:func:`closedform.kernel.pressure_v`): a scalar costs a microsecond, as the
    least-pressure searches need.
    """
    return np.asarray(_pressure(x, a, c, A, F0(punch, a, c), punch.kappa1, punch.kappa2, punch.b))


# -- the appendix's F-functions, as printed (for the errata checks) ------------
def _N1(x: np.ndarray, a: np.ndarray, c: np.ndarray, b: float) -> np.ndarray:
    return (2 * np.sqrt((c - x) * (a + x) * (a - b) * (c + b)) + 2 * (a * c + b * x)
            + (a - c) * (b - x))


def _N3(x: np.ndarray, a: np.ndarray, c: np.ndarray, b: float) -> np.ndarray:
    return (2 * np.sqrt((c - x) * (a + x) * (a + b) * (c - b)) + 2 * (a * c - b * x)
            - (a - c) * (b + x))


def _floats(*values: ArrayLike) -> list[np.ndarray]:
    return [np.asarray(v, dtype=float) for v in values]


def F1(x: ArrayLike, a: ArrayLike, c: ArrayLike, b: float) -> np.ndarray:
    """``F1(x) = ln|(b+x)(c+a)/N1|`` = ``w(x) int_{-a}^{-b} dt/(w(t)(t-x))`` (appendix)."""
    x, a, c = _floats(x, a, c)
    return np.log(np.abs((b + x) * (c + a) / _N1(x, a, c, b)))


def F2(x: ArrayLike, a: ArrayLike, c: ArrayLike, b: float) -> np.ndarray:
    """``F2(x) = ln|N1 (b-x) / (N3 (b+x))|`` = ``w(x) int_{-b}^{b} dt/(w(t)(t-x))``."""
    x, a, c = _floats(x, a, c)
    return np.log(np.abs(_N1(x, a, c, b) * (b - x) / (_N3(x, a, c, b) * (b + x))))


def F3(x: ArrayLike, a: ArrayLike, c: ArrayLike, b: float) -> np.ndarray:
    """``F3(x) = -ln|(b-x)(c+a)/N3|`` = ``w(x) int_{b}^{c} dt/(w(t)(t-x))``."""
    x, a, c = _floats(x, a, c)
    return -np.log(np.abs((b - x) * (c + a) / _N3(x, a, c, b)))

"""Partial slip by the Ciavarella–Jäger theorem (paper section "Application of a shear force").

The shear traction is the sliding traction ``f p(x)`` minus a corrective
traction ``f p*(x)`` on the stick zone ``[-(d+e), d-e]``, where ``p*`` is the
normal pressure of the same punch, with the same tilt ``alpha``, on the contact
``a* = d+e``, ``c* = d-e`` (eq. integral_equation_2). The two side conditions are

* horizontal equilibrium (eq. horizontal_equilibrium):
  ``P(a*, c*) = P - |Q|/f``, with eq. (equilibrium_condition_1);
* consistency (eq. consistency_condition): ``alpha(a*, c*) = alpha``.

With ``Q`` of either sign, ``q(x) = sign(Q) f [p(x) - p*(x)]`` integrates to ``Q``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from . import formulas
from threepart.errors import FullSlidingError, NoConvergenceError, StickZoneError
from threepart.validate import check_finite, check_positive
from .newton import SCALAR, State, solve_hm_scalar
from .normal import tilt_residual
from threepart.results import NormalResult, SlipResult

__all__ = ["SlipSolution", "solve_partial_slip", "stick_zone_bound"]


@dataclass(frozen=True)
class SlipSolution(SlipResult):
    """Closed-form partial-slip solution."""

    method: str = "closedform"

    def shear(self, x: ArrayLike) -> np.ndarray:
        n = self.normal
        corrective = formulas.pressure(n.punch, self.d + self.e, self.d - self.e, n.A, x)
        return math.copysign(self.f, self.Q) * (n.pressure(x) - corrective) if self.Q else \
            np.zeros(np.shape(x))


def _slip_iv(normal: NormalResult, Q: float, f: float) -> None:
    if not isinstance(normal, NormalResult):
        raise TypeError(f"`normal_solution` must be a NormalResult, not {type(normal).__name__}")
    check_finite(Q=Q)
    check_positive(f=f)
    if abs(Q) >= f * normal.P:
        raise FullSlidingError(
            f"|`Q`| = {abs(Q):.6g} >= f P = {f * normal.P:.6g} (`f` = {f:g}, `P` = {normal.P:.6g}): "
            "the contact slides as a whole (full sliding), there is no stick zone")


def stick_zone_bound(normal: NormalResult) -> float:
    """Largest ``|Q|/(fP)`` for which the stick zone still covers ``[-b, b]``.

    The stick zone shrinks with ``|Q|`` along ``alpha(a*, c*) = alpha``; the
    bound is where one of its ends reaches a join (``c* = b`` or ``a* = b``).
    Returns 1 when neither end reaches a join before full sliding.
    """
    punch, b, alpha = normal.punch, normal.punch.b, normal.alpha
    best = 0.0  # the largest corrective load at which an end reaches a join
    for sigma, far in ((-1.0, normal.a), (1.0, normal.c)):
        hs = np.linspace(b, 0.5 * (far + b), 257)[1:]
        if hs.size == 0 or hs[-1] <= b:
            continue
        g = State(punch, hs, sigma * (hs - b)).alpha - alpha
        cross = np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) <= 0)
        for i in cross:
            h = brentq(lambda t: float(State(punch, t, sigma * (t - b), SCALAR).alpha - alpha),
                       hs[i], hs[i + 1], xtol=1e-15 * hs[i + 1], rtol=1e-15)
            best = max(best, State(punch, h, sigma * (h - b), SCALAR).AP / (normal.A * normal.P))
    return 1.0 - best


def solve_partial_slip(normal_solution: NormalResult, Q: float, f: float) -> SlipSolution:
    """Stick zone ``[-(d+e), d-e]`` and shear ``q(x)`` for a shear force ``Q``, ``|Q| < f P``.

    The stick zone keeps the normal solution's tilt ``alpha``.

    Raises
    ------
    FullSlidingError
        ``|Q| >= f P``.
    StickZoneError
        The stick zone would end inside the central segment; the message gives
        the ``|Q|/(fP)`` bound of the closed form.
    NoConvergenceError
        The Newton iteration failed.
    """
    normal = normal_solution
    _slip_iv(normal, Q, f)
    punch, A, b = normal.punch, normal.A, normal.punch.b
    h, m = 0.5 * (normal.a + normal.c), 0.5 * (normal.c - normal.a)
    ratio = abs(Q) / (f * normal.P)
    AP_t = A * (normal.P - abs(Q) / f)
    r = math.sqrt(1.0 - ratio)
    res = tilt_residual(punch, AP_t, normal.alpha, h)
    hs, ms, ok = solve_hm_scalar(punch, res, b + (h - b) * r, m * r)
    if not ok:
        bound = stick_zone_bound(normal)
        if ratio >= bound:
            raise StickZoneError(
                f"`Q`/(f P) = {ratio:.6g}: the stick zone would end inside the central segment "
                f"[-b, b] = [{-b:g}, {b:g}], where the closed form does not hold; it holds for "
                f"|Q|/(f P) < {bound:.6g}")
        raise NoConvergenceError(f"the stick zone did not converge for Q = {Q!r}, f = {f!r}")
    return SlipSolution(normal=normal, Q=float(Q), f=float(f), d=hs, e=-ms)

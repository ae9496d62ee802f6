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

from . import formulas
from threepart.errors import FullSlidingError, StickZoneError
from threepart.validate import finite, positive
from .newton import HALF_PI, SCALAR, bracketed_root, ray_state, solve_phi
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


def _slip_iv(normal: NormalResult, Q: float, f: float) -> tuple[float, float]:
    if not isinstance(normal, NormalResult):
        raise TypeError(f"`normal_solution` must be a NormalResult, not {type(normal).__name__}")
    Q, f = finite("Q", Q), positive("f", f)
    if abs(Q) >= f * normal.P:
        raise FullSlidingError(
            f"|`Q`| = {abs(Q):.6g} >= f P = {f * normal.P:.6g} (`f` = {f:g}, `P` = {normal.P:.6g}): "
            "the contact slides as a whole (full sliding), there is no stick zone")
    return Q, f


def stick_zone_bound(normal: NormalResult) -> float:
    """Largest ``|Q|/(fP)`` for which the stick zone still covers ``[-b, b]``.

    The stick zone shrinks with ``|Q|`` at the normal solution's tilt; the
    bound is where one of its ends reaches a join. On the ray ``c* = b``
    (``phi = 0``) the tilt grows from 0 with the zone's size, on ``a* = b``
    (``phi = pi/2``) it falls from 0, so the join is reached on the ray
    whose tilt has the sign of ``alpha``; there the zone's radius is a
    bracketed root. Returns ``1 - P_0/P`` for ``alpha = 0`` (both ends reach
    their joins together) and 1 when the zone never reaches a join.
    """
    punch, A, alpha = normal.punch, normal.A, normal.alpha
    P0 = 0.5 * math.pi * punch.kappa0 * punch.b**2 / A
    if punch.b == 0:
        return 1.0
    if alpha == 0:
        return max(1.0 - P0 / normal.P, 0.0) if P0 > 0 else 1.0
    phi, sign = (0.0, 1.0) if alpha > 0 else (HALF_PI, -1.0)

    def fun(r: float) -> tuple[float, float]:
        st = ray_state(punch, r, phi, SCALAR)
        cos2 = math.cos(2 * phi)
        return sign * (st.alpha - alpha), sign * r * (st.alpha_h - cos2 * st.alpha_m)

    r0 = math.sqrt(normal.a + normal.c)
    r, _, above = bracketed_root(fun, r0, 0.0, math.inf, SCALAR)
    P_star = ray_state(punch, r, phi, SCALAR).AP / A
    return min(max(1.0 - P_star / normal.P, 0.0), 1.0)


def solve_partial_slip(normal_solution: NormalResult, Q: float, f: float) -> SlipSolution:
    """Stick zone ``[-(d+e), d-e]`` and shear ``q(x)`` for a shear force ``Q``, ``|Q| < f P``.

    The stick zone keeps the normal solution's tilt ``alpha``: its ends solve
    ``P(a*, c*) = P - |Q|/f`` (eq. horizontal_equilibrium with eq.
    equilibrium_condition_1) and ``alpha(a*, c*) = alpha`` (eq.
    consistency_condition) by the bracketed roots of
    :mod:`threepart.closedform.newton`.

    Raises
    ------
    FullSlidingError
        ``|Q| >= f P``.
    StickZoneError
        The stick zone would end inside the central segment; the message gives
        the ``|Q|/(fP)`` bound of the closed form.
    """
    normal = normal_solution
    Q, f = _slip_iv(normal, Q, f)
    punch, A = normal.punch, normal.A
    ratio = abs(Q) / (f * normal.P)
    dAP = A * (normal.P - abs(Q) / f) - 0.5 * math.pi * punch.kappa0 * punch.b**2
    inside = dAP > 0
    if inside:
        r, phi, below, above = solve_phi(punch, dAP, "tilt", normal.alpha, SCALAR, sign=-1.0)
        inside = not (below or above)
    if not inside:
        b = punch.b
        raise StickZoneError(
            f"`Q`/(f P) = {ratio:.6g}: the stick zone would end inside the central segment "
            f"[-b, b] = [{-b:g}, {b:g}], where the closed form does not hold; it holds for "
            f"|Q|/(f P) < {stick_zone_bound(normal):.6g}")
    st = ray_state(punch, r, phi, SCALAR)
    return SlipSolution(normal=normal, Q=Q, f=f, d=st.h, e=-st.m)

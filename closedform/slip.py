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
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from scipy.optimize import minimize_scalar

from . import formulas
from threepart.halfplane.bulk import check_sigma_bulk, corrective_tilt, slip_direction_margin
from threepart.errors import SlipReversalError, StickSeparationError, StickZoneError
from threepart.results.slip import check_shear
from .newton import HALF_PI, SCALAR, bracketed_root, ray_state, solve_phi
from threepart.results import Diagnostics, NormalResult, SlipResult

__all__ = ["SlipSolution", "solve_partial_slip", "stick_zone_bound", "coulomb_margin",
           "check_coulomb", "COULOMB_RTOL", "stick_zone_leaves", "stick_zones_on_path",
           "check_slip_direction"]

#: ``p*`` may dip below 0 (or above ``p``) by this fraction of the mean pressure ``P/(a+c)``
#: before the stick zone is refused: the closed forms' rounding, with a wide margin
COULOMB_RTOL = 1e-9
#: grid points per segment piece on which a minimum is bracketed before Brent refines it
_GRID = 65


@dataclass(frozen=True)
class SlipSolution(SlipResult):
    """Closed-form partial-slip solution."""

    method: str = "closedform"

    def shear(self, x: ArrayLike) -> np.ndarray:
        n = self.normal
        corrective = formulas.pressure(n.punch, self.d + self.e, self.d - self.e, n.A, x)
        return math.copysign(self.f, self.Q) * (n.pressure(x) - corrective) if self.Q else \
            np.zeros(np.shape(x))


def least_on(fun, lo: float, hi: float) -> tuple[float, float]:
    """``(x, fun(x))`` at the least value of ``fun`` on ``[lo, hi]``: a grid brackets it, Brent refines.

    ``fun`` is smooth on ``[lo, hi]`` (one segment of the punch), so the least
    grid point's neighbours bracket the minimum, found to ``1e-12 (hi - lo)``.
    """
    xg = np.linspace(lo, hi, _GRID)
    v = fun(xg)
    i = int(np.argmin(v))
    best = (float(xg[i]), float(v[i]))
    left, right = xg[max(i - 1, 0)], xg[min(i + 1, xg.size - 1)]
    if right > left:
        r = minimize_scalar(lambda t: float(fun(np.array([t]))[0]), bounds=(left, right),
                            method="bounded", options={"xatol": 1e-12 * (hi - lo)})
        if r.fun < best[1]:
            best = (float(r.x), float(r.fun))
    return best


def coulomb_margin(normal: NormalResult, a_star: float, c_star: float
                   ) -> tuple[tuple[float, float], tuple[float, float]]:
    """Least ``p*`` and least ``p - p*`` on the stick zone ``[-a*, c*]``, with their positions.

    ``|q| = f |p - p*| <= f p`` on the stick zone holds exactly when both are
    ``>= 0``. ``p*`` is eq. (pressure_abbreviated) on ``[-a*, c*]`` and ``p``
    the normal solution's pressure; both are smooth on each segment, so each
    piece of the stick zone between the joins ``x = ±b`` (ends and joins
    included) is searched by :func:`least_on`.

    Returns
    -------
    (x, p*_min), (x, (p - p*)_min)
    """
    punch, A = normal.punch, normal.A
    cuts = sorted({-a_star, c_star, *(t for t in (-punch.b, punch.b) if -a_star < t < c_star)})

    def p_star(x: np.ndarray) -> np.ndarray:
        return formulas.pressure(punch, a_star, c_star, A, x)

    def excess(x: np.ndarray) -> np.ndarray:
        return normal.pressure(x) - p_star(x)

    out = []
    for fun in (p_star, excess):
        out.append(min((least_on(fun, lo, hi) for lo, hi in zip(cuts[:-1], cuts[1:])),
                       key=lambda t: t[1]))
    return out[0], out[1]


def check_coulomb(normal: NormalResult, a_star: float, c_star: float, ratio: float) -> None:
    """Refuse a stick zone ``[-a*, c*]`` whose shear would break Coulomb's law.

    The Ciavarella–Jäger shear ``q = f (p - p*)`` obeys ``|q| <= f p`` only if
    ``0 <= p* <= p`` on the stick zone. A convex or flat centre (``R > 0``)
    satisfies it by construction: its corrective pressure is a contact
    pressure of a convex profile, positive, and grows with the load. A
    concave centre can fail, so there it is checked at the exact minima
    (:func:`coulomb_margin`); ``ratio`` is ``|Q|/(fP)``, for the message.

    Raises
    ------
    StickSeparationError
        If ``p* < 0`` or ``p* > p`` somewhere on the stick zone (beyond
        :data:`COULOMB_RTOL` of the mean pressure).
    """
    if normal.punch.kappa0 >= 0 or normal.punch.b == 0:
        return
    (x1, pmin), (x2, emin) = coulomb_margin(normal, a_star, c_star)
    tol = COULOMB_RTOL * normal.P / (normal.a + normal.c)
    if pmin >= -tol and emin >= -tol:
        return
    why = (f"its corrective pressure p* = {pmin:.4g} < 0 at x = {x1:.6g}, so |q| > f p there"
           if pmin < -tol else
           f"its corrective pressure exceeds p by {-emin:.4g} at x = {x2:.6g}, so q changes sign there")
    raise StickSeparationError(
        f"`Q`/(f P) = {ratio:.6g}: the single stick zone [{-a_star:.6g}, {c_star:.6g}] of the "
        f"Ciavarella–Jäger superposition on the concave centre R = {normal.punch.R:g} breaks "
        f"Coulomb's law: {why}; the true stick zone is not this single interval (it splits in "
        "two or rests on one flank)")


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


def stick_zones_on_path(normal: NormalResult, Q: float, f: float, sigma_bulk: float,
                        lam: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ends ``(a*, c*)`` of the stick zones at the fractions ``lam`` of ``(Q, sigma_bulk)``, and a flag.

    The load ``P - lam |Q|/f`` (eq. horizontal_equilibrium, eq.
    equilibrium_condition_1) at the tilt ``alpha*`` of
    :func:`threepart.halfplane.bulk.corrective_tilt` (eq. consistency_condition), by the
    vectorised bracketed roots of :mod:`closedform.newton`. ``lam = 0`` is the
    contact itself. The flag is True where the stick zone would end on the
    central segment (outside the closed form).
    """
    punch, A = normal.punch, normal.A
    lam = np.atleast_1d(np.asarray(lam, dtype=float))
    dAP = A * (normal.P - lam * abs(Q) / f) - 0.5 * math.pi * punch.kappa0 * punch.b**2
    alpha_star = corrective_tilt(normal.alpha, A, Q if Q else 1.0, f, lam * sigma_bulk)
    out = ~(dAP > 0)
    safe = np.where(out, A * normal.P, dAP)
    r, phi, below, above = solve_phi(punch, safe, "tilt", alpha_star, np, sign=-1.0)
    st = ray_state(punch, r, phi, np)
    zero = lam == 0
    out = (out | below | above) & ~zero
    return np.where(zero, normal.a, st.a), np.where(zero, normal.c, st.c), out


def check_slip_direction(normal: NormalResult, Q: float, f: float, sigma_bulk: float) -> None:
    """Refuse a bulk stress that reverses the slip anywhere on the load path (:class:`SlipReversalError`).

    The least of :func:`threepart.halfplane.bulk.slip_direction_margin` over the load
    fraction ``lam`` in ``[0, 1]`` (a grid brackets it, Brent refines it,
    :func:`least_on`, where the grid's least is within 5 % of ``|Q|/π`` of
    zero) must be ``>= 0``; at ``lam = 0`` it is
    ``|Q|/π - |sigma_bulk| (a + c)/8``. The message gives the largest
    ``|sigma_bulk|`` of the same sign that passes at this ``Q`` (bisection).
    """
    if sigma_bulk == 0:
        return
    least, end = _least_margin(normal, Q, f, sigma_bulk)
    if least >= -1e-12 * abs(Q):
        return
    lo, hi = 0.0, 1.0
    for _ in range(24):        # the bound to ~1e-7, on the grid alone
        mid = 0.5 * (lo + hi)
        if _least_margin(normal, Q, f, mid * sigma_bulk, refine=False)[0] >= 0:
            lo = mid
        else:
            hi = mid
    raise SlipReversalError(
        f"`sigma_bulk` = {sigma_bulk:.6g} reverses the slip at the {end} end of the contact with "
        f"`Q` = {Q:.6g} rising in proportion (the Ciavarella–Jäger superposition does not hold); "
        f"it holds for |sigma_bulk| <= {abs(lo * sigma_bulk):.6g} of the same sign at this `Q`")


def _least_margin(normal: NormalResult, Q: float, f: float, sigma_bulk: float,
                  refine: bool = True) -> tuple[float, str]:
    """Least slip-direction margin over the load path, and at which end (``"left"``/``"right"``).

    ``refine=False`` takes the least grid value only (for the bisection of the bound).
    """
    def both(lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a_s, c_s, out = stick_zones_on_path(normal, Q, f, sigma_bulk, lam)
        gl, gr = slip_direction_margin(Q, sigma_bulk, normal.a, normal.c, -a_s, c_s)
        big = abs(Q) if Q else 1.0       # not counted (outside the framework); finite for Brent
        return np.where(out, big, gl), np.where(out, big, gr)

    gl, gr = both(np.linspace(0.0, 1.0, _GRID))
    grid = (float(gl.min()), "left") if gl.min() < gr.min() else (float(gr.min()), "right")
    # Brent refines only a grid minimum within 5 % of |Q|/π of zero (as _check_separation)
    if not refine or grid[0] > 0.05 * abs(Q) / math.pi:
        return grid
    left = least_on(lambda t: both(t)[0], 0.0, 1.0)
    right = least_on(lambda t: both(t)[1], 0.0, 1.0)
    return (left[1], "left") if left[1] < right[1] else (right[1], "right")


#: bisection steps of :func:`_bound`, and how many of them one call of the vectorised roots takes
_BOUND_STEPS, _BOUND_TREE = 60, 5


def _bound(normal: NormalResult, Q: float, f: float, sigma_bulk: float) -> float:
    """Largest ``|Q|/(fP)`` (``sigma_bulk`` in proportion) at which the stick zone covers ``[-b, b]``.

    A bisection on the load fraction, :data:`_BOUND_STEPS` steps; every midpoint the next
    :data:`_BOUND_TREE` steps could probe (``2^5 - 1``, each halving exactly as a step would)
    goes to :func:`stick_zones_on_path` at once, and the bisection walks their flags.
    """
    if sigma_bulk == 0:
        return stick_zone_bound(normal)
    lo, hi = 0.0, 1.0
    rest = _BOUND_STEPS % _BOUND_TREE
    for depth in [_BOUND_TREE] * (_BOUND_STEPS // _BOUND_TREE) + ([rest] if rest else []):
        nodes, mids = [(lo, hi)], []
        for _ in range(depth):            # the tree of midpoints, level by level (node i: 2i+1, 2i+2)
            mids += [0.5 * (a + b) for a, b in nodes]
            nodes = [pair for a, b in nodes for pair in ((a, 0.5 * (a + b)), (0.5 * (a + b), b))]
        flags = stick_zones_on_path(normal, Q, f, sigma_bulk, mids)[2]
        i = 0
        for _ in range(depth):
            if flags[i]:
                hi, i = mids[i], 2 * i + 1
            else:
                lo, i = mids[i], 2 * i + 2
    return lo * abs(Q) / (f * normal.P)


def solve_partial_slip(normal_solution: NormalResult, Q: float, f: float, *,
                       sigma_bulk: float = 0.0) -> SlipSolution:
    """Stick zone ``[-(d+e), d-e]`` and shear ``q(x)`` for a shear force ``Q``, ``|Q| < f P``.

    The corrective contact ``p*`` carries the load ``P - |Q|/f`` (eq.
    horizontal_equilibrium with eq. equilibrium_condition_1) at the tilt
    ``alpha* = alpha - sign(Q) A sigma_bulk/(4 f)`` (eq. consistency_condition;
    ``alpha* = alpha`` without a bulk stress), solved by the bracketed roots
    of :mod:`threepart.closedform.newton` (docs/BULK_STRESS.md).

    Parameters
    ----------
    normal_solution
        The normal problem (any method) in the closed form's framework.
    Q
        Shear force the punch exerts on the substrate, along +x, ``|Q| < f P``.
    f
        Coefficient of friction, > 0.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q`` (tension positive),
        applied with ``Q`` in proportion after the normal load. Its strain is
        ``A sigma_bulk/4``: ``A`` must be that of an elastically similar pair,
        ``4(1 - nu^2)/E`` (eq. 4), as the uncoupled partial-slip problem assumes.

    Raises
    ------
    FullSlidingError
        ``|Q| >= f P``.
    StickZoneError
        The stick zone would end inside the central segment; the message gives
        the ``|Q|/(fP)`` bound of the closed form.
    SlipReversalError
        ``sigma_bulk`` reverses the slip at one end somewhere on the load path
        (:func:`check_slip_direction`); the message gives the bound on ``|sigma_bulk|``.
    """
    normal = normal_solution
    Q, f = check_shear(normal, Q, f, argument="normal_solution")
    sigma_bulk = check_sigma_bulk(sigma_bulk, normal, Q)
    t0 = time.perf_counter()
    punch = normal.punch
    ratio = abs(Q) / (f * normal.P)
    a_s, c_s, out = stick_zones_on_path(normal, Q, f, sigma_bulk, [1.0])
    check_slip_direction(normal, Q, f, sigma_bulk)
    if out[0]:
        raise StickZoneError(
            f"`Q`/(f P) = {ratio:.6g}: the stick zone would {stick_zone_leaves(punch.b)}, where the closed "
            f"form does not hold; it holds for |Q|/(f P) < {_bound(normal, Q, f, sigma_bulk):.6g}"
            + (f" (with `sigma_bulk` in proportion, {sigma_bulk:g} at this Q)" if sigma_bulk else ""))
    a_star, c_star = float(a_s[0]), float(c_s[0])
    check_coulomb(normal, a_star, c_star, ratio)
    return SlipSolution(normal=normal, Q=Q, f=f, d=0.5 * (a_star + c_star), e=0.5 * (a_star - c_star),
                        sigma_bulk=sigma_bulk,
                        diagnostics=Diagnostics(timings={"total": time.perf_counter() - t0}))


def stick_zone_leaves(b: float) -> str:
    """Where a stick zone outside the closed form ends: on the centre, or short of the join (b = 0)."""
    if b == 0:
        return "not contain the join x = 0 of the two arcs (it lies on one arc)"
    return f"end inside the central segment [-b, b] = [{-b:g}, {b:g}]"

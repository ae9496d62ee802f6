"""Bracketed Newton iterations for the inverse problems, on floats and on arrays alike.

Every inverse problem of the closed form is two nested one-dimensional roots,
each kept inside a bracket, so that an iteration cannot leave the admissible
set or stall:

* the contact edges are written ``a = b + u1^2``, ``c = b + u2^2`` with
  ``u1 = r cos(phi)``, ``u2 = r sin(phi)``: ``phi = 0`` is the lift-off line
  ``c = b``, ``phi = pi/2`` the line ``a = b``, and every ``(r, phi)`` with
  ``r >= 0``, ``0 <= phi <= pi/2`` is an admissible contact;
* the **inner** root is the radius ``r`` at which the load (eq.
  equilibrium_condition_1) takes its value, at a fixed ``phi``; its lower
  bracket ``r = 0`` is the contact ``[-b, b]``, whose load ``A P_0 = pi b^2/(2R)``
  lies below every admissible load;
* the **outer** root is the angle ``phi`` at which a second equation holds at
  that load: the lever arm (eq. equilibrium_condition_2, tilt free), the
  tilt ``alpha = 0`` (eq. consistency_condition, tilt suppressed), or the
  normal solution's tilt (the stick zone). Its bracket ``[0, pi/2]`` is the
  lift-off range itself: a target outside it is refused, not iterated on.

:func:`bracketed_root` is safeguarded Newton (Newton steps inside the
bracket, bisection otherwise), written once for Python floats
(``xp=SCALAR``, a single case in microseconds) and numpy arrays (a batch).
:class:`State` evaluates the closed forms in the join angles with their
exact ``(h, m)`` derivatives, from ``u1, u2`` so that ``a - b`` and ``c - b``
carry no cancellation near lift-off or near ``P_0``.
"""
from __future__ import annotations

import functools
import math
from typing import Any, Callable

import numpy as np

from threepart.problem.punch import Punch

from . import kernel

__all__ = ["State", "SCALAR", "bracketed_root", "ray_state", "solve_r", "solve_phi",
           "HALF_PI", "MAX_ITER", "EVALUATIONS", "evaluations", "XTOL", "XTOL_RANGE"]

HALF_PI = 0.5 * math.pi
MAX_ITER = 200          # bisection alone needs ~60 on a double-precision bracket
#: relative Newton step (error ~ its square) or bracket width at which to stop: the default of
#: every root finder's ``xtol`` (``closedform.solve_normal(..., xtol=...)``)
XTOL = 1e-12
#: the range of ``xtol`` a caller may ask for: below 1e-15 a step is rounding; above 1e-6 the
#: root's error (about its square) would pass 1e-12, coarser than the closed form claims
XTOL_RANGE = (1e-15, 1e-6)


class _Scalar:
    """The few array functions the iterations need, on Python floats."""

    sqrt, arctan2, sin, cos, isfinite = math.sqrt, math.atan2, math.sin, math.cos, math.isfinite

    @staticmethod
    def maximum(x: float, y: float) -> float:
        return x if x > y else y

    @staticmethod
    def minimum(x: float, y: float) -> float:
        return x if x < y else y

    @staticmethod
    def where(cond: bool, x: Any, y: Any) -> Any:
        return x if cond else y

    @staticmethod
    def logical_not(x: bool) -> bool:
        return not x

    @staticmethod
    def all(x: bool) -> bool:
        return bool(x)

    @staticmethod
    def abs(x: float) -> float:
        return abs(x)


SCALAR: Any = _Scalar


#: forward evaluations made so far, counted per case (a :class:`State` of n cases counts n);
#: read the difference around a solve (:func:`evaluations`)
EVALUATIONS = [0]


def evaluations() -> int:
    """The number of forward evaluations (cases times :class:`State` constructions) made so far."""
    return EVALUATIONS[0]


class State:
    """Closed forms (with ``A = 1``) and their ``(h, m)`` derivatives at ``a = b + u1^2``, ``c = b + u2^2``.

    ``h = (a+c)/2`` and ``m = (c-a)/2`` are the contact's half-width and centre;
    ``xp`` is :mod:`numpy` for arrays (``u1`` and ``u2`` broadcast) or :data:`SCALAR`
    for Python floats. The values are :func:`closedform.kernel.state`'s (the one
    home of these formulas, compiled), one attribute per :data:`~closedform.kernel.FIELDS`.

    Attributes
    ----------
    a, c, h, m
        The contact.
    AP, dAP
        ``A P`` (eq. equilibrium_condition_1, compressive) and ``A (P - P_0)``
        with ``A P_0 = pi b^2/(2R)``, the latter free of cancellation.
    F0
        Eq. (f0).
    T
        ``A P s``, the moment (eq. equilibrium_condition_2, compressive).
    alpha
        The tilt (eq. consistency_condition).
    AP_h, AP_m, T_h, T_m, alpha_h, alpha_m
        Their derivatives in ``h`` and ``m``.
    """

    a: Any
    c: Any
    h: Any
    m: Any
    dAP: Any
    AP: Any
    AP_h: Any
    AP_m: Any
    F0: Any
    T: Any
    T_h: Any
    T_m: Any
    alpha: Any
    alpha_h: Any
    alpha_m: Any

    def __init__(self, punch: Punch, u1: Any, u2: Any, xp: Any = np) -> None:
        const = _constants(punch)
        if xp is SCALAR:
            EVALUATIONS[0] += 1
            values: Any = kernel.state(*const, float(u1), float(u2))
        else:
            u1, u2 = np.broadcast_arrays(np.asarray(u1, dtype=float), np.asarray(u2, dtype=float))
            EVALUATIONS[0] += u1.size
            rows = kernel.states(*const, np.ravel(u1), np.ravel(u2))
            values = [row.reshape(u1.shape) if u1.ndim else row[0] for row in rows]
        self.__dict__.update(zip(kernel.FIELDS, values))     # one attribute per field


@functools.lru_cache(maxsize=64)
def _constants(punch: Punch) -> tuple[float, float, float, float]:
    """``(b, kappa0, kappa1, kappa2)`` of a punch (cached: the punch is frozen)."""
    return punch.b, punch.kappa0, punch.kappa1, punch.kappa2


def ray_state(punch: Punch, r: Any, phi: Any, xp: Any = np) -> State:
    """:class:`State` at ``u1 = r cos(phi)``, ``u2 = r sin(phi)``.

    ``cos(phi)`` is evaluated as ``sin(pi/2 - phi)``: exact zeros on the
    lift-off lines, and ``u1 == u2`` to the last bit at ``phi = pi/4``, so
    that a symmetric case has ``alpha = 0`` exactly.
    """
    return State(punch, r * xp.sin(HALF_PI - phi), r * xp.sin(phi), xp)


def _guarded_ratio(num: Any, den: Any, xp: Any) -> Any:
    """``num/den`` where ``den > 0``, NaN elsewhere (no division warnings, no ZeroDivisionError)."""
    ok = den > 0
    return xp.where(ok, num / xp.where(ok, den, 1.0), math.nan)


def bracketed_root(fun: Callable[[Any], tuple[Any, Any]], x: Any, lo: Any, hi: Any, xp: Any,
                   *, lo_known: Any = True, hi_known: Any = False,
                   max_iter: int = MAX_ITER, atol: float = 0.0, xtol: float = XTOL
                   ) -> tuple[Any, Any, Any]:
    """Root of an increasing ``fun`` in ``[lo, hi]`` by Newton steps safeguarded by bisection.

    Parameters
    ----------
    fun
        ``x -> (f, df/dx)``, elementwise; ``f`` increases with ``x``.
    x
        Starting point, inside ``[lo, hi]``.
    lo, hi
        The bracket; ``hi`` may be ``inf`` (an unbounded bracket is expanded
        by doubling).
    lo_known, hi_known
        Whether ``f(lo) < 0`` (``f(hi) >= 0``) is known. An unknown end is
        evaluated when a step would leave the bracket; if its sign is wrong,
        the root lies outside ``[lo, hi]`` and the case is flagged.
    xtol
        Relative Newton step or bracket width at which to stop (default :data:`XTOL`;
        the root's error is about its square).
    atol
        Absolute step or bracket width at which to stop, besides the relative
        ``xtol``: a root at ``x = 0`` (an angle ``phi`` at a join, where ``f`` is
        rounding) has no relative width, and bisection towards it never closed.

    Returns
    -------
    x, below, above
        The root; and the flags ``f(lo) >= 0`` (no root in the bracket, it lies
        below ``lo``) and ``f(hi) < 0`` (it lies above ``hi``), where ``x`` is
        the end that was evaluated.

    Raises
    ------
    NoConvergenceError
        If ``fun`` is not finite, or the bracket has not closed within
        ``max_iter`` iterations (it closes in at most about 60 bisections,
        so this signals a function that is not continuous).
    """
    from threepart.errors import NoConvergenceError

    lo0, hi0 = lo, hi
    below = above = xp.where(True, False, False)
    done = below
    for _ in range(max_iter):
        f, df = fun(x)
        if not xp.all(xp.isfinite(f)):
            raise NoConvergenceError("bracketed Newton iteration: the function is not finite at "
                                     f"{str(x)[:80]}; no result is returned")
        neg = f < 0
        below = below | (x == lo0) & xp.logical_not(neg) & xp.logical_not(lo_known)
        above = above | (x == hi0) & neg & xp.logical_not(hi_known)
        lo, lo_known = xp.where(neg, x, lo), lo_known | neg
        hi, hi_known = xp.where(neg, hi, x), hi_known | xp.logical_not(neg)
        newton = x - _guarded_ratio(f, df, xp)
        inside = (newton > lo) & (newton < hi)
        # outside the bracket: bisect a closed bracket, else try the unknown end
        fallback = xp.where(lo_known & hi_known, 0.5 * (lo + hi),
                            xp.where(lo_known, xp.where(xp.isfinite(hi), hi, 2 * x + (x == 0)), lo))
        tol = xp.maximum(xtol * xp.abs(x), atol)
        small = xp.abs(newton - x) <= tol          # a converged Newton step (NaN is not small)
        xn = xp.where(inside | small, newton, fallback)
        stop = below | above | (f == 0)
        close = small | (lo_known & hi_known & (hi - lo <= tol))
        x = xp.where(done | stop, x, xn)
        done = done | stop | close
        if xp.all(done):
            return x, below, above
    raise NoConvergenceError(f"bracketed Newton iteration: the bracket did not close in {max_iter} "
                             "steps")


def solve_r(punch: Punch, dAP: Any, phi: Any, r0: Any, xp: Any = np, xtol: float = XTOL) -> Any:
    """Radius ``r`` at which ``A (P - P_0) = dAP`` along the ray ``phi`` (inner root).

    ``r = 0`` is the contact ``[-b, b]`` with ``A (P - P_0) = 0 < dAP``; the load
    grows without bound with ``r``, so the root is bracketed.
    """
    cos2 = xp.cos(2 * phi)

    def fun(r: Any) -> tuple[Any, Any]:
        st = ray_state(punch, r, phi, xp)
        return st.dAP - dAP, r * (st.AP_h - cos2 * st.AP_m)

    return bracketed_root(fun, r0, 0.0 * r0, math.inf + 0.0 * r0, xp, xtol=xtol)[0]


#: the outer equations: name -> (state -> (value, d value/dh, d value/dm))
_TARGETS: dict[str, Callable[[State], tuple[Any, Any, Any]]] = {
    "moment": lambda st: (st.T, st.T_h, st.T_m),
    "tilt": lambda st: (st.alpha, st.alpha_h, st.alpha_m),
}


def solve_phi(punch: Punch, dAP: Any, target: str, value: Any, xp: Any = np,
              sign: float = 1.0, r0: Any = None, xtol: float = XTOL) -> tuple[Any, Any, Any, Any]:
    """Angle ``phi`` in ``[0, pi/2]`` at which ``target`` equals ``value`` at the load ``dAP``.

    ``target`` is ``"moment"`` (``A P s``, increasing in ``phi``) or ``"tilt"``
    (``alpha``, decreasing: pass ``sign = -1``). A two-dimensional Newton
    iteration in ``(r, phi)`` on both equations at once (:func:`_newton_2d`)
    answers every case it brings to a root strictly inside the lift-off
    range, which is the only root there; the other cases (few, and those
    outside the range) go to the nested, bracketed roots of
    :func:`_solve_phi_nested`, which decide a refusal as before.

    Returns
    -------
    r, phi, below, above
        The solution, and the flags of :func:`bracketed_root`: ``below``
        (the target lies below the value at ``phi = 0``, the line ``c = b``)
        and ``above`` (beyond ``phi = pi/2``, the line ``a = b``).
    """
    r, phi, ok = _newton_2d(punch, dAP, target, value, xp, sign, r0, xtol)
    if xp is SCALAR:
        return (r, phi, False, False) if ok else _solve_phi_nested(punch, dAP, target, value, xp, sign, r0,
                                                                    xtol)
    if ok.all():
        false = np.zeros(np.shape(ok), dtype=bool)
        return r, phi, false, false.copy()
    below, above = np.zeros(np.shape(ok), dtype=bool), np.zeros(np.shape(ok), dtype=bool)
    todo = ~ok
    pick = (lambda v: v[todo] if np.ndim(v) else v)
    r[todo], phi[todo], below[todo], above[todo] = _solve_phi_nested(
        punch, pick(dAP), target, pick(value), xp, sign, None if r0 is None else pick(r0), xtol)
    return r, phi, below, above


#: most iterations of the two-dimensional Newton step before a case goes to the nested roots
NEWTON_2D_ITER = 16
#: the outer equations of :func:`solve_phi`, as :func:`closedform.kernel.newton_2d` names them
_KERNEL_TARGET = {"moment": kernel.MOMENT, "tilt": kernel.TILT}


def _newton_2d(punch: Punch, dAP: Any, target: str, value: Any, xp: Any, sign: float,
               r0: Any, xtol: float = XTOL) -> tuple[Any, Any, Any]:
    """Newton's method in ``(r, phi)`` on the load and ``target`` equations together, ``phi`` bracketed.

    The iteration is :func:`closedform.kernel.newton_2d` (compiled; a batch is its
    loop over the cases): one forward evaluation per step gives both residuals and
    the exact Jacobian, the step is the nested iteration's in one, and a case
    counts as solved (``ok``) only when its full step is below ``xtol``, or at the
    rounding floor, with ``0 < phi < pi/2``; the system has one root there, so a
    converged case is that root. The rest go to :func:`_solve_phi_nested`. About 8
    evaluations per case (``NormalBatch.evaluations``; 31 for the nested roots alone).

    Returns
    -------
    r, phi, ok
    """
    const = _constants(punch)
    which = _KERNEL_TARGET[target]
    phi0 = _phi_guess(punch)
    if xp is SCALAR:
        r = r_guess(punch, dAP, xp) if r0 is None else r0
        r, phi, ok, n = kernel.newton_2d(*const, float(dAP), which, float(value), float(sign), float(r),
                                         phi0, float(xtol), NEWTON_2D_ITER)
        EVALUATIONS[0] += n
        return r, phi, ok
    dAP = np.asarray(dAP, dtype=float)
    shape = dAP.shape
    r = r_guess(punch, dAP, np) if r0 is None else r0

    def flat(v: Any) -> np.ndarray:
        return np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), shape)).ravel()

    r, phi, ok, n = kernel.newton_2d_many(*const, flat(dAP), which, flat(value), float(sign), flat(r), phi0,
                                          float(xtol), NEWTON_2D_ITER)
    EVALUATIONS[0] += n
    return r.reshape(shape), phi.reshape(shape), ok.reshape(shape)


@functools.lru_cache(maxsize=64)
def _phi_guess(punch: Punch) -> float:
    """Starting angle: ``tan^2 phi = (c - b)/(a - b) = sqrt(R2/R1)``, the untilted contact of two parabolas.

    Two parabolas of radii ``R1`` and ``R2`` pressed without tilt reach about
    equal heights ``(a - b)^2/R1 = (c - b)^2/R2`` at the contact's ends.
    """
    return math.atan((punch.R2 / punch.R1) ** 0.25)


def _solve_phi_nested(punch: Punch, dAP: Any, target: str, value: Any, xp: Any = np,
                      sign: float = 1.0, r0: Any = None, xtol: float = XTOL) -> tuple[Any, Any, Any, Any]:
    """Angle ``phi`` in ``[0, pi/2]`` at which ``target`` equals ``value`` at the load ``dAP``.

    ``target`` is ``"moment"`` (``A P s``, increasing in ``phi``) or ``"tilt"``
    (``alpha``, decreasing: pass ``sign = -1``). The radius follows ``phi``
    through :func:`solve_r`, warm-started from the previous iterate, and the
    derivative along the constant-load curve is exact:
    ``dr/dphi = -(dAP/dphi)/(dAP/dr)``. Returns ``r, phi, below, above`` as :func:`solve_phi`.
    """
    get = _TARGETS[target]
    if r0 is None:
        r0 = solve_r(punch, dAP, HALF_PI / 2 + 0.0 * dAP, r_guess(punch, dAP, xp), xp, xtol)
    radius = [r0]

    def fun(phi: Any) -> tuple[Any, Any]:
        r = solve_r(punch, dAP, phi, radius[0], xp, xtol)
        radius[0] = r
        st = ray_state(punch, r, phi, xp)
        cos2, sin2 = xp.cos(2 * phi), xp.sin(2 * phi)
        g, g_h, g_m = get(st)
        # along the constant-load curve: h_r = r, m_r = -r cos2, m_phi = r^2 sin2
        ap_r = r * (st.AP_h - cos2 * st.AP_m)
        r_phi = xp.where(ap_r > 0, -_guarded_ratio(st.AP_m * r * r * sin2, ap_r, xp), 0.0)
        dg = g_m * r * r * sin2 + r * (g_h - cos2 * g_m) * r_phi
        return sign * (g - value), sign * dg

    # an angle: its absolute xtol closes a bracket on phi = 0 (a stick-zone end on a join, issue 29)
    phi, below, above = bracketed_root(fun, HALF_PI / 2 + 0.0 * dAP, 0.0 * dAP, HALF_PI + 0.0 * dAP,
                                       xp, lo_known=False, hi_known=False, atol=xtol, xtol=xtol)
    r = solve_r(punch, dAP, phi, radius[0], xp, xtol)
    return r, phi, below, above


def r_guess(punch: Punch, dAP: Any, xp: Any) -> Any:
    """Starting radius: the Hertz half-width on the mean edge curvature, ``r^2 = 2 (h - b)``."""
    k = 0.5 * (1.0 / punch.R1 + 1.0 / punch.R2)
    return xp.sqrt(2 * xp.sqrt(2 * dAP / (math.pi * k)))

"""Inverse normal problem: contact extent and tilt for given loads.

* :func:`solve_normal` -- ``a, c, alpha`` for ``P`` and ``s`` (tilt free), or
  ``a_hat, c_hat`` and the tilt-suppressing lever arm ``s*`` (tilt suppressed);
* :func:`solve_normal_batch` -- the same for arrays of load cases at once;
* :func:`lift_off` -- the admissible lever arms ``[s_min, s_max]`` for a load ``P``
  (eq. Pctob and the lift-off lever arm, with the sign of ``P`` corrected).

All of them solve the consistency condition (eq. consistency_condition) and the
equilibrium conditions (eqs. equilibrium_condition_1, _2) with the vectorised
Newton iteration of :mod:`closedform.newton`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from . import formulas
from threepart.errors import LiftOffError, NoConvergenceError, SeparationError
from threepart.punch import Punch
from threepart.validate import check_finite, check_positive
from .newton import SCALAR, State, newton1d, newton1d_scalar, pick, solve_hm, solve_hm_scalar
from threepart.results import NormalResult

__all__ = ["NormalSolution", "NormalBatch", "LiftOff", "solve_normal", "solve_normal_batch",
           "lift_off", "P_min"]

TILTS = ("free", "suppressed")


@dataclass(frozen=True)
class NormalSolution(NormalResult):
    """Closed-form normal solution; ``pressure`` is eq. (pressure_abbreviated)."""

    method: str = "closedform"

    def pressure(self, x: ArrayLike) -> np.ndarray:
        return formulas.pressure(self.punch, self.a, self.c, self.A, x)


@dataclass(frozen=True)
class NormalBatch:
    """Arrays of solutions of :func:`solve_normal_batch` (same punch and ``A``)."""

    punch: Punch
    A: float
    a: np.ndarray
    c: np.ndarray
    alpha: np.ndarray
    P: np.ndarray
    s: np.ndarray
    tilt: str

    def __len__(self) -> int:
        return self.a.size

    def __getitem__(self, i: int) -> NormalSolution:
        return NormalSolution(self.punch, self.A, float(self.a[i]), float(self.c[i]),
                              float(self.alpha[i]), float(self.P[i]), float(self.s[i]), self.tilt)


@dataclass(frozen=True)
class LiftOff:
    """Admissible lever arms ``s_min < s < s_max`` for the load ``P``.

    At ``s_min`` (load to the left) the right edge reaches the join, ``c = b``,
    with the left edge at ``-a_min``; at ``s_max`` the left edge does, ``a = b``,
    with the right edge at ``c_max``.
    """

    P: float
    s_min: float
    s_max: float
    a_min: float
    c_max: float


def P_min(punch: Punch, A: float) -> float:
    """Load at which a convex centre (``R > 0``) first touches at both joins: ``pi b^2/(2AR)``.

    Below it the contact lies inside the central segment, outside the paper's
    solution. Zero for flat and concave centres.
    """
    return max(np.pi * punch.b**2 * punch.kappa0 / (2 * A), 0.0)


# -- input validation ----------------------------------------------------------
def _normal_iv(punch: Punch, P: np.ndarray, A: float, tilt: str) -> None:
    if not isinstance(punch, Punch):
        raise TypeError(f"`punch` must be a Punch, not {type(punch).__name__}")
    check_positive(A=A)
    if tilt not in TILTS:
        raise ValueError(f"`tilt` = {tilt!r} must be one of {TILTS}")
    bad = ~np.isfinite(P) | (P <= 0)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"`P` = {float(P.flat[i])!r} must be a finite compressive load > 0")
    pmin = P_min(punch, A)
    low = P <= pmin
    if low.any():
        i = int(np.argmax(low))
        raise LiftOffError(
            f"`P` = {P.flat[i]:.6g} is at or below P_min = pi b^2/(2AR) = {pmin:.6g}, the load at "
            f"which the convex centre (R = {punch.R:g}) first touches both joins x = ±b; below it the "
            "contact lies inside the central segment, outside the closed form")


# -- (h, m) helpers ----------------------------------------------------------------
def _along(punch: Punch, AP: Any, sigma: Any, xp: Any = np) -> Any:
    """Half-width ``h`` with ``A P(h, m) = AP`` on the line ``m = sigma (h - b)``.

    ``sigma = 0`` is the centred contact, ``-1`` the lift-off line ``c = b`` and
    ``+1`` the line ``a = b``. ``P(h)`` rises from ``P_min`` at ``h = b``.
    """
    b = punch.b

    def g(h: Any, idx: Any = None) -> tuple[Any, Any]:
        sg = pick(sigma, idx)
        st = State(punch, h, sg * (h - b), xp)
        return st.AP - pick(AP, idx), st.AP_h + sg * st.AP_m

    # start: a Hertz half-width on the mean curvature, beyond the central segment
    k = max(0.5 * (punch.kappa1 + punch.kappa2) + punch.kappa0,
            0.25 * (punch.kappa1 + punch.kappa2))
    x0 = b + xp.sqrt(2 * AP / (math.pi * k))
    if xp is SCALAR:
        return newton1d_scalar(g, x0, float(b), what="contact half-width")
    return newton1d(g, x0, np.full_like(x0, b), what="contact half-width")


def _lift_off_states(punch: Punch, AP: np.ndarray) -> tuple[State, State]:
    """Lift-off states for loads ``AP``: ``c = b`` (first) and ``a = b`` (second)."""
    n = AP.size
    sigma = np.r_[np.full(n, -1.0), np.full(n, 1.0)]
    h = _along(punch, np.r_[AP, AP], sigma)
    m = sigma * (h - punch.b)
    return State(punch, h[:n], m[:n]), State(punch, h[n:], m[n:])


def _free_residual(AP_t: Any, Ts_t: Any, href: Any):
    def res(st: State, idx: Any):
        P, T, hr = pick(AP_t, idx), pick(Ts_t, idx), pick(href, idx)
        return (st.AP / P - 1, (st.T - T) / (P * hr),
                st.AP_h / P, st.AP_m / P, st.T_h / (P * hr), st.T_m / (P * hr))
    return res


def tilt_residual(punch: Punch, AP_t: Any, alpha_t: Any, href: Any):
    """Residual for a given load and a given tilt (suppressed tilt, stick zone)."""
    kscale = abs(punch.kappa1) + abs(punch.kappa2) + abs(punch.kappa0)

    def res(st: State, idx: Any):
        P, al, scale = pick(AP_t, idx), pick(alpha_t, idx), kscale * pick(href, idx)
        return (st.AP / P - 1, (st.alpha - al) / scale,
                st.AP_h / P, st.AP_m / P, st.alpha_h / scale, st.alpha_m / scale)
    return res


def _solve_hm(punch: Punch, AP: Any, s: Any, tilt: str, xp: Any) -> tuple[Any, Any, Any]:
    """``(h, m, converged)`` of the normal problem, on floats or arrays.

    The free-tilt start shifts the centred contact by the linearised lever arm,
    ``m0 = (s - s0)/(ds/dm)``, kept inside the admissible set.
    """
    h0 = _along(punch, AP, 0.0 * AP, xp)
    if tilt == "free":
        st0 = State(punch, h0, 0.0 * h0, xp)
        s0 = st0.T / st0.AP
        dsdm = (st0.T_m - s0 * st0.AP_m) / st0.AP
        room = 0.9 * (h0 - punch.b) if punch.b > 0 else 0.9 * h0
        m0 = xp.maximum(xp.minimum((s - s0) / dsdm, room), -room)
        res = _free_residual(AP, AP * s, h0)
    else:
        m0 = 0.0 * h0
        res = tilt_residual(punch, AP, 0.0 * AP, h0)
    if xp is SCALAR:
        return solve_hm_scalar(punch, res, h0, m0)
    return solve_hm(punch, res, h0, m0)


def _fail(punch: Punch, P: np.ndarray, s: np.ndarray, A: float, tilt: str,
          ok: np.ndarray) -> None:
    """Explain a failed solve: a lever arm past lift-off, or a genuine non-convergence."""
    bad = np.flatnonzero(~ok)
    if tilt == "free":
        lo, hi = _lift_off_states(punch, A * P[bad])
        _check_lever(P[bad], s[bad], lo.T / lo.AP, hi.T / hi.AP)
    i = bad[0]
    raise NoConvergenceError(
        f"the normal problem did not converge for `P` = {P[i]:.6g}, `s` = {s[i]:.6g} "
        f"(tilt {tilt}) on {punch}")


def _check_lever(P: np.ndarray, s: np.ndarray, s_lo: np.ndarray, s_hi: np.ndarray) -> None:
    for side, over, lim, edge in (("right", s >= s_hi, s_hi, "left edge reaches the join, a -> b"),
                                  ("left", s <= s_lo, s_lo, "right edge reaches the join, c -> b")):
        if over.any():
            i = int(np.argmax(over))
            word = "exceeds" if side == "right" else "is below"
            raise LiftOffError(
                f"`s` = {s.flat[i]:.6g} {word} the lift-off lever arm {lim.flat[i]:.6g} for "
                f"`P` = {P.flat[i]:.6g} (the {edge}); admissible: "
                f"{s_lo.flat[i]:.6g} < s < {s_hi.flat[i]:.6g}")


def _check_separation(punch: Punch, a: np.ndarray, c: np.ndarray, A: float, P: np.ndarray,
                      s: np.ndarray) -> None:
    """A concave centre must not separate: the pressure stays >= 0 on ``[-b, b]``."""
    if punch.kappa0 >= 0 or punch.b == 0:
        return
    xg = np.linspace(-punch.b, punch.b, 129)
    p = formulas.pressure(punch, a[:, None], c[:, None], A, xg[None, :])
    imin = np.argmin(p, axis=1)
    pmin = p[np.arange(a.size), imin]
    scale = P / (a + c)
    for i in np.flatnonzero(pmin < 0.05 * scale):
        lo, hi = xg[max(imin[i] - 1, 0)], xg[min(imin[i] + 1, xg.size - 1)]
        r = minimize_scalar(lambda x: float(formulas.pressure(punch, a[i], c[i], A, x)),
                            bounds=(lo, hi), method="bounded", options={"xatol": 1e-12 * punch.b})
        if r.fun < 0:
            raise SeparationError(
                f"the concave centre `R` = {punch.R:g} separates for `P` = {P[i]:.6g}, "
                f"`s` = {s[i]:.6g}: the pressure would be {r.fun:.4g} < 0 at x = {r.x:.6g}, so the "
                f"contact is not simply connected; increase P or |R| (the closed form needs p >= 0)")


# -- public API ---------------------------------------------------------------------
def solve_normal(punch: Punch, P: float, s: float = 0.0, *, A: float,
                 tilt: str = "free") -> NormalSolution:
    """Contact ``[-a, c]`` and tilt ``alpha`` of the punch under the load ``P`` at lever arm ``s``.

    Parameters
    ----------
    punch
        The three-part punch.
    P
        Compressive normal load per unit length, > 0.
    s
        Lever arm of ``P`` (positive to the right); it equals the pressure
        centroid. An output when ``tilt="suppressed"`` (pass 0).
    A
        Compliance of eq. (4).
    tilt
        ``"free"``: solve eqs. (consistency_condition), (equilibrium_condition_1)
        and (equilibrium_condition_2) for ``a, c, alpha``. ``"suppressed"``:
        ``alpha = 0``; solve the consistency condition and eq.
        (equilibrium_condition_1) for ``a_hat, c_hat``, and return in ``s``
        the lever arm ``s*`` that holds the punch without a support.

    Raises
    ------
    ValueError
        Non-finite or non-positive ``P``/``A``, an unknown ``tilt``.
    LiftOffError
        ``s`` outside the lift-off lever arms, or ``P`` below :func:`P_min`.
    SeparationError
        A concave centre that would separate.
    NoConvergenceError
        The Newton iteration failed.
    """
    check_finite(P=P, s=s)
    if tilt == "suppressed" and s != 0:
        raise ValueError(f"`s` = {s!r} is an output when tilt='suppressed' (the lever arm s*); pass s=0")
    P, s = float(P), float(s)
    _normal_iv(punch, np.array([P]), A, tilt)
    h, m, ok = _solve_hm(punch, A * P, s, tilt, SCALAR)
    if not ok:
        _fail(punch, np.array([P]), np.array([s]), A, tilt, np.array([False]))
    st = State(punch, h, m, SCALAR)
    alpha, s = (st.alpha, s) if tilt == "free" else (0.0, st.T / st.AP)
    _check_separation(punch, np.array([h - m]), np.array([h + m]), A, np.array([P]), np.array([s]))
    return NormalSolution(punch, float(A), h - m, h + m, alpha, P, s, tilt)


def solve_normal_batch(punch: Punch, P: ArrayLike, s: ArrayLike = 0.0, *, A: float,
                       tilt: str = "free") -> NormalBatch:
    """:func:`solve_normal` for many load cases at once (vectorised Newton).

    ``P`` and ``s`` broadcast against each other; the first inadmissible case
    raises the same error :func:`solve_normal` would, with its values.
    """
    P_arr, s_arr = np.broadcast_arrays(np.asarray(P, float).ravel(), np.asarray(s, float).ravel())
    P_arr, s_arr = P_arr.copy(), s_arr.copy()
    _normal_iv(punch, P_arr, A, tilt)
    bad = ~np.isfinite(s_arr)
    if bad.any():
        raise ValueError(f"`s` = {float(s_arr[int(np.argmax(bad))])!r} must be a finite lever arm")
    h, m, ok = _solve_hm(punch, A * P_arr, s_arr, tilt, np)
    if not ok.all():
        _fail(punch, P_arr, s_arr, A, tilt, ok)
    st = State(punch, h, m)
    alpha = st.alpha if tilt == "free" else np.zeros_like(h)
    s_out = s_arr if tilt == "free" else st.T / st.AP
    _check_separation(punch, h - m, h + m, A, P_arr, s_out)
    return NormalBatch(punch, float(A), h - m, h + m, alpha, P_arr, s_out, tilt)


def lift_off(punch: Punch, P: float, A: float) -> LiftOff:
    """Admissible lever arms for the load ``P`` (eqs. Pctob and s_lift-off).

    ``s_min`` is where the right edge reaches the join (``c -> b``): ``a_min``
    solves ``P_lift-off(a) = P``. ``s_max`` is the mirror image (``a -> b``).
    """
    check_finite(P=P)
    P_arr = np.array([P], float)
    _normal_iv(punch, P_arr, A, "free")
    lo, hi = _lift_off_states(punch, A * P_arr)
    return LiftOff(P=float(P), s_min=float(lo.T[0] / lo.AP[0]), s_max=float(hi.T[0] / hi.AP[0]),
                   a_min=float(lo.h[0] - lo.m[0]), c_max=float(hi.h[0] + hi.m[0]))

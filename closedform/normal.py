"""Inverse normal problem: contact extent and tilt for given loads.

* :func:`solve_normal` -- ``a, c, alpha`` for ``P`` and ``s`` (tilt free), or
  ``a_hat, c_hat`` and the tilt-suppressing lever arm ``s*`` (tilt suppressed);
* :func:`solve_normal_batch` -- the same for arrays of load cases at once;
* :func:`lift_off` -- the admissible lever arms ``[s_min, s_max]`` for a load ``P``
  (eq. Pctob and the lift-off lever arm, with the sign of ``P`` corrected).

All of them solve the consistency condition (eq. consistency_condition) and the
equilibrium conditions (eqs. equilibrium_condition_1, _2) by the nested,
bracketed roots of :mod:`threepart.closedform.newton`: an admissible case
always converges, and a case outside the closed form's range is refused with
the named error of :mod:`threepart.errors` before any iteration could stall.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from threepart.results.answer import check_pressure
from threepart.errors import InputError, LiftOffError, NoConvergenceError, SeparationError
from threepart.problem.punch import Punch
from threepart.results import Diagnostics, NormalResult
from threepart.problem.checks import LENGTH_RANGE, check_tilt, finite, flag, positive, reals
from threepart.problem.validate import check_arcs, check_contact, check_punch, first_refused, lever_arm, load_scale

from . import formulas
from .newton import (HALF_PI, SCALAR, XTOL, XTOL_RANGE, State, r_guess, evaluations, ray_state, solve_phi,
                     solve_r)

__all__ = ["NormalSolution", "NormalBatch", "LiftOff", "solve_normal", "solve_normal_batch",
           "lift_off", "P_min"]

@dataclass(frozen=True)
class NormalSolution(NormalResult):
    """Closed-form normal solution; ``pressure`` is eq. (pressure_abbreviated)."""

    method: str = "closedform"

    def pressure(self, x: ArrayLike) -> np.ndarray:
        return formulas.pressure(self.punch, self.a, self.c, self.A, x)

    def check(self) -> None:
        """The answer check (:func:`threepart.results.answer.check_pressure`) wherever it could refuse.

        The pressure is eq. (inverted_IE) bounded at both ends; as
        ``PV int dt/(w(t)(t-x)) = 0`` inside the contact, it is, for every ``[-a, c]``,

        ``p(x) = w(x)/(pi A) int_{-a}^{c} [v'(t) - v'(x)]/(t - x) dt/w(t)``

        (the tilt, linear, cancels). On a convex profile (``v'' = 1/R1, 1/R, 1/R2 >= 0``:
        a flat or convex centre) ``v'`` never decreases, the divided difference is ``>= 0``
        and so is ``p``: sampling it could not refuse (``tests/test_answers.py`` checks the
        identity by quadrature and the sign on wide random contacts). A concave centre is
        sampled as every other method's answer is; a contact that is not finite is refused.
        """
        if not math.isfinite(self.a + self.c):
            raise NoConvergenceError(f"closedform: the contact [-a, c] = [{-self.a:.6g}, {self.c:.6g}] for "
                                     f"`P` = {self.P:.6g} is not finite; no result is returned")
        if self.punch.kappa0 < 0:
            check_pressure(self)


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
    #: forward evaluations (:class:`~threepart.closedform.newton.State`) per case, averaged over the batch
    evaluations: float = 0.0

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


def P_0(punch: Punch, A: float) -> float:
    """Load of the contact ``[-b, b]``: ``A P_0 = pi b^2/(2R)`` (negative for a concave centre)."""
    return math.pi * punch.b**2 * punch.kappa0 / (2 * A)


def P_min(punch: Punch, A: float, s: float = 0.0, tilt: str = "free") -> float:
    """Least load of the closed form's single contact, ``[-a, c]`` with ``a, c >= b`` and ``p >= 0``.

    * Convex centre (``R > 0``): ``pi b^2/(2AR)``, the load at which the contact
      first touches both joins; ``s`` plays no part (a lever arm makes the
      lift-off range, :func:`lift_off`, the tighter limit).
    * Flat centre (case A) and case C: 0.
    * Concave centre (case B): the separation load at the lever arm ``s``
      (or with the tilt suppressed): below it the pressure at the centre is
      tensile and the contact would split in two (:class:`SeparationError`).
      It is the root of ``min_{|x|<=b} p(x) = 0`` in ``P``, found by bracketing.
    """
    check_punch(punch)
    A = positive("A", A)
    s = lever_arm(punch, s)
    tilt = check_tilt(tilt)
    if punch.kappa0 >= 0 or punch.b == 0:
        return max(P_0(punch, A), 0.0)
    return _separation_load(punch, A, s, tilt)


# -- input validation ----------------------------------------------------------
def _normal_iv(punch: Punch, P: Any, A: float, tilt: str) -> float:
    """Validate before any numerics (``P`` a float64 array, or a float: one case); return ``A`` as a float."""
    check_punch(punch)
    A = positive("A", A)
    check_tilt(tilt)
    pmin = P_0(punch, A)
    if isinstance(P, float):      # one case: the same checks on a float, without numpy's overhead
        if not (math.isfinite(P) and P > 0):
            raise InputError(_not_a_load(P))
        if not LENGTH_RANGE[0] <= P <= LENGTH_RANGE[1]:
            positive("P", P)                                  # raises, naming the range
        load_scale(punch, P, A)
        if P <= pmin:
            raise LiftOffError(_below_P0(punch, P, pmin))
        return A
    bad = ~np.isfinite(P) | (P <= 0)
    if bad.any():
        raise InputError(_not_a_load(float(P.flat[int(np.argmax(bad))])))
    out = (P < LENGTH_RANGE[0]) | (P > LENGTH_RANGE[1])
    if out.any():
        positive("P", float(P.flat[int(np.argmax(out))]))     # raises, naming the range
    # the contact scale sqrt(2 A P R) and its cube must stay representable
    load_scale(punch, P, A)
    low = P <= pmin
    if low.any():
        raise LiftOffError(_below_P0(punch, P.flat[int(np.argmax(low))], pmin))
    return A


def _xtol_iv(xtol: Any) -> float:
    """``xtol`` as a float inside :data:`~closedform.newton.XTOL_RANGE`, else an error naming it."""
    x = finite("xtol", xtol)
    lo, hi = XTOL_RANGE
    if not lo <= x <= hi:
        raise InputError(f"`xtol` = {x!r} must lie in [{lo:g}, {hi:g}]: below, a step is rounding; "
                         "above, the roots' error (about its square) passes 1e-12")
    return x


def _not_a_load(P: float) -> str:
    return f"`P` = {P!r} must be a finite compressive load > 0"


def _below_P0(punch: Punch, P: float, pmin: float) -> str:
    return (f"`P` = {P:.6g} is at or below P_min = pi b^2/(2AR) = {pmin:.6g}, the load at "
            f"which the convex centre (R = {punch.R:g}) first touches both joins x = ±b; below it the "
            "contact lies inside the central segment, outside the closed form")


# -- the nested roots ----------------------------------------------------------------
def solve_state(punch: Punch, P: Any, s: Any, A: float, tilt: str, xp: Any,
           xtol: float = XTOL) -> tuple[State, Any, Any]:
    """State of the solution, and the flags below/above the lift-off range."""
    dAP = A * P - 0.5 * math.pi * punch.kappa0 * punch.b**2   # A (P - P_0), > 0
    if tilt == "free":
        r, phi, below, above = solve_phi(punch, dAP, "moment", A * P * s, xp, xtol=xtol)
    else:
        r, phi, below, above = solve_phi(punch, dAP, "tilt", 0.0 * dAP, xp, sign=-1.0, xtol=xtol)
    return ray_state(punch, r, phi, xp), below, above


def _lift_off_states(punch: Punch, P: Any, A: float, xp: Any = np) -> tuple[State, State]:
    """States at ``c = b`` (``phi = 0``) and ``a = b`` (``phi = pi/2``) for loads ``P``."""
    dAP = A * P - 0.5 * math.pi * punch.kappa0 * punch.b**2
    out = []
    for phi in (0.0, HALF_PI):
        ph = phi + 0.0 * dAP
        r0 = r_guess(punch, dAP, xp)
        out.append(ray_state(punch, solve_r(punch, dAP, ph, r0, xp), ph, xp))
    return out[0], out[1]




def _refuse_lift_off(punch: Punch, P: np.ndarray, s: np.ndarray, A: float, tilt: str,
                     below: np.ndarray, above: np.ndarray) -> None:
    """Raise the :class:`LiftOffError` of the first case outside the lift-off range."""
    i = int(np.argmax(below | above))
    lo, hi = _lift_off_states(punch, P[i], A, SCALAR)
    s_lo, s_hi = lo.T / lo.AP, hi.T / hi.AP
    if tilt == "suppressed":
        raise LiftOffError(
            f"with the tilt suppressed, `P` = {P[i]:.6g} lifts an edge off the outer segments: the tilt "
            f"at c = b is {lo.alpha:.6g} and at a = b {hi.alpha:.6g}, both of one sign")
    word, lim, edge = (("is below", s_lo, "right edge reaches the join, c -> b") if below[i] else
                       ("exceeds", s_hi, "left edge reaches the join, a -> b"))
    raise LiftOffError(
        f"`s` = {s[i]:.6g} {word} the lift-off lever arm {lim:.6g} for `P` = {P[i]:.6g} (the {edge}); "
        f"admissible: {s_lo:.6g} < s < {s_hi:.6g}")


#: grid of the central segment on which the least pressure is bracketed (ends included)
_CENTRE_GRID = 65


def _centre_pressure_min(punch: Punch, a: float, c: float, A: float) -> tuple[float, float]:
    """``(x, p)`` of the least pressure on the central segment ``[-b, b]``.

    A 65-point grid (the joins included) brackets the minimum and a bounded
    Brent search refines it to ``1e-12 b``.
    """
    b = punch.b
    xg = np.linspace(-b, b, _CENTRE_GRID)
    p = formulas.pressure(punch, a, c, A, xg)
    i = int(np.argmin(p))
    best = (float(xg[i]), float(p[i]))
    lo, hi = xg[max(i - 1, 0)], xg[min(i + 1, xg.size - 1)]
    r = minimize_scalar(lambda x: float(formulas.pressure(punch, a, c, A, x)), bounds=(lo, hi),
                        method="bounded", options={"xatol": 1e-12 * b})
    return (float(r.x), float(r.fun)) if r.fun < best[1] else best


#: a batch's case whose least centre pressure, refined all at once, is below this fraction of its
#: mean pressure is confirmed by :func:`_centre_pressure_min` (both are exact to ~1e-15 of it)
_CONFIRM = 1e-8
#: golden-section steps of :func:`_centre_minima`: the bracket of two grid steps, b/16, shrinks to 1e-12 b
_GOLDEN_STEPS = 60


def _centre_minima(punch: Punch, a: np.ndarray, c: np.ndarray, A: float, grid: np.ndarray) -> np.ndarray:
    """The least pressure on ``[-b, b]`` of each case, all at once (:func:`_centre_pressure_min`'s grid
    bracket, then a golden-section search of every bracket in one array)."""
    xg = np.linspace(-punch.b, punch.b, _CENTRE_GRID)
    i = np.argmin(grid, axis=1) if grid.size else np.zeros(0, dtype=int)
    best = grid[np.arange(i.size), i] if i.size else np.zeros(0)
    lo, hi = xg[np.maximum(i - 1, 0)], xg[np.minimum(i + 1, xg.size - 1)]
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = (formulas.pressure(punch, a, c, A, x) for x in (x1, x2))
    for _ in range(_GOLDEN_STEPS if a.size else 0):
        left = f1 < f2                                     # the minimum lies in [lo, x2]
        lo, hi = np.where(left, lo, x1), np.where(left, x2, hi)
        x_new = np.where(left, hi - g * (hi - lo), lo + g * (hi - lo))
        f_new = formulas.pressure(punch, a, c, A, x_new)
        x1, x2, f1, f2 = (np.where(left, x_new, x2), np.where(left, x1, x_new),
                          np.where(left, f_new, f2), np.where(left, f1, f_new))
    return np.minimum(best, np.minimum(f1, f2))


def check_separation(punch: Punch, a: np.ndarray, c: np.ndarray, A: float, P: np.ndarray,
                      s: np.ndarray, tilt: str) -> None:
    """A concave centre must not separate: the pressure stays >= 0 on ``[-b, b]``.

    All cases are screened on the grid at once; a case whose grid minimum lies
    within 5 % of its mean pressure of zero is refined by :func:`_centre_pressure_min`.
    """
    if punch.kappa0 >= 0 or punch.b == 0:
        return
    xg = np.linspace(-punch.b, punch.b, _CENTRE_GRID)
    grid = formulas.pressure(punch, a[:, None], c[:, None], A, xg[None, :])
    near = np.flatnonzero(grid.min(axis=1) < 0.05 * P / (a + c))
    # the cases near separation, refined all at once; those whose least pressure may be < 0 are
    # then confirmed (and the first named) one by one, as a single solve does
    least = _centre_minima(punch, a[near], c[near], A, grid[near])
    for i in near[least < _CONFIRM * P[near] / (a[near] + c[near])]:
        x, p = _centre_pressure_min(punch, float(a[i]), float(c[i]), A)
        if p < 0:
            where = f"`s` = {s[i]:.6g}" if tilt == "free" else "the tilt suppressed"
            sep = _separation_load(punch, A, float(s[i]), tilt)
            raise SeparationError(
                f"the concave centre `R` = {punch.R:g} separates for `P` = {P[i]:.6g} with {where}: the "
                f"pressure would be {p:.4g} < 0 at x = {x:.6g}: the contact splits in two or rests on one "
                f"flank, not the closed form's single contact; "
                f"the closed form needs `P` > {sep:.6g} (the separation load)")


def _separation_load(punch: Punch, A: float, s: float, tilt: str) -> float:
    """Root in ``P`` of ``min_{|x|<=b} p = 0`` for a concave centre, by bracketing and Brent.

    Where the lever arm ``s`` is past lift-off at a trial load, the load is too
    small for that ``s`` anyway and counts as below the root.
    """
    from scipy.optimize import brentq

    def margin(P: float) -> float:
        st, below, above = solve_state(punch, P, s, A, tilt, SCALAR)
        if below or above:
            return -1.0
        x, p = _centre_pressure_min(punch, st.a, st.c, A)
        return p / (P / (st.a + st.c))       # relative to the mean pressure

    hi = max(-P_0(punch, A), 1e-300)
    for _ in range(400):
        if margin(hi) > 0:
            break
        hi *= 2
    lo = hi / 2
    while lo > 1e-300 and margin(lo) > 0:
        hi, lo = lo, lo / 2
    return float(brentq(margin, lo, hi, xtol=1e-300, rtol=1e-13))


# -- public API ---------------------------------------------------------------------
def solve_normal(punch: Punch, P: float, s: float = 0.0, *, A: float,
                 tilt: str = "free", beyond_small_slopes: bool = False,
                 xtol: float = XTOL) -> NormalSolution:
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
    beyond_small_slopes
        Evaluate the paper's formulas even past half-plane theory's small-slope
        limit and the arcs' extents (no :func:`threepart.problem.validate.check_contact`),
        for a study of the formulas' own error such as the validity map
        (:mod:`threepart.reports.map.validity`); such an answer lies outside the
        theory. Default False: refused. A bool (Python's or numpy's); anything
        else is a ``TypeError``.
    xtol
        The root finders' relative step at which to stop (:data:`~closedform.newton.XTOL`,
        1e-12, by default; the roots' error is about its square), in
        :data:`~closedform.newton.XTOL_RANGE`, ``[1e-15, 1e-6]``.

    Raises
    ------
    ValueError
        Non-finite, non-positive or unrepresentably large ``P``/``A`` (outside
        ``LENGTH_RANGE``), an unknown ``tilt``, ``s`` outside the punch's
        footprint ``(-(b + R1), b + R2)`` (:func:`threepart.problem.validate.lever_arm`).
    TypeError
        A ``punch`` that is not a :class:`Punch`, a number of the wrong type.
    ArcExtentError, SlopeLimitError
        The solved contact runs past an arc's extent or past the small-slope
        limit (:func:`threepart.problem.validate.check_contact`).
    LiftOffError
        ``s`` outside the lift-off lever arms, or ``P`` at or below :func:`P_min` of a convex centre.
    SeparationError
        A concave centre that would separate (``P`` below its separation load).
    NoConvergenceError
        Never expected for admissible input: a bracketed root did not close.
    """
    check_punch(punch)
    P, s = positive("P", P), lever_arm(punch, s)
    beyond_small_slopes = flag("beyond_small_slopes", beyond_small_slopes)
    xtol = _xtol_iv(xtol)
    t0 = time.perf_counter()
    if tilt == "suppressed" and s != 0:
        raise InputError(f"`s` = {s!r} is an output when tilt='suppressed' (the lever arm s*); pass s=0")
    A = _normal_iv(punch, P, A, tilt)
    n0 = evaluations()
    st, below, above = solve_state(punch, P, s, A, tilt, SCALAR, xtol)
    n_eval = evaluations() - n0
    if below or above:
        _refuse_lift_off(punch, np.array([P]), np.array([s]), A, tilt, np.array([below]),
                         np.array([above]))
    alpha, s = (st.alpha, s) if tilt == "free" else (0.0, st.T / st.AP)
    if punch.kappa0 < 0 and punch.b > 0:   # a concave centre may separate
        check_separation(punch, np.array([st.a]), np.array([st.c]), A, np.array([P]), np.array([s]), tilt)
    if not beyond_small_slopes:
        check_contact(punch, st.a, st.c, alpha)
    return NormalSolution(punch, A, st.a, st.c, alpha, P, s, tilt,
                          diagnostics=Diagnostics(timings={"total": time.perf_counter() - t0}),
                          info={"evaluations": n_eval})


def solve_normal_batch(punch: Punch, P: ArrayLike, s: ArrayLike = 0.0, *, A: float,
                       tilt: str = "free", xtol: float = XTOL) -> NormalBatch:
    """:func:`solve_normal` for many load cases at once (vectorised; ``xtol`` as there).

    ``P`` and ``s`` broadcast against each other (arrays of equal length, or
    one of length 1), else ``ValueError`` naming both shapes; the first
    inadmissible case raises the same error :func:`solve_normal` would, with its values.
    """
    check_punch(punch)
    xtol = _xtol_iv(xtol)
    P_in, s_in = reals("P", P), reals("s", s)
    if P_in.size != s_in.size and 1 not in (P_in.size, s_in.size):
        raise InputError(f"`P` (shape {np.shape(P)}) and `s` (shape {np.shape(s)}) do not broadcast: "
                         f"give arrays of one length, or one of them a single value")
    P_arr, s_arr = np.broadcast_arrays(P_in, s_in)
    P_arr, s_arr = P_arr.copy(), s_arr.copy()
    A = _normal_iv(punch, P_arr, A, tilt)
    bad = ~((s_arr > -(punch.b + punch.R1)) & (s_arr < punch.b + punch.R2))
    if bad.any():
        i = int(np.argmax(bad))
        try:
            lever_arm(punch, s_arr[i])
        except ValueError as exc:
            raise type(exc)(f"case {i}: {exc}") from None
    if tilt == "suppressed" and np.any(s_arr != 0):
        raise InputError("`s` is an output when tilt='suppressed' (the lever arm s*); pass s=0")
    n0 = evaluations()
    st, below, above = solve_state(punch, P_arr, s_arr, A, tilt, np, xtol)
    n_eval = (evaluations() - n0) / P_arr.size
    if np.any(below | above):
        _refuse_lift_off(punch, P_arr, s_arr, A, tilt, np.asarray(below), np.asarray(above))
    alpha = st.alpha if tilt == "free" else np.zeros_like(st.h)
    s_out = s_arr if tilt == "free" else st.T / st.AP
    check_separation(punch, st.a, st.c, A, P_arr, s_out, tilt)
    k = first_refused(punch, st.a, st.c, alpha)   # the first case past the arcs or the slope limit
    if k is not None:
        i = k
        try:
            check_contact(punch, float(st.a[i]), float(st.c[i]), float(alpha[i]))
        except ValueError as exc:
            raise type(exc)(f"case {i} (`P` = {P_arr[i]:.6g}, `s` = {s_out[i]:.6g}): {exc}") from None
    return NormalBatch(punch, A, st.a, st.c, alpha, P_arr, s_out, tilt, n_eval)


def lift_off(punch: Punch, P: float, A: float, *, beyond_small_slopes: bool = False) -> LiftOff:
    """Admissible lever arms for the load ``P`` (eqs. Pctob and s_lift-off).

    ``s_min`` is where the right edge reaches the join (``c -> b``): ``a_min``
    solves ``P_lift-off(a) = P``. ``s_max`` is the mirror image (``a -> b``).
    Both lift-off contacts must lie on the arcs (:func:`threepart.problem.validate.check_arcs`),
    as :func:`solve_normal`'s must, so that every ``s`` strictly between them
    is one :func:`solve_normal` solves, but where the tilt there passes the
    small-slope limit (``SlopeLimitError``; the lift-off lever arms are still
    the geometry's) or a concave centre separates (``P`` below :func:`P_min` at
    that ``s``). ``beyond_small_slopes=True`` skips the arcs' check, as in
    :func:`solve_normal`, for a study of the formulas past the arcs (the
    validity map, :mod:`threepart.reports.map.validity`).

    Raises
    ------
    ArcExtentError
        If a lift-off contact runs past an arc's extent (``a_min > b + R1`` or
        ``c_max > b + R2``): before that edge lifts off the other has run off
        its arc, so the punch never reaches that lift-off; the message names
        ``P``, the lift-off and the arc's limit. Refused even if only one side
        is past, as :func:`solve_normal` refuses the contacts near it.
    """
    check_punch(punch)
    P = positive("P", P)
    A = _normal_iv(punch, P, A, "free")
    lo, hi = _lift_off_states(punch, P, A, SCALAR)
    checked = () if flag("beyond_small_slopes", beyond_small_slopes) else (lo, hi)
    for st, which in zip(checked, ("s_min (c = b)", "s_max (a = b)")):
        try:
            check_arcs(punch, st.a, st.c)
        except ValueError as exc:
            raise type(exc)(f"`P` = {P:.6g} has no lift-off lever arm {which} = {st.T / st.AP:.6g}: "
                            f"{exc}") from None
    return LiftOff(P=P, s_min=lo.T / lo.AP, s_max=hi.T / hi.AP, a_min=lo.a, c_max=hi.c)

"""Coulomb friction on a discretised interface: one load state's stick/slip sets by a primal-dual active set.

The one home of the incremental Coulomb problem that both the FEM
(:mod:`fem.coulomb`, nodal forces of the condensed two-body interface) and the
SIE load history (:mod:`sie.history`, element forces of the log-kernel shear)
solve. With ``t_i`` the shear force the punch drags the substrate with at
point ``i``, ``bound_i = f fn_i`` its Coulomb bound and

    w = xi + w_fixed - C t

the relative tangential displacement of the punch (punch minus substrate),
``xi`` the rigid shift and ``C`` the tangential flexibility, a point in
contact (``bound_i > 0``) either sticks (``w_i`` keeps ``w_prev_i``) or slips
(``t_i = bound_i sign(Δw_i)``); a point out of contact carries nothing; and
``sum t = Q``. The sets come from the complementarity function
``t_i = proj_[-bound_i, bound_i](t_i + c Δw_i)`` (Hüeber, Stadler & Wohlmuth
2008), with ``c`` the inverse of the mean diagonal of ``C``.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import FullSlidingError, NoConvergenceError
from .surface import solve_active, symmetric

__all__ = ["coulomb_state", "RETRIES"]

#: a slip point stays one while ``sign z`` is within this fraction below its bound (rounding)
HYSTERESIS = 1e-9
#: retries of a state whose active set does not settle, each with a ten times smaller ``c``
RETRIES = 2


def coulomb_state(C: np.ndarray, bound: np.ndarray, w_prev: np.ndarray, w_fixed: np.ndarray,
                  Q: float, stick0: np.ndarray, max_iter: int, sign0: np.ndarray | None = None,
                  damping: float = 1.0) -> tuple[np.ndarray, float, np.ndarray, int, float]:
    """Shear forces, rigid shift and stick set of one load state.

    Parameters
    ----------
    C
        Tangential flexibility, ``n x n`` (positive definite on ``sum t = 0``).
    bound
        Coulomb bounds ``f fn_i`` (``0`` out of contact).
    w_prev
        Relative tangential displacement of the previous state (the memory of slip).
    w_fixed
        The part of ``w`` that does not depend on the shear (normal coupling, bulk strain).
    Q
        Total shear force, ``sum t``.
    stick0
        Stick set to start from (the previous state's).
    max_iter
        Cap on the active-set iterations.
    sign0
        Slip directions to start from on the points outside ``stick0`` (the
        previous state's, ``±1``); by default the slip points start with no shear.
    damping
        The complementarity constant ``c`` is ``damping / mean(diag C)``. The sets
        it settles on do not depend on ``c``, but an iteration with a ``c`` too
        large for a strongly coupled ``C`` (the log kernel of the SIE) can cycle:
        one that does not settle is retried with ``c`` divided by ten, twice
        (:data:`RETRIES`).

    Returns
    -------
    t, xi, stick, iterations, residual
        ``residual`` is the largest ``|t_i| - bound_i`` left, relative to ``max bound``.

    Raises
    ------
    FullSlidingError
        If ``|Q| >= sum(bound)``: every point in contact slides.
    NoConvergenceError
        If the sets do not settle within ``max_iter`` iterations or a shear
        exceeds Coulomb's bound after they settle.
    """
    if abs(Q) >= float(bound.sum()):
        raise FullSlidingError(
            f"`Q` = {Q:.6g}: every point in contact slides (|Q| reached the discrete f P = "
            f"{float(bound.sum()):.6g})")
    its = 0
    for attempt in range(RETRIES + 1):
        c = damping * 10.0 ** -attempt / float(np.mean(np.diag(C)))
        found = _active_set(C, bound, w_prev, w_fixed, Q, stick0, sign0, c, max_iter)
        its += found[3]
        if found[0] is not None:
            break
    else:
        raise NoConvergenceError(
            f"stick/slip states did not settle within `max_iter` = {max_iter} iterations "
            f"(with {RETRIES + 1} values of the complementarity constant)")
    t, xi, stick = found[0], found[1], found[2]
    scale = max(float(bound.max()), 1e-300)
    over = float((np.abs(t) - bound).max()) / scale
    if over > 1e-9:
        raise NoConvergenceError(f"shear exceeds f p by {over:.3g} (relative) after {its} iterations")
    return t, xi, stick, its, over


def _active_set(C: np.ndarray, bound: np.ndarray, w_prev: np.ndarray, w_fixed: np.ndarray, Q: float,
                stick0: np.ndarray, sign0: np.ndarray | None, c: float, max_iter: int
                ) -> tuple[Any, float, np.ndarray, int]:
    """The primal-dual active set with constant ``c``: ``(t, xi, stick, iterations)``, ``t`` None if it did not settle."""
    touch = bound > 0
    stick = stick0 & touch
    sign = np.zeros(len(bound)) if sign0 is None else np.where(touch & ~stick, sign0, 0.0)
    if not stick.any():   # start from the point that carries the most force
        stick[np.argmax(bound)] = True
    sym = symmetric(C)
    zero = np.zeros(len(bound))
    for it in range(1, max_iter + 1):
        slip = touch & ~stick
        t_slip = np.where(slip, sign * bound, 0.0)
        # the stick points: C_SS t_S - xi = -(w_prev - w_fixed + C t_slip)_S, sum t_S = Q - sum t_slip,
        # the bordered system of the normal problem's fixed tilt (its factor, kept per set)
        t, xi, _ = solve_active(C, zero, w_prev - w_fixed + C @ t_slip, stick,
                                 Q - float(t_slip.sum()), 0.0, False, sym)
        t += t_slip
        z = t + c * (xi + w_fixed - C @ t - w_prev)
        # a slip point whose |z| falls below its bound only by rounding stays a slip point: such a
        # point (t at the bound, no slip increment) otherwise toggles with the rounding
        held = slip & (sign * z > (1.0 - HYSTERESIS) * bound)
        new_stick = touch & (np.abs(z) < bound) & ~held
        new_sign = np.where(touch & ~new_stick, np.sign(z), 0.0)
        if np.array_equal(new_stick, stick) and np.array_equal(new_sign[slip], sign[slip]):
            return t, xi, stick, it
        if not new_stick.any():
            # |Q| < sum(bound): some point sticks; an overshooting iterate emptied the set, so
            # the point nearest its bound (least |z|/bound) sticks again
            new_stick[np.flatnonzero(touch)[np.argmin(np.abs(z[touch]) / bound[touch])]] = True
            new_sign = np.where(touch & ~new_stick, np.sign(z), 0.0)
        stick, sign = new_stick, new_sign
    return None, 0.0, stick, max_iter

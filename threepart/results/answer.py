"""The one check of every answer: a compressive pressure, and a shear inside Coulomb's bound.

Every normal and partial-slip result, of every method (the closed form, the
SIE, the FEM and any registered since), is checked here when it is built
(:class:`threepart.results.NormalResult` calls :func:`check_pressure` and
:class:`~threepart.results.SlipResult` :func:`check_coulomb` from their
``__post_init__``; :class:`~threepart.results.cycles.SteadyStateResult` checks both of
its ends), so that no solve returns a contact that pulls on the half-plane or a
shear that exceeds friction, whatever the method's own checks missed (a
tolerance too loose, a discretisation too coarse):

* normal: ``min p >= -TOL p_max`` over the contact, else :class:`SeparationError`;
* partial slip: ``max (|q| - f p) <= TOL f p_max`` over the contact, else
  :class:`CoulombError`,

with ``TOL`` the table's ``("answer", "p_min")`` and ``("answer", "q_bound")``
(:mod:`threepart.tolerances`). Both are sampled at Chebyshev points of the
contact (and, for slip, of the stick zone), where the errors of a truncated
series and the corrective pressure's ends lie: one vectorised evaluation of
the fields, no Python loop over points, a few tens of microseconds for the
closed form.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import CoulombError, NoConvergenceError, SeparationError
from ..tolerances import tolerance

__all__ = ["check_pressure", "check_coulomb", "ANSWER_POINTS"]

#: Chebyshev points per interval (the contact, the stick zone) at which an answer is checked:
#: they cluster at the interval's ends, where a series' error and the corrective pressure's
#: square-root ends lie, and resolve a dip of the centre (width ~2b) by dozens of points
ANSWER_POINTS = 256


#: the :data:`ANSWER_POINTS` Chebyshev points of the first kind in ``(-1, 1)``, ends excluded
_UNIT = -np.cos((np.arange(ANSWER_POINTS) + 0.5) * np.pi / ANSWER_POINTS)


def _points(lo: float, hi: float) -> np.ndarray:
    """The Chebyshev points :data:`_UNIT` mapped to ``(lo, hi)`` (ends excluded, where p = 0)."""
    return 0.5 * (lo + hi) + 0.5 * (hi - lo) * _UNIT


def _resolution(result: Any) -> str:
    """What the result's discretisation was, for a message: ``n`` (SIE) or ``h`` (FEM), or ''."""
    d = result.diagnostics
    if d.n is not None:
        return (f"; with `n` = {d.n} the discretisation may not resolve this contact (raise `n`; "
                "or, if it persists, the answer is physically so)")
    if d.h is not None:
        return f"; the mesh (h = {d.h:.3g}) may not resolve this contact (refine it)"
    return ""


def _finite(result: Any, values: np.ndarray, what: str) -> None:
    if not np.isfinite(values).all():
        raise NoConvergenceError(f"{result.method or type(result).__name__}: the {what} of the answer "
                                 f"for `P` = {result.P:.6g} is not finite; no result is returned")


def check_pressure(result: Any) -> None:
    """Refuse a normal answer whose pressure is tensile: ``min p < -TOL p_max`` on ``(-a, c)``.

    Raises
    ------
    SeparationError
        Naming ``P``, ``s``, the least pressure and where, and the limit.
    NoConvergenceError
        If the pressure is not finite somewhere.
    """
    x = _points(-result.a, result.c)
    p = np.asarray(result.pressure(x), dtype=float)
    _finite(result, p, "pressure")
    peak = float(p.max())
    tol = tolerance("answer", "p_min").limit
    i = int(np.argmin(p))
    if not peak > 0:
        raise SeparationError(f"`P` = {result.P:.6g} with `s` = {result.s:.6g}: the "
                              f"{result.method or 'answer'}'s pressure is nowhere compressive on "
                              f"[{-result.a:.6g}, {result.c:.6g}] (max p = {peak:.4g}){_resolution(result)}")
    if p[i] < -tol * peak:
        raise SeparationError(
            f"`P` = {result.P:.6g} with `s` = {result.s:.6g}: the {result.method or 'answer'}'s "
            f"pressure is tensile, min p = {p[i]:.4g} at x = {x[i]:.6g} ({p[i] / peak:.3g} of the "
            f"peak {peak:.4g}, past -{tol:g}, threepart.tolerances 'answer' 'p_min'): the contact "
            f"separates into two zones or rests on one flank, not one contact [-a, c]"
            f"{_resolution(result)}")


def check_coulomb(result: Any) -> None:
    """Refuse a slip answer whose shear exceeds friction: ``|q| - f p > TOL f p_max`` somewhere.

    Sampled on the contact and on the stick zone ``[-(d+e), d-e]``, where a
    corrective pressure ``p*`` below 0 (or above ``2p``) would lift ``|q|``
    over ``f p``.

    Raises
    ------
    CoulombError
        Naming ``Q``, ``f``, ``P``, the largest excess and where, and the limit.
    NoConvergenceError
        If the shear or the pressure is not finite somewhere.
    """
    lo, hi = result.stick_zone
    x = np.concatenate([_points(-result.a, result.c),
                        _points(max(lo, -result.a), min(hi, result.c))])
    p = np.asarray(result.pressure(x), dtype=float)
    q = np.asarray(result.shear(x), dtype=float)
    _finite(result, q, "shear")
    _finite(result, p, "pressure")
    bound = result.f * float(p.max())
    excess = np.abs(q) - result.f * p
    tol = tolerance("answer", "q_bound").limit
    i = int(np.argmax(excess))
    if excess[i] > tol * bound:
        raise CoulombError(
            f"`Q` = {result.Q:.6g} with `f` = {result.f:g} on `P` = {result.P:.6g} "
            f"(|Q|/(f P) = {abs(result.Q) / (result.f * result.P):.9g}): the "
            f"{result.method or 'answer'}'s shear breaks Coulomb's law, |q| exceeds f p by "
            f"{excess[i]:.4g} at x = {x[i]:.6g} ({excess[i] / bound:.3g} of f p_max = {bound:.4g}, "
            f"past {tol:g}, threepart.tolerances 'answer' 'q_bound'){_resolution(result)}")

"""Where a FE contact ends, and whether the mesh resolves it: shared by every FE model.

The normal, partial-slip and finite-body models solve nodal contact forces;
this module turns them into contact (or stick-zone) ends, refuses a contact that
splits into two zones, and decides when a preset mesh must be refined because
an end lies too close to a join ``x = ±b``.

contact_ends     -- left and right ends ``(-a, c)`` from ``p^2 -> 0`` next to the outermost active nodes
check_one_zone   -- SeparationError unless the active nodes form one zone
end_size         -- element size at the contact ends
join_distance    -- distance of the nearer end from the nearer join
refined          -- the preset refined to resolve the ends, or None; MeshResolutionError past the limit
MIN_END_ELEMENTS, MAX_REFINEMENT -- the limits ``refined`` applies
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from threepart.errors import MeshResolutionError, SeparationError
from threepart.problem.punch import Punch

from .mesh import MeshPreset

__all__ = ["contact_ends", "check_one_zone", "end_size", "join_distance", "refined",
           "MIN_END_ELEMENTS", "MAX_REFINEMENT"]

#: nodes after the edge node used to extrapolate p^2 to zero (the edge node is skipped:
#: its lumped pressure carries the square-root edge inside one element)
_EDGE_FIT = 16


def _edge(x: np.ndarray, p: np.ndarray, i: int, step: int,
          breaks: tuple[float, ...] = ()) -> float:
    """Contact end next to edge node ``i`` (``step`` points inwards), from ``p^2 -> 0``.

    A quadratic in ``x`` is fitted by least squares to ``p^2`` on up to
    ``_EDGE_FIT`` nodes after the edge node, stopping at a profile breakpoint
    (the pressure is not smooth across ``x = ±b``) and at the first node out of
    contact. Its root is kept between the edge node's outer and inner neighbours.
    """
    j = i + step * np.arange(1, _EDGE_FIT + 1)
    j = j[(j >= 0) & (j < len(x))]
    inside = p[j] > 0
    j = j[: int(np.argmin(inside)) if not inside.all() else len(j)]
    for xb in breaks:  # keep the window on the edge node's side of each breakpoint
        j = j[(x[j] - xb) * (x[i] - xb) >= 0] if len(j) else j
    outer = x[i - step] if 0 <= i - step < len(x) else x[i]
    lo, hi = sorted((outer, x[j[0]] if len(j) else x[i]))
    if len(j) < 2:
        return float(0.5 * (x[i] + outer))
    deg = 2 if len(j) >= 6 else 1
    coef = np.polyfit(x[j] - x[i], p[j] ** 2, deg)
    roots = np.roots(coef)
    roots = roots[np.abs(roots.imag) < 1e-12 * (hi - lo)].real + x[i]
    ok = roots[(roots >= lo) & (roots <= hi)]
    if len(ok) == 0:
        return float(0.5 * (x[i] + outer))
    return float(ok[np.argmin(np.abs(ok - x[i]))])


def contact_ends(x: np.ndarray, p: np.ndarray, active: np.ndarray,
          breaks: tuple[float, ...] = ()) -> tuple[float, float]:
    """Left and right contact ends ``(-a, c)`` of the outermost active nodes."""
    idx = np.flatnonzero(active)
    return _edge(x, p, int(idx[0]), +1, breaks), _edge(x, p, int(idx[-1]), -1, breaks)


def check_one_zone(x: np.ndarray, active: np.ndarray, P: float, s: float) -> None:
    """Refuse a contact whose active nodes do not form one zone (a gap between them).

    The closed form, the SIE and this model answer a single contact; a gap of
    inactive nodes between active ones is two zones, refused like the others
    refuse it, never returned as the outer ends with a zero-pressure gap.
    """
    gap = _first_gap(active)
    if gap is not None:
        lo, hi = x[gap[0]], x[gap[1]]
        raise SeparationError(
            f"`P` = {P:g} with `s` = {s:g}: the FE contact separates into two zones (no contact "
            f"over [{lo:.6g}, {hi:.6g}]); the single-contact solutions do not apply")


def _first_gap(active: np.ndarray) -> tuple[int, int] | None:
    """First and last inactive node of the first gap between active nodes, or None for one zone."""
    idx = np.flatnonzero(active)
    gaps = np.flatnonzero(np.diff(idx) > 1)
    return (int(idx[gaps[0]] + 1), int(idx[gaps[0] + 1] - 1)) if len(gaps) else None


#: elements a contact end must lie from a join (where the pressure has a kink) to be resolved
MIN_END_ELEMENTS = 3

#: the most a preset is refined automatically to resolve an end near a join
MAX_REFINEMENT = 128
#: how many times a preset is refined at most (the first refinement moves the ends a little,
#: which may ask for a second)
REFINE_ATTEMPTS = 2


def join_distance(punch: Punch, left: float, right: float) -> float:
    """Distance of the nearer contact end from the nearer join ``x = ±b`` (inf for ``b = 0``)."""
    if punch.b == 0:
        return math.inf
    return min(abs(end - j) for end in (left, right) for j in (-punch.b, punch.b))


def end_size(x: np.ndarray, left: float, right: float) -> float:
    """Element size at the contact ends: twice the P2 node spacing there, the larger of the two."""
    k = np.clip(np.searchsorted(x, [left, right]), 1, len(x) - 1)
    return float(2 * np.max(x[k] - x[k - 1]))


def refinement_factor(punch: Punch, left: float, right: float, h: float) -> int:
    """How many times finer the mesh must be for both ends to lie ``MIN_END_ELEMENTS`` from a join.

    ``h`` is the element size at the ends.
    """
    d = join_distance(punch, left, right)
    need = MIN_END_ELEMENTS * h / d if d > 0 else math.inf
    if need <= 1:
        return 1
    # a quarter more than needed: the refined mesh's h is set by a snapped width (fem.mesh.snap)
    return int(math.ceil(1.25 * need)) if math.isfinite(need) else MAX_REFINEMENT + 1


def refined(punch: Punch, left: float, right: float, h_end: float, pre: object,
            attempt: int, base: object = None) -> MeshPreset | None:
    """The preset ``pre`` refined to resolve contact ends ``(left, right)``, or None if ``h_end`` does.

    ``pre`` is the mesh just solved on, ``attempt`` how many times the caller's
    preset ``base`` (default ``pre``) was refined already to reach it.

    Raises
    ------
    MeshResolutionError
        If the mesh is not a preset, was refined ``REFINE_ATTEMPTS`` times
        already, or would need more than ``MAX_REFINEMENT`` times finer elements
        than ``base``.
    """
    factor = refinement_factor(punch, left, right, h_end)
    if factor == 1:
        return None
    base = pre if base is None else base
    if isinstance(pre, MeshPreset) and isinstance(base, MeshPreset):
        factor = int(math.ceil(factor * pre.refine / base.refine))   # relative to base
    if not isinstance(pre, MeshPreset) or attempt >= REFINE_ATTEMPTS or factor > MAX_REFINEMENT:
        raise MeshResolutionError(
            f"a contact end lies {join_distance(punch, left, right):.3g} from a join, fewer than "
            f"{MIN_END_ELEMENTS} elements of h = {h_end:.3g}: the mesh cannot resolve it"
            + ("" if isinstance(pre, MeshPreset) else "; give a finer mesh")
            + (f" (it would need {factor}x finer, more than {MAX_REFINEMENT}x)"
               if isinstance(pre, MeshPreset) else ""))
    assert isinstance(base, MeshPreset)
    return replace(base, refine=base.refine * factor)

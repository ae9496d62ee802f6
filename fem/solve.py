"""``solve_normal``: the FE answer to the load-controlled normal contact problem.

Steps: locate the contact roughly with a trial solve on a coarse mesh (no closed
form is used), mesh the substrate around it with :mod:`meshes`, condense the
elastic body onto the candidate surface nodes (:mod:`fem.elasticity`), solve the
contact (:mod:`fem.contact`), and recover the pressure ``p_i = f_i / w_i`` and the
contact ends, found between nodes by extrapolating ``p^2`` to zero.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Union

import numpy as np
from numpy.typing import ArrayLike

from threepart.punch import Punch

from threepart.validate import check_finite
from threepart.errors import ContactZoneError, MeshResolutionError, SeparationError
from threepart.material import rigid_punch
from threepart.results import NormalResult
from threepart.meshes import SubstrateSpec

from .contact import ContactSolution, solve_contact
from .export import Fields, fields_of
from .elasticity import SurfaceCompliance, condense
from .mesh import PRESETS, MeshPreset, Substrate, make_substrate, preset, read_substrate

__all__ = ["FemResult", "solve_normal", "locate_contact", "MeshArg"]

MeshArg = Union[str, Path, MeshPreset, SubstrateSpec, Substrate]

#: nodes after the edge node used to extrapolate p^2 to zero (the edge node is skipped:
#: its lumped pressure carries the square-root edge inside one element)
_EDGE_FIT = 16


@dataclass(frozen=True)
class FemResult(NormalResult):
    """FE solution of the normal problem, with its discretisation.

    Attributes (beyond :class:`~closedform.results.NormalResult`)
    ----------
    h
        Element size along the contact zone (P2 node spacing is ``h/2``).
    dofs
        FE degrees of freedom.
    L
        Block size (width and depth).
    delta
        Rigid indentation of the punch (depends on ``L``: half-plane displacements diverge).
    timings
        Wall seconds of ``locate`` (trial and locate solves; cached per case in a run),
        ``mesh``, ``assemble``, ``factorise``, ``contact`` and ``total``.
    x_nodes, p_nodes
        Candidate node positions and their pressures ``f_i / w_i``.
    fields
        Displacement and stress (:class:`~fem.export.Fields`) when asked for.
    """

    h: float = math.nan
    dofs: int = 0
    L: float = math.nan
    delta: float = math.nan
    timings: dict[str, float] = field(default_factory=dict, compare=False)
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    p_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    fields: Fields | None = field(default=None, compare=False, repr=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure, linear between nodes, 0 at the ends and outside ``[-a, c]``."""
        x = np.asarray(x, dtype=float)
        inside = (self.x_nodes > -self.a) & (self.x_nodes < self.c)
        xs = np.concatenate([[-self.a], self.x_nodes[inside], [self.c]])
        ps = np.concatenate([[0.0], self.p_nodes[inside], [0.0]])
        return np.interp(x, xs, ps, left=0.0, right=0.0)


def _validate(P: float, s: float, E: float, nu: float, tilt: str, max_iter: int) -> None:
    """Check the scalar inputs before any numerics; messages name argument and limit."""
    check_finite(P=P, s=s, E=E, nu=nu)
    if P <= 0:
        raise ValueError(f"`P` = {P!r} must be > 0 (compressive load)")
    if E <= 0:
        raise ValueError(f"`E` = {E!r} must be > 0")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"`nu` = {nu!r} must lie in (-1, 0.5)")
    if tilt not in ("free", "suppressed"):
        raise ValueError(f"`tilt` = {tilt!r} must be 'free' or 'suppressed'")
    if not (isinstance(max_iter, (int, np.integer)) and max_iter >= 1):
        raise ValueError(f"`max_iter` = {max_iter!r} must be an integer >= 1")


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


def _ends(x: np.ndarray, p: np.ndarray, active: np.ndarray,
          breaks: tuple[float, ...] = ()) -> tuple[float, float]:
    """Left and right contact ends ``(-a, c)`` of the outermost active nodes."""
    idx = np.flatnonzero(active)
    return _edge(x, p, int(idx[0]), +1, breaks), _edge(x, p, int(idx[-1]), -1, breaks)


def _contact(sc: SurfaceCompliance, punch: Punch, P: float, s: float, tilt: str,
             max_iter: int, guess: tuple[float, float] | None = None) -> ContactSolution:
    """Solve the contact on ``sc``, warm-started from the trial contact ``guess`` if there is one."""
    g0 = punch.profile(sc.x)
    active = None if guess is None else (sc.x >= guess[0]) & (sc.x <= guess[1])
    sol = solve_contact(sc.C, sc.x, g0, P, s, free_tilt=tilt == "free", max_iter=max_iter,
                        active=active if active is not None and active.any() else None)
    if sol.active[0] or sol.active[-1]:
        raise ContactZoneError(
            f"the contact reaches the candidate zone end [{sc.x[0]:.6g}, {sc.x[-1]:.6g}]; "
            "use a wider zone (a larger preset `margin`)")
    _check_one_zone(sc.x, sol.active, P, s)
    return sol


def _check_one_zone(x: np.ndarray, active: np.ndarray, P: float, s: float) -> None:
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


def _guess(punch: Punch, P: float, s: float, A: float) -> tuple[float, float]:
    """Generous Hertz-type bracket of the contact, for the first trial mesh only."""
    a1, a2 = (math.sqrt(2 * P * A * R / math.pi) for R in (punch.R1, punch.R2))
    return min(-punch.b, s) - 1.5 * a1, max(punch.b, s) + 1.5 * a2


def locate_contact(punch: Punch, P: float, s: float, *, E: float, nu: float, tilt: str,
                   max_iter: int = 100, tries: int = 6) -> tuple[float, float]:
    """Estimate the contact ``(-a, c)`` by solves on the coarse ``"trial"`` and ``"locate"`` meshes.

    The trial zone is widened when the contact reaches its ends and narrowed
    around the contact when it spans too few elements. A solve on the
    ``"locate"`` mesh around the trial contact then places the ends to about
    1e-4 W, where the refined presets put mesh nodes. Estimates are cached for
    the run: the presets of one case share them.
    """
    return _locate(punch, float(P), float(s), float(E), float(nu), tilt, int(max_iter), int(tries))


@functools.lru_cache(maxsize=64)
def _locate(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
            max_iter: int, tries: int) -> tuple[float, float]:
    A = rigid_punch(E, nu)
    lo, hi = _guess(punch, P, s if tilt == "free" else 0.0, A)
    breaks = (-punch.b, punch.b)
    trial = PRESETS["trial"]
    for _ in range(tries):
        sc = condense(make_substrate(trial.spec(lo, hi, breaks)), E, nu)
        sol = solve_contact(sc.C, sc.x, punch.profile(sc.x), P, s, free_tilt=tilt == "free",
                            max_iter=max_iter)
        if sol.active[0] or sol.active[-1]:
            W = hi - lo
            lo, hi = lo - W, hi + W
            continue
        p = sol.f / sc.weights
        left, right = _ends(sc.x, p, sol.active, breaks)
        if right - left > 0.5 * (hi - lo):
            break
        lo, hi = left - 0.05 * (right - left) - sc.h, right + 0.05 * (right - left) + sc.h
    else:
        raise ContactZoneError(f"no stable contact estimate after {tries} trial meshes")
    sc = condense(make_substrate(PRESETS["locate"].spec(left, right, breaks)), E, nu)
    try:
        sol = _contact(sc, punch, P, s, tilt, max_iter, (left, right))
    except (ContactZoneError, SeparationError):
        return left, right   # the trial estimate; the final solve says what is wrong
    return _ends(sc.x, sol.f / sc.weights, sol.active, breaks)


#: elements a contact end must lie from a join (where the pressure has a kink) to be resolved
MIN_END_ELEMENTS = 3
#: the most a preset is refined automatically to resolve an end near a join
MAX_REFINEMENT = 8


def _join_distance(punch: Punch, left: float, right: float) -> float:
    """Distance of the nearer contact end from the nearer join ``x = ±b`` (inf for ``b = 0``)."""
    if punch.b == 0:
        return math.inf
    return min(abs(end - j) for end in (left, right) for j in (-punch.b, punch.b))


def _end_size(x: np.ndarray, left: float, right: float) -> float:
    """Element size at the contact ends: twice the P2 node spacing there, the larger of the two."""
    k = np.clip(np.searchsorted(x, [left, right]), 1, len(x) - 1)
    return float(2 * np.max(x[k] - x[k - 1]))


def _refinement(punch: Punch, left: float, right: float, h: float) -> int:
    """How many times finer the mesh must be for both ends to lie ``MIN_END_ELEMENTS`` from a join.

    ``h`` is the element size at the ends.
    """
    d = _join_distance(punch, left, right)
    need = MIN_END_ELEMENTS * h / d if d > 0 else math.inf
    if need <= 1:
        return 1
    # a quarter more than needed: the refined mesh's h is set by a snapped width (fem.mesh.snap)
    return int(math.ceil(1.25 * need)) if math.isfinite(need) else MAX_REFINEMENT + 1


def refined(punch: Punch, left: float, right: float, h_end: float, pre: object,
            attempt: int) -> MeshPreset | None:
    """The preset refined to resolve contact ends ``(left, right)``, or None if ``h_end`` does.

    Raises
    ------
    MeshResolutionError
        If the mesh is not a preset, was refined already (``attempt`` 1), or
        would need more than ``MAX_REFINEMENT`` times finer elements.
    """
    factor = _refinement(punch, left, right, h_end)
    if factor == 1:
        return None
    if not isinstance(pre, MeshPreset) or attempt >= 1 or factor > MAX_REFINEMENT:
        raise MeshResolutionError(
            f"a contact end lies {_join_distance(punch, left, right):.3g} from a join, fewer than "
            f"{MIN_END_ELEMENTS} elements of h = {h_end:.3g}: the mesh cannot resolve it"
            + ("" if isinstance(pre, MeshPreset) else "; give a finer mesh")
            + (f" (it would need {factor}x finer, more than {MAX_REFINEMENT}x)"
               if isinstance(pre, MeshPreset) else ""))
    return replace(pre, refine=pre.refine * factor)


def _substrate(mesh: MeshArg, punch: Punch, P: float, s: float, E: float, nu: float,
               tilt: str, max_iter: int
               ) -> tuple[Substrate, float, tuple[float, float] | None, float]:
    """The substrate selected by ``mesh``, its block size ``L``, the located contact and the seconds spent locating it."""
    guess, t_locate = None, 0.0
    if isinstance(mesh, Substrate):
        sub = mesh
    elif isinstance(mesh, SubstrateSpec):
        sub = make_substrate(mesh)
    elif isinstance(mesh, Path) or (isinstance(mesh, str) and mesh.endswith(".msh")):
        sub = read_substrate(mesh)
    else:
        pre = preset(mesh) if isinstance(mesh, str) else mesh
        if not isinstance(pre, MeshPreset):
            raise ValueError(f"`mesh` = {mesh!r} must be a preset name {sorted(PRESETS)}, "
                             "a MeshPreset, a SubstrateSpec, a Substrate or a .msh path")
        t0 = time.perf_counter()
        guess = locate_contact(punch, P, s, E=E, nu=nu, tilt=tilt, max_iter=max_iter)
        t_locate = time.perf_counter() - t0
        sub = make_substrate(pre.spec(*guess, (-punch.b, punch.b)))
    L = float(np.ptp(sub.mesh.p[0]))
    return sub, L, guess, t_locate


def solve_normal(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                 tilt: str = "free", mesh: MeshArg = "default",
                 max_iter: int = 100, fields: bool = False) -> FemResult:
    """Rigid punch pressed into a plane-strain elastic block by ``P`` at lever arm ``s``.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2).
    P
        Compressive load, > 0.
    s
        Lever arm of the load (pressure centroid), positive to the right; ignored
        (and returned as the centroid) when ``tilt == "suppressed"``.
    E, nu
        Substrate's Young's modulus and Poisson's ratio (plane strain).
    tilt
        ``"free"``: translation and tilt unknown; ``"suppressed"``: ``alpha = 0``.
    mesh
        A preset name (``"quick"``, ``"default"``, ``"fine"``), a
        :class:`~fem.mesh.MeshPreset`, a :class:`~meshes.SubstrateSpec`, a
        :class:`~fem.mesh.Substrate` or the path of a ``.msh`` file with
        ``"contact"`` and ``"base"`` groups.
    max_iter
        Cap on the active-set iterations.
    fields
        Also recover the displacement and stress fields (for :func:`fem.write_fields`).

    Returns
    -------
    FemResult
        With ``method = "fem"`` and ``A = 2 (1 - nu^2) / E``.

    Raises
    ------
    ValueError
        For invalid input, naming the argument and its limit.
    NoConvergenceError
        If the contact iteration does not converge.
    ContactZoneError
        If the contact reaches the end of the candidate zone.
    SeparationError
        If the contact separates into two zones (a concave centre at a light load).
    MeshResolutionError
        If a contact end lies within ``MIN_END_ELEMENTS`` elements of a join and a
        preset refined ``MAX_REFINEMENT`` times (or the mesh given) cannot resolve it.
        A preset is first refined automatically (``info["refined"]`` says how much).
    """
    if not isinstance(punch, Punch):
        raise ValueError(f"`punch` = {punch!r} must be a closedform.Punch")
    _validate(P, s, E, nu, tilt, max_iter)
    t_start = time.perf_counter()
    pre = preset(mesh) if isinstance(mesh, str) and not mesh.endswith(".msh") else mesh
    chosen: MeshArg = mesh
    for attempt in range(2):
        t0 = time.perf_counter()
        sub, L, guess, t_locate = _substrate(chosen, punch, P, s, E, nu, tilt, max_iter)
        t1 = time.perf_counter()
        sc = condense(sub, E, nu)
        t2 = time.perf_counter()
        sol = _contact(sc, punch, P, s, tilt, max_iter, guess)
        p = sol.f / sc.weights
        left, right = _ends(sc.x, p, sol.active, (-punch.b, punch.b))
        h_end = _end_size(sc.x, left, right)
        finer = refined(punch, left, right, h_end, pre, attempt)
        if finer is None:
            break
        chosen = finer   # refine at the ends and joins, solve again
    flds = fields_of(*sc.displacement(sol.f), E, nu) if fields else None
    t3 = time.perf_counter()
    timings = {"locate": t_locate, "mesh": t1 - t0 - t_locate, **sc.timings, "contact": t3 - t2,
               "total": t3 - t_start}
    s_out = float(np.sum(sc.x * sol.f) / np.sum(sol.f))
    info = {"dofs": sc.dofs, "h": sc.h, "h_end": h_end, "L": L, "n_candidates": len(sc.x),
            "backend": sc.backend,
            "iterations": sol.iterations, "delta": sol.delta, "timings": timings,
            "mesh": mesh if isinstance(mesh, str) else type(mesh).__name__,
            "refined": (float(chosen.refine / pre.refine) if isinstance(chosen, MeshPreset)
                        and isinstance(pre, MeshPreset) else 1.0)}
    return FemResult(punch=punch, A=rigid_punch(E, nu), a=-left, c=right,
                     alpha=sol.alpha, P=float(np.sum(sol.f)),
                     s=s_out, tilt=tilt, method="fem", info=info, h=sc.h, dofs=sc.dofs,
                     L=L, delta=sol.delta, timings=timings, x_nodes=sc.x, p_nodes=p, fields=flds)

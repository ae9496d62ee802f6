"""``solve_normal``: the FE answer to the load-controlled normal contact problem.

Steps: locate the contact roughly with a trial solve on a coarse mesh (no closed
form is used), mesh the substrate around it with :mod:`meshes`, condense the
elastic body onto the candidate surface nodes (:mod:`fem.elasticity`), solve the
contact (:mod:`fem.contact`), and recover the pressure ``p_i = f_i / w_i`` and the
contact ends, found between nodes by extrapolating ``p^2`` to zero.

``kinematics="first_order"`` condenses both displacement components and solves
the contact on the deformed surfaces to first order in the slopes
(:func:`fem.contact.first_order_compliance`; ``docs/SMALL_SLOPE.md``).
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple, Union

import numpy as np
from numpy.typing import ArrayLike

from threepart.problem.punch import Punch

from threepart.problem.checks import integer
from threepart.problem.validate import check_contact
from threepart.errors import ContactZoneError, InputError, InputTypeError, SeparationError
from threepart.problem.material import rigid_punch
from threepart.problem.material import NU
from threepart.results import Diagnostics, NormalResult
from threepart.stress import Stress
from threepart.meshes import SubstrateSpec

from threepart.halfplane.surface import PerArray

from .contact import ContactSolution, check_kinematics, solve_contact, solve_kinematic
from .export import Fields, fields_of
from .recovery import StressField, lazy_field, model_nu
from .elasticity import SurfaceCompliance, condense
from ._boundary import boundary
from ._iv import mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .ends import REFINE_ATTEMPTS, check_one_zone, contact_ends, end_size, refined
from .mesh import PRESETS, MeshPreset, Substrate, make_substrate, read_substrate

__all__ = ["FemResult", "solve_normal", "deformed_ends", "locate_contact", "locate_ends",
           "place_substrate", "preset_ends", "MeshArg", "TRIES_DEFAULT", "TRIES"]

MeshArg = Union[str, Path, MeshPreset, SubstrateSpec, Substrate]

@dataclass(frozen=True)
class FemResult(NormalResult):
    """FE solution of the normal problem, with its discretisation in ``diagnostics``.

    Attributes (beyond :class:`~threepart.results.NormalResult`)
    ----------
    delta
        Rigid indentation of the punch (depends on ``L``: half-plane displacements diverge).
    x_nodes, p_nodes
        Candidate node positions and their pressures ``f_i / w_i``.
    fields
        Displacement and stress (:class:`~fem.export.Fields`) when asked for.
    stress_field
        The substrate's displacement field, for :meth:`stress`.

    ``diagnostics`` (:class:`~threepart.results.Diagnostics`) holds ``h`` (the
    element size along the contact zone; P2 node spacing is ``h/2``), ``h_end``,
    ``dofs``, ``L`` (block size), the active-set ``iterations`` and the
    ``timings`` (``locate``, cached per case in a run; ``mesh``, ``assemble``,
    ``factorise``, ``contact``, ``total``).
    """

    delta: float = math.nan
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    p_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    fields: Fields | None = field(default=None, compare=False, repr=False)
    stress_field: StressField | None = field(default=None, compare=False, repr=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure, linear between nodes, 0 at the ends and outside ``[-a, c]``."""
        x = np.asarray(x, dtype=float)
        inside = (self.x_nodes > -self.a) & (self.x_nodes < self.c)
        xs = np.concatenate([[-self.a], self.x_nodes[inside], [self.c]])
        ps = np.concatenate([[0.0], self.p_nodes[inside], [0.0]])
        return np.interp(x, xs, ps, left=0.0, right=0.0)

    def stress(self, x: ArrayLike, z: ArrayLike, *, nu: float | None = None) -> Stress:  # type: ignore[override]
        """Stresses in the substrate at ``(x, z)``, ``z >= 0`` the depth, from the FE field.

        Recovered by :class:`fem.recovery.StressField` (L2 projection onto
        continuous P2); ``nu`` must be the model's Poisson ratio (``None``).
        A result without its field (rebuilt by hand) falls back to Flamant's
        kernels over its pressure (:meth:`NormalResult.stress`).
        """
        if self.stress_field is None:
            return super().stress(x, z, nu=NU if nu is None else nu)
        model_nu(nu, self.stress_field.nu)
        return self.stress_field.at(x, z)


def _contact(sc: SurfaceCompliance, punch: Punch, P: float, s: float, tilt: str,
             max_iter: int, guess: tuple[float, float] | None = None,
             kinematics: str = "small") -> ContactSolution:
    """Solve the contact on ``sc``, warm-started from the trial contact ``guess`` if there is one.

    ``kinematics = "first_order"`` needs ``sc`` condensed on both components;
    the slope its forces act along is ``sol.slope`` (:func:`fem.contact.solve_kinematic`).
    """
    g0 = punch.profile(sc.x)
    active = None if guess is None else (sc.x >= guess[0]) & (sc.x <= guess[1])
    if active is None and kinematics == "small":
        active = _last_active(sc)          # another load on this condensed body: start from its last contact
    sol = solve_kinematic(sc.C, sc.x, g0, punch.slope(sc.x), P, s, kinematics=kinematics,
                          free_tilt=tilt == "free", max_iter=max_iter,
                          active=active if active is not None and active.any() else None,
                          profile=punch.profile)
    if sol.active[0] or sol.active[-1]:
        raise ContactZoneError(
            f"the contact reaches the candidate zone end [{sc.x[0]:.6g}, {sc.x[-1]:.6g}]; "
            "use a wider zone (a larger preset `margin`)")
    check_one_zone(sc.x, sol.active, P, s)
    if kinematics == "small":
        _LAST_ACTIVE.put(sc.C, None, sol.active.copy())
    return sol


#: the last contact solved on each condensed body in memory (keyed by its compliance matrix, which the
#: run's memory shares between the copies it hands out): the start of the next solve on it without a trial
#: contact (another load on a given mesh, issue 41); the active set's answer does not depend on its start
#: condensed bodies whose last contact is kept
LAST_ACTIVE_KEPT = 8
_LAST_ACTIVE = PerArray(LAST_ACTIVE_KEPT)


def _last_active(sc: SurfaceCompliance) -> np.ndarray | None:
    last = _LAST_ACTIVE.get(sc.C)
    return None if last is None or last.shape != sc.x.shape else last.copy()


def _guess(punch: Punch, P: float, s: float, A: float) -> tuple[float, float]:
    """Generous Hertz-type bracket of the contact, for the first trial mesh only."""
    a1, a2 = (math.sqrt(2 * P * A * R / math.pi) for R in (punch.R1, punch.R2))
    return min(-punch.b, s) - 1.5 * a1, max(punch.b, s) + 1.5 * a2


#: trial meshes :func:`locate_contact` may try (its default, and the bounds of ``tries``)
TRIES_DEFAULT = 6
TRIES = (1, 20)


@boundary
def locate_contact(punch: Punch, P: float, s: float, *, E: float, nu: float, tilt: str,
                   max_iter: int = 100, tries: int = 6) -> tuple[float, float]:
    """Estimate the contact ``(-a, c)`` by solves on the coarse ``"trial"`` and ``"locate"`` meshes.

    The trial zone is widened when the contact reaches its ends and narrowed
    around the contact when it spans too few elements. A solve on the
    ``"locate"`` mesh around the trial contact then places the ends to about
    1e-4 W, where the refined presets put mesh nodes. Estimates are cached for
    the run: the presets of one case share them. ``tries`` (trial meshes) lies
    in ``[1, 20]``; the other arguments are checked as by :func:`solve_normal`.
    """
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=False)
    tries = integer("tries", tries, *TRIES)
    return locate_ends(punch, P, s, E, nu, tilt, max_iter, tries)


@functools.lru_cache(maxsize=64)
def locate_ends(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                max_iter: int, tries: int) -> tuple[float, float]:
    """The contact ends by the trial and locate solves (:func:`locate_contact` without its checks).

    For callers in :mod:`threepart.fem` whose input is already checked.
    """
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
        left, right = contact_ends(sc.x, p, sol.active, breaks)
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
    return contact_ends(sc.x, sol.f / sc.weights, sol.active, breaks)


def place_substrate(mesh: MeshPreset | Path | SubstrateSpec | Substrate, punch: Punch, P: float,
               s: float, E: float, nu: float, tilt: str, max_iter: int, say: Progress,
               ends: tuple[float, float] | None = None
               ) -> tuple[Substrate, float, tuple[float, float] | None, float]:
    """The substrate selected by the checked ``mesh`` (:func:`fem._iv.mesh_arg`), its block
    size ``L``, the located contact and the seconds spent locating it.

    A preset is meshed around the contact :func:`locate_contact` finds, or around
    ``ends`` when given (the ends a solve on a coarser mesh found, when refining).
    """
    guess, t_locate = ends, 0.0
    if isinstance(mesh, Substrate):
        sub = mesh
    elif isinstance(mesh, SubstrateSpec):
        sub = make_substrate(mesh)
    elif isinstance(mesh, Path):
        sub = read_substrate(mesh)
    else:
        if guess is None:
            guess, t_locate = preset_ends(punch, P, s, E, nu, tilt, max_iter, say)
        sub = make_substrate(mesh.spec(*guess, (-punch.b, punch.b)))
    L = float(np.ptp(sub.mesh.p[0]))
    return sub, L, guess, t_locate


def preset_ends(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str, max_iter: int,
                say: Progress) -> tuple[tuple[float, float], float]:
    """The contact a preset is meshed around (:func:`locate_ends`) and the seconds spent locating it;
    for a caller that meshes the preset itself (:func:`place_substrate` without the mesh)."""
    t0 = time.perf_counter()
    guess = locate_ends(punch, P, s, E, nu, tilt, max_iter, TRIES_DEFAULT)
    t_locate = time.perf_counter() - t0
    say(f"locate: contact about [{guess[0]:.6g}, {guess[1]:.6g}] ({t_locate:.1f} s)")
    return guess, t_locate


class _Refined(NamedTuple):
    """The contact solved on the mesh that resolves its ends (:func:`_solve_refining`)."""

    chosen: Any        # the mesh argument finally used (a preset refined at the ends, or as given)
    sc: SurfaceCompliance  # the condensed surface problem
    sol: ContactSolution   # the contact solution on it
    left: float
    right: float
    h_end: float       # the element size at the contact's ends
    L: float           # the block's half-width
    t_locate: float    # seconds spent placing the substrate (all attempts)
    t_mesh: float      # seconds of meshing in the last attempt
    t_contact: float   # perf_counter() when the last contact solve started


def _solve_refining(pre: Any, punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                    max_iter: int, say: Progress, kinematics: str) -> _Refined:
    """Mesh, condense and solve; refine a preset at the ends while an end lies near a join."""
    components = ("u^2",) if kinematics == "small" else ("u^1", "u^2")
    chosen, found, t_locate = pre, None, 0.0
    for attempt in range(REFINE_ATTEMPTS + 1):
        t0 = time.perf_counter()
        sub, L, guess, t_loc = place_substrate(chosen, punch, P, s, E, nu, tilt, max_iter, say,
                                               found)
        t_locate += t_loc
        t1 = time.perf_counter()
        say(f"mesh: {sub.mesh.t.shape[1]} triangles ({t1 - t0 - t_loc:.1f} s)")
        sc = condense(sub, E, nu, components)
        t2 = time.perf_counter()
        say(f"condense: {sc.dofs} DOFs onto {len(sc.x)} surface nodes ({t2 - t1:.1f} s)")
        sol = _contact(sc, punch, P, s, tilt, max_iter, guess, kinematics)
        p = sol.f / sc.weights
        left, right = contact_ends(sc.x, p, sol.active, (-punch.b, punch.b))
        h_end = end_size(sc.x, left, right)
        say(f"contact: [{left:.6g}, {right:.6g}], {sol.iterations} iterations "
            f"({time.perf_counter() - t2:.1f} s)")
        finer = refined(punch, left, right, h_end, chosen, attempt, pre)
        if finer is None:
            break
        say(f"refine: an end lies near a join, elements W / (n {finer.refine:g}) there")
        chosen, found = finer, (left, right)   # refine at these ends and the joins, solve again
    return _Refined(chosen, sc, sol, left, right, h_end, L, t_locate, t1 - t0 - t_loc, t2)


@boundary
def solve_normal(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                 tilt: str = "free", mesh: MeshArg = "default",
                 max_iter: int = 100, fields: bool = False,
                 progress: ProgressArg = None, kinematics: str = "small") -> FemResult:
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
        The block's, under the rigid punch (two similar bodies of E: E/2, ``material.block_modulus``).
    tilt
        ``"free"``: translation and tilt unknown; ``"suppressed"``: ``alpha = 0``.
    mesh
        A preset name (``"quick"``, ``"default"``, ``"fine"``), a :class:`~fem.mesh.MeshPreset`,
        a :class:`~meshes.SubstrateSpec`, a :class:`~fem.mesh.Substrate` or the path of a
        ``.msh`` file with ``"contact"`` and ``"base"`` groups.
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    fields
        Also recover the displacement and stress fields (for :func:`fem.write_fields`).
    progress
        One line per stage on stderr (:mod:`fem._progress`): ``None`` (default)
        when stderr is a terminal, ``True``, ``False``, or a callable taking each line.
    kinematics
        ``"small"`` (default): the half-plane theory's contact, the gap measured
        vertically between the undeformed surfaces, the force vertical.
        ``"first_order"``: the contact conditions on the deformed surfaces to first
        order in the slopes (:func:`fem.contact.first_order_compliance`): the gap
        to the punch's face over the displaced surface point, and the force along
        the punch's normal (a tangential traction ``p v'(x)`` outward). ``P`` and
        ``s`` stay the vertical resultant and its lever arm; ``a``, ``c`` and the
        pressure refer to the block's undeformed surface (the contact ends on the
        punch are :func:`deformed_ends`).

    Returns
    -------
    FemResult
        With ``method = "fem"`` and ``A = 2 (1 - nu^2) / E``; ``info["kinematics"]``
        is set for ``"first_order"`` only.

    Raises
    ------
    TypeError, ValueError
        For invalid input, naming the argument and its limit, before any numerics:
        ``P`` > 0 with ``A P max(R1, R2, b)`` representable, ``s`` inside the
        punch's footprint (:func:`threepart.problem.validate.lever_arm`), ``nu`` in
        ``(-1, 0.5)``, ``E`` > 0, ``tilt``, ``mesh``, ``max_iter``, ``kinematics``.
    ArcExtentError, SlopeLimitError
        If the solved contact runs past an arc's extent or its surface slope
        exceeds the small-slope limit (:func:`threepart.problem.validate.check_contact`).
    NoConvergenceError
        If the contact iteration does not converge, or a numerical step (gmsh,
        a factorisation) fails.
    ContactZoneError
        If the contact reaches the end of the candidate zone.
    SeparationError
        If the contact separates into two zones (a concave centre at a light load).
    MeshResolutionError
        If a contact end lies within ``MIN_END_ELEMENTS`` elements of a join and a
        preset refined ``MAX_REFINEMENT`` times (or the mesh given) cannot resolve it.
        A preset is first refined automatically (``info["refined"]`` says how much).
    """
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=False)
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    if not isinstance(fields, (bool, np.bool_)):
        raise InputTypeError(f"`fields` must be a bool, not {type(fields).__name__}")
    kinematics = check_kinematics(kinematics)
    say = Progress(progress_iv(progress))
    t_start = time.perf_counter()
    run = _solve_refining(pre, punch, P, s, E, nu, tilt, max_iter, say, kinematics)
    check_contact(punch, -run.left, run.right, run.sol.alpha)
    return _normal_result(run, punch, E, nu, tilt, (mesh, pre), fields, kinematics, t_start)


def _normal_result(run: _Refined, punch: Punch, E: float, nu: float, tilt: str, meshes: tuple[Any, Any],
                   fields: bool, kinematics: str, t_start: float) -> FemResult:
    """The :class:`FemResult` of :func:`solve_normal`'s refined contact ``run``."""
    mesh, pre = meshes
    sc, sol, left, right, t2 = run.sc, run.sol, run.left, run.right, run.t_contact
    # the nodal forces on the block: downward f (small), or (v' f, -f) in the global directions
    F = sol.f if kinematics == "small" else np.concatenate([sol.slope * sol.f, -sol.f])
    if fields:
        basis, u = sc.displacement(F)
        flds, stress_field = fields_of(basis, u, E, nu), StressField(basis=basis, u=u, E=E, nu=nu)
    else:   # a condensation read from the cache factorises only if a stress is asked for
        flds, stress_field = None, lazy_field(sc.displacement_later(F), E, nu)
    t3 = time.perf_counter()
    timings = {"locate": run.t_locate, "mesh": run.t_mesh, **sc.timings, "contact": t3 - t2,
               "total": t3 - t_start}
    s_out = float(np.sum(sc.x * sol.f) / np.sum(sol.f))
    info = {"n_candidates": len(sc.x), "backend": sc.backend,
            "mesh": mesh if isinstance(mesh, str) else type(mesh).__name__,
            "refined": (float(run.chosen.refine / pre.refine) if isinstance(run.chosen, MeshPreset)
                        and isinstance(pre, MeshPreset) else 1.0)}
    if kinematics != "small":
        info["kinematics"] = kinematics
    diag = Diagnostics(h=sc.h, h_end=run.h_end, dofs=sc.dofs, L=run.L, iterations=sol.iterations,
                       residual=sol.residual, timings=timings)
    return FemResult(punch=punch, A=rigid_punch(E, nu), a=-left, c=right,
                     alpha=sol.alpha, P=float(np.sum(sol.f)),
                     s=s_out, tilt=tilt, method="fem", diagnostics=diag, info=info,
                     delta=sol.delta, x_nodes=sc.x, p_nodes=sol.f / sc.weights, fields=flds,
                     stress_field=stress_field)


def deformed_ends(result: FemResult) -> tuple[float, float]:
    """The contact's half-widths ``(a, c)`` on the rigid punch: the ends moved by the surface's ``u_x``.

    ``result.a`` and ``result.c`` are positions on the block's undeformed
    surface; its point there has moved by ``u_x`` (the block's FE field, read
    at its surface DOFs ``y = 0`` and interpolated linearly), and touches the
    punch at ``x + u_x``: ``(a - u_x(-a), c + u_x(c))``. This is where a
    finite-deformation model (CalculiX, ``benchmarks/small_slope_calculix.py``)
    places the contact's end. To first order the two differ by ``u_x``, as
    large as the first-order change of the kinematics itself.

    Raises
    ------
    ValueError
        If ``result`` carries no displacement field (a rebuilt result) or is a
        finite-body result, whose punch deforms too.
    """
    if not isinstance(result, FemResult) or result.stress_field is None:
        raise InputError("`result` must be a FemResult of fem.solve_normal with its field")
    if "H" in result.info:
        raise InputError("`result` is a finite-body result (fem.solve_finite): its punch moves "
                         "too; deformed_ends takes a rigid punch's (fem.solve_normal)")
    basis, u = result.stress_field.basis, result.stress_field.u
    ux = basis.split_indices()[0]
    on = ux[np.abs(basis.doflocs[1, ux]) <= 1e-12 * float(np.ptp(basis.mesh.p[0]))]
    order = np.argsort(basis.doflocs[0, on])
    xs, us = basis.doflocs[0, on][order], u[on][order]
    return (result.a - float(np.interp(-result.a, xs, us)),
            result.c + float(np.interp(result.c, xs, us)))

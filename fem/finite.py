"""A punch of real shape on a finite block: where the half-plane idealisation stops (issue 12).

The punch (:mod:`meshes.punch`) is an elastic body: flat centre ``[-b, b]``, exact
edge arcs of radius ``R1`` and ``R2``, straight flanks from the flank angle
``theta`` up to its height ``H``, where it is welded to a rigid loading plate
that translates by ``-delta`` and tilts by ``alpha``. It stands on the block of
:mod:`fem.mesh`; both have ``E`` and ``nu`` (``A = 4 (1 - nu^2) / E``).

Contact is frictionless and the block's surface is flat, so the contact force
at a node is vertical. The punch's lower face has a vertex over each of the
block's surface vertices (:mod:`meshes.punch`), so the two bodies pair node by
node, and with ``g_i`` the height of the punch's face over node ``i`` (on the
exact circle, at vertices and edge midpoints alike)::

    gap_i = g_i + alpha x_i - delta + ((C_P + C_S) f)_i,

where ``C_P`` and ``C_S`` are the two bodies' vertical surface compliances
(:func:`fem.elasticity.condense`; the punch clamped at its top, the block at
its base). It is solved like the rigid punch (:func:`fem.contact.solve_contact`),
in two passes: on the ``"locate"`` mesh around the half-plane estimate of the
contact, then on the preset's mesh with nodes and fine elements at the ends the
first pass found. Small strain, small displacement; the geometry of the arcs
and of the finite bodies is exact (to the chords of the mesh).

``kinematics = "first_order"`` measures the gap between the deformed surfaces
and turns the contact force along the deformed face's normal, to first order in
the slopes (:func:`fem.contact.first_order_compliance`): both bodies are
condensed on both displacement components, and their compliances, each in its
own orientation, sum to that of the relative displacement
``u^block - u^punch``. The face's slope is that of the deformed punch face
(in contact, the interface: half the punch's ``v'`` plus half the two faces'
common deflection), taken from a first solve with the punch's face slope
``v'`` and used in one more; ``v'`` enters as its secant over the relative
tangential displacement, which keeps the spurious spike of a tangent off the
joins ``x = +-b`` (:func:`fem.contact.solve_kinematic`).
Both first-order terms act through the normal-tangential coupling of the
relative compliance, which vanishes for two elastically similar half-planes
(Dundurs' ``beta = 0``): with ``H = None`` (the mirrored block) the option
changes nothing but round-off; a punch of finite height couples through its
own shape.
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import replace
from typing import Any

import numpy as np

from threepart.errors import ContactZoneError, InputError
from threepart.problem.material import similar_pair
from threepart.meshes import SubstrateSpec
from threepart.meshes.punch import PunchSpec
from threepart.problem.punch import Punch
from threepart.results import Diagnostics
from threepart.problem.validate import check_contact, check_punch

from .contact import ContactSolution, check_kinematics, solve_kinematic
from .elasticity import SurfaceCompliance, condense
from .recovery import lazy_field
from .interface import check_matched, mirror
from ._boundary import boundary
from ._iv import height_iv, mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .ends import REFINE_ATTEMPTS, check_one_zone, contact_ends, end_size, refined
from .mesh import PRESETS, MeshPreset, make_punch, make_substrate
from .solve import FemResult, TRIES_DEFAULT, locate_ends

__all__ = ["solve_finite", "zone_margin"]


def _solve(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str, max_iter: int,
           zone: SubstrateSpec, H: float | None, theta: float, profile: str,
           kinematics: str = "small"
           ) -> tuple[ContactSolution, SurfaceCompliance, dict[str, float], int, float]:
    """Contact of the punch body on the block, both meshed around ``zone``; with the
    condensed block, the timings, both bodies' DOFs and the block's width ``L``.

    ``H = None`` is the paper's model: the punch body is the block's mirror
    image (:func:`fem.friction.mirror`), a large body whose lower face carries
    the profile of eq. (2) as the initial gap. The solution's ``slope`` is the
    face's slope the forces act along (zeros for ``kinematics = "small"``).
    """
    t0 = time.perf_counter()
    block = make_substrate(zone)
    if H is None:
        body = mirror(block)
    else:
        spec = PunchSpec(zone=zone, b=punch.b, R1=punch.R1, R2=punch.R2, H=H, theta=theta,
                         profile=profile, growth=zone.growth)
        body = make_punch(spec)
    t1 = time.perf_counter()
    components = ("u^2",) if kinematics == "small" else ("u^1", "u^2")
    S, B = condense(block, E, nu, components), condense(body, E, nu, components)
    check_matched(S.x, B.x, "the block and the punch body")
    t2 = time.perf_counter()
    if H is None:
        g0 = punch.profile(S.x)
    else:
        # the exact face over every node: the straight-sided P2 elements follow the chords,
        # by O(h^2 / R), but a gap that kinks at each vertex would err by O(h) at the peaks
        g0 = spec.height(S.x)
    if H is None:
        slope = punch.slope(S.x)
    else:   # the exact face's slope, by central differences far below the mesh size
        e = 1e-7 * float(np.ptp(S.x))
        slope = (spec.height(S.x + e) - spec.height(S.x - e)) / (2 * e)
    n = len(S.x)

    def face_common(sol: ContactSolution) -> np.ndarray:
        """The faces' common vertical displacement ``u_y^block + u_y^punch`` at the nodes."""
        assert sol.slope is not None
        F = np.concatenate([sol.slope * sol.f, -sol.f])
        return (S.C @ F)[n:] - (B.C @ F)[n:]    # B.C holds the punch's in its own orientation

    sol = solve_kinematic(S.C + B.C, S.x, g0, slope, P, s, kinematics=kinematics,
                          free_tilt=tilt == "free", max_iter=max_iter, face_common=face_common,
                          profile=punch.profile if H is None else spec.height)
    if sol.active[0] or sol.active[-1]:
        raise ContactZoneError(
            f"the contact reaches the candidate zone end [{S.x[0]:.6g}, {S.x[-1]:.6g}]")
    check_one_zone(S.x, sol.active, P, s)
    timings = {"mesh": t1 - t0, "condense": t2 - t1, "contact": time.perf_counter() - t2}
    return sol, S, timings, S.dofs + B.dofs, float(np.ptp(block.mesh.p[0]))


def locate_finite(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                  max_iter: int, H: float | None, theta: float, profile: str, say: Progress
                  ) -> tuple[float, float, MeshPreset]:
    """The finite body's contact ends ``(-a, c)`` on the ``"locate"`` mesh, and that mesh's preset.

    Starts from the half-plane estimate (the pair is a rigid punch on ``E/2``);
    a contact that reaches the candidate zone's end doubles the zone's margin
    (three times at most).
    """
    t0 = time.perf_counter()
    left, right = locate_ends(punch, P, s, 0.5 * E, nu, tilt, max_iter, TRIES_DEFAULT)
    say(f"locate: half-plane contact about [{left:.6g}, {right:.6g}] "
        f"({time.perf_counter() - t0:.1f} s)")
    return _located(punch, P, s, E, nu, tilt, max_iter, H, theta, profile, (left, right))


@functools.lru_cache(maxsize=64)
def _located(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str, max_iter: int,
             H: float | None, theta: float, profile: str, estimate: tuple[float, float]
             ) -> tuple[float, float, MeshPreset]:
    """:func:`locate_finite` from the half-plane ``estimate``: a pure function of its
    arguments, kept for the run, so that the two meshes of a map point (and its
    partial slip's) locate the contact once."""
    left, right = estimate
    breaks = (-punch.b, punch.b)
    locate = replace(PRESETS["locate"], margin=zone_margin(punch.b, left, right, 0.15))
    for _ in range(4):
        try:
            sol, S, _, _, _ = _solve(punch, P, s, E, nu, tilt, max_iter,
                                     locate.spec(left, right, breaks), H, theta, profile)
            break
        except ContactZoneError:
            locate = replace(locate, margin=min(2.0, 2 * locate.margin))
    else:
        raise ContactZoneError("the finite-body contact outgrows every candidate zone tried")
    left, right = contact_ends(S.x, sol.f / S.weights, sol.active, breaks)
    return left, right, locate


def zone_margin(b: float, left: float, right: float, margin: float) -> float:
    """The candidate zone's margin (a fraction of ``W``) for a contact ``[left, right]``.

    ``margin`` of ``W``, but no more than the overhangs past the joins ``±b``
    (and no less than 2 % of ``W``): a wide flat centre makes ``W`` large while
    the ends move only with the overhang, and the zone must stay on the punch's
    lower face, whose arcs end at the flanks.
    """
    W = right - left
    return min(margin, max(0.02, (W - 2 * b) / W))


def finite_iv(punch: Any, P: Any, s: Any, E: Any, nu: Any, H: Any, theta: Any, profile: Any,
               tilt: Any, mesh: Any, max_iter: Any, progress: Any,
               kinematics: Any = "small") -> tuple[Any, ...]:
    """The checked input of :func:`solve_finite`, before any numerics."""
    check_punch(punch)
    if not math.isinf(punch.R):
        raise InputError(f"`punch` has R = {punch.R!r}: the finite punch has a flat centre (R = inf)")
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=True)
    H, theta, profile = height_iv(punch, H, theta, profile)
    pre = mesh_arg(mesh, (MeshPreset,), allow_path=False)
    kinematics = check_kinematics(kinematics)
    return P, s, E, nu, H, theta, profile, tilt, pre, max_iter, progress_iv(progress), kinematics


@boundary
def solve_finite(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float, H: float | None,
                 theta: float = math.pi / 3, profile: str = "arc", tilt: str = "free",
                 mesh: str | MeshPreset = "default", max_iter: int = 100,
                 progress: ProgressArg = None, kinematics: str = "small") -> FemResult:
    """A punch of real shape and height ``H`` pressed into a finite block by ``P`` at ``s``.

    Parameters
    ----------
    punch
        ``b``, ``R1``, ``R2`` of the punch (a flat centre, ``R = inf``).
    P, s, tilt
        Load, lever arm and tilt mode, as in :func:`fem.solve_normal`.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    H, theta, profile
        The punch's height, flank angle and edge shape (``"arc"`` or ``"parabola"``).
        ``H = None``: the paper's model (the map's control), a punch body as large
        as the block, its lower face flat with the profile of eq. (2) as the gap.
        ``H`` is at most ``1000 (b + max(R1, R2))``, ``theta`` in ``(0, pi/2)``.
    mesh
        A preset (its size relative to the contact width, its grading).
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    progress
        One line per stage on stderr, as in :func:`fem.solve_normal`.
    kinematics
        ``"small"`` (default) or ``"first_order"``: the contact conditions on the
        deformed surfaces to first order in the slopes, as in
        :func:`fem.solve_normal` (module docstring; the first solve that locates
        the contact keeps the small kinematics).

    Returns
    -------
    FemResult
        With ``method = "fem"``; ``info`` holds ``H``, ``theta``, ``profile`` and,
        for ``"first_order"``, ``kinematics``.

    Raises
    ------
    TypeError, ValueError
        For invalid input (before any numerics, as :func:`fem.solve_normal`), or a
        punch whose lower face or height cannot hold the contact.
    ArcExtentError, SlopeLimitError
        With ``H = None`` (the paper's model): if the contact runs past an arc's
        extent or its surface slope exceeds the small-slope limit
        (:func:`threepart.problem.validate.check_contact`), as :func:`fem.solve_normal`.
        With a finite ``H`` the punch's exact face bounds the contact (it ends at
        the flank angle, ``b + R sin theta < b + R``: a zone past it is a
        ``ValueError``), and the slope limit is not applied: this model measures
        where the small-slope idealisation stops (the validity map's points reach
        ``(a - b)/R1 = 0.5``).
    ContactZoneError, SeparationError, NoConvergenceError
        As :func:`fem.solve_normal`.
    """
    P, s, E, nu, H, theta, profile, tilt, pre, max_iter, progress, kinematics = finite_iv(
        punch, P, s, E, nu, H, theta, profile, tilt, mesh, max_iter, progress, kinematics)
    say = Progress(progress)
    t_start = time.perf_counter()
    breaks = (-punch.b, punch.b)
    left, right, _ = locate_finite(punch, P, s, E, nu, tilt, max_iter, H, theta, profile, say)
    t_locate = time.perf_counter() - t_start
    pre = replace(pre, margin=zone_margin(punch.b, left, right, pre.margin))
    base = pre
    for attempt in range(REFINE_ATTEMPTS + 1):   # an end near a join refines the mesh there, as in solve_normal
        sol, S, timings, dofs, L = _solve(punch, P, s, E, nu, tilt, max_iter,
                                          pre.spec(left, right, breaks), H, theta, profile,
                                          kinematics)
        a_end, c_end = contact_ends(S.x, sol.f / S.weights, sol.active, breaks)
        finer = refined(punch, a_end, c_end, end_size(S.x, a_end, c_end), pre, attempt, base)
        if finer is None:
            break
        pre, left, right = finer, a_end, c_end
    say(f"contact: [{a_end:.6g}, {c_end:.6g}], {dofs} DOFs ({time.perf_counter() - t_start:.1f} s)")
    if H is None:
        check_contact(punch, -a_end, c_end, sol.alpha)
    timings = {"locate": t_locate, **timings, "total": time.perf_counter() - t_start}
    return _finite_result(punch, E, nu, tilt, (H, theta, profile), mesh, kinematics, sol, S,
                          (dofs, L), (a_end, c_end), timings)


def _finite_result(punch: Punch, E: float, nu: float, tilt: str, shape: tuple[float | None, float, str],
                   mesh: Any, kinematics: str, sol: Any, S: Any, size: tuple[int, float],
                   ends: tuple[float, float], timings: dict[str, float]) -> FemResult:
    """The :class:`FemResult` of :func:`solve_finite`'s contact ``sol`` on the surface ``S``
    (``size``: both bodies' DOFs and the block's width).

    Its stress field is made when first asked for (:func:`fem.recovery.lazy_field`): a
    condensation read from the cache factorises the block only then (a map point asks
    only for the surface's pressure).
    """
    H, theta, profile = shape
    dofs, L = size
    a_end, c_end = ends
    x = S.x
    p = sol.f / S.weights
    h = float(np.max(np.diff(x)) * 2)
    info = {"H": H, "theta": theta, "profile": "eq. 2" if H is None else profile,
            "mesh": mesh if isinstance(mesh, str) else type(mesh).__name__,
            "model": "punch of real shape on a finite block"}
    if kinematics != "small":
        info["kinematics"] = kinematics
    diag = Diagnostics(h=h, h_end=end_size(x, a_end, c_end), dofs=dofs,
                       L=L, iterations=sol.iterations,
                       residual=sol.residual, timings=timings)
    # the block's nodal forces: downward f (small), or (v' f, -f) in the global directions
    F = sol.f if kinematics == "small" else np.concatenate([sol.slope * sol.f, -sol.f])
    return FemResult(punch=punch, A=similar_pair(E, nu), a=-a_end, c=c_end, alpha=sol.alpha,
                     P=float(np.sum(sol.f)), s=float(np.sum(x * sol.f) / np.sum(sol.f)),
                     tilt=tilt, method="fem", diagnostics=diag, info=info, delta=sol.delta,
                     x_nodes=x, p_nodes=p,
                     stress_field=lazy_field(S.displacement_later(F), E, nu))

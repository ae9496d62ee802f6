"""Partial slip of a punch of real shape on a finite block (issue 23): the stick zone past the half-plane.

The bodies are those of :func:`fem.solve_finite`: the punch (:mod:`meshes.punch`:
flat centre ``[-b, b]``, exact edge arcs ``R1`` and ``R2``, straight flanks
from the flank angle ``theta`` up to its height ``H``, its top welded to a rigid
loading plate) on the block of :mod:`fem.mesh`, both of ``E`` and ``nu``. The
friction model is :mod:`fem.friction`'s (:class:`fem.twobody.TwoBodyModel`):
both bodies condensed onto their matched interface nodes, both displacement
components (:func:`fem.interface.interface`), the gap of the punch's exact face
``spec.height(x)`` over each node, Coulomb friction ``f`` node by node
(:func:`fem.coulomb.tangential`). Load path as everywhere: ``P`` at ``s`` first
(frictionless), then ``Q`` in equal steps. ``s`` is the lever arm of the
interface's normal force: the plate carries whatever moment ``Q`` adds.

Coupling, and what it means for the closed form. Dundurs' ``beta = 0`` makes
the normal and tangential problems uncouple for two similar *half-planes*; the
paper's model (``H = None`` here: the block's mirror image, the profile of
eq. 2) keeps that exactly, ``C_nt = C_tn = 0``. A punch of finite height and
real shape is not the block's mirror image, so its flexibility blocks do not
cancel the block's: the coupling ``C_nt``, ``C_tn`` the condensation gives is
kept, and each step iterates the normal and tangential problems to a fixed point.
Two effects follow that the closed form has not: the shear moves the pressure
(``C_nt t``: the punch's flanks and its clamped top respond unlike a
half-plane), so the stick zone shifts and ``e != 0`` even for a symmetric punch
at ``s = 0``, with the sign of ``Q``; and the frictionless normal load leaves a
relative tangential displacement ``C_tn fn`` that the stick nodes keep (friction
is engaged only after ``P``, as in the paper's load path). The differences from
the closed form's ``d`` and ``e`` therefore measure the half-plane idealisation
of both the normal and the tangential problem. They shrink as the punch grows
tall and the contact small against ``R1``, ``R2``, ``H`` and the punch's face
(tests/test_finite_slip.py: for a symmetric punch, ``(a - b)/R1 = 0.01``, the
closed form's ``d`` errs by 9.8e-4 at ``H = 4 b`` and 4.9e-4 at ``H = 40 b``; its
``e = 0`` holds to 6e-5 ``d``).
"""
from __future__ import annotations

import functools
import math
import time
from dataclasses import replace
from typing import Any

import numpy as np

from threepart.errors import ContactZoneError
from threepart.meshes import SubstrateSpec
from threepart.meshes.punch import PunchSpec
from threepart.problem.punch import Punch
from threepart.problem.checks import integer
from threepart.problem.validate import check_contact, shear_load

from ._boundary import boundary
from ._iv import STEPS
from ._progress import Progress, ProgressArg
from .ends import REFINE_ATTEMPTS, end_size, refined
from .finite import finite_iv, locate_finite, zone_margin
from .friction import FemSlipResult, shear_path
from .mesh import MeshPreset, make_punch, make_substrate
from .twobody import TwoBodyModel, with_nodes

__all__ = ["solve_finite_slip"]


def _model(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str, max_iter: int,
           f: float, zone: SubstrateSpec, H: float | None, theta: float, profile: str,
           guess: tuple[float, float]) -> TwoBodyModel:
    """The two-body model of the block meshed on ``zone`` and the punch body of height ``H``.

    ``H = None``: the paper's model, the block's mirror image with the profile
    of eq. (2) as the gap (:class:`TwoBodyModel`'s default).
    """
    t0 = time.perf_counter()
    block = make_substrate(zone)
    upper, gap = None, None
    if H is not None:
        spec = PunchSpec(zone=zone, b=punch.b, R1=punch.R1, R2=punch.R2, H=H, theta=theta,
                         profile=profile, growth=zone.growth)
        # the exact face over every node, as in fem.solve_finite
        upper, gap = make_punch(spec), spec.height
    t_mesh = time.perf_counter() - t0
    model = TwoBodyModel(punch, P, s, E, nu, tilt, block, float(np.ptp(block.mesh.p[0])), guess,
                         max_iter, f, upper=upper, gap=gap)
    active = model.normal.active
    if active[0] or active[-1]:
        x = model.itf.x
        raise ContactZoneError(f"the contact reaches the candidate zone end [{x[0]:.6g}, {x[-1]:.6g}]")
    model.timings["mesh"] = t_mesh
    return model


def _slip_finite_iv(punch: Any, P: Any, s: Any, Q: Any, f: Any, E: Any, nu: Any, H: Any,
                    theta: Any, profile: Any, tilt: Any, mesh: Any, steps: Any, max_iter: Any,
                    progress: Any) -> tuple[Any, ...]:
    """The checked input of :func:`solve_finite_slip`: :func:`fem.solve_finite`'s, ``Q``, ``f``, ``steps``."""
    P, s, E, nu, H, theta, profile, tilt, pre, max_iter, progress, _ = finite_iv(
        punch, P, s, E, nu, H, theta, profile, tilt, mesh, max_iter, progress)
    Q, f = shear_load(Q, f, P)
    steps = integer("steps", steps, *STEPS)
    return P, s, Q, f, E, nu, H, theta, profile, tilt, pre, steps, max_iter, progress


@boundary
def solve_finite_slip(punch: Punch, P: float, s: float = 0.0, *, Q: float, f: float, E: float,
                      nu: float, H: float | None, theta: float = math.pi / 3, profile: str = "arc",
                      tilt: str = "free", mesh: str | MeshPreset = "default", steps: int = 10,
                      max_iter: int = 100, progress: ProgressArg = None) -> FemSlipResult:
    """A punch of real shape and height ``H`` on a finite block, pressed by ``P`` at ``s``, then sheared by ``Q``.

    The contact is located as :func:`fem.solve_finite` locates it (the half-plane
    estimate, then the finite bodies on the ``"locate"`` mesh); a first shear
    solve on that mesh places the stick zone of ``Q``, whose ends then become
    mesh nodes with fine elements around them, as the contact ends are
    (:func:`fem.twobody.two_body_model`). An end within ``MIN_END_ELEMENTS`` of
    a join refines the preset, as in :func:`fem.solve_finite`.

    Parameters
    ----------
    punch
        ``b``, ``R1``, ``R2`` of the punch (a flat centre, ``R = inf``).
    P, s, tilt
        Normal load, its lever arm (of the interface's normal force) and tilt mode,
        as in :func:`fem.solve_normal`.
    Q, f
        Shear force the punch exerts on the block along ``+x``, ``|Q| < f P``,
        and coefficient of friction.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    H, theta, profile
        The punch's height, flank angle and edge shape, as in :func:`fem.solve_finite`;
        ``H = None`` is the paper's model (the mirror body, the profile of eq. 2).
    mesh
        A preset (its size relative to the contact width, its grading).
    steps
        Equal increments of ``Q`` from 0, in ``[1, 1000]``.
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    progress
        One line per stage and per load step on stderr, as in :func:`fem.solve_normal`.

    Returns
    -------
    FemSlipResult
        As :func:`fem.solve_partial_slip`, with ``method = "fem"``; ``info`` (and
        the normal result's) holds ``H``, ``theta`` and ``profile``.

    Raises
    ------
    TypeError, ValueError
        For invalid input, before any numerics (as :func:`fem.solve_finite`, and
        ``Q``, ``f``, ``steps`` as :func:`fem.solve_partial_slip`);
        ``FullSlidingError`` for ``|Q| >= f P``.
    ArcExtentError, SlopeLimitError
        With ``H = None`` only, as :func:`fem.solve_finite`.
    ContactZoneError, SeparationError, NoConvergenceError, MeshResolutionError
        As :func:`fem.solve_finite`, and when the stick/slip states or the
        coupled normal and tangential problems do not settle.
    """
    P, s, Q, f, E, nu, H, theta, profile, tilt, pre, steps, max_iter, progress = _slip_finite_iv(
        punch, P, s, Q, f, E, nu, H, theta, profile, tilt, mesh, steps, max_iter, progress)
    say = Progress(progress)
    t0 = time.perf_counter()
    left, right, locate = locate_finite(punch, P, s, E, nu, tilt, max_iter, H, theta, profile, say)
    ends = (_stick_ends(punch, P, s, Q, f, E, nu, tilt, max_iter, (H, theta, profile), locate,
                        (left, right), say) if pre.refine > 1 and Q != 0 else ())
    t_locate = time.perf_counter() - t0
    pre = replace(pre, margin=zone_margin(punch.b, left, right, pre.margin))
    model, a_end, c_end, h_end = _refined_model(punch, P, s, f, E, nu, tilt, max_iter,
                                                (H, theta, profile), pre, (left, right), ends, say)
    if H is None:
        check_contact(punch, -a_end, c_end, model.normal.alpha)
    model.timings["locate"] = t_locate
    model.h_end = h_end
    info = {"H": H, "theta": theta, "profile": "eq. 2" if H is None else profile,
            "model": ("two similar bodies" if H is None else
                      "punch of real shape on a finite block") + ", Coulomb friction"}
    return shear_path(model, Q, f, steps, say, t0, info)


def _stick_ends(punch: Punch, P: float, s: float, Q: float, f: float, E: float, nu: float, tilt: str,
                max_iter: int, shape: tuple[float | None, float, str], locate: Any,
                zone: tuple[float, float], say: Progress) -> tuple[float, ...]:
    """The stick zone of ``Q`` from a first shear solve on the locating mesh (its ends become nodes)."""
    t1 = time.perf_counter()
    ends = _trial_stick_zone(punch, P, s, Q, f, E, nu, tilt, max_iter, shape, locate, zone)
    say(f"locate: stick zone of Q = {Q:.6g} about [{ends[0]:.6g}, {ends[1]:.6g}] "
        f"({time.perf_counter() - t1:.1f} s)")
    return ends


@functools.lru_cache(maxsize=64)
def _trial_stick_zone(punch: Punch, P: float, s: float, Q: float, f: float, E: float, nu: float,
                      tilt: str, max_iter: int, shape: tuple[float | None, float, str], locate: Any,
                      zone: tuple[float, float]) -> tuple[float, ...]:
    """:func:`_stick_ends` without its line: a pure function of its arguments, kept for the
    run, so that the two meshes of a map point's partial slip place the stick zone once."""
    H, theta, profile = shape
    left, right = zone
    spec = replace(locate, margin=max(locate.margin, zone_margin(punch.b, left, right, 0.15)))
    trial = _model(punch, P, s, E, nu, tilt, max_iter, f, spec.spec(left, right, (-punch.b, punch.b)),
                   H, theta, profile, (left, right))
    return tuple(trial.stick_zone(trial.step(Q, "loading", 1 if Q > 0 else -1, 1.0)))


def _refined_model(punch: Punch, P: float, s: float, f: float, E: float, nu: float, tilt: str,
                   max_iter: int, shape: tuple[float | None, float, str], pre: Any,
                   zone: tuple[float, float], ends: tuple[float, ...], say: Progress
                   ) -> tuple[Any, float, float, float]:
    """The model on a mesh whose contact ends lie clear of the joins: ``(model, a_end, c_end, h_end)``."""
    H, theta, profile = shape
    left, right = zone
    base = pre
    for attempt in range(REFINE_ATTEMPTS + 1):   # an end near a join refines, as in solve_finite
        spec = pre.spec(left, right, (-punch.b, punch.b))
        model = _model(punch, P, s, E, nu, tilt, max_iter, f,
                       with_nodes(spec, ends) if ends else spec, H, theta, profile, (left, right))
        a_end, c_end = model.contact_ends()
        h_end = end_size(model.itf.x, a_end, c_end)
        say(f"mesh and normal contact: {model.itf.dofs} DOFs, contact [{a_end:.6g}, {c_end:.6g}]")
        finer = refined(punch, a_end, c_end, h_end, pre, attempt, base)
        if finer is None:
            break
        pre, left, right = finer, a_end, c_end
    return model, a_end, c_end, h_end

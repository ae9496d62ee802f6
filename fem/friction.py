"""Two elastically similar bodies with Coulomb friction: partial slip and the fretting cycle.

The model (issue 11). The substrate is the block of :mod:`fem.mesh`; the punch
body is its mirror image about the interface ``y = 0``, whose top ``y = L`` is
welded to a rigid loading plate. The plate translates by ``(xi, -delta)`` and
tilts by ``alpha``; the punch's shape enters, as in the paper, only as the
initial gap ``g(x)`` of eq. (2). Both bodies have the same ``E`` and ``nu``, so
Dundurs' ``beta = 0`` and the composite compliance is ``A = 4 (1 - nu^2) / E``.

Each body is condensed onto its interface nodes, both displacement components
(:mod:`fem.interface`); the meshes match node for node. With ``fn_i`` the
normal force the punch presses onto the substrate at node ``i`` (``f`` is the
coefficient of friction) and ``t_i`` the shear force it drags the substrate
with (``sum t_i = Q``), the gap and the relative tangential displacement of the
punch are::

    gap_i = g(x_i) + alpha x_i - delta + (C_nn fn)_i - (C_nt t)_i
    w_i   = xi + (C_tn fn)_i - (C_tt t)_i - lambda sigma_bulk u_b(x_i)

where ``C_nn = G^P_yy + G^S_yy``, ``C_nt = G^P_yx + G^S_yx``, ``C_tn = G^P_xy + G^S_xy``
and ``C_tt = G^P_xx + G^S_xx`` are sums of the two bodies' flexibility blocks
(``u = G F`` for nodal forces ``F``). For mirror images ``C_nt`` and ``C_tn``
vanish: the normal and tangential problems uncouple, as the paper assumes; the
solver does not rely on it (it iterates the two to a fixed point).

The bulk stress ``sigma_bulk`` (tension along ``x`` in the substrate only)
acts on the substrate's end faces; ``u_b`` is the substrate's surface
displacement under a unit end tension (:func:`fem.interface.bulk_field`), the
uniform strain ``(1 - nu^2)/E`` to round-off, so a positive ``sigma_bulk``
stretches the substrate and a stuck punch must follow it. Its vertical part is
uniform along the surface, a rigid shift that ``delta`` takes up. ``lambda``
is the load fraction: ``P`` at ``s`` first (frictionless normal contact,
:func:`fem.contact.solve_contact` on ``C_nn``), then ``Q`` and the bulk stress
together in proportion, in steps (``lambda = Q / Q_ref``, ``Q_ref`` the largest
shear of the path). Each step finds the stick and slip nodes by
:func:`fem.coulomb.tangential`.

The sign of the stick-zone offset, the half-plane check of this model
(tests/test_fem_bulk.py). The punch's surface strain under its traction ``-q``
is ``+(A/4)(2/π) PV∫ q(t)/(x - t) dt``, the substrate's ``-(A/4)(2/π) PV∫ ...``
plus its bulk strain ``sigma_bulk (1 - nu^2)/E = A sigma_bulk/4``; in a stick zone
the relative strain vanishes: ``(1/π) PV∫ q(t)/(x - t) dt = sigma_bulk/4``. With
``q = f p - f p*`` (``Q > 0``) and ``(1/π) PV∫ p/(x - t) dt = h'(x)/A`` this is
``(1/π) PV∫ p*/(x - t) dt = h'(x)/A - sigma_bulk/(4 f)``: ``p*`` is the normal
pressure of the same profile under an extra rigid tilt ``-sigma_bulk A/(4 f)``.
For Hertz it is centred at ``x0 = a sigma_bulk/(4 f p0)``, so
``e = -sign(Q) a sigma_bulk/(4 f p0)`` (Nowell & Hills' ``|e|``): a tension moves
the stick zone towards the leading edge (``x = c`` for ``Q > 0``; the trailing edge
``x = -a`` carries the tension peak), and the stick zone reaches ``x = c`` at
``sigma_bulk/(f p0) = 4 (1 - sqrt(1 - Q/(f P)))``. Past it the model opens a
zone of reversed slip (``t_i = -f fn_i``) at the leading edge.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Optional

import numpy as np
from numpy.typing import ArrayLike

from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch
from threepart.problem.material import NU
from threepart.results import BRANCHES, FrettingResult, NormalResult, SlipResult
from threepart.stress import Stress
from threepart.problem.checks import finite, integer
from threepart.problem.validate import check_states, shear_load

from .coulomb import Step, reversal
from ._boundary import boundary
from ._iv import MAX_FE_STATES, STEPS, mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .mesh import MeshPreset, Substrate
from .recovery import StressField, model_nu
from .solve import MeshArg
from .twobody import TwoBodyModel, two_body_model
from threepart.errors import InputError, InputTypeError

__all__ = ["FemSlipResult", "FemFrettingResult", "solve_partial_slip", "fretting_cycle"]


@dataclass(frozen=True)
class FemSlipResult(SlipResult):
    """FE partial-slip solution of the two-body model.

    Attributes (beyond :class:`~threepart.results.SlipResult`)
    ----------
    x_nodes, q_nodes
        Interface nodes and their shear ``t_i / w_i``.
    slip_nodes
        Relative slip of the punch since the shear was first applied.
    history
        One :class:`~fem.coulomb.Step` per load step.
    stress_field
        The substrate's displacement at the last step, for :meth:`stress`.
    """

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    q_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    slip_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    stress_field: StressField | None = field(default=None, compare=False, repr=False)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear traction, linear between nodes, 0 outside the contact."""
        return interp_nodes(self.normal, self.x_nodes, self.q_nodes, x)

    def slip(self, x: ArrayLike) -> np.ndarray:
        """Relative slip of the punch over the substrate since ``Q = 0`` (0 in the stick zone)."""
        return interp_nodes(self.normal, self.x_nodes, self.slip_nodes, x)

    def stress(self, x: ArrayLike, z: ArrayLike, *, nu: float | None = None) -> Stress:  # type: ignore[override]
        """Stresses in the substrate at ``(x, z)`` from the FE field, ``sigma_bulk`` included.

        Recovered by :class:`fem.recovery.StressField`; ``nu`` must be the
        model's (``None``).
        """
        if self.stress_field is None:
            return super().stress(x, z, nu=NU if nu is None else nu)
        model_nu(nu, self.stress_field.nu)
        return self.stress_field.at(x, z)


def interp_nodes(normal: NormalResult, xn: np.ndarray, values: np.ndarray, x: ArrayLike) -> np.ndarray:
    """Nodal ``values`` interpolated linearly over the contact ``[-a, c]``, 0 outside."""
    x = np.asarray(x, dtype=float)
    inside = (xn > -normal.a) & (xn < normal.c)
    xs = np.concatenate([[-normal.a], xn[inside], [normal.c]])
    vs = np.concatenate([[0.0], values[inside], [0.0]])
    return np.interp(x, xs, vs, left=0.0, right=0.0)


@dataclass(frozen=True)
class FemFrettingResult(FrettingResult):
    """FE fretting cycle of the two-body model, by the incremental load path.

    Attributes (beyond :class:`~threepart.results.FrettingResult`)
    ----------
    history
        One :class:`~fem.coulomb.Step` per recorded state, in the order of :attr:`Q`.
    x_nodes, weights
        Interface nodes and their lumped weights.
    """

    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    model: TwoBodyModel | None = field(default=None, compare=False, repr=False)

    def _state(self, Q: float, branch: str) -> Step:
        for st in self.history:
            if st.branch == branch and math.isclose(st.Q, Q, rel_tol=1e-12, abs_tol=1e-12 * self.Q_max):
                return st
        raise InputError(f"`Q` = {Q!r} on `branch` = {branch!r} is not a recorded state "
                         f"(one of the {len(self.history)} of `Q` on {BRANCHES})")

    def shear(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        st = self._state(Q, branch)
        return interp_nodes(self.normal, self.x_nodes, st.t / self.weights, x)

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        w = np.array([st.w for st in self.history if st.branch != "loading"])
        return interp_nodes(self.normal, self.x_nodes, 0.5 * np.ptp(w, axis=0), x)

    def stress(self, x: ArrayLike, z: ArrayLike, Q: float, branch: str, *,  # type: ignore[override]
               nu: float | None = None) -> Stress:
        """Stresses in the substrate at ``(x, z)`` in the recorded state ``(Q, branch)``, from the FE field.

        The bulk stress is ``sigma_bulk Q / Q_max`` (in phase with ``Q``);
        ``nu`` must be the model's (``None``).
        """
        st = self._state(Q, branch)
        if self.model is None:
            return super().stress(x, z, Q, branch, nu=NU if nu is None else nu)
        model_nu(nu, self.model.nu)
        return self.model.field(st, st.Q / self.Q_max).at(x, z)


#: a worn depth ``w(x)``, or None (:func:`solve_partial_slip`)
Depth = Optional[Callable[[np.ndarray], np.ndarray]]


def _depth(depth: Any) -> Depth:
    """``depth`` if None or callable; ``TypeError`` naming it otherwise."""
    if depth is not None and not callable(depth):
        raise InputTypeError(f"`depth` must be a function of x (the worn depth) or None, not {type(depth).__name__}")
    return depth


def _slip_iv(punch: Any, P: Any, s: Any, Q: Any, f: Any, E: Any, nu: Any, tilt: Any, mesh: Any,
             steps: Any, max_iter: Any, progress: Any, sigma_bulk: Any, name: str = "Q"
             ) -> tuple[Any, ...]:
    """The checked input of :func:`solve_partial_slip` (and, with ``Q_max``, :func:`fretting_cycle`,
    whose ``steps`` are its ``states``)."""
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=True)
    Q, f = shear_load(Q, f, P, name)
    steps = (check_states(steps, MAX_FE_STATES) if name == "Q_max"
             else integer("steps", steps, *STEPS))
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    sigma_bulk = finite("sigma_bulk", sigma_bulk)
    return P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress_iv(progress), sigma_bulk


@boundary
def solve_partial_slip(punch: Punch, P: float, s: float = 0.0, *, Q: float, f: float, E: float,
                       nu: float, tilt: str = "free", mesh: MeshArg = "default", steps: int = 10,
                       max_iter: int = 100, progress: ProgressArg = None,
                       sigma_bulk: float = 0.0, depth: Depth = None) -> FemSlipResult:
    """Two similar elastic bodies pressed by ``P`` at lever arm ``s``, then sheared by ``Q`` in steps.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2), the initial gap between the bodies.
    P, s, tilt
        Normal load, its lever arm and whether the tilt is free, as in
        :func:`fem.solve_normal`.
    Q, f
        Shear force the punch exerts on the substrate along ``+x``, ``|Q| < f P``,
        and coefficient of friction.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    mesh
        The substrate's mesh, as in :func:`fem.solve_normal`; the punch body is its mirror image.
    steps
        Equal increments of ``Q`` (and ``sigma_bulk``) from 0, in ``[1, 1000]``.
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    progress
        One line per stage and per load step on stderr, as in :func:`fem.solve_normal`.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate (tension positive), on its end
        faces, rising with ``Q`` in proportion (any finite value: the model is
        linear). Where it reverses the slip at one end the model still answers
        (the slip direction of each node comes out of the active set).
    depth
        A worn depth ``w(x)`` (both bodies together, ``>= 0``; docs/WEAR.md): the gap is
        ``punch.profile(x) + w(x)``, any profile. None: the punch's own.

    Returns
    -------
    FemSlipResult
        ``d``, ``e`` from the stick zone of the last step; ``shear``, ``slip``,
        ``stress``, the per-step ``history``; ``diagnostics`` holds the
        discretisation, the active-set iterations and the timings (``locate``,
        ``mesh``, ``assemble``, ``factorise``, ``bulk``, ``normal``, ``friction``, ``total``).

    Raises
    ------
    TypeError, ValueError
        For invalid input, before any numerics (as :func:`fem.solve_normal`,
        with ``A = 4 (1 - nu^2) / E``); ``FullSlidingError`` for ``|Q| >= f P``.
    ArcExtentError, SlopeLimitError, NoConvergenceError, ContactZoneError, SeparationError,
    MeshResolutionError
        As :func:`fem.solve_normal`, and when the stick/slip states do not settle.
    """
    P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress, sigma_bulk = _slip_iv(
        punch, P, s, Q, f, E, nu, tilt, mesh, steps, max_iter, progress, sigma_bulk)
    say = Progress(progress)
    t0 = time.perf_counter()
    model = two_body_model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q, sigma_bulk, say, _depth(depth))
    return shear_path(model, Q, f, steps, say, t0)


def shear_path(model: TwoBodyModel, Q: float, f: float, steps: int, say: Progress, t0: float,
               info: dict[str, Any] | None = None) -> FemSlipResult:
    """Shear ``model`` (under its normal load) by ``Q`` and its bulk stress in ``steps`` equal steps.

    The load path of :func:`solve_partial_slip` and :func:`fem.solve_finite_slip`;
    ``info`` is added to the normal result's and the slip result's ``info``,
    ``t0`` is when the solve began (for the total time).
    """
    direction = 1 if Q >= 0 else -1
    for k in range(1, steps + 1):
        t1 = time.perf_counter()
        st = model.step(Q * k / steps, "loading", direction, k / steps)
        say(f"step {k}/{steps}, Q = {st.Q:.6g}: {int(st.stick.sum())} nodes stick "
            f"({time.perf_counter() - t1:.1f} s)")
    left, right = model.stick_zone(st)
    field = model.field(st, 1.0)
    diag = model.diagnostics(steps, time.perf_counter() - t0)
    normal = model.normal_result(diag)
    if info:
        normal = replace(normal, info={**normal.info, **info})
    info = {**normal.info, "xi": st.xi, "stick_nodes": int(st.stick.sum())}
    return FemSlipResult(normal=normal, Q=float(Q), f=float(f), d=0.5 * (right - left),
                         e=-0.5 * (right + left), method="fem", sigma_bulk=model.sigma_bulk,
                         diagnostics=diag, info=info, x_nodes=model.itf.x,
                         q_nodes=st.t / model.itf.weights, slip_nodes=st.w - model.w0,
                         history=tuple(model.steps), stress_field=field)


@boundary
def fretting_cycle(punch: Punch, P: float, s: float = 0.0, *, Q_max: float, f: float, E: float,
                   nu: float, tilt: str = "free", mesh: MeshArg = "default", states: int = 21,
                   max_iter: int = 100, progress: ProgressArg = None,
                   sigma_bulk: float = 0.0, depth: Depth = None) -> FemFrettingResult:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of the two-body model, step by step.

    Each branch is stepped through ``states`` equally spaced values of ``Q``
    (both ends included), the states the closed form and the SIE record too;
    the bulk stress follows in phase, ``sigma_bulk Q / Q_max``. The energy
    dissipated per cycle is the work of the shear forces on the relative slip
    over the unloading and reloading branches, ``sum_i ∮ t_i dw_i``
    (trapezoidal in the steps); ``info["loop_energy"]`` holds the area of the
    ``Q``–``xi`` loop, the same energy by the global balance when
    ``sigma_bulk = 0``.

    Parameters (``depth`` too: a worn profile's cycle) and errors as :func:`solve_partial_slip`, with ``Q_max > 0``,
    ``states`` in ``[2, 1000]`` and ``sigma_bulk`` the bulk stress at ``Q_max``.
    """
    P, s, Q_max, f, E, nu, tilt, pre, states, max_iter, progress, sigma_bulk = _slip_iv(
        punch, P, s, Q_max, f, E, nu, tilt, mesh, states, max_iter, progress, sigma_bulk, "Q_max")
    say = Progress(progress)
    t0 = time.perf_counter()
    model = two_body_model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q_max, sigma_bulk, say, _depth(depth))
    path = [("loading", np.linspace(0.0, Q_max, states), 1),
            ("unloading", np.linspace(Q_max, -Q_max, states), -1),
            ("reloading", np.linspace(-Q_max, Q_max, states), 1)]
    recorded: list[Step] = []
    first = Step(Q=0.0, branch="loading", fn=model.fn, t=model.t, w=model.w.copy(), xi=0.0,
                 stick=model.stick, direction=1, iterations=0)
    for branch, Qs, direction in path:
        for k, Q in enumerate(Qs):
            if branch == "loading" and k == 0:
                recorded.append(first)
            elif k == 0:
                recorded.append(reversal(recorded[-1], branch, direction))
            else:
                t1 = time.perf_counter()
                recorded.append(model.step(float(Q), branch, direction, float(Q) / Q_max))
                say(f"{branch} {k}/{states - 1}, Q = {float(Q):.6g} "
                    f"({time.perf_counter() - t1:.1f} s)")
    cycle = [st for st in recorded if st.branch != "loading"]
    work = sum(float(np.sum(0.5 * (a.t + b.t) * (b.w - a.w))) for a, b in zip(cycle, cycle[1:]))
    loop = sum(0.5 * (a.Q + b.Q) * (b.xi - a.xi) for a, b in zip(cycle, cycle[1:]))
    diag = model.diagnostics(states, time.perf_counter() - t0)
    normal = model.normal_result(diag)
    # at Q = 0 and at each reversal nothing has slipped yet: the whole contact sticks
    stick = np.array([model.stick_zone(st) if st.iterations else (-normal.a, normal.c)
                      for st in recorded])
    info = {**normal.info, "loop_energy": float(loop)}
    return FemFrettingResult(normal=normal, Q_max=float(Q_max), f=float(f),
                             branch=np.array([st.branch for st in recorded]),
                             Q=np.array([st.Q for st in recorded]), stick=stick,
                             delta=np.array([st.xi for st in recorded]), energy=float(work),
                             method="fem", sigma_bulk=sigma_bulk, diagnostics=diag, info=info,
                             history=tuple(recorded), x_nodes=model.itf.x,
                             weights=model.itf.weights, model=model)

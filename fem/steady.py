"""The FEM's periodic steady state of an in-phase cycle, by marching the cycle until it repeats (issue 31).

No superposition: the two-body model of :func:`fem.load_history` (meshed and
condensed once) is marched from rest to state 0 (the first loading), then
``0 -> 1 -> 0`` again and again, ``steps`` states a half-cycle with the loads
``(P, s, Q, sigma_bulk)`` linear between the ends (:func:`threepart.halfplane.steady.ramp`,
docs/STEADY_STATE.md §0), until the friction work of a cycle settles. The last
cycle gives the permanent stick zone (the run of nodes that did not slip in any
of its steps), the energy (eq. S11 as the sum of its steps' friction work), the
shear at the two ends and the slip amplitude. Whether the first loading leaves
a trace in the steady state is the path-independence the tests check.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike

from threepart.errors import InputError, NoConvergenceError
from threepart.halfplane.load_history import History, check_history
from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch
from threepart.results.cycles import SteadyStateResult
from threepart.results import Diagnostics
from threepart.halfplane.steady import LoadState, check_cycle_states, ramp
from threepart.stress import Stress
from threepart.tolerances import tolerance
from threepart.problem.checks import integer
from threepart.problem.validate import shear_load

from ._boundary import boundary
from ._iv import mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .contact import ContactSolution
from .coulomb import Step
from .friction import interp_nodes
from .history import Carry, Marched, march_states, normal_state, setup_history, stick_intervals
from .mesh import MeshPreset, Substrate
from .recovery import model_nu
from .solve import FemResult, MeshArg
from .twobody import TwoBodyModel

__all__ = ["FemSteadyResult", "steady_state", "CYCLES", "STEPS", "FIRST"]

#: the most cycles marched after the first loading before NoConvergenceError
CYCLES = 6
#: states per half-cycle (and on the first loading): the step work is the trapezoid rule in the
#: state index, second order: 20 leave 1.2 % of the energy on the default mesh, 40 leave 0.4 %
STEPS = 40
#: bounds of ``cycles`` (two are needed to see the energy settle) and ``steps``
CYCLES_RANGE, STEPS_RANGE = (2, 100), (2, 1000)
#: first loadings by name: all four loads from zero together, or ``P`` (at ``s``) then ``Q`` and ``sigma_bulk``
FIRST = ("together", "normal")


@dataclass(frozen=True)
class FemSteadyResult(SteadyStateResult):
    """Steady state from :func:`steady_state`: the last marched cycle of the two-body model.

    Attributes (beyond :class:`~threepart.results.SteadyStateResult`)
    ----------
    x_nodes, weights
        Interface nodes and their lumped weights.
    q_ends
        Nodal shear tractions at the two ends, ``(2, nodes)``.
    amplitude
        Half the nodal slip over the last cycle's half-cycle ``0 -> 1``.
    energies
        Friction work of each marched cycle (the last is :attr:`energy`).
    """

    method: str = "fem"
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    q_ends: np.ndarray = field(default_factory=lambda: np.zeros((2, 0)), compare=False, repr=False)
    amplitude: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    energies: tuple[float, ...] = ()
    steps: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    model: TwoBodyModel | None = field(default=None, compare=False, repr=False)

    def shear(self, x: ArrayLike, state: int) -> np.ndarray:
        """The nodal shear traction at the end ``state`` (linear between the nodes, 0 outside its contact).

        The FEM marched the history, so the shear locked in the stick zone is
        that of its first loading; in shakedown too.
        """
        k = self._state(state)
        return interp_nodes(self.normals[k], self.x_nodes, self.q_ends[k], x)

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        """Half the slip over a half-cycle, linear between the nodes, 0 outside the larger contact."""
        x = np.asarray(x, dtype=float)
        lo, hi = min(-n.a for n in self.normals), max(n.c for n in self.normals)
        return np.where((x > lo) & (x < hi), np.interp(x, self.x_nodes, self.amplitude), 0.0)

    def stress(self, x: ArrayLike, z: ArrayLike, state: int, *,  # type: ignore[override]
               nu: float | None = None) -> Stress:
        """Stresses in the substrate at ``(x, z)`` at the end ``state``, from the FE field.

        ``nu`` must be the model's (``None``).
        """
        k = self._state(state)
        assert self.model is not None
        model_nu(nu, self.model.nu)
        return self.model.field(self.steps[k], self.states[k][3]).at(x, z)


def _check(punch: Any, states: Any, f: Any, E: Any, nu: Any, mesh: Any, cycles: Any, steps: Any,
           first: Any, max_iter: Any, progress: Any) -> tuple[Any, ...]:
    """The checked input, before any meshing or numerics."""
    (st0, st1), f = check_cycle_states(states, f)
    for k, (P, s, _, _) in enumerate((st0, st1)):
        try:
            _, _, E, nu, _, max_iter = normal_iv(punch, P, s, E, nu, "free", max_iter, pair=True)
        except ValueError as exc:
            raise type(exc)(f"`states[{k}]`: {exc}") from None
    cycles = integer("cycles", cycles, *CYCLES_RANGE)
    steps = integer("steps", steps, *STEPS_RANGE)
    if isinstance(first, str):
        if first not in FIRST:
            raise InputError(f"`first` = {first!r} must be one of {FIRST} or a sequence of "
                             "(P, s, Q, sigma_bulk) states")
    else:
        try:
            first = check_history(first)
            for k in range(len(first)):
                P, s, Q, _ = first.state(k)
                normal_iv(punch, P, s, E, nu, "free", max_iter, pair=True)
                shear_load(Q, f, P, name=f"first[{k}].Q", what="the first loading cannot pass this state")
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"`first`: {exc}") from None
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    return st0, st1, f, float(E), float(nu), pre, cycles, steps, first, int(max_iter), progress_iv(progress)


def _path(start: LoadState, end: LoadState, steps: int) -> list[LoadState]:
    """``steps`` states from ``start`` (excluded) to ``end`` (included, exactly), the loads linear."""
    lam = np.arange(1, steps + 1) / steps
    out = [tuple(float(v) for v in row) for row in zip(*ramp(start, end, lam))]
    return [*out[:-1], end]   # type: ignore[list-item]


def _first_loading(st0: LoadState, first: str | History, steps: int) -> list[LoadState]:
    """The states from rest to ``st0``: all four loads together, ``P`` then the rest, or given states then a ramp."""
    P0, s0, Q0, sb0 = st0
    if isinstance(first, History):
        given = [first.state(k) for k in range(len(first))]
        return [*given, *_path(given[-1], st0, steps)]
    if first == "normal":
        return [*_path((0.0, s0, 0.0, 0.0), (P0, s0, 0.0, 0.0), steps), *_path((P0, s0, 0.0, 0.0), st0, steps)]
    return _path((0.0, s0, 0.0, 0.0), st0, steps)


class _Marcher:
    """The model meshed once, and the normal solutions of the states it meets (each ``(P, s)`` once)."""

    def __init__(self, punch: Punch, states: list[LoadState], f: float, E: float, nu: float, pre: Any,
                 max_iter: int, say: Progress) -> None:
        self.f, self.E, self.nu, self.say = f, E, nu, say
        self.model, self.L, self.timings = setup_history(punch, check_history(states), E, nu, pre, max_iter, f, say)
        self.cache: dict[tuple[float, float], tuple[ContactSolution, FemResult]] = {}
        self.active: np.ndarray | None = None

    def normal(self, P: float, s: float) -> tuple[ContactSolution, FemResult]:
        """The state's normal contact, started from the last one solved (warm start)."""
        sol = normal_state(self.model, P, s, self.E, self.nu, self.cache, self.active)
        self.active = sol[0].active
        return sol

    def march(self, states: list[LoadState], carry: Carry | None) -> Marched:
        sols = [self.normal(P, s)[0] for P, s, _, _ in states]
        return march_states(self.model, check_history(states), self.f, sols, self.say, carry)


def _settled(energies: list[float], scale: float) -> bool:
    """The last two cycles' friction work agree to the table's ``settle``, or both are rounding of
    ``scale`` (:func:`_work_scale`: the elastic work of the cycle's shear, an upper bound of the friction's)."""
    if len(energies) < 2:
        return False
    change = abs(energies[-1] - energies[-2])
    return (change <= tolerance("fem-steady", "settle").limit * abs(energies[-1])
            or max(energies[-2:]) <= tolerance("fem-steady", "shakedown").limit * scale)


def _work_scale(run: Marched, st0: LoadState, st1: LoadState, f: float) -> float:
    """The scale of a cycle's work, ``max(|ΔQ|, f |ΔP|)`` times the largest nodal range of ``w`` in it."""
    return max(abs(st1[2] - st0[2]), f * abs(st1[0] - st0[0])) * float(np.ptp(run.w, axis=0).max())


def _permanent(run: Marched, x: np.ndarray) -> tuple[float, float] | None:
    """The widest run of nodes stuck in every step of the cycle ``run``, as ``(left, right)``."""
    zones = stick_intervals(np.all(run.stuck, axis=0), x)
    return max(zones, key=lambda z: z[1] - z[0]) if zones else None


@boundary
def steady_state(punch: Punch, states: Any, f: float, *, E: float, nu: float, mesh: MeshArg = "default",
                 cycles: int = CYCLES, steps: int = STEPS, first: str | Sequence[Any] = "together",
                 max_iter: int = 100, progress: ProgressArg = None) -> FemSteadyResult:
    """The periodic steady state of the in-phase cycle between ``states[0]`` and ``states[1]``, marched.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2), as the initial gap of the mirrored pair.
    states
        The two ends ``(P, s, Q, sigma_bulk)`` of the cycle, the loads linear in
        between (docs/STEADY_STATE.md §0); ``|Q| < f P`` at both.
    f
        Coefficient of friction, > 0.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    mesh
        As :func:`fem.load_history`: meshed once around the contacts of the cycle.
    cycles
        The most cycles marched after the first loading (:data:`CYCLES`); the march
        stops when the friction work of two successive cycles agrees to the
        table's ``("fem-steady", "settle")``.
    steps
        States per half-cycle and per leg of the first loading (:data:`STEPS`).
    first
        The first loading from rest to ``states[0]``: ``"together"`` (the four loads
        from zero in proportion), ``"normal"`` (``P`` at ``s`` first, then ``Q`` and
        ``sigma_bulk``), or a sequence of states marched first, then ``steps`` states to ``states[0]``.
    max_iter, progress
        As :func:`fem.load_history`.

    Returns
    -------
    FemSteadyResult
        ``d``, ``e`` of the last cycle's permanent stick zone (the run of nodes that
        slipped in none of its steps, each end half-way to the next node; in shakedown
        the smaller contact), ``energy`` (its friction work), ``shakedown`` (the
        permanent stick zone covers the smaller contact and the work is rounding),
        ``normals`` (FE normal results of the two ends), ``energies`` of every cycle;
        ``diagnostics`` hold ``h``, ``dofs``, ``steps`` (the cycles' states marched) and timings;
        ``info`` holds ``cycles`` (marched) and ``first_work``.

    Raises
    ------
    TypeError, ValueError
        Invalid input, before any numerics (``FullSlidingError`` for ``|Q| >= f P``).
    NoConvergenceError
        The energy has not settled after ``cycles`` cycles (naming the last two), or
        no node stuck through the last cycle; as :func:`fem.load_history` otherwise.
    """
    st0, st1, f, E, nu, pre, cycles, steps, path, max_iter, progress = _check(
        punch, states, f, E, nu, mesh, cycles, steps, first, max_iter, progress)
    say = Progress(progress)
    t0 = time.perf_counter()
    loading = _first_loading(st0, path, steps)
    cycle = [*_path(st0, st1, steps), *_path(st1, st0, steps)]
    cycle[steps:] = [*cycle[steps - 2::-1], st0]       # the way back through the same states
    marcher = _Marcher(punch, [*loading, *cycle], f, E, nu, pre, max_iter, say)
    run = marcher.march(loading, None)
    first_work = float(run.work.sum())
    energies: list[float] = []
    start, scale = run.carry, 0.0
    while not _settled(energies, scale):
        if len(energies) == cycles:
            raise NoConvergenceError(
                f"the FEM's cycle did not settle in `cycles` = {cycles}: the friction work of the last two "
                f"cycles was {energies[-2]:.6g} and {energies[-1]:.6g} N·mm/mm (relative change "
                f"{abs(energies[-1] / energies[-2] - 1):.3g}); raise `cycles`")
        start = run.carry
        run = marcher.march(cycle, start)
        energies.append(float(run.work.sum()))
        scale = max(scale, _work_scale(run, st0, st1, f))
        say(f"cycle {len(energies)}: friction work {energies[-1]:.6g}")
    return _result(marcher, run, start, (st0, st1), steps, energies, scale, first_work,
                   time.perf_counter() - t0)


def _result(marcher: _Marcher, run: Marched, start: Carry, ends: tuple[LoadState, LoadState], steps: int,
            energies: list[float], scale: float, first_work: float, total: float) -> FemSteadyResult:
    """The steady state of the last cycle ``run`` (which began from ``start``)."""
    model, itf = marcher.model, marcher.model.itf
    x = itf.x
    normals = tuple(marcher.normal(P, s)[1] for P, s, _, _ in ends)
    zone = _permanent(run, x)
    if zone is None:
        raise NoConvergenceError("no node of the FEM's interface stuck through the last cycle: "
                                 "no permanent stick zone, no result is returned")
    lo, hi = max(-n.a for n in normals), min(n.c for n in normals)
    inside = (x > lo) & (x < hi)
    perm = np.all(run.stuck, axis=0)
    shakedown = bool(np.all(perm[inside])
                     and energies[-1] <= tolerance("fem-steady", "shakedown").limit * scale)
    left, right = (lo, hi) if shakedown else zone
    k_ends = (len(run.q) - 1, steps - 1)               # the states 0 and 1 of the last cycle
    st = tuple(Step(Q=ends[j][2], branch="loading", fn=marcher.normal(*ends[j][:2])[0].f,
                    t=run.q[k] * itf.weights, w=run.w[k], xi=math.nan, stick=run.stuck[k],
                    direction=1, iterations=0) for j, k in enumerate(k_ends))
    amplitude = 0.5 * np.abs(run.slip[steps - 1] - start.slip)
    timings = {**marcher.timings, "total": total}
    diag = Diagnostics(h=itf.h, dofs=itf.dofs, L=marcher.L, iterations=run.iterations,
                       residual=run.residual, steps=len(energies) * 2 * steps, timings=timings)
    return FemSteadyResult(normals=(normals[0], normals[1]), states=ends, f=marcher.f,
                           d=0.5 * (right - left), e=-0.5 * (left + right), energy=energies[-1],
                           shakedown=shakedown, diagnostics=diag,
                           info={"cycles": len(energies), "first_work": first_work, "work_scale": scale},
                           x_nodes=x, weights=itf.weights, q_ends=run.q[list(k_ends)],
                           amplitude=amplitude, energies=tuple(energies), steps=st, model=model)

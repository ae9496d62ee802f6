"""A load history of any shape on the two-body friction model, with the memory of slip (issue 31).

The model is :mod:`fem.friction`'s: the substrate and its mirror image,
condensed onto their matched interface nodes (:mod:`fem.interface`), the bulk
stress on the substrate's end faces. The mesh is made **once**, for the union
of the contacts of the history's states (a preset is meshed around the contacts
of its largest load and of its extreme lever arms), and condensed once; each
state then costs a frictionless normal contact solve on ``C_nn`` (one per
distinct ``(P, s)``) and one Coulomb state (:func:`threepart.halfplane.coulomb.coulomb_state`)
on ``C_tt``: stick nodes keep the relative tangential displacement ``w`` of the
previous state, slip nodes carry ``t_i = ±f fn_i`` in the direction of their slip,
nodes out of contact carry nothing and re-enter with no memory. The mirrored
pair uncouples the normal and tangential problems (``C_nt = 0`` to round-off),
as the paper assumes.

The friction work of a step is ``Σ |Δw_i| (f fn_(k-1),i + f fn_k,i)/2`` over the
slipping nodes (:func:`threepart.halfplane.load_history.step_work`), as the SIE's.
"""
from __future__ import annotations

import math
import time
from typing import Any, NamedTuple

import numpy as np
from threepart.threads import one_blas_thread

from threepart.halfplane.coulomb import coulomb_state
from threepart.errors import ContactZoneError, FullSlidingError
from threepart.halfplane.load_history import History, check_history, check_period, step_work, stuck
from threepart.problem.material import similar_pair
from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch
from threepart.results.cycles import HistoryResult
from threepart.results import Diagnostics
from threepart.problem.validate import check_contact, shear_load

from ._boundary import boundary
from ._iv import mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .contact import ContactSolution, solve_contact
from .ends import contact_ends
from .mesh import MeshPreset, Substrate
from .solve import TRIES_DEFAULT, FemResult, MeshArg, locate_ends, place_substrate
from .twobody import TwoBodyModel

__all__ = ["load_history"]


def _check(punch: Any, history: Any, f: Any, E: Any, nu: Any, mesh: Any, max_iter: Any,
           progress: Any, period: Any) -> tuple[History, float, float, float, Any, int, Any, int | None]:
    """The checked input, every state's, before any meshing or numerics."""
    hist = check_history(history)
    for k in range(len(hist)):
        P, s, Q, _ = hist.state(k)
        try:
            _, _, E, nu, _, max_iter = normal_iv(punch, P, s, E, nu, "free", max_iter, pair=True)
            _, f = shear_load(Q, f, P, what="the history cannot be marched past this state")
        except ValueError as exc:
            raise type(exc)(f"`history` state {k}: {exc}") from None
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    return (hist, float(f), float(E), float(nu), pre, int(max_iter), progress_iv(progress),
            check_period(period, hist))


def _union(punch: Punch, hist: History, E: float, nu: float, max_iter: int) -> tuple[float, float]:
    """The contacts' union, located for the largest load and for the largest load at each extreme lever arm.

    A contact grows with ``P`` at a given ``s``, so these states' contacts hold
    the others' but for lever arms between the extremes at loads near the
    largest; the mesh's fine zone has a margin beyond the estimate.
    """
    picks = {int(np.argmax(hist.P))}
    for s in (hist.s.min(), hist.s.max()):
        at = np.flatnonzero(hist.s == s)
        picks.add(int(at[np.argmax(hist.P[at])]))
    ends = [locate_ends(punch, float(hist.P[k]), float(hist.s[k]), 0.5 * E, nu, "free", max_iter,
                        TRIES_DEFAULT) for k in sorted(picks)]
    return min(e[0] for e in ends), max(e[1] for e in ends)


def normal_state(model: TwoBodyModel, P: float, s: float, E: float, nu: float,
            cache: dict[tuple[float, float], tuple[ContactSolution, FemResult]],
            active: np.ndarray | None = None) -> tuple[ContactSolution, FemResult]:
    """The frictionless normal contact of ``(P, s)`` on the model's interface, and its result shape.

    ``active``: the active set to start from, the previous state's (warm start:
    a neighbouring state's contact settles in fewer iterations, to the same set).
    """
    if (P, s) in cache:
        return cache[P, s]
    itf, punch = model.itf, model.punch
    sol = solve_contact(itf.C_nn, itf.x, model.gap(itf.x), P, s, free_tilt=True,
                        max_iter=model.max_iter, active=active)
    if sol.active[0] or sol.active[-1]:
        raise ContactZoneError(f"the contact of `P` = {P:.6g} at `s` = {s:.6g} reaches the end of the "
                               f"meshed contact zone [{itf.x[0]:.6g}, {itf.x[-1]:.6g}] (meshed for the "
                               "history's largest load and extreme lever arms): give a mesh that covers it")
    p = sol.f / itf.weights
    left, right = contact_ends(itf.x, p, sol.active, (-punch.b, punch.b))
    check_contact(punch, -left, right, sol.alpha)
    res = FemResult(punch=punch, A=similar_pair(E, nu), a=-left, c=right, alpha=sol.alpha,
                    P=float(np.sum(sol.f)), s=float(np.sum(itf.x * sol.f) / np.sum(sol.f)),
                    tilt="free", method="fem", info={"model": "two similar bodies"},
                    diagnostics=Diagnostics(h=itf.h, dofs=itf.dofs), delta=sol.delta,
                    x_nodes=itf.x, p_nodes=p)
    cache[P, s] = (sol, res)
    return cache[P, s]


def stick_intervals(stick: np.ndarray, x: np.ndarray) -> tuple[tuple[float, float], ...]:
    """Runs of stick nodes, each ending half-way to the next node that is not one."""
    d = np.diff(np.concatenate([[0], stick.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1
    mid = 0.5 * (x[:-1] + x[1:])
    return tuple((float(mid[i - 1] if i > 0 else x[0]), float(mid[j] if j < len(x) - 1 else x[-1]))
                 for i, j in zip(starts, ends))


@boundary
def load_history(punch: Punch, history: Any, f: float, *, E: float, nu: float,
                 mesh: MeshArg = "default", max_iter: int = 100,
                 progress: ProgressArg = None, period: int | None = None) -> HistoryResult:
    """March the two-body model through a load history with the memory of slip.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2), as the initial gap of the mirrored pair.
    history
        A sequence of states ``(P, s, Q, sigma_bulk)`` or a CSV path, as
        :func:`sie.load_history`; the first state is applied in one step from rest.
    f
        Coefficient of friction, > 0; ``|Q_k| < f P_k`` in every state.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    mesh
        As :func:`fem.solve_partial_slip`; a preset is meshed once around the
        union of the contacts (no refinement at stick-zone ends, which move).
    max_iter
        Cap on the active-set iterations of a normal contact and of a Coulomb state.
    progress
        One line per stage and per 10 % of the states on stderr, as :func:`fem.solve_normal`.
    period
        States per cycle, as :func:`sie.load_history`.

    Returns
    -------
    HistoryResult
        ``method="fem"``; the shear and slip at the interface nodes (linear between
        them); ``diagnostics`` hold ``h``, ``dofs``, the active-set ``iterations``, the
        largest Coulomb ``residual``, ``steps`` (states) and the timings
        (``locate``, ``mesh``, ``condense``, ``normal``, ``friction``, ``total``);
        ``info`` holds ``normal_solves`` and the nodes' lumped ``weights`` (force = traction × weight).

    Raises
    ------
    TypeError, ValueError
        Invalid input, before any numerics, naming the state
        (``FullSlidingError`` for ``|Q_k| >= f P_k``).
    ArcExtentError, SlopeLimitError, NoConvergenceError, ContactZoneError
        As :func:`fem.solve_normal` for a state's contact; ``NoConvergenceError``
        also when a state's stick/slip sets do not settle.
    """
    hist, f, E, nu, pre, max_iter, progress, period = _check(punch, history, f, E, nu, mesh, max_iter,
                                                             progress, period)
    say = Progress(progress)
    t0 = time.perf_counter()
    model, L, timings = setup_history(punch, hist, E, nu, pre, max_iter, f, say)
    cache: dict[tuple[float, float], tuple[ContactSolution, FemResult]] = {}
    t2 = time.perf_counter()
    sols: list[tuple[ContactSolution, FemResult]] = []
    for P, s in zip(hist.P, hist.s):   # each state's contact started from the previous state's
        sols.append(normal_state(model, float(P), float(s), E, nu, cache,
                            sols[-1][0].active if sols else None))
    t3 = time.perf_counter()
    run = march_states(model, hist, f, [s[0] for s in sols], say)
    t4 = time.perf_counter()
    cycles = hist.cycles(period)
    energy = np.array([run.work[i + 1:j + 1].sum() for i, j in cycles])
    timings.update({"normal": t3 - t2, "friction": t4 - t3, "total": t4 - t0})
    diag = Diagnostics(h=model.itf.h, dofs=model.itf.dofs, L=L, iterations=run.iterations,
                       residual=run.residual, steps=len(hist), timings=timings)
    return HistoryResult(punch=punch, f=f, P=hist.P, s=hist.s, Q=hist.Q, sigma_bulk=hist.sigma_bulk,
                         normals=tuple(s[1] for s in sols), stick=run.sticks, energy=energy,
                         cycles=cycles, work=run.work, method="fem", x_nodes=model.itf.x,
                         q_nodes=run.q, slip_nodes=run.slip, delta=run.delta, diagnostics=diag,
                         info={"normal_solves": len(cache), "weights": model.itf.weights})


def setup_history(punch: Punch, hist: History, E: float, nu: float, pre: Any, max_iter: int, f: float,
           say: Progress) -> tuple[TwoBodyModel, float, dict[str, float]]:
    """The model meshed once around the contacts' union and condensed: model, block size ``L``, timings."""
    t0 = time.perf_counter()
    ends = _union(punch, hist, E, nu, max_iter) if isinstance(pre, MeshPreset) else None
    t_locate = time.perf_counter() - t0
    lower, L, guess, _ = place_substrate(pre, punch, float(hist.P.max()), float(hist.s[0]), 0.5 * E,
                                         nu, "free", max_iter, say, ends)
    t1 = time.perf_counter()
    k_max = int(np.argmax(hist.P))
    bulk = 1.0 if np.any(hist.sigma_bulk) else 0.0     # the unit field, scaled per state
    model = TwoBodyModel(punch, float(hist.P[k_max]), float(hist.s[k_max]), E, nu, "free", lower, L,
                         guess, max_iter, f, bulk)
    t2 = time.perf_counter()
    say(f"mesh and condense: {model.itf.dofs} DOFs, {len(model.itf.x)} interface nodes "
        f"({t2 - t1:.1f} s)")
    return model, L, {"locate": t_locate, "mesh": t1 - t0 - t_locate, "condense": t2 - t1}


class Carry(NamedTuple):
    """What a state passes to the next: ``w``, the Coulomb bound, the stick set, the shear's sign, the slip."""

    w: np.ndarray
    bound: np.ndarray
    stick: np.ndarray
    sign: np.ndarray
    slip: np.ndarray


class Marched(NamedTuple):
    """The states marched: nodal shear, accumulated slip, stick intervals and nodes, work per step,
    relative tangential displacement ``w``, the rigid shift ``delta`` of each state, iterations,
    residual, and the carry to a next state."""

    q: np.ndarray
    slip: np.ndarray
    sticks: tuple
    stuck: np.ndarray
    work: np.ndarray
    w: np.ndarray
    delta: np.ndarray
    iterations: int
    residual: float
    carry: Carry


def march_states(model: TwoBodyModel, hist: History, f: float, sols: list[ContactSolution],
           say: Progress, carry: Carry | None = None) -> Marched:
    """The states in order, from rest or from ``carry`` (the last state of a previous march)."""
    itf = model.itf
    K, N = len(hist), len(itf.x)
    q, slip, ws = np.zeros((K, N)), np.zeros((K, N)), np.zeros((K, N))
    masks = np.zeros((K, N), dtype=bool)
    work, delta = np.zeros(K), np.zeros(K)
    sticks = []
    if carry is None:
        carry = Carry(np.zeros(N), np.zeros(N), np.ones(N, dtype=bool), np.zeros(N), np.zeros(N))
    w_prev, bound_prev, stick_prev, sign_prev, acc = carry
    its_total, res_max = 0, 0.0
    report = max(1, math.ceil(K / 10))
    with one_blas_thread():
        for k in range(K):
            _, _, Q, sb = hist.state(k)
            fn = sols[k].f
            bound = f * fn
            w_fixed = itf.C_tn @ fn - sb * model.ub
            try:
                t, xi, stick, its, r = coulomb_state(itf.C_tt, bound, w_prev, w_fixed, Q, stick_prev,
                                                     model.max_iter, sign_prev)
            except FullSlidingError as exc:
                raise FullSlidingError(f"`history` state {k}: {exc}") from None
            w = xi + w_fixed - itf.C_tt @ t
            both = (bound > 0) & (bound_prev > 0)
            dslip = np.where(both & ~stick, w - w_prev, 0.0)
            acc = acc + dslip
            work[k] = step_work(bound_prev, bound, dslip)
            q[k], slip[k], ws[k], delta[k] = t / itf.weights, acc, w, xi
            masks[k] = stuck(stick, bound > 0, w, w - w_prev)
            sticks.append(stick_intervals(masks[k], itf.x))
            w_prev, bound_prev, stick_prev, sign_prev = w, bound, stick | (bound == 0), np.sign(t)
            its_total, res_max = its_total + its, max(res_max, r)
            if (k + 1) % report == 0:
                say(f"state {k + 1}/{K}: {int(stick.sum())} nodes stick")
    return Marched(q, slip, tuple(sticks), masks, work, ws, delta, its_total, res_max,
                   Carry(w_prev, bound_prev, stick_prev, sign_prev, acc))

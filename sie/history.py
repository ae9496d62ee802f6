"""A load history of any shape, marched numerically with the memory of slip (issue 31).

At each state ``(P_k, s_k, Q_k, sigma_bulk_k)`` the normal pressure ``p_k`` is
the SIE's (:func:`sie.solve_normal`: contact ``[-a_k, c_k]``, tilt ``alpha_k``);
with elastically similar bodies it does not depend on the shear. The shear
``q`` is constant over each of ``n`` equal elements of a fixed grid covering
the union of the contacts, and the relative tangential displacement of the
punch (punch minus substrate) at the elements' midpoints ``x_i`` is

    w(x) = xi + (A/π) ∫ q(t) ln|x - t| dt - (A sigma_bulk/4) x,

``xi`` the rigid shift (docs/BULK_STRESS.md, eqs. B1–B3: its derivative is
the relative surface strain, so a stick zone where ``w`` keeps its value obeys
eq. integral_equation_tangential with the bulk strain of B3). In each state
the elements in contact stick (``w_i`` keeps its previous value) or slip
(``|q_i| = f p̄_i``, ``p̄_i`` the element's mean pressure, with the sign of the
slip increment, i.e. opposing the substrate's slip); out of contact ``q = 0``,
and an element that enters the contact starts from the ``w`` it has there (no
memory); ``∫ q = Q`` (eq. horizontal_equilibrium). The sets come from the
active set of :func:`threepart.halfplane.coulomb.coulomb_state`.

The friction work of a step is ``Σ |Δw_i| (f p̄_(k-1),i + f p̄_k,i) h/2`` over
the slipping elements (:func:`threepart.halfplane.load_history.step_work`); a completed
cycle's energy is the sum over its steps.
"""
from __future__ import annotations

import math
import sys
import time
from typing import Any, Callable

import numpy as np

from threepart.threads import one_blas_thread
from threepart.halfplane.coulomb import coulomb_state
from threepart.errors import FullSlidingError, InputTypeError
from threepart.progress import heartbeat
from threepart.halfplane.load_history import History, check_history, check_period, step_work, stuck
from threepart.problem.punch import Punch
from threepart.results.cycles import HistoryResult
from threepart.halfplane.legendre import gauss01
from threepart.results import Diagnostics, NormalResult
from threepart.problem.checks import integer, positive, show
from threepart.problem.validate import check_punch, lever_arm, load_scale, shear_load

from .normal import DEFAULT_N, SieNormalResult, solve_normal

__all__ = ["load_history", "log_matrix", "element_loads", "DEFAULT_ELEMENTS", "ELEMENTS", "MAX_SUBSTEPS"]

#: shear elements over the union of the contacts (a 200-state history in about 1 s)
DEFAULT_ELEMENTS = 400
#: the range of ``n``: a dense ``n x n`` flexibility and a dense solve per active-set iteration
ELEMENTS = (8, 4000)
#: Gauss–Legendre points in θ per element for its mean pressure (p is smooth in θ)
PRESSURE_POINTS = 8
#: the cap on the active-set iterations of one state (per value of the complementarity constant)
MAX_ITER = 100
#: the complementarity constant of the active set, of ``1/C_ii``: the log kernel couples the
#: elements strongly (the largest eigenvalue of ``C`` is ~100 ``C_ii`` at n = 800), and with
#: ``c = 1/C_ii`` the sets cycle at a reversal; with 0.1 they settle in 3-4 iterations
DAMPING = 0.1
#: a step is marched in sub-steps so that no contact end moves more than this share of the widest
#: contact in one. In a step the friction work of an element a contact end passes is placed by
#: where the end passes it (the loads linear in the step): with that, 12 states a half-cycle of the
#: Hertz cycle of issue 37 (an end moves 1.1 % of the contact a state) fall 0.3 % short, 6 (2.2 %,
#: two sub-steps) 0.3 %; without it 3.0 % and 8.6 %
SUBSTEP_SHARE = 0.02
#: the most sub-steps of one step
MAX_SUBSTEPS = 64
#: a slip zone resolved by fewer elements than this gives a coarse energy (``info["resolved"]``)
RESOLVED_ELEMENTS = 3


def log_matrix(edges: np.ndarray, A: float) -> np.ndarray:
    """``C_ij = -(A/π) (1/h_j) ∫_(e_j) ln|x_i - t| dt`` at the midpoints ``x_i`` of the elements.

    With ``t_j = q_j h_j`` the element forces, ``w = xi - C t + ...`` is the
    module's relative displacement. ``∫ ln|x - t| dt = G(x - t0) - G(x - t1)``,
    ``G(u) = u ln|u| - u``.
    """
    x = 0.5 * (edges[:-1] + edges[1:])
    h = np.diff(edges)

    def G(u: np.ndarray) -> np.ndarray:
        au = np.abs(u)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(au > 0, u * np.log(au) - u, 0.0)

    L = G(x[:, None] - edges[None, :-1]) - G(x[:, None] - edges[None, 1:])
    return -(A / math.pi) * L / h[None, :]


def element_loads(normal: SieNormalResult, edges: np.ndarray) -> np.ndarray:
    """``∫ p dx`` over each element: Gauss–Legendre in ``θ`` (``x = m + h cos θ``) on its part of the contact.

    ``p`` is a sine series in ``θ`` and ``dx = -h sin θ dθ``: the integrand is
    smooth, also at the contact's square-root ends; an element is split at the
    joins ``x = ±b``, where the pressure has its log kinks.
    """
    m, h = 0.5 * (normal.c - normal.a), 0.5 * (normal.a + normal.c)
    b = normal.punch.b
    joins = [j for j in sorted({-b, b}) if edges[0] < j < edges[-1] and not np.any(edges == j)]
    cuts = np.sort(np.concatenate([edges, joins]))
    owner = np.searchsorted(edges, cuts[:-1], side="right") - 1       # the element of each piece
    lo = np.clip((cuts[:-1] - m) / h, -1.0, 1.0)
    hi = np.clip((cuts[1:] - m) / h, -1.0, 1.0)
    th0, th1 = np.arccos(hi), np.arccos(lo)           # θ falls as x rises
    s, w = gauss01(PRESSURE_POINTS)
    theta = th0[:, None] + (th1 - th0)[:, None] * s[None, :]
    p = normal.pressure(m + h * np.cos(theta))
    pieces = (th1 - th0) * np.sum(w[None, :] * p * h * np.sin(theta), axis=1)
    return np.bincount(owner, weights=pieces, minlength=len(edges) - 1)


def _check(punch: Any, history: Any, f: Any, A: Any, n: Any, period: Any, substeps: Any, progress: Any
           ) -> tuple[History, float, float, int, int | None, int | None]:
    """The checked input, every state's, before any numerics."""
    check_punch(punch)
    hist = check_history(history)
    f, A = positive("f", f), positive("A", A)
    n = integer("n", n, *ELEMENTS)
    if substeps is not None:
        substeps = integer("substeps", substeps, 1, MAX_SUBSTEPS)
    if not (progress is None or isinstance(progress, bool) or callable(progress)):
        raise InputTypeError(f"`progress` = {show(progress)} must be None, True, False or a callable")
    for k in range(len(hist)):
        P, s, Q, _ = hist.state(k)
        try:
            lever_arm(punch, s)
            load_scale(punch, P, A)
            shear_load(Q, f, P, what="the history cannot be marched past this state")
        except ValueError as exc:
            raise type(exc)(f"`history` state {k}: {exc}") from None
    return hist, f, A, n, check_period(period, hist), substeps


def _substeps(normals: list[NormalResult], given: int | None) -> list[int]:
    """Sub-steps of each step (the first, from the unloaded body, is one): ``given``, or enough that
    no contact end moves more than :data:`SUBSTEP_SHARE` of the widest contact in one."""
    if given is not None:
        return [1] + [given] * (len(normals) - 1)
    width = max(r.a + r.c for r in normals)
    out = [1]
    for r0, r1 in zip(normals[:-1], normals[1:]):
        move = max(abs(r1.a - r0.a), abs(r1.c - r0.c)) / (SUBSTEP_SHARE * width)
        out.append(int(min(MAX_SUBSTEPS, max(1, math.ceil(move - 1e-9)))))
    return out


def _marched_states(hist: History, counts: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """The states marched, ``(K, 4)``, the loads linear between the given ones, and the index of each given one."""
    rows, given = [np.array(hist.state(0))], [0]
    for k in range(1, len(hist)):
        a, b = np.array(hist.state(k - 1)), np.array(hist.state(k))
        m = counts[k]
        rows += [a + (j / m) * (b - a) for j in range(1, m)] + [b]
        given.append(len(rows) - 1)
    return np.array(rows), np.array(given)


def _stick_intervals(stick: np.ndarray, edges: np.ndarray) -> tuple[tuple[float, float], ...]:
    """The runs of stick elements as intervals between element edges."""
    d = np.diff(np.concatenate([[0], stick.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    return tuple((float(edges[i]), float(edges[j])) for i, j in zip(starts, ends))


def load_history(punch: Punch, history: Any, f: float, *, A: float, n: int = DEFAULT_ELEMENTS,
                 normal_n: int = DEFAULT_N, period: int | None = None, substeps: int | None = None,
                 progress: bool | None | Callable[[str], None] = None) -> HistoryResult:
    """March ``punch`` through a load history with the memory of slip.

    Parameters
    ----------
    punch
        Three-part punch geometry (paper eq. 2).
    history
        A sequence of states ``(P, s, Q, sigma_bulk)`` (normal load > 0, its lever
        arm, the shear force the punch exerts on the substrate along +x, the
        substrate's bulk stress, tension positive), or the path of a CSV file
        with those columns (:func:`threepart.halfplane.load_history.read_history`). The body
        starts unloaded; the first state is applied in one step, and between two
        states the loads move linearly.
    f
        Coefficient of friction, > 0; ``|Q_k| < f P_k`` in every state.
    A
        Composite compliance (eq. 4), > 0.
    n
        Shear elements over the union of the contacts, in :data:`ELEMENTS`.
    normal_n
        Sine terms of each state's normal pressure (:func:`sie.solve_normal`).
    period
        States per cycle, the cycles ending at the last state; by default a
        cycle ends at each return to the last state along the way it was reached
        (:meth:`threepart.halfplane.load_history.History.cycles`).
    substeps
        Sub-steps of each step, in ``[1, MAX_SUBSTEPS]``; by default enough that no contact end
        moves more than :data:`SUBSTEP_SHARE` of the widest contact in one (the work: :func:`_march`).
    progress
        ``None``/``True``: a line on stderr every :data:`threepart.progress.HEARTBEAT_S` s of a
        long march; ``False``: none; a callable: it gets each line.

    Returns
    -------
    HistoryResult
        ``method="sie"``; ``stick``, ``shear(x, k)``, ``slip(x, k)``, ``normals``, ``energy`` per
        completed cycle, ``work`` per step; ``diagnostics`` hold ``n``, the active-set ``iterations``,
        the largest Coulomb ``residual``, ``steps`` (marched) and the timings; ``info`` holds ``normal_solves``, ``h``, ``substeps``,
        ``slip_elements`` (the elements the widest slip zone at the left and right contact end
        spans over the last cycle, or the history) and ``resolved`` (False where one spans 1 or 2
        elements: a coarse energy; raise ``n``).

    Raises
    ------
    TypeError, ValueError
        Invalid input, before any numerics, naming the state
        (``FullSlidingError`` for ``|Q_k| >= f P_k``).
    SeparationError, ArcExtentError, SlopeLimitError, NoConvergenceError
        As :func:`sie.solve_normal` for a state's contact; ``NoConvergenceError``
        also when a state's stick/slip sets do not settle.
    """
    hist, f, A, n, period, substeps = _check(punch, history, f, A, n, period, substeps, progress)
    t0 = time.perf_counter()
    normals, states, given, marched, cache, counts = _normals(punch, hist, A, normal_n, substeps)
    t_normal = time.perf_counter() - t0
    edges = np.linspace(min(-r.a for r in marched), max(r.c for r in marched), n + 1)
    x = 0.5 * (edges[:-1] + edges[1:])
    loads = {key: element_loads(r, edges) for key, r in cache.items()}
    at = [0]          # the state being marched, for the progress lines
    with heartbeat(_say(progress), lambda: f"sie load history: state {at[0] + 1} of {len(states)} marched "
                                           f"({len(hist)} given), n = {n},"):
        q, slip, stick, work, delta, its, res, spans = _march(
            states, given, f, A, log_matrix(edges, A), x, edges,
            [loads[float(P), float(s)] for P, s in states[:, :2]], at, [(-r.a, r.c) for r in marched])
    cycles = hist.cycles(period)
    energy = np.array([work[i + 1:j + 1].sum() for i, j in cycles])
    last = range(cycles[-1][0] + 1, cycles[-1][1] + 1) if cycles else range(len(hist))
    widest = (int(max(spans[k][0] for k in last)), int(max(spans[k][1] for k in last)))
    total = time.perf_counter() - t0
    diag = Diagnostics(n=n, iterations=its, residual=res, steps=len(states),
                       timings={"normal": t_normal, "friction": total - t_normal, "total": total})
    info = {"normal_solves": len(cache), "h": float(edges[1] - edges[0]), "substeps": tuple(counts),
            "slip_elements": widest, "resolved": all(w == 0 or w >= RESOLVED_ELEMENTS for w in widest)}
    return HistoryResult(punch=punch, f=f, P=hist.P, s=hist.s, Q=hist.Q, sigma_bulk=hist.sigma_bulk,
                         normals=tuple(normals), stick=stick, energy=energy, cycles=cycles, work=work,
                         method="sie", x_nodes=x, q_nodes=q, slip_nodes=slip, edges=edges, delta=delta,
                         diagnostics=diag, info=info)


def _normals(punch: Punch, hist: History, A: float, normal_n: int, substeps: int | None) -> tuple[Any, ...]:
    """The normal solution of each given state, the marched states (sub-steps included), the index of
    each given one, their normal solutions, the solutions by ``(P, s)`` (each solved once), the sub-steps."""
    cache: dict[tuple[float, float], SieNormalResult] = {}

    def normal(P: float, s: float) -> SieNormalResult:
        if (P, s) not in cache:
            cache[P, s] = solve_normal(punch, P, s, A=A, n=normal_n)
        return cache[P, s]

    normals: list[NormalResult] = [normal(*hist.state(k)[:2]) for k in range(len(hist))]
    counts = _substeps(normals, substeps)
    states, given = _marched_states(hist, counts)
    marched = [normal(float(P), float(s)) for P, s in states[:, :2]]
    return normals, states, given, marched, cache, counts


def _say(progress: bool | None | Callable[[str], None]) -> Callable[[str], None]:
    """Where the lines of :func:`load_history`'s ``progress`` go."""
    if callable(progress):
        return progress
    if progress is False:
        return lambda msg: None
    return lambda msg: print(msg, file=sys.stderr, flush=True)


def _edge_spans(slipped: np.ndarray, touch: np.ndarray) -> tuple[int, int]:
    """Elements of the slip zone at the left and at the right end of the contact (0 where the end stuck)."""
    inside = np.flatnonzero(touch)
    if inside.size == 0:
        return 0, 0
    run = slipped[inside[0]:inside[-1] + 1]
    stuck_at = np.flatnonzero(~run)
    if stuck_at.size == 0:
        return run.size, run.size
    return int(stuck_at[0]), int(run.size - 1 - stuck_at[-1])


def _in_contact_share(edges: np.ndarray, before: tuple[float, float], after: tuple[float, float]) -> np.ndarray:
    """Of a step whose contact ends move linearly from ``before`` to ``after``, the fraction each element
    is in contact (touched: its inner edge inside), 0 or 1 but for the elements an end passes."""
    lo, hi = edges[:-1], edges[1:]
    share = np.ones(len(lo))
    for k, inner in ((0, hi), (1, lo)):       # the left end passes an element's right edge, the right its left
        e0, e1 = before[k], after[k]
        if e1 != e0:
            lam = np.clip((inner - e0) / (e1 - e0), 0.0, 1.0)     # where the end passes the inner edge
            growing = (e1 < e0) if k == 0 else (e1 > e0)
            share = np.minimum(share, np.where(growing, 1.0 - lam, lam))   # in contact after it, or before
    return share


def _passing_slip(passing: np.ndarray, slipped: np.ndarray, slipping: np.ndarray) -> np.ndarray:
    """The elements a contact end passes in a step that slip: those the active set sets slipping where
    they are in contact and that adjoin, through other such elements, an element that slipped in
    contact all the step (next to a stuck edge they only moved before touching, or after leaving)."""
    out = slipped.copy()
    candidates = passing & slipping
    while True:
        near = np.zeros_like(out)
        near[1:] |= out[:-1]
        near[:-1] |= out[1:]
        grown = out | (candidates & near)
        if np.array_equal(grown, out):
            return out & passing
        out = grown


def _march(states: np.ndarray, given: np.ndarray, f: float, A: float, C: np.ndarray, x: np.ndarray,
           edges: np.ndarray, loads: list[np.ndarray], at: list[int],
           ends: list[tuple[float, float]]) -> tuple[Any, ...]:
    """The marched states in order, recorded at the ``given`` ones: shear, accumulated slip, stick
    intervals, work per step (its sub-steps' sum), rigid shift, iterations, residual, slip-zone spans.

    A step's friction work is :func:`threepart.halfplane.load_history.step_work` of the elements slipping in contact
    at both its ends, plus that of the elements a contact end passes in it (which enter or leave
    the contact: :func:`_passing_slip`) over the share of the step they are in contact
    (:func:`_in_contact_share`, the ends moving linearly): issue 37, docs/STEADY_STATE.md §5.
    """
    K, N = len(given), len(x)
    h = np.diff(edges)
    q, slip = np.zeros((K, N)), np.zeros((K, N))
    work, delta = np.zeros(K), np.zeros(K)
    sticks, spans = [], []
    w_prev, bound_prev = np.zeros(N), np.zeros(N)
    stick_prev = np.ones(N, dtype=bool)
    sign_prev = np.zeros(N)
    acc = np.zeros(N)
    its_total, res_max = 0, 0.0
    k, held, step_work_sum = 0, np.ones(N, dtype=bool), 0.0
    # dense systems of a few hundred unknowns: BLAS threads only contend for the shared cores
    with one_blas_thread():
        for i, (_, _, Q, sb) in enumerate(states):
            at[0] = i
            bound = f * loads[i]
            w_fixed = -(A * sb / 4.0) * x
            try:
                t, xi, stick, its, res = coulomb_state(C, bound, w_prev, w_fixed, Q, stick_prev,
                                                       MAX_ITER, sign_prev, DAMPING)
            except FullSlidingError as exc:
                raise FullSlidingError(f"`history` state {k}: {exc}") from None
            w = xi + w_fixed - C @ t
            both = (bound > 0) & (bound_prev > 0)
            dslip = np.where(both & ~stick, w - w_prev, 0.0)
            acc = acc + dslip
            # an element that enters (leaves) the contact in the step slips after (before) it does:
            # the part of its relative displacement, the loads linear in the step
            share = _in_contact_share(edges, ends[i - 1], ends[i]) if i else np.zeros(N)   # from rest: none
            passing = (bound > 0) != (bound_prev > 0)
            dpass = np.where(_passing_slip(passing, both & ~stick, np.where(bound > 0, ~stick, ~stick_prev)),
                             (w - w_prev) * share, 0.0)
            step_work_sum += step_work(bound_prev, bound, dslip) + step_work(bound_prev, bound, dpass)
            held &= stuck(stick, bound > 0, w, w - w_prev) | (bound == 0)
            if i == given[k]:
                touch = bound > 0
                work[k], q[k], slip[k], delta[k] = step_work_sum, t / h, acc, xi
                sticks.append(_stick_intervals(held & touch, edges))
                spans.append(_edge_spans(~held & touch, touch))
                k, held, step_work_sum = k + 1, np.ones(N, dtype=bool), 0.0
            w_prev, bound_prev, stick_prev = w, bound, stick | (bound == 0)
            sign_prev = np.sign(t)
            its_total, res_max = its_total + its, max(res_max, res)
    return q, slip, tuple(sticks), work, delta, its_total, res_max, tuple(spans)

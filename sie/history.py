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
active set of :func:`threepart.coulomb.coulomb_state`.

The friction work of a step is ``Σ |Δw_i| (f p̄_(k-1),i + f p̄_k,i) h/2`` over
the slipping elements (:func:`threepart.history.step_work`); a completed
cycle's energy is the sum over its steps.
"""
from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from threadpoolctl import threadpool_limits

from threepart.coulomb import coulomb_state
from threepart.errors import FullSlidingError
from threepart.history import History, check_history, check_period, step_work, stuck
from threepart.punch import Punch
from threepart.cycles import HistoryResult
from threepart.results import Diagnostics, NormalResult
from threepart.validate import check_punch, integer, lever_arm, load_scale, positive, shear_load

from .normal import DEFAULT_N, SieNormalResult, solve_normal

__all__ = ["load_history", "log_matrix", "element_loads", "DEFAULT_ELEMENTS", "ELEMENTS"]

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
    s, w = np.polynomial.legendre.leggauss(PRESSURE_POINTS)
    theta = th0[:, None] + (th1 - th0)[:, None] * 0.5 * (s + 1)[None, :]
    p = normal.pressure(m + h * np.cos(theta))
    pieces = 0.5 * (th1 - th0) * np.sum(w[None, :] * p * h * np.sin(theta), axis=1)
    return np.bincount(owner, weights=pieces, minlength=len(edges) - 1)


def _check(punch: Any, history: Any, f: Any, A: Any, n: Any, period: Any
           ) -> tuple[History, float, float, int, int | None]:
    """The checked input, every state's, before any numerics."""
    check_punch(punch)
    hist = check_history(history)
    f, A = positive("f", f), positive("A", A)
    n = integer("n", n, *ELEMENTS)
    for k in range(len(hist)):
        P, s, Q, _ = hist.state(k)
        try:
            lever_arm(punch, s)
            load_scale(punch, P, A)
            shear_load(Q, f, P, what="the history cannot be marched past this state")
        except ValueError as exc:
            raise type(exc)(f"`history` state {k}: {exc}") from None
    return hist, f, A, n, check_period(period, hist)


def _stick_intervals(stick: np.ndarray, edges: np.ndarray) -> tuple[tuple[float, float], ...]:
    """The runs of stick elements as intervals between element edges."""
    d = np.diff(np.concatenate([[0], stick.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    return tuple((float(edges[i]), float(edges[j])) for i, j in zip(starts, ends))


def load_history(punch: Punch, history: Any, f: float, *, A: float, n: int = DEFAULT_ELEMENTS,
                 normal_n: int = DEFAULT_N, period: int | None = None) -> HistoryResult:
    """March ``punch`` through a load history with the memory of slip.

    Parameters
    ----------
    punch
        Three-part punch geometry (paper eq. 2).
    history
        A sequence of states ``(P, s, Q, sigma_bulk)`` (normal load > 0, its lever
        arm, the shear force the punch exerts on the substrate along +x, the
        substrate's bulk stress, tension positive), or the path of a CSV file
        with those columns (:func:`threepart.history.read_history`). The body
        starts unloaded; the first state is applied in one step.
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
        (:meth:`threepart.history.History.cycles`).

    Returns
    -------
    HistoryResult
        ``method="sie"``; ``stick``, ``shear(x, k)``, ``slip(x, k)``,
        ``normals``, ``energy`` per completed cycle (between visits of the last
        state), ``work`` per step; ``diagnostics`` hold ``n``, the active-set
        ``iterations`` summed over the states, the largest Coulomb ``residual``,
        ``steps`` (states) and the timings (``normal``, ``friction``, ``total``);
        ``info`` holds ``normal_solves`` (distinct ``(P, s)``) and ``h``.

    Raises
    ------
    TypeError, ValueError
        Invalid input, before any numerics, naming the state
        (``FullSlidingError`` for ``|Q_k| >= f P_k``).
    SeparationError, ArcExtentError, SlopeLimitError, NoConvergenceError
        As :func:`sie.solve_normal` for a state's contact; ``NoConvergenceError``
        also when a state's stick/slip sets do not settle.
    """
    hist, f, A, n, period = _check(punch, history, f, A, n, period)
    t0 = time.perf_counter()
    cache: dict[tuple[float, float], SieNormalResult] = {}
    normals: list[NormalResult] = []
    for k in range(len(hist)):
        P, s, _, _ = hist.state(k)
        if (P, s) not in cache:
            cache[P, s] = solve_normal(punch, P, s, A=A, n=normal_n)
        normals.append(cache[P, s])
    t_normal = time.perf_counter() - t0
    edges = np.linspace(min(-r.a for r in normals), max(r.c for r in normals), n + 1)
    x = 0.5 * (edges[:-1] + edges[1:])
    h = float(edges[1] - edges[0])
    C = log_matrix(edges, A)
    loads = {key: element_loads(r, edges) for key, r in cache.items()}
    march = _march(hist, f, A, C, x, edges, [loads[float(P), float(s)] for P, s in zip(hist.P, hist.s)])
    q, slip, stick, work, delta, its, res = march
    cycles = hist.cycles(period)
    energy = np.array([work[i + 1:j + 1].sum() for i, j in cycles])
    total = time.perf_counter() - t0
    diag = Diagnostics(n=n, iterations=its, residual=res, steps=len(hist),
                       timings={"normal": t_normal, "friction": total - t_normal, "total": total})
    return HistoryResult(punch=punch, f=f, P=hist.P, s=hist.s, Q=hist.Q, sigma_bulk=hist.sigma_bulk,
                         normals=tuple(normals), stick=stick, energy=energy, cycles=cycles, work=work,
                         method="sie", x_nodes=x, q_nodes=q, slip_nodes=slip, edges=edges, delta=delta,
                         diagnostics=diag, info={"normal_solves": len(cache), "h": h})


def _march(hist: History, f: float, A: float, C: np.ndarray, x: np.ndarray, edges: np.ndarray,
           loads: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray, tuple, np.ndarray, np.ndarray, int, float]:
    """The states in order: shear, accumulated slip, stick intervals, work per step, rigid shift, iterations, residual."""
    K, N = len(hist), len(x)
    h = np.diff(edges)
    q, slip = np.zeros((K, N)), np.zeros((K, N))
    work, delta = np.zeros(K), np.zeros(K)
    sticks = []
    w_prev, bound_prev = np.zeros(N), np.zeros(N)
    stick_prev = np.ones(N, dtype=bool)
    sign_prev = np.zeros(N)
    acc = np.zeros(N)
    its_total, res_max = 0, 0.0
    # dense systems of a few hundred unknowns: BLAS threads only contend for the shared cores
    with threadpool_limits(limits=1, user_api="blas"):
        for k in range(K):
            _, _, Q, sb = hist.state(k)
            bound = f * loads[k]
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
            work[k] = step_work(bound_prev, bound, dslip)
            q[k], slip[k], delta[k] = t / h, acc, xi
            sticks.append(_stick_intervals(stuck(stick, bound > 0, w, w - w_prev), edges))
            w_prev, bound_prev, stick_prev = w, bound, stick | (bound == 0)
            sign_prev = np.sign(t)
            its_total, res_max = its_total + its, max(res_max, res)
    return q, slip, tuple(sticks), work, delta, its_total, res_max

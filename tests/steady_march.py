"""An independent reference for the steady state: the load history marched step by step.

The tangential problem of two similar half-planes (docs/BULK_STRESS.md, B1–B2)
on a grid of panels, shear piecewise constant, collocated at the panels'
centres: the relative displacement (substrate minus punch) is

    u_i = Σ_j K_ij q_j + C + A sigma_bulk x_i/4,   K_ij = -(A/π) ∫_(panel j) ln|x_i - t| dt

(exact panel integrals), ``C`` the rigid shift. Each step of the history solves,
by an active set, Coulomb's law with the normal pressure of the closed form at
that state: a stick panel keeps its ``u`` of the last step; a slip panel carries
``q = ±f p`` against its slip; ``Σ q h = Q``. Nothing of the superposition
(eqs. S3–S11) enters: the stick zone is the set of panels that do not slip over
the last cycle, the energy the work ``Σ |q| |Δu| h`` of that cycle.
"""
from __future__ import annotations

import math

import numpy as np

from threepart import closedform as cf


#: a panel has slipped in the last cycle when its slip exceeds this fraction of the largest:
#: a panel next to a stick zone's end can be set to slip with a slip of rounding (~1e-18 mm
#: against 4e-5 mm), while a true slip falls as (x - r)^(3/2) to the end, above this a panel away
SLIP_FLOOR = 1e-9
#: the active set's rounding, the same on both sides: a stick panel is freed when |q| exceeds f p by
#: more than this of f p, a slip panel re-stuck when it slips backwards by more than this of the
#: largest slip. (With 1e-15 on the slip, a panel at a stick zone's end whose |q| - f p and
#: backward slip were both of rounding, 1.2e-12 and 4.2e-13, was freed and re-stuck for ever
#: when LAPACK ran on one thread, as it does in each pytest-xdist worker.)
ROUNDING = 1e-12


def kernel(x: np.ndarray, edges: np.ndarray, A: float) -> np.ndarray:
    """``K_ij = -(A/π) ∫_(e_j)^(e_j+1) ln|x_i - t| dt``, by ``∫ ln|y| dy = y ln|y| - y``."""
    def F(y: np.ndarray) -> np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(y == 0, 0.0, y * np.log(np.abs(y)) - y)
    return -(A / math.pi) * (F(x[:, None] - edges[None, :-1]) - F(x[:, None] - edges[None, 1:]))


def history(punch, states, f: float, A: float, edges: np.ndarray, *, steps: int = 40, cycles: int = 3,
            first: int = 40) -> tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """March ``(P_0, s_0)`` at ``Q = 0``, then ``Q``, ``sigma_bulk`` to state 0, then ``cycles`` cycles.

    Returns the panels' centres and widths, the friction work of the last cycle and
    the mask of the panels that slipped in it (by more than :data:`SLIP_FLOOR` of the most).
    """
    x, h = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    K = kernel(x, edges, A)
    P0, s0, Q0, g0 = states[0]
    path = [(P0, s0, t * Q0, t * g0, -1) for t in np.linspace(0, 1, first)[1:]]
    for c in range(cycles):
        for i, j in ((0, 1), (1, 0)):
            path += [(*(states[i][k] + t * (states[j][k] - states[i][k]) for k in range(4)), c)
                     for t in np.linspace(0, 1, steps + 1)[1:]]
    u_ref, stick, sign = np.zeros(x.size), np.ones(x.size, bool), np.zeros(x.size)
    work, amount = 0.0, np.zeros(x.size)
    for P, s, Q, g, c in path:
        p = cf.solve_normal(punch, P, s, A=A).pressure(x)
        q, u, stick, sign = _step(K, x, h, p, Q, g, f, A, u_ref, stick & (p > 0), sign)
        if c == cycles - 1:
            du = u - u_ref
            work += float(np.sum(np.abs(q) * np.abs(du) * h))
            amount += np.where(~stick & (p > 0), np.abs(du), 0.0)
        u_ref, stick = u, stick | (p <= 0)
    return x, h, work, amount > SLIP_FLOOR * amount.max()


def _step(K, x, h, p, Q, g, f, A, u_ref, stick, sign):
    """One state of the history: the active set of stick and slip panels, from the last one.

    A slip panel's shear is known (``q_i = ±f p_i``), so each iteration solves for the stick
    panels' shear and the shift ``C`` alone: their rows ``u_i = u_ref_i`` and ``Σ q h = Q``,
    the slip panels' shear moved to the right-hand side.
    """
    contact = np.flatnonzero(p > 0)
    for _ in range(500):
        held, free = contact[stick[contact]], contact[~stick[contact]]
        q = np.zeros(x.size)
        q[free] = sign[free] * f * p[free]
        n = held.size
        M, rhs = np.zeros((n + 1, n + 1)), np.zeros(n + 1)
        M[:n, :n], M[:n, n] = K[np.ix_(held, held)], 1.0
        rhs[:n] = u_ref[held] - A * g * x[held] / 4 - K[np.ix_(held, free)] @ q[free]
        M[n, :n], rhs[n] = h[held], Q - h[free] @ q[free]
        sol = np.linalg.solve(M, rhs)
        q[held] = sol[:n]
        u = K @ q + sol[n] + A * g * x / 4
        du = u - u_ref
        over = stick & (p > 0) & (np.abs(q) > f * p * (1 + ROUNDING))
        # q must oppose the substrate's slip relative to the punch: du and q of opposite signs
        back = ~stick & (p > 0) & (du * sign > ROUNDING * max(float(np.abs(du).max()), 1e-300))
        if not over.any() and not back.any():
            return q, u, stick, sign
        if over.any():      # first free the overloaded panels, then re-stick the wrong slips
            stick, sign = stick & ~over, np.where(over, np.sign(q), sign)
        else:
            stick = stick | back
    raise RuntimeError("the marched history's active set did not settle in 500 iterations")

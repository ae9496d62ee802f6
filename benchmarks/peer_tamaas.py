"""The FFT-BEM peer: the same rigid-punch contact solved by tamaas (PolonskyKeerRey, periodic).

A user who wants a numerical answer without a finite-element model would reach
for tamaas. This module solves a catalogue case with it, on a periodic line of
``L = period · W`` with ``cells`` cells per contact width ``W``, so that the FEM
benchmark can time both to the same accuracy, side by side, in one run.

Only the vertical load is imposed (tamaas has no rigid-body tilt unknown), so
the peer covers the tilt-free cases: the symmetric case A (``α = 0`` by
symmetry) and suppressed tilt. tamaas is a benchmark extra
(``pip install -e ".[bench]"``), never a runtime dependency.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from threepart.problem.punch import Punch

__all__ = ["PeerResult", "solve_peer", "available"]


def available() -> bool:
    """Whether tamaas is installed."""
    try:
        import tamaas  # noqa: F401
    except ImportError:
        return False
    return True


@dataclass(frozen=True)
class PeerResult:
    """tamaas's answer: contact ends, nodal pressure, and the time of its solve."""

    a: float
    c: float
    x: np.ndarray
    p: np.ndarray
    time_s: float
    cells_per_W: int
    period_W: float

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """Pressure interpolated linearly between the grid points."""
        return np.interp(x, self.x, self.p, left=0.0, right=0.0)


def _edge(x: np.ndarray, p: np.ndarray, i: int, step: int, k: int = 8) -> float:
    """Contact end next to the last loaded point ``i``: ``p²`` linear in ``x`` over ``k`` points."""
    j = i + step * np.arange(k)
    coef = np.polyfit(x[j] - x[i], p[j] ** 2, 1)
    return float(x[i] - coef[1] / coef[0])


def solve_peer(punch: Punch, P: float, *, E: float, nu: float, width: float,
               cells: int = 2048, period: float = 64.0, tol: float = 1e-12) -> PeerResult:
    """Rigid punch of ``punch``'s profile pressed by ``P`` (per unit length), no tilt.

    Parameters
    ----------
    punch
        Profile (eq. 2); the punch is pressed vertically (``α = 0``).
    P
        Load per unit length.
    E, nu
        The half-plane's modulus and Poisson's ratio (tamaas uses E/(1 - ν²),
        the rigid punch's compliance 2(1 - ν²)/E).
    width
        An estimate of the contact width W that sets the grid: ``cells`` per W
        over ``period`` W.
    cells, period, tol
        Grid density, period length and the solver's tolerance.
    """
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    L = period * width
    n = int(round(period * cells))
    model = tm.ModelFactory.createModel(tm.model_type.basic_1d, [L], [n])
    model.E, model.nu = E, nu
    # offset half a cell so that no grid point falls on a join or an end by accident
    x = (np.arange(n) + 0.5) * (L / n) - L / 2
    h = -punch.profile(x)
    h -= h.max()
    solver = tm.PolonskyKeerRey(model, h, tol)
    t0 = time.perf_counter()
    solver.solve(P / L)
    dt = time.perf_counter() - t0
    p = np.array(model.traction, dtype=float).ravel()
    on = np.flatnonzero(p > 0)
    left, right = _edge(x, p, int(on[0]), +1), _edge(x, p, int(on[-1]), -1)
    return PeerResult(a=-left, c=right, x=x, p=p, time_s=dt, cells_per_W=cells, period_W=period)


if __name__ == "__main__":   # a smoke run on the symmetric case A
    from threepart import closedform, rigid_punch

    pu, P = Punch(10.0, 10.0, 1.0), 28846.0
    ref = closedform.solve_normal(pu, P, A=rigid_punch(210e3, 0.3))
    W = ref.a + ref.c
    for cells in (256, 512, 1024, 2048):
        r = solve_peer(pu, P, E=210e3, nu=0.3, width=W, cells=cells)
        peak = max(q.p for q in ref.peaks())
        xs = r.x[(r.x > -ref.a + 0.05 * W) & (r.x < ref.c - 0.05 * W)]   # at its own nodes
        print(f"cells/W {cells:5d}  {r.time_s:6.2f} s  a {abs(r.a - ref.a) / W:.1e} W  "
              f"c {abs(r.c - ref.c) / W:.1e} W  p {np.max(np.abs(r.pressure(xs) - ref.pressure(xs))) / peak:.1e}")

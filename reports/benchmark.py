"""Speed of the closed form, the stresses and the fatigue history, measured side by side in one run.

Each figure is a ratio of two timings taken in the same process one after the
other, so that the machine's load (reported with them) cancels as far as it
can. Used by ``benchmarks/bench_speed.py`` (and ``bench_closedform.py``) and by
the verification report's speed section (:mod:`reports.verify.speed`).

measure         -- every figure of :data:`reports.verify.speed.TARGETS`, with the load before and after
naive           -- a per-case ``scipy.optimize.fsolve`` on the same equations (the baseline)
paper_equations -- its equations: the printed P(a, c) and s(a, c), transcribed in numpy
"""
from __future__ import annotations

import math
import os
import time
from typing import Any, Callable

import numpy as np
from scipy.optimize import fsolve

from threepart import closedform as cf
from threepart import fatigue as fat
from threepart.fatigue import history as fh
from threepart.problem.catalogue import get_case
from threepart.closedform import formulas
from threepart.closedform.newton import evaluations
from threepart.stress import stress

__all__ = ["measure", "naive", "paper_equations", "best_of", "SIZES"]

#: sizes of each measurement, full and quick (cases of the batch, of the naive fsolve, single
#: solves, scattered stress points, the grid's nx and nz, and the fatigue grid's)
SIZES = {"full": {"batch": 20_000, "naive": 200, "single": 2000, "points": 2000, "grid": (200, 100),
                  "fatigue": (41, 21)},
         "quick": {"batch": 5000, "naive": 50, "single": 500, "points": 500, "grid": (200, 100),
                   "fatigue": (21, 11)}}


def best_of(fn: Callable[[], Any], repeat: int = 3) -> float:
    """The smallest wall time of ``repeat`` runs of ``fn``, in seconds."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def paper_equations(punch: Any, a: np.ndarray, c: np.ndarray, A: float) -> tuple[np.ndarray, np.ndarray]:
    """``(P, s)`` of a contact ``[-a, c]``: eqs. (equilibrium_condition_1, _2) as printed, transcribed in numpy.

    ``8AP = (a+c)^2 F0 + 2 k1/R1 (a-2b-c) sqrt((a-b)(b+c)) - 2 k2/R2 (a+2b-c) sqrt((a+b)(c-b))``
    with ``F0`` of eq. (f0), and ``6AP (s - m) = k2/R2 ((a+b)(c-b))^(3/2) - k1/R1 ((a-b)(b+c))^(3/2)``,
    the sign of ``P`` corrected (docs/ERRATA.md): what a user would transcribe, shown beside issue 33's
    baseline (:func:`naive` on :mod:`closedform.formulas`, whose array handling costs it about 7x).
    """
    b, k1, k2 = punch.b, punch.k1 / punch.R1, punch.k2 / punch.R2
    W = a + c
    F0 = k1 * np.arccos((2 * b - a + c) / W) + k2 * np.arccos((a + 2 * b - c) / W) + np.pi / punch.R
    left, right = (a - b) * (b + c), (a + b) * (c - b)
    P = (W**2 * F0 + 2 * k1 * (a - 2 * b - c) * np.sqrt(left)
         - 2 * k2 * (a + 2 * b - c) * np.sqrt(right)) / (8 * A)
    s = 0.5 * (c - a) + (k2 * right**1.5 - k1 * left**1.5) / (6 * A * P)
    return P, s


def naive(punch: Any, A: float, P: np.ndarray, s: np.ndarray, equations: Any = None) -> np.ndarray:
    """``(a, c)`` of each case by ``fsolve`` on ``P(a, c)`` and ``s(a, c)``, from a symmetric Hertz-like start.

    The equations are the library's forward closed forms (eqs. equilibrium_condition_1 and _2 of
    :mod:`closedform.formulas`, issue 33's baseline) unless ``equations`` gives others (``(punch, a, c, A)
    -> (P, s)``, e.g. :func:`paper_equations`).
    """
    equations = equations or (lambda punch, a, c, A: (formulas.load(punch, a, c, A),
                                                      formulas.lever_arm(punch, a, c)))
    out = np.empty((P.size, 2))
    for i, (Pi, si) in enumerate(zip(P, s)):
        a0 = punch.b + math.sqrt(2 * Pi * A * punch.R1 / math.pi) * 0.5

        def res(ac: np.ndarray, Pi: float = Pi, si: float = si) -> list[float]:
            load, lever = equations(punch, *np.maximum(ac, punch.b), A)
            return [float(load / Pi - 1), float(lever - si)]

        out[i] = fsolve(res, [a0, a0], xtol=1e-13)
    return out


def _closedform(size: dict[str, Any]) -> dict[str, float]:
    case = get_case("caseA_moment")
    punch, A = case.punch, case.A
    rng = np.random.default_rng(0)
    P, s = rng.uniform(200.0, 2000.0, size["batch"]), rng.uniform(-0.3, 0.3, size["batch"])
    nn, ns = size["naive"], size["single"]
    t_naive = best_of(lambda: naive(punch, A, P[:nn], s[:nn])) / nn
    t_batch = best_of(lambda: cf.solve_normal_batch(punch, P, s, A=A)) / P.size
    # one solve at a time over the random draw, not one case repeated (issue 41)
    draw = [(float(Pi), float(si)) for Pi, si in zip(P[:ns], s[:ns])]
    t_single = best_of(lambda: [cf.solve_normal(punch, Pi, si, A=A) for Pi, si in draw]) / ns
    t_paper = best_of(lambda: naive(punch, A, P[:nn], s[:nn], paper_equations)) / nn
    n0 = evaluations()
    batch = cf.solve_normal_batch(punch, P, s, A=A)
    return {"batch_over_naive": t_naive / t_batch, "single_over_naive": t_naive / t_single,
            "evaluations_per_case": (evaluations() - n0) / P.size, "batch_us_per_case": 1e6 * t_batch,
            "single_us": 1e6 * t_single, "naive_us_per_case": 1e6 * t_naive,
            "naive_paper_us_per_case": 1e6 * t_paper, "single_over_naive_paper": t_paper / t_single,
            "batch_over_naive_paper": t_paper / t_batch,
            "batch_vs_naive_a": float(np.max(np.abs(naive(punch, A, P[:nn], s[:nn])[:, 0] / batch.a[:nn] - 1))),
            "batch_vs_naive_paper_a": float(np.max(np.abs(
                naive(punch, A, P[:nn], s[:nn], paper_equations)[:, 0] / batch.a[:nn] - 1)))}


def _stress(size: dict[str, Any]) -> dict[str, float]:
    case = get_case("caseA_moment")
    n = cf.solve_normal(case.punch, case.P, case.s or 0.0, A=case.A)
    W = n.a + n.c
    rng = np.random.default_rng(1)
    xs, zs = rng.uniform(-n.a - W / 4, n.c + W / 4, size["points"]), rng.uniform(0, W, size["points"])
    nx, nz = size["grid"]
    x, z = np.linspace(-n.a - W / 4, n.c + W / 4, nx)[None, :], np.linspace(0, W, nz)[:, None]
    kw: dict[str, Any] = {"pressure": n.pressure, "ends": (-n.a, n.c), "kinks": (-case.punch.b, case.punch.b)}
    t_point = best_of(lambda: stress(xs, zs, **kw), 1) / xs.size
    t_grid = best_of(lambda: stress(x, z, **kw), 1)
    return {"stress_us_per_point": 1e6 * t_point, "grid_s": t_grid,
            "grid_us_per_point": 1e6 * t_grid / (nx * nz)}


def _fatigue(size: dict[str, Any]) -> dict[str, float]:
    """The history of the fan-blade flank's fretting cycle (README), superposed and state by state."""
    from threepart import Punch
    from threepart.problem.material import compliance

    punch, A = Punch(60.0, 40.0, 1.0), compliance(115000.0, 0.32)
    normal = cf.solve_normal(punch, 1500.0, 0.28, A=A)
    cycle = cf.fretting_cycle(normal, 480.0, 0.8, states=5, sigma_bulk=300.0)
    W = normal.a + normal.c
    nx, nz = size["fatigue"]
    x = np.linspace(-normal.a - W / 4, normal.c + W / 4, nx)[None, :]
    z = np.linspace(0.0, W, nz)[:, None]
    t_new = best_of(lambda: fat.stress_history(cycle, x, z, nu=0.32), 1)
    keep = fh._superposes
    try:
        fh._superposes = lambda c: False   # type: ignore[assignment]  # the state-by-state path
        t_old = best_of(lambda: fat.stress_history(cycle, x, z, nu=0.32), 1)
    finally:
        fh._superposes = keep   # type: ignore[assignment]
    states = fat.stress_history(cycle, x[:, :2], z[:2], nu=0.32).states
    return {"fatigue_history_speedup": t_old / t_new,
            "fatigue_ms_per_point_and_state": 1e3 * t_new / (nx * nz * states)}


def measure(quick: bool = False, say: Callable[[str], None] | None = None) -> dict[str, Any]:
    """Every figure, its size, and the load average before and after (``os.getloadavg``)."""
    size = SIZES["quick" if quick else "full"]
    load0 = os.getloadavg()[0]
    figures: dict[str, float] = {}
    for name, part in (("closed form", _closedform), ("stress", _stress), ("fatigue history", _fatigue)):
        if say:
            say(f"[speed] {name} ...")
        figures.update(part(size))
    return {"figures": figures, "load": [load0, os.getloadavg()[0]], "cpus": os.cpu_count(),
            "sizes": {k: list(v) if isinstance(v, tuple) else v for k, v in size.items()}}

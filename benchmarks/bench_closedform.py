"""Closed-form speed, measured side by side in one run, against its speed targets.

    python benchmarks/bench_closedform.py [--cases 10000] [--json out.json]

Measures one ``solve_normal``, a batch of load cases, ``pressure`` on 10^6
points, and a naive per-case ``scipy.optimize.fsolve`` loop on the same
equations (:func:`threepart.reports.benchmark.naive`, shared with
``bench_speed.py`` and the report's speed section). Ratios are what to read:
the machines are noisy.
"""
from __future__ import annotations

import argparse
import json
import numpy as np

from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.closedform import formulas
from threepart.reports.benchmark import best_of
from threepart.reports.benchmark import naive as _naive
from threepart.reports.verify.speed import TARGETS, meets

#: case A with unequal radii (mm) on steel, from the catalogue; the loads are this benchmark's own
CASE = get_case("caseA_moment")
PUNCH, A = CASE.punch, CASE.A


def naive(P: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Per-case fsolve on (P(a, c), s(a, c)): the one baseline of reports/benchmark.py."""
    return _naive(PUNCH, A, P, s)


def main() -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=10_000)
    parser.add_argument("--naive-cases", type=int, default=200)
    parser.add_argument("--json", help="write the figures to this file")
    args = parser.parse_args()

    rng = np.random.default_rng(0)
    P = rng.uniform(200.0, 2000.0, args.cases)
    s = rng.uniform(-0.3, 0.3, args.cases)
    x = np.linspace(-1.2, 1.2, 10**6)
    sol = cf.solve_normal(PUNCH, 400.0, 0.1, A=A)

    n_single = min(2000, args.cases)       # one solve at a time over the random draw (issue 41), not one case
    draw = [(float(Pi), float(si)) for Pi, si in zip(P[:n_single], s[:n_single])]
    t_single = best_of(lambda: [cf.solve_normal(PUNCH, Pi, si, A=A) for Pi, si in draw]) / n_single
    t_batch = best_of(lambda: cf.solve_normal_batch(PUNCH, P, s, A=A), repeat=3)
    t_press = best_of(lambda: sol.pressure(x))
    nn = args.naive_cases
    t_naive = best_of(lambda: naive(P[:nn], s[:nn])) / nn

    batch = cf.solve_normal_batch(PUNCH, P, s, A=A)
    ref = naive(P[:nn], s[:nn])
    fig = {
        "single_solve_ms": 1e3 * t_single,
        "batch_cases": args.cases,
        "batch_cases_per_s": args.cases / t_batch,
        "pressure_1e6_points_s": t_press,
        "naive_fsolve_ms_per_case": 1e3 * t_naive,
        "batch_speedup_over_naive": t_naive * args.cases / t_batch,
        "single_speedup_over_naive": t_naive / t_single,
        "naive_vs_batch_max_rel_diff_a": float(np.max(np.abs(ref[:, 0] / batch.a[:nn] - 1))),
        "batch_max_rel_load_residual": float(np.max(np.abs(formulas.load(PUNCH, batch.a, batch.c, A) / P - 1))),
    }
    # the ratios' targets are the report's (reports/verify/speed.py); the absolute ones this script's
    targets = {"single_solve_ms": ("<=", 0.5), "batch_cases_per_s": (">=", 5e4),
               "batch_speedup_over_naive": TARGETS["batch_over_naive"][1:],
               "single_speedup_over_naive": TARGETS["single_over_naive"][1:],
               "pressure_1e6_points_s": ("<=", 0.3)}
    for key, val in fig.items():
        tgt = targets.get(key)
        mark = ""
        if tgt:
            mark = f"  target {tgt[0]} {tgt[1]:g}: {'met' if meets(val, *tgt) else 'MISSED'}"
        print(f"{key:<34} {val:12.4g}{mark}")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(fig, fh, indent=2)
    return fig


if __name__ == "__main__":
    main()

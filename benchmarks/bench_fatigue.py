"""Speed of the four fretting-fatigue parameters on a 200 x 100 grid of a closed-form cycle.

    python benchmarks/bench_fatigue.py [--nx 200] [--nz 100] [--states 21] [--repeat 3] [--json out.json]

The cycle: catalogue case ``caseA_moment`` (closed form), ``Q_max = 0.4 f P`` with
``f = 0.5``, the closed form's default 21 recorded states per branch (60 distinct
states: each branch starts where the previous one ended). The grid: x over
[-a - W/4, c + W/4] and z over [0, W] (W = a + c), nx x nz points with the surface
as the first row, as ``threepart fatigue`` lays it out.

Timed separately:

- ``history``: the stress at every state (``stress_history``; one stress evaluation
  per distinct state by :mod:`threepart.stress`), once;
- ``von_mises_range``, ``swt``, ``findley``, ``ruiz``: each parameter from that history,
  best of ``--repeat``.

Measured 2026-11-23 on the 2-core machine, shared (load 2-9), 200 x 100, 60 states:
history 2259 s; von Mises range 0.36 s, SWT 2.66 s, Findley 1.96 s, Ruiz 0.002 s
(docs/FATIGUE.md).
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from threepart import closedform as cf
from threepart import fatigue as fat
from threepart.problem.catalogue import get_case

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_sie import best_time  # noqa: E402  (the benchmarks' one timer)

F, E, NU = 0.5, 2.1e5, 0.3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nx", type=int, default=200)
    parser.add_argument("--nz", type=int, default=100)
    parser.add_argument("--states", type=int, default=21, help="recorded states per branch")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json")
    args = parser.parse_args()

    case = get_case("caseA_moment")
    normal = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
    cycle = cf.fretting_cycle(normal, 0.4 * F * case.P, F, states=args.states)
    W = normal.a + normal.c
    x = np.linspace(-normal.a - 0.25 * W, normal.c + 0.25 * W, args.nx)[None, :]
    z = np.linspace(0.0, W, args.nz)[:, None]

    t = time.perf_counter()
    h = fat.stress_history(cycle, x, z, nu=NU)
    out: dict[str, float] = {"points": float(h.x.size), "states": float(h.states),
                             "history_s": time.perf_counter() - t}
    for name, fun in [("von_mises_range", lambda: fat.von_mises_range(h)),
                      ("swt", lambda: fat.swt(h, E=E)),
                      ("findley", lambda: fat.findley(h)),
                      ("ruiz", lambda: fat.ruiz(cycle, h))]:
        out[f"{name}_s"], _ = best_time(fun, args.repeat)
    out["parameters_s"] = sum(out[f"{k}_s"] for k in ("von_mises_range", "swt", "findley", "ruiz"))
    for k, v in out.items():
        print(f"{k:20s} {v:.4g}")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"nx": args.nx, "nz": args.nz, "states_per_branch": args.states, **out}, fh, indent=1)


if __name__ == "__main__":
    main()

"""Issue 33's speed ratios, side by side in one run, and the peak memory of the stress on many points.

    python benchmarks/bench_speed.py [--quick] [--memory N] [--json out.json]

The ratios are :func:`threepart.reports.benchmark.measure`'s, the same the
verification report shows (:mod:`threepart.reports.verify.speed`, with their targets):
the closed-form batch and a single solve against a naive per-case ``fsolve``,
the forward evaluations per case, the stress per point and on a 200 x 100 grid,
and the fatigue history superposed against state by state. ``--memory N``
measures, in a child process, the peak resident memory of ``stress`` on ``N``
points of a grid and the time it took (``--scattered``: also on ``N`` random
points, which take the pointwise rule chunk by chunk).

Measured 2026-11-26 (2 CPUs shared, load 3-5, at nice 10): 10**7 grid points (10,000 x 1,000)
in 142 s with a peak of 862 MB.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time

from threepart.reports.benchmark import measure
from threepart.reports.verify.speed import SHOWN, TARGETS, met

#: the child that measures the peak memory: a grid of n points, 1000 depths, under caseA_moment
MEMORY_CHILD = """
import resource, sys, time
import numpy as np
from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.stress import stress
n, scattered = int(sys.argv[1]), sys.argv[2] == "scattered"
case = get_case("caseA_moment")
sol = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
W = sol.a + sol.c
nz = 1000 if n >= 10**5 else 10
x = np.linspace(-sol.a - W / 4, sol.c + W / 4, n // nz)[None, :]
z = np.linspace(W / nz, W, nz)[:, None]
if scattered:      # the same number of points, drawn at random: the pointwise rule, chunk by chunk
    rng = np.random.default_rng(0)
    x, z = rng.uniform(-sol.a - W / 4, sol.c + W / 4, n), rng.uniform(0, W, n)
t = time.perf_counter()
s = stress(x, z, pressure=sol.pressure, ends=(-sol.a, sol.c), kinks=(-case.punch.b, case.punch.b),
           progress=lambda m: print(m, file=sys.stderr, flush=True))
print(time.perf_counter() - t, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, s.sxx.size)
"""


def memory(n: int, scattered: bool = False) -> dict[str, float]:
    """Peak RSS (MB) and seconds of ``stress`` on ``n`` points (a grid, or scattered), in a child process."""
    out = subprocess.run([sys.executable, "-c", MEMORY_CHILD, str(n), "scattered" if scattered else "grid"],
                         check=True, capture_output=True, text=True).stdout.split()
    kind = "scattered" if scattered else "grid"
    return {f"memory_{kind}_points": float(out[2]), f"memory_{kind}_s": float(out[0]),
            f"memory_{kind}_peak_MB": float(out[1])}


def main() -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--memory", type=int, default=0, help="points of the memory measurement (0: none)")
    parser.add_argument("--scattered", action="store_true", help="measure the memory on scattered points too")
    parser.add_argument("--json")
    args = parser.parse_args()
    t = time.perf_counter()
    rec = measure(args.quick, say=print)
    if args.memory:
        rec["figures"].update(memory(args.memory))
        if args.scattered:
            rec["figures"].update(memory(args.memory, scattered=True))
    for k, v in rec["figures"].items():
        label, op, target = TARGETS.get(k, (SHOWN.get(k, k), "", None))
        mark = f"  target {op} {target:g}: {'met' if met(k, v) else 'MISSED'}" if target is not None else ""
        print(f"{k:<32} {v:12.4g}{mark}")
    print(f"load average {rec['load'][0]:.2f} before, {os.getloadavg()[0]:.2f} after; "
          f"{time.perf_counter() - t:.1f} s; peak RSS {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rec, fh, indent=1)
    return rec


if __name__ == "__main__":
    main()

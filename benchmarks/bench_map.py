"""Time the quick validity map on 1 and on 2 local dask workers, side by side, and the speed-up.

Run ``python benchmarks/bench_map.py`` (the real finite-body ``evaluate`` of
:mod:`reports.map.validity`; issue 12's budget is 15 minutes for the quick map on
this 2-core machine) or ``python benchmarks/bench_map.py --fake 2`` (the same
quick grid with a fake ``evaluate`` that sleeps 2 s per point, so that the
engine itself is timed: dask's start-up and per-task overhead). Each run
writes a fresh map into a temporary directory, removed afterwards, and the
numbers of the runs are checked to agree.

Per run it prints the cluster's start-up, the sweep's wall time, the sum of
the tasks' own times (``time_s``), the overhead per task
(``(sweep x workers - sum) / tasks``: dask, the workers' first imports and idle
workers at the end) and the total with the plots; then the
speed-up of the sweep and of the total. ``--workers 1,2,4`` times other counts.

``python benchmarks/bench_map.py --estimate-full N`` estimates the full map
without running it: it evaluates every ``len(grid)/N``-th point of the full
grid (all axes represented) in this process, one after the other, and scales
the mean ``time_s`` to the full grid plus its bisection steps (``--crossings``
per curve, each at most ``STEP_CAP["full"]`` steps) on ``--workers`` workers.
It also times ``max(1, N // 4)`` points of each study of the full map
(:mod:`reports.map.studies`: the partial slip and the small slope on their
subsets) and adds them, the small-slope crossings (``--slope-evaluations``
evaluations of a slope point each) and the CalculiX referee points
(``--referee-s`` CPU seconds each, not timed here: ``python -m
threepart.reports.map.referee`` times them).
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from threepart.reports.map import validity
from threepart.reports.map.boundary import CURVE_AXES, STEP_CAP
from threepart.reports.map.sweep import exit_status, run_map
from threepart.reports.map.referee import REFEREE_POINTS
from threepart.reports.map.validity import RESULT_KEYS
from threepart.reports.map.validity_slip import evaluate_slip
from threepart.reports.map.validity_slope import evaluate_slope


class SleepEvaluate:
    """A fake ``evaluate``: sleeps ``seconds`` and returns a smooth error surface of the point."""

    def __init__(self, seconds: float):
        self.seconds = seconds

    def __call__(self, point: Any, quick: bool) -> dict[str, float]:
        t0 = time.perf_counter()
        time.sleep(self.seconds)
        e = 0.003 * (point.a_minus_b_over_R1 / 0.01) * (point.b_over_R1 / 0.1)
        return {"peak_rel_error": e, "p_left_rel_error": e, "p_right_rel_error": e,
                "a_rel_error": e / 3, "c_rel_error": e / 3, "alpha_error": e / 10,
                "fem_error_estimate": 1e-4, "P": 1.0, "s": 0.0, "time_s": time.perf_counter() - t0}


class SleepControl:
    """A fake ``control``: sleeps ``seconds``, error 1e-4."""

    def __init__(self, seconds: float):
        self.seconds = seconds

    def __call__(self, quick: bool) -> dict[str, float]:
        t0 = time.perf_counter()
        time.sleep(self.seconds)
        return {"control_rel_error": 1e-4, "time_s": time.perf_counter() - t0}


def one_run(workers: int, fake: float | None, root: Path) -> dict[str, Any]:
    """The quick map on a new local cluster of ``workers`` processes; its map.json document."""
    kw: dict[str, Any] = {}
    if fake is not None:
        kw = {"evaluate": SleepEvaluate(fake), "control": SleepControl(fake)}
    print(f"--- {workers} worker(s) ---", flush=True)
    return run_map(root / f"map-{workers}", quick=True, workers=workers, **kw,
                   say=lambda m: print(f"    {m}", flush=True))


def _time_study(name: str, fn: Any, points: list[Any], k: int, quick: bool) -> tuple[float, float]:
    """The mean wall and CPU seconds of ``fn(point, quick)`` over ``k`` points spread over ``points``."""
    sample = points[::max(1, len(points) // k)][:k]
    wall, cpu = [], []
    for p in sample:
        c0, t0 = time.process_time(), time.perf_counter()
        fn(p, quick)
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - t0)
        print(f"    {name} {p.key()}  wall {wall[-1]:.1f} s, CPU {cpu[-1]:.1f} s", flush=True)
    return sum(wall) / len(wall), sum(cpu) / len(cpu)


def estimate_full(n: int, workers: int, crossings: float, quick: bool = False,
                  slope_evaluations: float = 7.0, referee_s: float = 120.0) -> int:
    """Time ``n`` points spread over the full grid; print the full map's estimated wall time.

    Each point's wall time (``time_s``) and this process's CPU time are both
    printed: on a machine that other jobs load, the CPU time is the better
    estimate of the wall time on an idle one (each point is single-threaded;
    run with ``OMP_NUM_THREADS=1``). ``quick`` times the same points on the
    quick meshes.
    """
    grid = validity.map_points(False)
    sample = grid[::max(1, len(grid) // n)][:n]
    wall, cpu = [], []
    for p in sample:
        c0 = time.process_time()
        r = validity.evaluate(p, quick)
        cpu.append(time.process_time() - c0)
        wall.append(r["time_s"])
        print(f"    {p.key()}  peak error {100 * r['peak_rel_error']:+.3g} %  wall {r['time_s']:.1f} s, "
              f"CPU {cpu[-1]:.1f} s", flush=True)
    curves = len({tuple(getattr(p, a) for a in CURVE_AXES) for p in grid})
    steps = curves * crossings * STEP_CAP["full"]
    slips = validity.subset(grid, validity.SLIP_SUBSET)
    slopes = validity.subset(grid, validity.SLOPE_SUBSET)
    k = max(1, n // 4)
    slip_t = _time_study("slip", evaluate_slip, slips, k, quick)
    slope_t = _time_study("slope", evaluate_slope, slopes, k, quick)
    n_cross = len(validity.slope_curves(grid))
    for i, (what, times) in enumerate((("wall", wall), ("CPU", cpu))):
        mean = sum(times) / len(times)
        grid_s = mean * (len(grid) + steps)
        study_s = (slip_t[i] * len(slips) + slope_t[i] * (len(slopes) + slope_evaluations * n_cross)
                   + referee_s * len(REFEREE_POINTS))
        print(f"full grid: {len(grid)} points, {curves} curves; {what} time of a sample of "
              f"{len(sample)} on {'quick' if quick else 'default'} meshes: mean {mean:.1f} s per "
              f"point; with {crossings:g} crossings per curve x {STEP_CAP['full']} steps = "
              f"{steps:.0f} bisection points: {grid_s / workers / 60:.0f} min on {workers} workers; "
              f"studies: {len(slips)} slip x {slip_t[i]:.1f} s, {len(slopes)} slope points and "
              f"{n_cross} crossings x {slope_evaluations:g} x {slope_t[i]:.1f} s, "
              f"{len(REFEREE_POINTS)} CalculiX x {referee_s:g} s: {study_s / workers / 60:.0f} min; "
              f"total about {(grid_s + study_s) / workers / 60:.0f} min "
              f"(without the control and its convergence study)")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fake", type=float, metavar="SECONDS",
                        help="a fake evaluate that sleeps SECONDS per point (times the engine alone)")
    parser.add_argument("--workers", default="1,2", metavar="N1,N2,...",
                        help="local worker counts to time, the first is the baseline (default: 1,2)")
    parser.add_argument("--estimate-full", type=int, metavar="N",
                        help="time N points spread over the full grid and estimate the full map")
    parser.add_argument("--crossings", type=float, default=1.5,
                        help="with --estimate-full: located crossings per curve (default 1.5)")
    parser.add_argument("--slope-evaluations", type=float, default=7.0,
                        help="with --estimate-full: slope points per small-slope crossing (default 7)")
    parser.add_argument("--referee-s", type=float, default=120.0,
                        help="with --estimate-full: CPU seconds per CalculiX point (default 120)")
    args = parser.parse_args(argv)
    if args.estimate_full is not None:
        if args.estimate_full < 1:
            parser.error(f"--estimate-full {args.estimate_full} must be >= 1")
        return estimate_full(args.estimate_full, int(args.workers.split(",")[-1]), args.crossings,
                             slope_evaluations=args.slope_evaluations, referee_s=args.referee_s)
    counts = [int(w) for w in args.workers.split(",")]
    if args.fake is not None and not (math.isfinite(args.fake) and args.fake >= 0):
        parser.error(f"--fake {args.fake} must be a number of seconds >= 0")
    if not counts or min(counts) < 1:
        parser.error(f"--workers {args.workers} must list counts >= 1")
    n = len(validity.map_points(True))
    what = f"fake evaluate (sleep {args.fake:g} s)" if args.fake is not None else "validity.evaluate"
    print(f"quick validity map: {n} points and the control, {what}")
    docs = {}
    with tempfile.TemporaryDirectory(prefix="bench_map-") as tmp:
        for w in counts:
            docs[w] = one_run(w, args.fake, Path(tmp))
    print(f"\n{'workers':>7} {'startup s':>10} {'sweep s':>9} {'sum of tasks s':>16} "
          f"{'overhead/task s':>16} {'total s':>9} {'exit':>5}")
    for w, doc in docs.items():
        t = doc["timings"]
        print(f"{w:>7} {t['startup_s']:10.2f} {t['sweep_s']:9.2f} {t['evaluate_s']:16.2f} "
              f"{t.get('overhead_per_task_s', math.nan):16.3f} {t['total_s']:9.2f} {exit_status(doc):>5}")
    base = counts[0]
    for w in counts[1:]:
        t0, t1 = docs[base]["timings"], docs[w]["timings"]
        print(f"speed-up {base} -> {w} workers: sweep {t0['sweep_s'] / t1['sweep_s']:.2f}x, "
              f"total {t0['total_s'] / t1['total_s']:.2f}x (ideal {w / base:g}x)")
    ref = [{k: p[k] for k in RESULT_KEYS if k != "time_s"} for p in docs[base]["points"]]
    same = all([{k: p[k] for k in RESULT_KEYS if k != "time_s"} for p in d["points"]] == ref
               for d in docs.values())
    print(f"the runs' numbers agree: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())

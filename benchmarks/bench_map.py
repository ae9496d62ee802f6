"""Time the quick validity map on 1 and on 2 local dask workers, side by side, and the speed-up.

Run ``python benchmarks/bench_map.py`` (the real finite-body ``evaluate`` of
:mod:`reports.validity`; issue 12's budget is 15 minutes for the quick map on
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
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from threepart.reports import validity
from threepart.reports.map import exit_status, run_map
from threepart.reports.validity import RESULT_KEYS


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
                "fem_error_estimate": 1e-4, "P": 1.0, "time_s": time.perf_counter() - t0}


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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fake", type=float, metavar="SECONDS",
                        help="a fake evaluate that sleeps SECONDS per point (times the engine alone)")
    parser.add_argument("--workers", default="1,2", metavar="N1,N2,...",
                        help="local worker counts to time, the first is the baseline (default: 1,2)")
    args = parser.parse_args(argv)
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

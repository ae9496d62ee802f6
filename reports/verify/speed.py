"""The verification report's speed section: each ratio measured in the run, beside its target (issue 33).

The figures come from :func:`reports.benchmark.measure`, taken side by side in the
verification run itself, so that a regression shows where people look. The
machine's load average before and after is shown with them: a ratio is what to
read, the absolute times follow the load.

TARGETS         -- figure -> (label, ">=" or "<=", target)
speed_record    -- the measurement, as stored in ``report.json`` under ``speed``
speed_section   -- the section of the report, or None when the run has no speed record
"""
from __future__ import annotations

from typing import Any, Callable

from .sections import Section, Table, fmt

__all__ = ["TARGETS", "speed_record", "speed_section", "met"]

#: the targets of issue 33, each a ratio or a size measured side by side in one run
TARGETS: dict[str, tuple[str, str, float]] = {
    "batch_over_naive": ("closed-form batch against a per-case fsolve on closedform.formulas",
                         ">=", 300.0),
    "single_over_naive": ("one closed-form solve against that per-case fsolve", ">=", 30.0),
    "evaluations_per_case": ("forward evaluations per case of the batch", "<=", 12.0),
    "grid_s": ("stress on a 200 x 100 grid, s", "<=", 0.2),
    "fatigue_history_speedup": ("fatigue history of the fan-blade flank's cycle, superposed against "
                                "state by state", ">=", 2.5),
}
#: figures shown without a target, for the reader
SHOWN = {"batch_us_per_case": "batch, µs per case", "single_us": "one solve, µs",
         "naive_us_per_case": "naive fsolve on closedform.formulas (the targets' baseline), µs per case",
         "naive_paper_us_per_case": "fsolve on the printed equations transcribed in numpy (no target), µs per case",
         "single_over_naive_paper": "one closed-form solve against that fsolve",
         "batch_over_naive_paper": "closed-form batch against that fsolve",
         "stress_us_per_point": "stress at scattered points, µs per point",
         "grid_us_per_point": "stress on the grid, µs per point",
         "fatigue_ms_per_point_and_state": "fatigue history, ms per point and state"}


def meets(value: float, op: str, target: float) -> bool:
    """Whether ``value`` meets ``target`` under ``op`` (``">="`` or ``"<="``)."""
    return value >= target if op == ">=" else value <= target


def met(name: str, value: float) -> bool:
    """Whether the figure ``name`` meets its target in :data:`TARGETS`."""
    _, op, target = TARGETS[name]
    return meets(value, op, target)


def speed_record(quick: bool, say: Callable[[str], None] | None = None) -> dict[str, Any]:
    """The speed measurement of the run, with each target and whether it is met."""
    from ..benchmark import measure

    rec = measure(quick, say)
    rec["targets"] = {k: {"op": op, "target": t, "met": met(k, rec["figures"][k])}
                      for k, (_, op, t) in TARGETS.items() if k in rec["figures"]}
    return rec


def _sizes(sizes: dict[str, Any] | None) -> str:
    """The measurement's sizes, as a clause: the default run's are the quick ones, ``--full``'s the full."""
    if not sizes:
        return ""
    grid = sizes.get("fatigue") or ("?", "?")
    return (f", at {sizes.get('batch')} batch cases, {sizes.get('single')} single solves of a random draw and "
            f"a {grid[0]} x {grid[1]} fatigue grid")


def speed_section(doc: dict[str, Any]) -> Section | None:
    """The report's section "Speed", or None when ``doc`` holds no speed record."""
    rec = doc.get("speed")
    if not rec:
        return None
    figures = rec["figures"]
    rows = [(label, fmt(figures[k]), f"{op} {target:g}", "met" if met(k, figures[k]) else "MISSED")
            for k, (label, op, target) in TARGETS.items() if k in figures]
    rows += [(label, fmt(figures[k]), "", "") for k, label in SHOWN.items() if k in figures]
    load = rec.get("load", [None, None])
    intro = (f"Measured in this run, each ratio side by side in one process, on {rec.get('cpus')} "
             f"CPUs at a load average of {fmt(load[0])} before and {fmt(load[1])} after "
             "(reports/benchmark.py; benchmarks/bench_speed.py measures the same at the command "
             "line, with the peak memory of the stress on 10^7 points)"
             + _sizes(rec.get("sizes")) + ".",)
    table = Table(("figure", "measured", "target", ""), tuple(rows))
    return Section("Speed", "speed", (intro,), (table,))

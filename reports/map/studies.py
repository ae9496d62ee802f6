"""The map's studies on subsets of its points (issue 23): partial slip, the small-slope load axis, CalculiX.

Each study is a set of dask tasks beside the grid's, each with its own key in
``points.jsonl`` (:func:`reports.map.log.task_key`), so that a resumed map
computes none of the finished ones again:

* ``slip:<point>`` -- :func:`reports.map.validity_slip.evaluate_slip` on the points
  of :data:`reports.map.validity.SLIP_SUBSET`: the stick zone's ``d`` and ``e`` at
  ``Q/fP = 0.4``, the closed form against the finite body's friction model;
* ``slope:<point>`` -- :func:`reports.map.validity_slope.evaluate_slope` on the
  points of :data:`reports.map.validity.SLOPE_SUBSET`: what the small-slope
  kinematics cost there, against the load level ``p0/E*``;
* ``crossing:<curve>`` -- :func:`reports.map.validity_slope.slope_crossing` on each
  curve ``(R2/R1, b/R1, H/b)`` of that subset: the overhang and ``p0/E*`` where
  that cost reaches 1 %;
* ``referee:<point>`` -- :func:`reports.map.referee.referee` on
  :data:`reports.map.referee.REFEREE_POINTS` (full map only): CalculiX against
  the finite-body FEM and the closed form. Without ``ccx`` the task leaves a
  note, not a failure, and is tried again by the next run.

Every grid point also gets its load level ``p0/E*``
(:func:`reports.map.validity_slope.load_level`: closed form only, no FE).

Names
-----
Studies        -- the studies' functions and subsets (the defaults run the real ones)
study_tasks    -- the dask tasks of the studies
point_columns  -- a point's load level, partial-slip and small-slope columns
small_slope    -- the ``small_slope`` section of ``map.json``
referee_section -- the ``referee`` section of ``map.json``
failures       -- the number of failed study tasks
curve_name     -- the name of a curve ``(R2/R1, b/R1, H/b)`` in its task key
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Callable, Sequence

from threepart.calculix import CcxMissing

from . import validity
from .engine import Task
from .log import task_key, task_record
from .referee import REFEREE_POINTS, referee
from .schema import COORDINATES, SLIP_COLUMNS, SLOPE_COLUMNS
from .validity import MapPoint
from .validity_slip import SLIP_RESULT_KEYS, evaluate_slip
from .validity_slope import SLOPE_LEVEL, SLOPE_RESULT_KEYS, evaluate_slope, load_level, slope_crossing

__all__ = ["Studies", "study_tasks", "point_columns", "small_slope", "referee_section", "failures",
           "curve_name", "REFEREE_KEYS", "FIGURES"]

#: the keys of :func:`reports.map.referee.referee`'s dict that the map reads (the rest is kept
#: as it is, opaque, in ``referee.points[].detail``)
REFEREE_KEYS = ("calculix", "fem", "closed_form", "fem_minus_calculix", "closed_form_minus_calculix",
                "closed_form_minus_fem")
#: the figures of each of those, read by name
FIGURES = ("p_left", "p_right", "a", "c")


@dataclass(frozen=True)
class Studies:
    """The studies' functions and the points they run on.

    A subset left ``None`` is the declared subset of the map's own grid
    (:data:`reports.map.validity.SLIP_SUBSET`, :data:`~reports.map.validity.SLOPE_SUBSET`,
    :func:`~reports.map.validity.slope_curves`, and :data:`REFEREE_POINTS` in the
    full map); with a grid of the caller's own (``run_map(points=...)``) it is
    empty. Each function runs on a worker, so it must be picklable.
    """

    slip: Callable[[MapPoint, bool], dict[str, Any]] = evaluate_slip
    slope: Callable[[MapPoint, bool], dict[str, Any]] = evaluate_slope
    crossing: Callable[..., dict[str, Any]] = slope_crossing
    referee: Callable[[MapPoint], dict[str, Any]] = referee
    load_level: Callable[[MapPoint], float] = load_level
    slip_points: Sequence[MapPoint] | None = None
    slope_points: Sequence[MapPoint] | None = None
    slope_curves: Sequence[tuple[float, float, float]] | None = None
    referee_points: Sequence[MapPoint] | None = None

    def subsets(self, grid: list[MapPoint], own: bool, quick: bool) -> Studies:
        """These studies with every ``None`` subset resolved against ``grid`` (``own``: the map's grid)."""
        def pick(given: Any, default: Any) -> Any:
            return list(given) if given is not None else (list(default) if own else [])

        return Studies(self.slip, self.slope, self.crossing, self.referee, self.load_level,
                       pick(self.slip_points, validity.subset(grid, validity.SLIP_SUBSET)),
                       pick(self.slope_points, validity.subset(grid, validity.SLOPE_SUBSET)),
                       pick(self.slope_curves, validity.slope_curves(grid)),
                       pick(self.referee_points, () if quick else REFEREE_POINTS))


def curve_name(curve: tuple[float, float, float]) -> str:
    """``R2R1=1_bR1=0.1_Hb=4``: a curve of the small-slope crossing in its task key."""
    r, b, h = curve
    return f"R2R1={r:.6g}_bR1={b:.6g}_Hb={h:.6g}"


def study_tasks(st: Studies, quick: bool) -> list[Task]:
    """The tasks of the studies, each ``(key, fn, args, line maker)``.

    The long ones (the crossings and the referee points) come first, so that
    they do not finish last alone on a worker.
    """
    rec = functools.partial
    tasks: list[Task] = []
    for c in st.slope_curves or ():
        k = task_key("crossing", curve_name(c))
        tasks.append((k, st.crossing, (*c, quick), rec(task_record, k, "crossing")))
    for p in st.referee_points or ():
        k = task_key("referee", p.key())
        tasks.append((k, st.referee, (p,), rec(task_record, k, "referee", absent=(CcxMissing,))))
    for p in st.slip_points or ():
        k = task_key("slip", p.key())
        tasks.append((k, st.slip, (p, quick), rec(task_record, k, "slip", keys=SLIP_RESULT_KEYS)))
    for p in st.slope_points or ():
        k = task_key("slope", p.key())
        tasks.append((k, st.slope, (p, quick), rec(task_record, k, "slope", keys=tuple(SLOPE_RESULT_KEYS))))
    return tasks


def point_columns(st: Studies, point: MapPoint, records: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """``load_level`` and the :data:`SLIP_COLUMNS` and :data:`SLOPE_COLUMNS` of ``point`` (null where not run)."""
    try:
        level: float | None = float(st.load_level(point))
    except (ValueError, ArithmeticError):   # the closed form has no load here: no level, no crash
        level = None
    out: dict[str, Any] = {"load_level": level}
    for kind, cols in (("slip", SLIP_COLUMNS), ("slope", SLOPE_COLUMNS)):
        r = records.get(task_key(kind, point.key()), {})
        out.update({c: r.get(c) for c in cols[:-1]})
        out[cols[-1]] = r.get("error") or r.get("note")
    return out


def small_slope(st: Studies, records: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """The ``small_slope`` section: per curve, where the small-slope cost of the peak reaches 1 %."""
    curves = []
    for c in st.slope_curves or ():
        r = records.get(task_key("crossing", curve_name(c)), {})
        res = r.get("result") or {}
        x, level = res.get("a_minus_b_over_R1"), res.get("load_level")
        curves.append({"R2_over_R1": c[0], "b_over_R1": c[1], "H_over_b": c[2],
                       "a_minus_b_over_R1": x, "load_level": level,
                       "within_grid": None if r.get("error") or not r else x is not None,
                       "ends": res.get("ends", []), "evaluations": res.get("evaluations"),
                       "time_s": res.get("time_s"), "error": r.get("error") if r else "not run"})
    return {"level": SLOPE_LEVEL, "curves": curves, "plot": None}


def _figures(d: Any) -> dict[str, Any] | None:
    return {q: d.get(q) for q in FIGURES} if isinstance(d, dict) else None


def referee_section(st: Studies, records: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """The ``referee`` section: per CalculiX point its coordinates, peaks and signed differences."""
    points = []
    for p in st.referee_points or ():
        r = records.get(task_key("referee", p.key()), {})
        res: dict[str, Any] = r["result"] if isinstance(r.get("result"), dict) else {}
        points.append({"key": p.key(), **{k: float(p.as_dict()[k]) for k in COORDINATES},
                       **{k: _figures(res.get(k)) for k in REFEREE_KEYS},
                       "note": r.get("note"), "error": r.get("error") if r else "not run",
                       "detail": res or None})
    missing = any(pt["note"] for pt in points)
    return {"points": points,
            "note": "ccx (CalculiX) is not on the PATH: the referee points were not run" if missing
            else None}


def failures(st: Studies, records: dict[str, dict[str, Any]]) -> int:
    """The study tasks that failed (a missing ``ccx`` is a note, not a failure)."""
    return sum(records.get(t[0], {}).get("error") is not None for t in study_tasks(st, False))

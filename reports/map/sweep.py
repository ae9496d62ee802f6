"""``threepart map``: the validity map of issue 12, swept point by point on dask.distributed.

The physics is :mod:`reports.map.validity` (the grid, one point's errors, the
control); this module runs it. Every point is an independent task on a
``dask.distributed`` cluster: a :class:`~dask.distributed.LocalCluster` of
single-threaded worker processes by default, or an existing cluster through
its scheduler's address. Results are appended to ``out/points.jsonl`` as they
arrive (one JSON line per task, flushed and fsynced), so an interrupted sweep
resumes where it stopped; a point whose ``evaluate`` raised is recorded with
its error message and retried by the next run. At the end the map is written
as ``map.json`` (valid against ``reports/map/map.schema.json``), ``map.csv`` (the
same points, one row each), ``boundaries.csv`` and ``plots/*.png``, one contour
map of the signed peak-pressure error per ``R2/R1``, ``H/b`` and ``s/s_lift-off``.

Alongside the grid, the boundary (issue 23) is located: for each curve of
the grid (the group axes and ``b/R1``) and each level of
:data:`reports.map.boundary.LEVELS` bracketed by two adjacent grid points,
a bisection in ``log((a - b)/R1)`` starts once the curve's grid points are
in (:class:`_Boundary`), each step one more point in ``points.jsonl`` with
its own key, submitted as soon as the step before it is logged, so that no
curve waits for another and a resumed map reuses the finished steps.

The output directory
--------------------
``out`` is written in place (a resumable sweep cannot be one atomic rename), as
a :class:`threepart.output.ResumableDir` with the command ``"map"``: its
signed marker lists every file with its checksum, updated after each file and
each line of the log, so that the directory is threepart's own at every
moment, even after a kill.

* missing or empty: a new map is started;
* an unfinished map (marker state ``"writing"``: interrupted, or with failed
  points) of the same mode: resumed, with or without ``force``;
* a finished map (state ``"complete"``), or an unfinished one of the other
  mode: refused (a map is expensive), or with ``force`` its files (only those
  its marker lists, checked unchanged) are removed and a new map is started;
* anything else (a file threepart did not write or one edited since, another
  command's output, a map still being written by a live process): refused
  with :class:`~threepart.output.OutputExistsError` before any work.

With ``--scheduler``, the scheduler is reached before ``out`` is touched.

Modules (:mod:`reports.map`)
-------
schema   -- the fields of a point (the design-space axes), the schema, ``map.csv``
log      -- the sweep's log ``points.jsonl``: its records and the resume state
engine   -- dask.distributed: the cluster and the sweep
plots    -- the designer's reading and the contour plots
boundary -- the boundary: where the signed error crosses a level, by bisection
studies  -- the studies on subsets: partial slip, the small-slope load axis, CalculiX

Names
-----
run_map           -- run (or resume) the sweep and write the map; returns the ``map.json`` document
main              -- ``threepart map``: :func:`run_map` and the exit status
exit_status       -- 0 when every point succeeded and the control is within :data:`CONTROL_LIMIT`
check_arguments   -- the argument check of :func:`run_map`, before any work
below_level       -- per ``b/R1``, the largest ``(a-b)/R1`` up to which the error stays below a level
designer_sentence -- the sentence that says what one contour map means for a designer
validate          -- validate a document against ``map.schema.json``
load_schema       -- the JSON schema of ``map.json``
COLUMNS           -- the fields of every point, in CSV order
COORDINATES       -- the coordinates of a point (:data:`reports.map.schema.GROUP_AXES` and ``PLOT_AXES``)
CONTROL_LIMIT     -- the control's largest admissible peak-pressure error (issue 12: 1e-3)
"""
from __future__ import annotations

import os
import time
import uuid
from contextlib import ExitStack
from pathlib import Path
from typing import Any, Callable, Sequence

import dask

from threepart.output import ResumableDir, json_safe, strict_json
from threepart.tolerances import tolerance

from . import validity
from .engine import Task, open_engine, sweep
from .boundary import CURVE_AXES, LEVELS, REL_WIDTH, STEP_CAP, X, Bisection, Sample, start
from .log import CONTROL_KEY, POINTS_FILE, done, read_log
from .plots import below_level, contour, designer_sentence, slope_plot, stick_sentence, stick_zone
from .studies import Studies, failures, point_columns, referee_section, small_slope, study_tasks
from .schema import (COLUMNS, COORDINATES, GROUP_AXES, SCHEMA_FILE, SCHEMA_VERSION,
                         boundaries_csv, csv_text, finite, groups, load_schema, plot_name, validate)
from .validity import MapPoint
from threepart.errors import InputError

__all__ = ["run_map", "main", "exit_status", "check_arguments", "below_level", "designer_sentence",
           "validate", "load_schema", "SCHEMA_FILE", "SCHEMA_VERSION", "COLUMNS", "COORDINATES",
           "CONTROL_LIMIT", "LEVELS", "POINTS_FILE", "DEFAULT_WORKERS", "MAX_WORKERS", "Studies"]

#: the command recorded in the marker of a map directory
COMMAND = "map"
#: issue 12: the control (paper's profile, large bodies) must match the closed form to 1e-3 in
#: peak pressure, the map's zero line
CONTROL_LIMIT = tolerance("map", "control").limit
#: local worker processes when none are asked for
DEFAULT_WORKERS = 2
#: the most worker processes of a local cluster: the CPUs this process may run on. Each worker
#: is a CPU-bound FE solve of its own (up to about 1 GB); more only share the cores and multiply
#: the memory (`--workers 50` started 52 processes on 2 cores)
MAX_WORKERS = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
#: seconds to wait for an existing scheduler to answer
CONNECT_TIMEOUT = 20


Evaluate = Callable[[Any, bool], dict[str, Any]]
Say = Callable[[str], None]


def check_arguments(workers: int | None, scheduler: str | None) -> None:
    """Check the engine's arguments before any work (one-line ``ValueError`` naming the limit)."""
    if workers is not None:
        if isinstance(workers, bool) or not isinstance(workers, int):
            raise InputError(f"`--workers` = {workers!r} must be an integer >= 1")
        if not 1 <= workers <= MAX_WORKERS:
            raise InputError(f"`--workers` = {workers} must lie in [1, {MAX_WORKERS}], the CPUs of "
                             "this machine (each worker is a process that keeps a core busy)")
        if scheduler is not None:
            raise InputError("give `--workers` (a local cluster) or `--scheduler` (an existing "
                             "cluster, which has its own workers), not both")
    if scheduler is not None and (not isinstance(scheduler, str) or not scheduler.strip()):
        raise InputError(f"`--scheduler` = {scheduler!r} must be a scheduler address, "
                         "e.g. tcp://host:8786")


def _plan(rd: ResumableDir, plots: Sequence[str]) -> None:
    """Drop the plots of an earlier grid (ours and unchanged only) and make ``plots/``."""
    for f in [f for f in rd.marker["files"] if f.startswith("plots/") and f not in plots]:
        rd.remove(f)
    rd.mkdir("plots")


#: a plot of the map: its file, the function that draws it (``draw(..., path=path)``) and its
#: arguments but the path
Plot = tuple[str, Callable[..., None], dict[str, Any]]


def _plots(doc: dict[str, Any]) -> list[Plot]:
    """The map's plots, each listed in ``doc``: one contour map per group of points, a stick-zone
    plot per group with partial slip, and the small-slope plot.

    A group is one combination of values of :data:`reports.map.schema.GROUP_AXES`.
    """
    points, out = doc["points"], list[Plot]()
    for values in groups(points):
        where = dict(zip(GROUP_AXES, values))
        rel = plot_name(values)
        group = [p for p in points if all(p[a] == v for a, v in where.items())]
        lines = [b for b in doc["boundaries"] if all(b[a] == v for a, v in where.items())]
        sentence = designer_sentence(group, **where, boundaries=lines)
        out.append((rel, contour, {"points": group, **where, "sentence": sentence, "boundaries": lines}))
        doc["plots"].append({"file": rel, **where, "sentence": sentence,
                             "below_1_percent": [{k: row[k] for k in ("b_over_R1", "limit", "stop")}
                                                 for row in below_level(group)]})
        slipped = [p for p in group if p["d_rel_error"] is not None]
        if slipped:
            rel = plot_name(values, "stick_zone")
            sentence = stick_sentence(slipped)
            out.append((rel, stick_zone, {"points": slipped, **where, "sentence": sentence}))
            doc["stick_zone_plots"].append({"file": rel, **where, "sentence": sentence})
    sloped = [p for p in points if p["slope_peak_rel_error"] is not None]
    if sloped:
        rel = "plots/small_slope.png"
        out.append((rel, slope_plot, {"points": sloped, "section": doc["small_slope"]}))
        doc["small_slope"]["plot"] = rel
    return out


def _png(draw: Callable[..., None], kw: dict[str, Any]) -> bytes:
    """One plot drawn into a temporary file: its PNG bytes (run on a worker of the map's engine)."""
    import tempfile

    with tempfile.TemporaryDirectory(prefix="threepart-map-plot-") as tmp:
        path = Path(tmp) / "plot.png"
        draw(**kw, path=path)
        return path.read_bytes()


def _drawn(doc: dict[str, Any], engine: _Engine) -> list[tuple[Plot, bytes]]:
    """The map's plots (:func:`_plots`) with their PNG bytes (:func:`_render`); the seconds start
    the timings' ``write_s``."""
    t3 = time.perf_counter()
    plots = _plots(doc)
    drawn = list(zip(plots, _render(plots, engine.client)))
    engine.timings["write_s"] = time.perf_counter() - t3
    return drawn


def _render(plots: Sequence[Plot], client: Any) -> list[bytes]:
    """The plots' PNG bytes: drawn side by side on the engine's workers while it is open (each plot
    takes matplotlib about a second), else here, one after another (a resumed map with nothing left
    to compute starts no cluster for its plots)."""
    if client is None:
        return [_png(draw, kw) for _, draw, kw in plots]
    return client.gather([client.submit(_png, draw, kw, pure=False,
                                        key=f"threepart-map-plot-{i}-{uuid.uuid4().hex[:8]}")
                          for i, (_, draw, kw) in enumerate(plots)])


def _step_point(b: Bisection, x: float) -> MapPoint:
    """The map point of a bisection step: the curve's coordinates at the overhang ``x``."""
    return MapPoint(**b.curve, **{X: x})


def _task_time(rec: dict[str, Any]) -> float:
    """The seconds a task's line records: a point's ``time_s``, a study's ``*time_s``."""
    res: dict[str, Any] = rec["result"] if isinstance(rec.get("result"), dict) else rec
    times = [v for k, v in res.items() if k.startswith("time") or k.endswith("time_s")]
    return sum(v for v in times if finite(v))


class _Engine:
    """The dask client of a run, opened when the first batch computes (unless given a scheduler),
    and the run's timings and engine record."""

    def __init__(self, stack: ExitStack, workers: int | None, say: Say) -> None:
        self.stack, self.workers, self.say = stack, workers, say
        self.info: dict[str, Any] = {"kind": "dask.distributed", "scheduler": None, "workers": 0,
                                     "dask_version": dask.__version__}
        self.timings: dict[str, float] = {"startup_s": 0.0, "sweep_s": 0.0}
        self.client: Any = None
        self.said = False

    def connect(self, scheduler: str | None) -> None:
        """Reach ``scheduler``, or start a local cluster of :attr:`workers` (``None``)."""
        t1 = time.perf_counter()
        n = 0 if scheduler is not None else self.workers or DEFAULT_WORKERS
        self.client, self.info = self.stack.enter_context(open_engine(scheduler, n, CONNECT_TIMEOUT))
        self.timings["startup_s"] = time.perf_counter() - t1

    def ready(self) -> Any:
        """The client, opened and announced on first use."""
        if self.client is None:
            self.connect(None)
        if not self.said:
            self.said = True
            self.say(f"engine: {self.info['kind']} at {self.info['scheduler']}, {self.info['workers']} "
                     f"workers (ready in {self.timings['startup_s']:.1f} s)")
        return self.client


class _Batch:
    """Runs batches of tasks on the engine, logging each record and keeping it in ``records``."""

    def __init__(self, engine: _Engine, records: dict[str, Any], log: Callable[[dict[str, Any]], None],
                 mode: str) -> None:
        self.engine, self.records, self.log, self.mode = engine, records, log, mode

    def run(self, batch: list[Task], done0: int, of: int,
            follow: Callable[[dict[str, Any]], list[Task]]) -> None:
        """Run ``batch`` (and the tasks ``follow`` makes of each record), keeping each record as it arrives."""
        client = self.engine.ready()
        t2 = time.perf_counter()

        def arrived(rec: dict[str, Any]) -> list[Task]:
            self.records[rec["key"]] = rec     # before the follow-ups, which read it
            return follow(rec)

        sweep(client, batch, self.log, self.mode, done0, of, self.engine.say, arrived)
        self.engine.timings["sweep_s"] += time.perf_counter() - t2


def _pending(st: Any, grid: Sequence[MapPoint], records: dict[str, Any], quick: bool,
             evaluate: Evaluate, control: Callable[[bool], dict[str, Any]]) -> tuple[list[Task], int]:
    """The tasks not yet done (the control's, the studies', the points') and the number of all.

    Longest first, so that none of them finishes last alone on a worker: the control (the
    finite body's convergence study, about four points' work) and the studies (the
    crossings first, :func:`~reports.map.studies.study_tasks`) before the grid's points.
    """
    studied = study_tasks(st, quick)
    tasks: list[Task] = [] if done(records.get(CONTROL_KEY)) else [
        (CONTROL_KEY, control, (quick,), None)]
    tasks += [*(t for t in studied if not done(records.get(t[0]))),
              *((p.key(), evaluate, (p, quick), p) for p in grid if not done(records.get(p.key())))]
    return tasks, len(grid) + 1 + len(studied)


def _grid(points: Sequence[MapPoint] | None, quick: bool) -> list[MapPoint]:
    """The map's points: ``points``, or the grid of the mode; ``ValueError`` on a repeated key."""
    grid = list(validity.map_points(quick) if points is None else points)
    keys = [p.key() for p in grid]
    if len(set(keys)) != len(keys) or CONTROL_KEY in keys:
        raise InputError("`points` must have distinct keys, none of them 'control'")
    return grid


def _studied(st: Any, n: int) -> str:
    """The study tasks of a run, counted for its first line."""
    return (f"{n} study tasks ({len(st.slip_points or ())} partial slip, {len(st.slope_points or ())} "
            f"small slope, {len(st.slope_curves or ())} crossings, {len(st.referee_points or ())} CalculiX)")


def _curve(p: MapPoint) -> tuple[float, ...]:
    """The curve of a grid point (:data:`reports.map.boundary.CURVE_AXES`), as :func:`~reports.map.boundary.curves` keys it."""
    return tuple(float(getattr(p, a)) for a in CURVE_AXES)


class _Boundary:
    """The bisection of every bracketed crossing, run alongside the grid as its curves finish.

    A curve's bisections start (:func:`reports.map.boundary.start`) once its last
    grid point is logged, and each one's next step is submitted as soon as its
    step before is logged: no curve waits for another, nor for the rest of the
    grid. A step already logged (a resumed map) is taken at once; two levels of
    one curve that want the same point share its one task. ``tasks`` collects
    the steps submitted; ``keys`` holds every step's point, logged before or now.
    """

    def __init__(self, grid: Sequence[MapPoint], records: dict[str, Any], cap: int,
                 evaluate: Evaluate, quick: bool, say: Say) -> None:
        self.grid, self.records, self.cap, self.evaluate, self.quick, self.say = (
            grid, records, cap, evaluate, quick, say)
        self.curve_of = {p.key(): _curve(p) for p in grid}
        self.left: dict[tuple[float, ...], set[str]] = {}
        for k, c in self.curve_of.items():
            self.left.setdefault(c, set()).add(k)
        self.started: dict[tuple[float, ...], list[Bisection]] = {}
        self.waiting: dict[str, list[tuple[Bisection, float]]] = {}
        self.keys: set[str] = set()
        self.tasks: list[Task] = []

    def ready(self, pending: set[str]) -> list[Task]:
        """The first steps of every curve none of whose grid points is among the ``pending`` keys
        (each has its record: a resumed map's log)."""
        out: list[Task] = []
        for k in self.curve_of:
            if k not in pending:
                out += self._grid_point(k)
        return out

    def run(self, batch: _Batch, tasks: list[Task], total: int) -> list[Task]:
        """Run the ``tasks`` of the map (``total`` in all) and the bisection alongside them: the
        steps it submitted."""
        first = self.ready({t[0] for t in tasks})
        if tasks or first:
            batch.run([*tasks, *first], total - len(tasks), total + len(first), self.arrived)
        return self.tasks

    def arrived(self, rec: dict[str, Any]) -> list[Task]:
        """The tasks a logged record makes possible: the next steps of the bisections waiting for it,
        or, for a curve's last grid point, that curve's first steps."""
        out: list[Task] = []
        for b, x in self.waiting.pop(rec["key"], []):
            self._take(b, x, rec)
            out += self._ask(b)
        return out + self._grid_point(rec["key"])

    def bisections(self) -> list[Bisection]:
        """Every bisection, in the order of :func:`~reports.map.boundary.start` on the whole grid."""
        return [b for c in self.left for b in self.started.get(c, [])]   # the grid's curve order

    def _grid_point(self, key: str) -> list[Task]:
        """The first steps of ``key``'s curve if ``key`` was the last of its grid points to arrive."""
        c = self.curve_of.get(key)
        if c is None or key not in self.left[c]:
            return []
        self.left[c].discard(key)
        return [] if self.left[c] else self._start(c)

    def _start(self, c: tuple[float, ...]) -> list[Task]:
        points = [{k: self.records[p.key()].get(k) for k in COLUMNS} for p in self.grid if _curve(p) == c]
        self.started[c] = found = start(points)
        if found:
            self.say(f"boundary: {len(found)} crossing{'s' * (len(found) > 1)} at "
                     + ", ".join(f"{a} = {v:g}" for a, v in zip(CURVE_AXES, c)))
        return [t for b in found for t in self._ask(b)]

    def _ask(self, b: Bisection) -> list[Task]:
        """``b``'s next step: a new task, or none (finished, shared with a step in flight, or logged)."""
        while (x := b.next_x(self.cap)) is not None:
            pt = _step_point(b, x)
            k = pt.key()
            self.keys.add(k)
            if k in self.waiting:
                self.waiting[k].append((b, x))
                return []
            if not done(self.records.get(k)):
                self.waiting[k] = [(b, x)]
                task: Task = (k, self.evaluate, (pt, self.quick), pt)
                self.tasks.append(task)
                return [task]
            self._take(b, x, self.records[k])
        return []

    @staticmethod
    def _take(b: Bisection, x: float, rec: dict[str, Any]) -> None:
        if rec.get("error") is not None or not finite(rec.get("peak_rel_error")):
            b.fail(rec.get("error") or "no finite peak error")
        else:
            b.take(Sample(x, rec["peak_rel_error"], rec.get("fem_error_estimate") or 0.0, rec["key"]))


def _document(mode: str, engine: _Engine, st: Any, grid: Sequence[MapPoint], records: dict[str, Any],
              tasks: list[Task], bisections: list[Bisection],
              steps_done: int) -> tuple[dict[str, Any], list[dict[str, Any]], list[dict[str, Any]]]:
    """The ``map.json`` document (its run time still 0), its point rows and its boundaries."""
    timings = engine.timings
    grid_keys = {p.key() for p in grid}
    computed = [records[t[0]] for t in tasks if t[0] in grid_keys]
    ran = [records[t[0]].get("control", {}) if t[0] == CONTROL_KEY else records[t[0]] for t in tasks]
    task_s = sum(_task_time(r) for r in ran)
    timings["evaluate_s"] = task_s
    if tasks and timings["sweep_s"] > 0 and engine.info["workers"]:
        timings["overhead_per_task_s"] = max(
            0.0, (timings["sweep_s"] * engine.info["workers"] - task_s) / len(tasks))
    ctl = records[CONTROL_KEY]
    rows = ({**records[p.key()], **point_columns(st, p, records)} for p in grid)   # once a point
    mapped = [{k: row.get(k) for k in COLUMNS} for row in rows]
    cap = STEP_CAP[mode]
    boundaries = [b.result(cap) for b in bisections]
    failed = (sum(p["error"] is not None for p in mapped) + (ctl["error"] is not None)
              + sum(b["status"] == "failed" for b in boundaries) + failures(st, records))
    doc: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION, "tool": "threepart map", "mode": mode, "engine": engine.info,
        "control_rel_error": ctl["control_rel_error"], "control_limit": CONTROL_LIMIT,
        "control": {**ctl["control"], "error": ctl["error"]},
        "points": mapped, "boundaries": boundaries,
        "bisection": {"levels": list(LEVELS), "rel_width": REL_WIDTH, "step_cap": cap,
                      "steps": steps_done},
        "small_slope": small_slope(st, records), "referee": referee_section(st, records),
        "timings": timings, "plots": [], "stick_zone_plots": [],
        "summary": {"points": len(mapped), "failed": failed, "computed": len(computed),
                    "resumed": len(mapped) - len(computed), "run_time_s": 0.0},
    }
    return doc, mapped, boundaries


def _write(rd: ResumableDir, doc: dict[str, Any], mapped: list[dict[str, Any]],
           boundaries: list[dict[str, Any]], plots: Sequence[tuple[Plot, bytes]],
           timings: dict[str, float], say: Say) -> None:
    """The drawn plots, ``map.csv`` and ``boundaries.csv`` into the map directory (``map.json`` follows)."""
    t3 = time.perf_counter()
    _plan(rd, [*(plot_name(g, kind) for g in groups(mapped) for kind in ("peak_error", "stick_zone")),
               "plots/small_slope.png"])
    for (rel, _, kw), png in plots:
        rd.write(rel, png)
        if "sentence" in kw:
            say(f"  {rel}: {kw['sentence']}")
    rd.write("map.csv", csv_text(mapped))
    rd.write("boundaries.csv", boundaries_csv(boundaries))
    timings["write_s"] = timings.get("write_s", 0.0) + time.perf_counter() - t3


def exit_status(doc: dict[str, Any]) -> int:
    """0 when every point succeeded and the control is within :data:`CONTROL_LIMIT`, else 1."""
    control = doc["control_rel_error"]
    ok = doc["summary"]["failed"] == 0 and control is not None and control <= CONTROL_LIMIT
    return 0 if ok else 1


def run_map(out: str | Path, *, quick: bool = False, scheduler: str | None = None,
            workers: int | None = None, force: bool = False, evaluate: Evaluate = validity.evaluate,
            points: Sequence[MapPoint] | None = None,
            control: Callable[[bool], dict[str, Any]] = validity.control,
            studies: Studies | None = None, say: Say = print) -> dict[str, Any]:
    """Run (or resume) the validity map on dask.distributed and write it to ``out``.

    Parameters
    ----------
    out
        The map directory: missing, empty, an unfinished map to resume, or
        with ``force`` a finished map to replace (see the module docstring).
    quick
        The quick grid and meshes (``validity.map_points(True)``).
    scheduler
        Address of a running dask scheduler (e.g. ``tcp://host:8786``); by
        default a local cluster is started for the run and closed after it.
    workers
        Worker processes of the local cluster (default :data:`DEFAULT_WORKERS`),
        each with one thread.
    force
        Replace a finished map (or an unfinished one of the other mode) that
        threepart wrote in ``out``; nothing else is ever replaced.
    evaluate, points, control
        The physics: ``evaluate(point, quick)`` returns :data:`RESULT_KEYS`,
        ``points`` the grid (default ``validity.map_points(quick)``), and
        ``control(quick)`` the control with ``control_rel_error``. Each runs
        on a worker, so it must be picklable (a module-level function).
    studies
        The studies on subsets of the grid (:class:`reports.map.studies.Studies`:
        partial slip, small slope, its crossings, CalculiX) and the load level
        of every point. Default: the real ones on the declared subsets of the
        map's own grid; with ``points`` given, only the subsets ``studies`` names.
    say
        Where the progress lines go.

    Returns
    -------
    dict
        The ``map.json`` document (see ``reports/map/map.schema.json``).

    Raises
    ------
    threepart.output.OutputExistsError
        If ``out`` may not be written; checked before any work.
    ValueError
        If an argument is out of range (:func:`check_arguments`).
    OSError
        If ``out`` cannot be written or the scheduler cannot be reached.
    """
    check_arguments(workers, scheduler)
    t0 = time.perf_counter()
    mode = "quick" if quick else "full"
    out = Path(os.path.abspath(out))
    ResumableDir.check(out, command=COMMAND, mode=mode, force=force)   # before any work
    grid = _grid(points, quick)
    with ExitStack() as stack:
        engine = _Engine(stack, workers, say)
        if scheduler is not None:   # reached before `out` is touched: an unreachable one leaves nothing
            engine.connect(scheduler)
        rd = ResumableDir.open(out, command=COMMAND, mode=mode, force=force)
        stack.callback(rd.close)
        records = read_log(rd.log_lines(POINTS_FILE), mode)
        st = (studies or Studies()).subsets(grid, points is None, quick)
        tasks, total = _pending(st, grid, records, quick, evaluate, control)
        say(f"threepart map --{mode}: {len(grid)} points, the control and {_studied(st, total - len(grid) - 1)}"
            f" -> {out} ({rd.action}; {total - len(tasks)} of {total} already done)")
        batch = _Batch(engine, records, lambda rec: rd.append(POINTS_FILE, strict_json(rec)), mode)
        # the boundary: each curve's crossings bisected as soon as its grid points are in
        boundary = _Boundary(grid, records, STEP_CAP[mode], evaluate, quick, say)
        tasks += boundary.run(batch, tasks, total)
        doc, mapped, boundaries = _document(mode, engine, st, grid, records, tasks,
                                            boundary.bisections(), len(boundary.keys))
        drawn = _drawn(doc, engine)   # before the engine closes: on its workers
    _write(rd, doc, mapped, boundaries, drawn, engine.timings, say)
    doc["timings"]["total_s"] = doc["summary"]["run_time_s"] = time.perf_counter() - t0
    validate(doc := json_safe(doc))
    rd.write("map.json", strict_json(doc, indent=1) + "\n")
    rd.seal(finished=doc["summary"]["failed"] == 0)
    return doc



def main(out: str | Path = "map", quick: bool = False, scheduler: str | None = None,
         workers: int | None = None, force: bool = False, quiet: bool = False) -> int:
    """Run ``threepart map`` and return its exit status (see :func:`exit_status`).

    Parameters
    ----------
    out, quick, scheduler, workers, force
        As for :func:`run_map`.
    quiet
        Print no progress.

    Returns
    -------
    int
        0 when every point succeeded and the control is within
        :data:`CONTROL_LIMIT`, 1 otherwise.
    """
    t0 = time.perf_counter()

    def say(msg: str) -> None:
        if not quiet:
            print(f"{time.perf_counter() - t0:7.1f}s  {msg}", flush=True)

    doc = run_map(out, quick=quick, scheduler=scheduler, workers=workers, force=force, say=say)
    s = doc["summary"]
    status = exit_status(doc)
    control = doc["control_rel_error"]
    say(f"{'DONE' if status == 0 else 'FAILED'}: {s['points'] - s['failed']}/{s['points']} points "
        f"({s['computed']} computed now), {len(doc['boundaries'])} boundaries "
        f"({doc['bisection']['steps']} bisection steps), control error "
        f"{'n/a' if control is None else f'{control:.2e}'} (limit {CONTROL_LIMIT:g}), "
        f"{s['run_time_s']:.1f} s -> {Path(out) / 'map.json'}")
    for p in doc["points"]:
        if p["error"] is not None:
            say(f"  failed: {p['key']}: {p['error']}")
    for b in doc["boundaries"]:
        if b["status"] == "failed":
            say(f"  failed: boundary {b['level']:+g} at b/R1 = {b['b_over_R1']:g}: {b['error']}")
    if doc["control"].get("error"):
        say(f"  failed: control: {doc['control']['error']}")
    return status

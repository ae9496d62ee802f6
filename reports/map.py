"""``threepart map``: the validity map of issue 12, swept point by point on dask.distributed.

The physics is :mod:`reports.validity` (the grid, one point's errors, the
control); this module runs it. Every point is an independent task on a
``dask.distributed`` cluster: a :class:`~dask.distributed.LocalCluster` of
single-threaded worker processes by default, or an existing cluster through
its scheduler's address. Results are appended to ``out/points.jsonl`` as they
arrive (one JSON line per task, flushed and fsynced), so an interrupted sweep
resumes where it stopped; a point whose ``evaluate`` raised is recorded with
its error message and retried by the next run. At the end the map is written
as ``map.json`` (valid against ``reports/map.schema.json``), ``map.csv`` (the
same points, one row each) and ``plots/*.png``, one contour map of the
peak-pressure error per ``R2/R1`` and ``H/b``.

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

Names
-----
run_map           -- run (or resume) the sweep and write the map; returns the ``map.json`` document
main              -- ``threepart map``: :func:`run_map` and the exit status
exit_status       -- 0 when every point succeeded and the control is within :data:`CONTROL_LIMIT`
check_arguments   -- the argument check of :func:`run_map`, before any work
below_level       -- per ``b/R1``, the largest ``(a-b)/R1`` up to which the error stays below a level
designer_sentence -- the sentence that says what one contour map means for a designer
validate          -- validate a document against ``map.schema.json``
COLUMNS           -- the fields of every point, in CSV order
CONTROL_LIMIT     -- the control's largest admissible peak-pressure error (issue 12: 1e-3)
"""
from __future__ import annotations

import csv
import gc
import io
import json
import math
import os
import textwrap
import time
import uuid
from asyncio import CancelledError
from contextlib import ExitStack, contextmanager, nullcontext
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

import dask
from dask.distributed import Client, LocalCluster, as_completed

from threepart.output import ResumableDir, json_safe, strict_json, validate_json
from threepart.tolerances import tolerance

from . import validity
from .validity import RESULT_KEYS, MapPoint

__all__ = ["run_map", "main", "exit_status", "check_arguments", "below_level", "designer_sentence",
           "validate", "load_schema", "SCHEMA_FILE", "SCHEMA_VERSION", "COLUMNS", "COORDINATES",
           "CONTROL_LIMIT", "LEVELS", "POINTS_FILE", "DEFAULT_WORKERS"]

SCHEMA_FILE = Path(__file__).with_name("map.schema.json")
SCHEMA_VERSION = "1.0"
#: the command recorded in the marker of a map directory
COMMAND = "map"
#: the sweep's log: one JSON line per finished task, the resume state
POINTS_FILE = "points.jsonl"
#: the key of the control's line in :data:`POINTS_FILE`
CONTROL_KEY = "control"
#: issue 12: the control (paper's profile, large bodies) must match the closed form to 1e-3 in
#: peak pressure, the map's zero line
CONTROL_LIMIT = tolerance("map", "control").limit
#: the error levels drawn as contour lines (1 %, 5 %, 10 %); the first is the designer's limit
LEVELS = (0.01, 0.05, 0.10)
#: the filled bands of the contour maps (fractions of the peak pressure)
BANDS = (0.0, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5)
#: local worker processes when none are asked for
DEFAULT_WORKERS = 2
#: seconds to wait for an existing scheduler to answer
CONNECT_TIMEOUT = 20
#: the coordinates of a point (:class:`reports.validity.MapPoint`)
COORDINATES = ("R2_over_R1", "H_over_b", "b_over_R1", "a_minus_b_over_R1")
#: the fields of every point in ``map.json`` and the columns of ``map.csv``, in order
COLUMNS = ("key", *COORDINATES, *RESULT_KEYS, "error")

Evaluate = Callable[[Any, bool], dict[str, Any]]
Say = Callable[[str], None]


# ---------------------------------------------------------------------------------------
# input and the output directory
# ---------------------------------------------------------------------------------------
def check_arguments(workers: int | None, scheduler: str | None) -> None:
    """Check the engine's arguments before any work (one-line ``ValueError`` naming the limit)."""
    if workers is not None:
        if isinstance(workers, bool) or not isinstance(workers, int):
            raise ValueError(f"`--workers` = {workers!r} must be an integer >= 1")
        if workers < 1:
            raise ValueError(f"`--workers` = {workers} must be >= 1")
        if scheduler is not None:
            raise ValueError("give `--workers` (a local cluster) or `--scheduler` (an existing "
                             "cluster, which has its own workers), not both")
    if scheduler is not None and (not isinstance(scheduler, str) or not scheduler.strip()):
        raise ValueError(f"`--scheduler` = {scheduler!r} must be a scheduler address, "
                         "e.g. tcp://host:8786")


# ---------------------------------------------------------------------------------------
# the log of finished tasks
# ---------------------------------------------------------------------------------------
def _read_log(data: bytes, mode: str) -> dict[str, dict[str, Any]]:
    """The last line of every key of this mode in the whole lines ``data`` of ``points.jsonl``."""
    records: dict[str, dict[str, Any]] = {}
    for line in data.decode("utf-8").splitlines():
        try:
            rec = json.loads(line)
        except ValueError:
            continue
        if isinstance(rec, dict) and rec.get("mode") == mode and isinstance(rec.get("key"), str):
            records[rec["key"]] = rec
    return records


def _one_line(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {' '.join(str(exc).split())}".rstrip(": ")


def _point_record(point: Any, result: Any, error: str | None, mode: str) -> dict[str, Any]:
    """One line of the log (and one point of the map): coordinates, :data:`RESULT_KEYS`, error."""
    rec: dict[str, Any] = {"key": point.key(), **{k: float(point.as_dict()[k]) for k in COORDINATES}}
    rec.update({k: None for k in RESULT_KEYS})
    if error is None:
        if not isinstance(result, dict):
            error = f"evaluate returned {type(result).__name__}, not a dict"
        else:
            missing = [k for k in RESULT_KEYS if k not in result]
            if missing:
                error = f"evaluate returned no {missing[0]!r}"
            else:
                try:
                    rec.update({k: float(result[k]) for k in RESULT_KEYS})
                except (TypeError, ValueError):
                    error = "evaluate returned a value that is not a number"
                    rec.update({k: None for k in RESULT_KEYS})
    return json_safe({**rec, "error": error, "mode": mode})


def _control_record(result: Any, error: str | None, mode: str) -> dict[str, Any]:
    value = None
    if error is None:
        try:
            value = float(result["control_rel_error"])
        except (TypeError, KeyError, ValueError):
            error = "control returned no number `control_rel_error`"
    control = {k: v for k, v in result.items() if k != "control_rel_error"} if error is None else {}
    return json_safe({"key": CONTROL_KEY, "control_rel_error": value, "control": control,
                      "error": error, "mode": mode})


# ---------------------------------------------------------------------------------------
# the engine
# ---------------------------------------------------------------------------------------
@contextmanager
def _quiet_workers() -> Iterator[None]:
    """Start worker processes that leave Ctrl-C to this one and log only errors.

    A terminal's Ctrl-C reaches every process of the group. The workers
    spawned here inherit an ignored SIGINT (an ignored signal survives
    ``exec``; Python and asyncio then install no handler of their own), so
    only this process is interrupted and closes the cluster; their
    ``distributed`` loggers (configured from the environment at import) say
    nothing below ERROR, such as the cancelled tasks of that close.
    """
    import signal

    saved_env = os.environ.get(_WORKER_LOG_ENV)
    os.environ[_WORKER_LOG_ENV] = "error"
    saved = signal.signal(signal.SIGINT, signal.SIG_IGN) if _main_thread() else None
    try:
        yield
    finally:
        if saved is not None:
            signal.signal(signal.SIGINT, saved)
        if saved_env is None:
            os.environ.pop(_WORKER_LOG_ENV, None)
        else:
            os.environ[_WORKER_LOG_ENV] = saved_env


#: the dask setting (as an environment variable) of the worker processes' log level
_WORKER_LOG_ENV = "DASK_LOGGING__DISTRIBUTED"


def _main_thread() -> bool:
    import threading

    return threading.current_thread() is threading.main_thread()


@contextmanager
def _silenced(loggers: Sequence[str] = ("distributed", "dask", "tornado", "asyncio")) -> Iterator[None]:
    """Raise the level of ``loggers`` above CRITICAL for the block (the cluster's close on Ctrl-C)."""
    import logging

    saved = {name: logging.getLogger(name).level for name in loggers}
    for name in loggers:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for name, level in saved.items():
            logging.getLogger(name).setLevel(level)


@contextmanager
def _engine(scheduler: str | None, workers: int | None) -> Iterator[tuple[Any, dict[str, Any]]]:
    """A dask client on a new local cluster or on ``scheduler``; closed on exit (the cluster too).

    On an interrupt the close is silent: the one line that says so is the
    command line's.
    """
    cluster = None
    if scheduler is None:
        with _quiet_workers():
            cluster = LocalCluster(n_workers=workers or DEFAULT_WORKERS, threads_per_worker=1,
                                   processes=True)
        try:
            client = Client(cluster)
        except BaseException:
            with _silenced():
                cluster.close()
            raise
    else:
        client = _connect(scheduler)
    interrupted = False
    try:
        engine = {"kind": "dask.distributed", "scheduler": client.scheduler.address,
                  "workers": len(client.nthreads()), "dask_version": dask.__version__}
        yield client, engine
    except BaseException:
        interrupted = True
        raise
    finally:
        with _silenced() if interrupted else nullcontext():
            client.close()
            if cluster is not None:
                cluster.close()


def _connect(scheduler: str) -> Any:
    """A client of the scheduler at ``scheduler``, or a one-line ``OSError``."""
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, ValueError, TypeError) as exc:
        reason = _one_line(exc)
    # the half-made client sits in reference cycles; collected later, on whatever thread, its
    # __del__ can deadlock the start of the next client in this process (it takes the loop
    # runners' lock): collect it now, outside the handler, where nothing refers to it any more
    gc.collect()
    raise OSError(f"cannot reach the dask scheduler `--scheduler` = {scheduler!r}: {reason}")


def _sweep(client: Any, tasks: list[tuple[str, Callable[..., Any], tuple[Any, ...], Any]],
           log: Callable[[dict[str, Any]], None], mode: str, done0: int, total: int,
           say: Say) -> list[dict[str, Any]]:
    """Submit every task, log each result as it arrives, and report progress; return the records."""
    futures = {}
    for key, fn, args, point in tasks:
        fut = client.submit(fn, *args, pure=False, key=f"threepart-map-{key}-{uuid.uuid4().hex[:8]}")
        futures[fut] = (key, point)
    records: list[dict[str, Any]] = []
    t0 = time.perf_counter()
    try:
        for fut in as_completed(list(futures)):
            key, point = futures[fut]
            try:
                result, error = fut.result(), None
            except (Exception, CancelledError) as exc:   # a failed point is recorded, never a crash
                result, error = None, _one_line(exc)
            rec = (_control_record(result, error, mode) if point is None
                   else _point_record(point, result, error, mode))
            log(rec)
            records.append(rec)
            done = done0 + len(records)
            elapsed = time.perf_counter() - t0
            eta = elapsed / len(records) * (total - done)
            status = "FAILED " + rec["error"] if rec["error"] else (
                f"peak error {_pct(rec.get('peak_rel_error'))}" if point is not None
                else f"control error {rec['control_rel_error']:.2e}")
            say(f"[{done:>{len(str(total))}}/{total}] {key}  {status}  "
                f"elapsed {elapsed:.1f} s, ETA {eta:.0f} s")
    finally:   # on an interrupt or an error: nothing left running for this run
        try:
            client.cancel([f for f in futures if not f.done()])
        except Exception:   # the scheduler is gone already: nothing to cancel
            pass
    return records


def _pct(v: Any) -> str:
    """A fraction as a percentage, e.g. ``0.0123`` as ``"1.23 %"``."""
    return "n/a" if v is None else f"{100 * v:.3g} %"


# ---------------------------------------------------------------------------------------
# the designer's reading and the plots
# ---------------------------------------------------------------------------------------
def _finite(v: Any) -> bool:
    return isinstance(v, (int, float)) and math.isfinite(v)


def below_level(points: Sequence[dict[str, Any]], level: float = LEVELS[0]) -> list[dict[str, Any]]:
    """Per ``b/R1``, how far in ``(a-b)/R1`` the peak-pressure error stays below ``level``.

    Parameters
    ----------
    points
        Map points (dicts with ``b_over_R1``, ``a_minus_b_over_R1`` and
        ``peak_rel_error``, None where the point failed) of one ``R2/R1`` and ``H/b``.
    level
        The error level, a fraction of the peak pressure.

    Returns
    -------
    list of dict
        One per ``b/R1``, ascending: ``b_over_R1``; ``limit``, the largest
        ``(a-b)/R1`` such that every point up to it is below ``level`` (None
        if the first is not); ``swept``, the largest ``(a-b)/R1`` swept;
        ``stop``, why the scan stopped: ``"level"`` (the next point reaches
        it), ``"failed"`` (the next point has no result) or ``"end"``; and
        ``first`` and ``first_error``, the smallest ``(a-b)/R1`` and its error.
    """
    rows = []
    for b in sorted({p["b_over_R1"] for p in points}):
        line = sorted((p for p in points if p["b_over_R1"] == b), key=lambda p: p["a_minus_b_over_R1"])
        limit: float | None = None
        stop = "end"
        for p in line:
            e = p.get("peak_rel_error")
            if e is None or not _finite(e):
                stop = "failed"
                break
            if e >= level:
                stop = "level"
                break
            limit = p["a_minus_b_over_R1"]
        rows.append({"b_over_R1": b, "limit": limit, "swept": line[-1]["a_minus_b_over_R1"],
                     "stop": stop, "first": line[0]["a_minus_b_over_R1"],
                     "first_error": line[0].get("peak_rel_error")})
    return rows


def designer_sentence(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float,
                      level: float = LEVELS[0]) -> str:
    """What the contour map of ``points`` (one ``R2/R1`` and ``H/b``) means for a designer, in one sentence."""
    rows = below_level(points, level)
    estimates = [p["fem_error_estimate"] for p in points if _finite(p.get("fem_error_estimate"))]
    caveat = ""
    if estimates and max(estimates) > level / 3:
        caveat = (f" (the FEM's own error estimate reaches {_pct(max(estimates))} here: differences "
                  "smaller than that are not resolved)")
    head = f"For R2/R1 = {R2_over_R1:g} and H/b = {H_over_b:g}, the closed form's peak pressure"
    if rows and all(r["limit"] is None and r["stop"] == "level" for r in rows):
        first = [r["first_error"] for r in rows]
        lightest = ", ".join(f"{v:g}" for v in sorted({r["first"] for r in rows}))
        return (f"{head} is off by {_pct(min(first))} to {_pct(max(first))} already at the lightest "
                f"load swept, (a−b)/R1 = {lightest}, for every b/R1: over "
                f"this whole range, design with a finite-body model{caveat}.")
    parts = []
    for row in rows:
        at = f"at b/R1 = {row['b_over_R1']:g}"
        if row["limit"] is None and row["stop"] == "failed":
            parts.append(f"unknown {at} (its first point failed)")
        elif row["limit"] is None:
            parts.append(f"at no load swept {at} ({_pct(row['first_error'])} already at "
                         f"(a−b)/R1 = {row['first']:g})")
        elif row["stop"] == "end":
            parts.append(f"over the whole sweep, (a−b)/R1 ≤ {row['swept']:g}, {at}")
        else:
            why = " (the next point failed)" if row["stop"] == "failed" else ""
            parts.append(f"up to (a−b)/R1 = {row['limit']:g} {at}{why}")
    return (f"{head} is within {_pct(level)} of the finite body's {'; '.join(parts)}; "
            f"at larger (a−b)/R1, that is heavier loads, design with a finite-body model{caveat}.")


def _plot_name(R2_over_R1: float, H_over_b: float) -> str:
    return f"plots/peak_error_R2R1_{R2_over_R1:g}_Hb_{H_over_b:g}.png"


def _contour(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float, sentence: str,
             path: Path) -> None:
    """The peak-pressure error over ``(a-b)/R1`` and ``b/R1`` (both log scale), 1/5/10 % lines."""
    import numpy as np
    from matplotlib.colors import BoundaryNorm
    from matplotlib.tri import Triangulation

    from .plots import new_figure, save

    fig, axes = new_figure(size=(7.0, 5.2))
    ax = axes[0, 0]
    ok = [p for p in points if _finite(p.get("peak_rel_error"))]
    bad = [p for p in points if not _finite(p.get("peak_rel_error"))]
    norm = BoundaryNorm(BANDS, 256, extend="max")
    cmap = "viridis"
    x = np.log10([p["a_minus_b_over_R1"] for p in ok])
    y = np.log10([p["b_over_R1"] for p in ok])
    z = np.array([p["peak_rel_error"] for p in ok], dtype=float)
    filled = None
    if len(ok) >= 3:
        try:
            tri = Triangulation(x, y)
            filled = ax.tricontourf(tri, z, levels=BANDS, cmap=cmap, norm=norm, extend="max")
            lines = [lv for lv in LEVELS if z.min() < lv < z.max()]
            if lines:
                cs = ax.tricontour(tri, z, levels=lines, colors="k", linewidths=1.2)
                ax.clabel(cs, fmt={lv: _pct(lv) for lv in lines}, fontsize=8)
        except (ValueError, RuntimeError):   # collinear points: no triangulation, markers only
            filled = None
    dots = ax.scatter(x, y, c=z, cmap=cmap, norm=norm, edgecolors="k", s=28, zorder=3)
    for xi, yi, zi in zip(x, y, z):
        ax.annotate(f"{100 * zi:.2g}", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if bad:
        ax.scatter(np.log10([p["a_minus_b_over_R1"] for p in bad]), np.log10([p["b_over_R1"] for p in bad]),
                   marker="x", color="tab:red", s=40, zorder=3)
    cb = fig.colorbar(filled if filled is not None else dots, ax=ax)
    cb.set_label("closed form's peak-pressure error vs finite body")
    cb.ax.yaxis.set_major_formatter(lambda v, _pos: _pct(v))
    xs = sorted({p["a_minus_b_over_R1"] for p in points})
    ys = sorted({p["b_over_R1"] for p in points})
    for ticks, setter, lim in ((np.log10(xs), ax.set_xticks, ax.set_xlim),
                               (np.log10(ys), ax.set_yticks, ax.set_ylim)):
        setter(ticks, [f"{10 ** v:.3g}" for v in ticks])
        pad = 0.05 * (ticks[-1] - ticks[0]) or 0.1   # the edge points' markers stay whole
        lim(ticks[0] - pad, ticks[-1] + pad)
    ax.set_xlabel("(a − b)/R1, overhang of the contact onto the edge arc (log scale)")
    ax.set_ylabel("b/R1, half-width of the flat centre (log scale)")
    ax.set_title(f"Peak-pressure error of the closed form, R2/R1 = {R2_over_R1:g}, H/b = {H_over_b:g}\n"
                 f"lines at {', '.join(_pct(lv) for lv in LEVELS)}; dots: the points, with their "
                 f"error in %{'; ×: failed points' if bad else ''}", fontsize=10)
    ax.grid(True, color="0.85", lw=0.5)
    fig.supxlabel(textwrap.fill(sentence, 110), fontsize=7.5)
    save(fig, path)


# ---------------------------------------------------------------------------------------
# the map document and its files
# ---------------------------------------------------------------------------------------
def load_schema() -> dict[str, Any]:
    """The JSON schema of ``map.json``."""
    return json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))


def validate(doc: dict[str, Any]) -> None:
    """Validate ``doc`` against ``map.schema.json`` (needs ``jsonschema``; skipped without it)."""
    validate_json(doc, SCHEMA_FILE)


def _csv_text(points: Sequence[dict[str, Any]]) -> str:
    """``map.csv``: the :data:`COLUMNS` of every point; null as an empty field, floats round-trip."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for p in points:
        w.writerow(["" if p[k] is None else f"{p[k]:.17g}" if isinstance(p[k], float) else p[k]
                    for k in COLUMNS])
    return buf.getvalue()


def _groups(points: Sequence[dict[str, Any]]) -> list[tuple[float, float]]:
    return sorted({(p["R2_over_R1"], p["H_over_b"]) for p in points}, key=lambda g: (-g[0], g[1]))


def _plan(rd: ResumableDir, plots: Sequence[str]) -> None:
    """Drop the plots of an earlier grid (ours and unchanged only) and make ``plots/``."""
    for f in [f for f in rd.marker["files"] if f.startswith("plots/") and f not in plots]:
        rd.remove(f)
    rd.mkdir("plots")


def _draw(rd: ResumableDir, doc: dict[str, Any], say: Say) -> None:
    """Draw one contour map per ``R2/R1`` and ``H/b`` into ``out/plots`` and list them in ``doc``."""
    points = doc["points"]
    for r, h in _groups(points):
        rel = _plot_name(r, h)
        group = [p for p in points if (p["R2_over_R1"], p["H_over_b"]) == (r, h)]
        sentence = designer_sentence(group, r, h)
        rd.write(rel, lambda path: _contour(group, r, h, sentence, path))
        doc["plots"].append({"file": rel, "R2_over_R1": r, "H_over_b": h, "sentence": sentence,
                             "below_1_percent": [{k: row[k] for k in ("b_over_R1", "limit", "stop")}
                                                 for row in below_level(group)]})
        say(f"  {rel}: {sentence}")


def exit_status(doc: dict[str, Any]) -> int:
    """0 when every point succeeded and the control is within :data:`CONTROL_LIMIT`, else 1."""
    control = doc["control_rel_error"]
    ok = doc["summary"]["failed"] == 0 and control is not None and control <= CONTROL_LIMIT
    return 0 if ok else 1


def run_map(out: str | Path, *, quick: bool = False, scheduler: str | None = None,
            workers: int | None = None, force: bool = False, evaluate: Evaluate = validity.evaluate,
            points: Sequence[MapPoint] | None = None,
            control: Callable[[bool], dict[str, Any]] = validity.control,
            say: Say = print) -> dict[str, Any]:
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
    say
        Where the progress lines go.

    Returns
    -------
    dict
        The ``map.json`` document (see ``reports/map.schema.json``).

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
    grid = list(validity.map_points(quick) if points is None else points)
    keys = [p.key() for p in grid]
    if len(set(keys)) != len(keys) or CONTROL_KEY in keys:
        raise ValueError("`points` must have distinct keys, none of them 'control'")
    engine: dict[str, Any] = {"kind": "dask.distributed", "scheduler": None, "workers": 0,
                              "dask_version": dask.__version__}
    timings: dict[str, float] = {"startup_s": 0.0, "sweep_s": 0.0}
    with ExitStack() as stack:
        client = None
        if scheduler is not None:   # reached before `out` is touched: an unreachable one leaves nothing
            t1 = time.perf_counter()
            client, engine = stack.enter_context(_engine(scheduler, None))
            timings["startup_s"] = time.perf_counter() - t1
        rd = ResumableDir.open(out, command=COMMAND, mode=mode, force=force)
        stack.callback(rd.close)
        records = _read_log(rd.log_lines(POINTS_FILE), mode)
        tasks: list[tuple[str, Callable[..., Any], tuple[Any, ...], Any]] = [
            (p.key(), evaluate, (p, quick), p) for p in grid if not _done(records.get(p.key()))]
        if not _done(records.get(CONTROL_KEY)):
            tasks.append((CONTROL_KEY, control, (quick,), None))
        total = len(grid) + 1
        say(f"threepart map --{mode}: {len(grid)} points and the control -> {out} "
            f"({rd.action}; {total - len(tasks)} of {total} already done)")
        if tasks:
            if client is None:
                t1 = time.perf_counter()
                client, engine = stack.enter_context(_engine(None, workers))
                timings["startup_s"] = time.perf_counter() - t1
            say(f"engine: {engine['kind']} at {engine['scheduler']}, {engine['workers']} "
                f"workers (ready in {timings['startup_s']:.1f} s)")
            t2 = time.perf_counter()

            def log(rec: dict[str, Any]) -> None:
                rd.append(POINTS_FILE, strict_json(rec))

            for rec in _sweep(client, tasks, log, mode, total - len(tasks), total, say):
                records[rec["key"]] = rec
            timings["sweep_s"] = time.perf_counter() - t2
    computed = [records[t[0]] for t in tasks if t[0] != CONTROL_KEY]
    ran = [records[t[0]].get("control", {}) if t[0] == CONTROL_KEY else records[t[0]] for t in tasks]
    task_s = sum(r["time_s"] for r in ran if _finite(r.get("time_s")))
    timings["evaluate_s"] = task_s
    if tasks and timings["sweep_s"] > 0 and engine["workers"]:
        timings["overhead_per_task_s"] = max(
            0.0, (timings["sweep_s"] * engine["workers"] - task_s) / len(tasks))
    ctl = records[CONTROL_KEY]
    mapped = [{k: records[key].get(k) for k in COLUMNS} for key in keys]
    failed = sum(p["error"] is not None for p in mapped) + (ctl["error"] is not None)
    doc: dict[str, Any] = {
        "schema_version": SCHEMA_VERSION, "tool": "threepart map", "mode": mode, "engine": engine,
        "control_rel_error": ctl["control_rel_error"], "control_limit": CONTROL_LIMIT,
        "control": {**ctl["control"], "error": ctl["error"]},
        "points": mapped, "timings": timings, "plots": [],
        "summary": {"points": len(mapped), "failed": failed, "computed": len(computed),
                    "resumed": len(mapped) - len(computed), "run_time_s": 0.0},
    }
    t3 = time.perf_counter()
    _plan(rd, [_plot_name(r, h) for r, h in _groups(mapped)])
    _draw(rd, doc, say)
    rd.write("map.csv", _csv_text(mapped))
    timings["write_s"] = time.perf_counter() - t3
    timings["total_s"] = doc["summary"]["run_time_s"] = time.perf_counter() - t0
    doc = json_safe(doc)
    validate(doc)
    rd.write("map.json", strict_json(doc, indent=1) + "\n")
    rd.seal(finished=failed == 0)
    return doc


def _done(rec: dict[str, Any] | None) -> bool:
    """Whether a log line is a finished task (no error, every field present)."""
    if rec is None or rec.get("error") is not None:
        return False
    need = ("control_rel_error", "control") if rec["key"] == CONTROL_KEY else COLUMNS
    return all(k in rec for k in need)


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
        f"({s['computed']} computed now), control error "
        f"{'n/a' if control is None else f'{control:.2e}'} (limit {CONTROL_LIMIT:g}), "
        f"{s['run_time_s']:.1f} s -> {Path(out) / 'map.json'}")
    for p in doc["points"]:
        if p["error"] is not None:
            say(f"  failed: {p['key']}: {p['error']}")
    if doc["control"].get("error"):
        say(f"  failed: control: {doc['control']['error']}")
    return status

"""The log of a validity-map sweep, ``points.jsonl``: one JSON line per finished task, the resume state.

Names
-----
POINTS_FILE    -- the log's file name
CONTROL_KEY    -- the key of the control's line
read_log       -- the last line of every key of one mode
point_record   -- the line of one point: coordinates, results and error
control_record -- the line of the control
task_record    -- the line of a study task (partial slip, small slope, crossing, referee)
task_key       -- the key of a study task
done           -- whether a line is a finished task
one_line       -- an exception as one line
"""
from __future__ import annotations

import json
from typing import Any

from threepart.output import json_safe

from .schema import COORDINATES, POINT_FIELDS, SCHEMA_VERSION
from .validity import EDGE_KEYS, RESULT_KEYS

__all__ = ["POINTS_FILE", "CONTROL_KEY", "read_log", "point_record", "control_record", "task_record",
           "task_key", "done", "one_line"]

#: the sweep's log: one JSON line per finished task, the resume state
POINTS_FILE = "points.jsonl"
#: the key of the control's line in :data:`POINTS_FILE`
CONTROL_KEY = "control"


def read_log(data: bytes, mode: str) -> dict[str, dict[str, Any]]:
    """The last line of every key of this mode in the whole lines ``data`` of ``points.jsonl``.

    Lines of another layout (``SCHEMA_VERSION``: e.g. the unsigned errors of
    1.0) are not resumed: their points are computed again.
    """
    records: dict[str, dict[str, Any]] = {}
    for line in data.decode("utf-8").splitlines():
        try:
            rec = json.loads(line)
        except ValueError:
            continue
        if (isinstance(rec, dict) and rec.get("mode") == mode and isinstance(rec.get("key"), str)
                and rec.get("layout") == SCHEMA_VERSION):
            records[rec["key"]] = rec
    return records


def one_line(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {' '.join(str(exc).split())}".rstrip(": ")


def point_record(point: Any, result: Any, error: str | None, mode: str) -> dict[str, Any]:
    """One line of the log (and one point of the map): coordinates, :data:`RESULT_KEYS`, error."""
    rec: dict[str, Any] = {"key": point.key(), **{k: float(point.as_dict()[k]) for k in COORDINATES}}
    rec.update({k: None for k in (*RESULT_KEYS, *EDGE_KEYS)})
    if error is None:
        values, error = _numbers(result, RESULT_KEYS, "evaluate")
        rec.update(values)
        if error is None:   # optional figures: a number or None (a fake evaluate may leave them out)
            rec.update({k: None if result.get(k) is None else float(result[k]) for k in EDGE_KEYS})
    return json_safe({**rec, "error": error, "mode": mode, "layout": SCHEMA_VERSION})


def _numbers(result: Any, keys: tuple[str, ...], what: str) -> tuple[dict[str, float], str | None]:
    """``keys`` of the dict ``result`` as floats, or ``({}, the one-line reason they are not)``."""
    if not isinstance(result, dict):
        return {}, f"{what} returned {type(result).__name__}, not a dict"
    missing = [k for k in keys if k not in result]
    if missing:
        return {}, f"{what} returned no {missing[0]!r}"
    try:
        return {k: float(result[k]) for k in keys}, None
    except (TypeError, ValueError):
        return {}, f"{what} returned a value that is not a number"


def control_record(result: Any, error: str | None, mode: str) -> dict[str, Any]:
    value = None
    if error is None:
        try:
            value = float(result["control_rel_error"])
        except (TypeError, KeyError, ValueError):
            error = "control returned no number `control_rel_error`"
    control = {k: v for k, v in result.items() if k != "control_rel_error"} if error is None else {}
    return json_safe({"key": CONTROL_KEY, "control_rel_error": value, "control": control,
                      "error": error, "mode": mode, "layout": SCHEMA_VERSION})


def task_key(kind: str, name: str) -> str:
    """The key of a study task of ``kind`` (``slip``, ``slope``, ``crossing``, ``referee``) on
    ``name`` (a point's key or a curve's name): ``"slip:R2R1=1_..."``."""
    return f"{kind}:{name}"


def task_record(key: str, kind: str, result: Any, exc: BaseException | None, mode: str,
                keys: tuple[str, ...] = (), absent: tuple[type[BaseException], ...] = ()
                ) -> dict[str, Any]:
    """The line of a study task: its ``keys`` as floats (or, with no ``keys``, the whole
    ``result`` as JSON under ``"result"``), ``error`` and ``note``.

    An exception of a type in ``absent`` (e.g. :class:`threepart.calculix.CcxMissing`) is a
    ``note``, not a failure: the task could not run here. Neither such a line nor a failed one
    is :func:`done`, so the next run tries the task again.
    """
    rec: dict[str, Any] = {"key": key, "kind": kind, **{k: None for k in keys}}
    error = note = None
    if exc is not None:
        if isinstance(exc, absent):
            note = one_line(exc)
        else:
            error = one_line(exc)
    elif keys:
        values, error = _numbers(result, keys, kind)
        rec.update(values)
    elif not isinstance(result, dict):
        error = f"{kind} returned {type(result).__name__}, not a dict"
    else:
        rec["result"] = result
    return json_safe({**rec, "error": error, "note": note, "mode": mode, "layout": SCHEMA_VERSION})


def done(rec: dict[str, Any] | None) -> bool:
    """Whether a log line is a finished task (no error, no note, every field present)."""
    if rec is None or rec.get("error") is not None or rec.get("note") is not None:
        return False
    if "kind" in rec:
        return "error" in rec
    need = ("control_rel_error", "control") if rec["key"] == CONTROL_KEY else POINT_FIELDS
    return all(k in rec for k in need)


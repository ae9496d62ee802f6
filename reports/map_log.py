"""The log of a validity-map sweep, ``points.jsonl``: one JSON line per finished task, the resume state.

Names
-----
POINTS_FILE    -- the log's file name
CONTROL_KEY    -- the key of the control's line
read_log       -- the last line of every key of one mode
point_record   -- the line of one point: coordinates, results and error
control_record -- the line of the control
done           -- whether a line is a finished task
one_line       -- an exception as one line
"""
from __future__ import annotations

import json
from typing import Any

from threepart.output import json_safe

from .map_schema import COLUMNS, COORDINATES, SCHEMA_VERSION
from .validity import RESULT_KEYS

__all__ = ["POINTS_FILE", "CONTROL_KEY", "read_log", "point_record", "control_record", "done",
           "one_line"]

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
    return json_safe({**rec, "error": error, "mode": mode, "layout": SCHEMA_VERSION})


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



def done(rec: dict[str, Any] | None) -> bool:
    """Whether a log line is a finished task (no error, every field present)."""
    if rec is None or rec.get("error") is not None:
        return False
    need = ("control_rel_error", "control") if rec["key"] == CONTROL_KEY else COLUMNS
    return all(k in rec for k in need)


"""The fields of a validity-map point, the schema of ``map.json`` and the text of ``map.csv``.

The map's design space is declared here once: :data:`GROUP_AXES` (one contour
map per combination of their values) and :data:`PLOT_AXES` (the x and y of
each contour map) make up a point's :data:`COORDINATES`, which are the fields
of :class:`reports.map.validity.MapPoint`. A new axis is a new field of
``MapPoint``, a name in one of these two tuples (with its short label in
:data:`FILE_LABELS` if it groups the plots) and its entry in
``map.schema.json``; ``tests/test_map.py`` checks that the three agree.

Names
-----
SCHEMA_FILE    -- ``reports/map/map.schema.json``
SCHEMA_VERSION -- the version of ``map.json``'s layout
GROUP_AXES     -- the coordinates that make one contour map per combination
PLOT_AXES      -- the coordinates along x and y of each contour map
FILE_LABELS    -- the short label of each group axis in a plot's file name
COORDINATES    -- the coordinates of a point, in CSV order
POINT_FIELDS   -- the fields of a grid point's own line of ``points.jsonl``
SLIP_COLUMNS   -- the partial-slip columns of a point (null where not run)
SLOPE_COLUMNS  -- the small-slope columns of a point (null where not run)
COLUMNS        -- the fields of every point in ``map.json`` and the columns of ``map.csv``
BOUNDARY_COLUMNS -- the columns of ``boundaries.csv`` (one located crossing per row)
load_schema    -- the JSON schema of ``map.json``
validate       -- validate a document against ``map.schema.json``
csv_text       -- ``map.csv`` of a list of points
boundaries_csv -- ``boundaries.csv`` of a list of boundary records
groups         -- the values of :data:`GROUP_AXES` that the points take, in plot order
plot_name      -- the file of one group's contour map
finite         -- whether a value is a finite number
pct            -- a fraction as a percentage
"""
from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path
from typing import Any, Sequence

from threepart.output import validate_json

from .validity import EDGE_KEYS, RESULT_KEYS
from .validity_slip import SLIP_RESULT_KEYS
from .validity_slope import SLOPE_RESULT_KEYS

__all__ = ["SCHEMA_FILE", "SCHEMA_VERSION", "GROUP_AXES", "PLOT_AXES", "FILE_LABELS", "COORDINATES",
           "COLUMNS", "POINT_FIELDS", "SLIP_COLUMNS", "SLOPE_COLUMNS", "BOUNDARY_COLUMNS", "load_schema", "validate", "csv_text", "boundaries_csv",
           "groups", "plot_name", "finite", "pct"]

SCHEMA_FILE = Path(__file__).with_name("map.schema.json")
#: 2.0 (issue 23): signed errors, the lever-arm axis s_over_lift, the located boundaries;
#: 3.0: the load level p0/E* of every point, the partial-slip and small-slope columns of a
#: subset of points, the small-slope crossings and the CalculiX referee points
SCHEMA_VERSION = "3.1"
#: one contour map per combination of these coordinates (R2/R1 descending, then ascending)
GROUP_AXES = ("R2_over_R1", "H_over_b", "s_over_lift")
#: the x and y of each contour map (both on log scales)
PLOT_AXES = ("a_minus_b_over_R1", "b_over_R1")
#: the short label of each group axis in a plot's file name
FILE_LABELS = {"R2_over_R1": "R2R1", "H_over_b": "Hb", "s_over_lift": "sL"}
#: the coordinates of a point (:class:`reports.map.validity.MapPoint`), in CSV order
COORDINATES = (*GROUP_AXES, *reversed(PLOT_AXES))
#: the fields of a grid point's own line of ``points.jsonl`` (its normal problem)
POINT_FIELDS = ("key", *COORDINATES, *RESULT_KEYS, *EDGE_KEYS, "error")
#: the partial-slip columns of a point (:mod:`reports.map.validity_slip`; null where not run)
SLIP_COLUMNS = (*SLIP_RESULT_KEYS, "slip_error")
#: the small-slope columns of a point (:mod:`reports.map.validity_slope`; null where not run;
#: its ``load_level`` is the point's own column)
SLOPE_COLUMNS = (*(k for k in SLOPE_RESULT_KEYS if k != "load_level"), "slope_error")
#: the fields of every point in ``map.json`` and the columns of ``map.csv``, in order
COLUMNS = ("key", *COORDINATES, *RESULT_KEYS, *EDGE_KEYS, "load_level", *SLIP_COLUMNS, *SLOPE_COLUMNS, "error")
#: the columns of ``boundaries.csv``: the curve, the level, the crossing and its band, the
#: final bracket, the number of steps, and whether the curve crosses the level once
BOUNDARY_COLUMNS = (*GROUP_AXES, "b_over_R1", "level", "a_minus_b_over_R1", "band_lo", "band_hi",
                    "bracket_lo", "bracket_hi", "fem_error_estimate", "steps", "crossed_once",
                    "status")


def load_schema() -> dict[str, Any]:
    """The JSON schema of ``map.json``."""
    return json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))


def validate(doc: dict[str, Any]) -> None:
    """Validate ``doc`` against ``map.schema.json`` (needs ``jsonschema``; skipped without it)."""
    validate_json(doc, SCHEMA_FILE)


def csv_text(points: Sequence[dict[str, Any]]) -> str:
    """``map.csv``: the :data:`COLUMNS` of every point; null as an empty field, floats round-trip."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for p in points:
        w.writerow([_cell(p[k]) for k in COLUMNS])
    return buf.getvalue()


def _cell(v: Any) -> Any:
    """A CSV field: null empty, floats to 17 digits (they round-trip), the rest as they are."""
    return "" if v is None else f"{v:.17g}" if isinstance(v, float) else v


def boundaries_csv(boundaries: Sequence[dict[str, Any]]) -> str:
    """``boundaries.csv``: :data:`BOUNDARY_COLUMNS` of every boundary record of ``map.json``."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(BOUNDARY_COLUMNS)
    for b in boundaries:
        flat = {**b, "band_lo": b["band"][0], "band_hi": b["band"][1], "bracket_lo": b["bracket"][0],
                "bracket_hi": b["bracket"][1], "steps": len(b["steps"])}
        w.writerow([_cell(flat[k]) for k in BOUNDARY_COLUMNS])
    return buf.getvalue()


def groups(points: Sequence[dict[str, Any]]) -> list[tuple[float, ...]]:
    """The values of :data:`GROUP_AXES` that ``points`` take: the first descending, the rest ascending."""
    return sorted({tuple(p[a] for a in GROUP_AXES) for p in points}, key=lambda g: (-g[0], *g[1:]))


def plot_name(group: Sequence[float], kind: str = "peak_error") -> str:
    """The file of the ``kind`` plot of ``group`` (values of :data:`GROUP_AXES`).

    For example ``plots/peak_error_R2R1_1_Hb_4_sL_0.5.png`` (the contour map)
    or ``plots/stick_zone_R2R1_1_Hb_4_sL_0.png`` (the partial slip).
    """
    labels = "_".join(f"{FILE_LABELS[a]}_{v:g}" for a, v in zip(GROUP_AXES, group))
    return f"plots/{kind}_{labels}.png"


def finite(v: Any) -> bool:
    return isinstance(v, (int, float)) and math.isfinite(v)


def pct(v: Any) -> str:
    """A fraction as a percentage, e.g. ``0.0123`` as ``"1.23 %"``."""
    return "n/a" if v is None else f"{100 * v:.3g} %"

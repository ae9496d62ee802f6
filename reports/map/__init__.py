"""reports.map: where the half-plane formulas stop, the finite-body validity map (``threepart map``).

The physics of one point is :mod:`~reports.map.validity` (peak pressure), with its partial-slip
and small-slope studies (:mod:`~reports.map.validity_slip`, :mod:`~reports.map.validity_slope`)
and the CalculiX referee of chosen points (:mod:`~reports.map.referee`); :mod:`~reports.map.sweep`
runs the grid on dask.distributed (:mod:`~reports.map.engine`), logs it (:mod:`~reports.map.log`),
locates the boundary (:mod:`~reports.map.boundary`), runs the studies on subsets
(:mod:`~reports.map.studies`), draws it (:mod:`~reports.map.plots`) and writes ``map.json``
against its schema (:mod:`~reports.map.schema`, ``map.schema.json``).

run_map           -- run (or resume) the sweep and write the map; returns the ``map.json`` document
main              -- ``threepart map``: :func:`run_map` and the exit status
exit_status       -- 0 when every point succeeded and the control is within its limit
check_arguments   -- the argument check of :func:`run_map`, before any work
validate          -- validate a document against ``map.schema.json``
load_schema       -- the JSON schema of ``map.json``
"""
from __future__ import annotations

from .sweep import check_arguments, exit_status, load_schema, main, run_map, validate

__all__ = ["run_map", "main", "exit_status", "check_arguments", "validate", "load_schema"]

"""reports.verify: the verification run (``threepart verify``) and its tolerance report.

:mod:`~reports.verify.runs` solves each catalogue case by every registered method and compares
them (:mod:`reports.compare`); :mod:`~reports.verify.studies` runs the convergence studies
(:mod:`~reports.verify.side`: beside the cases, in a second process, on more than one core),
:mod:`~reports.verify.flight` the flight cycle's marched history, :mod:`~reports.verify.robustness`
``--full``'s wide random draw, :mod:`~reports.verify.stress` the stresses and fatigue hot spots;
:mod:`~reports.verify.report` puts them into ``report.json`` (``report.schema.json``), and
:mod:`~reports.verify.sections`, :mod:`~reports.verify.render` and :mod:`~reports.verify.plots`
write it as Markdown, HTML and PNG.

main          -- ``threepart verify``: run, write the report, return the exit status
build_report  -- the ``report.json`` document of a run
write_report  -- write the report's files into a directory
validate      -- validate a document against ``report.schema.json``
load_schema   -- the JSON schema of ``report.json``
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from threepart.lazy import lazy_names

#: each public name and its module, loaded on first use: importing a leaf of this package
#: (:mod:`~reports.verify.sections`, as :mod:`reports.referee.verdict` does) loads no run
_HOMES = {name: "report" for name in ("main", "build_report", "write_report", "validate", "load_schema")}

__all__ = list(_HOMES)

if TYPE_CHECKING:   # pragma: no cover - for type checkers and IDEs only
    from .report import build_report, load_schema, main, validate, write_report

__getattr__, __dir__ = lazy_names(__name__, _HOMES)

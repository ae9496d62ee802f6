"""reports: the verification run, tolerance reports, regression baselines and the paper's figures.

The only package that knows more than one solver: it runs the case catalogue
through :mod:`closedform`, :mod:`sie` and :mod:`fem` and compares them.

The cases come from the one catalogue (:mod:`threepart.problem.catalogue`) and the limits
from the one tolerance table (:mod:`threepart.tolerances`). ``threepart verify``
is :func:`reports.verify.report.main` and ``threepart figures`` :func:`reports.figures.main`;
the report is one list of sections (:mod:`reports.verify.sections`) rendered as
Markdown and HTML (:mod:`reports.verify.render`).

Runs and comparison
-------------------
CaseRun         -- every result, time, error and check of one case
run_case        -- solve one case with all three methods and compare
MODES           -- discretisation settings of ``quick``, ``default`` and ``full``
compare         -- method-agnostic comparison of two results, judged against the table
Check           -- one compared quantity: values, normalised error, limit, reason, verdict

A flight cycle (a case with two ``states``) is solved by every method with a
steady state and marched as a load history (:mod:`reports.verify.flight`).

Studies
-------
sie_study       -- SIE convergence in n against the closed form (orders, Richardson)
fem_study       -- FEM convergence in h against the closed form (orders, GCI)

The pytest plugin (:mod:`reports.plugin`, entry point pytest11): fixtures ``threepart_case``
and ``threepart_check`` that judge another code by the catalogue's references.

Reference data (``threepart export-refs``, :mod:`reports.refs`)
--------------
export_refs     -- the catalogue's reference solutions as a versioned dataset (JSON, CSV, schema)
load_refs       -- read a dataset back, every CSV checked against its JSON bit for bit
"""
from __future__ import annotations

from .verify.runs import MODES, CaseRun, run_case
from .compare import Check, compare
from .refs import export_refs, load_refs
from .verify.studies import fem_study, sie_study

__all__ = ["CaseRun", "run_case", "MODES", "compare", "Check", "sie_study", "fem_study",
           "export_refs", "load_refs"]

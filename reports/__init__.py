"""reports: the verification run, tolerance reports, regression baselines and the paper's figures.

The only package that knows more than one solver: it runs the case catalogue
through :mod:`closedform`, :mod:`sie` and :mod:`fem` and compares them.

Catalogue and comparison
------------------------
Case            -- one case of ``cases.json``: punch, material, P, s, tilt, f, Q/fP
CaseRun         -- every result, time, error and check of one case
load_cases      -- read the case catalogue (``reports/cases.json``)
get_case        -- one catalogue case by name
run_case        -- solve one case with all three methods and compare
MODES           -- discretisation settings of ``quick``, ``default`` and ``full``
compare         -- method-agnostic comparison of two results, judged against the table
Check           -- one compared quantity: values, normalised error, limit, reason, verdict
TOLERANCES      -- the one tolerance table, ``(comparison, quantity) -> Tolerance``
Tolerance       -- a limit and the reason for it

Studies, report, figures
------------------------
sie_study       -- SIE convergence in n against the closed form (orders, Richardson)
fem_study       -- FEM convergence in h against the closed form (orders, GCI)
verify_main     -- ``threepart verify``: run everything and write md/html/json/png
figures_main    -- ``threepart figures``: the paper's pressure and shear figures
"""
from __future__ import annotations

from .catalogue import MODES, Case, CaseRun, get_case, load_cases, run_case
from .compare import Check, compare
from .studies import fem_study, sie_study
from .tolerances import TOLERANCES, Tolerance


def verify_main(mode: str = "default", out: str = "report", force: bool = False) -> int:
    """Run ``threepart verify`` (see :func:`reports.verify.main`)."""
    from .verify import main

    return main(mode=mode, out=out, force=force)


def figures_main(out: str = "figures", force: bool = False) -> int:
    """Run ``threepart figures`` (see :func:`reports.figures.main`)."""
    from .figures import main

    return main(out=out, force=force)


__all__ = ["Case", "CaseRun", "load_cases", "get_case", "run_case", "MODES", "compare", "Check",
           "TOLERANCES", "Tolerance", "sie_study", "fem_study", "verify_main", "figures_main"]

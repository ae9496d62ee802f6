"""reports: the verification run, tolerance reports, regression baselines and the paper's figures.

The only package that knows more than one solver: it runs the case catalogue
through :mod:`closedform`, :mod:`sie` and :mod:`fem` and compares them.

The cases come from the one catalogue (:mod:`threepart.catalogue`) and the limits
from the one tolerance table (:mod:`threepart.tolerances`).

Runs and comparison
-------------------
CaseRun         -- every result, time, error and check of one case
run_case        -- solve one case with all three methods and compare
MODES           -- discretisation settings of ``quick``, ``default`` and ``full``
compare         -- method-agnostic comparison of two results, judged against the table
Check           -- one compared quantity: values, normalised error, limit, reason, verdict

Studies, report, figures
------------------------
sie_study       -- SIE convergence in n against the closed form (orders, Richardson)
fem_study       -- FEM convergence in h against the closed form (orders, GCI)
verify_main     -- ``threepart verify``: run everything and write md/html/json/png
figures_main    -- ``threepart figures``: the paper's pressure and shear figures
"""
from __future__ import annotations

from .catalogue import MODES, CaseRun, run_case
from .compare import Check, compare
from .studies import fem_study, sie_study


def verify_main(mode: str = "default", out: str = "report", force: bool = False) -> int:
    """Run ``threepart verify`` (see :func:`reports.verify.main`)."""
    from .verify import main

    return main(mode=mode, out=out, force=force)


def figures_main(out: str = "figures", force: bool = False) -> int:
    """Run ``threepart figures`` (see :func:`reports.figures.main`)."""
    from .figures import main

    return main(out=out, force=force)


__all__ = ["CaseRun", "run_case", "MODES", "compare", "Check",
           "sie_study", "fem_study", "verify_main", "figures_main"]

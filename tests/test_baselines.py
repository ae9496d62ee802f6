"""Regression baselines: the key figures of the quick verification run and of the paper's figures.

The committed files live in ``tests/baselines/``. A mismatch writes
``*.obtained.json`` beside the baseline; ``pytest --force-regen`` renews them.
Kept fast: closedform and SIE on the whole catalogue, the FEM on one quick case.
"""
from __future__ import annotations

import math

import pytest

from threepart.problem.catalogue import get_case, load_cases
from threepart.reports import figures
from threepart.reports.compare import normal_of
from threepart.reports.verify.runs import MODES, run_case

from threepart.tolerances import BASELINES

from .regression import check_baseline

# --- tolerance per quantity of the baselines: threepart.tolerances.BASELINES, each with its reason ---
CF = BASELINES["closedform"].limits()
CF_X = BASELINES["closedform_x"].limits()
SIE_ERR = BASELINES["sie_error"].limits()
HISTORY_ERR = BASELINES["history_error"].limits()
FEM = BASELINES["fem"].limits()
FEM_ERR = BASELINES["fem_error"].limits()

QUICK = MODES["quick"]


def _tolerances(data, rule):
    return {k: rule(k) for k in data}


def _cf_rule(key: str) -> dict[str, float]:
    if key.startswith("sie-history_"):
        return HISTORY_ERR
    if key.startswith("sie_"):
        return SIE_ERR
    return CF_X if key.startswith("x_") else CF


def test_quick_run_closedform_and_sie(request):
    cache: dict = {}
    rows: list[dict] = []
    for case in (c for c in load_cases() if not c.beyond):
        run = run_case(case, QUICK, cache, methods=("closedform", "sie"))
        assert not run.errors, run.errors
        cf = run.results["closedform"]
        n = normal_of(cf)   # a flight cycle: its wider end state
        left, right = n.peaks()
        row = {"case": case.name, "a": n.a, "c": n.c, "alpha": n.alpha, "s": n.s, "p_left": left.p,
               "x_left": left.x, "p_right": right.p, "x_right": right.x,
               "d": getattr(cf, "d", math.nan), "e": getattr(cf, "e", math.nan)}
        row.update({f"{c.comparison}_{c.quantity}": c.error for c in run.checks})
        rows.append(row)
    # a quantity missing for a case (slip-only, cycle-only) is None in that case's place
    keys = list(dict.fromkeys(k for row in rows for k in row))
    data = {k: [None if isinstance(v, float) and math.isnan(v) else v
                for v in (row.get(k, math.nan) for row in rows)] for k in keys}
    check_baseline(request.config, "quick_closedform_sie", data, _tolerances(data, _cf_rule))


def test_quick_run_beyond_the_closed_form(request):
    """Past the paper's framework: the closed form refuses (checked) and the SIE's figures are kept."""
    data: dict[str, list] = {"case": []}
    for case in (c for c in load_cases() if c.beyond):
        run = run_case(case, QUICK, methods=("closedform", "sie"))
        assert not run.errors and run.passed, (run.errors, run.failed())
        assert case.closedform_refuses in run.refusals["closedform"]
        res = run.results["sie"]
        n = getattr(res, "normal", res)
        left, right = n.peaks()
        row = {"a": n.a, "c": n.c, "alpha": n.alpha, "s": n.s, "p_left": left.p, "x_left": left.x,
               "p_right": right.p, "x_right": right.x,
               "d": getattr(res, "d", None), "e": getattr(res, "e", None)}
        data["case"].append(case.name)
        for k, v in row.items():
            data.setdefault(k, []).append(v)
    check_baseline(request.config, "quick_beyond_sie", data, _tolerances(data, _cf_rule))


def test_quick_run_one_fem_case(request):
    case = get_case("caseA_moment")
    run = run_case(case, QUICK, methods=("closedform", "fem"))
    assert not run.errors, run.errors
    res = run.results["fem"]
    left, right = res.peaks()
    data = {"a": [res.a], "c": [res.c], "alpha": [res.alpha], "s": [res.s],
            "p_left": [left.p], "p_right": [right.p]}
    data.update({f"fem_{c.quantity}": [c.error] for c in run.checks})
    assert all(c.passed for c in run.checks), [c for c in run.checks if not c.passed]
    check_baseline(request.config, "quick_fem_caseA_moment", data,
                   _tolerances(data, lambda k: FEM_ERR if k.startswith("fem_") else FEM))


def test_paper_figures_are_admissible():
    assert figures.check_admissible() == []


@pytest.mark.parametrize("which", ["a", "b"])
def test_paper_figures(request, which):
    data = figures.figure_data(which)
    check_baseline(request.config, f"figures_{which}", data, _tolerances(data, _cf_rule))


# --- the baseline mechanism itself ------------------------------------------------------------
class _Config:
    def __init__(self, regen: bool):
        self.regen = regen

    def getoption(self, name):
        assert name == "force_regen"
        return self.regen


def test_baseline_mechanism(tmp_path):
    data = {"a": [1.0, 2.0], "case": ["x", "y"]}
    tol = {"a": {"rtol": 1e-6}}
    with pytest.raises(pytest.fail.Exception, match="created"):
        check_baseline(_Config(False), "demo", data, tol, directory=tmp_path)
    assert (tmp_path / "demo.json").exists()
    check_baseline(_Config(False), "demo", {"a": [1.0 + 1e-9, 2.0], "case": ["x", "y"]}, tol,
                   directory=tmp_path)  # within rtol
    assert not (tmp_path / "demo.obtained.json").exists()
    bad = {"a": [1.1, 2.0], "case": ["x", "y"]}
    with pytest.raises(pytest.fail.Exception, match=r"a\[x\]"):
        check_baseline(_Config(False), "demo", bad, tol, directory=tmp_path)
    assert (tmp_path / "demo.obtained.json").exists()
    assert '"a": [\n  1.0,' in (tmp_path / "demo.json").read_text()  # baseline unchanged
    with pytest.raises(pytest.fail.Exception, match="regenerated"):
        check_baseline(_Config(True), "demo", bad, tol, directory=tmp_path)
    check_baseline(_Config(False), "demo", bad, tol, directory=tmp_path)


def test_baseline_rows_keyed_by_case_name(tmp_path):
    """A case added to the catalogue (issue 40) is named once; the others are matched by name, not position."""
    tol = {"a": {"rtol": 1e-6}}
    with pytest.raises(pytest.fail.Exception, match="created"):
        check_baseline(_Config(False), "keyed", {"case": ["x", "y"], "a": [1.0, 2.0]}, tol, directory=tmp_path)
    # reordered: still the same figures
    check_baseline(_Config(False), "keyed", {"case": ["y", "x"], "a": [2.0, 1.0]}, tol, directory=tmp_path)
    # a new case between the others: only it is named, and a changed figure still by its case
    grown = {"case": ["x", "new", "y"], "a": [1.0, 5.0, 2.5]}
    with pytest.raises(pytest.fail.Exception) as info:
        check_baseline(_Config(False), "keyed", grown, tol, directory=tmp_path)
    lines = str(info.value).splitlines()[1:]
    assert lines == ["case 'new': only in obtained",
                     "a[y]: obtained 2.5, baseline 2.0 (rtol 1e-06, atol 0)"]

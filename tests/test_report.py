"""The report a person reads: verdict and tightest margins first, units on every number.

Fast: every solver is a fake (tests/fakes.py), so only the report's own logic runs.
"""
from __future__ import annotations

import json
import re
from dataclasses import replace

import pytest

from threepart import catalogue
from threepart.convergence import is_monotone
from threepart.errors import LiftOffError
from threepart.reports import render, verify
from threepart.tolerances import ERROR_UNITS, NORMALISATION

from .fakes import fake_solver, install_fakes

NAMES = ("caseA_sym", "slip_Q0.4", "caseA_moment", "beyond_edge_on_flat")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A quick report on fake solvers; the fake closed form refuses the case past lift-off."""
    cf = fake_solver("closedform")
    cases = [c for c in catalogue.load_cases() if c.name in NAMES]
    within = {(c.punch, c.P, c.s_load) for c in cases if not c.beyond}

    def refusing(punch, P, s, **options):   # the case past lift-off has its s resolved at run time
        if (punch, P, s) not in within:
            raise LiftOffError(f"`s` = {s:g} exceeds the lift-off lever arm (fake)")
        return cf.normal(punch, P, s, **options)

    with pytest.MonkeyPatch.context() as mp:
        install_fakes(mp, closedform=replace(cf, normal=refusing))
        mp.setattr(verify, "STUDY_CASE", "caseA_moment")
        out = tmp_path_factory.mktemp("report") / "rep"
        assert verify.main(mode="quick", out=out, cases=cases, quiet=True) == 0
    return json.loads((out / "report.json").read_text()), out


def test_the_tightest_margins_are_the_worst_checks_worst_first(report):
    doc, _ = report
    ratios = sorted((c["error"] / c["limit"] for case in doc["cases"] for c in case["checks"]),
                    reverse=True)
    tight = doc["summary"]["tightest"]
    assert [t["ratio"] for t in tight] == pytest.approx(ratios[:len(tight)], rel=1e-12)
    assert len(tight) == min(verify.TIGHTEST, len(ratios))
    assert all(t["unit"] == ERROR_UNITS[t["quantity"]] for t in tight)
    for case in doc["cases"]:
        own = [c["error"] / c["limit"] for c in case["checks"]]
        assert case["worst_ratio"] == pytest.approx(max(own), rel=1e-12)


def test_the_first_screen_holds_the_verdict_and_the_margins(report):
    _, out = report
    page = (out / "report.html").read_text()
    verdict = page.index("PASSED: ")
    margins = page.index("Tightest margins")
    first_fold = page.index("<details")
    assert verdict < margins < first_fold
    # the case details and the long tables fold away
    assert page.count("<details") >= len(NAMES) + 3


def test_every_error_and_limit_carries_its_unit_and_every_unit_is_defined(report):
    doc, _ = report
    for case in doc["cases"]:
        head, rows = render._checks(case)
        i_err, i_lim = head.index("error"), head.index("limit")
        for row, check in zip(rows, case["checks"]):
            unit = ERROR_UNITS[check["quantity"]]
            assert row[i_err].endswith(f" {unit}") and row[i_lim].endswith(f" {unit}"), row
    text = "\n".join(render._how_to_read(doc))
    used = {ERROR_UNITS[c["quantity"]] for case in doc["cases"] for c in case["checks"]}
    for unit in used:
        assert f"{unit}: {NORMALISATION[unit]}" in text
    assert "4PA/b = 1" in text
    head, _ = render._results(doc["cases"][0])
    assert all(re.search(r"\[.+\]$", h) for h in head[1:]), head


def test_the_case_past_lift_off_is_refused_correctly_and_judged_against_the_sie(report):
    doc, out = report
    case = next(c for c in doc["cases"] if c["name"] == "beyond_edge_on_flat")
    assert case["reference"] == "sie" and "closedform" not in case["results"]
    assert [c["comparison"] for c in case["checks"]][0] == "refusal"
    _, rows = render._case_lines(doc, beyond=True)
    assert rows == [[case["name"], case["description"], "refuses, correctly (LiftOffError)", "pass",
                     render._used(case["worst_ratio"])]]
    assert "Beyond the closed form" in (out / "report.md").read_text()


def test_a_closed_form_that_answers_past_its_framework_fails_the_case(tmp_path, monkeypatch):
    install_fakes(monkeypatch)   # this fake closed form answers everything
    case = catalogue.get_case("beyond_edge_on_flat")
    assert verify.main(mode="quick", out=tmp_path / "rep", cases=[case], quiet=True) == 1
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert doc["summary"]["failed"] == ["beyond_edge_on_flat/refusal/closedform"]


@pytest.mark.parametrize("errors, monotone", [
    ([1e-2, 3e-3, 1e-3, 2e-4], True),
    ([3.6e-3, 2.5e-4, 3.3e-4], False),           # the FEM's a on quick -> default -> fine, today
    ([1e-3, 1e-3], False),
    ([1e-3, 1e-6, 1e-15, 1e-15], True),          # round-off ends the sequence
    ([5e-3], False),
])
def test_an_order_needs_a_monotone_sequence(errors, monotone):
    assert is_monotone(errors) is monotone


def test_a_study_prints_no_order_for_a_sequence_that_is_not_monotone():
    st = {"param": "h", "values": [0.1, 0.05, 0.025], "labels": ["30", "60", "120"],
          "errors": {"a": [3.6e-3, 2.5e-4, 3.3e-4]}, "orders": {"a": None}, "gci": {}, "notes": []}
    head, rows = render._study(st)
    assert rows[-1] == ["observed order", "", "not monotone"]

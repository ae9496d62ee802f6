"""The robustness study of ``threepart verify --full`` (:mod:`reports.verify.robustness`, issue 29).

A small draw runs here and yields one check per rule, each against its row of the
tolerance table; a planted wrong answer (the SIE's ``c`` moved by ten times the
table's limit on one draw) fails exactly its rule and names that draw; the seeded
draw is reproducible and covers the ranges the module promises; the verification
run adds the study in its full mode only, and the report carries it.
"""
from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import pytest

from threepart.reports.verify import render, robustness
from threepart.reports.verify import report as verify
from threepart.reports.verify.runs import MODES
from threepart import closedform
from threepart.tolerances import tolerance

#: a small draw: every group and every rule reached, in a few seconds
SMALL = {"normal": 12, "slip": 6, "fretting": 2}
#: the planted error of the SIE's c, in units of the table's limit of the contact ends
PLANT = 10


def test_small_study_gives_one_check_per_rule_against_the_table():
    run = robustness.study(SMALL)
    assert [c.quantity for c in run.checks] == list(robustness.RULES)
    assert {c.comparison for c in run.checks} == {"robustness"}
    for c in run.checks:
        assert c.limit == tolerance("robustness", c.quantity).limit
        assert c.passed, f"{c.quantity}: {c.error} > {c.limit}: {c.reason}"
    assert run.passed and run.case.name == "robustness_study"
    assert "seed 29: 12 normal, 6 slip, 2 fretting draws" in run.case.description


class _Shifted:
    """A normal result whose ``c`` is moved by ``dc``; every other attribute is the result's own."""

    def __init__(self, res: Any, dc: float) -> None:
        self._res, self.c = res, res.c + dc

    def __getattr__(self, name: str) -> Any:
        return getattr(self._res, name)


def _planted_draw() -> Any:
    """The first normal draw whose closed-form contact lies within the paper (the SIE's will too)."""
    for case in robustness.draws("normal", SMALL["normal"]):
        try:
            if closedform.solve_normal(case.punch, case.P, case.s, A=case.A, tilt=case.tilt).within_paper:
                return case
        except ValueError:
            continue
    raise AssertionError("no normal draw within the paper")


def test_a_planted_wrong_answer_fails_exactly_its_check_and_names_the_draw(monkeypatch):
    target = _planted_draw()
    dc = PLANT * tolerance("robustness", "a").limit
    real = robustness.solvers

    def normal(method: str, case: Any, **kw: Any) -> Any:
        res = real.normal(method, case, **kw)
        return _Shifted(res, dc * (res.a + res.c)) if method == "sie" and case.name == target.name else res

    monkeypatch.setattr(robustness, "solvers", SimpleNamespace(
        normal=normal, slip=real.slip, fretting=real.fretting))
    run = robustness.study({"normal": SMALL["normal"]})
    assert [c.quantity for c in run.failed()] == ["a"]
    bad = run.failed()[0]
    # the planted shift, less the closed form's own rounding against the SIE (a limit's worth)
    assert abs(bad.error - dc) <= tolerance("robustness", "a").limit
    assert f"first offending draw {target.name}: {robustness.reproduce(target)}" in bad.reason
    assert target.name in run.case.description and run.case.punch == target.punch


@pytest.mark.parametrize("group", ["normal", "slip", "fretting"])
def test_the_seeded_draw_is_reproducible_and_covers_its_ranges(group):
    first, again = robustness.draws(group, 40), robustness.draws(group, 40)
    assert first == again
    assert robustness.draws(group, 40, seed=robustness.SEED + 1) != first
    for case in first:
        p = case.punch
        assert robustness.R_LOW <= min(p.R1, p.R2) and max(p.R1, p.R2) <= robustness.R_HIGH
        threshold = closedform.P_min(p, case.A)
        assert case.P > max(threshold, 0.0)
        if case.tilt == "suppressed":
            assert case.s == 0.0
        if group != "normal":
            assert case.f is not None and case.Q is not None and abs(case.Q) < case.f * case.P
            assert (case.Q > 0) if group == "fretting" else True
    if group == "fretting":
        assert all(c.sigma_bulk != 0.0 and c.cycle for c in first)
    if group == "slip":     # with and without a bulk stress
        assert {c.sigma_bulk == 0.0 for c in first} == {True, False}
    assert {c.tilt for c in first} == {"free", "suppressed"}
    assert {math.isinf(c.punch.R) for c in first} == {True, False}


def test_verify_adds_the_study_in_the_full_mode_only_and_reports_it(monkeypatch, tmp_path):
    monkeypatch.setattr(robustness, "COUNTS", {"normal": 3, "slip": 2})
    said: list[str] = []
    runs, _, timings = verify.run(MODES["default"], [], said.append, robustness=True)
    assert runs == [] and "robustness_study_s" not in timings
    runs, studies, timings = verify.run(MODES["full"], [], said.append, robustness=True)
    assert [r.case.name for r in runs] == ["robustness_study"] and "robustness_study_s" in timings
    assert any(line.startswith("[study] robustness PASS") for line in said)
    doc = verify.build_report(MODES["full"], runs, studies, timings, {})
    verify.validate(doc)
    assert doc["passed"] and doc["summary"]["checks"] == len(robustness.RULES)
    assert doc["summary"]["by_comparison"]["robustness"]["failed"] == 0
    md = render.markdown(doc)
    assert "robustness_study" in md and "wrong_refusals" in md

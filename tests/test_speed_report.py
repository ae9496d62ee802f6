"""The verification report's speed section (issue 33): measured in the run, rendered with its targets.

No timing is asserted (the machine is shared): the section must render every
target, and the record must hold the closed form's forward evaluations per case,
a count, within its target, and the batch's answers equal to the naive fsolve's, on the library's
formulas and on its own transcription of the printed equations.
"""
from __future__ import annotations

from threepart.reports.verify import render
from threepart.reports.verify.runs import MODES
from threepart.reports.verify.speed import TARGETS, speed_record, speed_section
from threepart.reports.verify import build_report, validate
from threepart.tolerances import tolerance

#: fsolve's xtol is 1e-13 on (a, c); the closed form is exact to rounding
FSOLVE = tolerance("closedform", "round_off").limit


def test_the_speed_section_renders_every_target_and_the_load():
    doc = build_report(MODES["quick"], [], [], {}, {})
    doc["speed"] = speed_record(quick=True)
    validate(doc)
    md = render.markdown(doc)
    assert "## Speed" in md and "load average" in md
    for label, op, target in TARGETS.values():
        assert label in md and f"{op} {target:g}" in md
    figures = doc["speed"]["figures"]
    assert figures["evaluations_per_case"] <= TARGETS["evaluations_per_case"][2]
    assert figures["batch_vs_naive_a"] <= FSOLVE
    # the printed equations, transcribed apart from the library (sign of P corrected), give the same a
    assert figures["batch_vs_naive_paper_a"] <= FSOLVE
    assert doc["speed"]["targets"]["evaluations_per_case"]["met"]


def test_no_speed_record_no_section():
    assert speed_section(build_report(MODES["quick"], [], [], {}, {})) is None

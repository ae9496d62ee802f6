"""The one case catalogue: each suite holds what its readers need, and every case is admissible."""
from __future__ import annotations

import json

import pytest

from threepart import closedform, rigid_punch, sie
from threepart.problem.catalogue import CASES_FILE, SUITES, get_case, load_cases, slip_loads
from threepart.tolerances import tolerance

CASES = load_cases(None)
#: a case within 10 % of the lift-off lever arm tests the closed form at its framework's edge
NEAR_LIFT_OFF = 0.9
#: "a few hundred MPa": the bulk stress of a dovetail flank's disc under the centrifugal load (MPa)
BULK_MPA = (100.0, 1000.0)


def test_verification_suite_covers_every_punch_kind_and_load():
    cases = load_cases("verify")
    inside = [c for c in cases if not c.beyond]
    assert len(inside) >= 11
    # past the framework: both lift-off regimes and a stick zone on the centre
    assert {c.closedform_refuses for c in cases if c.beyond} == {"LiftOffError", "StickZoneError"}
    assert {"general", "A", "B", "C", "Hertz"} <= {c.punch.case for c in cases}
    assert any(c.tilt == "suppressed" for c in cases)
    assert any(c.s_lift_off_fraction and c.s_lift_off_fraction > NEAR_LIFT_OFF for c in cases)
    assert sorted(c.Q_over_fP for c in inside if c.kind == "slip" and not c.sigma_bulk) == [0.2, 0.4, 0.7]
    # a flank under a bulk stress of a few hundred MPa (issue 21), in the closed form's framework
    assert any(c.kind == "slip" and c.material and BULK_MPA[0] <= c.sigma_bulk <= BULK_MPA[1] for c in inside)
    sym = get_case("caseA_sym")
    assert sym.punch.R1 == sym.punch.R2 == 10.0 and sym.punch.b == 1.0
    assert sym.material == (210e3, 0.3) and sym.bodies == "rigid punch" and sym.A == rigid_punch(210e3, 0.3)
    assert sym.load_4PA_over_b == pytest.approx(1.0, rel=tolerance("catalogue", "paper_load").limit)


def test_fem_suite_is_the_normal_part_of_the_verification():
    fem = {c.name for c in load_cases("fem")}
    verify_normal = {c.name for c in load_cases("verify") if c.kind == "normal" and not c.beyond}
    assert fem == verify_normal
    assert all(c.material is not None for c in load_cases("fem")), "the FEM needs E and nu"


def test_sie_suite_is_nondimensional():
    cases = load_cases("sie")
    assert len(cases) == 9
    assert {"general", "A", "B", "C", "Hertz"} <= {c.punch.case for c in cases}
    assert all(c.material is None for c in cases)
    assert {c.A for c in cases} == {1.0, 1.5}
    with pytest.raises(ValueError, match="nondimensional"):
        _ = cases[0].E
    loads = slip_loads("sie")
    assert loads and all(0 < abs(q) < 1 and f > 0 for q, f in loads), "partial slip needs |Q| < fP"
    assert {q > 0 for q, _ in loads} == {True, False}, "both directions of the shear load"


def test_every_case_names_known_suites_and_names_are_unique():
    raw = json.loads(CASES_FILE.read_text(encoding="utf-8"))["cases"]
    assert len(CASES) == len(raw) == len({c["name"] for c in raw})
    assert all(c.suites and set(c.suites) <= set(SUITES) for c in CASES)
    with pytest.raises(ValueError, match="`suite`"):
        load_cases("bench")


def test_a_case_needs_one_of_material_and_compliance(tmp_path):
    data = json.loads(CASES_FILE.read_text(encoding="utf-8"))
    nondimensional = next(c for c in reversed(data["cases"]) if "A" in c)
    data["cases"] = [dict(nondimensional, material={"E": 4000.0, "nu": 0.0})]
    data["cases"][0].pop("A")
    ok = tmp_path / "ok.json"
    ok.write_text(json.dumps(data))
    assert load_cases(None, ok)[0].A == 1e-3       # two similar bodies: 4 (1 - 0) / 4000
    data["cases"][0]["A"] = 1.0
    both = tmp_path / "both.json"
    both.write_text(json.dumps(data))
    with pytest.raises(ValueError, match="exactly one"):
        load_cases(None, both)


@pytest.mark.parametrize("case", [c for c in CASES if c.s_max is not None], ids=lambda c: c.name)
def test_stored_lift_off_lever_arm_is_the_sies(case):
    """The stored lever arm (the closed form's) against the SIE's lift-off, an independent exact root."""
    _, s_max = sie.lift_off(case.punch, case.P, case.A)
    assert case.s_max == pytest.approx(s_max, rel=tolerance("catalogue", "stored_lift_off").limit)


@pytest.mark.parametrize("case", [c for c in CASES if c.beyond], ids=lambda c: c.name)
def test_every_case_past_the_framework_is_refused_by_the_closed_form(case):
    from threepart import errors

    case = case.resolved()
    with pytest.raises(getattr(errors, case.closedform_refuses)):
        res = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        closedform.solve_partial_slip(res, *case.shear_load)


@pytest.mark.parametrize("case", [c for c in CASES if not c.beyond], ids=lambda c: c.name)
def test_every_case_is_admissible(case):
    case = case.resolved()
    lim = closedform.lift_off(case.punch, case.P, case.A)
    res = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
    assert lim.s_min < res.s < lim.s_max
    b = case.punch.b
    assert res.a > b and res.c > b
    if case.kind == "slip":
        slip = closedform.solve_partial_slip(res, case.Q, case.f)
        lo, hi = slip.stick_zone
        assert -res.a < lo < -b and b < hi < res.c, "stick zone must end in the outer segments"

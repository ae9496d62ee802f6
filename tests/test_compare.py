"""The comparator, the report's schema and the safe writes, on fake solver results."""
from __future__ import annotations

import json
import math
from dataclasses import replace

import pytest

from threepart import catalogue, rigid_punch
from threepart.punch import Punch
from threepart.reports import verify
from threepart.reports.compare import compare
from threepart.tolerances import COMPARISONS, QUANTITIES, TOLERANCES, tolerance

from .fakes import _normal, _slip, fake_solver, install_fakes

PUNCH = Punch(R1=10.0, R2=10.0, b=1.0)
A = rigid_punch(210e3, 0.3)   # rigid punch, steel half-plane, N and mm
P = 28846.0


def _pair(slip: bool = False):
    ref = _normal(PUNCH, P, 0.1, A=A)
    if slip:
        ref = _slip(ref, 0.4 * 0.5 * P, 0.5)
    return ref


def test_table_has_a_reason_for_every_entry():
    for key, tol in TOLERANCES.items():
        assert tol.reason.strip(), key
        assert tol.limit > 0, key
    for cmp in COMPARISONS:
        for q in QUANTITIES:
            assert tolerance(cmp, q).limit > 0


def test_identical_results_pass_everything():
    ref = _pair(slip=True)
    checks = compare(ref, ref, "sie")
    assert [c.quantity for c in checks] == list(QUANTITIES)
    assert all(c.passed for c in checks)
    # a difference of a result with itself is 0; q_integral and q_bound check the result itself
    assert all(c.error == 0 for c in checks if c.quantity not in ("q_integral", "q_bound"))
    integral = next(c for c in checks if c.quantity == "q_integral")
    assert integral.reference == ref.Q and integral.error < 1e-12   # closed form: quadrature only


def _perturb(ref, quantity: str, size: float):
    """``ref`` with exactly one figure moved by ``size`` (normalised as in the table)."""
    n = ref.normal if hasattr(ref, "normal") else ref
    W = n.a + n.c
    if quantity in ("a", "c"):
        n = replace(n, **{quantity: getattr(n, quantity) + size * W})
    elif quantity == "alpha":
        scale = float(n.punch.slope(n.c) - n.punch.slope(-n.a))
        n = replace(n, alpha=n.alpha + size * scale)
    elif quantity == "P":
        n = replace(n, P=n.P * (1 + size))  # the field scales by the same tiny factor
    elif quantity == "s":
        n = replace(n, s=n.s + size * W)
    elif quantity == "p_right":
        n = replace(n, peak_shift=size)
    elif quantity == "p_interior_max":
        n = replace(n, bump=size)
    elif quantity in ("d", "e"):
        return replace(ref, **{quantity: getattr(ref, quantity) + size * ref.d})
    else:  # pragma: no cover
        raise AssertionError(quantity)
    return replace(ref, normal=n) if hasattr(ref, "normal") else n


def _p_separable(comparison):
    """P moves the pressure too: it is only separable when 3x its limit stays inside the field tolerance."""
    return 3 * tolerance(comparison, "P").limit < 0.3 * tolerance(comparison, "p_L2").limit


PERTURBATIONS = [(comp, q) for comp in COMPARISONS
                 for q in ("a", "c", "alpha", "s", "p_right", "p_interior_max")]
PERTURBATIONS += [(comp, "P") for comp in COMPARISONS if _p_separable(comp)]
PERTURBATIONS += [("sie", "d"), ("sie", "e")]          # only the SIE solves partial slip


@pytest.mark.parametrize("comparison,quantity", PERTURBATIONS)
def test_a_perturbed_result_fails_that_tolerance_only(comparison, quantity):
    ref = _pair(quantity in ("d", "e"))
    limit = tolerance(comparison, quantity).limit
    size = 3 * limit
    bad = _perturb(ref, quantity, size)
    # below the limit the same perturbation passes
    ok = _perturb(ref, quantity, 0.3 * limit)
    failed = [c.quantity for c in compare(ref, bad, comparison) if not c.passed]
    assert failed == [quantity], f"{quantity} perturbed by {size:g}: failed {failed}"
    assert all(c.passed for c in compare(ref, ok, comparison))


def test_nan_never_passes():
    ref = _pair()
    bad = replace(ref, alpha=math.nan)
    failed = [c.quantity for c in compare(ref, bad, "sie") if not c.passed]
    assert failed == ["alpha"]


def test_a_normal_result_is_compared_only_with_the_normal_part_of_a_slip_case():
    ref = _pair(slip=True)
    checks = compare(ref, ref.normal, "fem-quick")
    assert {c.quantity for c in checks}.isdisjoint({"d", "e", "q_L2"})


# ---------------------------------------------------------------------------------------
# the verification run on fake solvers: schema, exit status, safe writes
# ---------------------------------------------------------------------------------------
@pytest.fixture
def fake_solvers(monkeypatch):
    install_fakes(monkeypatch)
    cases = [c for c in catalogue.load_cases() if c.name in ("caseA_sym", "slip_Q0.4", "caseA_moment")]
    monkeypatch.setattr(verify, "STUDY_CASE", "caseA_moment")
    return cases


def test_report_json_validates_against_its_schema(tmp_path, fake_solvers):
    import jsonschema
    out = tmp_path / "rep"
    status = verify.main(mode="default", out=out, cases=fake_solvers, quiet=True)
    doc = json.loads((out / "report.json").read_text())
    jsonschema.validate(doc, verify.load_schema())
    assert status == 0 and doc["passed"]
    assert {p.name for p in (out / "plots").iterdir()} >= {"caseA_sym_overlay.png", "sie_plain_caseA_moment_convergence.png",
                                                            "fem_caseA_moment_convergence.png"}
    html = (out / "report.html").read_text()
    assert "data:image/png;base64," in html and 'src="plots/' not in html
    assert doc["environment"]["packages"]["numpy"]
    # a broken document does not validate
    doc["cases"][0]["checks"][0]["passed"] = "yes"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(doc, verify.load_schema())


def test_failed_tolerance_gives_nonzero_exit(tmp_path, fake_solvers, monkeypatch):
    fake = fake_solver("sie")
    fake = replace(fake, normal=lambda *a, **k: replace(fake.normal(*a, **k), alpha=1e-3))
    install_fakes(monkeypatch, sie=fake)
    status = verify.main(mode="quick", out=tmp_path / "rep", cases=fake_solvers, quiet=True)
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert status == 1 and not doc["passed"]
    assert all(f.endswith("/sie/alpha") for f in doc["summary"]["failed"])


def test_solver_error_is_reported_not_raised(tmp_path, fake_solvers, monkeypatch):
    def broken(*args, **options):
        raise ImportError("fem not built")

    install_fakes(monkeypatch, fem=replace(fake_solver("fem"), normal=broken))
    status = verify.main(mode="quick", out=tmp_path / "rep", cases=fake_solvers, quiet=True)
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert status == 1 and doc["summary"]["errors"] == len(fake_solvers)

"""The comparator, the report's schema and the safe writes, on fake solver results."""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace

import numpy as np

import pytest

from threepart import closedform as cf
from threepart.closedform import FrettingSolution
from threepart.problem import catalogue
from threepart import rigid_punch
from threepart.problem.punch import Punch
from threepart.reports.verify import report as verify
from threepart.reports.compare import compare
from threepart.tolerances import (COMPARISONS, FRETTING_QUANTITIES, NORMAL_QUANTITIES, QUANTITIES, STRESS_QUANTITIES,
                                  SLIP_QUANTITIES, TOLERANCES, tolerance)

from .fakes import _normal, _slip, fake_solver, install_fakes, unrendered

PUNCH = Punch(R1=10.0, R2=10.0, b=1.0)
A = rigid_punch(210e3, 0.3)   # rigid punch, steel half-plane, N and mm
P = 28846.0
#: ∫q dx of the fake's Ciavarella–Jäger shear by the comparator's Gauss rule: exact up to rounding
GAUSS_ROUND_OFF = 1e-12


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
    assert integral.reference == ref.Q and integral.error < GAUSS_ROUND_OFF   # closed form: quadrature only


#: a perturbation "just over" and "just under" a tolerance: every normalised size below is exact
#: to better than 1e-3 of itself (scalars exactly; fields up to the comparator's 4001-point grid)
OVER, UNDER = 1.1, 0.9


def _perturb(ref, quantity: str, size: float):
    """``ref`` with exactly one compared figure moved by ``size`` (normalised as in the table).

    ``ref`` is a fake normal or slip result (:mod:`tests.fakes`) or a closed-form
    fretting cycle (:func:`_cycle`); each move is built from the normalisation
    written in :mod:`threepart.tolerances`, not from the comparator.
    """
    if quantity in FRETTING_QUANTITIES:
        return _perturb_cycle(ref, quantity, size)
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
    elif quantity == "p_left":
        n = replace(n, left_shift=size)
    elif quantity == "p_right":
        n = replace(n, peak_shift=size)
    elif quantity in ("x_left", "x_right"):
        n = replace(n, x_shifts=(size, 0.0) if quantity == "x_left" else (0.0, size))
    elif quantity == "p_interior_max":
        n = replace(n, bump=size)
    elif quantity == "p_L2":
        n = replace(n, edge_bump=size)
    elif quantity in ("d", "e"):
        return replace(ref, **{quantity: getattr(ref, quantity) + size * ref.d})
    elif quantity == "q_interior_max":
        return replace(ref, bumps=size)
    elif quantity == "q_L2":
        return replace(ref, edge_dip=size)
    elif quantity == "q_integral":
        # the shear is unchanged (its stick zone is d0, e0), so ∫q dx = Q_old: |Q_old - Q| / Q = size
        return replace(ref, Q=ref.Q / (1 - size))
    elif quantity == "q_bound":
        return replace(ref, bound_bump=size)
    else:  # pragma: no cover
        raise AssertionError(quantity)
    return replace(ref, normal=n) if hasattr(ref, "normal") else n


@dataclass(frozen=True)
class _BumpedCycle(FrettingSolution):
    """A closed-form cycle whose shear at ``Q_max`` (loading) carries a bump of ``bump`` max|q|."""

    bump: float = 0.0

    def shear(self, x, Q, branch):
        q = super().shear(x, Q, branch)
        if self.bump and branch == "loading" and Q == self.Q_max:
            n = self.normal
            mid = 0.5 * (n.c - n.a)     # the middle of the contact: a point of the comparator's grid
            q = q + self.bump * _q_peak(self) * np.exp(-(((np.asarray(x) - mid) / (0.01 * n.width)) ** 2))
        return q


def _q_peak(cycle) -> float:
    """max|q| at Q_max on loading: at a stick-zone end, where the slip zone's q = f p is smooth."""
    n = cycle.normal
    x = np.linspace(-n.a, n.c, 200001)
    return float(np.max(np.abs(FrettingSolution.shear(cycle, x, cycle.Q_max, "loading"))))


def _cycle():
    """A correct fretting cycle: the closed form's, three states a branch (the cycle figures' reference)."""
    normal = cf.solve_normal(PUNCH, P, 0.1, A=A)
    cyc = cf.fretting_cycle(normal, 0.4 * 0.5 * P, 0.5, states=3)
    return _BumpedCycle(**{k: getattr(cyc, k) for k in cyc.__dataclass_fields__})


def _perturb_cycle(ref, quantity: str, size: float):
    """The closed-form cycle with one cycle figure moved by ``size`` (normalised as in the table)."""
    mid = 4              # the unloading branch's middle state (Q = 0), not a loop tip
    if quantity == "energy":
        return replace(ref, energy=ref.energy * (1 + size))
    if quantity == "stick":
        tip = int(np.flatnonzero(ref.branch == "loading")[-1])
        d_max = 0.5 * float(ref.stick[tip, 1] - ref.stick[tip, 0])
        stick = np.array(ref.stick, dtype=float)
        stick[mid, 0] -= size * d_max
        return replace(ref, stick=stick)
    if quantity == "loop":
        _, h = ref.loop()
        delta = np.array(ref.delta, dtype=float)
        delta[mid] += size * float(np.max(np.abs(h)))
        return replace(ref, delta=delta)
    if quantity == "q_states":
        return replace(ref, bump=size)
    raise AssertionError(quantity)  # pragma: no cover


def _p_separable(comparison):
    """P moves the pressure too: it is only separable when OVER x its limit stays inside the field tolerance."""
    return OVER * tolerance(comparison, "P").limit < UNDER * tolerance(comparison, "p_L2").limit


COMPARED = NORMAL_QUANTITIES + SLIP_QUANTITIES + FRETTING_QUANTITIES
PERTURBATIONS = [(comp, q) for comp in COMPARISONS for q in COMPARED
                 if q != "P" or _p_separable(comp)]


@pytest.fixture(scope="module")
def cycle():
    return _cycle()


def test_every_compared_quantity_is_perturbed():
    assert len(COMPARED) == 21
    assert {q for _, q in PERTURBATIONS} == set(COMPARED)


@pytest.mark.parametrize("comparison,quantity", PERTURBATIONS)
def test_a_perturbed_result_fails_that_tolerance_only(comparison, quantity, cycle):
    if quantity in FRETTING_QUANTITIES:
        ref = cycle
    else:
        ref = _pair(quantity in SLIP_QUANTITIES)
    limit = tolerance(comparison, quantity).limit
    bad = _perturb(ref, quantity, OVER * limit)
    ok = _perturb(ref, quantity, UNDER * limit)    # just below the limit the same move passes
    checks = _traction_checks(ref, bad, comparison)
    failed = [c.quantity for c in checks if not c.passed]
    assert failed == [quantity], f"{quantity} perturbed by {OVER} x {limit:g}: failed {failed}"
    error = next(c.error for c in checks if c.quantity == quantity)
    assert limit < error < OVER**2 * limit, f"{quantity}: error {error:g} is not just over {limit:g}"
    assert all(c.passed for c in _traction_checks(ref, ok, comparison)), \
        [(c.quantity, c.error, c.limit) for c in _traction_checks(ref, ok, comparison) if not c.passed]


def _traction_checks(ref, other, comparison):
    """The checks of every figure but the stresses, which follow the tractions they come from.

    A moved shear field moves the stress field with it; the stress figures are
    perturbed on their own in tests/test_stress_compare.py.
    """
    checks = compare(ref, other, comparison, stresses=False)    # compare's own switch: the same list
    assert not {c.quantity for c in checks} & set(STRESS_QUANTITIES)
    return checks


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


def test_report_json_validates_against_its_schema(tmp_path, fake_solvers, monkeypatch):
    import jsonschema

    from threepart.fretting_wear import wear_case
    from threepart.reports.verify.speed import speed_record
    from threepart.reports.verify.wear_section import WEAR_CASE, study_record

    # the default mode's two extra records, each of the same shape, made small: the speed ratios at
    # the quick sizes (tests/test_speed_report.py), and the catalogue's wear case over 1000 cycles
    # (its whole march, 26 s, is threepart verify's, and the slow test_cli_wear.py's over 2e5 cycles)
    monkeypatch.setattr(verify, "speed_record", lambda quick, say=None: speed_record(True, say))
    monkeypatch.setattr(verify, "wear_study", lambda root, say: study_record(
        wear_case(WEAR_CASE).run(cycles=1000), root, WEAR_CASE, 0.0))
    out = tmp_path / "rep"
    status = verify.main(mode="default", out=out, cases=fake_solvers, quiet=True)
    doc = json.loads((out / "report.json").read_text())
    jsonschema.validate(doc, verify.load_schema())
    assert status == 0 and doc["passed"]
    assert doc["speed"]["figures"] and doc["wear"]["case"] == WEAR_CASE     # the default mode's records
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
    unrendered(monkeypatch)
    status = verify.main(mode="quick", out=tmp_path / "rep", cases=fake_solvers, quiet=True)
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert status == 1 and not doc["passed"]
    assert all(f.endswith("/sie/alpha") for f in doc["summary"]["failed"])


def test_solver_error_is_reported_not_raised(tmp_path, fake_solvers, monkeypatch):
    def broken(*args, **options):
        raise ImportError("fem not built")

    install_fakes(monkeypatch, fem=replace(fake_solver("fem"), normal=broken))
    unrendered(monkeypatch)
    status = verify.main(mode="quick", out=tmp_path / "rep", cases=fake_solvers, quiet=True)
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert status == 1 and doc["summary"]["errors"] == len(fake_solvers)

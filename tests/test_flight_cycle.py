"""The flight cycle: its catalogue case, the fatigue parameters of its steady state, its comparison.

References: the closed form's own classification (eq. S12: both ends slip); the
fretting cycle's Masing states, whose fatigue parameters threepart computes from
another result type (eq. S14: at ``P``, ``s`` constant the steady cycle is the
fretting cycle); the tolerance table, perturbed as tests/test_compare.py does.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from threepart import closedform as cf
from threepart.problem import catalogue
from threepart.fatigue import fatigue
from threepart.problem.punch import Punch
from threepart.reports.compare import compare
from threepart.reports.verify.flight import HISTORY_QUANTITIES, history_checks
from threepart.tolerances import STEADY_QUANTITIES, tolerance

#: the perturbation's factors on a tolerance, as tests/test_compare.py: over fails, under passes
OVER, UNDER = 3.0, 0.3
CASE = "fan_blade_flight_cycle"


def test_the_flight_case_loads_and_lies_where_the_closed_form_holds():
    case = catalogue.get_case(CASE)
    assert case.kind == "steady" and case in catalogue.load_cases("verify")
    (P0, s0, Q0, g0), (P1, s1, Q1, g1) = case.states
    # in phase about the running loads of the flank with a bulk stress, as the description says
    bulk = catalogue.get_case("fan_blade_flank_bulk")
    means = [(P0 + P1) / 2, (s0 + s1) / 2, (Q0 + Q1) / 2, (g0 + g1) / 2]
    assert means == pytest.approx([bulk.P, bulk.s, bulk.Q, bulk.sigma_bulk],
                                  rel=tolerance("steady", "round_off").limit)
    assert P1 > P0 and s1 > s0 and Q1 > Q0 and g1 > g0
    r = cf.steady_state(case.punch, case.states, case.f, A=case.A)
    lo, hi = max(-n.a for n in r.normals), min(n.c for n in r.normals)
    left, right = r.stick_zone
    assert not r.shakedown and lo < left < right < hi and r.energy > 0     # both ends slip (S12)


@pytest.mark.parametrize("states,match", [
    ([[1485.0, 0.27, 432.0, 297.0]], r"`states` must be a list of 2 states"),
    ([[1485.0, 0.27, 432.0], [1515.0, 0.28, 528.0, 303.0]], r"`states\[0\]` must be a list"),
    ([[1485.0, 0.27, 432.0, 297.0], [-1.0, 0.28, 528.0, 303.0]], r"`states\[1\]\[0\] \(P\)` = -1.0 must be > 0"),
    ([[1485.0, 0.27, "x", 297.0], [1515.0, 0.28, 528.0, 303.0]], r"`states\[0\]\[2\]`"),
])
def test_bad_states_are_named(tmp_path, states, match):
    case = {"name": "bad", "suites": ["verify"], "punch": {"R1": 6.0, "R2": 4.0, "b": 1.0}, "P": 1500.0, "A": 1e-5,
            "s": 0.0, "f": 0.8, "states": states}
    path = tmp_path / "cases.json"
    path.write_text(json.dumps({"cases": [case]}), encoding="utf-8")
    with pytest.raises(ValueError, match=match):
        catalogue.load_cases(None, path)


def test_states_need_a_friction_coefficient(tmp_path):
    case = {"name": "nof", "suites": ["verify"], "punch": {"R1": 6.0, "R2": 4.0, "b": 1.0}, "P": 1500.0, "A": 1e-5,
            "states": [[1485.0, 0.0, 432.0, 0.0], [1515.0, 0.0, 528.0, 0.0]]}
    path = tmp_path / "cases.json"
    path.write_text(json.dumps({"cases": [case]}), encoding="utf-8")
    with pytest.raises(ValueError, match=r"`states` \(a cycle\) needs the coefficient of friction `f`"):
        catalogue.load_cases(None, path)


#: a fretting cycle at P, s constant (case A, a moment, a bulk stress) and its steady state (eq. S14)
PUNCH, A, F, P, S, QMAX, SIGMA = Punch(R1=10.0, R2=5.0, b=1.0), 1e-5, 0.5, 400.0, 0.1, 80.0, 20.0


def test_the_steady_cycle_at_constant_load_has_the_fatigue_of_the_fretting_cycles_extremes():
    """fatigue(steady) = fatigue(fretting cycle at its Masing states -Q_max and Q_max), to round-off."""
    normal = cf.solve_normal(PUNCH, P, S, A=A)
    cyc = cf.fretting_cycle(normal, QMAX, F, sigma_bulk=SIGMA, states=5)
    tips = [int(np.flatnonzero((cyc.branch == "unloading") & np.isclose(cyc.Q, -QMAX))[0]),
            int(np.flatnonzero((cyc.branch == "reloading") & np.isclose(cyc.Q, QMAX))[-1])]
    steady = cf.steady_state(PUNCH, [(P, S, -QMAX, -SIGMA), (P, S, QMAX, SIGMA)], F, A=A)
    W = normal.a + normal.c
    x = np.linspace(-normal.a - 0.2 * W, normal.c + 0.2 * W, 21)
    z = np.array([0.0, 0.02 * W, 0.2 * W])[:, None]
    line = np.linspace(-normal.a, normal.c, 41)
    E = 4 / A
    a = fatigue(steady, x, z, E=E, surface=line)
    b = fatigue(cyc, x, z, E=E, states=tips, surface=line)
    assert a.states == b.states == 2
    limit = tolerance("flight", "fatigue").limit
    for pa, pb in ((a.von_mises_range, b.von_mises_range), (a.swt, b.swt), (a.findley, b.findley),
                   (a.ruiz.ffdp, b.ruiz.ffdp), (a.ruiz.fdp, b.ruiz.fdp)):
        scale = float(np.max(np.abs(pb.value)))
        assert np.max(np.abs(pa.value - pb.value)) <= limit * scale, pa.name


def test_a_steady_cycle_takes_no_state_indices():
    steady = cf.steady_state(PUNCH, [(P, S, -QMAX, 0.0), (P, S, QMAX, 0.0)], F, A=A)
    with pytest.raises(ValueError, match=r"`states` = \[0, 1\] selects recorded states"):
        fatigue(steady, 0.0, 0.0, E=1e5, states=[0, 1])


@dataclass
class _Moved:
    """A steady state with one compared figure moved by ``by`` of its normalisation."""

    base: Any
    quantity: str
    by: float

    def __getattr__(self, name: str) -> Any:
        return getattr(self.base, name)

    @property
    def _W(self) -> float:
        return min(n.c for n in self.base.normals) - max(-n.a for n in self.base.normals)

    @property
    def stick_zone(self) -> tuple[float, float]:
        left, right = self.base.stick_zone
        return (left + (self.by * self._W if self.quantity == "stick_ends" else 0.0), right)

    @property
    def energy(self) -> float:
        return self.base.energy * (1 + (self.by if self.quantity == "cycle_energy" else 0.0))

    def shear(self, x: Any, state: int) -> np.ndarray:
        q = np.asarray(self.base.shear(x, state), float)
        if self.quantity != "q_range" or state == 0:
            return q
        # the range q_1 - q_0 moves by `by` of its largest value over the larger contact
        big = max(self.base.normals, key=lambda n: n.a + n.c)
        xs = np.linspace(-big.a, big.c, 4001)
        scale = float(np.max(np.abs(self.base.shear(xs, 1) - self.base.shear(xs, 0))))
        return q + self.by * scale

    def slip_amplitude(self, x: Any) -> np.ndarray:
        d = np.asarray(self.base.slip_amplitude(x), float)
        if self.quantity != "slip_amplitude":
            return d
        return d * (1 + self.by)


@pytest.fixture(scope="module")
def flight():
    case = catalogue.get_case(CASE)
    return cf.steady_state(case.punch, case.states, case.f, A=case.A)


@pytest.mark.parametrize("quantity", STEADY_QUANTITIES)
def test_a_perturbed_steady_state_fails_that_tolerance_only(quantity, flight):
    limit = tolerance("sie", quantity).limit
    bad = compare(flight, _Moved(flight, quantity, OVER * limit), "sie")
    assert [c.quantity for c in bad if not c.passed] == [quantity]
    ok = compare(flight, _Moved(flight, quantity, UNDER * limit), "sie")
    assert all(c.passed for c in ok), [(c.quantity, c.error) for c in ok if not c.passed]


@pytest.fixture(scope="module")
def flight_run():
    """The flight case by every method with a steady state (closed form, SIE) and the SIE's march."""
    from threepart.reports.verify.runs import MODES, run_case

    return run_case(catalogue.get_case(CASE), MODES["quick"], methods=("closedform", "sie"))


@dataclass
class _Shifted:
    """A steady state whose left stick-zone end is moved by ``dl`` and whose energy is scaled by ``k``."""

    base: Any
    dl: float = 0.0
    k: float = 1.0

    @property
    def stick_zone(self) -> tuple[float, float]:
        left, right = self.base.stick_zone
        return left + self.dl, right

    @property
    def d(self) -> float:
        return self.base.d

    @property
    def energy(self) -> float:
        return self.base.energy * self.k


@pytest.mark.parametrize("quantity", HISTORY_QUANTITIES)
def test_a_perturbed_history_check_fails_that_tolerance_only(quantity, flight_run):
    """The marched history judged against a steady state moved by 3x (fails) and 0.3x (passes) a limit."""
    hist, ref = flight_run.histories["sie"], flight_run.results["closedform"]
    limit = tolerance("sie-history", quantity).limit
    h = float(np.max(np.diff(hist.edges)))

    def moved(by: float) -> _Shifted:
        return _Shifted(ref, dl=by * h) if quantity == "stick_end" else _Shifted(ref, k=1 + by)

    assert [c.quantity for c in history_checks(moved(OVER * limit), hist, "sie") if not c.passed] == [quantity]
    assert all(c.passed for c in history_checks(moved(UNDER * limit), hist, "sie"))


@pytest.fixture(scope="module")
def flight_report(tmp_path_factory, flight_run):
    """The report of the flight case alone; its plot drawn up and listed, not rendered (unchecked here)."""
    from threepart.reports.verify import report as verify
    from threepart.reports.verify.runs import MODES

    from .fakes import unrendered

    run = flight_run
    out = tmp_path_factory.mktemp("flight")
    with pytest.MonkeyPatch.context() as mp:
        unrendered(mp)
        doc = verify.write_report(out, MODES["quick"], [run], [], {}, lambda msg: None)   # validates the schema
    return doc, out


def test_the_report_has_the_flight_cycle_with_its_checks_plot_and_hot_spots(flight_report):
    doc, out = flight_report
    (case,) = doc["cases"]
    assert case["kind"] == "steady" and case["passed"] and set(case["results"]) == {"closedform", "sie"}
    judged = [(c["comparison"], c["quantity"]) for c in case["checks"]]
    assert judged == [("sie", q) for q in STEADY_QUANTITIES] + [("sie-history", q) for q in HISTORY_QUANTITIES]
    assert all(c["limit"] == tolerance(c["comparison"], c["quantity"]).limit for c in case["checks"])
    # the tightest margins rank the flight cycle's checks with the rest
    assert {(t["comparison"], t["quantity"]) for t in doc["summary"]["tightest"]} == set(judged)
    assert case["plots"] == [f"plots/{CASE}_steady.png"] and (out / case["plots"][0]).is_file()
    spots = case["fatigue"]["hot_spots"]
    assert set(spots) == {"closedform", "sie"} and case["fatigue"]["states"] == 2
    # the hot spots lie at the slip zones' ends of the smaller contact, where the tractions jump
    ref = case["results"]["closedform"]
    left = -(ref["d"] + ref["e"])
    assert spots["closedform"]["ruiz_ffdp"]["x"] < left
    md = (out / "report.md").read_text(encoding="utf-8")
    assert "Permanent stick zone (mm): closed form [" in md and "state 1: P = 1515 N/mm" in md
    assert "MPa²·mm" in md     # Ruiz's FFDP with its unit


def test_the_reference_dataset_names_the_flight_cycle_it_does_not_hold():
    from threepart.reports import refs

    with pytest.raises(ValueError, match=r"case 'fan_blade_flight_cycle' is a steady case: the reference "
                                         r"dataset holds normal, slip, fretting cases only"):
        refs.reference(catalogue.get_case(CASE))


def test_the_flight_cycles_von_mises_range_and_ruiz_by_hand(flight):
    """The two end states' stresses built from the closed-form tractions (threepart.stress.stress with
    p_k, q_k of eq. S13 and sigma_bulk_k): the von Mises range of their difference, and Ruiz's FFDP
    (max σxx⁺ of the two ends) x (larger |q|) x δ, against fatigue(steady)."""
    from threepart.stress import stress

    case = catalogue.get_case(CASE)
    nu = case.nu
    W = min(n.c for n in flight.normals) + min(n.a for n in flight.normals)
    left, right = flight.stick_zone
    lo, hi = max(-n.a for n in flight.normals), min(n.c for n in flight.normals)
    inner = [np.linspace(lo, left, 7)[1:-1], np.linspace(right, hi, 7)[1:-1]]    # inside both slip zones
    x = np.sort(np.concatenate([np.linspace(-1.1 * W / 2 - 0.1, 1.1 * W / 2 + 0.1, 23), *inner]))
    z = np.array([0.0, 0.01 * W, 0.1 * W])[:, None]
    ends = []
    for k, n in enumerate(flight.normals):
        ends.append(stress(x, z, pressure=n.pressure, shear=lambda t, k=k: flight.shear(t, k), ends=(-n.a, n.c),
                           sigma_bulk=case.states[k][3], nu=nu,
                           kinks=(-case.punch.b, case.punch.b, *flight.stick_zone)))
    dxx, dzz, dxz = (getattr(ends[1], c) - getattr(ends[0], c) for c in ("sxx", "szz", "sxz"))
    dyy = nu * (dxx + dzz)
    vm = np.sqrt(0.5 * ((dxx - dyy) ** 2 + (dyy - dzz) ** 2 + (dzz - dxx) ** 2) + 3 * dxz ** 2)
    res = fatigue(flight, x, z, E=case.E, nu=nu)
    limit = tolerance("flight", "fatigue").limit
    assert np.max(np.abs(res.von_mises_range.value - vm)) <= limit * np.max(vm)
    xs = res.ruiz.x
    top = [stress(xs, 0 * xs, pressure=n.pressure, shear=lambda t, k=k: flight.shear(t, k), ends=(-n.a, n.c),
                  sigma_bulk=case.states[k][3], nu=nu, kinks=(-case.punch.b, case.punch.b, *flight.stick_zone))
           for k, n in enumerate(flight.normals)]
    tension = np.maximum(np.maximum(top[0].sxx, top[1].sxx), 0.0)
    q = np.maximum(np.abs(flight.shear(xs, 0)), np.abs(flight.shear(xs, 1)))
    ffdp = tension * q * flight.slip_amplitude(xs)
    assert np.max(np.abs(res.ruiz.ffdp.value - ffdp)) <= limit * np.max(ffdp)
    assert np.max(ffdp) > 0    # both slip zones' tension is there to be judged

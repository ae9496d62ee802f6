"""The case catalogue is admissible and covers issue 5's list; the study helpers are right."""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import closedform
from threepart.reports import load_cases
from threepart.reports.studies import gci, observed_order

CASES = load_cases()


def test_catalogue_covers_the_issue():
    names = {c.name for c in CASES}
    kinds = {c.punch.case for c in CASES}
    assert {"general", "A", "B", "C", "Hertz"} <= kinds
    assert any(c.tilt == "suppressed" for c in CASES)
    assert any(c.s_lift_off_fraction and c.s_lift_off_fraction > 0.9 for c in CASES)
    assert sorted(c.Q_over_fP for c in CASES if c.kind == "slip") == [0.2, 0.4, 0.7]
    assert {"caseA_sym", "caseA_moment"} <= names
    sym = next(c for c in CASES if c.name == "caseA_sym")
    assert sym.punch.R1 == sym.punch.R2 == 10.0 and sym.punch.b == 1.0
    assert sym.load_4PA_over_b == pytest.approx(1.0, rel=1e-4)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_every_case_is_admissible(case):
    case = case.resolved()
    lim = closedform.lift_off(case.punch, case.P, case.A)
    res = closedform.solve_normal(case.punch, case.P, case.s, A=case.A, tilt=case.tilt)
    assert lim.s_min < res.s < lim.s_max
    b = case.punch.b
    assert res.a > b and res.c > b
    if case.kind == "slip":
        slip = closedform.solve_partial_slip(res, case.Q, case.f)
        lo, hi = slip.stick_zone
        assert -res.a < lo < -b and b < hi < res.c, "stick zone must end in the outer segments"


def test_observed_order_and_gci_on_a_manufactured_sequence():
    h = np.array([0.4, 0.2, 0.1, 0.05])
    f = 1.0 + 0.3 * h**2
    assert observed_order(h, f - 1.0) == pytest.approx(2.0, abs=1e-12)
    assert observed_order(1 / h, f - 1.0, inverse=True) == pytest.approx(2.0, abs=1e-12)
    p, g, fext = gci(f, h)
    assert p == pytest.approx(2.0, rel=1e-8)
    assert fext == pytest.approx(1.0, rel=1e-12)
    assert g == pytest.approx(1.25 * abs(f[-2] - f[-1]) / f[-1] / 3, rel=1e-8)
    # unequal refinement ratios: the iteration still recovers p
    h2 = np.array([0.3, 0.2, 0.07])
    p2, _, fext2 = gci(1.0 + h2**2, h2)
    assert p2 == pytest.approx(2.0, rel=1e-6) and fext2 == pytest.approx(1.0, rel=1e-9)
    # oscillating sequence: no order
    assert math.isnan(gci([1.0, 1.1, 1.05], [0.4, 0.2, 0.1])[0])
    # errors at round-off carry no order
    assert math.isnan(observed_order([8, 16, 32], [1e-16, 2e-16, 1e-16], inverse=True))

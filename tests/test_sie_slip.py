"""Partial slip: Hertz exact, equilibrium and Coulomb, and the closed form's stick zone."""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import sie
from threepart.punch import Punch
from threepart.sie.cases import CASES, SLIP_LOADS
from threepart.sie.tolerances import TOLERANCES as TOL


@pytest.fixture(scope="module")
def normal_A():
    k = CASES["A"]
    return sie.solve_normal(k.punch, k.P, k.s, A=k.A)


@pytest.mark.parametrize("scheme", ["plain", "projected"])
def test_hertz_stick_zone_is_exact(scheme):
    """Hertz: d = a sqrt(1 - |Q|/fP), stick zone centred on the contact centre."""
    R, P, f, Q = 2.0, 3.0, 0.5, -1.1
    normal = sie.solve_normal(Punch(R, R, 0.0), P, 0.2, A=1.0, n=8, scheme=scheme)
    r = sie.solve_partial_slip(normal, Q, f)
    h = 0.5 * (normal.a + normal.c)
    assert r.d == pytest.approx(h * math.sqrt(1 - abs(Q) / (f * P)), rel=1e-13)
    assert r.e == pytest.approx(-0.2, rel=1e-13)
    assert r.n == 8 and r.info["scheme"] == scheme


@pytest.mark.parametrize("Q", [0.3, -0.45])
def test_shear_integrates_to_Q_and_obeys_coulomb(normal_A, Q):
    f = 0.6
    r = sie.solve_partial_slip(normal_A, Q, f)
    x = np.linspace(-normal_A.a, normal_A.c, 20001)
    q, p = r.shear(x), normal_A.pressure(x)
    assert np.trapezoid(q, x) == pytest.approx(Q, rel=1e-6)
    assert np.all(np.sign(q[np.abs(q) > 1e-12]) == np.sign(Q))
    assert np.all(np.abs(q) <= f * p + 1e-9 * p.max())  # |q| <= f p everywhere
    lo, hi = r.stick_zone
    slip = (x < lo) | (x > hi)
    np.testing.assert_allclose(np.abs(q[slip]), f * p[slip], atol=1e-14)
    assert normal_A.a > r.d + r.e and r.d - r.e < normal_A.c


def test_zero_shear_sticks_everywhere(normal_A):
    r = sie.solve_partial_slip(normal_A, 0.0, 0.5)
    assert r.stick_zone == pytest.approx((-normal_A.a, normal_A.c), rel=1e-13)
    assert np.all(r.shear(np.linspace(-1, 1, 7)) == 0)


def test_stick_zone_of_plain_scheme_converges(normal_A):
    ref = sie.solve_partial_slip(normal_A, 0.3, 0.6)
    normal = sie.solve_normal(CASES["A"].punch, 1.0, 0.1, A=1.0, n=512, scheme="plain")
    r = sie.solve_partial_slip(normal, 0.3, 0.6)
    assert r.d == pytest.approx(ref.d, rel=1e-5) and r.e == pytest.approx(ref.e, abs=1e-5 * ref.d)


@pytest.mark.parametrize("Q, f, match", [
    (0.7, 0.7, r"`Q` = 0.7 must satisfy \|Q\| < f P = 0.7"),
    (0.1, 0.0, "`f` = 0.0 must be > 0"),
    (math.nan, 0.5, "`Q`"),
    (0.495, 0.5, "does not contain the central segment"),
])
def test_bad_input_is_refused(normal_A, Q, f, match):
    with pytest.raises(ValueError, match=match):
        sie.solve_partial_slip(normal_A, Q, f)


def test_outer_ends_can_be_waived(normal_A):
    r = sie.solve_partial_slip(normal_A, 0.495, 0.5, outer_ends=False)
    lo, hi = r.stick_zone
    assert not (lo < -0.4 and hi > 0.4)


def test_normal_must_be_a_result():
    with pytest.raises(ValueError, match="`normal`"):
        sie.solve_partial_slip("nope", 0.1, 0.5)


# -- agreement with the closed form -----------------------------------------------------
def check_slip_agreement(s_r, c_r) -> None:
    x = np.linspace(-c_r.a, c_r.c, 801)
    q = c_r.shear(x)
    err = {"stick_rel": max(abs(s_r.d - c_r.d), abs(s_r.e - c_r.e)) / c_r.d,
           "pressure_peak": float(np.abs(s_r.shear(x) - q).max() / np.abs(q).max())}
    bad = {k: v for k, v in err.items() if not v <= TOL[k].value}
    assert not bad, f"SIE stick zone disagrees with closedform: {bad}"


@pytest.mark.parametrize("name", [k for k in CASES if k != "near_lift_off"])
@pytest.mark.parametrize("load", SLIP_LOADS)
def test_agreement_with_closed_form(name, load):
    from threepart import closedform as cf
    k = CASES[name]
    q, f = load
    c_n = cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    s_n = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    check_slip_agreement(sie.solve_partial_slip(s_n, q * f * k.P, f),
                         cf.solve_partial_slip(c_n, q * f * k.P, f))
    # the SIE stick zone from the closed-form normal solution agrees too
    check_slip_agreement(sie.solve_partial_slip(c_n, q * f * k.P, f),
                         cf.solve_partial_slip(c_n, q * f * k.P, f))


def test_near_lift_off_stick_zone_is_refused_by_both():
    from threepart import closedform as cf
    k = CASES["near_lift_off"]
    s_n = sie.solve_normal(k.punch, k.P, k.s, A=k.A)
    with pytest.raises(ValueError, match="central segment"):
        sie.solve_partial_slip(s_n, 0.1, 0.7)
    with pytest.raises(ValueError):
        cf.solve_partial_slip(cf.solve_normal(k.punch, k.P, k.s, A=k.A), 0.1, 0.7)


def test_perturbed_stick_zone_fails_the_agreement_check():
    from threepart import closedform as cf
    k = CASES["A"]
    c_n = cf.solve_normal(k.punch, k.P, k.s, A=k.A)
    wrong_n = sie.solve_normal(k.punch, k.P, k.s, A=k.A * (1 + 1e-7))
    with pytest.raises(AssertionError, match="disagrees"):
        check_slip_agreement(sie.solve_partial_slip(wrong_n, 0.2, 0.7), cf.solve_partial_slip(c_n, 0.2, 0.7))

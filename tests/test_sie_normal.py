"""Normal problem: exact limits, identities, an independent pointwise reference, and the closed form."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from threepart.errors import SeparationError
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

from threepart import sie
from threepart.punch import Punch
from threepart.sie.cases import CASES, S_MAX_A
from threepart.sie.roots import newton
from threepart.sie.tolerances import TOLERANCES as TOL

SCHEMES = ["plain", "projected"]


def interior(r, k: int = 41) -> np.ndarray:
    """Points strictly inside the contact (the ends are square-root sensitive)."""
    return np.linspace(-r.a, r.c, k + 2)[1:-1]


# -- exact limits ---------------------------------------------------------------------
@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("n", [2, 3, 8, 101])
def test_hertz_is_exact_for_any_n(scheme, n):
    R, P, A = 2.0, 3.0, 1.5
    r = sie.solve_normal(Punch(R, R, 0.0), P, A=A, n=n, scheme=scheme)
    a = math.sqrt(2 * P * A * R / math.pi)
    assert r.a == pytest.approx(a, rel=TOL["hertz"].value)
    assert r.c == pytest.approx(a, rel=TOL["hertz"].value)
    assert abs(r.alpha) < TOL["hertz"].value
    x = interior(r)
    exact = 2 * P / (math.pi * a * a) * np.sqrt(a * a - x * x)
    np.testing.assert_allclose(r.pressure(x), exact, atol=TOL["hertz"].value * exact.max())
    assert r.n == n and r.method == "sie" and r.info["scheme"] == scheme


@pytest.mark.parametrize("scheme", SCHEMES)
def test_tilted_hertz_centre_and_tilt(scheme):
    """Hertz cylinder with a load at s: contact centred at m = s = -alpha R, alpha < 0 for s > 0."""
    R, P, s = 2.0, 1.0, 0.3
    r = sie.solve_normal(Punch(R, R, 0.0), P, s, A=1.0, n=16, scheme=scheme)
    assert 0.5 * (r.c - r.a) == pytest.approx(s, rel=1e-13)
    assert r.alpha == pytest.approx(-s / R, rel=1e-13)


def flat_rounded_a(P: float, A: float, R1: float, b: float) -> float:
    """Symmetric flat rounded punch: 2PAR1/a^2 = pi - 2 phi0 - sin 2 phi0, sin phi0 = b/a."""
    def f(a: float) -> float:
        phi0 = math.asin(b / a)
        return 2 * P * A * R1 / a**2 - (math.pi - 2 * phi0 - math.sin(2 * phi0))
    return brentq(f, b * (1 + 1e-12), 100 * b + 10, xtol=1e-15, rtol=1e-15)


def test_flat_rounded_contact_law_projected_is_exact():
    for P, b in [(1.0, 0.5), (0.2, 1.0), (5.0, 0.1)]:
        r = sie.solve_normal(Punch(1.0, 1.0, b), P, A=1.0, n=8)
        a = flat_rounded_a(P, 1.0, 1.0, b)
        assert r.a == pytest.approx(a, rel=1e-13) and r.c == pytest.approx(a, rel=1e-13)
        assert abs(r.alpha) < 1e-15


# -- identities -----------------------------------------------------------------------
def integrate(r, fun) -> float:
    """∫ fun(x) p(x) dx on the contact, split at the kinks."""
    pts = [x for x in (-r.punch.b, r.punch.b) if -r.a < x < r.c]
    return quad(lambda x: fun(x) * float(r.pressure(x)), -r.a, r.c, points=pts or None,
                limit=200, epsabs=1e-13)[0]


@pytest.mark.parametrize("name", ["A", "B", "C", "general", "suppressed"])
def test_load_and_centroid_identities(name):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    assert integrate(r, lambda x: 1.0) == pytest.approx(k.P, rel=1e-8)
    assert integrate(r, lambda x: x) == pytest.approx(k.P * r.s, abs=1e-8 * k.P * r.width)


def test_symmetric_punch_centred_load_has_no_tilt():
    r = sie.solve_normal(Punch(1.5, 1.5, 0.4, R=-6.0), 2.0, A=1.0)
    assert r.a == pytest.approx(r.c, rel=1e-14)
    assert abs(r.alpha) < 1e-15


@pytest.mark.parametrize("name", ["A", "B", "C", "general", "near_lift_off"])
def test_pressure_against_independent_quadrature(name):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    x = np.concatenate([interior(r, 25), [-k.punch.b + 1e-7, k.punch.b - 1e-9, k.punch.b + 1e-5]])
    ref = sie.pressure_by_quadrature(k.punch, k.A, r.a, r.c, r.alpha, x)
    err = np.abs(r.pressure(x) - ref).max() / ref.max()
    assert err < TOL["reference_peak"].value, err
    assert err < r.info["pressure_bound"] / ref.max() + 1e-12


@settings(max_examples=40, deadline=None)
@given(R1=st.floats(0.3, 5.0), R2=st.floats(0.3, 5.0), b=st.just(0.0) | st.floats(1e-6, 1.0),
       P=st.floats(0.05, 10.0), s_frac=st.floats(-0.4, 0.4),
       invR=st.sampled_from([0.0, 0.1, -0.1]))
def test_mirror_symmetry_and_finiteness(R1, R2, b, P, s_frac, invR):
    """Mirroring the punch and the load swaps a and c and flips alpha; nothing is NaN."""
    R = math.inf if invR == 0 else 1 / invR
    punch = Punch(R1, R2, b, R)
    s = s_frac * max(b, math.sqrt(P * min(R1, R2)))
    try:
        r = sie.solve_normal(punch, P, s, A=1.0, n=64)
    except SeparationError as exc:  # concave centre separating: a named refusal, not a NaN
        assert "tensile" in str(exc)
        return
    m = sie.solve_normal(punch.mirrored(), P, -s, A=1.0, n=64)
    vals = np.array([r.a, r.c, r.alpha, r.s])
    assert np.all(np.isfinite(vals)) and r.a + r.c > 0
    W = r.a + r.c
    assert m.a == pytest.approx(r.c, abs=1e-12 * W) and m.c == pytest.approx(r.a, abs=1e-12 * W)
    assert m.alpha == pytest.approx(-r.alpha, abs=1e-12 * W / min(R1, R2))
    x = interior(r, 9)
    assert np.all(r.pressure(x) >= -1e-12 * r.pressure(x).max())


# -- agreement with the closed form -------------------------------------------------------
def check_agreement(sie_r, cf_r) -> dict[str, float]:
    """Relative differences per quantity; AssertionError names any that exceed its tolerance."""
    W = cf_r.a + cf_r.c
    slope = W / min(cf_r.punch.R1, cf_r.punch.R2)
    x = np.linspace(-cf_r.a, cf_r.c, 801)
    p_cf = cf_r.pressure(x)
    err = {
        "ends_rel": max(abs(sie_r.a - cf_r.a) / cf_r.a, abs(sie_r.c - cf_r.c) / cf_r.c),
        "ends_width": max(abs(sie_r.a - cf_r.a), abs(sie_r.c - cf_r.c)) / W,
        "alpha": abs(sie_r.alpha - cf_r.alpha) / max(abs(cf_r.alpha), slope),
        "s": abs(sie_r.s - cf_r.s) / max(abs(cf_r.s), W),
        "pressure_peak": float(np.abs(sie_r.pressure(x) - p_cf).max() / p_cf.max()),
    }
    bad = {k: v for k, v in err.items() if not v <= TOL[k].value}
    assert not bad, f"SIE disagrees with closedform: {bad} (tolerances: {[TOL[k].value for k in bad]})"
    return err


@pytest.fixture(scope="module")
def cf():
    from threepart import closedform

    return closedform.solve_normal


@pytest.mark.parametrize("name", list(CASES))
def test_agreement_with_closed_form(cf, name):
    k = CASES[name]
    ref = cf(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    check_agreement(sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt), ref)


@pytest.mark.parametrize("perturb", [dict(R2=2.0 * (1 + 1e-7)), dict(b=0.4 + 1e-8)])
def test_perturbed_right_hand_side_fails_the_agreement_check(cf, perturb):
    k = CASES["A"]
    ref = cf(k.punch, k.P, k.s, A=k.A)
    wrong = sie.solve_normal(dataclasses.replace(k.punch, **perturb), k.P, k.s, A=k.A)
    with pytest.raises(AssertionError, match="disagrees"):
        check_agreement(wrong, ref)


def test_near_lift_off_case_is_near_lift_off():
    from threepart import closedform
    lo = closedform.lift_off(CASES["A"].punch, 1.0, 1.0)
    assert S_MAX_A == pytest.approx(lo.s_max, rel=1e-12)
    r = sie.solve_normal(CASES["near_lift_off"].punch, 1.0, CASES["near_lift_off"].s, A=1.0)
    assert r.a == pytest.approx(CASES["A"].punch.b, rel=2e-2) and r.a > CASES["A"].punch.b


def test_solver_goes_beyond_lift_off():
    """Past s_max the left edge lies on the flat face; the SIE still solves (closed form does not)."""
    punch = CASES["A"].punch
    r = sie.solve_normal(punch, 1.0, 1.1 * S_MAX_A, A=1.0)
    assert r.a < punch.b
    x = interior(r, 15)
    ref = sie.pressure_by_quadrature(punch, 1.0, r.a, r.c, r.alpha, x)
    assert np.abs(r.pressure(x) - ref).max() < 1e-6 * ref.max()


# -- refusals -----------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    (dict(P=0.0), "`P` = 0.0 must be > 0"),
    (dict(P=math.nan), "`P`"),
    (dict(A=-1.0), "`A` = -1.0 must be > 0"),
    (dict(s=math.inf), "`s`"),
    (dict(tilt="fixed"), "`tilt` = 'fixed'"),
    (dict(tilt="suppressed", s=0.1), "`s` = 0.1 must be 0"),
    (dict(n=1), "`n` = 1 must be >= 2"),
    (dict(n=10.0), "`n` = 10.0 must be an integer"),
    (dict(scheme="gauss"), "`scheme` = 'gauss'"),
    (dict(scheme="plain", n=5000), "`n` = 5000 exceeds 4096"),
])
def test_bad_input_is_refused(kwargs, match):
    args = dict(P=1.0, s=0.0, A=1.0) | kwargs
    with pytest.raises(ValueError, match=match):
        sie.solve_normal(Punch(1.0, 2.0, 0.4), args.pop("P"), args.pop("s"), **args)


def test_bad_punch_is_refused():
    with pytest.raises(ValueError, match="`punch`"):
        sie.solve_normal((1.0, 2.0, 0.4), 1.0, A=1.0)


def test_separating_concave_centre_is_refused():
    with pytest.raises(ValueError, match="`P` = 0.01 .* tensile"):
        sie.solve_normal(Punch(1.0, 1.0, 0.5, R=-0.5), 0.01, A=1.0)


def test_failed_iteration_raises_named_exception():
    def no_root(z):
        return np.array([z[0] ** 2 + 1.0, z[1] - 1.0]), np.array([[2 * z[0], 0.0], [0.0, 1.0]])
    with pytest.raises(sie.NoConvergenceError, match="test problem"):
        newton(no_root, np.array([0.5, 1.0]), what="test problem")
    assert issubclass(sie.NoConvergenceError, RuntimeError)


def test_non_finite_residual_raises_named_exception(monkeypatch):
    from threepart.sie import schemes
    monkeypatch.setattr(schemes.Projected, "moments",
                        lambda self, punch, m, h: (np.full(3, np.nan), np.full((3, 2), np.nan)))
    with pytest.raises(sie.NoConvergenceError):
        sie.solve_normal(Punch(1.0, 2.0, 0.4), 1.0, A=1.0)


@pytest.mark.parametrize("name", ["A", "B", "general"])
def test_lift_off_lever_arms_agree_with_closed_form(name):
    from threepart import closedform
    k = CASES[name]
    lo = closedform.lift_off(k.punch, k.P, k.A)
    s_min, s_max = sie.lift_off(k.punch, k.P, k.A)
    assert s_min == pytest.approx(lo.s_min, rel=1e-12) and s_max == pytest.approx(lo.s_max, rel=1e-12)
    r = sie.solve_normal(k.punch, k.P, s_max, A=k.A)  # the left edge sits on the join
    assert r.a == pytest.approx(k.punch.b, rel=1e-12)


def test_lift_off_needs_a_join():
    with pytest.raises(ValueError, match="b = 0"):
        sie.lift_off(Punch(1.0, 2.0, 0.0), 1.0, 1.0)

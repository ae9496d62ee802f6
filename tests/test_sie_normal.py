"""Normal problem: exact limits, identities, an independent pointwise reference, and the closed form."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from threepart.errors import SlopeLimitError

from threepart.errors import SeparationError
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

from threepart import sie
from threepart.problem.catalogue import load_cases
from threepart.problem.punch import Punch
from threepart.reports.compare import compare
from threepart.sie.roots import newton
from threepart.tolerances import tolerance

SCHEMES = ["plain", "projected"]
#: Cattaneo's d = a sqrt(1 - Q/fP) within 1e-6 of full sliding: d is 1e-3 a, its Newton solve
#: stops at a fixed residual
NEAR_SLIDING = 1e-6
#: a, c of the sharp punch (R1 = 0.0314) against the closed form, where the residual's rounding
#: floor is 5.9e-10; and Hertz's e = -s next to full sliding (units of W)
SHARP_FLOOR = 1e-8
#: the nondimensional SIE cases, lever arms resolved (stored lift-off arms: no closed form needed)
CASES = {c.name: c.resolved() for c in load_cases("sie")}


def tol(comparison: str, quantity: str) -> float:
    return tolerance(comparison, quantity).limit


def interior(r, k: int = 41) -> np.ndarray:
    """Points strictly inside the contact (the ends are square-root sensitive)."""
    return np.linspace(-r.a, r.c, k + 2)[1:-1]


# -- exact limits ---------------------------------------------------------------------
@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("n", [2, 3, 8, 101])
def test_hertz_is_exact_for_any_n(scheme, n):
    R, P, A = 2.0, 0.15, 1.5        # slope a/R = 0.27, inside the small-slope limit
    r = sie.solve_normal(Punch(R, R, 0.0), P, A=A, n=n, scheme=scheme)
    a = math.sqrt(2 * P * A * R / math.pi)
    exact_tol = tol("sie-exact", "hertz")
    assert r.a == pytest.approx(a, rel=exact_tol, abs=0)
    assert r.c == pytest.approx(a, rel=exact_tol, abs=0)
    assert abs(r.alpha) < exact_tol * (2 * a / R)           # slope scale over the contact
    x = interior(r)
    exact = 2 * P / (math.pi * a * a) * np.sqrt(a * a - x * x)
    np.testing.assert_allclose(r.pressure(x), exact, atol=exact_tol * exact.max())
    assert r.diagnostics.n == n and r.method == "sie" and r.diagnostics.scheme == scheme


@pytest.mark.parametrize("scheme", SCHEMES)
def test_tilted_hertz_centre_and_tilt(scheme):
    """Hertz cylinder with a load at s: contact centred at m = s = -alpha R, alpha < 0 for s > 0."""
    R, P, s = 2.0, 0.1, 0.3
    r = sie.solve_normal(Punch(R, R, 0.0), P, s, A=1.0, n=16, scheme=scheme)
    assert 0.5 * (r.c - r.a) == pytest.approx(s, rel=tol("sie-exact", "hertz"), abs=0)
    assert r.alpha == pytest.approx(-s / R, rel=tol("sie-exact", "hertz"), abs=0)


def flat_rounded_a(P: float, A: float, R1: float, b: float) -> float:
    """Symmetric flat rounded punch: 2PAR1/a^2 = pi - 2 phi0 - sin 2 phi0, sin phi0 = b/a."""
    def f(a: float) -> float:
        phi0 = math.asin(b / a)
        return 2 * P * A * R1 / a**2 - (math.pi - 2 * phi0 - math.sin(2 * phi0))
    return brentq(f, b * (1 + 1e-12), 100 * b + 10, xtol=1e-15, rtol=1e-15)


def test_flat_rounded_contact_law_projected_is_exact():
    exact = tol("sie-exact", "flat_rounded")
    for P, b in [(0.1, 0.5), (0.05, 1.0), (0.2, 0.1)]:     # slopes (a - b)/R1 <= 0.5
        r = sie.solve_normal(Punch(1.0, 1.0, b), P, A=1.0, n=8)
        a = flat_rounded_a(P, 1.0, 1.0, b)
        assert r.a == pytest.approx(a, rel=exact, abs=0) and r.c == pytest.approx(a, rel=exact, abs=0)
        assert abs(r.alpha) < exact * 2 * (a - b)            # slope scale v'(a) - v'(-a) with R1 = 1


# -- identities -----------------------------------------------------------------------
def integrate(r, fun) -> float:
    """∫ fun(x) p(x) dx on the contact, split at the kinks."""
    pts = [x for x in (-r.punch.b, r.punch.b) if -r.a < x < r.c]
    return quad(lambda x: fun(x) * float(r.pressure(x)), -r.a, r.c, points=pts or None,
                limit=200, epsabs=1e-13)[0]


@pytest.mark.parametrize("name", ["nd_A", "nd_B", "nd_C", "nd_general", "nd_suppressed"])
def test_load_and_centroid_identities(name):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    quad_tol = tol("sie-identity", "load")
    assert integrate(r, lambda x: 1.0) == pytest.approx(k.P, rel=quad_tol, abs=0)
    assert integrate(r, lambda x: x) == pytest.approx(k.P * r.s, abs=quad_tol * k.P * r.width)


def test_symmetric_punch_centred_load_has_no_tilt():
    r = sie.solve_normal(Punch(1.5, 1.5, 0.4, R=-6.0), 0.5, A=1.0)
    assert r.a == pytest.approx(r.c, rel=tol("sie-exact", "symmetry"), abs=0)
    assert abs(r.alpha) < tol("sie-exact", "symmetry") * 2 * (r.a - r.punch.b) / r.punch.R1   # slope scale v'(c) - v'(-a)


@pytest.mark.parametrize("name", ["nd_A", "nd_B", "nd_C", "nd_general", "nd_near_lift_off"])
def test_pressure_against_independent_quadrature(name):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    x = np.concatenate([interior(r, 25), [-k.punch.b + 1e-7, k.punch.b - 1e-9, k.punch.b + 1e-5]])
    ref = sie.pressure_by_quadrature(k.punch, k.A, r.a, r.c, r.alpha, x)
    err = np.abs(r.pressure(x) - ref).max() / ref.max()
    assert err < tol("sie-reference", "p"), err
    assert err < r.info["pressure_bound"] / ref.max() + tol("sie-reference", "bound_slack")


@settings(max_examples=40, deadline=None)
@given(R1=st.floats(0.3, 5.0), R2=st.floats(0.3, 5.0), b=st.just(0.0) | st.floats(1e-6, 1.0),
       P=st.floats(0.005, 0.05), s_frac=st.floats(-0.4, 0.4),
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
    mirror = tol("sie-exact", "mirror")
    assert m.a == pytest.approx(r.c, abs=mirror * W) and m.c == pytest.approx(r.a, abs=mirror * W)
    assert m.alpha == pytest.approx(-r.alpha, abs=mirror * W / min(R1, R2))
    x = interior(r, 9)
    assert np.all(r.pressure(x) >= -mirror * r.pressure(x).max())


# -- agreement with the closed form -------------------------------------------------------
def check_agreement(sie_r, cf_r) -> list:
    """Judge the SIE result against the closed form with the verification run's comparator and table.

    AssertionError names every quantity that exceeds its ``("sie", quantity)`` tolerance.
    """
    checks = compare(cf_r, sie_r, "sie")
    bad = {c.quantity: f"{c.error:.1e} > {c.limit:g}" for c in checks if not c.passed}
    assert not bad, f"SIE disagrees with closedform: {bad}"
    return checks


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
    k = CASES["nd_A"]
    ref = cf(k.punch, k.P, k.s, A=k.A)
    wrong = sie.solve_normal(dataclasses.replace(k.punch, **perturb), k.P, k.s, A=k.A)
    with pytest.raises(AssertionError, match="disagrees"):
        check_agreement(wrong, ref)


def test_near_lift_off_case_is_near_lift_off():
    """At 0.999 of its stored lift-off lever arm the left end lies just outside the join.

    The stored arm itself is checked against closedform.lift_off in tests/test_catalogue.py;
    here the SIE's own lift-off root is the reference.
    """
    k = CASES["nd_near_lift_off"]
    assert k.s_max == pytest.approx(sie.lift_off(k.punch, k.P, k.A)[1], rel=tol("sie-exact", "lift_off"))
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A)
    assert k.punch.b < r.a < k.punch.b * (1 + tol("sie-identity", "near_lift_off_gap"))


def test_solver_goes_beyond_lift_off():
    """Past s_max the left edge lies on the flat face; the SIE still solves (closed form does not)."""
    k = CASES["nd_near_lift_off"]
    r = sie.solve_normal(k.punch, k.P, 1.1 * k.s_max, A=k.A)
    assert r.a < k.punch.b
    x = interior(r, 15)
    ref = sie.pressure_by_quadrature(k.punch, k.A, r.a, r.c, r.alpha, x)
    assert np.abs(r.pressure(x) - ref).max() < tol("sie-reference", "p") * ref.max()


# -- refusals -----------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    (dict(P=0.0), "`P` = 0.0 must be > 0"),
    (dict(P=math.nan), "`P`"),
    (dict(A=-1.0), "`A` = -1.0 must be > 0"),
    (dict(s=math.inf), "`s`"),
    (dict(tilt="fixed"), "`tilt` = 'fixed'"),
    (dict(tilt="suppressed", s=0.1), "`s` = 0.1 must be 0"),
    (dict(n=1), r"`n` = 1 must lie in \[2, 65536\]"),
    (dict(n=2**30), r"`n` = 1073741824 must lie in \[2, 65536\]"),
    (dict(scheme="gauss"), "`scheme` = 'gauss'"),
    (dict(scheme="plain", n=5000), "`n` = 5000 exceeds 4096"),
])
def test_bad_input_is_refused(kwargs, match):
    args = dict(P=1.0, s=0.0, A=1.0) | kwargs
    with pytest.raises(ValueError, match=match):
        sie.solve_normal(Punch(1.0, 2.0, 0.4), args.pop("P"), args.pop("s"), **args)


def test_bad_punch_is_refused():
    with pytest.raises(TypeError, match="`punch` must be a threepart.Punch, not tuple"):
        sie.solve_normal((1.0, 2.0, 0.4), 1.0, A=1.0)
    with pytest.raises(TypeError, match="`n` = 10.0 must be an integer, not float"):
        sie.solve_normal(Punch(1.0, 2.0, 0.4), 0.1, A=1.0, n=10.0)


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


@pytest.mark.parametrize("name", ["nd_A", "nd_B", "nd_general"])
def test_lift_off_lever_arms_agree_with_closed_form(name):
    from threepart import closedform
    k = CASES[name]
    lo = closedform.lift_off(k.punch, k.P, k.A)
    s_min, s_max = sie.lift_off(k.punch, k.P, k.A)
    rel = tol("sie-exact", "lift_off")
    assert s_min == pytest.approx(lo.s_min, rel=rel, abs=0) and s_max == pytest.approx(lo.s_max, rel=rel, abs=0)
    if name == "nd_B":      # at its lift-off lever arm the tilt is past the small-slope limit
        for solver in (sie, closedform):
            with pytest.raises(SlopeLimitError, match="tilt alpha = -0.2"):
                solver.solve_normal(k.punch, k.P, s_max * (1 - 1e-9), A=k.A)
        return
    r = sie.solve_normal(k.punch, k.P, s_max, A=k.A)  # the left edge sits on the join
    assert r.a == pytest.approx(k.punch.b, rel=rel, abs=0)


def test_lift_off_needs_a_join():
    with pytest.raises(ValueError, match="b = 0"):
        sie.lift_off(Punch(1.0, 2.0, 0.0), 1.0, 1.0)


# -- the fuzz's findings ------------------------------------------------------------------
def test_a_tilt_past_the_small_slope_limit_is_refused():
    """Punch(10, 5, 1) at s = 5: the SIE's answer was a tilt of -0.8 rad (46 degrees)."""
    from threepart import solve

    for method in ("sie", "auto"):
        with pytest.raises(SlopeLimitError, match=r"tilt alpha = -0.8 rad\), past the small-slope"):
            solve(Punch(10.0, 5.0, 1.0), 400.0, 5.0, A=8.67e-6, method=method)


@pytest.mark.parametrize("s", [1e14, 1e16, 1e300, -6.0])
def test_a_lever_arm_off_the_footprint_is_refused_before_any_numerics(s):
    """At s = 1e14 the contact width was 4 % off, at 1e16 zero (a = -1e300) with exit status 0."""
    from threepart import closedform

    punch = Punch(5.0, 10.0, 1.0)
    for solve_normal in (sie.solve_normal, closedform.solve_normal):
        with pytest.raises(ValueError, match=r"`s` = .* lies outside the punch's footprint "
                           r"\(-6, 11\) = \(-\(b \+ R1\), b \+ R2\)"):
            solve_normal(punch, 400.0, s, A=8.67e-6)
    with pytest.raises(ValueError, match="footprint"):
        closedform.P_min(Punch(5.0, 10.0, 1.0, R=-20.0), 8.67e-6, s=s)


def test_a_sharp_edge_arc_converges_and_agrees_with_the_closed_form():
    """R1 = 0.0314 next to a flat centre: the residual's rounding floor is 5.9e-10 (was refused)."""
    from threepart import closedform, rigid_punch

    A = rigid_punch(210e3, 0.3)
    punch, P, s = Punch(0.03140302943810751, 84.39590767832716, 1), 0.2933372464340942, -0.37321612887217803
    r = sie.solve_normal(punch, P, s, A=A)
    ref = closedform.solve_normal(punch, P, s, A=A)
    assert abs(r.a - ref.a) <= SHARP_FLOOR * ref.width and abs(r.c - ref.c) <= SHARP_FLOOR * ref.width


def test_the_pressure_is_zero_at_the_ends_past_lift_off():
    """Past lift-off the pressure at x = c was 7.9e-5 (the end's rounding in (x - m)/h)."""
    from threepart import closedform, rigid_punch

    A = rigid_punch(210e3, 0.3)
    punch = Punch(10.0, 10.0, 1.0)
    s = 1.25 * closedform.lift_off(punch, 28846.0, A).s_max
    r = sie.solve_normal(punch, 28846.0, s, A=A)
    assert not r.within_paper
    ends = np.array([-r.a, r.c, np.nextafter(r.c, np.inf), np.nextafter(-r.a, -np.inf), -1e3, 1e3])
    assert np.all(r.pressure(ends) == 0.0)
    assert float(r.pressure(np.nextafter(r.c, -np.inf))) >= 0.0


@pytest.mark.parametrize("ratio", [1 - 1e-3, 1 - 1e-6])
def test_partial_slip_next_to_full_sliding_converges(ratio):
    """|Q|/(fP) >= 1 - 1e-6 failed to converge; Hertz's stick zone is d = a sqrt(1 - |Q|/fP)."""
    from threepart import rigid_punch

    A = rigid_punch(210e3, 0.3)
    normal = sie.solve_normal(Punch(10.0, 10.0, 0.0), 1000.0, 0.2, A=A)
    r = sie.solve_partial_slip(normal, ratio * 0.3 * 1000.0, 0.3)
    h = 0.5 * normal.width
    assert r.d == pytest.approx(h * math.sqrt(1 - ratio), rel=NEAR_SLIDING, abs=0)
    assert abs(r.e + 0.2) <= SHARP_FLOOR * normal.width


def test_partial_slip_closer_to_full_sliding_is_refused_by_name():
    """Past 1 - 1e-6 (SLIP_RATIO_LIMIT) the SIE refuses: the stick zone is not resolved there."""
    from threepart import rigid_punch
    from threepart.errors import FullSlidingError

    normal = sie.solve_normal(Punch(10.0, 10.0, 0.0), 1000.0, 0.2, A=rigid_punch(210e3, 0.3))
    with pytest.raises(FullSlidingError, match=r"\|`Q`\|/\(f P\) = 0.999999.* is within 1e-06 of "
                       r"full sliding, past 0.999999 \(threepart.problem.validate.SLIP_RATIO_LIMIT\)"):
        sie.solve_partial_slip(normal, (1 - 1e-8) * 0.3 * 1000.0, 0.3)

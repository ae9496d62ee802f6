"""Every forward closed form against an independent quadrature of its defining integral.

Acceptance: <= 1e-10 relative over cases A, B, C, the general case and Hertz.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart.closedform import Punch, formulas, special
from tests import quad_reference as ref
from threepart.tolerances import tolerance

RTOL = tolerance("closedform", "quadrature").limit  # the acceptance bound for closed form vs quadrature
A = 1.3
ROUND_OFF = tolerance("closedform", "round_off").limit
EXACT = tolerance("closedform", "exact").limit
#: F_j / w against scipy's Cauchy-weight quadrature (QAWC), whose own error near the segment ends is ~1e-10
SEGMENT = 1e-9
#: R = 1e12 stands for R = ∞: the general form differs from case A by O(b/R) = 1e-13 plus rounding
R_LIMIT = 1e-10
#: the moment at a = c + 1e-9 against a = c: it moves by O(1e-9) and the removable 0/0 loses half the digits
REMOVABLE = 1e-6
#: b = 1e-10 stands for b = 0 (case C): the general form's b ln b terms, relative and absolute
B_LIMIT, B_LIMIT_ABS = 1e-8, 1e-10
#: R2 = R (1 + 1e-12), b = 1e-12 stand for Hertz: the general form's log terms of b
HERTZ_LIMIT = 1e-9

CASES = {
    "general": (Punch(1.0, 2.0, 0.3, R=5.0), 0.7, 0.5),
    "A": (Punch(1.0, 1.5, 0.3), 0.45, 0.62),
    "A-symmetric": (Punch(1.0, 1.0, 0.3), 0.5, 0.5),
    "B": (Punch(1.0, 2.0, 0.3, R=-4.0), 0.5, 0.8),
    "C": (Punch(1.0, 2.0, 0.0, R=7.0), 0.4, 0.2),
    "Hertz": (Punch(1.0, 1.0, 0.0), 0.3, 0.3),
    "Hertz-shifted": (Punch(1.0, 1.0, 0.0), 0.1, 0.5),
    "near-lift-off": (Punch(1.0, 2.0, 0.3, R=20.0), 0.6, 0.3 + 1e-7),
}
ids = list(CASES)


@pytest.fixture(params=ids)
def case(request):
    return CASES[request.param]


def test_tilt_against_consistency_integral(case):
    punch, a, c = case
    scale = (a + c) * (punch.kappa1 + punch.kappa2 + abs(punch.kappa0))
    assert abs(formulas.tilt(punch, a, c) - ref.tilt(punch, a, c)) <= RTOL * scale


def test_load_against_vertical_equilibrium_integral(case):
    punch, a, c = case
    assert formulas.load(punch, a, c, A) == pytest.approx(ref.load(punch, a, c, A), rel=RTOL)


def test_moment_against_rotational_equilibrium_integral(case):
    punch, a, c = case
    scale = ref.load(punch, a, c, A) * (a + c)
    assert abs(formulas.moment(punch, a, c, A) - ref.moment(punch, a, c, A)) <= RTOL * scale


def test_pressure_against_inversion_integral(case):
    punch, a, c = case
    x = np.r_[np.linspace(-a, c, 13)[1:-1], [t for t in (-punch.b, punch.b) if -a < t < c],
              -a + 1e-6 * (a + c), c - 1e-6 * (a + c)]
    got = formulas.pressure(punch, a, c, A, x)
    want = np.array([ref.pressure(punch, a, c, A, xi) for xi in x])
    assert np.max(np.abs(got - want)) <= RTOL * np.max(np.abs(want))


def test_F_functions_against_segment_integrals():
    """Appendix: F_j(x)/w(x) are the segment integrals, principal values inside."""
    a, c, b = 0.7, 0.5, 0.3
    for x in (-0.6, -0.3 + 1e-3, -0.1, 0.2, 0.45):
        w = math.sqrt((x + a) * (c - x))
        for F, (lo, hi) in ((formulas.F1, (-a, -b)), (formulas.F2, (-b, b)), (formulas.F3, (b, c))):
            want = ref.segment_cauchy(lo, hi, a, c, x)
            assert F(x, a, c, b) / w == pytest.approx(want, rel=SEGMENT, abs=ROUND_OFF)


def test_pressure_vanishes_at_the_edges_and_outside(case):
    punch, a, c = case
    p = formulas.pressure(punch, a, c, A, [-a, c, -a - 1.0, c + 1.0])
    assert np.all(p == 0.0)


@pytest.mark.parametrize("name", [k for k, v in CASES.items() if v[0].b > 0])
def test_pressure_abbreviated_as_printed_equals_reduced_form(name):
    """Eq. (pressure_abbreviated) with F1..F3 and alpha terms equals the reduced form used.

    (b > 0 only: for b = 0 the printed case-C form is checked below.)
    """
    punch, a, c = CASES[name]
    alpha = formulas.tilt(punch, a, c)
    x = np.linspace(-a, c, 15)[1:-1]
    x = x[np.abs(np.abs(x) - punch.b) > 1e-9]
    w = np.sqrt((x + a) * (c - x))
    b, R1, R2, k1, k2 = punch.b, punch.R1, punch.R2, punch.k1, punch.k2
    k0 = punch.kappa0
    printed = -(w / (math.pi * A)) * (
        formulas.F0(punch, a, c)
        + (alpha * R1 + b * k1 + x) / (R1 * w) * formulas.F1(x, a, c, b)
        + (alpha + x * k0) / w * formulas.F2(x, a, c, b)   # (alpha R + x)/R, finite for R = inf
        - (-alpha * R2 + b * k2 - x) / (R2 * w) * formulas.F3(x, a, c, b))
    assert np.allclose(-printed, formulas.pressure(punch, a, c, A, x), rtol=ROUND_OFF, atol=EXACT)


@pytest.mark.parametrize("name", [k for k, v in CASES.items() if v[0].b > 0])
def test_pressure_at_a_scalar_and_broadcast_is_the_printed_form(name):
    """The compiled pressure (a numpy ufunc) at one float ``x``, as the least-pressure searches call
    it, and broadcast over a column of contacts, against eq. (pressure_abbreviated) as printed."""
    punch, a, c = CASES[name]
    x = np.linspace(-a, c, 9)[1:-1]
    x = x[np.abs(np.abs(x) - punch.b) > 1e-9]
    contacts = np.array([[a, c], [1.1 * a, 1.05 * c]])      # both edges on the outer segments
    for aj, cj in contacts:
        alpha = formulas.tilt(punch, aj, cj)
        w = np.sqrt((x + aj) * (cj - x))
        printed = (w / (math.pi * A)) * (
            formulas.F0(punch, aj, cj)
            + (alpha * punch.R1 + punch.b * punch.k1 + x) / (punch.R1 * w) * formulas.F1(x, aj, cj, punch.b)
            + (alpha + x * punch.kappa0) / w * formulas.F2(x, aj, cj, punch.b)
            - (-alpha * punch.R2 + punch.b * punch.k2 - x) / (punch.R2 * w) * formulas.F3(x, aj, cj, punch.b))
        one = np.array([formulas.pressure(punch, float(aj), float(cj), A, float(xi)) for xi in x])
        assert np.allclose(one, printed, rtol=ROUND_OFF, atol=EXACT)
        assert formulas.pressure(punch, float(aj), float(cj), A, 0.0).shape == ()
    grid = formulas.pressure(punch, contacts[:, :1], contacts[:, 1:], A, x[None, :])
    assert grid.shape == (2, x.size)
    for j, (aj, cj) in enumerate(contacts):
        assert np.allclose(grid[j], [formulas.pressure(punch, aj, cj, A, xi) for xi in x], rtol=0, atol=0)


# -- anchors -------------------------------------------------------------------------
@pytest.mark.parametrize("P,R,Av", [(0.1, 1.0, 1.0), (400.0, 10.0, 8.67e-6), (3e-3, 50.0, 2.0)])
def test_hertz_anchor(P, R, Av):
    """Hertz: a^2 = 2PAR/pi and p0 = 2P/(pi a), to 1e-12."""
    from threepart.closedform import solve_normal

    sol = solve_normal(Punch(R, R, 0.0), P, A=Av)
    a_h = math.sqrt(2 * P * Av * R / math.pi)
    assert sol.a == pytest.approx(a_h, rel=ROUND_OFF) and sol.c == pytest.approx(a_h, rel=ROUND_OFF)
    assert float(sol.pressure(0.0)) == pytest.approx(2 * P / (math.pi * a_h), rel=ROUND_OFF)
    assert sol.alpha == 0.0 or abs(sol.alpha) < EXACT


@pytest.mark.parametrize("b_over_a", [0.05, 0.3, 0.7, 0.95])
def test_flat_rounded_punch_anchor(b_over_a):
    """Ciavarella, Hills & Monno (1998): 2PAR/a^2 = pi - 2 phi0 - sin 2phi0, sin phi0 = b/a."""
    from threepart.closedform import solve_normal

    R, Av, a = 10.0, 1e-5, 1.0
    phi0 = math.asin(b_over_a)
    P = a * a * (math.pi - 2 * phi0 - math.sin(2 * phi0)) / (2 * Av * R)
    sol = solve_normal(Punch(R, R, b_over_a * a), P, A=Av)
    assert sol.a == pytest.approx(a, rel=ROUND_OFF) and sol.c == pytest.approx(a, rel=ROUND_OFF)


# -- specialised forms equal the general form in the limit ------------------------------
def test_case_a_is_the_general_form_as_R_goes_to_infinity():
    a, c, b, R1, R2 = 0.45, 0.62, 0.3, 1.0, 1.5
    far = Punch(R1, R2, b, R=1e12)
    x = np.linspace(-a, c, 21)
    assert np.allclose(special.case_a_pressure(a, c, b, R1, R2, A, x),
                       formulas.pressure(far, a, c, A, x), rtol=R_LIMIT, atol=ROUND_OFF)
    assert special.case_a_tilt(a, c, b, R1, R2) == pytest.approx(formulas.tilt(far, a, c), rel=R_LIMIT)
    assert special.case_a_load(a, c, b, R1, R2, A) == pytest.approx(formulas.load(far, a, c, A), rel=R_LIMIT)
    assert special.case_a_moment(a, c, b, R1, R2, A) == pytest.approx(
        formulas.moment(far, a, c, A), rel=R_LIMIT)


def test_case_a_against_quadrature():
    punch, a, c = CASES["A"]
    assert special.case_a_load(a, c, punch.b, punch.R1, punch.R2, A) == pytest.approx(
        ref.load(punch, a, c, A), rel=RTOL)
    assert special.case_a_moment(a, c, punch.b, punch.R1, punch.R2, A) == pytest.approx(
        ref.moment(punch, a, c, A), rel=RTOL)
    assert special.case_a_tilt(a, c, punch.b, punch.R1, punch.R2) == pytest.approx(
        ref.tilt(punch, a, c), rel=RTOL)


def test_case_a_moment_removable_singularity_at_a_equals_c():
    b, R1, R2 = 0.3, 1.0, 1.5
    near = special.case_a_moment(0.5 + 1e-9, 0.5, b, R1, R2, A)
    assert np.isfinite(special.case_a_moment(0.5, 0.5, b, R1, R2, A))
    assert special.case_a_moment(0.5, 0.5, b, R1, R2, A) == pytest.approx(near, rel=REMOVABLE)


def test_case_c_is_the_general_form_as_b_goes_to_zero():
    a, c, R1, R2 = 0.4, 0.2, 1.0, 2.0
    small = Punch(R1, R2, 1e-10, R=7.0)
    x = np.linspace(-a, c, 21)
    assert np.allclose(special.case_c_pressure(a, c, R1, R2, A, x),
                       formulas.pressure(small, a, c, A, x), rtol=B_LIMIT, atol=B_LIMIT_ABS)
    for sp, gen in ((special.case_c_tilt(a, c, R1, R2), formulas.tilt(small, a, c)),
                    (special.case_c_load(a, c, R1, R2, A), formulas.load(small, a, c, A)),
                    (special.case_c_moment(a, c, R1, R2, A), formulas.moment(small, a, c, A))):
        assert sp == pytest.approx(gen, rel=B_LIMIT)


def test_case_c_against_quadrature():
    punch, a, c = CASES["C"]
    assert special.case_c_load(a, c, punch.R1, punch.R2, A) == pytest.approx(
        ref.load(punch, a, c, A), rel=RTOL)
    assert special.case_c_moment(a, c, punch.R1, punch.R2, A) == pytest.approx(
        ref.moment(punch, a, c, A), rel=RTOL)
    assert special.case_c_tilt(a, c, punch.R1, punch.R2) == pytest.approx(ref.tilt(punch, a, c), rel=RTOL)
    x = np.linspace(-a, c, 9)[1:-1]
    want = [ref.pressure(punch, a, c, A, xi) for xi in x]
    assert np.allclose(special.case_c_pressure(a, c, punch.R1, punch.R2, A, x), want, rtol=RTOL)


def test_hertz_pressure_is_the_limit_of_the_general_form():
    a, R = 0.3, 1.0
    gen = Punch(R, R * (1 + 1e-12), 1e-12, R=3.0)
    x = np.linspace(-a, a, 21)
    assert np.allclose(special.hertz_pressure(a, R, A, x), formulas.pressure(gen, a, a, A, x),
                       rtol=HERTZ_LIMIT, atol=ROUND_OFF)


@pytest.mark.parametrize("R", [math.inf, 30.0, -40.0])
def test_lift_off_forms_against_quadrature(R):
    """Eq. (Pctob) and s_lift-off (corrected) at c = b, against the equilibrium integrals."""
    b, R1, a = 0.3, 1.0, 0.5
    punch = Punch(R1, 2.0, b, R=R)
    P = ref.load(punch, a, b, A)
    assert special.P_lift_off(a, b, R1, R, A) == pytest.approx(P, rel=RTOL)
    assert special.s_lift_off(a, b, R1, R) == pytest.approx(ref.moment(punch, a, b, A) / P, rel=RTOL)

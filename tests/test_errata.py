"""docs/ERRATA.md, enforced: each printed form is shown wrong and its correction right.

The ``printed_*`` functions transcribe the paper's equations literally. The
references are quadratures of the defining integrals (tests/quad_reference.py).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from threepart.closedform import Punch, formulas, special
from tests import quad_reference as ref
from threepart.tolerances import tolerance

A = 1.3
#: closed form against the quadrature reference; identities in double precision
RTOL = tolerance("closedform", "quadrature").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
#: a printed equation is wrong when it misses the oracle by far more than any rounding: at least this
ERRATUM = 1e-3
#: ∫f p dx by quad (epsrel 1e-12) on the pieces between the kinks, against f P
SHEAR_QUADRATURE = 1e-9
PUNCH, a, c = Punch(1.0, 2.0, 0.3, R=5.0), 0.7, 0.5     # general case
b, R1, R2, R = PUNCH.b, PUNCH.R1, PUNCH.R2, PUNCH.R
k1, k2 = PUNCH.k1, PUNCH.k2
t1 = math.acos((-a + 2 * b + c) / (a + c))
t2 = math.acos((a + 2 * b - c) / (a + c))
W1, W3 = math.sqrt((a - b) * (b + c)), math.sqrt((a + b) * (c - b))


def printed_P():
    """Eq. (equilibrium_condition_1) as printed."""
    return ((a + c) ** 2 * (-k1 / R1 * t1 - k2 / R2 * t2 - math.pi / R)
            - k1 / R1 * 2 * (a - 2 * b - c) * W1 + k2 / R2 * 2 * (a + 2 * b - c) * W3) / (8 * A)


def printed_Ps():
    """Eq. (equilibrium_condition_2) as printed."""
    X = (a**2 - 2 * b**2 + c**2) / (a - c)
    return (a - c) / (48 * A) * (3 * (a + c) ** 2 * (k1 / R1 * t1 + k2 / R2 * t2 + math.pi / R)
                                 + k1 / R1 * 4 * (X + (a - 2 * b - c) / 2) * W1
                                 - k2 / R2 * 4 * (X + (a + 2 * b - c) / 2) * W3)


def test_E1_load_expression_has_the_opposite_sign():
    P = ref.load(PUNCH, a, c, A)            # P = -int p dx > 0, eq. (vertical)
    assert P > 0
    assert printed_P() == pytest.approx(-P, rel=RTOL)
    assert formulas.load(PUNCH, a, c, A) == pytest.approx(P, rel=RTOL)


def test_E2_moment_expression_is_int_p_x_dx_not_P_s():
    Ps = ref.moment(PUNCH, a, c, A)          # moment of the compressive pressure
    assert printed_Ps() == pytest.approx(-Ps, rel=RTOL)
    assert formulas.moment(PUNCH, a, c, A) == pytest.approx(Ps, rel=RTOL)
    # the ratio of the two printed expressions is the centroid: the slips cancel in s
    assert printed_Ps() / printed_P() == pytest.approx(Ps / ref.load(PUNCH, a, c, A), rel=RTOL)


def test_E3_hertz_contact_law_sign():
    """Eq. (contact_law_Hertz) prints PA/R1 = -pi a^2/(2 R1^2); the load is positive."""
    hertz = Punch(1.0, 1.0, 0.0)
    P = ref.load(hertz, 0.3, 0.3, A)
    assert P * A / 1.0 == pytest.approx(+math.pi * 0.3**2 / 2, rel=ROUND_OFF)


def test_E4_case_A_and_C_equilibrium_signs():
    punch_a = Punch(R1, R2, b)
    printed_A = (a + c) ** 2 / (4 * A) * (-t1 / (2 * R1) - t2 / (2 * R2)
                                          + (-a + 2 * b + c) * W1 / ((a + c) ** 2 * R1)
                                          + (a + 2 * b - c) * W3 / ((a + c) ** 2 * R2))
    assert printed_A == pytest.approx(-ref.load(punch_a, a, c, A), rel=RTOL)
    assert special.case_a_load(a, c, b, R1, R2, A) == pytest.approx(ref.load(punch_a, a, c, A), rel=RTOL)
    ac, cc = 0.4, 0.2
    g = math.asin((ac - cc) / (ac + cc))
    printed_C = (ac + cc) ** 2 / (4 * A) * ((1 / R1 - 1 / R2) * (cc - ac) * math.sqrt(ac * cc) / (ac + cc) ** 2
                                            - 0.5 * (1 / R1 - 1 / R2) * g - (1 / R1 + 1 / R2) * math.pi / 4)
    punch_c = Punch(R1, R2, 0.0)
    assert printed_C == pytest.approx(-ref.load(punch_c, ac, cc, A), rel=RTOL)
    assert special.case_c_load(ac, cc, R1, R2, A) == pytest.approx(ref.load(punch_c, ac, cc, A), rel=RTOL)


def test_E5_lift_off_load_sign():
    """Eq. (Pctob) as printed is -P at c = b."""
    al = 0.6
    tt = math.acos((3 * b - al) / (al + b))
    printed = ((al + b) ** 2 * (-k1 / R1 * tt - math.pi / R)
               - k1 / R1 * 2 * (al - 3 * b) * math.sqrt(2 * b * (al - b))) / (8 * A)
    P = ref.load(PUNCH, al, b, A)
    assert printed == pytest.approx(-P, rel=RTOL)
    assert special.P_lift_off(al, b, R1, R, A) == pytest.approx(P, rel=RTOL)


@pytest.mark.parametrize("Rc", [5.0, math.inf, -40.0])
def test_E6_lift_off_lever_arm_coefficient(Rc):
    """s_lift-off: the printed 3a^2 - 4ab + 3b^2 must be 3a^2 - 4ab + b^2."""
    punch, al = Punch(R1, R2, b, R=Rc), 0.6
    kk1 = punch.k1
    tt = math.acos((3 * b - al) / (al + b))
    root = math.sqrt(b * (al - b))
    ratio = R1 / Rc     # the printed form divided through by R (0 for a flat centre)

    def s_with(coef):
        num = (al - b) * (2 * math.sqrt(2) * b * kk1 / root * coef
                          + 3 * (al + b) ** 2 * (kk1 * tt + math.pi * ratio))
        den = 6 * ((al + b) ** 2 * (kk1 * tt + math.pi * ratio)
                   + 2 * math.sqrt(2) * kk1 * (al - 3 * b) * root)
        return -num / den

    s_true = ref.moment(punch, al, b, A) / ref.load(punch, al, b, A)
    printed = s_with(3 * al**2 - 4 * al * b + 3 * b**2)
    assert abs(printed - s_true) > ERRATUM * abs(s_true)
    assert s_with(3 * al**2 - 4 * al * b + b**2) == pytest.approx(s_true, rel=RTOL)
    assert special.s_lift_off(al, b, R1, Rc) == pytest.approx(s_true, rel=RTOL)


def test_E7_regular_integral_over_the_central_segment():
    """Appendix: int_{-b}^{b} dt/w is pi - beta1 - beta2, not beta1 + beta2 - pi."""
    w = lambda t: 1 / math.sqrt((t + a) * (c - t))
    val = quad(w, -b, b, epsabs=0, epsrel=1e-13)[0]
    assert val == pytest.approx(math.pi - t1 - t2, rel=ROUND_OFF)
    assert abs(val - (t1 + t2 - math.pi)) > ERRATUM * val


def test_E8_horizontal_equilibrium_sliding_term_is_plus_fP():
    """Eq. (horizontal_equilibrium): int -f p dx = +f P (p < 0), not -f P."""
    from threepart.closedform import solve_normal

    sol = solve_normal(PUNCH, 1.5 * ref.load(PUNCH, a, c, A), 0.0, A=A)   # slope 0.45 < SLOPE_LIMIT
    f = 0.3
    h, m = sol.width / 2, (sol.c - sol.a) / 2
    p_paper = lambda th: -float(sol.pressure(m + h * math.cos(th)))   # the paper's p < 0
    kinks = sorted({0.0, math.pi, *[math.acos((t - m) / h) for t in (-b, b)]})
    sliding = sum(quad(lambda th: -f * p_paper(th) * h * math.sin(th), lo, hi, epsabs=0,
                       epsrel=1e-12)[0] for lo, hi in zip(kinks[:-1], kinks[1:]))
    assert sliding == pytest.approx(+f * sol.P, rel=SHEAR_QUADRATURE)


def test_E9_pressure_abbreviated_and_consistency_as_printed_are_right():
    """No erratum: eqs. (consistency_condition), (pressure_abbreviated), (f0) check out."""
    printed_alpha = (k1 / R1 * (a - 2 * b - c) * t1 + k2 / R2 * (a + 2 * b - c) * t2
                     + math.pi * (a - c) / R + k1 / R1 * 2 * W1 - k2 / R2 * 2 * W3) / (2 * math.pi)
    assert printed_alpha == pytest.approx(ref.tilt(PUNCH, a, c), rel=RTOL)
    x = np.array([-0.55, -0.1, 0.4])
    assert np.allclose(formulas.pressure(PUNCH, a, c, A, x),
                       [ref.pressure(PUNCH, a, c, A, xi) for xi in x], rtol=RTOL)

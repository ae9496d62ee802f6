"""Partial slip (Ciavarella-Jaeger) against the defining integral equations."""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import rigid_punch
from threepart import closedform as cf
from threepart.closedform import Punch
from tests import quad_reference as ref
from threepart.tolerances import tolerance

A = rigid_punch(210e3, 0.3)   # rigid punch, steel half-plane, N and mm
#: closed form against the quadrature reference; identities in double precision; exact figures
RTOL = tolerance("closedform", "quadrature").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
EXACT = tolerance("closedform", "exact").limit
#: the stick zone's tilt by quadrature, in units of the slope scale (kappa1 + kappa2) W
TILT_QUADRATURE = 1e-11
#: ∫q dx by quad (epsrel 1e-12) on the pieces between the kinks, against Q
SHEAR_QUADRATURE = 1e-9
#: |q| = f p in the slip zones by construction: rounding of f p minus a zero correction
SLIDING = 1e-13
#: dg/dx in the stick zone by the nested quadrature of strain_in_stick, units of f P / (2W)
STRAIN_QUADRATURE = 1e-8
#: ... and in the slip zone it is of order 1 in those units, far above this
SLIP_STRAIN = 1e-3
#: the fuzz case's corrective pressure exceeds Coulomb's bound by about half (measured 1.5)
BREACH = 1.4
CASES = [(Punch(10.0, 10.0, 1.0), 400.0, 0.0), (Punch(10.0, 5.0, 1.0), 400.0, 0.1),
         (Punch(10.0, 20.0, 1.0, R=1000.0), 4000.0, -0.1), (Punch(10.0, 5.0, 0.0), 400.0, 0.03)]


@pytest.fixture(params=range(len(CASES)))
def normal(request):
    punch, P, s = CASES[request.param]
    return cf.solve_normal(punch, P, s, A=A)


@pytest.mark.parametrize("ratio", [0.2, 0.4, 0.7, -0.4])
def test_stick_zone_side_conditions_by_quadrature(normal, ratio):
    """Eq. (horizontal_equilibrium) and consistency with the normal tilt, on the stick zone."""
    f = 0.5
    slip = cf.solve_partial_slip(normal, ratio * f * normal.P, f)
    a_s, c_s = slip.d + slip.e, slip.d - slip.e
    assert ref.load(normal.punch, a_s, c_s, A) == pytest.approx(normal.P * (1 - abs(ratio)), rel=RTOL)
    scale = normal.punch.kappa1 + normal.punch.kappa2
    assert abs(ref.tilt(normal.punch, a_s, c_s) - normal.alpha) < TILT_QUADRATURE * scale * (a_s + c_s)


@pytest.mark.parametrize("ratio", [0.4, -0.7])
def test_shear_integrates_to_Q_and_has_its_sign(normal, ratio):
    f = 0.5
    Q = ratio * f * normal.P
    slip = cf.solve_partial_slip(normal, Q, f)
    h, m = normal.width / 2, (normal.c - normal.a) / 2
    g = lambda th: float(slip.shear(m + h * math.cos(th))) * h * math.sin(th)
    ends = [math.acos((t - m) / h) for t in (*slip.stick_zone, -normal.punch.b, normal.punch.b)
            if -normal.a < t < normal.c]
    pts = sorted({0.0, math.pi, *ends})
    total = sum(ref.quiet_quad(g, lo, hi, epsabs=0, epsrel=1e-12, limit=200)[0] for lo, hi in zip(pts[:-1], pts[1:]))
    assert total == pytest.approx(Q, rel=SHEAR_QUADRATURE)
    x = np.linspace(-normal.a, normal.c, 501)[1:-1]
    assert np.all(np.sign(slip.shear(x)) * math.copysign(1, Q) >= 0)
    # slip zones carry the sliding traction f p; the stick zone carries less
    lo, hi = slip.stick_zone
    out = (x < lo) | (x > hi)
    assert np.allclose(np.abs(slip.shear(x[out])), f * normal.pressure(x[out]), rtol=SLIDING)
    assert np.all(np.abs(slip.shear(x[~out])) <= f * normal.pressure(x[~out]) * (1 + SLIDING))


def test_no_relative_slip_in_the_stick_zone(normal):
    """Eqs. (integral_equation_tangential), (stick_zone_strain): dg/dx = 0 on the stick zone."""
    slip = cf.solve_partial_slip(normal, 0.4 * 0.5 * normal.P, 0.5)
    lo, hi = slip.stick_zone
    q = lambda t: float(slip.shear(t))
    breaks = (lo, hi, -normal.punch.b, normal.punch.b)
    qscale = 0.5 * normal.P / normal.width
    for x in np.linspace(lo, hi, 7)[1:-1]:
        assert abs(ref.strain_in_stick(q, normal.a, normal.c, breaks, x)) < STRAIN_QUADRATURE * qscale
    # ... and it does not vanish in the slip zones
    x_slip = 0.5 * (-normal.a + lo)
    assert abs(ref.strain_in_stick(q, normal.a, normal.c, breaks, x_slip)) > SLIP_STRAIN * qscale


def test_zero_shear_keeps_the_whole_contact_stuck(normal):
    slip = cf.solve_partial_slip(normal, 0.0, 0.5)
    assert slip.d + slip.e == pytest.approx(normal.a, rel=ROUND_OFF)
    assert slip.d - slip.e == pytest.approx(normal.c, rel=ROUND_OFF)
    assert np.all(slip.shear(np.linspace(-normal.a, normal.c, 11)) == 0)


def test_symmetric_hertz_stick_zone_is_mindlin():
    """Cattaneo-Mindlin: d/a = sqrt(1 - Q/fP), e = 0."""
    sol = cf.solve_normal(Punch(10.0, 10.0, 0.0), 400.0, A=A)
    slip = cf.solve_partial_slip(sol, 0.36 * 0.4 * 400.0, 0.4)
    assert slip.d == pytest.approx(sol.a * 0.8, rel=ROUND_OFF)
    assert abs(slip.e) < EXACT * sol.a


# -- Coulomb's law on a concave centre (the fuzz's silent wrong answer) ------------------------
FUZZ_PUNCH = Punch(129.99466117361627, 14.000802771729001, 1, R=-58.14116867456134)
FUZZ_P, FUZZ_Q, FUZZ_F = 49551.68031495414, -5483.299786174661, 0.12412140892765157


def test_a_stick_zone_that_breaks_coulomb_is_refused_by_name():
    """The single stick zone [-5.15, 1.58] needs p* = -1109 < 0 on the concave centre: |q| = 1.46 f p.

    Checked independently: the shear of that stick zone, q = f (p - p*) with p* the closed
    form's pressure on [-(d+e), d-e], exceeds f p on a dense grid.
    """
    from threepart.closedform import formulas
    from threepart.errors import StickSeparationError, StickZoneError

    normal = cf.solve_normal(FUZZ_PUNCH, FUZZ_P, A=A, tilt="suppressed")
    with pytest.raises(StickSeparationError, match=r"`Q`/\(f P\) = 0.891532: the single stick zone "
                       r"\[-5.15101, 1.58018\] .* breaks Coulomb's law: its corrective pressure p\* = "
                       r"-1109 < 0 at x = -0.17"):
        cf.solve_partial_slip(normal, FUZZ_Q, FUZZ_F)
    assert issubclass(StickSeparationError, StickZoneError)      # so that method="auto" falls back
    x = np.linspace(-normal.a, normal.c, 4001)
    p_star = formulas.pressure(FUZZ_PUNCH, 5.15101, 1.58018, A, x)
    assert np.max(FUZZ_F * np.abs(normal.pressure(x) - p_star) / np.maximum(
        FUZZ_F * normal.pressure(x), 1e-300)) > BREACH


def test_auto_falls_back_and_the_sie_refuses_the_same_stick_zone():
    """The SIE's one-flank stick zone [-5.20, -1.27] would penetrate at x = 1.29: refused too."""
    from threepart import sie, solve
    from threepart.errors import StickSeparationError

    with pytest.raises(StickSeparationError, match="penetrate the half-plane at x = 1.28"):
        sie.solve_partial_slip(sie.solve_normal(FUZZ_PUNCH, FUZZ_P, A=A, tilt="suppressed"),
                               FUZZ_Q, FUZZ_F)
    with pytest.raises(StickSeparationError):
        solve(FUZZ_PUNCH, FUZZ_P, A=A, tilt="suppressed", Q=FUZZ_Q, f=FUZZ_F)


def test_case_c_stick_zone_bound_is_the_true_one():
    """Case C near lift-off: the bound is where the SIE's stick zone stops containing x = 0.

    The message used to say "< 1"; the SIE (an independent method) puts the stick zone's
    left end at x = 0 between Q/fP = 0.01 (end at -0.0045) and 0.065 (end at +0.021).
    """
    from threepart import sie

    punch = Punch(10.0, 5.0, 0.0)
    s = 0.99 * cf.lift_off(punch, 28846.0, A).s_max
    normal = cf.solve_normal(punch, 28846.0, s, A=A)
    with pytest.raises(cf.StickZoneError, match=r"not contain the join x = 0 .* holds for "
                       r"\|Q\|/\(f P\) < 0.0198"):
        cf.solve_partial_slip(normal, 0.065 * 0.3 * 28846.0, 0.3)
    for q, inside in ((0.0195, True), (0.0202, False)):
        lo, _ = sie.solve_partial_slip(normal, q * 0.3 * 28846.0, 0.3).stick_zone
        assert (lo < 0) == inside, (q, lo)

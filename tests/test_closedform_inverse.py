"""Inverse problems: solve, then check against quadrature, limits and identities."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from threepart import rigid_punch
from threepart import closedform as cf
from threepart.closedform import Punch, formulas
from tests import quad_reference as ref
from threepart.tolerances import tolerance

A = rigid_punch(210e3, 0.3)   # rigid punch, steel half-plane, N and mm
#: closed form against the quadrature reference; identities in double precision; exact figures
RTOL = tolerance("closedform", "quadrature").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
EXACT = tolerance("closedform", "exact").limit
#: α of a symmetric case is 0 up to the rounding of a difference of O(1) slopes (rad)
TILT_ZERO = 1e-16
#: a = c of a symmetric case: both ends from one Newton solve that stops at 1e-14
SYMMETRY = 1e-13
#: s = s_max (1 - 1e-9) puts the left end much closer to the join than 1e-3 b
NEAR_JOIN = 1e-3
#: the batch's lever arm against quadrature: a ratio of two quadratures, with no absolute floor for small |s|
BATCH_LEVER_ARM = 1e-9
#: p ~ sqrt(distance): 100 times nearer the end gives 10 times less, to O(distance / overhang)
SQRT_EDGE = 1e-2
#: ∫p dx and ∫x p dx of the returned pressure by _moments' quadrature over the whole contact
MOMENTS = 1e-8


def _moments(sol):
    """Quadrature of the pressure, ``int p dx`` and ``int x p dx``, in ``x = m + h cos(theta)``.

    Gauss-Kronrod on ``[0, pi]`` split at the joins' angles (the ``(x-b) ln|x-b|`` kinks).
    """
    h, m = sol.width / 2, (sol.c - sol.a) / 2
    kinks = [math.acos((t - m) / h) for t in (-sol.punch.b, sol.punch.b) if -sol.a < t < sol.c]
    pts = sorted({0.0, math.pi, *kinks})

    def integral(power):
        f = lambda th: float(sol.pressure(m + h * math.cos(th))) * (m + h * math.cos(th)) ** power \
            * h * math.sin(th)
        return sum(ref.quiet_quad(f, lo, hi, epsabs=0, epsrel=1e-12, limit=200)[0]
                   for lo, hi in zip(pts[:-1], pts[1:]))

    return integral(0), integral(1)


@pytest.mark.parametrize("punch,P,s", [
    (Punch(10.0, 10.0, 1.0), 400.0, 0.3),
    (Punch(10.0, 5.0, 1.0), 400.0, -0.4),
    (Punch(10.0, 20.0, 1.0, R=1000.0), 4000.0, 0.2),
    (Punch(10.0, 20.0, 1.0, R=-5000.0), 400.0, 0.1),
    (Punch(10.0, 5.0, 0.0), 400.0, 0.05),
])
def test_solution_satisfies_the_defining_integrals(punch, P, s):
    sol = cf.solve_normal(punch, P, s, A=A)
    assert ref.load(punch, sol.a, sol.c, A) == pytest.approx(P, rel=RTOL)
    assert ref.moment(punch, sol.a, sol.c, A) / P == pytest.approx(s, rel=RTOL, abs=ROUND_OFF * sol.width)
    assert ref.tilt(punch, sol.a, sol.c) == pytest.approx(sol.alpha, rel=RTOL, abs=TILT_ZERO)


def test_symmetric_punch_central_load_has_no_tilt_and_a_equals_c():
    sol = cf.solve_normal(Punch(10.0, 10.0, 1.0, R=300.0), 2000.0, 0.0, A=A)
    assert sol.a == pytest.approx(sol.c, rel=SYMMETRY) and abs(sol.alpha) < TILT_ZERO


def test_cylinder_shifts_under_a_moment():
    """A single cylinder (R1 = R2, b = 0) just rolls: contact centred at s, alpha = -s/R1."""
    R, P, s = 10.0, 400.0, 0.05
    sol = cf.solve_normal(Punch(R, R, 0.0), P, s, A=A)
    a0 = math.sqrt(2 * P * A * R / math.pi)
    assert (sol.c - sol.a) / 2 == pytest.approx(s, rel=ROUND_OFF)
    assert (sol.a + sol.c) / 2 == pytest.approx(a0, rel=ROUND_OFF)
    assert sol.alpha == pytest.approx(-s / R, rel=ROUND_OFF)


def test_suppressed_tilt_solves_alpha_zero_and_returns_the_holding_lever_arm():
    punch = Punch(10.0, 5.0, 1.0)
    sup = cf.solve_normal(punch, 400.0, A=A, tilt="suppressed")
    assert sup.alpha == 0.0
    assert abs(ref.tilt(punch, sup.a, sup.c)) < ROUND_OFF * (punch.kappa1 + punch.kappa2)
    assert ref.load(punch, sup.a, sup.c, A) == pytest.approx(400.0, rel=RTOL)
    # the lever arm s* holds the punch without the support: free solve at s* has no tilt
    free = cf.solve_normal(punch, 400.0, sup.s, A=A)
    assert abs(free.alpha) < EXACT and free.a == pytest.approx(sup.a, rel=RTOL)
    assert ref.moment(punch, sup.a, sup.c, A) / 400.0 == pytest.approx(sup.s, rel=RTOL)


@pytest.mark.parametrize("punch", [Punch(10.0, 5.0, 1.0), Punch(10.0, 20.0, 1.0, R=1000.0),
                                   Punch(8.0, 12.0, 0.5, R=-3000.0)])
def test_lift_off_edges_reach_the_joins(punch):
    P = 4000.0
    lim = cf.lift_off(punch, P, A)
    # at s_min the right edge is at the join: quadrature gives P and s there
    assert ref.load(punch, lim.a_min, punch.b, A) == pytest.approx(P, rel=RTOL)
    assert ref.moment(punch, lim.a_min, punch.b, A) / P == pytest.approx(lim.s_min, rel=RTOL)
    assert ref.load(punch, punch.b, lim.c_max, A) == pytest.approx(P, rel=RTOL)
    assert ref.moment(punch, punch.b, lim.c_max, A) / P == pytest.approx(lim.s_max, rel=RTOL)
    # just inside the range the solution approaches the joins
    near = cf.solve_normal(punch, P, lim.s_max * (1 - 1e-9), A=A)
    assert near.a - punch.b < NEAR_JOIN * punch.b


def test_lift_off_is_the_mirror_image():
    punch, P = Punch(10.0, 5.0, 1.0, R=800.0), 5000.0
    lim, mir = cf.lift_off(punch, P, A), cf.lift_off(punch.mirrored(), P, A)
    assert lim.s_max == pytest.approx(-mir.s_min, rel=ROUND_OFF)
    assert lim.c_max == pytest.approx(mir.a_min, rel=ROUND_OFF)


def test_batch_round_trip_against_quadrature():
    punch = Punch(10.0, 5.0, 1.0)
    rng = np.random.default_rng(1)
    P = rng.uniform(100, 2000, 200)
    s = rng.uniform(-0.3, 0.3, 200)
    batch = cf.solve_normal_batch(punch, P, s, A=A)
    for i in range(0, 200, 40):
        assert ref.load(punch, batch.a[i], batch.c[i], A) == pytest.approx(P[i], rel=RTOL)
        assert ref.moment(punch, batch.a[i], batch.c[i], A) / P[i] == pytest.approx(s[i], rel=BATCH_LEVER_ARM)
    assert np.allclose(formulas.load(punch, batch.a, batch.c, A), P, rtol=ROUND_OFF)
    assert np.allclose(formulas.lever_arm(punch, batch.a, batch.c), s, rtol=0, atol=ROUND_OFF)


def test_peaks_of_flat_rounded_punch_sit_near_the_joins():
    sol = cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, 0.2, A=A)
    left, right = sol.peaks()
    x = np.linspace(-sol.a, sol.c, 200001)
    p = sol.pressure(x)
    assert max(left.p, right.p) >= p.max() * (1 - ROUND_OFF)
    assert -sol.a < left.x < -sol.punch.b and sol.punch.b < right.x < sol.c


# -- property tests ---------------------------------------------------------------------
@st.composite
def loaded_punch(draw):
    R1 = draw(st.floats(0.5, 2.0))
    R2 = R1 * draw(st.floats(0.2, 5.0))
    b = draw(st.one_of(st.just(0.0), st.floats(0.01, 1.0)))
    kind = draw(st.sampled_from(["flat", "convex", "concave"]))
    R = {"flat": math.inf, "convex": draw(st.floats(5.0, 200.0)),
         "concave": -draw(st.floats(50.0, 500.0))}[kind]
    punch = Punch(R1, R2, b, R=R)
    Av = 1.0
    # loads up to 0.05 (1 + b): contacts inside the arcs and the small-slope limit
    P = cf.P_min(punch, Av) + draw(st.floats(1e-4, 0.05)) * (1 + b)
    try:
        lim = cf.lift_off(punch, P, Av)
    except cf.ArcExtentError:
        assume(False)   # the load's lift-off arm runs past an arc: refused by name (test_hostile)
    frac = draw(st.floats(0.001, 0.999))
    s = lim.s_min + frac * (lim.s_max - lim.s_min)
    return punch, P, s, Av


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(loaded_punch())
def test_property_solve_then_forward_and_pressure(case):
    """100 examples in the default run; the slow profile below draws 1000."""
    check_solve_then_forward_and_pressure(case)


@pytest.mark.slow
@settings(max_examples=1000, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(loaded_punch())
def test_property_solve_then_forward_and_pressure_1000(case):
    check_solve_then_forward_and_pressure(case)


def check_solve_then_forward_and_pressure(case):
    punch, P, s, Av = case
    try:
        sol = cf.solve_normal(punch, P, s, A=Av)
    except cf.SeparationError:
        assume(False)  # concave centre that separates: inadmissible, tested separately
    except (cf.SlopeLimitError, cf.ArcExtentError):
        assume(False)  # past half-plane theory's limits: refused by name, tested in test_hostile
    # forward evaluation gives P and s back
    assert formulas.load(punch, sol.a, sol.c, Av) == pytest.approx(P, rel=RTOL)
    assert formulas.lever_arm(punch, sol.a, sol.c) == pytest.approx(s, rel=RTOL, abs=RTOL * sol.width)
    # pressure >= 0 over the contact, -> 0 at both ends
    x = np.linspace(-sol.a, sol.c, 401)
    p = sol.pressure(x)
    peak = p.max()
    assert p.min() >= -ROUND_OFF * peak and p[0] == 0 and p[-1] == 0
    # bounded ends: p ~ sqrt(distance) within the overhang beyond the joins
    overhang = min(sol.a - sol.punch.b, sol.c - sol.punch.b) if sol.punch.b > 0 else min(sol.a, sol.c)
    eps = 1e-6 * overhang
    for edge, inward in ((-sol.a, 1.0), (sol.c, -1.0)):
        near, nearer = sol.pressure(edge + inward * 100 * eps), sol.pressure(edge + inward * eps)
        assert nearer <= near
        if eps > 1e-12 * sol.width:  # resolvable in double precision
            assert nearer == pytest.approx(0.1 * near, rel=SQRT_EDGE)
    # its integral is P and its centroid is s
    Pq, Mq = _moments(sol)
    assert Pq == pytest.approx(P, rel=MOMENTS)
    assert Mq / Pq == pytest.approx(s, rel=MOMENTS, abs=MOMENTS * sol.width)


def test_the_root_finders_tolerance_is_a_keyword_and_is_checked():
    """``xtol`` reaches every root finder of the closed form: a looser one stops sooner (fewer
    forward evaluations) and still solves eqs. (equilibrium_condition_1) and (2) to the forward
    formulas' own P and s within xtol; outside XTOL_RANGE it is refused by name."""
    from threepart import solve
    from threepart.closedform.newton import XTOL_RANGE

    punch, P, s = Punch(10.0, 5.0, 1.0), 400.0, 0.2
    counts = []
    for xtol in (XTOL_RANGE[1], 1e-9, XTOL_RANGE[0]):
        sol = cf.solve_normal(punch, P, s, A=A, xtol=xtol)
        assert formulas.load(punch, sol.a, sol.c, A) == pytest.approx(P, rel=xtol + RTOL)
        assert formulas.lever_arm(punch, sol.a, sol.c) == pytest.approx(s, abs=(xtol + RTOL) * sol.width)
        counts.append(sol.info["evaluations"])
        batch = cf.solve_normal_batch(punch, [P, 1.5 * P], [s, 0.0], A=A, xtol=xtol)
        assert batch.a[0] == pytest.approx(sol.a, rel=xtol + RTOL)
    assert counts == sorted(counts) and counts[0] < counts[-1], counts
    via = solve(punch, P, s, A=A, method="closedform", xtol=1e-9)
    assert via.a == pytest.approx(cf.solve_normal(punch, P, s, A=A, xtol=1e-9).a, rel=RTOL)
    for bad in (1e-3, 1e-16, float("nan")):
        with pytest.raises(ValueError, match=r"^`xtol` = "):
            cf.solve_normal(punch, P, s, A=A, xtol=bad)
    with pytest.raises(TypeError, match=r"`xtol`"):
        cf.solve_normal_batch(punch, [P], [s], A=A, xtol="1e-9")

"""Every class of bad input raises a ValueError (or named subclass) naming the argument and limit."""
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
#: closed form against the quadrature reference; identities in double precision
RTOL = tolerance("closedform", "quadrature").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
#: 1e-9 inside the lift-off lever arm the contact ends this close to the join (mm)
NEAR_JOIN = 1e-6
#: the load that the concave centre refuses as separating (test_concave_centre_that_separates)
SEPARATING_P = 400.0
#: just above P_sep the centre's smallest pressure is 0: not below -1e-7 (quadrature), not above
#: 1e-5 (the 1e-9 step of the load), of the mean pressure
CENTRE_ZERO = (1e-7, 1e-5)


@pytest.mark.parametrize("kwargs,match", [
    (dict(R1=-1.0, R2=1.0, b=0.1), r"`R1` = -1.0 must be > 0"),
    (dict(R1=1.0, R2=0.0, b=0.1), r"`R2` = 0.0 must be > 0"),
    (dict(R1=1.0, R2=1.0, b=-0.1), r"`b` = -0.1 must be >= 0"),
    (dict(R1=1.0, R2=1.0, b=0.1, R=0.0), r"`R` = 0 is not allowed"),
    (dict(R1=math.nan, R2=1.0, b=0.1), r"`R1` = nan must be a finite number"),
    (dict(R1=1.0, R2=math.inf, b=0.1), r"`R2` = inf must be a finite number"),
    (dict(R1=1.0, R2=1.0, b=0.1, R=math.nan), r"`R` = nan"),
])
def test_bad_geometry(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Punch(**kwargs)


@pytest.mark.parametrize("P,s,Av,tilt,match", [
    (0.0, 0.0, A, "free", r"`P` = 0.0 must be > 0"),
    (-5.0, 0.0, A, "free", r"`P` = -5.0 must be > 0"),
    (math.inf, 0.0, A, "free", r"`P` = inf must be a finite number"),
    (400.0, math.nan, A, "free", r"`s` = nan must be a finite number"),
    (400.0, 0.0, -1.0, "free", r"`A` = -1.0 must be > 0"),
    (400.0, 0.0, A, "locked", r"`tilt` = 'locked' must be one of"),
    (400.0, 0.2, A, "suppressed", r"`s` = 0.2 is an output when tilt='suppressed'"),
])
def test_bad_loads(P, s, Av, tilt, match):
    with pytest.raises(ValueError, match=match):
        cf.solve_normal(Punch(10.0, 5.0, 1.0), P, s, A=Av, tilt=tilt)


def test_lever_arm_past_lift_off_names_the_limit():
    punch, P = Punch(10.0, 5.0, 1.0), 400.0
    lim = cf.lift_off(punch, P, A)
    with pytest.raises(cf.LiftOffError, match=rf"`s` = 0.6 exceeds the lift-off lever arm "
                                               rf"{lim.s_max:.6g} for `P` = 400 \(the left edge"):
        cf.solve_normal(punch, P, 0.6, A=A)
    with pytest.raises(cf.LiftOffError, match=rf"is below the lift-off lever arm {lim.s_min:.6g}"):
        cf.solve_normal(punch, P, -0.6, A=A)
    with pytest.raises(cf.LiftOffError, match="exceeds the lift-off lever arm"):
        cf.solve_normal_batch(punch, [P, P], [0.0, 0.6], A=A)


def test_lift_off_limits_are_real():
    """Just inside the limit solves (an edge at the join); just outside is refused."""
    punch, P = Punch(10.0, 5.0, 1.0), 400.0
    lim = cf.lift_off(punch, P, A)
    inside = cf.solve_normal(punch, P, lim.s_max - 1e-9, A=A)
    assert inside.a - punch.b < NEAR_JOIN
    with pytest.raises(cf.LiftOffError):
        cf.solve_normal(punch, P, lim.s_max + 1e-9, A=A)


def test_load_below_the_convex_centre_limit():
    punch = Punch(10.0, 20.0, 1.0, R=100.0)
    pmin = math.pi * punch.b**2 / (2 * A * punch.R)
    with pytest.raises(cf.LiftOffError, match=rf"`P` = 400 is at or below P_min = pi b\^2/\(2AR\) = "
                                               rf"{pmin:.6g}"):
        cf.solve_normal(punch, 400.0, A=A)
    # P_min is the Hertz load of the central radius with a = b (quadrature)
    assert ref.load(punch, punch.b, punch.b, A) == pytest.approx(pmin, rel=RTOL)


def test_concave_centre_that_separates():
    punch = Punch(10.0, 20.0, 1.0, R=-200.0)
    with pytest.raises(cf.SeparationError, match=r"the concave centre `R` = -200 separates for "
                                                  r"`P` = 400.*splits in two or rests on one flank"):
        cf.solve_normal(punch, 400.0, A=A)


def test_separation_claim_is_true():
    """The refused concave case really has tensile pressure (independent quadrature)."""
    punch, P = Punch(10.0, 20.0, 1.0, R=-200.0), 400.0
    # the load/consistency conditions still have a root; its pressure is negative at the centre
    from threepart.closedform.newton import SCALAR
    from threepart.closedform.normal import solve_state

    st, below, above = solve_state(punch, P, 0.0, A, "free", SCALAR)
    assert not (below or above)
    assert ref.pressure(punch, st.a, st.c, A, 0.0) < 0


@pytest.mark.parametrize("s,tilt", [(0.0, "free"), (0.05, "free"), (0.0, "suppressed")])
def test_separation_load_is_where_the_centre_pressure_vanishes(s, tilt):
    """P_min of a concave centre: just above it solves, with a zero of p on [-b, b] (quadrature)."""
    punch = Punch(10.0, 20.0, 1.0, R=-200.0)
    P_sep = cf.P_min(punch, A, s, tilt)
    assert P_sep > SEPARATING_P  # 400 separates (above)
    sol = cf.solve_normal(punch, P_sep * (1 + 1e-9), s, A=A, tilt=tilt)
    x = np.linspace(-punch.b, punch.b, 201)
    p = np.array([ref.pressure(punch, sol.a, sol.c, A, xi) for xi in x])
    mean = sol.P / sol.width
    assert p.min() >= -CENTRE_ZERO[0] * mean and p.min() <= CENTRE_ZERO[1] * mean
    with pytest.raises(cf.SeparationError, match=rf"needs `P` > {P_sep:.6g}"):
        cf.solve_normal(punch, P_sep * (1 - 1e-6), s, A=A, tilt=tilt)


def test_full_sliding():
    sol = cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, A=A)
    with pytest.raises(cf.FullSlidingError, match=r"\|`Q`\| = 200 >= f P = 200 .*full sliding"):
        cf.solve_partial_slip(sol, 200.0, 0.5)
    with pytest.raises(cf.FullSlidingError, match="full sliding"):
        cf.solve_partial_slip(sol, -250.0, 0.5)


@pytest.mark.parametrize("Q,f,match", [(10.0, 0.0, r"`f` = 0.0 must be > 0"),
                                       (10.0, -0.3, r"`f` = -0.3 must be > 0"),
                                       (math.nan, 0.5, r"`Q` = nan must be a finite number")])
def test_bad_friction_input(Q, f, match):
    sol = cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, A=A)
    with pytest.raises(ValueError, match=match):
        cf.solve_partial_slip(sol, Q, f)


def test_stick_zone_inside_the_central_segment_gives_the_bound():
    sol = cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, 0.1, A=A)
    from threepart.closedform.slip import stick_zone_bound

    bound = stick_zone_bound(sol)
    with pytest.raises(cf.StickZoneError, match=rf"`Q`/\(f P\) = 0.99: the stick zone would end inside "
                                                rf"the central segment .* it holds for \|Q\|/\(f P\) < "
                                                rf"{bound:.6g}"):
        cf.solve_partial_slip(sol, 0.99 * 200.0, 0.5)
    # the bound is where an end of the stick zone reaches a join
    at = cf.solve_partial_slip(sol, (bound - 1e-10) * 200.0, 0.5)
    lo, hi = at.stick_zone
    assert min(-lo, hi) - sol.punch.b < NEAR_JOIN


def test_no_nan_anywhere_on_a_sweep_to_the_limits():
    punch, P = Punch(10.0, 5.0, 1.0, R=-3000.0), 4000.0
    lim = cf.lift_off(punch, P, A)
    s = np.linspace(lim.s_min, lim.s_max, 201)[1:-1]
    b = cf.solve_normal_batch(punch, P, s, A=A)
    assert np.all(np.isfinite(b.a)) and np.all(np.isfinite(b.alpha))
    assert np.all(b.a >= punch.b) and np.all(b.c >= punch.b)


def test_material_errors():
    with pytest.raises(ValueError, match=r"`nu1` = 0.7 must lie in \(-1, 0.5\]"):
        cf.compliance(210e3, 0.7)
    with pytest.raises(ValueError, match=r"`E1` = -1.0 must be > 0"):
        cf.compliance(-1.0, 0.3)
    with pytest.raises(ValueError, match="give both `E2` and `nu2`"):
        cf.compliance(210e3, 0.3, E2=70e3)


@pytest.mark.parametrize("kwargs,match", [
    (dict(R1="10", R2=5.0, b=1.0), r"`R1` = '10' must be a real number, not str"),
    (dict(R1=10.0, R2=None, b=1.0), r"`R2` = None must be a real number, not NoneType"),
    (dict(R1=True, R2=5.0, b=1.0), r"`R1` = True must be a real number, not bool"),
    (dict(R1=10.0, R2=5.0, b=1.0, R="inf"), r"`R` = 'inf' must be a real number"),
])
def test_punch_rejects_non_real_types_before_any_arithmetic(kwargs, match):
    with pytest.raises(TypeError, match=match):
        Punch(**kwargs)


def test_punch_rejects_lengths_outside_double_range():
    with pytest.raises(ValueError, match=r"`R1` = 1e-300 is outside \[1e-60, 1e\+60\]"):
        Punch(R1=1e-300, R2=5.0, b=1.0)
    with pytest.raises(ValueError, match=r"`R1` = 1000.*\(401 characters\) is outside the double"):
        Punch(R1=10**400, R2=5.0, b=1.0)


@pytest.mark.parametrize("P,error,match", [
    (1e308, ValueError, r"`P` = 1e\+308 is outside \[1e-60, 1e\+60\]"),
    (1e-320, ValueError, r"`P` = 1e-320 is outside \[1e-60, 1e\+60\]"),
    (True, TypeError, r"`P` = True must be a real number, not bool"),
])
def test_extreme_loads_are_named_errors_not_overflow(P, error, match):
    with pytest.raises(error, match=match):
        cf.solve_normal(Punch(10.0, 5.0, 1.0), P, A=A)
    with pytest.raises(error, match=match):
        cf.lift_off(Punch(10.0, 5.0, 1.0), P, A)


def test_P_min_validates_its_input():
    with pytest.raises(ValueError, match=r"`A` = -1.0 must be > 0"):
        cf.P_min(Punch(10.0, 5.0, 1.0), -1.0)
    with pytest.raises(ValueError, match=r"`tilt` = 'held' must be one of"):
        cf.P_min(Punch(10.0, 5.0, 1.0), A, tilt="held")
    with pytest.raises(TypeError, match="`punch` must be a threepart.Punch"):
        cf.P_min("punch", A)
    # the convex limit is the Hertz load of the central radius with a = b (quadrature)
    punch = Punch(10.0, 20.0, 1.0, R=100.0)
    assert cf.P_min(punch, A) == pytest.approx(ref.load(punch, punch.b, punch.b, A), rel=RTOL)


def test_no_nan_from_an_edge_a_rounding_error_inside_a_join():
    """A converged edge may sit at ``b - 1e-16``: the pressure is finite and matches the edge at b."""
    punch = Punch(10.0, 5.0, 1.0)
    x = np.linspace(-1.1, 1.0, 301)
    inside = cf.formulas.pressure(punch, 1.1, punch.b - 1e-16, A, x)
    at = cf.formulas.pressure(punch, 1.1, punch.b, A, x)
    assert np.all(np.isfinite(inside))
    np.testing.assert_allclose(inside, at, rtol=0, atol=ROUND_OFF * at.max())


def test_a_failing_iteration_is_a_named_error_never_a_number(monkeypatch):
    """If the closed forms were not finite, the compiled 2-D Newton iteration reports no convergence
    (never a number), and the bracketed roots it hands the case to raise NoConvergenceError."""
    from threepart.closedform import kernel, newton

    b, k0, k1, k2 = 1.0, 0.0, 0.1, 0.2
    for bad in ("value", "dAP"):
        args = {"dAP": 1.0, "value": 0.1} | {bad: float("nan")}
        r, phi, ok, n = kernel.newton_2d(b, k0, k1, k2, args["dAP"], kernel.MOMENT, args["value"], 1.0,
                                         1.0, 0.7, 1e-12, newton.NEWTON_2D_ITER)
        assert not ok and n == newton.NEWTON_2D_ITER
    real_state = newton.State

    class Broken(real_state):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.dAP = self.dAP * float("nan")

    monkeypatch.setattr(newton, "State", Broken)
    monkeypatch.setattr(newton.kernel, "newton_2d", lambda *args: (math.nan, math.nan, False, 16))
    with pytest.raises(cf.NoConvergenceError, match="function is not finite"):
        cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, A=A)

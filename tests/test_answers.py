"""Every answer of every half-plane method obeys the contact laws, and each method refuses the rest.

* The property test draws a few hundred cases as ``tests/test_robustness.py``
  does (radii ``0.03 b`` to ``1000 b``, loads from just above their threshold
  to ``10^4`` times it, lever arms across the lift-off range, both tilt
  modes), and a shear load on each: every answer of the closed form and of
  the SIE, normal and partial slip, must have ``p >= 0`` and ``|q| <= f p``
  on a 4001-point grid of its contact and stick zone (not the points the
  code checks itself), or be one of the named refusals. The reference is
  the laws themselves.
* The tester's findings of issue 29: ``method="auto"`` passed on an SIE
  contact whose pressure is tensile (the separation load, an exact root of
  the closed form, lies above the load); the SIE at ``n = 2`` broke
  Coulomb's law; ``lift_off`` answered past an arc's extent; ``peaks(n)``
  was wrong for small ``n`` (against a dense evaluation of the closed-form
  pressure, eq. pressure_abbreviated).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import threepart
from threepart import Punch, closedform, rigid_punch, sie
from threepart.closedform import formulas
from threepart.closedform.normal import _lift_off_states
from threepart.closedform.newton import SCALAR
from threepart.errors import (ArcExtentError, CoulombError, FullSlidingError, LiftOffError,
                              NoConvergenceError, SeparationError, SlopeLimitError, StickZoneError)
from threepart.tolerances import tolerance
from threepart.problem.validate import SLOPE_LIMIT
from tests.test_robustness import cases

A = rigid_punch(210e3, 0.3)
#: the named refusals a half-plane method may answer with on admissible input
REFUSALS = (LiftOffError, SeparationError, StickZoneError, FullSlidingError, ArcExtentError,
            SlopeLimitError, NoConvergenceError)
#: p >= -P_MIN p_max and |q| - f p <= Q_BOUND f p_max: the table's limits of every answer
P_MIN = tolerance("answer", "p_min").limit
Q_BOUND = tolerance("answer", "q_bound").limit
#: cases of the property test: a few hundred, within about 30 s on one idle core
EXAMPLES = 300
#: uniform grid points of the contact (and of the stick zone) on which an answer is judged
GRID = 4001


def _lever_arm(punch: Punch, P: float, frac: float) -> float:
    """A lever arm ``frac`` of the way to lift-off (the SIE's range); 0 where lift-off is refused."""
    if punch.b == 0:
        return frac * math.sqrt(2 * P * A * min(punch.R1, punch.R2) / math.pi)
    try:
        s_min, s_max = sie.lift_off(punch, P, A)
    except (ArcExtentError, SlopeLimitError):
        return 0.0      # that lift-off lies past the arcs or the slopes: a central load
    return frac * s_max if frac > 0 else -frac * s_min


def _grid(lo: float, hi: float) -> np.ndarray:
    return np.linspace(lo, hi, GRID)[1:-1]


def _assert_compressive(r) -> None:
    x = _grid(-r.a, r.c)
    p = r.pressure(x)
    assert p.min() >= -P_MIN * p.max(), \
        f"{r.method}: p = {p.min():.4g} at x = {x[np.argmin(p)]:.6g} (peak {p.max():.4g}) for {r}"


def _assert_coulomb(r) -> None:
    lo, hi = r.stick_zone
    x = np.concatenate([_grid(-r.a, r.c), _grid(max(lo, -r.a), min(hi, r.c))])
    p, q = r.pressure(x), r.shear(x)
    excess = np.abs(q) - r.f * p
    assert excess.max() <= Q_BOUND * r.f * p.max(), \
        f"{r.method}: |q| - f p = {excess.max():.4g} at x = {x[np.argmax(excess)]:.6g} for {r}"


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(cases(), st.floats(1e-3, 1 - 1e-6), st.floats(0.05, 2.0), st.booleans())
def test_every_answer_is_compressive_and_obeys_coulomb(case, ratio, f, negative):
    punch, P, frac, tilt = case
    s = 0.0 if tilt == "suppressed" else _lever_arm(punch, P, frac)
    assume(-(punch.b + punch.R1) < s < punch.b + punch.R2)
    Q = (-1 if negative else 1) * ratio * f * P
    for method in (closedform, sie):
        try:
            normal = method.solve_normal(punch, P, s, A=A, tilt=tilt)
        except REFUSALS:
            continue
        _assert_compressive(normal)
        try:
            slip = method.solve_partial_slip(normal, Q, f)
        except REFUSALS:
            continue
        _assert_coulomb(slip)


# --- item 1: auto passed on a tensile SIE contact --------------------------------------------
#: the tester's case: a sharp R1 corner and a concave centre, loaded just below separation
TENSILE = dict(punch=Punch(R1=0.0370489869606223, R2=109.15631315882291, b=1, R=-4311.852827280567),
               P=22.63675790703573, s=0.08332458301910572, A=1.7333e-5)


def test_auto_refuses_a_contact_below_its_separation_load():
    punch, P, s, A_ = TENSILE["punch"], TENSILE["P"], TENSILE["s"], TENSILE["A"]
    # the reference: the closed form's separation load at this s, an exact root, lies above P
    assert closedform.P_min(punch, A_, s) > P
    for method in ("auto", "sie"):
        with pytest.raises(SeparationError, match=r"`P` = 22\.6368 with `s` = 0\.0833246: the "
                                                  r"(one-contact|sie's) pressure is tensile"):
            threepart.solve(punch, P, s, A=A_, method=method)


def test_the_shared_check_refuses_a_tensile_answer_that_a_method_let_through():
    # the fake normal result stands in for a method whose own check missed the dip: the
    # Hertz pressure of the fake, less a bump of 2 % of the peak, built with the check on
    from tests.fakes import FakeNormal, _normal

    @dataclass(frozen=True)
    class Dipped(FakeNormal):
        checks_answer = True

        def pressure(self, x):
            x = np.asarray(x, dtype=float)
            return super().pressure(x) - DIP * super().pressure(self.s) * np.exp(-((x - self.s) / (DIP_WIDTH * self.half)) ** 2)

    good = _normal(Punch(10.0, 10.0, 0.0), 400.0, A=A)
    with pytest.raises(SeparationError, match=r"`P` = 400 with `s` = 0: the fake's pressure is tensile, "
                                              r"min p = -\S+ at x = \S+ \(-0\.00"):
        Dipped(**{k: getattr(good, k) for k in good.__dataclass_fields__})


# --- item 2: the SIE broke Coulomb's law at a small n; its kinks are now summed exactly ------------
PUNCH = Punch(10.0, 5.0, 1.0)
NORMAL = closedform.solve_normal(PUNCH, 400.0, 0.1, A=A)
#: a dip of 102 % of the peak at the centre: the pressure there is -2 % of the peak
DIP = 1.02
#: the dip's width, of the contact's half-width: a few of the check's Chebyshev points span it
DIP_WIDTH = 0.05


@pytest.mark.parametrize("n", [2, 4, 8])
def test_the_sie_stick_zone_at_a_small_n_is_the_closed_forms(n):
    # the projected scheme sums each join's kink exactly (sie.projection.ramp_remainder), so a
    # piecewise-quadratic profile is solved exactly at any n: the tester's n = 2 broke Coulomb's law
    got = sie.solve_partial_slip(NORMAL, 100.0, 0.5, n=n)
    ref = closedform.solve_partial_slip(NORMAL, 100.0, 0.5)
    _assert_coulomb(got)
    assert abs(got.d - ref.d) <= tolerance("sie", "d").limit * ref.d
    assert abs(got.e - ref.e) <= tolerance("sie", "e").limit * ref.d


def test_the_shared_check_refuses_a_shear_past_coulomb():
    from tests.fakes import FakeSlip, _normal, _slip

    @dataclass(frozen=True)
    class Bumped(FakeSlip):
        checks_answer = True

    slip = _slip(_normal(Punch(10.0, 10.0, 0.0), 400.0, A=A), 100.0, 0.5)
    fields = {k: getattr(slip, k) for k in slip.__dataclass_fields__}
    Bumped(**fields)                                         # Coulomb's law holds: built
    with pytest.raises(CoulombError, match=r"`Q` = 100 with `f` = 0\.5 on `P` = 400 .* the fake's "
                                           r"shear breaks Coulomb's law, \|q\| exceeds f p by"):
        Bumped(**{**fields, "bound_bump": DIP - 1})


# --- item 3: lift_off answered past an arc's extent -------------------------------------------------
def test_lift_off_past_an_arc_is_refused_like_solve_normal():
    with pytest.raises(ArcExtentError, match=r"`P` = 1e\+06 has no lift-off lever arm s_min .* runs past "
                                             r"the R1 arc's extent -\(b \+ R1\) = -11"):
        closedform.lift_off(PUNCH, 1e6, A)
    with pytest.raises(ArcExtentError, match=r"`P` = 1e\+06 has no lift-off lever arm s_min"):
        sie.lift_off(PUNCH, 1e6, A)
    with pytest.raises(ArcExtentError, match="runs past the R2 arc's extent b \\+ R2 = 6"):
        closedform.solve_normal(PUNCH, 1e6, 0.0, A=A)


@st.composite
def lift_off_cases(draw):
    """A convex or flat centre (``b = 1``) and a load from ``P_min`` to far past the arcs."""
    R1, R2 = (10 ** draw(st.floats(math.log10(0.03), 3)) for _ in range(2))
    R = math.inf if draw(st.booleans()) else 10 ** draw(st.floats(math.log10(0.03), 4))
    punch = Punch(R1, R2, 1.0, R)
    P = max(closedform.P_min(punch, A), 1e-3 / A) * 10 ** draw(st.floats(1e-6, 6))
    return punch, P, draw(st.floats(0.0, 1.0))


#: how far outside (of W) and inside (of the range) the lift-off range s is taken
OUTSIDE, INSIDE = 1e-6, 1e-9


@settings(max_examples=100, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(lift_off_cases())
def test_every_lever_arm_inside_the_lift_off_range_solves(case):
    punch, P, t = case
    lo, hi = _lift_off_states(punch, P, A, SCALAR)
    # the reference: the arcs' geometric extents (eq. 2), against the lift-off contacts
    past = lo.a > punch.b + punch.R1 or hi.c > punch.b + punch.R2
    try:
        lim = closedform.lift_off(punch, P, A)
    except ArcExtentError:
        assert past
        with pytest.raises(ArcExtentError, match=re.escape(f"`P` = {P:.6g} has no lift-off lever arm")):
            sie.lift_off(punch, P, A)
        return
    assert not past
    s_min, s_max = sie.lift_off(punch, P, A)
    assert abs(s_min - lim.s_min) <= tolerance("catalogue", "stored_lift_off").limit * (lim.a_min + punch.b)
    width = lim.s_max - lim.s_min
    s = lim.s_min + (INSIDE + (1 - 2 * INSIDE) * t) * width
    try:
        got = closedform.solve_normal(punch, P, s, A=A)
    except SlopeLimitError:
        # the reference: the same contact's slope by the formulas, past the limit
        got = closedform.solve_normal(punch, P, s, A=A, beyond_small_slopes=True)
        assert got.slope > SLOPE_LIMIT
    assert got.a >= punch.b and got.c >= punch.b
    W = lim.c_max + punch.b
    for beyond in (lim.s_min - OUTSIDE * W, lim.s_max + OUTSIDE * W):
        with pytest.raises(LiftOffError, match=r"`s` = .* the lift-off lever arm"):
            closedform.solve_normal(punch, P, beyond, A=A)


# --- item 4: peaks(n) was wrong for small n ---------------------------------------------------------
#: a dense grid of the closed-form pressure: its maxima lie within p'' h^2/2 ~ 1e-11 of the
#: peaks (h = W/2e6), and their positions within h plus the flat top's sqrt(1e-16) W
DENSE = 2_000_001
PEAK_P, PEAK_X = 1e-9, 1e-5


@pytest.mark.parametrize("n", [2, 3, 17, 2001])
def test_peaks_do_not_depend_on_n(n):
    x = np.linspace(-NORMAL.a, NORMAL.c, DENSE)
    p = formulas.pressure(PUNCH, NORMAL.a, NORMAL.c, A, x)
    W = NORMAL.width
    for peak, side in zip(NORMAL.peaks(n), (x < 0, x > 0)):
        i = int(np.argmax(np.where(side, p, -np.inf)))
        assert abs(peak.p - p[i]) <= PEAK_P * p[i], (n, peak, p[i])
        assert abs(peak.x - x[i]) <= PEAK_X * W, (n, peak, x[i])


@pytest.mark.parametrize("n, error, match", [
    (True, TypeError, r"`n` = True must be an integer, not bool"),
    (2.0, TypeError, r"`n` = 2\.0 must be an integer, not float"),
    (1, ValueError, r"`n` = 1 must lie in \[2, 1000000\]"),
    (0, ValueError, r"`n` = 0 must lie in \[2, 1000000\]"),
    (10**9, ValueError, r"`n` = 1000000000 must lie in \[2, 1000000\]"),
])
def test_peaks_refuse_a_bad_n(n, error, match):
    with pytest.raises(error, match=match):
        NORMAL.peaks(n)


# -- the closed form's pressure on a convex profile: compressive by construction ---------------------
def _convex_contacts(n: int, seed: int):
    """``n`` random convex punches (radii over decades, flat, convex or Hertz centre) and contacts
    ``[-a, c]`` with ``a, c >= b`` from 1e-9 b past a join to 30 b: any contact, solved or not."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        kind = rng.choice(["A", "general", "C"])
        b = 0.0 if kind == "C" else 1.0
        R1, R2 = 10 ** rng.uniform(math.log10(0.03), 3, 2)
        R = 10 ** rng.uniform(math.log10(0.03), 4) if kind == "general" else math.inf
        ell = b or 1.0
        a, c = (b + ell * 10 ** rng.uniform(-9, math.log10(30)) for _ in range(2))
        yield Punch(R1, R2, b, R), a, c


def _divided_difference_pressure(punch: Punch, a: float, c: float, x: float) -> float:
    """``w(x)/(pi A) int_0^pi [v'(t) - v'(x)]/(t - x) dtheta`` at ``t = m + h cos(theta)``
    (``dt/w(t) = dtheta``): eq. (inverted_IE) as a proper integral, by adaptive quadrature."""
    from scipy.integrate import quad

    h, m = 0.5 * (a + c), 0.5 * (c - a)
    vx = float(punch.slope(x))

    def dd(theta: float) -> float:
        t = m + h * math.cos(theta)
        return 0.0 if t == x else (float(punch.slope(t)) - vx) / (t - x)

    kinks = sorted(math.acos(min(1.0, max(-1.0, (t - m) / h))) for t in (-punch.b, punch.b, x))
    total, _ = quad(dd, 0.0, math.pi, points=kinks, epsabs=0.0, epsrel=1e-13, limit=400)
    return math.sqrt((x + a) * (c - x)) * total / (math.pi * A)


def test_on_a_convex_profile_the_closed_forms_pressure_is_the_divided_difference_and_never_tensile():
    """Why the closed form's answer check samples only a concave centre (``NormalSolution.check``).

    On any contact of a convex punch, (1) eq. (pressure_abbreviated) equals the
    divided-difference form of eq. (inverted_IE) by quadrature, and (2) its least value
    over the answer check's points, points 1e-12 to 1e-3 of the width from each edge and
    the joins is >= -1e-12 of its peak (rounding; measured: no negative value at all, and the
    identity within 1.7e-12): the check's 1e-6 could never refuse it.
    """
    from threepart.results.answer import _points

    worst_identity = worst_sign = 0.0
    for i, (punch, a, c) in enumerate(_convex_contacts(400, seed=33)):
        W = a + c
        near = W * np.logspace(-12, -3, 10)
        x = np.concatenate([_points(-a, c), -a + near, c - near,
                            [t for t in (-punch.b, punch.b) if -a < t < c]])
        p = formulas.pressure(punch, a, c, A, x)
        assert np.isfinite(p).all()
        peak = p.max()
        worst_sign = min(worst_sign, p.min() / peak)
        if i % 20 == 0:       # the identity at three points of every 20th contact
            for xi in (-a + 0.3 * W, 0.5 * (c - a) + 1e-3 * W, c - 0.01 * W):
                ref = _divided_difference_pressure(punch, a, c, xi)
                worst_identity = max(worst_identity,
                                     abs(float(formulas.pressure(punch, a, c, A, xi)) - ref) / peak)
    assert worst_sign >= -tolerance("closedform", "round_off").limit
    assert worst_identity <= tolerance("closedform", "quadrature").limit


def test_a_concave_centres_closed_form_answer_is_still_sampled():
    """A concave centre's pressure may be tensile: a contact built below its separation load is refused."""
    punch = Punch(1.0, 1.0, 1.0, -2.0)
    with pytest.raises(SeparationError, match="pressure is nowhere compressive"):
        closedform.NormalSolution(punch, A, 1.05, 1.05, 0.0, 1.0, 0.0)
    closedform.NormalSolution(Punch(1.0, 1.0, 1.0), A, 1.05, 1.05, 0.0, 1.0, 0.0)   # convex: never refused
    with pytest.raises(NoConvergenceError, match="not finite"):                    # unless not a number
        closedform.NormalSolution(Punch(1.0, 1.0, 1.0), A, math.nan, 1.05, 0.0, 1.0, 0.0)

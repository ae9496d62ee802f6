"""The closed form never fails on admissible input: wide random cases against the SIE.

Cases are drawn as a designer's sweep would be, far wider than the catalogue:

* radii ``R1``, ``R2`` from ``0.03 b`` to ``1000 b``; case A (flat centre), B
  (concave, ``|R|`` from ``b`` to ``10^4 b``), C (``b = 0``) and the general
  convex centre (``R`` from ``0.03 b`` to ``10^4 b``);
* loads from just above their threshold to ``10^4`` times it: ``P_min`` of a
  convex centre, the separation load of a concave one, and for the flat
  centre and case C the load ``P_ref`` that pushes a Hertz contact of the
  larger radius ``1e-2`` of ``b`` (or of the smaller radius) wide;
* lever arms across the whole lift-off range, taken from the SIE's own
  lift-off lever arms (for ``b = 0``: within a Hertz half-width);
* both tilt modes.

The SIE (:mod:`threepart.sie`, projected scheme: its contact ends carry no
discretisation error) is the reference. Where it finds a contact with both
edges on the outer segments, the closed form must find the same one to
``1e-8 W``; where the SIE's contact leaves that framework (an edge at or
inside a join, or a one-flank contact) or separates, the closed form must
refuse with :class:`~threepart.LiftOffError` or
:class:`~threepart.SeparationError`. Where the SIE's contact runs past an arc
or past the small-slope limit, both refuse (``ArcExtentError``,
``SlopeLimitError``). It must never raise anything else.

The partial-slip sweep draws ``Q/(fP)`` and ``f`` on top of the same cases:
every closed-form stick zone obeys Coulomb's law ``|q| <= f p`` (on a dense
grid and at the exact minima of ``p*`` and ``p - p*``) and agrees with the
SIE's to ``1e-8 W``; where the closed form refuses, the SIE answers or
refuses with the same named error.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from threepart import (LiftOffError, NoConvergenceError, Punch, SeparationError, closedform,
                       rigid_punch, sie)
from threepart.closedform.slip import coulomb_margin
from threepart.errors import (ArcExtentError, SlopeLimitError, StickSeparationError,
                              StickZoneError)

#: the refusals of a contact past the arcs or the small-slope limit (both methods)
LIMITS = (SlopeLimitError, ArcExtentError)

A = rigid_punch(210e3, 0.3)
B = 1.0
AGREE = 1e-8          # |Δa|, |Δc|, |Δs| in units of W; |Δα| in units of W/min(R1, R2)
EXAMPLES = 500
#: the SIE's pressure by the inversion integral where the closed form refused a separating
#: contact: its minimum lies below this fraction of the mean (quadrature's noise about 0)
SEPARATION = 1e-9
#: the closed form's lift-off lever arms against the SIE's, both exact roots near P_sep
LIFT_OFF = 1e-9


@st.composite
def cases(draw):
    kind = draw(st.sampled_from(["A", "B", "C", "general"]))
    tilt = draw(st.sampled_from(["free", "suppressed"]))
    R1, R2 = (B * 10 ** draw(st.floats(math.log10(0.03), 3)) for _ in range(2))
    b = 0.0 if kind == "C" else B
    R = math.inf
    if kind == "B":
        R = -B * 10 ** draw(st.floats(0, 4))
    elif kind == "general":
        R = B * 10 ** draw(st.floats(math.log10(0.03), 4))
    punch = Punch(R1, R2, b, R)
    threshold = closedform.P_min(punch, A)
    if threshold <= 0:
        ell = b if b > 0 else min(R1, R2)
        threshold = math.pi * (1e-2 * ell) ** 2 / (2 * A * max(R1, R2))
    P = threshold * 10 ** draw(st.floats(1e-6, 4))
    frac = draw(st.floats(-1 + 1e-6, 1 - 1e-6))
    return punch, P, frac, tilt


def _lever_arm(punch: Punch, P: float, frac: float) -> float:
    if punch.b == 0:
        return frac * math.sqrt(2 * P * A * min(punch.R1, punch.R2) / math.pi)
    try:
        s_min, s_max = sie.lift_off(punch, P, A)
    except ArcExtentError:
        # the lift-off contact runs past an arc: draw across the footprint instead, where both
        # methods must agree or refuse alike (ArcExtentError, LiftOffError)
        s_min, s_max = -(punch.b + punch.R1), punch.b + punch.R2
    return frac * s_max if frac > 0 else -frac * s_min


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(cases())
def test_closed_form_agrees_with_the_sie_or_refuses_rightly(case):
    punch, P, frac, tilt = case
    s = 0.0 if tilt == "suppressed" else _lever_arm(punch, P, frac)
    if not -(punch.b + punch.R1) < s < punch.b + punch.R2:
        # a lever arm off the punch's footprint is refused by both before any numerics
        for solver in (sie, closedform):
            with pytest.raises(ValueError, match="`s` = .* lies outside the punch's footprint"):
                solver.solve_normal(punch, P, s, A=A, tilt=tilt)
        return
    try:
        ref = sie.solve_normal(punch, P, s, A=A, tilt=tilt, n=16)
        sie_error = None
    except (SeparationError, *LIMITS) as exc:
        ref, sie_error = None, exc
    except NoConvergenceError:
        assume(False)  # the reference found nothing to compare with
    try:
        got = closedform.solve_normal(punch, P, s, A=A, tilt=tilt)
        cf_error = None
    except (LiftOffError, SeparationError, *LIMITS) as exc:
        got, cf_error = None, exc
    if sie_error is not None:
        assert cf_error is not None, f"SIE refuses ({sie_error}), the closed form solves {got}"
        return
    assert ref is not None
    inside = min(ref.a, ref.c) > punch.b
    if not inside:
        assert cf_error is not None, f"SIE contact [{-ref.a}, {ref.c}] leaves the framework, " \
                                     f"the closed form solves {got}"
        return
    if isinstance(cf_error, SeparationError):
        # at the separation load the SIE's acceptance is within its truncation bound: judge the
        # refusal by the inversion integral (adaptive quadrature) on the SIE's contact
        from threepart.closedform.normal import _centre_pressure_min

        x = np.r_[np.linspace(-punch.b, punch.b, 101), _centre_pressure_min(punch, ref.a, ref.c, A)[0]]
        p = sie.pressure_by_quadrature(punch, A, ref.a, ref.c, ref.alpha, x)
        mean = P / ref.width
        assert p.min() < SEPARATION * mean, f"closed form refuses a contact whose pressure is >= 0: {cf_error}"
        return
    assert cf_error is None, f"SIE solves [{-ref.a}, {ref.c}] inside the framework; closed form: {cf_error}"
    assert got is not None
    W = ref.a + ref.c
    assert abs(got.a - ref.a) <= AGREE * W and abs(got.c - ref.c) <= AGREE * W, (got, ref)
    assert abs(got.s - ref.s) <= AGREE * W
    assert abs(got.alpha - ref.alpha) <= AGREE * W / min(punch.R1, punch.R2)


def _coulomb_excess(r, minima: bool = True) -> float:
    """Largest ``(|q| - f p)/(f P/W)`` of a slip result: a dense grid, the joins, the stick
    zone's ends and (``minima``: a closed-form stick zone) the exact minima of ``p*`` and
    ``p - p*``, each evaluated by the result's own ``shear`` and ``pressure``."""
    n = r.normal
    lo, hi = r.stick_zone
    minima = [x for (x, _) in coulomb_margin(n, -lo, hi)] if minima else []
    x = np.r_[np.linspace(-n.a, n.c, 4001), -n.punch.b, n.punch.b, lo, hi, minima]
    x = x[(x >= -n.a) & (x <= n.c)]
    excess = np.abs(r.shear(x)) - r.f * r.pressure(x)
    return float(excess.max() / (r.f * n.P / n.width))


#: the shear's excess over f p allowed on the grid, in units of the mean f P/W: the closed
#: forms' rounding (p and p* are each accurate to ~1e-13 of the peak)
COULOMB = 1e-9


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(cases(), st.floats(1e-3, 0.999), st.sampled_from([1.0, -1.0]), st.floats(0.05, 1.0))
def test_partial_slip_obeys_coulomb_and_agrees_with_the_sie(case, ratio, sign, f):
    """500 random admissible slip cases (concave centres included), against the SIE."""
    punch, P, frac, tilt = case
    s = 0.0 if tilt == "suppressed" else _lever_arm(punch, P, frac)
    try:
        normal = closedform.solve_normal(punch, P, s, A=A, tilt=tilt)
    except (LiftOffError, SeparationError, *LIMITS):
        assume(False)           # the normal problem is tested above
    except ValueError as exc:
        assert "footprint" in str(exc)
        assume(False)           # the normal problem is tested above
    Q = sign * ratio * f * P
    try:
        got = closedform.solve_partial_slip(normal, Q, f)
        cf_error = None
    except StickZoneError as exc:
        got, cf_error = None, exc
    try:
        ref = sie.solve_partial_slip(normal, Q, f, n=16)
        sie_error = None
    except StickSeparationError as exc:
        ref, sie_error = None, exc
    if cf_error is not None:
        # the SIE answers where the stick zone ends on the centre; a stick zone that breaks
        # Coulomb's law is refused by both with the same named error, or answered by the SIE
        if sie_error is not None:
            assert isinstance(cf_error, StickSeparationError), (cf_error, sie_error)
            return
        assert ref is not None
        # its p* carries the truncation error of 16 sine terms, bounded by `pressure_bound`
        slack = ref.info["pressure_bound"] / (normal.P / normal.width)
        assert _coulomb_excess(ref, minima=False) <= COULOMB + slack, f"the SIE's fallback breaks Coulomb: {ref}"
        if not isinstance(cf_error, StickSeparationError):
            lo, hi = ref.stick_zone
            assert not (lo <= -punch.b and hi >= punch.b and punch.b > 0) or \
                abs(lo + punch.b) < AGREE * normal.width or abs(hi - punch.b) < AGREE * normal.width, \
                f"closed form refuses ({cf_error}), the SIE's stick zone {ref.stick_zone} holds the centre"
        return
    assert got is not None
    assert _coulomb_excess(got) <= COULOMB, f"closed-form stick zone breaks |q| <= f p: {got}"
    assert sie_error is None, f"the SIE refuses ({sie_error}), the closed form answers {got}"
    assert ref is not None
    W = normal.width
    assert abs(got.d - ref.d) <= AGREE * W and abs(got.e - ref.e) <= AGREE * W, (got, ref)


@pytest.mark.parametrize("P", [1.0, 3.0, 10.0, 30.0, 100.0, 1e3, 1e4])
def test_suppressed_tilt_at_every_load(P):
    """Light loads that used to stall the damped Newton: agreement with the SIE."""
    punch = Punch(10.0, 5.0, 1.0)
    got = closedform.solve_normal(punch, P, A=A, tilt="suppressed")
    ref = sie.solve_normal(punch, P, A=A, tilt="suppressed", n=16)
    W = ref.a + ref.c
    assert abs(got.a - ref.a) <= AGREE * W and abs(got.c - ref.c) <= AGREE * W
    assert abs(got.s - ref.s) <= AGREE * W
    batch = closedform.solve_normal_batch(punch, [P, 2 * P], A=A, tilt="suppressed")
    assert abs(batch.a[0] - ref.a) <= AGREE * W and batch.alpha[0] == 0.0


def test_concave_centre_near_its_separation_load():
    """Punch(10, 5, 1, R=-20) at P = 100 used to end in NoConvergenceError."""
    punch = Punch(10.0, 5.0, 1.0, R=-20.0)
    P_sep = closedform.P_min(punch, A)
    for P in (100.0, 0.5 * P_sep, P_sep * (1 - 1e-6)):
        with pytest.raises(SeparationError):
            closedform.solve_normal(punch, P, A=A)
    got = closedform.solve_normal(punch, P_sep * 1.01, A=A)
    ref = sie.solve_normal(punch, P_sep * 1.01, A=A, n=16)
    assert abs(got.a - ref.a) <= AGREE * ref.width
    lim = closedform.lift_off(punch, P_sep * 1.01, A)
    s_min, s_max = sie.lift_off(punch, P_sep * 1.01, A)
    assert lim.s_min == pytest.approx(s_min, rel=LIFT_OFF) and lim.s_max == pytest.approx(s_max, rel=LIFT_OFF)


@pytest.mark.parametrize("ratio", [1e3, 1e-3])
def test_strongly_asymmetric_punch_inside_the_lift_off_range(ratio):
    punch = Punch(1.0 * ratio, 1.0, 1.0) if ratio > 1 else Punch(1.0, 1.0 / ratio, 1.0)
    P = 1e3
    s_min, s_max = sie.lift_off(punch, P, A)
    for frac in (-0.9, -0.5, 0.0, 0.5, 0.9):
        s = frac * s_max if frac > 0 else -frac * s_min
        got = closedform.solve_normal(punch, P, s, A=A)
        ref = sie.solve_normal(punch, P, s, A=A, n=16)
        assert abs(got.a - ref.a) <= AGREE * ref.width and abs(got.c - ref.c) <= AGREE * ref.width

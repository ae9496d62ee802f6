"""Past the paper: contacts and stick zones the closed form refuses, answered by the SIE.

Every figure is checked against a reference that owes nothing to the SIE
(:mod:`tests.beyond_reference`): the paper's own forward formulas on a shifted
punch for an edge on the central segment, Hertz for the punch on one corner,
and scipy quadrature for the gap outside a contact. The closed form must
refuse each of these with the right named error, and ``method="auto"`` must
answer with the SIE and say why.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import quad

from threepart import Punch, closedform as cf, rigid_punch, sie, solve
from threepart.problem.catalogue import get_case
from threepart.cli import main
from threepart.errors import LiftOffError, SeparationError, StickZoneError
from threepart.tolerances import tolerance

from . import beyond_reference as ref

A = rigid_punch(210e3, 0.3)
P = 28846.0
#: the tolerance of an exact method (a, c, d, e in units of W) against an exact reference
EXACT = tolerance("sie-exact", "beyond").limit
#: the peak's position by a bounded search on Hertz's flat maximum, in units of W
PEAK_X = 1e-6
#: the gap's slope outside the contact against quad of the Cauchy integral (epsrel 1e-11) of the
#: SIE's pressure, relative and in units of |α|
GAP_SLOPE, GAP_SLOPE_ABS = 1e-7, 1e-9
#: the command line's contact ends (printed to 12 digits) against the reference roots, in units of W
CLI = 1e-9
#: the issue's acceptance figures past lift-off on the default mesh: a, c in W, p of the peak
ACCEPT_ENDS, ACCEPT_PRESSURE = 2e-4, 2e-3

EDGE_ON_CENTRE = {                    # (punch, s): the left edge lies on the central segment
    "flat, equal radii": (Punch(10, 10, 1), 1.6),
    "flat, R2/R1 = 0.5": (Punch(10, 5, 1), 1.2),
    "convex centre R = 30": (Punch(10, 10, 1, R=30), 1.5),
}
ON_CORNER = {                         # (punch, s): the punch rests on its R2 corner alone
    "flat": (Punch(10, 10, 1), 2.5),
    # R2 = 10: the contact on the corner alone stays inside the small-slope limit (tilt -0.22)
    "convex centre, R2/R1 = 0.5": (Punch(20, 10, 1, R=60), 3.0),
}


@pytest.mark.parametrize("name", EDGE_ON_CENTRE)
def test_an_edge_on_the_centre_matches_the_shifted_punch(name):
    punch, s = EDGE_ON_CENTRE[name]
    left, right = ref.edge_on_centre(punch, P, A, s=s)
    r = solve(punch, P, s, A=A)
    assert r.method == "sie" and "exceeds the lift-off lever arm" in r.info["auto"]
    assert not r.within_paper and r.segments == ("centre", "R2")
    W = r.width
    assert abs(-r.a - left) <= EXACT * W and abs(r.c - right) <= EXACT * W
    scale = punch.slope(r.c) - punch.slope(-r.a)
    assert abs(r.alpha - ref.forward(punch, left, right, A)[2]) <= EXACT * scale
    with pytest.raises(LiftOffError, match="exceeds the lift-off lever arm"):
        cf.solve_normal(punch, P, s, A=A)


def test_the_mirror_image_puts_the_right_edge_on_the_centre():
    punch, s = EDGE_ON_CENTRE["flat, R2/R1 = 0.5"]
    left, right = ref.edge_on_centre(punch, P, A, s=s)
    r = solve(punch.mirrored(), P, -s, A=A)
    assert r.segments == ("R1", "centre")
    assert abs(r.a - right) <= EXACT * r.width and abs(r.c + left) <= EXACT * r.width


@pytest.mark.parametrize("name", ON_CORNER)
def test_the_punch_on_one_corner_is_a_shifted_hertz_contact(name):
    punch, s = ON_CORNER[name]
    left, right, alpha = ref.on_corner(punch, P, s, A)
    r = solve(punch, P, s, A=A)
    assert r.method == "sie" and r.segments == ("R2",) and not r.within_paper
    W = r.width
    assert abs(-r.a - left) <= EXACT * W and abs(r.c - right) <= EXACT * W
    assert abs(r.alpha - alpha) <= EXACT * abs(alpha)
    x = np.linspace(left, right, 401)[1:-1]   # the ends: 0 against the square root of round-off
    hertz = cf.special.hertz_pressure(0.5 * W, punch.R2, A, x - s)
    pressure = tolerance("sie-exact", "beyond_pressure").limit
    assert np.max(np.abs(r.pressure(x) - hertz)) <= pressure * hertz.max()
    peak = r.peaks()[1]
    assert abs(peak.x - s) <= PEAK_X * W and peak.p == pytest.approx(hertz.max(), rel=pressure)


@pytest.mark.parametrize("name, q", [("near_lift_off", 0.7), ("caseA_moment", 0.9), ("general", 0.9)])
def test_a_stick_zone_that_ends_on_the_centre(name, q):
    """The corrective problem has the normal tilt and load P - |Q|/f: the shifted punch again."""
    k = get_case(name).resolved()
    Q, f = q * 0.5 * k.P, 0.5
    with pytest.raises(StickZoneError, match="inside the central segment"):
        cf.solve_partial_slip(cf.solve_normal(k.punch, k.P, k.s, A=k.A), Q, f)
    r = solve(k.punch, k.P, k.s, A=k.A, Q=Q, f=f)
    assert r.method == "sie" and not r.within_paper and r.stick_segments == ("centre", "R2")
    left, right = ref.edge_on_centre(k.punch, k.P - Q / f, k.A, alpha=r.alpha)
    lo, hi = r.stick_zone
    assert abs(lo - left) <= EXACT * r.normal.width and abs(hi - right) <= EXACT * r.normal.width
    # the default SIE call needs no flag for it
    direct = sie.solve_partial_slip(sie.solve_normal(k.punch, k.P, k.s, A=k.A), Q, f)
    assert direct.stick_zone == pytest.approx(r.stick_zone, abs=EXACT * r.normal.width)


def test_a_stick_zone_on_one_corner_is_hertz():
    """At Q/fP = 0.9 near lift-off the stick zone sits on R2 alone: Hertz of load P/10 at the tilt."""
    k = get_case("near_lift_off").resolved()
    r = solve(k.punch, k.P, k.s, A=k.A, Q=0.45 * k.P, f=0.5)
    h = math.sqrt(2 * 0.1 * k.P * k.A * k.punch.R2 / math.pi)
    centre = k.punch.b - r.alpha * k.punch.R2          # where α + g'(x) = 0 on R2
    assert r.stick_segments == ("R2",)
    assert r.stick_zone == pytest.approx((centre - h, centre + h), abs=EXACT * r.normal.width)


# -- separation: refused by the SIE, with the gap checked by quadrature -----------------------
CONCAVE = Punch(10, 10, 1, R=-20)


def test_the_gap_slope_outside_the_contact_matches_quadrature():
    """``v' - α - (A/π)∫p(t)/(x - t)dt`` outside the contact, by scipy quad of the SIE pressure."""
    from threepart.sie.normal import _gap_slope_outside

    r = sie.solve_normal(CONCAVE, 8000.0, 2.5, A=A)
    m, h = 0.5 * (r.c - r.a), 0.5 * r.width
    for xi in (-2.5, -1.3, 1.05, 1.7):
        x = m + h * xi
        integral = quad(lambda t: float(r.pressure(t)) / (x - t), -r.a, r.c, limit=400,
                        points=[1.0], epsabs=0, epsrel=1e-11)[0]
        expected = float(CONCAVE.slope(x, r.alpha)) - A / math.pi * integral
        got = float(_gap_slope_outside(CONCAVE, m, h, r.alpha, np.array([xi]))[0])
        assert got == pytest.approx(expected, rel=GAP_SLOPE, abs=GAP_SLOPE_ABS * abs(r.alpha)), xi


@pytest.mark.parametrize("P_, s, why", [(5000.0, 1.6, "would penetrate the half-plane"),
                                        (14000.0, 0.0, "pressure is tensile")])
def test_a_contact_that_separates_is_refused_by_every_method(P_, s, why):
    with pytest.raises(SeparationError, match=why):
        sie.solve_normal(CONCAVE, P_, s, A=A)
    with pytest.raises(SeparationError):
        cf.solve_normal(CONCAVE, P_, s, A=A)
    with pytest.raises(SeparationError, match="separates into two zones"):
        solve(CONCAVE, P_, s, A=A)


def test_a_one_flank_contact_is_answered_and_its_gap_stays_open():
    """On the R2 flank alone the single contact is valid: Hertz again, and auto says so."""
    r = solve(CONCAVE, 8000.0, 2.5, A=A)
    left, right, _ = ref.on_corner(CONCAVE, 8000.0, 2.5, A)
    assert r.method == "sie" and r.segments == ("R2",)
    assert abs(-r.a - left) <= EXACT * r.width and abs(r.c - right) <= EXACT * r.width


# -- the command line ---------------------------------------------------------------------
GEOM = ["--E", "210000", "--nu", "0.3", "--rigid", "--P", str(P)]


@pytest.mark.parametrize("name", ["flat, equal radii", "convex centre R = 30"])
def test_the_command_line_answers_past_lift_off(capsys, name):
    punch, s = EDGE_ON_CENTRE[name]
    geo = ["--R1", str(punch.R1), "--R2", str(punch.R2), "--b", str(punch.b), "--R", str(punch.R)]
    assert main(["solve", *geo, *GEOM, "--s", str(s), "--method", "auto", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    left, right = ref.edge_on_centre(punch, P, A, s=s)
    W = right - left
    assert out["method"] == "sie" and "lift-off" in out["method_note"]
    assert abs(out["contact"]["left"] - left) <= CLI * W and abs(out["contact"]["right"] - right) <= CLI * W
    assert out["segments"] == ["centre", "R2"] and out["within_paper"] is False


def test_the_command_line_answers_on_one_corner(capsys):
    punch, s = ON_CORNER["flat"]
    assert main(["solve", "--R1", "10", "--R2", "10", "--b", "1", *GEOM, "--s", str(s), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    left, right, _ = ref.on_corner(punch, P, s, A)
    assert out["segments"] == ["R2"]
    assert abs(out["contact"]["left"] - left) <= CLI * (right - left)
    assert abs(out["contact"]["right"] - right) <= CLI * (right - left)


def test_a_concave_centre_is_answered_or_refused_never_left_unconverged():
    """Across the separation transition every load is answered (one zone) or refused (two)."""
    verdicts = {}
    for P_ in (5000.0, 25000.0, 40000.0):
        for s in np.linspace(0.2, 3.0, 8):
            try:
                r = sie.solve_normal(CONCAVE, P_, s, A=A)
            except SeparationError:
                verdicts[P_, s] = "two zones"
                continue
            verdicts[P_, s] = r.segments
            if r.segments == ("R2",):      # on one flank: Hertz, independently
                left, right, _ = ref.on_corner(CONCAVE, P_, s, A)
                assert abs(-r.a - left) <= EXACT * r.width and abs(r.c - right) <= EXACT * r.width
    assert {"two zones", ("R2",), ("R1", "centre", "R2")} <= set(verdicts.values()), verdicts


@pytest.mark.parametrize("s, zones", [(1.4, 1), (1.8, 2)])
def test_the_fem_sees_the_separation_the_sie_refuses(s, zones):
    """P = 40000 N/mm on the concave centre: one zone at s = 1.4 mm, two at 1.8 mm (FE active set)."""
    from threepart import fem

    P_ = 40000.0
    try:
        r = fem.solve_normal(CONCAVE, P_, s, E=210e3, nu=0.3, mesh="quick")
        inside = (r.x_nodes > -r.a) & (r.x_nodes < r.c)
        fem_zones = 1 + int(np.any(inside & (r.p_nodes <= 0)))
    except SeparationError:
        fem_zones = 2
    assert fem_zones == zones
    if zones == 2:
        with pytest.raises(SeparationError):
            sie.solve_normal(CONCAVE, P_, s, A=A)
    else:
        ok = sie.solve_normal(CONCAVE, P_, s, A=A)
        limit = tolerance("fem-quick", "a").limit
        assert abs(ok.a - r.a) <= limit * ok.width and abs(ok.c - r.c) <= limit * ok.width


# -- the FEM past lift-off: an independent physical model against the exact references ------
FEM_BEYOND = ["beyond_edge_on_flat", "beyond_convex_edge", "beyond_corner"]


def _fem_against_reference(name: str, mesh: str) -> dict[str, float]:
    """FE errors against the exact reference of the case (shifted punch or Hertz, not the SIE)."""
    from threepart import fem

    k = get_case(name).resolved()
    if name == "beyond_corner":
        left, right, alpha = ref.on_corner(k.punch, k.P, k.s, k.A)
    else:
        left, right = ref.edge_on_centre(k.punch, k.P, k.A, s=k.s)
        alpha = ref.forward(k.punch, left, right, k.A)[2]
    r = fem.solve_normal(k.punch, k.P, k.s, E=k.E, nu=k.nu, mesh=mesh)
    exact = sie.solve_normal(k.punch, k.P, k.s, A=k.A)       # its pressure: exact to 1e-10 (above)
    W = right - left
    x = np.linspace(left + 0.05 * W, right - 0.05 * W, 801)
    peak = max(p.p for p in exact.peaks())
    assert r.segments == exact.segments
    return {"a": abs(-r.a - left) / W, "c": abs(r.c - right) / W,
            "alpha": abs(r.alpha - alpha) / abs(alpha),
            "p": float(np.max(np.abs(r.pressure(x) - exact.pressure(x)))) / peak}


@pytest.mark.parametrize("name", FEM_BEYOND)
def test_the_fem_answers_past_lift_off_on_the_quick_mesh(name):
    err = _fem_against_reference(name, "quick")
    assert err["a"] <= tolerance("fem-quick", "a").limit and err["c"] <= tolerance("fem-quick", "c").limit
    assert err["p"] <= tolerance("fem-quick", "p_interior_max").limit, err


@pytest.mark.slow
@pytest.mark.parametrize("name", FEM_BEYOND)
def test_the_fem_answers_past_lift_off_to_2e_4_W_on_the_default_mesh(name):
    """The acceptance figures: a, c within 2e-4 W, the pressure within 2e-3 of the peak."""
    err = _fem_against_reference(name, "default")
    assert err["a"] <= ACCEPT_ENDS and err["c"] <= ACCEPT_ENDS and err["p"] <= ACCEPT_PRESSURE, err


def test_an_option_the_method_does_not_take_is_named():
    with pytest.raises(ValueError, match=r"`mesh` is not an option of method 'auto' \(its options: n, scheme\)"):
        solve(Punch(10, 10, 1), P, 1.6, A=A, mesh="quick")
    with pytest.raises(ValueError, match=r"`n` is not an option of method 'closedform' \(its options: xtol\)"):
        solve(Punch(10, 10, 1), P, 0.1, A=A, method="closedform", n=64)
    with pytest.raises(ValueError, match="`method` = 'magic' must be one of auto, closedform, sie, fem"):
        solve(Punch(10, 10, 1), P, 0.1, A=A, method="magic")

"""The periodic steady state of in-phase loading (issue 31, docs/STEADY_STATE.md).

References, each independent of the code under test:

* P and s constant: today's fretting cycle (Masing's rule on the loading
  states), with and without a mean shear and a bulk stress (eq. S14);
* Hertz (``b = 0``, ``R1 = R2``, ``s = 0``): the stick zone from Hertz's
  formulas alone, ``c'^2 = 2 A R P*/π`` and the Nowell–Hills-type offset
  ``x0 = sign(ΔQ) A Δsigma R/(8 f)`` (eq. S15), and the energy in the closed form
  of eq. (S16), a one-dimensional integral in ``lam`` taken by ``quad``;
* the friction work by brute quadrature: the slip ``2 f gap* - f gap_lam`` of
  eq. (S7) differenced in ``lam`` (not the rate formula S9), times ``f p``;
* the SIE against the closed form, and past the closed form against the SIE's
  own fretting cycle;
* the rate formulas (S8, S9) against central differences, the shakedown bound
  ``|ΔQ| <= f |ΔP|`` (Mindlin–Deresiewicz, Jäger) and the slip-direction bound at
  the start of a half-cycle, ``|Δsigma| <= 4 |ΔQ|/(π h)`` (eq. S10 at ``lam -> 0``).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

import threepart
from threepart import Punch, closedform as cf, registry, rigid_punch, sie
from threepart.closedform import formulas
from threepart.closedform.fretting import stick_gap
from threepart.closedform.steady import _Cycle
from threepart.errors import (CycleSlipReversalError, FullSlidingError, LiftOffError, OneSidedSlipError,
                              SeparationError, StickSeparationError, StickZoneError)
from threepart.halfplane.steady import gap_rate, tilt_rate
from threepart.tolerances import tolerance

A = rigid_punch(210e3, 0.3)
F = 0.5            # the coefficient of friction of every case (an input, not a limit)
R = 10.0
HERTZ = Punch(R, R, 0.0)
CASE_A = Punch(10.0, 5.0, 1.0)
SYMMETRIC = Punch(10.0, 10.0, 1.0)
#: the reduction to the fretting cycle: stick-zone ends (of W) and energy (relative)
ROUND_OFF = tolerance("steady", "round_off").limit
#: Hertz's stick zone (of W), both methods
HERTZ_ZONE = tolerance("steady", "hertz_zone").limit
#: Hertz's energy against eq. (S16) by quad
HERTZ_ENERGY = tolerance("steady", "hertz_energy").limit
#: closed form vs SIE: stick-zone ends (of W) and energy (relative)
ZONE = tolerance("steady", "zone").limit
ENERGY = tolerance("steady", "energy").limit
#: the SIE's shear (its pressures at n = 1024) against the closed form's, of the peak (measured 5.5e-7)
SIE_SHEAR = tolerance("sie", "q_interior_max").limit
#: the marched history (tests/steady_march.py) against the steady state: its energy (relative)
MARCH_ENERGY = tolerance("steady", "march_energy").limit
#: ... and its never-slipping panels' ends, in panel widths there
MARCH_PANELS = tolerance("steady", "march_panels").limit
#: ... and the friction work of its shaken-down cycle, of a slipping cycle's
MARCH_STILL = tolerance("steady", "march_shakedown").limit
#: the rate formulas against central differences
RATE = tolerance("steady", "rate").limit

#: a general cycle on case A: P, s, Q and sigma_bulk all change
GENERAL = [(400.0, 0.1, -80.0, -20.0), (450.0, 0.15, 80.0, 20.0)]


def width(result) -> float:
    n = result.normals[0]
    return n.a + n.c


# -- (i) P and s constant: today's fretting cycle ---------------------------------------------------
@pytest.mark.parametrize("sigma", [0.0, 20.0])
@pytest.mark.parametrize("mean_Q, mean_sigma", [(0.0, 0.0), (30.0, 7.0), (-45.0, -12.0)])
def test_constant_load_is_the_fretting_cycle(sigma, mean_Q, mean_sigma):
    """Stick zone and energy of cf.fretting_cycle (Q_max = ΔQ/2); the mean shear stays locked in (eq. S14)."""
    normal = cf.solve_normal(CASE_A, 400.0, 0.1, A=A)
    cyc = cf.fretting_cycle(normal, 80.0, F, sigma_bulk=sigma, states=3)
    states = [(400.0, 0.1, mean_Q - 80.0, mean_sigma - sigma), (400.0, 0.1, mean_Q + 80.0, mean_sigma + sigma)]
    r = cf.steady_state(CASE_A, states, F, A=A)
    W = width(r)
    assert not r.shakedown
    assert np.max(np.abs(np.array(r.stick_zone) - cyc.stick[-1])) <= ROUND_OFF * W
    assert abs(r.energy - cyc.energy) <= ROUND_OFF * cyc.energy
    # the shear at the two ends: Masing's states at -Q_max and Q_max, shifted by the mean
    x = np.linspace(-normal.a, normal.c, 401)
    q_max = np.max(np.abs(cyc.shear(x, 80.0, "loading")))
    if mean_Q == 0 and mean_sigma == 0:
        assert np.max(np.abs(r.shear(x, 0) - cyc.shear(x, -80.0, "unloading"))) <= ROUND_OFF * q_max
        assert np.max(np.abs(r.shear(x, 1) - cyc.shear(x, 80.0, "reloading"))) <= ROUND_OFF * q_max
    xs = np.linspace(-1.5 * normal.a, 1.5 * normal.c, 301)
    amp = cyc.slip_amplitude(xs)
    assert np.max(np.abs(r.slip_amplitude(xs) - amp)) <= ROUND_OFF * np.max(amp)


@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_shear_balances_each_state_and_slides_in_the_slip_zones(method):
    """∫ q = Q at both ends, q = ∓ f p in the slip zones (eq. S3), |q| <= f p in the stick zone here."""
    r = threepart.steady_state(CASE_A, GENERAL, F, A=A, method=method)
    left, right = r.stick_zone
    for k in (0, 1):
        n = r.normals[k]
        Q = GENERAL[k][2]
        total = panel_integral(lambda t: r.shear(t, k), [-n.a, -1.0, left, right, 1.0, n.c])
        assert abs(total - Q) <= ENERGY * abs(Q)
        x = np.concatenate([np.linspace(-n.a, left, 50)[1:-1], np.linspace(right, n.c, 50)[1:-1]])
        slide = (1.0 if k == 1 else -1.0) * F * n.pressure(x)
        assert np.max(np.abs(r.shear(x, k) - slide)) <= ZONE * np.max(n.pressure(x))
        inside = np.linspace(left, right, 101)
        assert np.all(np.abs(r.shear(inside, k)) <= F * n.pressure(inside) * (1 + ZONE))


def panel_integral(fun, cuts, nodes: int = 400) -> float:
    """``∫ fun`` over the panels between ``cuts``, Gauss–Legendre in ``θ`` with ``x = lo + (hi - lo)(1 - cos θ)/2``.

    The map makes the square-root ends and kinks at the cuts smooth (vectorised; the
    SIE's shear is too slow for adaptive quadrature point by point).
    """
    th, w = np.polynomial.legendre.leggauss(nodes)
    th, w = 0.5 * math.pi * (th + 1), 0.5 * math.pi * w
    cuts = sorted(set(cuts))
    total = 0.0
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        x = lo + (hi - lo) * 0.5 * (1 - np.cos(th))
        total += float(np.sum(w * 0.5 * (hi - lo) * np.sin(th) * fun(x)))
    return total


# -- (ii) shakedown ---------------------------------------------------------------------------------
@pytest.mark.parametrize("punch, s", [(HERTZ, 0.0), (SYMMETRIC, 0.0)])
def test_shakedown_below_f_delta_P(punch, s):
    """|ΔQ| <= f ΔP with the tilt held at 0 (a symmetric punch, s = 0): nothing slips (Mindlin–Deresiewicz).

    Just above the bound, Hertz slips a little, with the energy of eq. (S16).
    """
    P1, P2 = 300.0, 500.0
    dQ = 0.999 * F * (P2 - P1)
    for method in ("closedform", "sie"):
        r = threepart.steady_state(punch, [(P1, s, -0.5 * dQ, 0.0), (P2, s, 0.5 * dQ, 0.0)], F, A=A,
                                   method=method)
        assert r.shakedown and r.energy == 0
        assert np.all(r.slip_amplitude(np.linspace(-2.0, 2.0, 51)) == 0)
        with pytest.raises(ValueError, match="shaken down: its shear is locked in by the load history"):
            r.shear([0.0], 0)
    if punch is HERTZ:        # Hertz's shakedown bound is exact: a hair above it the cycle slips
        dQ = 1.001 * F * (P2 - P1)
        r = cf.steady_state(punch, [(P1, s, -0.5 * dQ, 0.0), (P2, s, 0.5 * dQ, 0.0)], F, A=A)
        assert not r.shakedown
        assert abs(r.energy - hertz_energy(P1, P2, dQ)) <= HERTZ_ENERGY * r.energy


@pytest.mark.parametrize("punch, states", [
    (SYMMETRIC, [(300.0, 0.0, -45.0, 0.0), (500.0, 0.0, 45.0, 0.0)]),      # |ΔQ| = 0.9 f ΔP
    (CASE_A, [(400.0, -0.2, -20.0, 0.0), (400.0, 0.2, 20.0, 0.0)]),         # the contact moves
])
def test_the_marched_history_shakes_down_too(punch, states):
    """Where (S12) finds shakedown, the history marched by Coulomb's law (tests/steady_march.py)
    does no friction work in its last cycle (of the work of the same ΔQ at the first state held)."""
    from .steady_march import history
    assert threepart.steady_state(punch, states, F, A=A, method="sie", n=256).shakedown
    assert cf.steady_state(punch, states, F, A=A).shakedown
    L = 1.03 * max(max(n.a, n.c) for n in (cf.solve_normal(punch, P, s, A=A) for P, s, _, _ in states))
    _, _, work, _ = history(punch, states, F, A, np.linspace(-L, L, 201), steps=20, cycles=2)
    held = [states[0], (*states[0][:2], states[1][2], states[0][3])]
    assert work <= MARCH_STILL * cf.steady_state(punch, held, F, A=A).energy


def test_a_changing_tilt_shifts_the_shakedown_stick_zone_to_one_edge():
    """Case A (R1 != R2): the tilt changes with P, so at |ΔQ| just below f ΔP the stick zone of
    load P* ~ P_0 sits at the mean tilt, off the smaller contact on one side (eq. S12).

    The marched history (tests/steady_march.py) slips at the other end only: one end slips,
    the other has shaken down, as the refusal says.
    """
    from .steady_march import history
    dQ = 0.999 * F * 200.0
    states = [(300.0, 0.1, -0.5 * dQ, 0.0), (500.0, 0.1, 0.5 * dQ, 0.0)]
    for method in ("closedform", "sie"):
        with pytest.raises(OneSidedSlipError, match=r"would reach the right edge of the smaller contact"):
            threepart.steady_state(CASE_A, states, F, A=A, method=method)
    L = 1.03 * max(max(n.a, n.c) for n in (cf.solve_normal(CASE_A, P, s, A=A) for P, s, _, _ in states))
    x, _, work, slipped = history(CASE_A, states, F, A, np.linspace(-L, L, 301), steps=20, cycles=2)
    assert work > 0 and slipped.any() and np.all(x[slipped] < 0)


def test_a_bulk_stress_alone_slips_at_one_end():
    """P, s, Q held, sigma_bulk cycled: the stick zone is the contact shifted (eq. S5): one end slips."""
    with pytest.raises(OneSidedSlipError, match=r"would reach the \w+ edge of the smaller contact .* but not the other"):
        cf.steady_state(CASE_A, [(400.0, 0.1, 10.0, -5.0), (400.0, 0.1, 10.0, 5.0)], F, A=A)


# -- (iii) Hertz ------------------------------------------------------------------------------------
def hertz_zone(states) -> tuple[float, float]:
    """Stick zone from Hertz's formulas alone: ``c'^2 = 2 A R P*/π``, offset ``sign(ΔQ) A Δsigma R/(8 f)`` (S15)."""
    (P1, _, Q1, s1), (P2, _, Q2, s2) = states
    sign = 1.0 if Q2 >= Q1 else -1.0
    P_star = (F * (P1 + P2) - abs(Q2 - Q1)) / (2 * F)
    half = math.sqrt(2 * A * R * P_star / math.pi)
    x0 = sign * A * (s2 - s1) * R / (8 * F)
    return x0 - half, x0 + half


def hertz_energy(P1: float, P2: float, dQ: float) -> float:
    """Eq. (S16): ``W = Σ -(f^2 D A/π) ∫_0^1 [P ln(P/P*) - P + P*] dlam`` over the two half-cycles, by quad."""
    total = 0.0
    for Pa, Pb in ((P1, P2), (P2, P1)):
        D = (F * (Pb - Pa) - abs(dQ)) / (2 * F)

        def g(lam: float) -> float:
            # P ln(P/P*) - P + P* = P* [(1 + u) ln(1 + u) - u], u = P/P* - 1: its series for small u
            P, P_star = Pa + lam * (Pb - Pa), Pa + lam * D
            u = (P - P_star) / P_star
            if abs(u) < 0.1:
                return P_star * sum((-u) ** k / (k * (k - 1)) for k in range(2, 24))
            return P_star * ((1 + u) * math.log1p(u) - u)
        total += -F * F * D * A / math.pi * quad(g, 0.0, 1.0, epsabs=0, epsrel=1e-13)[0]
    return total


HERTZ_CASES = {
    "fretting": [(400.0, 0.0, -80.0, 0.0), (400.0, 0.0, 80.0, 0.0)],
    "rising_P": [(300.0, 0.0, -50.0, 0.0), (500.0, 0.0, 90.0, 0.0)],
    "falling_P": [(500.0, 0.0, -50.0, 0.0), (300.0, 0.0, 90.0, 0.0)],
    "mean_Q": [(300.0, 0.0, 20.0, 0.0), (500.0, 0.0, 160.0, 0.0)],
    "bulk": [(300.0, 0.0, -50.0, -10.0), (500.0, 0.0, 90.0, 15.0)],
}


@pytest.mark.parametrize("name", list(HERTZ_CASES))
@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_hertz_stick_zone_and_energy(name, method):
    states = HERTZ_CASES[name]
    r = threepart.steady_state(HERTZ, states, F, A=A, method=method)
    assert np.max(np.abs(np.array(r.stick_zone) - hertz_zone(states))) <= HERTZ_ZONE * width(r)
    if name != "bulk":
        dQ = states[1][2] - states[0][2]
        limit = HERTZ_ENERGY if method == "closedform" else ENERGY
        assert abs(r.energy - hertz_energy(states[0][0], states[1][0], dQ)) <= limit * r.energy


def brute_work(punch, states, result, nodes: int = 48, panel: int = 160) -> float:
    """Friction work by brute quadrature: the slip of eq. (S7) differenced in ``lam``, times ``f p``.

    On each half-cycle the slip since its start is ``sign f (2 gap*_lam - gap_i - gap_lam)``;
    its change over ``±1e-6`` in ``lam`` (central differences of
    :func:`closedform.fretting.stick_gap`, not the rate formula S9) times ``f p_lam``,
    integrated over the whole contact (cut at its joins and stick-zone ends) by
    Gauss–Legendre in ``θ``, and over ``lam`` by Gauss–Legendre.
    """
    cycle = _Cycle(punch, A, F, tuple(states), result.normals)
    t, w = np.polynomial.legendre.leggauss(nodes)
    lam, wl = 0.5 * (1 - np.cos(0.5 * math.pi * (t + 1))), 0.25 * math.pi * w * np.sin(0.5 * math.pi * (t + 1))
    th, wth = np.polynomial.legendre.leggauss(panel)
    th, wth = 0.5 * math.pi * (th + 1), 0.5 * math.pi * wth
    step, total = 1e-6, 0.0
    for j in (0, 1):
        mid, up, down = cycle(lam)[j], cycle(lam + step)[j], cycle(lam - step)[j]
        for k in range(nodes):
            a, c = mid["a"][k], mid["c"][k]
            cuts = sorted({-a, c, *(v for v in (-punch.b, punch.b, mid["left"][k], mid["right"][k])
                                     if -a < v < c)})
            for lo, hi in zip(cuts[:-1], cuts[1:]):
                x = lo + (hi - lo) * 0.5 * (1 - np.cos(th))
                jac = 0.5 * (hi - lo) * np.sin(th)

                def slip(z):
                    return (2 * stick_gap(punch, -z["left"][k], z["right"][k], x)
                            - stick_gap(punch, z["a"][k], z["c"][k], x))
                rate = (slip(up) - slip(down)) / (2 * step)
                p = formulas.pressure(punch, a, c, A, x)
                total += wl[k] * F * F * float(np.sum(wth * jac * p * np.abs(rate)))
    return total


@pytest.mark.parametrize("punch, states", [(CASE_A, GENERAL), (HERTZ, HERTZ_CASES["bulk"])])
def test_energy_is_the_friction_work_by_brute_quadrature(punch, states):
    r = cf.steady_state(punch, states, F, A=A)
    assert abs(r.energy - brute_work(punch, states, r)) <= ENERGY * r.energy


def test_closed_form_and_sie_agree_on_a_general_cycle():
    a = cf.steady_state(CASE_A, GENERAL, F, A=A)
    b = sie.steady_state(CASE_A, GENERAL, F, A=A)
    assert np.max(np.abs(np.array(a.stick_zone) - b.stick_zone)) <= ZONE * width(a)
    assert abs(a.energy - b.energy) <= ENERGY * a.energy
    x = np.linspace(-1.5, 1.5, 301)
    assert np.max(np.abs(a.slip_amplitude(x) - b.slip_amplitude(x))) <= ZONE * np.max(a.slip_amplitude(x))
    for k in (0, 1):       # over the contact less 5 % of W at each end, as the SIE's q_interior_max
        n = a.normals[k]
        inner = np.linspace(-n.a + 0.05 * (n.a + n.c), n.c - 0.05 * (n.a + n.c), 2001)
        q = a.shear(inner, k)
        assert np.max(np.abs(q - b.shear(inner, k))) <= SIE_SHEAR * np.max(np.abs(q))


def march_grid(r, band: int = 150, middle: int = 100) -> np.ndarray:
    """Panel edges for :func:`tests.steady_march.history`: fine over the slip zones, coarse in between.

    The closed form's stick zone and contacts only place the panels; each band runs
    from the stick zone into it by the slip zone's width and out past the larger contact.
    """
    lo, hi = min(-n.a for n in r.normals), max(n.c for n in r.normals)
    left, right = r.stick_zone
    m1, m2 = 2 * left - lo, 2 * right - hi
    out = 0.02 * (hi - lo)
    return np.concatenate([np.linspace(lo - out, m1, band + 1), np.linspace(m1, m2, middle + 1)[1:],
                           np.linspace(m2, hi + out, band + 1)[1:]])


@pytest.mark.parametrize("punch, states", [
    (CASE_A, GENERAL), (HERTZ, HERTZ_CASES["bulk"]),
    (CASE_A, [(400.0, -0.05, -60.0, 0.0), (400.0, 0.05, 60.0, 0.0)]),     # the contact moves: s changes alone
])
def test_a_marched_history_settles_on_the_steady_state(punch, states):
    """First loading, then three cycles marched by Coulomb's law on a grid (tests/steady_march.py).

    Its last cycle's friction work and the panels that never slip in it are the
    steady state's energy and permanent stick zone, to the grid's resolution.
    """
    from .steady_march import history
    r = cf.steady_state(punch, states, F, A=A)
    x, h, work, slipped = history(punch, states, F, A, march_grid(r))
    assert abs(work - r.energy) <= MARCH_ENERGY * r.energy
    lo, hi = max(-n.a for n in r.normals), min(n.c for n in r.normals)
    held = np.flatnonzero(~slipped & (x > lo) & (x < hi))
    first, last = held[0], held[-1]
    assert abs(x[first] - 0.5 * h[first] - r.stick_zone[0]) <= MARCH_PANELS * h[first]
    assert abs(x[last] + 0.5 * h[last] - r.stick_zone[1]) <= MARCH_PANELS * h[last]


# -- (iv) signs ---------------------------------------------------------------------------------------
def flip(states, which):
    """The states with the sign of Q, of sigma_bulk, or ΔP (the two loads swapped) flipped."""
    (P1, s1, Q1, g1), (P2, s2, Q2, g2) = states
    if which == "Q":
        return [(P1, s1, -Q1, g1), (P2, s2, -Q2, g2)]
    if which == "sigma":
        return [(P1, s1, Q1, -g1), (P2, s2, Q2, -g2)]
    return [(P2, s1, Q1, g1), (P1, s2, Q2, g2)]


@pytest.mark.parametrize("which", ["Q", "sigma", "dP"])
def test_a_flipped_sign_moves_the_stick_zone_as_predicted(which):
    """Q or sigma_bulk flipped: the offset (S15) flips; ΔP flipped: P* and the offset are unchanged.

    The unflipped reference fails the flipped Q or sigma_bulk; the energy is that of
    the brute quadrature either way, and by the mirror x -> -x unchanged when Q flips.
    """
    states = HERTZ_CASES["bulk"]
    base = cf.steady_state(HERTZ, states, F, A=A)
    flipped = flip(states, which)
    r = cf.steady_state(HERTZ, flipped, F, A=A)
    W = width(r)
    assert np.max(np.abs(np.array(r.stick_zone) - hertz_zone(flipped))) <= HERTZ_ZONE * W
    miss = np.max(np.abs(np.array(r.stick_zone) - hertz_zone(states)))
    if which == "dP":
        assert miss <= HERTZ_ZONE * W
    else:       # the unflipped reference misses by twice the offset
        offset = abs(sum(hertz_zone(states))) / 2
        assert offset > HERTZ_ZONE * W and abs(miss - 2 * offset) <= HERTZ_ZONE * W
        assert abs(r.e + base.e) <= HERTZ_ZONE * W
    if which == "Q":
        assert abs(r.energy - base.energy) <= ROUND_OFF * base.energy
    assert abs(r.energy - brute_work(HERTZ, flipped, r)) <= ENERGY * r.energy


def test_swapping_the_two_states_is_the_same_cycle():
    a = cf.steady_state(CASE_A, GENERAL, F, A=A)
    b = cf.steady_state(CASE_A, GENERAL[::-1], F, A=A)
    assert np.max(np.abs(np.array(a.stick_zone) - b.stick_zone)) <= ROUND_OFF * width(a)
    assert abs(a.energy - b.energy) <= ROUND_OFF * a.energy


# -- the rates and the slip direction -------------------------------------------------------------
def test_tilt_and_gap_rates_are_the_derivatives():
    """Eq. (S8) against central differences of solve_normal; eq. (S9) of stick_gap."""
    P, s, dP, ds, eps = 420.0, 0.12, 50.0, 0.05, 1e-4
    n = cf.solve_normal(CASE_A, P, s, A=A)
    up, down = (cf.solve_normal(CASE_A, P + k * eps * dP, s + k * eps * ds, A=A) for k in (1, -1))
    fd = (up.alpha - down.alpha) / (2 * eps)
    assert abs(tilt_rate(A, n.a, n.c, dP, dP * s + P * ds) - fd) <= RATE * abs(fd)
    # a stick zone of the corrective contact whose load and tilt change by (dP*, dalpha*)
    zone = cf.solve_normal(CASE_A, 200.0, 0.0, A=A, tilt="suppressed")
    alpha0, dPs, dal = 0.0, -30.0, 2e-4
    x = np.concatenate([np.linspace(-1.6, -zone.a, 40)[:-1], np.linspace(zone.c, 1.6, 40)[1:]])

    def gap(k: int) -> np.ndarray:
        a_s, c_s, _ = _zone(200.0 + k * eps * dPs, alpha0 + k * eps * dal)
        return stick_gap(CASE_A, a_s, c_s, x)
    fd = (gap(1) - gap(-1)) / (2 * eps)
    rate = gap_rate(x, -zone.a, zone.c, A, dPs, dal)
    assert np.max(np.abs(rate - fd)) <= RATE * np.max(np.abs(fd))


def _zone(P: float, alpha: float):
    """Ends of the bounded contact of load ``P`` at the tilt ``alpha`` (the closed form's root)."""
    from threepart.closedform.newton import ray_state, solve_phi
    dAP = A * P - 0.5 * math.pi * CASE_A.kappa0 * CASE_A.b**2
    r, phi, lo, hi = solve_phi(CASE_A, np.array([dAP]), "tilt", np.array([alpha]), np, sign=-1.0)
    st = ray_state(CASE_A, r, phi, np)
    return float(st.a[0]), float(st.c[0]), bool(lo[0] or hi[0])


@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_the_bulk_stress_bound_at_the_start_of_a_half_cycle(method):
    """Hertz, P held: eq. (S10) at lam -> 0 reads |Δsigma| <= 4|ΔQ|/(π a); below it the cycle holds, above it refuses.

    (For Hertz it binds before the final stick zone reaches the contact's edge,
    Nowell & Hills' bound, docs/BULK_STRESS.md §3.)
    """
    a = math.sqrt(2 * A * R * 400.0 / math.pi)
    bound = 4 * 160.0 / (math.pi * a)
    ok = [(400.0, 0.0, -80.0, -0.499 * bound), (400.0, 0.0, 80.0, 0.499 * bound)]
    assert threepart.steady_state(HERTZ, ok, F, A=A, method=method).energy > 0
    bad = [(400.0, 0.0, -80.0, -0.501 * bound), (400.0, 0.0, 80.0, 0.501 * bound)]
    with pytest.raises(CycleSlipReversalError, match="the right end of the contact slips backwards"):
        threepart.steady_state(HERTZ, bad, F, A=A, method=method)


# -- where it stops -------------------------------------------------------------------------------------
def test_past_the_central_segment_the_sie_answers_and_matches_its_fretting_cycle():
    states = [(400.0, 0.1, -190.0, 0.0), (400.0, 0.1, 190.0, 0.0)]
    with pytest.raises(StickZoneError, match="would end inside the central segment"):
        cf.steady_state(CASE_A, states, F, A=A)
    r = threepart.steady_state(CASE_A, states, F, A=A)
    assert r.method == "sie" and "central segment" in r.info["auto"]
    cyc = sie.fretting_cycle(sie.solve_normal(CASE_A, 400.0, 0.1, A=A), 190.0, F, states=2)
    assert np.max(np.abs(np.array(r.stick_zone) - cyc.stick[-1])) <= ZONE * width(r)
    assert abs(r.energy - cyc.energy) <= ENERGY * cyc.energy


@pytest.mark.parametrize("states, f, error, match", [
    ([(400.0, 0.1, 0.0, 0.0), (400.0, 0.1, 200.0, 0.0)], F, FullSlidingError,
     r"\|`states\[1\].Q`\| = 200 >= f P = 200 .*no steady state with a stick zone"),
    ([(400.0, 0.1, 0.0, 0.0)], F, ValueError, r"`states` has 1 entries: it must hold the two ends"),
    ([(400.0, 0.1, 0.0), (400.0, 0.1, 1.0, 0.0)], F, ValueError, r"`states\[0\]` = .* has 3 values: it must be a \(P, s, Q"),
    ([(-400.0, 0.1, 0.0, 0.0), (400.0, 0.1, 1.0, 0.0)], F, ValueError, r"`states\[0\].P` = -400.0 must be > 0"),
    ([(400.0, 0.1, math.nan, 0.0), (400.0, 0.1, 1.0, 0.0)], F, ValueError, r"`states\[0\].Q` = nan must be"),
    ([(400.0, 0.1, 0.0, 0.0), (400.0, 0.1, 1.0, 0.0)], 0.0, ValueError, r"`f` = 0.0 must be > 0"),
])
def test_bad_input_is_refused_with_the_named_error(states, f, error, match):
    for method in ("closedform", "sie"):
        with pytest.raises(error, match=match):
            threepart.steady_state(CASE_A, states, f, A=A, method=method)


def test_a_state_past_lift_off_is_the_closed_forms_refusal():
    with pytest.raises(LiftOffError, match=r"`s` = 0.9 exceeds the lift-off lever arm"):
        cf.steady_state(CASE_A, [(400.0, 0.9, 0.0, 0.0), (400.0, 0.1, 10.0, 0.0)], F, A=A)


@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_a_concave_centre_is_refused_where_it_separates(method):
    """R = -50: at P = 400 the normal contact separates; at P = 8000 it holds but the permanent
    stick zone's p* goes tensile on the dip (|Δq| <= f (p_0 + p_1) would break)."""
    concave = Punch(10.0, 5.0, 1.0, -50.0)
    with pytest.raises(SeparationError, match="separate"):
        threepart.steady_state(concave, [(400.0, 0.1, -80.0, 0.0), (450.0, 0.15, 80.0, 0.0)], F, A=A,
                               method=method)
    with pytest.raises(StickSeparationError, match=r"breaks Coulomb's law: p\* < 0 at x = "):
        threepart.steady_state(concave, [(8000.0, 0.1, -1600.0, -20.0), (9000.0, 0.15, 1600.0, 20.0)], F,
                               A=A, method=method)


def test_states_must_be_a_sequence():
    with pytest.raises(TypeError, match="`states` must be a sequence of two"):
        cf.steady_state(CASE_A, 3.0, F, A=A)


def test_the_registry_dispatches_steady_state():
    assert registry.get("closedform").steady is cf.steady_state
    assert registry.get("sie").steady is sie.steady_state
    assert registry.get("fem").steady is not None         # fem.steady_state, through E = 4(1 - nu^2)/A


def test_stress_at_an_end_is_the_fretting_state():
    """At P, s constant the stress of state 1 is that of the fretting cycle at Q_max on reloading."""
    normal = cf.solve_normal(CASE_A, 400.0, 0.1, A=A)
    cyc = cf.fretting_cycle(normal, 80.0, F, sigma_bulk=20.0, states=3)
    r = cf.steady_state(CASE_A, [(400.0, 0.1, -80.0, -20.0), (400.0, 0.1, 80.0, 20.0)], F, A=A)
    x, z = np.linspace(-1.5, 1.5, 7)[:, None], np.array([[0.05, 0.5]])
    got, want = r.stress(x, z, 1), cyc.stress(x, z, 80.0, "reloading")
    scale = np.max(normal.pressure(np.linspace(-1, 1, 101)))
    for name in ("sxx", "szz", "sxz"):
        assert np.max(np.abs(getattr(got, name) - getattr(want, name))) <= ZONE * scale
    with pytest.raises(ValueError, match=r"`state` = 2 must be 0 or 1"):
        r.stress(x, z, 2)

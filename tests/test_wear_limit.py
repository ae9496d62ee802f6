"""The closed-form worn limit of partial-slip fretting (closedform/wear.py, docs/WEAR.md).

Every figure is checked against an independent reference:

* the load and moment by Gauss–Chebyshev quadrature of the first kind of the
  singular pressure (eqs. W1, W2);
* Hertz against the explicit formula of eq. (W11) and both punches against a
  direct Gauss–Chebyshev collocation of eq. (integral_equation) on the stick
  zone with unbounded ends, the tilt an unknown (written here, :func:`collocate`);
* the worn depth against the half-plane displacement integral evaluated by
  adaptive quadrature (QUADPACK's algebraic-logarithmic weights): the worn
  profile plus the displacement is a rigid-body motion over the whole scar;
* the signs p >= 0 and depth >= 0, and the limits where the stick zone does not
  move (symmetric punch, Hertz with a moment).
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from scipy.integrate import quad

from threepart import closedform as cf
from threepart.closedform.wear import STICK_RULES, wear_limit
from threepart.errors import FullSlidingError, StickZoneError
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3   # compliance of two similar steel bodies, eq. (4)
F_MU = 0.5   # coefficient of friction of the case
P = 400.0   # the load (N/mm): the scale of the load and moment checks
THREE = Punch(R1=10, R2=5, b=1)
HERTZ = Punch(R1=10, R2=10, b=0)
#: Gauss–Chebyshev nodes of the load and moment quadrature (the joins' (x ∓ b) ln|x ∓ b| limit its order)
QUAD_NODES = 2**16
#: collocation points of the reference solve: Hertz is exact for any n; the three-part punch converges
COLLOCATION_N = (64, 1600)


def _limit(punch: Punch, s: float, ratio: float = 0.4, **kw) -> cf.wear.WearLimit:
    normal = cf.solve_normal(punch, P, s, A=A)
    return wear_limit(normal, ratio * F_MU * P, F_MU, **kw)


#: the cases checked against the references: the issue's three-part punch with a moment
#: (Punch(10, 5, 1), P = 400, s = 0.1, Q_max = 0.4 f P) under each rule, and Hertz with a moment
CASES = tuple(f"three-{rule}" for rule in STICK_RULES) + ("hertz",)


@functools.lru_cache(maxsize=None)
def _case(name: str):
    if name == "hertz":
        return _limit(HERTZ, 0.1)
    return _limit(THREE, 0.1, stick=name.split("-")[1])


def _chebyshev_nodes(n: int, x1: float, x2: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ``x_i`` of the first-kind rule on ``[x1, x2]`` and ``w(x_i) = sqrt((x-x1)(x2-x))``."""
    tau = np.cos(np.pi * (2 * np.arange(1, n + 1) - 1) / (2 * n))
    h, m = 0.5 * (x2 - x1), 0.5 * (x1 + x2)
    return m + h * tau, h * np.sqrt(1 - tau * tau)


def collocate(punch: Punch, x1: float, x2: float, P: float, s: float, n: int
              ) -> tuple[np.ndarray, np.ndarray, float]:
    """Solve eq. (integral_equation) on ``[x1, x2]`` with both ends unbounded, load ``P`` at lever arm ``s``.

    ``g'(x) + alpha = (A/π) ∫ p(t)/(x - t) dt`` with ``p = F/w``: Gauss–Chebyshev
    of the first kind (Erdogan–Gupta), ``n`` nodes ``τ_i`` and ``n - 1``
    collocation points ``ξ_k = cos(πk/n)``, closed by ``∫p = P`` and
    ``∫x p = P s``; the unknowns are ``F(τ_i)`` and the tilt. Returns the nodes,
    ``p`` there and the tilt.
    """
    i, k = np.arange(1, n + 1), np.arange(1, n)
    tau, xi = np.cos(np.pi * (2 * i - 1) / (2 * n)), np.cos(np.pi * k / n)
    h, m = 0.5 * (x2 - x1), 0.5 * (x1 + x2)
    M = np.zeros((n + 1, n + 1))
    rhs = np.zeros(n + 1)
    M[: n - 1, :n] = A / (h * n) / (xi[:, None] - tau[None, :])
    M[: n - 1, n] = -1.0
    rhs[: n - 1] = punch.slope(m + h * xi)
    M[n - 1, :n], rhs[n - 1] = np.pi / n, P
    M[n, :n], rhs[n] = np.pi / n * (m + h * tau), P * s
    sol = np.linalg.solve(M, rhs)
    x = m + h * tau
    return x, sol[:n] / (h * np.sqrt(1 - tau * tau)), float(sol[n])


def displacement(limit, x: float) -> float:
    """``U(x) = -(A/π) ∫ p_L(t) ln|x - t| dt`` by QUADPACK's weighted rules (the singular ends exact)."""
    x1, x2 = limit.stick_zone

    eps = 1e-13 * (x2 - x1)

    def F(t: float) -> float:                      # p w, bounded and continuous: its end values a hair inside
        t = min(max(t, x1 + eps), x2 - eps)
        return float(limit.pressure(t) * math.sqrt((t - x1) * (x2 - t)))

    opts = dict(epsabs=0.0, epsrel=1e-10, limit=400)
    if x <= x1 or x >= x2:
        val = quad(lambda t: F(t) * math.log(abs(x - t)), x1, x2, weight="alg",
                   wvar=(-0.5, -0.5), **opts)[0]
    else:
        left = quad(lambda t: F(t) / math.sqrt(x2 - t), x1, x, weight="alg-logb", wvar=(-0.5, 0.0),
                    **opts)[0]
        right = quad(lambda t: F(t) / math.sqrt(t - x1), x, x2, weight="alg-loga", wvar=(0.0, -0.5),
                     **opts)[0]
        val = left + right
    return -limit.normal.A / math.pi * val


# --- (a) load and moment -------------------------------------------------------------------------
@pytest.mark.parametrize("case", CASES)
def test_the_stick_zone_carries_the_load_and_the_moment(case):
    L = _case(case)
    x, w = _chebyshev_nodes(QUAD_NODES, *L.stick_zone)
    F = L.pressure(x) * w
    load, moment = np.pi / QUAD_NODES * F.sum(), np.pi / QUAD_NODES * (x * F).sum()
    tol = tolerance("wear-limit", "quadrature").limit
    assert abs(load - P) <= tol * P, f"∫p = {load!r}, P = {P}"
    assert abs(moment - P * L.s) <= tol * P * (L.stick_zone[1] - L.stick_zone[0]), \
        f"∫x p = {moment!r}, P s = {P * L.s!r}"
    assert L.s == L.normal.s and L.P == P


# --- (b) Hertz: explicit formula and collocation ----------------------------------------------------
def test_hertz_against_its_explicit_formula():
    hertz = _case("hertz")
    """Eq. (W11): p = Q_max/(π f ρ) + ρ/(A R), ρ = sqrt(d^2 - (x - s)^2), d^2 = a^2 (1 - Q_max/(f P))."""
    n, Q = hertz.normal, hertz.Q_max
    d = 0.5 * (n.a + n.c) * math.sqrt(1 - Q / (F_MU * P))
    s = 0.5 * (n.c - n.a)
    tol = tolerance("wear-limit", "round_off").limit
    assert hertz.stick_zone == pytest.approx((s - d, s + d), abs=tol * d)
    x = np.linspace(s - 0.999 * d, s + 0.999 * d, 801)
    rho = np.sqrt(d * d - (x - s) ** 2)
    exact = Q / (math.pi * F_MU * rho) + rho / (A * HERTZ.R1)
    assert np.max(np.abs(hertz.pressure(x) - exact) / exact) <= tol
    assert abs(hertz.alpha - n.alpha) <= tol * abs(n.alpha)      # the tilt does not change
    assert hertz.K == pytest.approx((Q / (math.pi * F_MU),) * 2, rel=tol)


@pytest.mark.parametrize("case", CASES)
def test_against_a_collocation_of_the_integral_equation(case):
    """Gauss–Chebyshev collocation with unbounded ends and the tilt free: exact for Hertz."""
    L, n = _case(case), COLLOCATION_N[0] if case == "hertz" else COLLOCATION_N[1]
    x, p, alpha = collocate(L.normal.punch, *L.stick_zone, P, L.s, n)
    x1, x2 = L.stick_zone
    away = np.abs(x - 0.5 * (x1 + x2)) <= 0.45 * (x2 - x1)      # 5 % of the width from each end
    p_scale = float(np.max(L.pressure(x[away])))
    tol = tolerance("wear-limit", "hertz" if case == "hertz" else "collocation").limit
    err = np.max(np.abs(L.pressure(x[away]) - p[away])) / p_scale
    assert err <= tol, f"max |Δp| = {err:.3g} of the largest pressure"
    slope_scale = abs(L.normal.punch.slope(x2) - L.normal.punch.slope(x1))
    assert abs(alpha - L.alpha) <= tol * slope_scale, f"tilt {L.alpha!r} vs collocation {alpha!r}"


# --- (c) the worn depth closes the gap -------------------------------------------------------------
@pytest.mark.parametrize("case", CASES)
def test_the_worn_depth_closes_the_gap_over_the_scar(case):
    """g + depth + alpha x + U = D over the whole scar, stick zone included; open gap beyond."""
    L = _case(case)
    (x1, x2), (xw1, xw2) = L.stick_zone, L.worn_zone
    n = L.normal
    assert xw1 < -n.a and xw2 > n.c                         # the scar covers the original contact
    pts = np.concatenate([np.linspace(xw1, x1, 7)[1:-1], np.linspace(x1, x2, 9)[1:-1],
                          np.linspace(x2, xw2, 7)[1:-1], [-n.a, n.c]])
    R = np.array([n.punch.profile(t) + L.depth(t) + L.alpha * t + displacement(L, t) for t in pts])
    depth_max = float(np.max(L.depth(np.linspace(xw1, xw2, 2001))))
    spread = float(np.ptp(R))
    assert spread <= tolerance("wear-limit", "gap").limit * depth_max, \
        f"the worn gap varies by {spread:.3g} = {spread / depth_max:.3g} of the depth over the scar"
    beyond = np.array([xw1 - 0.05 * (x2 - x1), xw2 + 0.05 * (x2 - x1)])
    gap = [n.punch.profile(t) + L.alpha * t + displacement(L, t) - R.mean() for t in beyond]
    assert min(gap) > 0, f"the limit surface penetrates the unworn profile beyond the scar: {gap}"


# --- (d) signs -------------------------------------------------------------------------------------
@pytest.mark.parametrize("punch, s, ratio", [(THREE, 0.1, 0.4), (THREE, -0.15, 0.3), (THREE, 0.0, 0.2),
                                             (HERTZ, 0.1, 0.4), (Punch(R1=8, R2=4, b=0), 0.05, 0.6)])
@pytest.mark.parametrize("stick", STICK_RULES)
def test_pressure_and_depth_are_never_negative(punch, s, ratio, stick):
    L = _limit(punch, s, ratio, stick=stick)
    x = np.linspace(L.worn_zone[0] - 0.1, L.worn_zone[1] + 0.1, 20001)
    assert np.all(L.pressure(x) >= 0) and np.all(L.depth(x) >= 0)
    assert np.all(L.depth(x[(x > L.stick_zone[0]) & (x < L.stick_zone[1])]) == 0)
    assert np.all(np.isfinite(L.pressure(x[x != L.stick_zone[0]])))


# --- the tilt: where the stick zone does not move ----------------------------------------------------
@pytest.mark.parametrize("punch, s", [(Punch(R1=10, R2=10, b=1), 0.0), (HERTZ, 0.1), (HERTZ, -0.05)])
def test_no_moment_correction_where_the_stick_zone_cannot_move(punch, s):
    """Symmetric punch centred, or Hertz with any moment: C1 = 0, tilt unchanged, both rules agree."""
    held, consistent = _limit(punch, s), _limit(punch, s, stick="consistent")
    tol = tolerance("wear-limit", "round_off").limit
    n = held.normal
    assert abs(held.C1) * (n.a + n.c) <= tol * held.C0
    assert abs(held.alpha - n.alpha) <= tol * max(abs(n.alpha), n.width / HERTZ.R1)
    assert consistent.stick_zone == pytest.approx(held.stick_zone, abs=tol * n.width)


def _coulomb_margin(L) -> np.ndarray:
    """``f p_L w - Q_max/π`` on the stick zone: the limit's shear at ``Q_max`` is the bonded flat
    punch's ``Q_max/(π w)`` (nothing slips), so Coulomb's ``|q| <= f p`` holds where this is >= 0."""
    x1, x2 = L.stick_zone
    u = np.linspace(0.0, 1.0, 20001)[1:-1] ** 2                    # graded towards both ends
    x = np.concatenate([x1 + (x2 - x1) * 0.5 * u, x2 - (x2 - x1) * 0.5 * u])
    return L.f * L.pressure(x) * np.sqrt((x - x1) * (x2 - x)) - L.Q_max / math.pi


@pytest.mark.parametrize("punch, s", [(THREE, 0.1), (THREE, -0.1), (Punch(R1=8, R2=4, b=0), 0.05)])
def test_pinned_and_consistent_limits_obey_coulomb_and_held_does_not(punch, s):
    """Eqs. W10, W12: the two fixed points keep |q| <= f p over the stick zone; "held" breaks it at one end."""
    held, pinned, consistent = (_limit(punch, s, stick=rule) for rule in ("held", "pinned", "consistent"))
    scale = held.Q_max / math.pi
    tol = tolerance("wear-limit", "round_off").limit
    for L in (pinned, consistent):
        assert np.min(_coulomb_margin(L)) >= -tol * scale, f"{L.stick}: |q| > f p in the stick zone"
    assert np.min(_coulomb_margin(held)) < 0
    # the pinned end is the cycle's; the receding end's K equals Q_max/(π f), the pinned one's exceeds it
    C = held.Q_max / (math.pi * F_MU)
    recede = int(np.argmin(held.K))
    assert pinned.stick_zone[1 - recede] == held.stick_zone[1 - recede]
    assert abs(pinned.K[recede] - C) <= tol * C and pinned.K[1 - recede] > C
    assert consistent.K == pytest.approx((C, C), rel=tol)
    # the receding end recedes, and pinned lies between held and consistent at the other end
    assert (pinned.stick_zone[recede] - held.stick_zone[recede]) * (1 if recede == 0 else -1) > 0
    x_c = consistent.stick_zone[1 - recede]
    assert (x_c - held.stick_zone[1 - recede]) * (1 if recede == 0 else -1) > 0


def test_a_suppressed_tilt_stays_and_the_support_carries_the_moment():
    """tilt="suppressed": C1 = 0, alpha = 0, and s is the limit's own centroid (quadrature, W2)."""
    normal = cf.solve_normal(THREE, P, 0.0, A=A, tilt="suppressed")
    L = wear_limit(normal, 0.4 * F_MU * P, F_MU)
    assert L.C1 == 0 and L.alpha == 0
    x, w = _chebyshev_nodes(QUAD_NODES, *L.stick_zone)
    F = L.pressure(x) * w
    tol = tolerance("wear-limit", "quadrature").limit
    assert abs(np.pi / QUAD_NODES * F.sum() - P) <= tol * P
    assert abs(np.pi / QUAD_NODES * (x * F).sum() - P * L.s) <= tol * P * normal.width
    _, _, alpha = collocate(THREE, *L.stick_zone, P, L.s, COLLOCATION_N[1])
    assert abs(alpha) <= tolerance("wear-limit", "collocation").limit * abs(
        THREE.slope(L.stick_zone[1]) - THREE.slope(L.stick_zone[0]))


# --- refusals ----------------------------------------------------------------------------------------
def test_refusals():
    normal = cf.solve_normal(THREE, P, 0.1, A=A)
    with pytest.raises(FullSlidingError, match=r"`Q_max`.*>= f P"):
        wear_limit(normal, F_MU * P, F_MU)
    with pytest.raises(StickZoneError, match=r"central segment.*`Q_max`/\(f P\) <"):
        wear_limit(normal, 0.9 * F_MU * P, F_MU)
    with pytest.raises(ValueError, match="`stick`"):
        wear_limit(normal, 0.4 * F_MU * P, F_MU, stick="moving")
    with pytest.raises(ValueError, match="`f`"):
        wear_limit(normal, 0.4 * F_MU * P, -1.0)
    with pytest.raises(TypeError):
        wear_limit("normal", 0.4 * F_MU * P, F_MU)


# --- property-based: any admissible three-part case under any rule -------------------------------------
hyp = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, assume, given, settings, strategies as st  # noqa: E402

from threepart.errors import LiftOffError  # noqa: E402


@settings(max_examples=25, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(R2=st.floats(3.0, 20.0), b=st.one_of(st.just(0.0), st.floats(0.1, 1.0)), s=st.floats(-0.2, 0.2),
       ratio=st.floats(0.05, 0.6), stick=st.sampled_from(STICK_RULES))
def test_load_moment_and_signs_over_admissible_cases(R2, b, s, ratio, stick):
    """W1, W2 by quadrature, p >= 0 and depth >= 0, for random punches, moments and amplitudes."""
    punch = Punch(R1=10, R2=R2, b=b)
    try:
        L = _limit(punch, s, ratio, stick=stick)
    except (LiftOffError, StickZoneError):
        assume(False)
        raise
    x, w = _chebyshev_nodes(QUAD_NODES, *L.stick_zone)
    F = L.pressure(x) * w
    tol = tolerance("wear-limit", "quadrature").limit
    assert abs(np.pi / QUAD_NODES * F.sum() - P) <= tol * P
    assert abs(np.pi / QUAD_NODES * (x * F).sum() - P * s) <= tol * P * L.normal.width
    grid = np.linspace(L.worn_zone[0] - 0.05, L.worn_zone[1] + 0.05, 4001)
    assert np.all(L.pressure(grid) >= 0) and np.all(L.depth(grid) >= 0)

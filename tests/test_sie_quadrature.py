"""Gauss–Chebyshev rule, discrete Cauchy operator, exact projection and the kink series."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import beta as beta_fn

from threepart.problem.punch import Punch
from threepart.sie.projection import ramp_coefficients, ramp_remainder, slope_coefficients
from threepart.sie.quadrature import cauchy_matrix, gauss_chebyshev, plain_functionals
from threepart.sie.fretting import GAP_TERMS, _gap_sums
from threepart.sie.series import kinked_sums, log_kink, power_series, sine_series
from threepart.tolerances import tolerance


def tol(quantity: str) -> float:
    return tolerance("sie-quadrature", quantity).limit


def moment(j: int) -> float:
    """``∫ sqrt(1-x^2) x^j dx`` on [-1, 1]."""
    return 0.0 if j % 2 else beta_fn(j / 2 + 0.5, 1.5)


@pytest.mark.parametrize("n", [2, 3, 10, 57, 200])
def test_weights_sum_to_half_pi(n):
    rule = gauss_chebyshev(n)
    assert rule.weights.sum() == pytest.approx(np.pi / 2, rel=tol("weights"), abs=0)
    assert np.all(rule.weights > 0)
    np.testing.assert_allclose(np.sin((n + 1) * np.arccos(rule.nodes)), 0, atol=tol("nodes"))  # zeros of U_n
    np.testing.assert_allclose(np.cos((n + 1) * np.arccos(rule.collocation)), 0, atol=tol("nodes"))  # of T_{n+1}


@pytest.mark.parametrize("n", [2, 5, 12])
def test_exactness_degree_is_2n_minus_1(n):
    rule = gauss_chebyshev(n)
    for j in range(2 * n):
        assert rule.weights @ rule.nodes**j == pytest.approx(moment(j), abs=tol("exactness")), j
    err = abs(rule.weights @ rule.nodes ** (2 * n) - moment(2 * n))
    assert err > tol("beyond_degree") * moment(2 * n), "rule should not be exact beyond degree 2n - 1"


@pytest.mark.parametrize("n", [3, 8, 20])
def test_cauchy_matrix_maps_U_to_T(n):
    """Finite Hilbert transform: -(1/π) PV ∫ sqrt(1-σ²) U_{k-1}(σ)/(σ-s) dσ = T_k(s), exactly for k <= n."""
    rule = gauss_chebyshev(n)
    K = cauchy_matrix(rule)
    th, ts = np.arccos(rule.nodes), np.arccos(rule.collocation)
    for k in range(1, n + 1):
        np.testing.assert_allclose(K @ (np.sin(k * th) / np.sin(th)), np.cos(k * ts), atol=tol("cauchy"))


def test_cauchy_matrix_against_adaptive_principal_value():
    """A smooth density: spectral agreement with scipy's Cauchy-weight quadrature."""
    rule = gauss_chebyshev(24)
    K = cauchy_matrix(rule)
    got = K @ np.exp(rule.nodes)
    ref = [-quad(lambda t: math.sqrt(1 - t * t) * math.exp(t), -1, 1, weight="cauchy", wvar=s,
                 epsabs=1e-14)[0] / np.pi for s in rule.collocation]
    np.testing.assert_allclose(got, ref, atol=tol("principal_value"))


def test_plain_functionals_give_chebyshev_coefficients_of_a_polynomial():
    """For a slope of degree <= n the discrete G_0..G_2 equal the exact Chebyshev coefficients."""
    n = 9
    fun = plain_functionals(n)
    coef = np.array([0.3, -1.2, 0.7, 0.25, -0.1])
    vals = np.polynomial.chebyshev.chebval(fun.rule.collocation, coef)
    np.testing.assert_allclose(fun.rows @ vals, coef[:3], atol=tol("functionals"))


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("beta", [-0.95, -0.3, 0.0, 0.42, 0.999])
def test_ramp_coefficients_against_quadrature(beta):
    tb = math.acos(beta)
    ref = [(1 if k == 0 else 2) / np.pi * quad(lambda t: max(math.cos(t) - beta, 0) * math.cos(k * t),
                                              0, np.pi, points=[tb], epsabs=1e-15, limit=200)[0] for k in range(12)]
    np.testing.assert_allclose(ramp_coefficients(beta, np.arange(12)), ref, atol=tol("ramp"))


def test_ramp_coefficients_outside_the_interval():
    np.testing.assert_array_equal(ramp_coefficients(1.5, np.arange(4)), 0)
    np.testing.assert_allclose(ramp_coefficients(-1.5, np.arange(4)), [1.5, 1, 0, 0])
    # continuous at β = ±1
    np.testing.assert_allclose(ramp_coefficients(-1 + 1e-13, np.arange(6)), [1, 1, 0, 0, 0, 0],
                               atol=tol("ramp_continuity"))


def test_slope_coefficients_and_gradient():
    punch = Punch(1.0, 2.0, 0.3, R=-5.0)
    m, h = 0.1, 0.7
    G, dm, dh = slope_coefficients(punch, m, h, 6)
    kinks = [math.acos((punch.b - m) / h), math.acos((-punch.b - m) / h)]
    ref = [(1 if k == 0 else 2) / np.pi * quad(lambda t: float(punch.slope(m + h * math.cos(t))) * math.cos(k * t),
                                              0, np.pi, points=kinks, epsabs=1e-15)[0] for k in range(7)]
    np.testing.assert_allclose(G, ref, atol=tol("slope"))
    eps = 1e-6
    fd_m = (slope_coefficients(punch, m + eps, h, 6)[0] - slope_coefficients(punch, m - eps, h, 6)[0]) / (2 * eps)
    fd_h = (slope_coefficients(punch, m, h + eps, 6)[0] - slope_coefficients(punch, m, h - eps, 6)[0]) / (2 * eps)
    np.testing.assert_allclose(dm, fd_m, atol=tol("slope_gradient"))
    np.testing.assert_allclose(dh, fd_h, atol=tol("slope_gradient"))


def test_log_kink_sums_its_series():
    phi = np.array([0.05, 1.0, 2.5, -0.7, 4.0, 0.0])
    k = np.arange(2, 400001, dtype=float)
    direct = [np.sum(np.sin(k * p) / (k**2 - 1)) for p in phi]
    np.testing.assert_allclose(log_kink(phi), direct, atol=tol("log_kink"))


def test_sine_series_matches_direct_sum():
    g = np.random.default_rng(1).normal(size=40)
    th = np.linspace(0, np.pi, 17)
    direct = np.sin(np.outer(th, np.arange(1, 41))) @ g
    np.testing.assert_allclose(sine_series(g, th), direct, atol=tol("sine_series"))


def test_a_long_sine_series_is_the_geometric_sum():
    """2048 terms ``r^k`` at 135 angles (two full blocks of the compiled loop and a partial one, in a
    2-D array): ``Σ r^k sin kθ = r sin θ/(1 - 2r cos θ + r^2)``, the tail past 2048 below 1e-17."""
    r = 0.98
    th = np.linspace(0.0, np.pi, 135).reshape(3, 45)
    exact = r * np.sin(th) / (1 - 2 * r * np.cos(th) + r * r)
    got = sine_series(r ** np.arange(1, 2049), th)
    assert got.shape == th.shape
    assert np.max(np.abs(got - exact)) <= tol("sine_series_long") * np.max(np.abs(exact))
    assert sine_series(r ** np.arange(1, 2049), 0.7).shape == ()


def test_power_series_is_the_geometric_sum():
    """Horner's rule on ``c_k = r^k``, ``k < n``: ``Σ (rz)^k = (1 - (rz)^n)/(1 - rz)``, in [-1, 1]."""
    r, n = 0.98, 2048
    z = np.linspace(-0.999, 0.999, 131)
    exact = (1 - (r * z) ** n) / (1 - r * z)
    np.testing.assert_allclose(power_series(r ** np.arange(n), z), exact, rtol=tol("power_series"), atol=0)
    assert power_series([2.0], z).tolist() == [2.0] * z.size


@pytest.mark.parametrize("shared", [True, False])
def test_kinked_sums_are_the_kink_and_remainder_terms(shared):
    """The compiled pass over the kinks and remainders against numpy's :func:`log_kink` and
    :func:`ramp_remainder` summed term by term; the remainders at the kinks' angles (one sine and
    logarithm shared) or at others."""
    theta = np.concatenate([np.linspace(0.0, np.pi, 97), [1.1, 2.3]])      # two points on the kinks
    p = np.random.default_rng(2).normal(size=theta.size)
    w, tw = np.array([0.7, -1.3]), np.array([1.1, 2.3])
    v, tv = np.array([0.4, 2.1]), (tw if shared else np.array([0.5, 2.9]))
    direct = p + sum(wj * (log_kink(theta + tj) + log_kink(theta - tj)) for wj, tj in zip(w, tw)) \
        + sum(vj * ramp_remainder(theta, tj) for vj, tj in zip(v, tv))
    got = kinked_sums(theta, p, w, tw, v, tv)
    assert np.max(np.abs(got - direct)) <= tol("kinked_sums") * np.max(np.abs(direct))


@pytest.mark.parametrize("u", [1e-9, 1e-6, 1e-3, 0.1, 1.0, 5.0])
def test_gap_sums_are_the_quadrature_of_the_gap_slope(u):
    """The stick gap's ``Σ G_k J_k(φ)``, ``J_k = ∫_1^ξ (1 - ρ^k) dξ``, against mpmath's quadrature of
    ``[Σ G_k - Σ G_k ρ^k] sinh t`` over ``[0, φ]`` for ``G_k = r^k`` (both sums in closed form)."""
    import mpmath
    r, K = 0.999, GAP_TERMS
    G = np.concatenate([[0.0], r ** np.arange(1, K + 1)])
    phi = float(np.log1p(u + np.sqrt(u * (u + 2.0))))
    with mpmath.workdps(30):
        rr = mpmath.mpf(r)
        total = rr * (1 - rr**K) / (1 - rr)

        def slope(t):
            q = rr * mpmath.exp(-t)
            return (total - q * (1 - q**K) / (1 - q)) * mpmath.sinh(t)
        exact = float(mpmath.quad(slope, [0, phi]))
    got = float(_gap_sums(G, np.array([phi]), np.array([u]))[0])
    assert abs(got - exact) <= tol("gap_sums") * abs(exact)


@pytest.mark.parametrize("m, h", [(0.1, 0.7), (-0.4, 1.5), (0.0, 0.2), (0.9, 0.5), (1.3, 0.3), (-0.7, 0.3)])
def test_the_low_slope_coefficients_are_the_projection(m, h):
    """``G_0..G_2`` (the moments of every Newton step, summed on floats) against quad split at the
    kinks, contacts over both joins, one, or none (a ramp whole or absent), with their gradients
    against central differences."""
    punch = Punch(1.0, 2.0, 0.3, R=-5.0)
    kinks = [math.acos(t) for t in ((punch.b - m) / h, (-punch.b - m) / h) if -1 < t < 1]
    if kinks:
        ref = [(1 if k == 0 else 2) / np.pi * quad(lambda t: float(punch.slope(m + h * math.cos(t))) * math.cos(k * t),
                                                  0, np.pi, points=kinks, epsabs=1e-15)[0] for k in range(3)]
    else:               # on one segment the slope is linear in s: T_0 and T_1 alone
        centre, end = (float(punch.slope(x)) for x in (m, m + h))
        ref = [centre, end - centre, 0.0]
    for kmax in (0, 1, 2):
        G, dm, dh = slope_coefficients(punch, m, h, kmax)
        assert G.shape == dm.shape == dh.shape == (kmax + 1,)
        np.testing.assert_allclose(G, ref[:kmax + 1], rtol=0, atol=tol("slope"))
    eps = 1e-6
    fd_m = (slope_coefficients(punch, m + eps, h, 2)[0] - slope_coefficients(punch, m - eps, h, 2)[0]) / (2 * eps)
    fd_h = (slope_coefficients(punch, m, h + eps, 2)[0] - slope_coefficients(punch, m, h - eps, 2)[0]) / (2 * eps)
    np.testing.assert_allclose(dm, fd_m, atol=tol("slope_gradient"))
    np.testing.assert_allclose(dh, fd_h, atol=tol("slope_gradient"))


@pytest.mark.parametrize("n, error", [(1, ValueError), (0, ValueError), (2**16 + 1, ValueError),
                                      (2.5, TypeError), (True, TypeError)])
def test_bad_n(n, error):
    with pytest.raises(error, match="`n`"):
        gauss_chebyshev(n)

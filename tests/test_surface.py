"""The core's contact on a discrete surface compliance (threepart/halfplane/surface.py).

References: Hertz's closed form (the contact half-width and the pressure of a
cylinder on a half-plane, and the tilt and shift a moment gives it), and the
quadrature of the log kernel.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from threepart.errors import InputError
from threepart.halfplane.surface import influence, solve_contact
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3
R, P = 10.0, 400.0
#: Hertz: a^2 = 2 A P R/π (eq. 4's A, both bodies)
a_H = math.sqrt(2 * A * P * R / math.pi)
#: a repeated solve and a fresh one, a hat's area by the trapezoidal rule: the same arithmetic, to rounding
ROUNDING = tolerance("wear-limit", "round_off").limit


def _nodes(n: int, s: float = 0.0) -> np.ndarray:
    return np.linspace(s - 1.3 * a_H, s + 1.3 * a_H, n)


def _hat(x: np.ndarray, j: int):
    """The hat of node ``j``: 1 there, linear to 0 at its neighbours."""
    return lambda t: float(np.interp(t, x, np.eye(x.size)[j]))


def test_the_influence_is_the_log_kernel_integrated():
    """C_ij against QUADPACK of -(A/π) ln(|x_i - t|/L) times node j's hat, divided by the hat's area."""
    x = np.array([-0.3, -0.1, 0.05, 0.2, 0.4, 0.43])
    C, w = influence(x, A)
    L = 10 * (x[-1] - x[0])
    assert np.allclose(w, [np.trapezoid(np.eye(x.size)[j], x) for j in range(x.size)], rtol=ROUNDING, atol=0)
    for i in range(x.size):
        for j in range(x.size):
            hat = _hat(x, j)
            lo, hi = x[max(j - 1, 0)], x[min(j + 1, x.size - 1)]
            pts = sorted({x[i], x[j]} & set(x[(x > lo) & (x < hi)]))
            ref = -A / math.pi * quad(lambda t: hat(t) * math.log(abs(x[i] - t) / L), lo, hi, points=pts or None,
                                      epsabs=0, epsrel=1e-13, limit=200)[0] / w[j]
            assert C[i, j] == pytest.approx(ref, rel=tolerance("surface", "kernel").limit)
    # the kernel's quadratic form is positive (L is long enough): on a symmetric grid K is symmetric
    xs = np.linspace(-0.3, 0.3, 9)
    Cs, ws = influence(xs, A)
    assert np.all(np.linalg.eigvalsh(0.5 * ((Cs * ws) + (Cs * ws).T)) > 0)


@pytest.mark.parametrize("bad", [np.array([0.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0])])
def test_the_influence_refuses_nodes_out_of_order(bad):
    """Fewer than two nodes or nodes not strictly increasing: a one-line InputError naming `x`."""
    with pytest.raises(InputError, match="`x` must be at least 2 strictly increasing"):
        influence(bad, A)


@pytest.mark.parametrize("s", [0.0, 0.03])
def test_hertz_on_nodes(s):
    """The nodes' contact against Hertz: its width, its pressure away from the ends, and the tilt -s/R."""
    x = _nodes(800, s)
    C, w = influence(x, A)
    sol = solve_contact(C, x, x * x / (2 * R), P, s, free_tilt=True)
    p = sol.f / w
    on = np.flatnonzero(sol.active)
    h = x[1] - x[0]
    assert abs(x[on[0]] - (s - a_H)) <= h and abs(x[on[-1]] - (s + a_H)) <= h
    p0 = 2 * P / (math.pi * a_H)
    inner = np.abs(x - s) < 0.8 * a_H
    ref = p0 * np.sqrt(1 - ((x[inner] - s) / a_H) ** 2)
    assert np.max(np.abs(p[inner] - ref)) <= tolerance("surface", "hertz").limit * p0
    assert abs(sol.alpha + s / R) <= tolerance("surface", "hertz").limit * a_H / R
    rounding = tolerance("wear-limit", "round_off").limit
    assert sum(sol.f) == pytest.approx(P, rel=rounding) and np.sum(x * sol.f) == pytest.approx(P * s, abs=rounding * P)


def test_a_factor_is_reused_only_for_the_same_compliance_and_set():
    """Two compliances, one the other's copy scaled: each solve equals a fresh solve's (the factor cache
    never hands one compliance's factor to another, nor to an array that reuses a freed one's id)."""
    from threepart.halfplane import surface

    x = _nodes(200)
    C, w = influence(x, A)
    first = solve_contact(C, x, x * x / (2 * R), P)
    for scale in (2.0, 0.5, 2.0):
        D = C * scale
        sol = solve_contact(D, x, x * x / (2 * R), P, active=first.active.copy())
        surface._FACTORS.clear()
        fresh = solve_contact(D.copy(), x, x * x / (2 * R), P, active=first.active.copy())
        assert np.allclose(sol.f, fresh.f, rtol=0, atol=ROUNDING * P)
        del D
    again = solve_contact(C, x, x * x / (2 * R), P, active=first.active.copy())
    assert np.allclose(again.f, first.f, rtol=0, atol=ROUNDING * P)


def test_per_array_keeps_by_identity_and_drops_the_least_recent():
    """PerArray: an equal but other array is not the key; the least recently used entry goes first."""
    from threepart.halfplane.surface import PerArray

    kept = PerArray(2)
    a, b, c = np.zeros(3), np.zeros(3), np.ones(3)
    kept.put(a, "k", 1)
    assert kept.get(a, "k") == 1 and kept.get(b, "k") is None and kept.get(a, "other") is None
    kept.put(b, "k", 2)
    assert kept.get(a, "k") == 1        # a is now the more recent
    kept.put(c, "k", 3)                 # b, the least recent, goes
    assert kept.get(b, "k") is None and kept.get(a, "k") == 1 and kept.get(c, "k") == 3

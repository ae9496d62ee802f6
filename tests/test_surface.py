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

from threepart.halfplane.surface import influence, solve_contact
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3
R, P = 10.0, 400.0
#: Hertz: a^2 = 2 A P R/π (eq. 4's A, both bodies)
a_H = math.sqrt(2 * A * P * R / math.pi)


def _cells(n: int, s: float = 0.0) -> np.ndarray:
    return np.linspace(s - 1.3 * a_H, s + 1.3 * a_H, n + 1)


def test_the_influence_is_the_log_kernel_integrated():
    """C_ij against QUADPACK of -(A/π) ln(|x_i - t|/L) over cell j, divided by its width."""
    edges = np.array([-0.3, -0.1, 0.05, 0.2, 0.4])
    C = influence(edges, A)
    L = 10 * (edges[-1] - edges[0])
    x = 0.5 * (edges[1:] + edges[:-1])
    for i in range(4):
        for j in range(4):
            lo, hi = edges[j], edges[j + 1]
            pts = [x[i]] if lo < x[i] < hi else None
            ref = -A / math.pi * quad(lambda t: math.log(abs(x[i] - t) / L), lo, hi, points=pts,
                                      epsabs=0, epsrel=1e-13, limit=200)[0] / (hi - lo)
            assert C[i, j] == pytest.approx(ref, rel=tolerance("surface", "kernel").limit)
    assert np.all(np.linalg.eigvalsh(0.5 * (C + C.T)) > 0)       # positive definite: L is long enough


@pytest.mark.parametrize("s", [0.0, 0.03])
def test_hertz_on_cells(s):
    """The cells' contact against Hertz: its width, its pressure away from the ends, and the tilt -s/R."""
    edges = _cells(800, s)
    x, w = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    sol = solve_contact(influence(edges, A), x, x * x / (2 * R), P, s, free_tilt=True)
    p = sol.f / w
    on = np.flatnonzero(sol.active)
    h = w[0]
    assert abs(edges[on[0]] - (s - a_H)) <= h and abs(edges[on[-1] + 1] - (s + a_H)) <= h
    p0 = 2 * P / (math.pi * a_H)
    inner = np.abs(x - s) < 0.8 * a_H
    ref = p0 * np.sqrt(1 - ((x[inner] - s) / a_H) ** 2)
    assert np.max(np.abs(p[inner] - ref)) <= tolerance("surface", "hertz").limit * p0
    assert abs(sol.alpha + s / R) <= tolerance("surface", "hertz").limit * a_H / R
    rounding = tolerance("wear-limit", "round_off").limit
    assert sum(sol.f) == pytest.approx(P, rel=rounding) and np.sum(x * sol.f) == pytest.approx(P * s, abs=rounding * P)

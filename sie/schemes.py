"""The two discretisations of the normal integral equation, behind one interface.

Both reduce the problem on a trial contact ``[m - h, m + h]`` to three numbers,
the (discrete or exact) Chebyshev coefficients ``G_0, G_1, G_2`` of the
geometric slope ``g'(x) = v'(x) - α``, with their gradients in ``(m, h)``:

* consistency: ``α + G_0 = 0``;
* load: ``P = π h G_1 / (2A)``;
* centroid: ``P (s - m) = π h^2 G_2 / (4A)``.

``"plain"``
    Gauss–Chebyshev collocation (:mod:`sie.quadrature`): ``n`` nodes,
    ``n + 1`` collocation points, the tilt as extra unknown. It sees the
    slope only at the collocation points, so the kinks at ``x = ±b`` limit it
    to algebraic convergence (load ~ ``n^-2``, pointwise pressure ~ ``n^-1``).
``"projected"``
    Kink-aware: the slope is projected onto Chebyshev polynomials exactly,
    segment by segment (:mod:`sie.projection`), so ``G_0, G_1, G_2`` and hence
    ``a, c, α, s`` carry no discretisation error for any ``n >= 2``. The
    pressure keeps ``n`` sine terms; the leading, log-singular part of each
    kink's coefficients is summed in closed form (:func:`sie.series.log_kink`)
    and the remainder, whose coefficients fall as ``k^-3``, is truncated, so the
    pointwise error is below the bound ``info["pressure_bound"]`` ~ ``n^-2``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from threepart.punch import Punch

from .projection import kinks, slope_coefficients
from .quadrature import plain_functionals
from .series import ChebyshevPressure

__all__ = ["SCHEMES", "Plain", "Projected", "make_scheme"]


@dataclass(frozen=True)
class Plain:
    """Plain Gauss–Chebyshev collocation with ``n`` nodes."""

    n: int
    name: str = "plain"

    def moments(self, punch: Punch, m: float, h: float) -> tuple[np.ndarray, np.ndarray]:
        """``(G_0, G_1, G_2)`` of the collocation system and their ``(m, h)`` Jacobian."""
        fun = plain_functionals(self.n)
        s = fun.rule.collocation
        x = m + h * s
        G = fun.rows @ punch.slope(x)
        curv = punch.curvature(x)
        J = np.column_stack([fun.rows @ curv, fun.rows @ (curv * s)])
        return G, J

    def pressure(self, punch: Punch, A: float, m: float, h: float) -> tuple[ChebyshevPressure, dict]:
        """Solve the collocation system on ``[m - h, m + h]`` and expand the nodal values in ``sin kθ``."""
        fun = plain_functionals(self.n)
        u, _ = fun.solve(punch.slope(m + h * fun.rule.collocation))
        # u_i sin θ_i = Σ_k g_k sin kθ_i at θ_i = iπ/(n+1): a type-I discrete sine transform
        g = scipy.fft.idst(2.0 * u * np.sin(fun.rule.angles), type=1) / A
        return ChebyshevPressure(m=m, h=h, g=g), {}


@dataclass(frozen=True)
class Projected:
    """Exact segment-wise Chebyshev projection with closed-form kink terms, ``n`` sine terms."""

    n: int
    name: str = "projected"

    def moments(self, punch: Punch, m: float, h: float) -> tuple[np.ndarray, np.ndarray]:
        """Exact ``(G_0, G_1, G_2)`` and their ``(m, h)`` Jacobian."""
        G, dm, dh = slope_coefficients(punch, m, h, 2)
        return G, np.column_stack([dm, dh])

    def pressure(self, punch: Punch, A: float, m: float, h: float) -> tuple[ChebyshevPressure, dict]:
        """Pressure from the exact coefficients, kinks summed in closed form."""
        k = np.arange(1, self.n + 1, dtype=float)
        G = slope_coefficients(punch, m, h, self.n)[0]
        g = G[1:] / A
        terms = []
        bound = 0.0
        for amp, beta in kinks(punch, m, h):
            if amp == 0.0 or not -1.0 < beta < 1.0:
                continue
            tb = math.acos(beta)
            sb = math.sin(tb)
            # leading coefficients -(2/π) sin θ_b cos kθ_b/(k^2 - 1), k >= 2, summed exactly
            sing = np.zeros_like(g)
            sing[1:] = -2.0 / np.pi * sb * np.cos(k[1:] * tb) / (k[1:] ** 2 - 1)
            g = g - amp / A * sing
            terms.append((-amp * sb / (np.pi * A), tb))
            # truncated remainder (2/π) cos θ_b sin kθ_b/(k(k^2-1)), k > n
            bound += abs(amp * beta) / A * 2.0 / np.pi / (2.0 * self.n * (self.n + 1))
        return ChebyshevPressure(m=m, h=h, g=g, kinks=tuple(terms)), {"pressure_bound": bound}


SCHEMES: dict[str, type[Plain] | type[Projected]] = {"plain": Plain, "projected": Projected}


def make_scheme(scheme: str, n: int) -> Plain | Projected:
    """The scheme object named ``scheme`` with ``n`` terms."""
    if scheme not in SCHEMES:
        raise ValueError(f"`scheme` = {scheme!r} must be one of {sorted(SCHEMES)}")
    return SCHEMES[scheme](n)

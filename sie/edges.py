"""The pressure's edge multipliers of the SIE, from its bounded density at the end nodes.

The SIE's pressure on ``[m - h, m + h]`` (:class:`sie.series.ChebyshevPressure`,
``x = m + h cos θ``) is

    p(θ) = Σ g_k sin kθ + Σ_j w_j [S(θ + θ_j) + S(θ - θ_j)] + Σ_i v_i [F(θ - θ_i) - F(θ + θ_i)]/2,

odd in ``θ`` about both ends ``θ = 0`` (``x = c``) and ``θ = π`` (``x = -a``).
There ``r = h (1 - cos θ) ≈ h θ²/2``, so ``K_N = √(2/h) dp/dθ`` at the end, with
the derivatives summed in closed form (docs/EDGES.md, E4): ``F' = -S`` and

    S'(φ) = cos φ (1/4 - ln|2 sin(φ/2)|) - cos²(φ/2).

K_N     -- ``(K_N(-a), K_N(c))`` of an SIE density
edges   -- the registry's ``edges`` call: ``((K_N, None), (K_N, None))`` of an SIE normal result
"""
from __future__ import annotations

import math

import numpy as np

from threepart.results import NormalResult

from .series import ChebyshevPressure, log_kink
from threepart.errors import InputError

__all__ = ["K_N", "edges"]


def _dS(phi: float) -> float:
    """``S'(φ)`` of :func:`sie.series.log_kink`: ``cos φ (1/4 - ln|2 sin(φ/2)|) - cos²(φ/2)``."""
    return math.cos(phi) * (0.25 - math.log(abs(2.0 * math.sin(0.5 * phi)))) - math.cos(0.5 * phi) ** 2


def K_N(density: ChebyshevPressure) -> tuple[float, float]:
    """``(K_N(-a), K_N(c))`` of a density: ``√(2/h)`` times its slope in ``θ`` at ``θ = π`` and ``θ = 0`` (E4)."""
    g = np.asarray(density.g, dtype=float)
    k = np.arange(1, g.size + 1, dtype=float)
    right = float(np.sum(k * g))
    left = float(np.sum(k * g * np.where(k % 2 == 1, 1.0, -1.0)))
    for w, tb in density.kinks:
        right += 2.0 * w * _dS(tb)
        left -= 2.0 * w * _dS(math.pi - tb)
    for v, tb in getattr(density, "remainders", ()):
        right += v * float(log_kink(tb))
        left += v * float(log_kink(math.pi - tb))
    scale = math.sqrt(2.0 / density.h)
    return scale * left, scale * right


def edges(normal: NormalResult) -> tuple[tuple[float, float | None], tuple[float, float | None]]:
    """``((K_N(-a), None), (K_N(c), None))`` of an SIE normal result (its ``density``)."""
    density = getattr(normal, "density", None)
    if density is None:
        raise InputError("`normal` has no SIE density to take the edge multipliers from")
    left, right = K_N(density)
    return (left, None), (right, None)

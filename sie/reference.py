"""Independent pointwise reference: the bounded inversion formula by adaptive quadrature.

For a *given* contact ``[-a, c]`` and tilt ``α`` (paper eq. inverted_IE, with
the compressive sign) and ``x = m + h cos θ``, ``t = m + h cos φ``,

    p(x) = (sin θ / π) ∫_0^π [F(cos φ) - F(cos θ)] / (cos φ - cos θ) dφ,
    F(s) = v'(m + h s) / A,

since ``PV ∫_0^π dφ/(cos φ - cos θ) = 0``. The integrand is bounded, so
:func:`scipy.integrate.quad` with break points at ``θ`` and at the kinks
``x = ±b`` evaluates it to near machine precision. It is slow (one adaptive
integral per point) and is meant for tests and benchmarks only; it shares no
code with :mod:`sie.schemes`.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import IntegrationWarning, quad

from threepart.problem.punch import Punch


def quiet_quad(*args, **kwargs):
    """``scipy.integrate.quad`` asked for near machine precision: its round-off warning is expected.

    The requested ``epsrel`` is at the level of rounding, so QUADPACK reports
    that round-off limits it; the value is still the best double-precision
    estimate. Only that warning is silenced, only here.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        return quad(*args, **kwargs)


__all__ = ["pressure_by_quadrature", "quiet_quad"]


def pressure_by_quadrature(punch: Punch, A: float, a: float, c: float, alpha: float,
                           x: ArrayLike) -> np.ndarray:
    """Bounded pressure on ``[-a, c]`` at points ``x`` by the inversion integral (0 outside)."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    m, h = 0.5 * (c - a), 0.5 * (a + c)
    kinks = [math.acos(sb) for sb in ((punch.b - m) / h, (-punch.b - m) / h) if -1 < sb < 1]

    def F(phi: float) -> float:
        return float(punch.slope(m + h * math.cos(phi), alpha)) / A

    out = np.zeros_like(x)
    for i, xi in enumerate(x):
        s = (xi - m) / h
        if not -1 < s < 1:
            continue
        th = math.acos(s)
        Fth = F(th)

        def integrand(phi: float) -> float:
            d = math.cos(phi) - s
            return 0.0 if d == 0 else (F(phi) - Fth) / d

        pts = sorted({th, *kinks})
        val, _ = quiet_quad(integrand, 0.0, math.pi, points=pts, limit=400, epsabs=1e-15, epsrel=1e-13)
        out[i] = math.sin(th) / math.pi * val
    return out.reshape(np.shape(x)) if np.ndim(x) else out

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
    pressure keeps ``n`` sine terms; each kink's coefficients are summed in
    closed form, the log-singular leading part (:func:`sie.series.log_kink`)
    and the remainder that falls as ``k^-3`` (:func:`sie.projection.ramp_remainder`),
    so the sine terms left carry only rounding and the pressure is exact for
    any ``n`` (``info["pressure_bound"]`` bounds that rounding). Truncating the
    remainder at ``n`` terms, as before issue 29, left an error ~ ``n^-2``
    next to a join: 1.8e-2 of the peak at ``n = 1024`` for an edge radius of 0.03 b.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numpy.typing import ArrayLike

import numpy as np
import scipy.fft

from threepart.problem.punch import Punch

from .projection import kinks, slope_coefficients
from .quadrature import plain_functionals
from .series import ChebyshevPressure, kinked_sums, sine_series
from threepart.errors import InputError

__all__ = ["SCHEMES", "Plain", "Projected", "make_scheme", "KinkedPressure"]

#: rounding of the closed-form kink sums, per unit of a kink's pressure amplitude |amp|/A
#: (a few logarithms and cosines of O(1), each good to ~1e-16)
KINK_ROUNDING = 1e-14


@dataclass(frozen=True)
class KinkedPressure(ChebyshevPressure):
    """A :class:`sie.series.ChebyshevPressure` plus the kinks' ``k^-3`` remainders in closed form.

    Attributes
    ----------
    remainders
        Pairs ``(w_j, θ_j)``: ``p += w_j [F(θ - θ_j) - F(θ + θ_j)]/2``
        (:func:`sie.projection.ramp_remainder`).
    """

    remainders: tuple[tuple[float, float], ...] = ()

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """The pressure at ``x``: the sine series, the kinks and their remainders summed in one
        compiled pass (:func:`sie.series.kinked_sums`; as :func:`sie.projection.ramp_remainder` term by term)."""
        x = np.asarray(x, dtype=float)
        if not self.remainders:
            return super().__call__(x)
        s = np.clip((x - self.m) / self.h, -1.0, 1.0)
        theta = np.arccos(s)
        inside = (x > self.m - self.h) & (x < self.m + self.h) & (np.abs(s) < 1.0)
        w, tw = (np.array([k[i] for k in self.kinks], dtype=float) for i in (0, 1))
        v, tv = (np.array([r[i] for r in self.remainders], dtype=float) for i in (0, 1))
        flat = np.ascontiguousarray(theta).ravel()
        p = kinked_sums(flat, sine_series(self.g, flat), w, tw, v, tv).reshape(theta.shape)
        return np.where(inside, p, 0.0)


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
        return G, np.array([dm, dh]).T

    def pressure(self, punch: Punch, A: float, m: float, h: float) -> tuple[ChebyshevPressure, dict]:
        """Pressure from the exact coefficients, kinks summed in closed form."""
        k = np.arange(1, self.n + 1, dtype=float)
        G = slope_coefficients(punch, m, h, self.n)[0]
        g = G[1:] / A
        terms = []
        bound = 0.0
        rests = []
        for amp, beta in kinks(punch, m, h):
            if amp == 0.0 or not -1.0 < beta < 1.0:
                continue
            tb = math.acos(beta)
            sb = math.sin(tb)
            # a ramp's coefficients for k >= 2 (sie.projection.ramp_coefficients), both parts summed
            # exactly: the leading -(2/π) sin θ_b cos kθ_b/(k^2 - 1) and the remainder
            # (2/π) cos θ_b sin kθ_b/(k(k^2 - 1)); what is left of g_k (k >= 2) is rounding
            g[1:] -= amp / A * 2.0 / np.pi * (-sb * np.cos(k[1:] * tb) / (k[1:] ** 2 - 1)
                                              + beta * np.sin(k[1:] * tb) / (k[1:] * (k[1:] ** 2 - 1)))
            terms.append((-amp * sb / (np.pi * A), tb))
            rests.append((2.0 * amp * beta / (np.pi * A), tb))
            bound += KINK_ROUNDING * abs(amp) / A
        bound += float(np.sum(np.abs(g[1:])))      # the rounding left in the sine terms k >= 2
        return KinkedPressure(m=m, h=h, g=g, kinks=tuple(terms), remainders=tuple(rests)), \
            {"pressure_bound": bound}


SCHEMES: dict[str, type[Plain] | type[Projected]] = {"plain": Plain, "projected": Projected}


def make_scheme(scheme: str, n: int) -> Plain | Projected:
    """The scheme object named ``scheme`` with ``n`` terms."""
    if scheme not in SCHEMES:
        raise InputError(f"`scheme` = {scheme!r} must be one of {sorted(SCHEMES)}")
    return SCHEMES[scheme](n)

"""Pressure as a sine series in θ, with optional closed-form kink terms.

The bounded solution on ``[m - h, m + h]`` is ``p = Σ_{k≥1} g_k sin kθ`` with
``x = m + h cos θ`` (:mod:`sie.projection`). A slope kink at ``s_b = cos θ_b``
contributes coefficients whose leading part is
``-(2/π) sin θ_b cos kθ_b / (k^2 - 1)``; its sum is the log-singular function

    Σ_{k≥2} cos kθ_b sin kθ / (k^2 - 1) = [S(θ + θ_b) + S(θ - θ_b)] / 2,
    S(φ) = Σ_{k≥2} sin kφ / (k^2 - 1) = sin φ (1/4 - ln|2 sin(φ/2)|),

which carries the ``(x ∓ b) ln|x ∓ b|`` terms of the pressure. The identity
follows from ``Σ cos jφ / j = -ln|2 sin(φ/2)|``; it is checked against direct
summation in the tests.

The two series loops, Clenshaw's (:func:`sine_series`) and Horner's
(:func:`power_series`), run compiled by numba (``cache=True``: compiled once per
machine), a point at a time: a series of thousands of terms at a few points
costs microseconds, not a numpy call per term.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

__all__ = ["sine_series", "power_series", "kinked_sums", "log_kink", "ChebyshevPressure"]

#: compiled once per machine (cached beside the source), IEEE arithmetic (inf, NaN: never an exception)
compiled = njit(cache=True, error_model="numpy", nogil=True)


#: points recurred side by side in the compiled loops (independent recurrences: SIMD lanes)
_BLOCK = 64


@compiled
def _clenshaw(g: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """:func:`sine_series` on a 1-D array of angles, :data:`_BLOCK` points at a time."""
    out = np.empty(theta.size)
    x2, b1, b2 = np.empty(_BLOCK), np.empty(_BLOCK), np.empty(_BLOCK)
    for start in range(0, theta.size, _BLOCK):
        m = min(_BLOCK, theta.size - start)
        for i in range(m):
            x2[i] = 2.0 * math.cos(theta[start + i])
            b1[i], b2[i] = 0.0, 0.0
        for k in range(g.size - 1, -1, -1):
            gk = g[k]
            for i in range(m):
                t = gk + x2[i] * b1[i] - b2[i]
                b2[i] = b1[i]
                b1[i] = t
        for i in range(m):
            out[start + i] = math.sin(theta[start + i]) * b1[i]
    return out


@compiled
def _horner(c: np.ndarray, z: np.ndarray) -> np.ndarray:
    """:func:`power_series` on a 1-D array of points (``c`` not empty), :data:`_BLOCK` at a time."""
    out = np.empty(z.size)
    acc = np.empty(_BLOCK)
    for start in range(0, z.size, _BLOCK):
        m = min(_BLOCK, z.size - start)
        for i in range(m):
            acc[i] = c[c.size - 1] + z[start + i] * 0.0
        for k in range(c.size - 2, -1, -1):
            ck = c[k]
            for i in range(m):
                acc[i] = ck + acc[i] * z[start + i]
        for i in range(m):
            out[start + i] = acc[i]
    return out


def sine_series(g: ArrayLike, theta: ArrayLike) -> np.ndarray:
    """``Σ_{k=1}^{n} g_k sin kθ`` by Clenshaw's recurrence for ``sin θ Σ g_k U_{k-1}(cos θ)``.

    Parameters
    ----------
    g
        Coefficients ``g_1..g_n`` (``g[0]`` multiplies ``sin θ``).
    theta
        Angles, any shape.
    """
    g = np.ascontiguousarray(g, dtype=float).ravel()
    theta = np.asarray(theta, dtype=float)
    return _clenshaw(g, np.ascontiguousarray(theta).ravel()).reshape(theta.shape)


def power_series(c: ArrayLike, z: ArrayLike) -> np.ndarray:
    """``Σ_{k=0}^{n-1} c_k z^k`` by Horner's rule (``numpy.polynomial.polynomial.polyval``'s loop).

    Outside the contact the sine series continues as a power series in
    ``ρ = ξ - sgn ξ sqrt(ξ^2 - 1)`` (:func:`sie.normal._gap_slope_outside`).

    Parameters
    ----------
    c
        Coefficients ``c_0..c_{n-1}``, at least one.
    z
        Points, any shape.
    """
    c = np.ascontiguousarray(c, dtype=float).ravel()
    z = np.asarray(z, dtype=float)
    return _horner(c, np.ascontiguousarray(z).ravel()).reshape(z.shape)


@compiled
def _chord(phi: float) -> tuple[float, float, float, float]:
    """``|2 sin(φ/2)|``, its logarithm (``-inf`` at 0), ``sin φ`` and ``cos φ``: what both kink sums take of ``φ``."""
    s = abs(2.0 * math.sin(0.5 * phi))
    return s, (math.log(s) if s > 0 else -math.inf), math.sin(phi), math.cos(phi)


@compiled
def _kink_and_rest(phi: float) -> tuple[float, float]:
    """``S(φ)`` of :func:`log_kink` and ``F(φ)`` of :func:`sie.projection.ramp_remainder`'s kernel, from one
    :func:`_chord`: ``F(φ) = 2 sin^2(φ/2) ln|2 sin(φ/2)| + (3/4) cos φ - 1/2``, ``2 |sin(φ/2)| = s``."""
    s, log_s, sin_phi, cos_phi = _chord(phi)
    if s > 0:
        return sin_phi * (0.25 - log_s), s * (0.5 * s) * log_s + 0.75 * cos_phi - 0.5
    return 0.0, 0.75 * cos_phi - 0.5


@compiled
def kinked_sums(theta: np.ndarray, p: np.ndarray, w: np.ndarray, tw: np.ndarray, v: np.ndarray,
                tv: np.ndarray) -> np.ndarray:
    """``p + Σ_j w_j [S(θ + θ_j) + S(θ - θ_j)] + Σ_j v_j [F(θ - θ_j) - F(θ + θ_j)]/2`` at each ``θ``.

    The kink terms of :class:`ChebyshevPressure` (angles ``tw``) and the remainders of
    :class:`sie.schemes.KinkedPressure` (angles ``tv``), added in their order; where a
    remainder's angle is its kink's, ``S`` and ``F`` share one sine and one logarithm.
    """
    out = np.empty(theta.size)
    n = min(w.size, v.size)
    fm, fp = np.empty(max(n, 1)), np.empty(max(n, 1))
    for i in range(theta.size):
        th, pk, extra = theta[i], p[i], 0.0
        for j in range(w.size):
            sp, fp_ = _kink_and_rest(th + tw[j])
            sm, fm_ = _kink_and_rest(th - tw[j])
            pk = pk + w[j] * (sp + sm)
            if j < n:
                fp[j], fm[j] = fp_, fm_
        for j in range(v.size):
            if j < n and tv[j] == tw[j]:
                minus, plus = fm[j], fp[j]
            else:
                minus, plus = _kink_and_rest(th - tv[j])[1], _kink_and_rest(th + tv[j])[1]
            extra = extra + v[j] * (0.5 * (minus - plus))
        out[i] = pk + extra
    return out


def log_kink(phi: ArrayLike) -> np.ndarray:
    """``S(φ) = Σ_{k≥2} sin kφ/(k^2 - 1) = sin φ (1/4 - ln|2 sin(φ/2)|)``, with ``S(2πj) = 0``."""
    phi = np.asarray(phi, dtype=float)
    s = np.abs(2.0 * np.sin(0.5 * phi))
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.sin(phi) * (0.25 - np.log(s))
    return np.where(s > 0, out, 0.0)


@dataclass(frozen=True)
class ChebyshevPressure:
    """A bounded pressure ``p(x)`` on ``[m - h, m + h]``, zero outside.

    ``p = Σ g_k sin kθ + Σ_j w_j [S(θ + θ_j) + S(θ - θ_j)]`` with ``x = m + h cos θ``.

    Attributes
    ----------
    m, h
        Centre and half-width of the loaded interval.
    g
        Sine coefficients ``g_1..g_n`` (pressure units).
    kinks
        Pairs ``(w_j, θ_j)`` of closed-form kink terms (empty for plain collocation).
    """

    m: float
    h: float
    g: np.ndarray = field(repr=False, compare=False)
    kinks: tuple[tuple[float, float], ...] = ()

    def __call__(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        s = (x - self.m) / self.h
        # the open interval by its ends, as the result reports them (a = h - m, c = h + m):
        # exactly 0 at and beyond them, whatever the rounding of (x - m)/h
        inside = (x > self.m - self.h) & (x < self.m + self.h) & (np.abs(s) < 1.0)
        theta = np.arccos(np.clip(s, -1.0, 1.0))
        p = sine_series(self.g, theta)
        for w, tb in self.kinks:
            p = p + w * (log_kink(theta + tb) + log_kink(theta - tb))
        return np.where(inside, p, 0.0)

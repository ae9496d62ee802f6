"""Exact Chebyshev projection of the piecewise-linear slope ``v'(x)`` (paper eq. 2).

On the contact ``[-a, c]`` put ``x = m + h s`` with ``h = (a + c)/2``,
``m = (c - a)/2`` and ``s = cos θ``. The slope of eq. (2) is, without the tilt,

    g'(x) = κ0 x - κ1 (-b - x)_+ + κ2 (x - b)_+,

with ``κ0 = 1/R`` and the curvature jumps ``κ1 = 1/R1 - 1/R``,
``κ2 = 1/R2 - 1/R`` (:class:`closedform.geometry.Punch`). Each ramp
``(s - β)_+`` has Chebyshev coefficients in closed form, so

    g'(m + h s) = Σ_k G_k T_k(s)

is projected exactly, segment by segment, for any number of terms. The bounded
solution of ``-(1/π) PV ∫ p(t)/(t - x) dt = v'(x)/A`` is then
``p = Σ_{k≥1} (G_k/A) sin kθ`` under the consistency condition
``α + G_0 = 0``; the load is ``P = π h G_1/(2A)`` and the moment about the
contact centre ``P (s - m) = π h^2 G_2/(4A)``.

Because ``v''`` jumps at ``x = ±b`` the coefficients decay only as ``k^-2``;
their leading part ``-(2/π) sin θ_b cos kθ_b/(k^2 - 1)`` is what
:func:`sie.series.log_kink` sums in closed form.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from threepart.problem.punch import Punch

__all__ = ["ramp_coefficients", "ramp_coefficients_dbeta", "slope_coefficients", "kinks",
           "ramp_remainder"]


def ramp_coefficients(beta: float, k: ArrayLike) -> np.ndarray:
    """Chebyshev coefficients of the ramp ``(s - β)_+`` on ``[-1, 1]``.

    With ``θ_b = arccos β`` (``T_0`` taken with weight ``1/π``, the others ``2/π``):

    * ``k = 0``: ``(sin θ_b - θ_b cos θ_b)/π``
    * ``k = 1``: ``(θ_b - sin θ_b cos θ_b)/π``
    * ``k >= 2``: ``(2/π) [-sin θ_b cos kθ_b/(k^2-1) + cos θ_b sin kθ_b/(k(k^2-1))]``

    For ``β >= 1`` the ramp vanishes; for ``β <= -1`` it is ``s - β``.
    """
    k = np.asarray(k)
    kf = k.astype(float)
    if beta >= 1.0:
        return np.zeros(k.shape)
    if beta <= -1.0:
        return np.where(k == 0, -beta, np.where(k == 1, 1.0, 0.0))
    tb = math.acos(beta)
    sb, cb = math.sin(tb), beta
    with np.errstate(divide="ignore", invalid="ignore"):
        high = 2.0 / np.pi * (-sb * np.cos(kf * tb) / (kf**2 - 1)
                              + cb * np.sin(kf * tb) / (kf * (kf**2 - 1)))
    return np.where(k == 0, (sb - tb * cb) / np.pi,
                    np.where(k == 1, (tb - sb * cb) / np.pi, high))


def ramp_coefficients_dbeta(beta: float, k: ArrayLike) -> np.ndarray:
    """``d/dβ`` of :func:`ramp_coefficients`: minus the coefficients of the step ``H(s - β)``."""
    k = np.asarray(k)
    kf = k.astype(float)
    if beta >= 1.0:
        return np.zeros(k.shape)
    if beta <= -1.0:
        return np.where(k == 0, -1.0, 0.0)
    tb = math.acos(beta)
    with np.errstate(divide="ignore", invalid="ignore"):
        high = -2.0 / np.pi * np.sin(kf * tb) / kf
    return np.where(k == 0, -tb / np.pi, high)


def kinks(punch: Punch, m: float, h: float) -> tuple[tuple[float, float], ...]:
    """Ramps of ``g'(m + h s)``: pairs ``(amplitude, β)``, i.e. ``Σ amplitude (s - β)_+``.

    The left ramp ``-κ1 (-b - x)_+ = -κ1 h (β1 - s)_+`` is written as
    ``-κ1 h (s - β1)_+`` plus a linear part that
    :func:`slope_coefficients` adds separately.
    """
    return ((punch.kappa2 * h, (punch.b - m) / h), (-punch.kappa1 * h, (-punch.b - m) / h))


def slope_coefficients(punch: Punch, m: float, h: float, kmax: int
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact Chebyshev coefficients ``G_0..G_kmax`` of ``g'(m + h s)`` and their gradients.

    Parameters
    ----------
    punch
        The punch geometry (eq. 2); the tilt is not included.
    m, h
        Centre and half-width of the interval, ``h > 0``.
    kmax
        Highest degree returned.

    Returns
    -------
    G, dG_dm, dG_dh
        Arrays of length ``kmax + 1``.

    Notes
    -----
    Up to ``kmax = 2`` (the three moments a Newton step on the contact ends needs, called
    thousands of times a solve) the same sums run on plain floats (:func:`_low_coefficients`).
    """
    if kmax <= 2:
        G, dm, dh = _low_coefficients(punch, m, h)
        return np.array(G[:kmax + 1]), np.array(dm[:kmax + 1]), np.array(dh[:kmax + 1])
    k = np.arange(kmax + 1)
    e0 = (k == 0).astype(float)
    e1 = (k == 1).astype(float)
    k0, k1, k2, b = punch.kappa0, punch.kappa1, punch.kappa2, punch.b
    # central curvature: κ0 (m + h s)
    G = k0 * m * e0 + k0 * h * e1
    dm = k0 * e0
    dh = k0 * e1
    # right ramp κ2 (x - b)_+ = κ2 h (s - β2)_+
    if k2 != 0.0:
        beta = (b - m) / h
        r, dr = ramp_coefficients(beta, k), ramp_coefficients_dbeta(beta, k)
        G = G + k2 * h * r
        dm = dm - k2 * dr
        dh = dh + k2 * (r - beta * dr)
    # left ramp -κ1 (-b - x)_+ = -κ1 h [(s - β1)_+ - (s - β1)]
    if k1 != 0.0:
        beta = (-b - m) / h
        r, dr = ramp_coefficients(beta, k), ramp_coefficients_dbeta(beta, k)
        G = G - k1 * h * r + k1 * (b + m) * e0 + k1 * h * e1
        dm = dm + k1 * dr + k1 * e0
        dh = dh - k1 * (r - beta * dr) + k1 * e1
    return G, dm, dh


def _low_ramp(beta: float) -> tuple[list[float], list[float]]:
    """:func:`ramp_coefficients` and :func:`ramp_coefficients_dbeta` for ``k = 0, 1, 2``, on floats.

    The same expressions, term by term, as the array functions (they agree to rounding).
    """
    if beta >= 1.0:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    if beta <= -1.0:
        return [-beta, 1.0, 0.0], [-1.0, 0.0, 0.0]
    tb = math.acos(beta)
    sb, cb = math.sin(tb), beta
    c2, s2 = math.cos(2.0 * tb), math.sin(2.0 * tb)
    r = [(sb - tb * cb) / math.pi, (tb - sb * cb) / math.pi,
         2.0 / math.pi * (-sb * c2 / 3.0 + cb * s2 / 6.0)]
    dr = [-tb / math.pi, -2.0 / math.pi * math.sin(tb), -2.0 / math.pi * s2 / 2.0]
    return r, dr


def _low_coefficients(punch: Punch, m: float, h: float
                      ) -> tuple[list[float], list[float], list[float]]:
    """``G_0..G_2`` of ``g'(m + h s)`` and their ``(m, h)`` gradients: :func:`slope_coefficients` on floats."""
    k0, k1, k2, b = punch.kappa0, punch.kappa1, punch.kappa2, punch.b
    G, dm, dh = [k0 * m, k0 * h, 0.0], [k0, 0.0, 0.0], [0.0, k0, 0.0]
    if k2 != 0.0:       # right ramp κ2 (x - b)_+ = κ2 h (s - β2)_+
        beta = (b - m) / h
        r, dr = _low_ramp(beta)
        G = [G[i] + k2 * h * r[i] for i in range(3)]
        dm = [dm[i] - k2 * dr[i] for i in range(3)]
        dh = [dh[i] + k2 * (r[i] - beta * dr[i]) for i in range(3)]
    if k1 != 0.0:       # left ramp -κ1 (-b - x)_+ = -κ1 h [(s - β1)_+ - (s - β1)]
        beta = (-b - m) / h
        r, dr = _low_ramp(beta)
        G = [G[i] - k1 * h * r[i] for i in range(3)]
        G[0], G[1] = G[0] + k1 * (b + m), G[1] + k1 * h
        dm = [dm[i] + k1 * dr[i] for i in range(3)]
        dm[0] = dm[0] + k1
        dh = [dh[i] - k1 * (r[i] - beta * dr[i]) for i in range(3)]
        dh[1] = dh[1] + k1
    return G, dm, dh


def _remainder_kernel(phi: np.ndarray) -> np.ndarray:
    """``F(φ) = Σ_{k>=2} cos kφ/(k(k^2-1)) = 2 sin^2(φ/2) ln|2 sin(φ/2)| + (3/4) cos φ - 1/2``.

    From ``1/(k(k^2-1)) = 1/(2(k-1)) + 1/(2(k+1)) - 1/k`` and
    ``Σ_{j>=1} cos jφ/j = -ln|2 sin(φ/2)|`` (the sine sums cancel); ``F(0) = 1/4``.
    """
    half = np.abs(np.sin(0.5 * phi))
    with np.errstate(divide="ignore", invalid="ignore"):
        log_part = np.where(half > 0, 2.0 * half * half * np.log(2.0 * half), 0.0)
    return log_part + 0.75 * np.cos(phi) - 0.5


def ramp_remainder(theta: ArrayLike, theta_b: float) -> np.ndarray:
    """``Σ_{k>=2} sin kθ_b sin kθ/(k(k^2-1)) = [F(θ - θ_b) - F(θ + θ_b)]/2``, summed in closed form.

    The part of a ramp's coefficients (:func:`ramp_coefficients`) that falls as
    ``k^-3``, ``(2/π) cos θ_b sin kθ_b/(k(k^2-1))``, times ``sin kθ`` and summed:
    with the log-singular leading part (:func:`sie.series.log_kink`) it makes a
    ramp's pressure exact for any number of sine terms. The truncated sum
    converged only as ``n^-2`` near the kink, slowly for a sharp edge radius or
    a kink next to a contact end (issue 29).
    """
    theta = np.asarray(theta, dtype=float)
    return 0.5 * (_remainder_kernel(theta - theta_b) - _remainder_kernel(theta + theta_b))

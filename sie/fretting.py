"""The fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` from the SIE's stick zones (issue 11).

Every state of the cycle is a superposition of loading states (Masing's rule,
Ciavarella–Jäger): with ``q_load(x; u) = f [p(x) - p*_u(x)]`` of
:func:`sie.solve_partial_slip`,

    unloading:  q = q_load(Q_max) - 2 q_load((Q_max - Q)/2)
    reloading:  q = -q_load(Q_max) + 2 q_load((Q_max + Q)/2),

and the same for the relative slip and the rigid tangential displacement
``delta``. The zone not slipped since the last reversal is the loading stick
zone of ``(Q_max ∓ Q)/2``.

Everything follows from the loading stick zones ``[m* - h*, m* + h*]`` that
:func:`sie.normal.solve_ends` finds from the discretised load and consistency
equations (paper eqs. horizontal_equilibrium, integral_equation_2), also where
they end on the central segment:

* ``delta``: the log-potential of eq. (integral_equation_tangential) in the
  stick zone, ``F(u) = f [D(P) - D(P - u/f)]`` with the rigid approach
  ``D = <g>_w + alpha m - (A P/π) ln(h/2)`` of a bounded pressure on
  ``[m - h, m + h]`` (``<·>_w`` the mean under the Chebyshev weight, taken by
  Gauss–Legendre quadrature in ``θ`` between the joins);
* the energy per cycle, ``W = (4A/π) ∫_0^Q_max (2u - Q_max) ln(h/h*(u)) du``
  (``dD/dP = -(A/π) ln(h/2)``), by composite Gauss–Legendre quadrature with a
  panel end wherever a stick-zone end crosses a join;
* the slip on loading, ``f`` times the gap of the stick zone's normal problem,
  integrated term by term from the exact Chebyshev coefficients of the slope
  (:func:`sie.projection.slope_coefficients`).
"""
from __future__ import annotations

import math
import time
from typing import Any, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from threepart.halfplane.bulk import check_sigma_bulk, corrective_tilt, slip_dissipation
from threepart.errors import InputError, NoConvergenceError, StickSeparationError
from threepart.halfplane.legendre import gauss01
from threepart.problem.punch import Punch
from threepart.results import Diagnostics, MasingCycle, NormalResult
from threepart.problem.validate import SLIP_RATIO_LIMIT, check_states
from threepart.results.slip import check_shear

from .normal import DEFAULT_N, DEFAULT_SCHEME, check_scheme, solve_ends
from .projection import slope_coefficients
from .schemes import Plain, Projected
from .series import compiled
from .slip import (SieSlipResult, check_slip_direction, coulomb_violation, stick_zone,
                   stick_zone_by_continuation)

__all__ = ["SieFrettingResult", "fretting_cycle", "mean_profile", "approach", "stick_gap", "Zones",
           "loop_integral"]

#: Chebyshev terms of the gap series: a kink at θ_b truncated at N terms leaves ~1/(N^2 φ) of
#: the gap at x = m + h cosh φ, large next to a tiny slip zone: 5.6e-6 of the gap (3e-7 of the
#: bulk-stress friction work against the closed form) at 4096 terms, 4e-8 at 16384 (issue 29)
GAP_TERMS = 16384
#: Gauss–Legendre nodes per panel of the first energy quadrature; doubled until it settles
ENERGY_NODES = 16
MAX_ENERGY_NODES = 1024
ENERGY_RTOL = 1e-12


def loop_integral(zones: Any, Q_max: float, edges: Sequence[float], n: int) -> float:
    """``∫_0^Q_max (2u - Q_max) ln(h/h*(u)) du`` of the loop energy, composite Gauss–Legendre.

    ``edges`` cut ``[0, Q_max]`` into panels (a stick-zone end crossing a join);
    each is mapped by ``u = lo + L s^2 (3 - 2s)``, which removes the square-root
    behaviour at its ends, and integrated at ``n`` nodes. ``zones(u)[1]`` is the
    stick zone's half-width ``h*`` at ``u``, ``zones.h0`` the contact's.
    """
    s, w = gauss01(n)
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        u = lo + (hi - lo) * s * s * (3 - 2 * s)
        weights = 6 * (hi - lo) * s * (1 - s) * w
        h_star = np.array([zones(float(v))[1] for v in u])
        total += float(np.sum(weights * (2 * u - Q_max) * np.log(zones.h0 / h_star)))
    return total


def mean_profile(punch: Punch, m: float, h: float) -> float:
    """``<g>_w = (1/π) ∫_0^π g(m + h cos θ) dθ``, the profile of eq. (2) averaged with weight ``1/(π w)``.

    ``g`` is a quadratic between the joins, so each piece is integrated by a
    16-point Gauss–Legendre rule in ``θ`` (an entire integrand: exact to rounding).
    """
    cuts = [math.acos((j - m) / h) for j in sorted({punch.b, -punch.b}) if abs(j - m) < h]
    edges = np.array(sorted({0.0, math.pi, *cuts}))
    s, w = gauss01(16)
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        theta = lo + (hi - lo) * s
        total += (hi - lo) * float(np.sum(w * punch.profile(m + h * np.cos(theta))))
    return total / math.pi


def approach(punch: Punch, A: float, alpha: float, P: float, m: float, h: float) -> float:
    """Rigid approach ``D = g(x) + alpha x - (A/π) ∫ p ln|x - t| dt`` of a bounded pressure of load ``P``.

    The same for every ``x`` in ``[m - h, m + h]`` (eq. integral_equation); its
    mean under the Chebyshev weight, where ``ln|x - t|`` averages to ``ln(h/2)``,
    gives ``<g>_w + alpha m - (A P/π) ln(h/2)``. Up to a term linear in ``P``.
    """
    return mean_profile(punch, m, h) + alpha * m - A * P / math.pi * math.log(0.5 * h)


#: below this argument the cubic and quartic remainders are summed as Taylor series (to rounding)
SERIES_BELOW = 0.5
#: ``1/n!`` for ``n = 0..18``: the Taylor coefficients of :func:`_exp_remainder`
_INVERSE_FACTORIALS = np.array([1.0 / math.factorial(n) for n in range(19)])
#: past this argument ``expm1(-t)`` is -1 to the last bit (``e^-40 = 4e-18``, half an ulp of 1 is 5.6e-17)
_EXP_UNDERFLOW = 40.0


@compiled
def _exp_remainder(t: float) -> float:
    """``e^-t - 1 + t - t^2/2`` for ``t >= 0``, free of cancellation (``-t^3/6`` at small ``t``)."""
    if t < SERIES_BELOW:
        acc = 0.0
        for n in range(18, 2, -1):   # Σ_{n=3}^{18} (-t)^n/n! = (-t)^3 Σ (-t)^(n-3)/n!, by Horner
            acc = acc * (-t) + _INVERSE_FACTORIALS[n]
        return acc * math.pow(-t, 3.0)
    em1 = -1.0 if t > _EXP_UNDERFLOW else math.expm1(-t)
    return em1 + t - 0.5 * t * t


@compiled
def _gap_sums_at(G: np.ndarray, phi: np.ndarray, base: np.ndarray) -> np.ndarray:
    """:func:`_gap_sums` with ``base`` = :func:`_cosh_remainder`: ``D_j`` made and summed term by term.

    The terms ``G_k J_k`` are added with Neumaier's compensation (their signs alternate on the
    left end), as accurate as the matrix product this replaced.
    """
    out = np.empty(phi.size)
    for i in range(phi.size):
        ph = phi[i]
        d_lo, d_mid = 0.0, -_exp_remainder(ph) / 1.0                   # D_{k-1}, D_k
        total, carry = 0.0, 0.0
        for k in range(1, G.size):
            j = float(k + 1)
            d_hi = -_exp_remainder(j * ph) / j                          # D_{k+1}
            term = (base[i] - 0.5 * (d_lo - d_hi)) * G[k]               # G_k J_k
            t = total + term
            carry += (total - t) + term if abs(total) >= abs(term) else (term - t) + total
            total = t
            d_lo, d_mid = d_mid, d_hi
        out[i] = total + carry
    return out


def _cosh_remainder(phi: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``cosh φ - 1 - φ^2/2`` with ``u = cosh φ - 1`` given exactly (``φ^4/24`` at small ``φ``)."""
    small = phi < SERIES_BELOW
    p2 = np.where(small, phi * phi, 0.0)
    acc = np.zeros_like(p2)
    for n in range(9, 1, -1):      # Σ_{n=2}^{9} φ^(2n)/(2n)!
        acc = acc * p2 + 1.0 / math.factorial(2 * n)
    return np.where(small, acc * p2 * p2, u - 0.5 * phi * phi)


def _gap_sums(G: np.ndarray, phi: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``Σ_{k>=1} G_k J_k(φ)`` at each point, ``J_k = ∫_1^ξ (1 - ρ^k) dξ``, ``ξ = cosh φ``, ``ρ = e^-φ``.

    ``J_k = (cosh φ - 1 - φ^2/2) - [D_{k-1} - D_{k+1}]/2`` with ``D_j = -c(jφ)/j``,
    ``c(t) = e^-t - 1 + t - t^2/2`` (:func:`_exp_remainder`) and ``D_0 = 0``: the
    ``k φ^3/3`` that ``J_k`` starts with comes out without the cancellation of
    ``(ξ - 1) - ∫ ρ^k dξ``.

    Compiled (:func:`_gap_sums_at`): GAP_TERMS terms at a point in tens of microseconds.
    """
    return _gap_sums_at(np.ascontiguousarray(G, dtype=float), np.ascontiguousarray(phi, dtype=float),
                        np.ascontiguousarray(_cosh_remainder(phi, u), dtype=float))


def _tangent_deviation(punch: Punch, x: np.ndarray, x0: float) -> np.ndarray:
    """``∫_{x0}^x [g'(t) - g'(x0)] dt`` of the profile (eq. 2), each quadratic piece exactly.

    The tilt is linear and drops out. A ramp ``c (t - β)_+`` of the slope gives
    ``c (x - x0)^2/2`` with both on its right, ``c (x - β)^2/2`` from its left to
    its right, ``c (x0 - β)(x0 + β - 2x)/2`` the other way, and 0 on its left.
    """
    # the left ramp -κ1 (-b - t)_+ is -κ1 (t + b)_+ plus the slope κ1 (t + b), a curvature κ1
    out = 0.5 * (punch.kappa0 + punch.kappa1) * (x - x0) ** 2
    for beta, c in ((punch.b, punch.kappa2), (-punch.b, -punch.kappa1)):
        right = np.where(x >= beta, 0.5 * (x - x0) ** 2, 0.5 * (x0 - beta) * (x0 + beta - 2 * x))
        left = np.where(x > beta, 0.5 * (x - beta) ** 2, 0.0)
        out = out + c * (right if x0 >= beta else left)
    return out


def stick_gap(punch: Punch, alpha: float, m: float, h: float, x: ArrayLike,
              terms: int = GAP_TERMS) -> np.ndarray:
    """Gap outside ``[m - h, m + h]`` of the normal problem on it with tilt ``alpha``; 0 inside.

    The gap slope outside is ``v'(x) - Σ_{k>=1} G_k ρ^k`` (eq. integral_equation
    continued outside the contact, :func:`sie.normal._gap_slope_outside`); it is
    integrated term by term from each end ``e = m ± h`` (``ρ^k`` alternates in sign on
    the left, ``G^±_k = (±1)^k G_k``):

        gap = T(x) + (x - e) [v'(e) - Σ G^±_k] ± h Σ G^±_k J_k(φ),    |x - m| = h cosh φ,

    with ``T`` the profile's deviation from its tangent at ``e``
    (:func:`_tangent_deviation`) and ``J_k`` of :func:`_gap_sums`. Each term is of
    the gap's own size; ``v(x) - v(e) - h Σ G_k I_k``, as before issue 29, was a
    difference of O(1) terms and left 1e-7 of the gap next to a slip zone of 2e-5 W.
    """
    x = np.asarray(x, dtype=float)
    flat = np.ravel(x)
    G = slope_coefficients(punch, m, h, terms)[0]
    out = np.zeros_like(flat)
    for side, Gs in ((1.0, G), (-1.0, G * (-1.0) ** np.arange(len(G)))):
        end = m + side * h
        sel = side * (flat - end) > 0
        if not np.any(sel):
            continue
        xs = flat[sel]
        u = side * (xs - end) / h                       # cosh φ - 1, without rounding ξ first
        phi = np.log1p(u + np.sqrt(u * (u + 2.0)))
        # v'(e) - Σ G^±_k: zero for the full series at a solved end (consistency); kept as computed,
        # it carries the truncated tail of Σ G^±_k (dropping it put 1.6e-6 into the friction work)
        slope_gap = float(punch.slope(np.array([end]), alpha)[0]) - float(np.sum(Gs[1:]))
        out[sel] = (_tangent_deviation(punch, xs, end) + (xs - end) * slope_gap
                    + side * h * _gap_sums(Gs, phi, u))
    return out.reshape(x.shape)


@dataclass(frozen=True)
class SieFrettingResult(MasingCycle):
    """Fretting cycle from :func:`fretting_cycle`, with the discretisation of its stick zones.

    ``shear``, ``slip`` and ``slip_amplitude`` take any ``Q`` on a branch: the
    loading state of ``(Q_max ∓ Q)/2`` (with ``sigma_bulk`` in proportion) is
    solved anew by :func:`sie.slip.stick_zone`, with the discretisation of
    ``diagnostics`` (``n``, ``scheme``); the cycle checked the slip direction once.
    """

    def _load(self, u: float) -> SieSlipResult:
        """The loading state at ``u > 0``, bulk stress ``sigma_bulk u/Q_max``."""
        nrm = self.normal
        sch = check_scheme(self.diagnostics.scheme or DEFAULT_SCHEME, self.diagnostics.n or DEFAULT_N)
        sb = self.sigma_bulk * u / self.Q_max
        m, h, _, _ = stick_zone(nrm, u, self.f, sch, sb)
        stick, _ = sch.pressure(nrm.punch, nrm.A, m, h)
        return SieSlipResult(normal=nrm, Q=u, f=self.f, d=h, e=-m, method="sie",
                             diagnostics=Diagnostics(n=sch.n, scheme=sch.name), stick=stick,
                             sigma_bulk=sb)

    def _stick_load(self, u: float) -> tuple[float, float]:
        return self._load(u).stick_zone

    def _q_load(self, x: np.ndarray, u: float) -> np.ndarray:
        if u == 0:
            return np.zeros(x.shape)
        return self._load(u).shear(x)

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        nrm = self.normal
        if u == 0:
            return np.zeros(x.shape)
        sl = self._load(u)
        alpha = float(corrective_tilt(nrm.alpha, nrm.A, 1.0, self.f, sl.sigma_bulk))
        gap = stick_gap(nrm.punch, alpha, -sl.e, sl.d, x)
        return np.where((x > -nrm.a) & (x < nrm.c), self.f * gap, 0.0)


def _check_fretting(normal: NormalResult, Q_max: float, f: float, states: int
                    ) -> tuple[float, float, int]:
    Q_max, f = check_shear(normal, Q_max, f, "Q_max", "there is no fretting cycle",
                           limit=SLIP_RATIO_LIMIT)
    return Q_max, f, check_states(states)


class Zones:
    """Loading stick zones ``(m*, h*)`` of one normal solution, by :func:`sie.normal.solve_ends`."""

    def __init__(self, normal: NormalResult, f: float, sch: Plain | Projected,
                 bulk_tilt: float = 0.0) -> None:
        self.normal, self.f, self.sch = normal, f, sch
        self.bulk_tilt = bulk_tilt      # corrective tilt shift per unit u (bulk stress in phase)
        self.m0, self.h0 = 0.5 * (normal.c - normal.a), 0.5 * (normal.a + normal.c)
        self.solves = 0

    def __call__(self, u: float) -> tuple[float, float]:
        nrm = self.normal
        if u == 0:
            return self.m0, self.h0
        P_star = nrm.P - u / self.f
        alpha = nrm.alpha + self.bulk_tilt * u
        try:
            m, h, _, _, _ = solve_ends(nrm.punch, nrm.A, P_star, self.sch, alpha=alpha,
                                       m0=self.m0, h0=self.h0 * math.sqrt(P_star / nrm.P))
        except NoConvergenceError:
            m, h, _, _ = stick_zone_by_continuation(nrm, P_star, self.sch, alpha)
        self.solves += 1
        if m - h < -nrm.a * (1 + 1e-12) or m + h > nrm.c * (1 + 1e-12):
            raise InputError(f"stick zone [{m - h:.6g}, {m + h:.6g}] at u = {u:g} leaves the contact "
                             f"[{-nrm.a:.6g}, {nrm.c:.6g}]; is `normal` consistent with its punch?")
        return m, h

    def crossings(self, Q_max: float, top: tuple[float, float]) -> list[float]:
        """Forces in ``(0, Q_max)`` at which a stick-zone end crosses a join ``x = ±b``."""
        (m0, h0), (m1, h1) = (self.m0, self.h0), top
        out = []
        for j in sorted({-self.normal.punch.b, self.normal.punch.b}):
            for side, before, after in ((-1.0, m0 - h0, m1 - h1), (1.0, m0 + h0, m1 + h1)):
                if (before - j) * (after - j) < 0:
                    def end(u: float, side: float = side, j: float = j) -> float:
                        m, h = self(u)
                        return m + side * h - j
                    out.append(float(brentq(end, 0.0, Q_max, xtol=1e-14 * Q_max, rtol=1e-15)))
        return sorted(out)


def _energy(zones: Zones, Q_max: float, top: tuple[float, float]) -> tuple[float, int, list[float]]:
    """``W = (4A/π) ∫_0^Q_max (2u - Q_max) ln(h/h*(u)) du``, composite Gauss–Legendre doubled until it settles.

    The panels end where a stick-zone end crosses a join (a ``|u - u_c|^(3/2)``
    branch point of ``h*``); on each panel ``u = lo + (hi - lo) s^2 (3 - 2s)``
    makes such a branch point at either end, or at the limit just beyond
    ``Q_max``, smooth.
    """
    nrm = zones.normal
    cuts = zones.crossings(Q_max, top)
    edges = [0.0, *cuts, Q_max]
    # the stick zones' Newton tolerance (~1e-14 of h*) bounds the accuracy of ln(h/h*)
    floor = 1e-13 * nrm.A * Q_max**2
    n, previous = ENERGY_NODES, math.nan
    while n <= MAX_ENERGY_NODES:
        W = 4 * nrm.A / math.pi * loop_integral(zones, Q_max, edges, n)
        if abs(W - previous) <= ENERGY_RTOL * abs(W) + floor:
            return W, n, cuts
        previous, n = W, 2 * n
    raise NoConvergenceError(f"sie fretting energy: the quadrature did not settle with {MAX_ENERGY_NODES} "
                             f"nodes per panel (`Q_max` = {Q_max:g}); no result is returned")


def _check_coulomb(normal: NormalResult, f: float, tilt_rate: float, u: np.ndarray,
                   mh: np.ndarray) -> None:
    """Coulomb's law in every recorded loading state ``Q = u`` with stick zones ``mh`` (m, h)."""
    for v, (m, h) in zip(u[1:], mh[1:]):
        why = coulomb_violation(normal, normal.P - v / f, m, h, normal.alpha + tilt_rate * v)
        if why is not None:
            raise StickSeparationError(
                f"`Q`/(f P) = {v / (f * normal.P):.6g} of the cycle's loading branch: the stick zone "
                f"[{m - h:.6g}, {m + h:.6g}] on the concave centre R = {normal.punch.R:g} breaks "
                f"Coulomb's law: {why}")


def _cycle_energy(zones: Zones, normal: NormalResult, Q_max: float, f: float, tilt_rate: float,
                  sigma_bulk: float, mh1: tuple[float, float]) -> tuple[float, Any, list[float]]:
    """The cycle's energy, its quadrature nodes and the join crossings (none under a bulk stress:
    the friction work, :func:`threepart.halfplane.bulk.slip_dissipation`); ``mh1`` the stick zone at ``Q_max``."""
    if sigma_bulk == 0:
        return _energy(zones, Q_max, mh1)
    punch, (m1, h1) = normal.punch, mh1
    energy, nodes = slip_dissipation(
        normal.pressure, lambda x: stick_gap(punch, normal.alpha + tilt_rate * Q_max, m1, h1, x), f,
        normal.a, normal.c, (m1 - h1, m1 + h1), joins=(-punch.b, punch.b))
    return energy, nodes, []


def fretting_cycle(normal: NormalResult, Q_max: float, f: float, *, n: int | None = None,
                   scheme: str | None = None, states: int = 21,
                   sigma_bulk: float = 0.0) -> SieFrettingResult:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` at the normal solution's ``P``, ``s``, ``alpha``.

    Parameters
    ----------
    normal
        A normal solution (any method): its punch, ``A``, ``a``, ``c``, ``alpha``
        and ``P`` are used.
    Q_max
        Amplitude of the shear force, ``0 < Q_max < f P``.
    f
        Coefficient of friction, > 0.
    n, scheme
        Discretisation of the stick zones, as :func:`sie.solve_partial_slip`.
    states
        Recorded states per branch, evenly spaced in ``Q``, both ends included (>= 2).
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q_max`` (tension positive), in
        phase with ``Q``; Masing's superposition carries it (docs/BULK_STRESS.md).

    Returns
    -------
    SieFrettingResult
        ``method="sie"``; ``stick`` is the zone not slipped since the last
        reversal (the whole contact at ``Q = 0`` and at each reversal); stick
        zones ending on the central segment are solved as any other. ``diagnostics`` hold ``n``,
        ``scheme``, ``steps`` (the recorded states per branch) and the time;
        ``info`` holds ``energy_nodes`` (per panel), ``crossings`` (forces at
        which a stick-zone end crosses a join) and ``solves``.

    Raises
    ------
    TypeError
        ``normal`` not a NormalResult, ``states`` not an integer.
    ValueError
        ``Q_max`` or ``f`` not finite and > 0, ``states`` outside ``[2, MAX_STATES]``
        (``FullSlidingError`` for ``Q_max >= f P``).
    StickSeparationError
        A recorded stick zone on a concave centre breaks Coulomb's law.
    SlipReversalError
        ``sigma_bulk`` reverses the slip at one end on the loading branch
        (:func:`sie.slip.check_slip_direction`), and so on every branch.
    NoConvergenceError
        A stick zone or the energy quadrature did not converge.

    Notes
    -----
    Under a bulk stress ``energy`` is the friction work
    (:func:`threepart.halfplane.bulk.slip_dissipation`): the bulk stress works on the
    substrate too, so it is no longer the ``Q``–``delta`` loop's area.
    """
    Q_max, f, states = _check_fretting(normal, Q_max, f, states)
    n = (normal.diagnostics.n or DEFAULT_N) if n is None else n
    scheme = (normal.diagnostics.scheme or DEFAULT_SCHEME) if scheme is None else scheme
    sch = check_scheme(scheme, n)
    sigma_bulk = check_sigma_bulk(sigma_bulk, normal, Q_max)
    t0 = time.perf_counter()
    tilt_rate = float(corrective_tilt(0.0, normal.A, 1.0, f, sigma_bulk)) / Q_max
    zones = Zones(normal, f, sch, tilt_rate)
    u = np.linspace(0.0, Q_max, states)
    mh = np.array([zones(float(v)) for v in u])
    check_slip_direction(normal, Q_max, f, sigma_bulk, sch, (float(mh[-1, 0]), float(mh[-1, 1])))
    _check_coulomb(normal, f, tilt_rate, u, mh)
    punch, A, alpha = normal.punch, normal.A, normal.alpha
    D0 = approach(punch, A, alpha, normal.P, zones.m0, zones.h0)
    F = np.array([f * (D0 - approach(punch, A, alpha + tilt_rate * v, normal.P - v / f, m, h))
                  if v > 0 else 0.0 for v, (m, h) in zip(u, mh)])
    energy, nodes, cuts = _cycle_energy(zones, normal, Q_max, f, tilt_rate, sigma_bulk,
                                        (float(mh[-1, 0]), float(mh[-1, 1])))
    stick = np.column_stack([mh[:, 0] - mh[:, 1], mh[:, 0] + mh[:, 1]])
    info = {"energy_nodes": nodes, "crossings": cuts, "solves": zones.solves}
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, steps=states,
                              timings={"total": time.perf_counter() - t0})
    return SieFrettingResult.from_loading(normal, Q_max, f, u, stick, F, energy=energy, method="sie",
                                          diagnostics=diagnostics, info=info, sigma_bulk=sigma_bulk)

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

import functools
import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.special
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from threepart.bulk import check_sigma_bulk, corrective_tilt, slip_dissipation
from threepart.errors import NoConvergenceError, StickSeparationError
from threepart.punch import Punch
from threepart.results import Diagnostics, MasingCycle, NormalResult
from threepart.validate import SLIP_RATIO_LIMIT, check_shear, check_states

from .normal import DEFAULT_N, DEFAULT_SCHEME, check_scheme, solve_ends
from .projection import slope_coefficients
from .schemes import Plain, Projected
from .slip import (SieSlipResult, check_slip_direction, coulomb_violation, stick_zone,
                   stick_zone_by_continuation)

__all__ = ["SieFrettingResult", "fretting_cycle", "mean_profile", "approach", "stick_gap"]

#: Chebyshev terms of the gap series: a kink at θ_b truncated at N terms leaves ~1/(N^2 φ) of
#: the gap at x = m + h cosh φ, large next to a tiny slip zone: 5.6e-6 of the gap (3e-7 of the
#: bulk-stress friction work against the closed form) at 4096 terms, 1e-7 (5e-10) at 16384 (issue 29)
GAP_TERMS = 16384
#: Gauss–Legendre nodes per panel of the first energy quadrature; doubled until it settles
ENERGY_NODES = 16
MAX_ENERGY_NODES = 1024
ENERGY_RTOL = 1e-12


@functools.lru_cache(maxsize=16)
def _gauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on ``[0, 1]``."""
    t, w = scipy.special.roots_legendre(n)     # O(n); numpy's leggauss solves an n x n eigenproblem
    return 0.5 * (t + 1), 0.5 * w


def mean_profile(punch: Punch, m: float, h: float) -> float:
    """``<g>_w = (1/π) ∫_0^π g(m + h cos θ) dθ``, the profile of eq. (2) averaged with weight ``1/(π w)``.

    ``g`` is a quadratic between the joins, so each piece is integrated by a
    16-point Gauss–Legendre rule in ``θ`` (an entire integrand: exact to rounding).
    """
    cuts = [math.acos((j - m) / h) for j in sorted({punch.b, -punch.b}) if abs(j - m) < h]
    edges = np.array(sorted({0.0, math.pi, *cuts}))
    s, w = _gauss(16)
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


#: points per block of the power matrix ``ρ_i^j`` (a block of GAP_TERMS columns: 64 MB at most)
POWER_BLOCK = 512


def _power_sums(rho: np.ndarray, coef: np.ndarray) -> np.ndarray:
    """``Σ_j coef[j, q] ρ_i^j`` for every point ``i`` and column ``q``, as ``(len(rho), q)``.

    A matrix product over blocks of points, ``ρ^j = exp(j ln ρ)``; numpy's
    ``polyval`` is a Python loop over the coefficients, 2 s a cycle at 16384 terms.
    """
    j = np.arange(coef.shape[0], dtype=float)
    log_rho = np.log(rho)
    out = np.empty((len(rho), coef.shape[1]))
    for i in range(0, len(rho), POWER_BLOCK):
        out[i:i + POWER_BLOCK] = np.exp(np.outer(log_rho[i:i + POWER_BLOCK], j)) @ coef
    return out


def _integrated_powers(G: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """``Σ_{k>=1} G_k I_k(ρ)`` with ``I_k = ∫_1^ξ ρ^k dξ``, ``ρ = ξ - sqrt(ξ^2 - 1)`` (``0 < ρ <= 1``).

    ``G`` is ``(K,)`` or ``(K, q)`` (several coefficient sets at once; the result is then
    ``(len(rho), q)``). With ``ξ = cosh φ``, ``ρ = e^-φ``: ``I_1 = [-ln ρ - (1 - ρ^2)/2]/2`` and
    ``I_k = [(1 - ρ^(k-1))/(k-1) - (1 - ρ^(k+1))/(k+1)]/2`` for ``k >= 2``.
    """
    G2 = G.reshape(len(G), -1)
    rho = np.ravel(rho)
    k = np.arange(2, len(G2), dtype=float)[:, None]
    Gk = G2[2:]
    const = np.sum(Gk * (1 / (k - 1) - 1 / (k + 1)), axis=0)
    zero = np.zeros((1, G2.shape[1]))
    low = _power_sums(rho, np.concatenate([zero, Gk / (k - 1)]))                # Σ G_k ρ^(k-1)/(k-1)
    high = (rho * rho)[:, None] * _power_sums(rho, np.concatenate([zero, Gk / (k + 1)]))
    first = G2[1] * 0.5 * (-np.log(rho) - 0.5 * (1 - rho * rho))[:, None]
    out = first + 0.5 * (const - low + high)
    return out if G.ndim == 2 else out[:, 0]


def stick_gap(punch: Punch, alpha: float, m: float, h: float, x: ArrayLike,
              terms: int = GAP_TERMS) -> np.ndarray:
    """Gap outside ``[m - h, m + h]`` of the normal problem on it with tilt ``alpha``; 0 inside.

    The gap slope outside is ``v'(x) - Σ_{k>=1} G_k ρ^k`` (eq. integral_equation
    continued outside the contact, :func:`sie.normal._gap_slope_outside`); it is
    integrated term by term from each end. ``ρ^k`` alternates in sign on the left.
    """
    x = np.asarray(x, dtype=float)
    G = slope_coefficients(punch, m, h, terms)[0]
    xi = (x - m) / h
    a = np.maximum(np.abs(xi), 1.0)
    rho = 1.0 / (a + np.sqrt(a * a - 1.0))
    sign = (-1.0) ** np.arange(len(G))
    v = punch.profile(x, alpha)
    both = _integrated_powers(np.column_stack([G, G * sign]), rho).reshape(x.shape + (2,))
    right = v - float(punch.profile(m + h, alpha)) - h * both[..., 0]
    left = v - float(punch.profile(m - h, alpha)) + h * both[..., 1]
    return np.where(xi > 1.0, right, np.where(xi < -1.0, left, 0.0))


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


class _Zones:
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
            raise ValueError(f"stick zone [{m - h:.6g}, {m + h:.6g}] at u = {u:g} leaves the contact "
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


def _energy(zones: _Zones, Q_max: float, top: tuple[float, float]) -> tuple[float, int, list[float]]:
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
        s, w = _gauss(n)
        total = 0.0
        for lo, hi in zip(edges[:-1], edges[1:]):
            u = lo + (hi - lo) * s * s * (3 - 2 * s)
            weights = 6 * (hi - lo) * s * (1 - s) * w
            h_star = np.array([zones(float(v))[1] for v in u])
            total += float(np.sum(weights * (2 * u - Q_max) * np.log(zones.h0 / h_star)))
        W = 4 * nrm.A / math.pi * total
        if abs(W - previous) <= ENERGY_RTOL * abs(W) + floor:
            return W, n, cuts
        previous, n = W, 2 * n
    raise NoConvergenceError(f"sie fretting energy: the quadrature did not settle with {MAX_ENERGY_NODES} "
                             f"nodes per panel (`Q_max` = {Q_max:g}); no result is returned")


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
    (:func:`threepart.bulk.slip_dissipation`): the bulk stress works on the
    substrate too, so it is no longer the ``Q``–``delta`` loop's area.
    """
    Q_max, f, states = _check_fretting(normal, Q_max, f, states)
    n = (normal.diagnostics.n or DEFAULT_N) if n is None else n
    scheme = (normal.diagnostics.scheme or DEFAULT_SCHEME) if scheme is None else scheme
    sch = check_scheme(scheme, n)
    sigma_bulk = check_sigma_bulk(sigma_bulk, normal, Q_max)
    t0 = time.perf_counter()
    tilt_rate = float(corrective_tilt(0.0, normal.A, 1.0, f, sigma_bulk)) / Q_max
    zones = _Zones(normal, f, sch, tilt_rate)
    u = np.linspace(0.0, Q_max, states)
    mh = np.array([zones(float(v)) for v in u])
    check_slip_direction(normal, Q_max, f, sigma_bulk, sch, (float(mh[-1, 0]), float(mh[-1, 1])))
    for v, (m, h) in zip(u[1:], mh[1:]):    # Coulomb's law in every recorded loading state
        why = coulomb_violation(normal, normal.P - v / f, m, h, normal.alpha + tilt_rate * v)
        if why is not None:
            raise StickSeparationError(
                f"`Q`/(f P) = {v / (f * normal.P):.6g} of the cycle's loading branch: the stick zone "
                f"[{m - h:.6g}, {m + h:.6g}] on the concave centre R = {normal.punch.R:g} breaks "
                f"Coulomb's law: {why}")
    punch, A, alpha = normal.punch, normal.A, normal.alpha
    D0 = approach(punch, A, alpha, normal.P, zones.m0, zones.h0)
    F = np.array([f * (D0 - approach(punch, A, alpha + tilt_rate * v, normal.P - v / f, m, h))
                  if v > 0 else 0.0 for v, (m, h) in zip(u, mh)])
    if sigma_bulk == 0:
        energy, nodes, cuts = _energy(zones, Q_max, (float(mh[-1, 0]), float(mh[-1, 1])))
    else:
        m1, h1 = float(mh[-1, 0]), float(mh[-1, 1])
        energy, nodes = slip_dissipation(
            normal.pressure, lambda x: stick_gap(punch, alpha + tilt_rate * Q_max, m1, h1, x), f,
            normal.a, normal.c, (m1 - h1, m1 + h1), joins=(-punch.b, punch.b))
        cuts = []
    stick = np.column_stack([mh[:, 0] - mh[:, 1], mh[:, 0] + mh[:, 1]])
    info = {"energy_nodes": nodes, "crossings": cuts, "solves": zones.solves}
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, steps=states,
                              timings={"total": time.perf_counter() - t0})
    return SieFrettingResult.from_loading(normal, Q_max, f, u, stick, F, energy=energy, method="sie",
                                          diagnostics=diagnostics, info=info, sigma_bulk=sigma_bulk)

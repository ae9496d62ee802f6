"""The periodic steady state of in-phase loading between two states, from the SIE's stick zones (issue 31).

The same superposition as the closed form (docs/STEADY_STATE.md): from the
start ``i`` of a half-cycle to the state at the fraction ``lam`` of it the shear
changes by ``Δq = sign(ΔQ) f [p_i + p_lam - 2 p*_lam]`` (eq. S4), ``p*_lam`` the
bounded pressure of the same punch on the stick zone of load
``P* = [f (P_i + P_lam) - |ΔQ|]/(2f)`` (eq. S6) at the tilt
``alpha* = (alpha_i + alpha_lam)/2 - sign(ΔQ) A Δsigma_bulk/(8 f)`` (eq. S5).
Here every contact and every stick zone comes from the discretised load and
consistency equations (:func:`sie.normal.solve_ends`), so the stick zone may end
on the central segment, as in :mod:`sie.slip`. The slip direction is checked at
:data:`PATH_STATES` fractions of each half-cycle, and the energy is the
friction work of :func:`threepart.halfplane.steady.half_cycle_work` on the SIE's
pressures, contacts and stick zones.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from threepart.errors import (CycleSlipReversalError, NoConvergenceError,
                              StickSeparationError)
from threepart.problem.punch import Punch
from threepart.results.cycles import SteadyStateResult
from threepart.results import Diagnostics
from threepart.halfplane.steady import (LoadState, Path, check_cycle_states, common_contact, corrective_load,
                                        corrective_tilt_cycle, cycle_margin, half_cycle_work, ramp,
                                        shakes_down, tilt_rate)
from threepart.problem.validate import check_punch

from .fretting import stick_gap
from .normal import DEFAULT_N, DEFAULT_SCHEME, SieNormalResult, check_scheme, solve_ends, solve_normal
from .schemes import Plain, Projected
from .series import ChebyshevPressure
from .slip import PATH_STATES

__all__ = ["SieSteadyResult", "steady_state", "WORK_RTOL"]

#: the SIE's energy quadrature settles to this: its pressure series (n = 1024) leaves ~1e-9 of W
#: between two Gauss rules (the closed form's settles to 1e-14); the energy agrees with the closed
#: form's to ~1e-12 all the same
WORK_RTOL = 1e-8


@dataclass(frozen=True)
class SieSteadyResult(SteadyStateResult):
    """Steady state from :func:`steady_state`; ``stick`` is the corrective pressure ``p*``."""

    method: str = "sie"
    stick: ChebyshevPressure | None = field(default=None, repr=False, compare=False)

    def corrective(self, x: ArrayLike) -> np.ndarray:
        assert self.stick is not None
        return self.stick(x)

    def gap(self, x: ArrayLike, which: str | int) -> np.ndarray:
        punch = self.normals[0].punch
        if which == "stick":
            return stick_gap(punch, self.info["alpha_star"], -self.e, self.d, x)
        n = self.normals[self._state(which)]
        return stick_gap(punch, n.alpha, 0.5 * (n.c - n.a), 0.5 * (n.a + n.c), x)


class _SieCycle:
    """Normals and stick zones of both half-cycles at fractions ``lam``, each solved once (memoised)."""

    def __init__(self, punch: Punch, A: float, f: float, states: tuple[LoadState, LoadState],
                 ends: tuple[SieNormalResult, SieNormalResult], sch: Plain | Projected) -> None:
        self.punch, self.A, self.f, self.states, self.ends, self.sch = punch, A, f, states, ends, sch
        (P0, s0, Q0, _), (P1, s1, Q1, _) = states
        self.sign = (1.0 if Q1 >= Q0 else -1.0, 1.0 if Q0 > Q1 else -1.0)
        self.dP_star = tuple((f * (e[0] - b[0]) - abs(e[2] - b[2])) / (2 * f)
                             for b, e in (states, states[::-1]))
        self._normal: dict[float, tuple[float, float, float]] = {}
        self._zone: dict[tuple[int, float], tuple[float, float]] = {}
        self._density: dict[tuple[float, float], ChebyshevPressure] = {}
        self.solves = 0

    def normal(self, t: float) -> tuple[float, float, float]:
        """``(m, h, alpha)`` of the contact at the fraction ``t`` of ``0 -> 1``."""
        if t in (0.0, 1.0):
            n = self.ends[int(t)]
            return 0.5 * (n.c - n.a), 0.5 * (n.a + n.c), n.alpha
        if t not in self._normal:
            P, s, _, _ = (float(v) for v in ramp(self.states[0], self.states[1], t))
            e0, e1 = self.ends
            m0 = (1 - t) * 0.5 * (e0.c - e0.a) + t * 0.5 * (e1.c - e1.a)
            h0 = (1 - t) * 0.5 * (e0.a + e0.c) + t * 0.5 * (e1.a + e1.c)
            m, h, G, _, _ = solve_ends(self.punch, self.A, P, self.sch, s=s, m0=m0, h0=h0)
            self.solves += 1
            self._normal[t] = (m, h, -float(G[0]))
        return self._normal[t]

    def zone(self, j: int, lam: float) -> tuple[float, float]:
        """``(m*, h*)`` of the stick zone at the fraction ``lam`` of the half-cycle ``j``."""
        key = (j, lam)
        if lam == 0:         # the stick zone starts as the whole contact (eqs. S5, S6 at lam = 0)
            m, h, _ = self.normal(float(j))
            return m, h
        if key not in self._zone:
            start, end = (self.states, self.states[::-1])[j]
            _, _, Q, sigma = (float(v) for v in ramp(start, end, lam))
            m, h, alpha = self.normal(lam if j == 0 else 1.0 - lam)
            P = float(ramp(start, end, lam)[0])
            P_star = float(corrective_load(start[0], P, Q - start[2], self.f))
            alpha_star = float(corrective_tilt_cycle(self.ends[j].alpha, alpha, self.A, self.sign[j],
                                                     sigma - start[3], self.f))
            self._zone[key] = _stick_ends(self.punch, self.A, self.sch, P_star, alpha_star, P, m, h)
            self.solves += 1
        return self._zone[key]

    def density(self, m: float, h: float) -> ChebyshevPressure:
        """The bounded pressure on ``[m - h, m + h]`` (memoised)."""
        if (m, h) not in self._density:
            self._density[m, h] = self.sch.pressure(self.punch, self.A, m, h)[0]
        return self._density[m, h]

    def half(self, j: int, lam: np.ndarray) -> dict[str, Any]:
        """Contact ends, stick-zone ends and rates of the half-cycle ``j`` at the fractions ``lam``."""
        start, end = (self.states, self.states[::-1])[j]
        rows = [self.normal(float(t) if j == 0 else 1.0 - float(t)) for t in lam]
        zones = [self.zone(j, float(t)) for t in lam]
        m, h, alpha = (np.array(v) for v in zip(*rows))
        P, s, _, _ = ramp(start, end, lam)
        dP, ds = end[0] - start[0], end[1] - start[1]
        rate = tilt_rate(self.A, h - m, h + m, dP, dP * s + P * ds)
        zm, zh = (np.array(v) for v in zip(*zones))
        return {"a": h - m, "c": h + m, "m": m, "h": h, "left": zm - zh, "right": zm + zh,
                "dP_star": self.dP_star[j],
                "dalpha_star": 0.5 * rate - self.sign[j] * self.A * (end[3] - start[3]) / (8 * self.f)}

    def path(self, j: int) -> Path:
        """The pieces :func:`threepart.halfplane.steady.half_cycle_work` integrates, on the half-cycle ``j``."""
        def pieces(lam: np.ndarray) -> Any:
            z = self.half(j, lam)
            dens = [self.density(float(mm), float(hh)) for mm, hh in zip(z["m"], z["h"])]

            def pressure(x: np.ndarray) -> np.ndarray:
                return np.array([d(row) for d, row in zip(dens, x)])
            return pressure, z["a"], z["c"], z["left"], z["right"], z["dP_star"], z["dalpha_star"]
        return pieces


def _stick_ends(punch: Punch, A: float, sch: Plain | Projected, P_star: float, alpha_star: float,
                P: float, m: float, h: float) -> tuple[float, float]:
    """``(m*, h*)`` of the bounded pressure of load ``P_star`` at the tilt ``alpha_star``.

    Newton from the contact ``m ± h`` (load ``P``) scaled by ``sqrt(P*/P)``; where it
    fails, a continuation in the load from the contact itself, the tilt in proportion.
    """
    try:
        ms, hs, _, _, _ = solve_ends(punch, A, P_star, sch, alpha=alpha_star, m0=m,
                                     h0=h * math.sqrt(P_star / P))
        return ms, hs
    except NoConvergenceError:
        pass
    G0 = float(sch.moments(punch, m, h)[0][0])
    alpha0, steps = -G0, 32
    for k in range(1, steps + 1):
        t = k / steps
        load = P * (P_star / P) ** t
        m, h, _, _, _ = solve_ends(punch, A, load, sch, alpha=alpha0 + t * (alpha_star - alpha0), m0=m, h0=h)
    return m, h


def _crossings(cycle: _SieCycle, j: int) -> tuple[float, ...]:
    """Fractions of the half-cycle ``j`` at which a stick-zone or contact end crosses a join ``±b``.

    Each end moves monotonically on the half-cycle (eq. S10 holds), so a change
    of side between ``lam = 0`` and 1 has one root, found by Brent's method.
    """
    b = cycle.punch.b
    if b == 0:
        return ()

    def ends(lam: float) -> np.ndarray:
        m, h, _ = cycle.normal(lam if j == 0 else 1.0 - lam)
        zm, zh = cycle.zone(j, lam) if lam > 0 else (m, h)
        return np.array([zm - zh, zm + zh, m - h, m + h])

    out = []
    e0, e1 = ends(0.0), ends(1.0)
    for k in range(4):
        for join in (-b, b):
            if (e0[k] - join) * (e1[k] - join) < 0:
                out.append(brentq(lambda t: float(ends(t)[k]) - join, 0.0, 1.0, xtol=1e-14, rtol=1e-13))
    return tuple(sorted(out))


def _classify(cycle: _SieCycle) -> tuple[float, float, bool]:
    """``(m*, h*, shakedown)`` of the permanent stick zone (eq. S12), or :class:`OneSidedSlipError`
    (:class:`DisjointContactsError` where the end contacts do not overlap)."""
    lo, hi = common_contact(((-cycle.ends[0].a, cycle.ends[0].c), (-cycle.ends[1].a, cycle.ends[1].c)))
    m, h = cycle.zone(0, 1.0)
    left, right = m - h, m + h
    if shakes_down(left, right, lo, hi):
        return 0.5 * (lo + hi), 0.5 * (hi - lo), True
    return m, h, False


def _check_direction(cycle: _SieCycle) -> float:
    """Least slip-direction margin (eq. S10) at :data:`PATH_STATES` fractions of each half-cycle (0 and 1 included).

    Raises
    ------
    CycleSlipReversalError
        Where it is negative, or a stick zone leaves its contact.
    """
    lam = np.linspace(0.0, 1.0, PATH_STATES)
    least = math.inf
    for j in (0, 1):
        z = cycle.half(j, lam)
        gl, gr = cycle_margin(z["left"], z["right"], z["a"], z["c"], cycle.A, cycle.f, z["dP_star"],
                              z["dalpha_star"])
        tol = 1e-12 * (z["a"] + z["c"])
        outside = (z["left"] < -z["a"] - tol) | (z["right"] > z["c"] + tol)
        g = np.minimum(gl, gr)
        k = int(np.argmin(g))
        scale = abs(cycle.f * z["dP_star"]) / math.pi
        if g[k] < -1e-9 * scale or outside.any():
            k = int(np.argmax(outside)) if outside.any() else k
            end = "left" if gl[k] <= gr[k] else "right"
            raise CycleSlipReversalError(
                f"in the cycle between {cycle.states[0]} and {cycle.states[1]} the {end} end of the "
                f"contact slips backwards at {lam[k]:.4g} of the way from state {j} to state {1 - j}: "
                "the change of P, s or sigma_bulk outpaces the shear's; the SIE models only slip in "
                "the sense of ΔQ")
        least = min(least, float(g.min()))
    return least


def _check_coulomb(cycle: _SieCycle, m: float, h: float) -> None:
    """On a concave centre: ``0 <= p* <= (p_0 + p_1)/2`` at 1599 points clustered at the stick zone's ends."""
    punch = cycle.punch
    if punch.kappa0 >= 0 or punch.b == 0:
        return
    x = m + h * np.cos(np.linspace(0, np.pi, 1601)[1:-1])
    p_star = cycle.density(m, h)(x)
    mean = 0.5 * (cycle.ends[0].pressure(x) + cycle.ends[1].pressure(x))
    tol = 1e-9 * min(n.P / (n.a + n.c) for n in cycle.ends)
    for v, what in ((p_star, "p* < 0"), (mean - p_star, "p* > (p_0 + p_1)/2")):
        i = int(np.argmin(v))
        if v[i] < -tol:
            raise StickSeparationError(
                f"the permanent stick zone [{m - h:.6g}, {m + h:.6g}] on the concave centre R = "
                f"{punch.R:g} breaks Coulomb's law: {what} at x = {x[i]:.6g}; the true stick zone is "
                "not this single interval")


def steady_state(punch: Punch, states: Any, f: float, *, A: float, n: int | None = None,
                 scheme: str | None = None) -> SieSteadyResult:
    """The periodic steady state of the cycle between ``states[0]`` and ``states[1]``, by the SIE.

    Parameters
    ----------
    punch, states, f, A
        As :func:`threepart.closedform.steady_state`: the two ends ``(P, s, Q, sigma_bulk)``
        of the cycle, the loads linear in between, ``|Q| < f P`` at both.
    n, scheme
        Discretisation (defaults ``sie.normal.DEFAULT_N`` and ``DEFAULT_SCHEME``,
        the projected scheme), as :func:`sie.solve_normal`.

    Returns
    -------
    SieSteadyResult
        ``d``, ``e``, ``energy``, ``shakedown``, ``normals`` (SIE normal results);
        ``diagnostics`` hold ``n``, ``scheme``, the Newton solves and the time;
        ``info`` holds ``P_star``, ``alpha_star``, ``margin`` and ``energy_nodes``.

    Raises
    ------
    ValueError, TypeError
        For invalid input; ``FullSlidingError`` for ``|Q| >= f P`` at either state.
    OneSidedSlipError
        The permanent stick zone would reach one edge of the smaller contact only.
    CycleSlipReversalError
        A point would slip backwards on a half-cycle (eq. S10).
    StickSeparationError, SeparationError
        On a concave centre, as the normal and partial-slip SIE solvers.
    NoConvergenceError
        If a Newton iteration or the energy quadrature fails.
    """
    check_punch(punch)
    (st0, st1), f = check_cycle_states(states, f)
    n = DEFAULT_N if n is None else n
    sch = check_scheme(DEFAULT_SCHEME if scheme is None else scheme, n)
    t0 = time.perf_counter()
    ends = tuple(solve_normal(punch, P, s, A=A, n=sch.n, scheme=sch.name) for P, s, _, _ in (st0, st1))
    A = ends[0].A
    cycle = _SieCycle(punch, A, f, (st0, st1), (ends[0], ends[1]), sch)
    m, h, shakedown = _classify(cycle)
    sign = cycle.sign[0]
    alpha_star = float(corrective_tilt_cycle(ends[0].alpha, ends[1].alpha, A, sign, st1[3] - st0[3], f))
    info: dict[str, Any] = {"P_star": (f * (st0[0] + st1[0]) - abs(st1[2] - st0[2])) / (2 * f),
                            "alpha_star": alpha_star, "energy_nodes": 0}
    energy, stick = 0.0, None
    if not shakedown:
        _check_coulomb(cycle, m, h)
        info["margin"] = _check_direction(cycle)
        works = [half_cycle_work(cycle.path(j), A, f, punch.b, rtol=WORK_RTOL, breaks=_crossings(cycle, j))
                 for j in (0, 1)]
        energy, info["energy_nodes"] = works[0][0] + works[1][0], max(works[0][1], works[1][1])
        stick = cycle.density(m, h)
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, iterations=cycle.solves,
                              timings={"total": time.perf_counter() - t0})
    return SieSteadyResult(normals=(ends[0], ends[1]), states=(st0, st1), f=f, d=h, e=-m, energy=energy,
                           shakedown=shakedown, diagnostics=diagnostics, info=info, stick=stick)

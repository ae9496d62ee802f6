"""The periodic steady state of in-phase loading between two states, in closed form (issue 31).

Two states ``(P, s, Q, sigma_bulk)`` are the ends of the cycle; the loads move
linearly between them, all four in phase. With elastically similar bodies the
shear of the steady state changes, from the start ``i`` of a half-cycle to the
state at the fraction ``lam`` of it, by

    Δq = sign(ΔQ) f [p_i + p_lam - 2 p*_lam]                              (S4)

(docs/STEADY_STATE.md), where ``p*_lam`` is the bounded normal pressure of the
same punch on the stick zone, of load ``P* = [f (P_i + P_lam) - |ΔQ|]/(2f)``
(eq. S6, horizontal equilibrium) at the tilt
``alpha* = (alpha_i + alpha_lam)/2 - sign(ΔQ) A Δsigma_bulk/(8 f)`` (eq. S5, the
stick condition of the change). The permanent stick zone is that of
``lam = 1``. Every contact and stick zone on the path is solved vectorised:
Newton's method on the closed forms of eqs. (equilibrium_condition_1,
equilibrium_condition_2, consistency_condition), warm-started between the
known states, and the bracketed roots of :mod:`closedform.newton` (with a
target tilt, as the partial-slip stick zone) where it does not settle. The
energy per cycle is the friction work of the two half-cycles (eq. S11,
:func:`threepart.halfplane.steady.half_cycle_work`).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
from numpy.typing import ArrayLike

from threepart.errors import (CycleSlipReversalError, InputError, LiftOffError,
                              StickSeparationError, StickZoneError)
from threepart.problem.punch import Punch
from threepart.results.cycles import SteadyStateResult
from threepart.results import Diagnostics
from threepart.halfplane.steady import (WORK_NODES, LoadState, Path, check_cycle_states, common_contact,
                                        corrective_load, corrective_tilt_cycle, cycle_margin,
                                        half_cycle_work, lam_rule, ramp, shakes_down, tilt_rate)
from threepart.problem.validate import check_punch

from . import formulas
from .fretting import stick_gap
from .newton import State, ray_state, solve_phi
from .normal import NormalSolution, check_separation, solve_state, solve_normal_batch
from .slip import least_on, stick_zone_leaves

__all__ = ["SteadySolution", "steady_state", "MARGIN_GRID"]

#: fractions of each half-cycle at which the slip direction is screened (a grid; Brent refines)
MARGIN_GRID = 65


@dataclass(frozen=True)
class SteadySolution(SteadyStateResult):
    """Closed-form steady state from :func:`steady_state`."""

    method: str = "closedform"

    def corrective(self, x: ArrayLike) -> np.ndarray:
        n = self.normals[0]
        return formulas.pressure(n.punch, self.d + self.e, self.d - self.e, n.A, x)

    def gap(self, x: ArrayLike, which: str | int) -> np.ndarray:
        punch = self.normals[0].punch
        if which == "stick":
            return stick_gap(punch, self.d + self.e, self.d - self.e, x)
        n = self.normals[self._state(which)]
        return stick_gap(punch, n.a, n.c, x)


#: Newton steps of the warm-started ends before the bracketed roots take over
NEWTON_STEPS = 12


def _newton_ends(punch: Punch, AP: np.ndarray, target: str, value: np.ndarray, h: np.ndarray,
                 m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ends ``(a, c)`` of the bounded contact of load ``AP/A`` with ``target`` (``"tilt"`` or ``"moment"``) = ``value``.

    Newton's method in ``(h, m)`` on eq. (equilibrium_condition_1) and eq.
    (consistency_condition) or (equilibrium_condition_2), with the exact
    derivatives of :class:`closedform.newton.State`, from a close start ``(h, m)``
    (the states of a cycle lie between known ones). Returns a flag of the
    elements that converged with both ends on the outer segments; the others go
    to :func:`closedform.newton.solve_phi` (also the judge of an end on the centre).
    """
    b = punch.b
    h, m = h.astype(float), m.astype(float)
    ok = np.zeros(h.shape, dtype=bool)
    for _ in range(NEWTON_STEPS):
        a, c = h - m, h + m
        inside = (a > b) & (c > b)
        st = State(punch, np.sqrt(np.where(inside, a - b, 1.0)), np.sqrt(np.where(inside, c - b, 1.0)), np)
        g, g_h, g_m = (st.alpha, st.alpha_h, st.alpha_m) if target == "tilt" else (st.T, st.T_h, st.T_m)
        r1, r2 = st.AP - AP, g - value
        det = st.AP_h * g_m - st.AP_m * g_h
        with np.errstate(divide="ignore", invalid="ignore"):
            dh = -(r1 * g_m - st.AP_m * r2) / det
            dm = -(st.AP_h * r2 - g_h * r1) / det
        for _ in range(8):      # a step that would put an end on the centre, or jump, is halved
            bad = (h + dh - m - dm <= b) | (h + dh + m + dm <= b) | (np.abs(dh) >= 0.5 * h)
            if not np.any(bad):
                break
            dh, dm = np.where(bad, 0.5 * dh, dh), np.where(bad, 0.5 * dm, dm)
        good = inside & np.isfinite(dh) & np.isfinite(dm) & ~bad
        # a step below 1e-12 h leaves an error ~1e-24 h after it (quadratic convergence)
        ok = good & (np.abs(dh) <= 1e-12 * h) & (np.abs(dm) <= 1e-12 * h)
        h, m = np.where(good, h + dh, h), np.where(good, m + dm, m)
        if np.all(ok | ~good):
            break
    a, c = h - m, h + m
    return a, c, ok & (a > b) & (c > b)


class _Cycle:
    """Both half-cycles at once: normals and stick zones at fractions ``lam`` (vectorised).

    The normal at the fraction ``lam`` of the half-cycle ``1 -> 0`` is that at
    ``1 - lam`` of ``0 -> 1``, so one call of the root finder solves the normals of
    both, and one more the stick zones of both (eqs. S5, S6). With ``P`` and ``s``
    the same at both ends the normal is the same throughout and is not solved again.
    """

    def __init__(self, punch: Punch, A: float, f: float, states: tuple[LoadState, LoadState],
                 ends: tuple[NormalSolution, NormalSolution]) -> None:
        self.punch, self.A, self.f, self.states, self.ends = punch, A, f, states, ends
        (P0, s0, Q0, _), (P1, s1, Q1, _) = states
        self.sign = (1.0 if Q1 >= Q0 else -1.0, 1.0 if Q0 > Q1 else -1.0)
        self.dP_star = tuple((f * (e[0] - b[0]) - abs(e[2] - b[2])) / (2 * f)
                             for b, e in (states, states[::-1]))
        self.fixed = P0 == P1 and s0 == s1
        self._memo: dict[bytes, tuple[dict[str, Any], dict[str, Any]]] = {}
        self._permanent: tuple[float, float] | None = None

    def prime(self, *lams: np.ndarray) -> None:
        """Solve the states at several sets of fractions in one call of the root finders, for :meth:`__call__`."""
        both = self.solve_state(np.concatenate(lams))
        start = 0
        for lam in lams:
            idx = slice(start, start + lam.size)
            parts = [{k: v[idx] if isinstance(v, np.ndarray) else v for k, v in half.items()} for half in both]
            self._memo[lam.tobytes()] = (parts[0], parts[1])
            start += lam.size

    def __call__(self, lam: np.ndarray) -> tuple[dict[str, Any], dict[str, Any]]:
        """The half-cycles ``0 -> 1`` and ``1 -> 0`` at the fractions ``lam``: ends, stick zones, rates."""
        lam = np.atleast_1d(np.asarray(lam, dtype=float))
        hit = self._memo.get(lam.tobytes())
        return hit if hit is not None else self.solve_state(lam)

    def normals(self, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(a, c, alpha, P, s)`` at the fractions ``lam`` of ``0 -> 1``, lift-off and separation refused."""
        punch, A = self.punch, self.A
        P, s, _, _ = ramp(self.states[0], self.states[1], lam)
        if self.fixed:
            n, one = self.ends[0], np.ones_like(lam)
            return n.a * one, n.c * one, n.alpha * one, P, s
        (h0, m0), (h1, m1) = ((0.5 * (n.a + n.c), 0.5 * (n.c - n.a)) for n in self.ends)
        a, c, ok = _newton_ends(punch, A * P, "moment", A * P * s, h0 + lam * (h1 - h0), m0 + lam * (m1 - m0))
        if np.all(ok):
            st = State(punch, np.sqrt(a - punch.b), np.sqrt(c - punch.b), np)
            check_separation(punch, st.a, st.c, A, P, s, "free")
            return st.a, st.c, st.alpha, P, s
        st, below, above = solve_state(punch, P, s, A, "free", np)
        if np.any(below | above):
            i = int(np.argmax(below | above))
            raise LiftOffError(f"the state at {lam[i]:.4g} of the way from {self.states[0]} to "
                               f"{self.states[1]} (`P` = {P[i]:.6g}, `s` = {s[i]:.6g}) lifts a contact "
                               "edge off the outer segments, outside the closed form")
        check_separation(punch, st.a, st.c, A, P, s, "free")
        return st.a, st.c, st.alpha, P, s

    def solve_state(self, lam: np.ndarray) -> tuple[dict[str, Any], dict[str, Any]]:
        punch, A, f = self.punch, self.A, self.f
        k = lam.size
        a, c, alpha, P, s = self.normals(np.concatenate([lam, 1.0 - lam]))
        halves = []
        for j, (start, end) in enumerate((self.states, self.states[::-1])):
            idx = slice(j * k, (j + 1) * k)
            _, _, Q, sigma = ramp(start, end, lam)
            P_star = corrective_load(start[0], P[idx], Q - start[2], f)
            alpha_star = corrective_tilt_cycle(self.ends[j].alpha, alpha[idx], A, self.sign[j],
                                               sigma - start[3], f)
            dP, ds = end[0] - start[0], end[1] - start[1]
            rate = tilt_rate(A, a[idx], c[idx], dP, dP * s[idx] + P[idx] * ds)
            halves.append({"a": a[idx], "c": c[idx], "P": P[idx], "P_star": P_star, "alpha_star": alpha_star,
                           "dalpha_star": 0.5 * rate - self.sign[j] * A * (end[3] - start[3]) / (8 * f),
                           "dP_star": self.dP_star[j]})
        P_star = np.concatenate([h["P_star"] for h in halves])
        alpha_star = np.concatenate([h["alpha_star"] for h in halves])
        # Newton from h*^2 and m* interpolated between the contact (lam = 0) and the permanent zone
        (hp, mp), lam2 = self.permanent(), np.concatenate([lam, lam])
        first = np.repeat([[0.5 * (n.a + n.c), 0.5 * (n.c - n.a)] for n in self.ends], k, axis=0)
        a_s, c_s, ok = _newton_ends(punch, A * P_star, "tilt", alpha_star,
                                    np.sqrt(first[:, 0] ** 2 + lam2 * (hp * hp - first[:, 0] ** 2)),
                                    first[:, 1] + lam2 * (mp - first[:, 1]))
        a_s, c_s, out = self._bracketed(P_star, alpha_star, a_s, c_s, ok)
        for j, h in enumerate(halves):
            idx = slice(j * k, (j + 1) * k)
            h.update(left=-a_s[idx], right=c_s[idx], out=out[idx])
        return halves[0], halves[1]

    def _bracketed(self, P_star: np.ndarray, alpha_star: np.ndarray, a_s: np.ndarray, c_s: np.ndarray,
                   ok: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The stick zones Newton did not settle, by the bracketed roots; flags an end on the centre."""
        punch, A = self.punch, self.A
        dAP = A * P_star - 0.5 * math.pi * punch.kappa0 * punch.b**2
        out = ~(dAP > 0)
        todo = ~ok | out
        if np.any(todo):
            r, phi, lo, hi = solve_phi(punch, np.where(out, A * max(n.P for n in self.ends), dAP)[todo],
                                       "tilt", alpha_star[todo], np, sign=-1.0)
            zs = ray_state(punch, r, phi, np)
            a_s, c_s = a_s.copy(), c_s.copy()
            a_s[todo], c_s[todo] = zs.a, zs.c
            out = out.copy()
            out[todo] |= lo | hi
        return a_s, c_s, out

    def permanent(self) -> tuple[float, float]:
        """``(h*, m*)`` of the permanent stick zone (``lam = 1``), by Newton from the smaller contact scaled."""
        if self._permanent is None:
            (P0, _, Q0, g0), (P1, _, Q1, g1) = self.states
            P_star = np.array([(self.f * (P0 + P1) - abs(Q1 - Q0)) / (2 * self.f)])
            alpha_star = corrective_tilt_cycle(self.ends[0].alpha, self.ends[1].alpha, self.A, self.sign[0],
                                               g1 - g0, self.f)
            n = min(self.ends, key=lambda e: e.P)
            # the excess half-width over b scales as P^(1/2) (Hertz) to P^(2/3) (flat centre)
            ratio = max(P_star[0], 0.0) / n.P
            h = self.punch.b + (0.5 * (n.a + n.c) - self.punch.b) * ratio ** (0.5 if self.punch.b == 0 else 2 / 3)
            a_s, c_s, ok = _newton_ends(self.punch, self.A * P_star, "tilt", np.atleast_1d(alpha_star),
                                        np.array([h]), np.array([0.5 * (n.c - n.a)]))
            a_s, c_s, _ = self._bracketed(P_star, np.atleast_1d(alpha_star), a_s, c_s, ok)
            self._permanent = (0.5 * float(a_s[0] + c_s[0]), 0.5 * float(c_s[0] - a_s[0]))
        return self._permanent

    def path(self, j: int) -> Path:
        """The pieces :func:`threepart.halfplane.steady.half_cycle_work` integrates, on the half-cycle ``j``."""
        def pieces(lam: np.ndarray) -> Any:
            z = self(lam)[j]
            a, c = z["a"][:, None], z["c"][:, None]

            def pressure(x: np.ndarray) -> np.ndarray:
                return formulas.pressure(self.punch, a, c, self.A, x)
            return pressure, z["a"], z["c"], z["left"], z["right"], z["dP_star"], z["dalpha_star"]
        return pieces

    def least_margin(self) -> tuple[float, float, int, str]:
        """Least slip-direction margin (eq. S10) over both half-cycles: ``(value, lam, half, end)``."""
        def margins(lam: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
            out = []
            for z in self(np.atleast_1d(np.asarray(lam, dtype=float))):
                gl, gr = cycle_margin(z["left"], z["right"], z["a"], z["c"], self.A, self.f, z["dP_star"],
                                      z["dalpha_star"])
                # a stick zone past the contact's end is a reversal too (its end moved outwards)
                flag, tol = -abs(self.f * z["dP_star"]) / math.pi, 1e-12 * (z["a"] + z["c"])
                out.append((np.where(z["left"] < -z["a"] - tol, flag, gl),
                            np.where(z["right"] > z["c"] + tol, flag, gr)))
            return out
        lam = np.linspace(0.0, 1.0, MARGIN_GRID)      # lam = 0: the stick zone is the contact
        found = margins(lam)
        best = min(((float(g.min()), float(lam[int(np.argmin(g))]), j, end)
                    for j, pair in enumerate(found) for g, end in zip(pair, ("left", "right"))),
                   key=lambda t: t[0])
        scale = max(abs(self.f * d) for d in self.dP_star) / math.pi
        if best[0] > 0.05 * scale:
            return best
        for j in (0, 1):
            for e, end in enumerate(("left", "right")):
                x, v = least_on(lambda t, j=j, e=e: margins(t)[j][e], float(lam[0]), 1.0)
                if v < best[0]:
                    best = (v, x, j, end)
        return best


def _permanent(cycle: _Cycle) -> tuple[float, float, bool]:
    """``(left, right, shakedown)`` of the permanent stick zone, or the refusal that applies (eq. S12)."""
    lo, hi = common_contact(((-cycle.ends[0].a, cycle.ends[0].c), (-cycle.ends[1].a, cycle.ends[1].c)))
    z = cycle(np.array([1.0]))[0]
    left, right, out = float(z["left"][0]), float(z["right"][0]), bool(z["out"][0])
    tol = 1e-12 * (hi - lo)
    if not out and left <= lo + tol and right >= hi - tol:
        return lo, hi, True
    if out:
        raise StickZoneError(
            f"the permanent stick zone of the cycle (load P* = {float(z['P_star'][0]):.6g}) would "
            f"{stick_zone_leaves(cycle.punch.b)}, where the closed form does not hold")
    shakes_down(left, right, lo, hi)     # OneSidedSlipError where it reaches one edge only
    return left, right, False


#: a contact end closer to its join than this fraction of ``b`` is the join itself in double precision
JOIN_RESOLUTION = 1e-13


def _check_resolved(punch: Punch, normals: tuple[NormalSolution, NormalSolution]) -> None:
    """Refuse an end state whose contact passes the joins ``±b`` by rounding only (a load so small that
    ``a - b`` is lost against ``b``): its edges, slip zones and energy would be divisions by zero."""
    for k, n in enumerate(normals):
        if punch.b > 0 and min(n.a, n.c) - punch.b <= JOIN_RESOLUTION * punch.b:
            raise InputError(
                f"`states[{k}].P` = {n.P:g}: the contact [{-n.a:.17g}, {n.c:.17g}] passes the joins ±b = "
                f"±{punch.b:g} by less than {JOIN_RESOLUTION:g} b, rounding in double precision: the load is "
                "too small for the closed form to resolve its edges")


def _check_coulomb(normals: tuple[NormalSolution, NormalSolution], left: float, right: float) -> None:
    """On a concave centre: ``0 <= p* <= (p_0 + p_1)/2`` on the stick zone, else :class:`StickSeparationError`."""
    punch, A = normals[0].punch, normals[0].A
    if punch.kappa0 >= 0 or punch.b == 0:
        return
    cuts = sorted({left, right, *(t for t in (-punch.b, punch.b) if left < t < right)})
    p_star: Callable[[np.ndarray], np.ndarray] = lambda x: formulas.pressure(punch, -left, right, A, x)
    funs = (p_star, lambda x: 0.5 * (normals[0].pressure(x) + normals[1].pressure(x)) - p_star(x))
    tol = 1e-9 * min(n.P / (n.a + n.c) for n in normals)
    for fun, what in zip(funs, ("p* < 0", "p* > (p_0 + p_1)/2")):
        x, v = min((least_on(fun, lo, hi) for lo, hi in zip(cuts[:-1], cuts[1:])), key=lambda t: t[1])
        if v < -tol:
            raise StickSeparationError(
                f"the permanent stick zone [{left:.6g}, {right:.6g}] on the concave centre R = "
                f"{punch.R:g} breaks Coulomb's law: {what} at x = {x:.6g} (by {-v:.4g}); the true "
                "stick zone is not this single interval")


def steady_state(punch: Punch, states: Any, f: float, *, A: float) -> SteadySolution:
    """The periodic steady state of the cycle between ``states[0]`` and ``states[1]`` (docs/STEADY_STATE.md).

    Parameters
    ----------
    punch
        Three-part punch geometry (eq. 2).
    states
        The two ends of the cycle, each ``(P, s, Q, sigma_bulk)``; between them
        the four move linearly, in phase. ``|Q| < f P`` at both.
    f
        Coefficient of friction, > 0.
    A
        Compliance of the elastically similar pair (eq. 4), > 0.

    Returns
    -------
    SteadySolution
        ``d``, ``e`` (the permanent stick zone, eqs. S5, S6), ``energy`` (eq. S11),
        ``shakedown`` (eq. S12), ``normals``; ``info`` holds ``P_star``,
        ``alpha_star``, the least slip-direction ``margin`` (N/mm) and the
        quadrature's ``energy_nodes``.

    Raises
    ------
    ValueError, TypeError
        For invalid input; ``FullSlidingError`` for ``|Q| >= f P`` at either state.
    LiftOffError, SeparationError
        A state of the cycle leaves the closed form's normal contact.
    StickZoneError
        The permanent stick zone would end on the central segment;
        ``OneSidedSlipError`` (a subclass): it would reach one contact edge only;
        ``CycleSlipReversalError`` (a subclass): a point would slip backwards on a
        half-cycle (eq. S10); ``StickSeparationError``: a concave centre's
        corrective pressure breaks Coulomb's law.
    """
    check_punch(punch)
    (st0, st1), f = check_cycle_states(states, f)
    t0 = time.perf_counter()
    batch = solve_normal_batch(punch, [st0[0], st1[0]], [st0[1], st1[1]], A=A)
    normals = (batch[0], batch[1])
    _check_resolved(punch, normals)
    cycle = _Cycle(punch, batch.A, f, (st0, st1), normals)
    grid = np.linspace(0.0, 1.0, MARGIN_GRID)
    first = [lam_rule(n, ())[0] for n in (WORK_NODES, 2 * WORK_NODES)]
    cycle.prime(grid[-1:], grid, *first)          # one call of each root finder for the whole cycle
    left, right, shakedown = _permanent(cycle)
    info: dict[str, Any] = {"P_star": (f * (st0[0] + st1[0]) - abs(st1[2] - st0[2])) / (2 * f),
                            "alpha_star": float(corrective_tilt_cycle(normals[0].alpha, normals[1].alpha, cycle.A,
                                                                      cycle.sign[0], st1[3] - st0[3], f))}
    energy, nodes = 0.0, 0
    if not shakedown:
        _check_coulomb(normals, left, right)
        least, lam, k, end = cycle.least_margin()
        if least < -1e-12 * abs(st1[2] - st0[2]):
            raise CycleSlipReversalError(
                f"in the cycle between {st0} and {st1} the {end} end of the contact slips backwards at "
                f"{lam:.4g} of the way from state {k} to state {1 - k} (margin {least:.4g} N/mm): the "
                "change of P, s or sigma_bulk outpaces the shear's; the steady state is not the "
                "superposition of eq. (S4)")
        works = [half_cycle_work(cycle.path(j), cycle.A, f, punch.b) for j in (0, 1)]
        energy, nodes = works[0][0] + works[1][0], max(works[0][1], works[1][1])
        info["margin"] = least
    diagnostics = Diagnostics(timings={"total": time.perf_counter() - t0})
    info["energy_nodes"] = nodes
    return SteadySolution(normals=normals, states=(st0, st1), f=f, d=0.5 * (right - left),
                          e=-0.5 * (left + right), energy=energy, shakedown=shakedown,
                          diagnostics=diagnostics, info=info)

"""Partial slip, the fretting cycle and fretting wear on a worn profile, by the SIE (issue 39).

Partial slip and the fretting cycle on a :class:`sie.profile.WornProfile` are
those of :mod:`sie.slip` and :mod:`sie.fretting` with the profile's scheme
(:class:`sie.profile.ProfileScheme`): Ciavarella–Jäger's corrective problem on
the same worn profile, Masing's rule for the cycle. P and s stay constant, so
the pressure does not change over a cycle.

Wear per cycle (docs/WEAR.md, section 5). A point of a slip zone travels
``∮|ds| = 4 |s_Q_max(x)|`` per cycle (Masing: twice the loading slip at
``Q_max`` each half-cycle), ``s_Q_max = f G*(x)`` with ``G*`` the gap of the
corrective contact at ``Q_max`` (:func:`sie.profile.profile_gap`), and slips
only where ``|q| = f p``. So per cycle

    Archard:  Δw = k p ∮|ds| = 4 k f p G*,       energy:  Δw = k ∮ q·ds = 4 k f² p G*,

and the friction work is ``W = ∫ 4 f² p G* dx``: under the energy law the
worn volume per cycle is ``k W`` (eq. W15). ``w`` is the two bodies' wear
together, the combined depth of the gap (docs/WEAR.md, section 4): how they
share it does not change the contact.

The march (:func:`march`). The unworn contact comes from the Gauss–Chebyshev SIE;
the depth then grows at :data:`NODES` nodes over that contact and :data:`GRID_MARGIN`
of it beyond each end (the scar outgrows the contact, docs/WEAR.md section 4), graded
towards the unworn stick zone's ends and the punch's joins (:func:`_grid`). Each state
collocates eq. (0.1) of docs/WEAR.md, the displacement form of eq. (integral_equation),
at the nodes with the pressure linear between them
(:func:`threepart.halfplane.surface.influence`), for the normal contact and for the
corrective contact at ``Q_max`` (:func:`sie.nodes.node_state`), by the core's active-set
solve; ``WearResult.final`` is the fretting cycle on the last state's nodes
(:func:`sie.nodes.node_fretting`). The global series of :func:`sie.profile.solve_profile`
resolves neither a pressure that falls to 0 over the slip zones nor the singular ends that
form at the stick zone's (its bounded contact turned tensile and the energy stalled at 23 %
of its start, docs/WEAR.md section 8); the nodes do, to their spacing. Cycle jumping
(``jump=None``) is :func:`threepart.fretting_wear.jump_size`. Where a state is not found
(a named error) the march ends early: ``cycles[-1]`` is the last state solved, and
``info["stopped"]`` says why (never silently: the requested count is ``info["requested"]``).

ProfileFrettingResult   -- SieFrettingResult on a worn profile
solve_profile_slip      -- partial slip on a worn profile
profile_fretting_cycle  -- the fretting cycle on a worn profile: energy from the loop (ln h/h*)
wear_rate               -- the depth worn per cycle, the friction work and the stick zone at Q_max
march                   -- the wear march of threepart.wear (registered as method "sie")
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from threepart.errors import InputError, NoConvergenceError, StickSeparationError
from threepart.fretting_wear import MarchState, WearResult, march_depth, register_marcher
from threepart.problem.checks import integer
from threepart.problem.punch import Punch
from threepart.results import Diagnostics
from threepart.halfplane.legendre import gauss01
from threepart.halfplane.surface import influence
from threepart.problem.validate import SLIP_RATIO_LIMIT, check_states
from threepart.results.slip import check_shear

from .nodes import COULOMB_FLOOR, NodeState, node_fretting, node_state
from .fretting import SieFrettingResult, Zones, loop_integral
from .profile import (DEFAULT_TERMS, ProfileNormalResult, WornProfile, profile_approach, profile_gap,
                      solve_profile)
from .slip import SieSlipResult, stick_zone

__all__ = ["ProfileFrettingResult", "solve_profile_slip", "profile_fretting_cycle", "wear_rate",
           "march", "NODES", "POINTS", "GRID_MARGIN"]

#: nodes of the march over the unworn contact and its margins
NODES = 400
#: the range of ``points`` a caller may ask for: fewer than 50 nodes leave a slip zone a handful; a
#: dense solve of 5000 nodes per state is the most this machine's memory and a march's time allow
POINTS = (50, 5000)
#: the length, of the contact's width, over which the march's spacing grows back to uniform near a feature
GRADING = 0.25
#: the grid reaches this fraction of the contact's width beyond each end (the scar outgrows it)
GRID_MARGIN = 0.15
#: Gauss–Legendre nodes per slip zone of the friction work, u = lo + L s^2 (3 - 2s)
WORK_NODES = 96
#: Gauss–Legendre nodes per panel of the loop's energy, and the coarser level that checks it
LOOP_NODES = (24, 48)


def _coulomb(normal: ProfileNormalResult, stick, lo: float, hi: float, Q: float, f: float) -> None:
    """``p >= p*`` on the stick zone ``[lo, hi]``, sampled at 801 points clustered at its ends."""
    x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(np.linspace(0, np.pi, 803)[1:-1])
    p = normal.pressure(x)
    excess = p - stick(x)
    i = int(np.argmin(excess))
    if excess[i] < -COULOMB_FLOOR * float(np.max(p)):
        raise StickSeparationError(f"`Q`/(f P) = {abs(Q) / (f * normal.P):.6g} on the worn profile: the "
                                   f"corrective pressure exceeds p by {-excess[i]:.4g} at x = {x[i]:.6g}; "
                                   "the stick zone is not one interval")


def solve_profile_slip(normal: ProfileNormalResult, Q: float, f: float) -> SieSlipResult:
    """Partial slip on a worn profile: the stick zone and shear ``q = sign(Q) f (p - p*)``.

    As :func:`sie.solve_partial_slip`, the corrective ``p*`` the bounded pressure
    of the worn profile on the stick zone at the normal tilt, load ``P - |Q|/f``.

    Raises
    ------
    StickSeparationError
        ``p* > p`` somewhere on the stick zone.
    """
    if not isinstance(normal, ProfileNormalResult):
        raise InputError("`normal` must be a worn profile's normal result (sie.profile.solve_profile)")
    Q, f = check_shear(normal, Q, f, limit=SLIP_RATIO_LIMIT)
    sch = normal.scheme
    t0 = time.perf_counter()
    m, h, its, res = stick_zone(normal, Q, f, sch)
    stick, extra = sch.pressure(normal.punch, normal.A, m, h)
    _coulomb(normal, stick, m - h, m + h, Q, f)
    return SieSlipResult(normal=normal, Q=float(Q), f=float(f), d=h, e=-m, method="sie",
                         diagnostics=Diagnostics(n=sch.n, scheme=sch.name, iterations=its, residual=res,
                                                 timings={"total": time.perf_counter() - t0}),
                         info={"P_star": normal.P - abs(Q) / f, **extra}, stick=stick)


@dataclass(frozen=True)
class ProfileFrettingResult(SieFrettingResult):
    """A fretting cycle on a worn profile (:func:`profile_fretting_cycle`); ``normal`` carries the profile."""

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """The pressure of the cycle's worn profile (constant over the cycle: P and s are)."""
        return self.normal.pressure(x)

    def _load(self, u: float) -> SieSlipResult:
        nrm = self.normal
        assert isinstance(nrm, ProfileNormalResult)
        sch = nrm.scheme
        m, h, _, _ = stick_zone(nrm, u, self.f, sch)
        stick, _ = sch.pressure(nrm.punch, nrm.A, m, h)
        return SieSlipResult(normal=nrm, Q=u, f=self.f, d=h, e=-m, method="sie",
                             diagnostics=Diagnostics(n=sch.n, scheme=sch.name), stick=stick)

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        nrm = self.normal
        assert isinstance(nrm, ProfileNormalResult) and nrm.profile is not None
        if u == 0:
            return np.zeros(x.shape)
        sl = self._load(u)
        gap = profile_gap(nrm.profile, nrm.alpha, -sl.e, sl.d, x)
        return np.where((x > -nrm.a) & (x < nrm.c), self.f * gap, 0.0)


def _loop_energy(zones: Zones, Q_max: float, top: tuple[float, float]) -> tuple[float, float]:
    """``W = (4A/π) ∫_0^Q_max (2u - Q_max) ln(h/h*(u)) du`` (sie.fretting) and its two-level estimate.

    Composite Gauss–Legendre with a panel end where a stick-zone end crosses a
    join, ``u = lo + L s^2 (3 - 2s)`` on each panel, at :data:`LOOP_NODES`.
    """
    edges = [0.0, *zones.crossings(Q_max, top), Q_max]
    values = []
    for n in LOOP_NODES:
        values.append(4 * zones.normal.A / math.pi * loop_integral(zones, Q_max, edges, n))
    return values[-1], abs(values[-1] - values[0])


def profile_fretting_cycle(normal: ProfileNormalResult, Q_max: float, f: float, *,
                           states: int = 21) -> ProfileFrettingResult:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` on a worn profile (as :func:`sie.fretting_cycle`).

    ``energy`` is the loop's area from the loading stick zones (``ln h/h*``);
    ``info`` holds ``energy_estimate`` (against the coarser rule) and
    ``friction_work``, ``∫ 4 f² p G* dx`` of the slip (the local route, eq. W15).
    """
    if not isinstance(normal, ProfileNormalResult):
        raise InputError("`normal` must be a worn profile's normal result (sie.profile.solve_profile)")
    Q_max, f = check_shear(normal, Q_max, f, "Q_max", "there is no fretting cycle", limit=SLIP_RATIO_LIMIT)
    states = check_states(states)
    t0 = time.perf_counter()
    sch = normal.scheme
    zones = Zones(normal, f, sch)
    u = np.linspace(0.0, Q_max, states)
    mh = np.array([zones(float(v)) for v in u])
    prof, A, alpha = normal.profile, normal.A, normal.alpha
    assert prof is not None
    D0 = profile_approach(prof, A, alpha, normal.P, zones.m0, zones.h0)
    F = np.array([f * (D0 - profile_approach(prof, A, alpha, normal.P - v / f, m, h)) if v > 0 else 0.0
                  for v, (m, h) in zip(u, mh)])
    top = (float(mh[-1, 0]), float(mh[-1, 1]))
    energy, estimate = _loop_energy(zones, Q_max, top)
    stick = np.column_stack([mh[:, 0] - mh[:, 1], mh[:, 0] + mh[:, 1]])
    work = wear_rate(normal, Q_max, f, np.array([0.0]))[1]
    info = {"energy_estimate": estimate, "friction_work": work, "solves": zones.solves}
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, steps=states,
                              timings={"total": time.perf_counter() - t0})
    return ProfileFrettingResult.from_loading(normal, Q_max, f, u, stick, F, energy=energy, method="sie",
                                              diagnostics=diagnostics, info=info)


def wear_rate(normal: ProfileNormalResult, Q_max: float, f: float, x: np.ndarray
              ) -> tuple[np.ndarray, float, tuple[float, float], np.ndarray]:
    """``4 f p G*`` at ``x`` (the Archard depth per cycle and unit ``k``), the friction work, the stick zone.

    Returns
    -------
    rate, work, stick, travel
        ``p ∮|ds|`` at ``x``; ``W = ∫ f p ∮|ds| dx`` over both slip zones
        (Gauss–Legendre, :data:`WORK_NODES`, ``u = lo + L s^2(3 - 2s)`` each);
        the stick zone at ``Q_max``; ``∮|ds| = 4 f G*`` at ``x``.
    """
    prof = normal.profile
    assert prof is not None
    sch = normal.scheme
    m, h, _, _ = stick_zone(normal, Q_max, f, sch)
    lo, hi = m - h, m + h

    s, w = gauss01(WORK_NODES)
    nodes, weights = [], []
    for a_, b_ in ((-normal.a, lo), (hi, normal.c)):
        if b_ > a_:
            nodes.append(a_ + (b_ - a_) * s * s * (3 - 2 * s))
            weights.append(6 * (b_ - a_) * s * (1 - s) * w)
    x = np.asarray(x, dtype=float)
    t = np.concatenate([*nodes, x])
    inside = (t > -normal.a) & (t < normal.c) & ((t < lo) | (t > hi))
    gap = profile_gap(prof, normal.alpha, m, h, np.where(inside, t, m))
    travel = np.where(inside, 4.0 * f * np.maximum(gap, 0.0), 0.0)
    p_travel = np.maximum(normal.pressure(t), 0.0) * travel
    q = t.size - x.size
    work = f * float(np.sum(np.concatenate(weights or [np.zeros(0)]) * p_travel[:q]))
    rate, tr = p_travel[q:], travel[q:]
    return rate, work, (lo, hi), tr


def _grid(base: ProfileNormalResult, points: int, features: tuple[float, ...] = ()) -> np.ndarray:
    """The march's nodes: over the unworn contact and :data:`GRID_MARGIN` of it beyond each end.

    Without ``features``, ``points`` uniform nodes. With them (the stick zone's ends at
    ``Q_max``, the punch's joins), the spacing is ``h(x) ∝ sqrt(d(x)/l)``, capped at 1,
    ``d`` the distance to the nearest feature and ``l`` :data:`GRADING` of the contact's
    width: the ``(1 - cos)`` spacing of Gauss–Chebyshev points, which a square-root end
    asks for (the worn state's pressure, docs/WEAR.md eq. W3; the slope at a curvature
    jump). The nodes are the spacing's quantiles.
    """
    W = base.a + base.c
    lo, hi = -base.a - GRID_MARGIN * W, base.c + GRID_MARGIN * W
    if not features:
        return np.linspace(lo, hi, points)
    t = np.linspace(lo, hi, 40 * points)
    d = np.min(np.abs(t[:, None] - np.asarray(features)[None, :]), axis=1)
    density = 1.0 / np.sqrt(np.clip(d / (GRADING * W), 1e-12, 1.0))
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(t))])
    x = np.interp(np.linspace(0.0, cdf[-1], points), cdf, t)
    x[0], x[-1] = lo, hi
    return x


def _features(punch: Punch, stick: tuple[float, float]) -> tuple[float, ...]:
    """Where the march's nodes gather (:func:`_grid`): the stick zone's ends and the joins ``±b`` with a curvature jump."""
    joins = tuple(v for v, kappa in ((-punch.b, punch.kappa1), (punch.b, punch.kappa2)) if punch.b > 0 and kappa)
    return (*stick, *joins)


def march(punch: Punch, P: float, s: float, Q_max: float, f: float, *, A: float, law: str, k: float,
          cycles: int, jump: int | None = None, tilt: str = "free", n: int = DEFAULT_TERMS,
          points: int = NODES) -> WearResult:
    """Fretting wear at constant ``P``, ``s`` with ``Q`` between ``±Q_max``: threepart.wear's SIE march.

    Input is checked by :func:`threepart.fretting_wear.wear`. The unworn contact comes
    from the Gauss–Chebyshev SIE (``n`` terms); the march then collocates the same
    integral equation in its displacement form (eq. 0.1 of docs/WEAR.md) at ``points``
    nodes with the pressure linear between them (:func:`threepart.halfplane.surface.influence`),
    where the depth grows. The nodes are graded towards the unworn stick zone's ends at
    ``Q_max`` (found first on uniform nodes) and the punch's joins (:func:`_grid`). Each step
    solves the normal contact and the corrective contact at ``Q_max``
    (:func:`sie.nodes.node_state`) and grows the depth by ``ΔN`` cycles' wear: ``jump`` cycles, or
    the module docstring's control. A global series resolves neither the pressure that
    falls to 0 over the slip zones nor the singular ends that form at the stick zone's;
    nodes do, to their spacing (docs/WEAR.md, section 8).
    """
    points = integer("points", points, *POINTS)
    t0 = time.perf_counter()
    law_factor = f if law == "energy" else 1.0
    base = solve_profile(WornProfile(punch, np.array([-1.0, 1.0]), np.zeros(2)), P, s, A=A, tilt=tilt, n=n)
    x = _grid(base, points)
    C, w = influence(x, A)
    first = node_state(C, x, w, punch.profile(x), P, s, Q_max, f, tilt == "free")
    x = _grid(base, points, _features(punch, first.stick))
    C, w = influence(x, A)
    g = punch.profile(x)

    def solve(depth: np.ndarray, last: NodeState | None) -> MarchState:
        st = node_state(C, x, w, g + depth, P, s, Q_max, f, tilt == "free",
                        None if last is None else (last.normal, last.corrective))
        return MarchState(rate=st.rate, travel=st.travel, work=st.work, stick=st.stick, contact=st.contact,
                          alpha=st.normal.alpha, pressure=st.p, solved=st)

    spacing = np.gradient(x)
    rec, stopped, last = march_depth(solve, w, spacing, k=k, law_factor=law_factor, A=A, P=P, cycles=cycles,
                                     jump=jump, failures=(StickSeparationError, NoConvergenceError))
    worn = g + rec["depths"][-1]       # the last state's profile
    return WearResult(punch=punch, P=P, s=s, Q_max=Q_max, f=f, A=A, law=law, k=k, x=x, method="sie",
                      final_cycle=lambda: node_fretting(last, C, x, w, worn, punch=punch, A=A, P=P, s=s,
                                                        Q_max=Q_max, f=f, tilt=tilt),
                      **rec, info={"time": time.perf_counter() - t0, "steps": len(rec["cycles"]) - 1,
                            "jump": "auto" if jump is None else jump, "n": n, "points": x.size,
                            "stopped": stopped, "requested": cycles, "tilt": tilt})


register_marcher("sie", march)

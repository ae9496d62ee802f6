"""The results of load cycles: the periodic steady state and the marched load history.

Both build on the one result shape of :mod:`threepart.results` (their normal
solutions are :class:`~threepart.results.NormalResult` records) and share its
coordinate checks: every ``shear``, ``slip``, ``slip_amplitude`` and ``stress``
checks its ``x`` (and ``z``), and a steady state's shear at both ends is checked
against Coulomb's law when it is built (:mod:`threepart.results.answer`).

Names
-----
SteadyStateResult -- the periodic steady state of an in-phase cycle (docs/STEADY_STATE.md)
HistoryResult     -- a contact marched through a load history with the memory of slip
MarchedSteadyResult -- the steady state of a cycle as the last cycle of a marched history (``auto``)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
from numpy.typing import ArrayLike

from .answer import check_coulomb
from ..problem.punch import Punch
from .edges import Edged
from ..problem.material import NU
from .contact import Diagnostics, NormalResult, Answer, interior_kinks
from ..problem.checks import LENGTH_RANGE, show
from ..halfplane.steady import common_contact
from ..stress.flamant import Stress, stress
from threepart.errors import DisjointContactsError, InputError, InputTypeError, StickZoneError

__all__ = ["SteadyStateResult", "HistoryResult", "MarchedSteadyResult"]

#: a stick zone may pass the end contacts' common part by this fraction of its width (rounding of
#: the roots), besides the method's element ``h``
ZONE_SLACK = 1e-9
#: points of each panel's first scan in :meth:`SteadyStateResult.largest_slip_amplitude`
AMPLITUDE_SCAN = 33
#: ... whose ends lie this fraction of the larger contact inside the panel's (a contact end itself is
#: outside), and the zoom's last spacing
AMPLITUDE_INSET = 1e-12
#: the most zooms of the scan (each narrows it by (AMPLITUDE_SCAN - 1)/2), and the width of the
#: last, of the larger contact
AMPLITUDE_ROUNDS, AMPLITUDE_XTOL = 8, 1e-10


@dataclass(frozen=True)
class SteadyStateResult(Edged, Answer):
    """The periodic steady state of a cycle between two states, the loads moving linearly, in phase.

    Attributes
    ----------
    normals, states, f
        The normal solutions at the two ends, the ends ``(P, s, Q, sigma_bulk)``, the friction coefficient.
    d, e
        The permanent stick zone ``[-(d+e), d-e]`` (eqs. S5, S6); in shakedown the smaller contact.
    energy
        Friction work dissipated per cycle and unit length, N·mm/mm (eq. S11); 0 in shakedown.
    shakedown
        True when nothing slips in the steady state (eq. S12).

    A subclass gives ``p*`` (:meth:`corrective`) and the gaps (:meth:`gap`); the shear and slip follow.
    """

    edge_kind = "steady"   # its edge records (threepart.results.edges.EDGE_KINDS)

    normals: tuple[NormalResult, NormalResult]
    states: tuple[tuple[float, float, float, float], tuple[float, float, float, float]]
    f: float
    d: float
    e: float
    energy: float
    shakedown: bool
    method: str = ""
    diagnostics: Diagnostics = field(default_factory=Diagnostics, compare=False)
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    @property
    def stick_zone(self) -> tuple[float, float]:
        return -(self.d + self.e), self.d - self.e      # (-(d+e), d-e)

    @property
    def sign(self) -> float:
        """``sign(ΔQ)``, ``ΔQ = Q_1 - Q_0``: the sense of slip from state 0 to state 1 (+1 at ``ΔQ = 0``)."""
        return 1.0 if self.states[1][2] >= self.states[0][2] else -1.0

    def corrective(self, x: ArrayLike) -> np.ndarray:
        """Corrective pressure ``p*`` on the stick zone (0 outside)."""
        raise NotImplementedError

    def gap(self, x: ArrayLike, which: str | int) -> np.ndarray:
        """Gap of the corrective contact (``which="stick"``) or of the normal contact 0 or 1, 0 inside it."""
        raise NotImplementedError

    def check(self) -> None:
        """The stick zone inside both end contacts (:meth:`check_stick_zone`); Coulomb's law at both ends
        of the cycle (:func:`threepart.results.answer.check_coulomb`), none in shakedown."""
        self.check_stick_zone()
        if not self.shakedown:
            for k in (0, 1):
                check_coulomb(_End(self, k))

    def check_stick_zone(self) -> None:
        """Refuse a permanent stick zone that is empty, not finite or outside either end contact.

        The ends may pass the contacts' common part by the method's element ``h``
        (a marched zone ends half-way between nodes) and rounding of its width.

        Raises
        ------
        DisjointContactsError
            If the end contacts do not overlap (:func:`threepart.halfplane.steady.common_contact`).
        StickZoneError
            If the zone is inverted or leaves the contacts' common part.
        """
        lo, hi = common_contact(((-self.normals[0].a, self.normals[0].c), (-self.normals[1].a, self.normals[1].c)))
        left, right = self.stick_zone
        slack = ZONE_SLACK * (hi - lo) + (self.diagnostics.h or 0.0)
        if not (math.isfinite(left) and math.isfinite(right) and left <= right
                and left >= lo - slack and right <= hi + slack):
            raise StickZoneError(
                f"{self.method or 'the'} steady state's stick zone [{left:.6g}, {right:.6g}] is not inside the "
                f"contacts' common part [{lo:.6g}, {hi:.6g}]: no stick zone is returned outside a contact")

    def _state(self, state: Any) -> int:
        if isinstance(state, (bool, np.bool_)) or not isinstance(state, (int, np.integer)) or state not in (0, 1):
            raise InputError(f"`state` = {show(state)} must be 0 or 1 (an end of the cycle, one int)")
        return int(state)

    def shear(self, x: ArrayLike, state: int) -> np.ndarray:
        """Shear ``q(x)`` at the end ``state``; integrates to its ``Q`` (eqs. S3, S13).

        ``∓sign(ΔQ) f p`` in the slip zones. The steady state fixes only the change in
        the stick zone (eq. S4); of the shear locked in there, which the load history
        sets, this is the part proportional to ``p*``: ``q_0 = sign f (k_0 p* - p_0)``,
        ``q_1 = sign f (p_1 - k_1 p*)``, ``k_0 + k_1 = 2`` (Masing's states at ``P``, ``s``
        constant without a mean). In shakedown a ``ValueError``: the shear is all history.
        """
        k = self._state(state)
        if self.shakedown:
            raise InputError("the cycle has shaken down: its shear is locked in by the load history, "
                             "the steady state does not determine it (only energy = 0 and the stick zone)")
        (P0, _, Q0, _), (P1, _, Q1, _), (P, _, Q, _) = *self.states, self.states[k]
        sgn, f, f_star = self.sign, self.f, 0.5 * (self.f * (P0 + P1) - abs(Q1 - Q0))   # f P* (eq. S6)
        p, p_star = self.normals[k].pressure(x), self.corrective(x)
        if k == 0:
            return sgn * f * ((sgn * Q + f * P) / f_star * p_star - p)
        return sgn * f * (p - (f * P - sgn * Q) / f_star * p_star)

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        """Half the slip over a half-cycle (eq. S7), ``f |gap* - (gap_0 + gap_1)/2|``; 0 outside the larger contact."""
        x = np.asarray(x, dtype=float)
        if self.shakedown:
            return np.zeros(x.shape)
        lo, hi = min(-n.a for n in self.normals), max(n.c for n in self.normals)
        amp = self.f * np.abs(self.gap(x, "stick") - 0.5 * (self.gap(x, 0) + self.gap(x, 1)))
        return np.where((x > lo) & (x < hi), amp, 0.0)

    def largest_slip_amplitude(self) -> tuple[float, float]:
        """``(delta, x)``: the largest slip amplitude (:meth:`slip_amplitude`) and where it lies.

        The one routine of the command line and the report. The larger contact is cut
        into panels at both contacts' ends, the stick zones' ends and the joins; each
        panel is scanned at :data:`AMPLITUDE_SCAN` points, its ends taken just inside
        (the largest value often lies at the larger contact's edge, where the amplitude
        falls to 0 outside), and the scan zoomed on the best point's neighbours until they
        lie :data:`AMPLITUDE_XTOL` of the contact apart.
        ``(0, -a)`` where nothing slips.
        """
        lo, hi = min(-n.a for n in self.normals), max(n.c for n in self.normals)
        if self.shakedown:
            return 0.0, lo
        zones = self.stick_intervals if isinstance(self, MarchedSteadyResult) else (self.stick_zone,)
        b = self.normals[0].punch.b
        cuts = np.array(sorted({lo, hi, *(t for n in self.normals for t in (-n.a, n.c)),
                                *(t for t in (-b, b, *(e for z in zones for e in z)) if lo < t < hi)}))
        inset = AMPLITUDE_INSET * (hi - lo)
        left, right = cuts[:-1] + inset, cuts[1:] - inset
        keep = right > left
        left, right = left[keep], right[keep]
        xs = left[:, None] + (right - left)[:, None] * np.linspace(0.0, 1.0, AMPLITUDE_SCAN)[None, :]
        v = np.asarray(self.slip_amplitude(xs.ravel()), dtype=float).reshape(xs.shape)
        k, i = (int(j) for j in np.unravel_index(int(np.argmax(v)), v.shape))
        best, xs = (float(v[k, i]), float(xs[k, i])), xs[k]
        for _ in range(AMPLITUDE_ROUNDS):          # zoom on the best point's neighbours in its panel
            xs = np.linspace(xs[max(i - 1, 0)], xs[min(i + 1, len(xs) - 1)], AMPLITUDE_SCAN)
            v = np.asarray(self.slip_amplitude(xs), dtype=float)
            i = int(np.argmax(v))
            if v[i] > best[0]:
                best = (float(v[i]), float(xs[i]))
            if xs[-1] - xs[0] <= AMPLITUDE_XTOL * (hi - lo):
                break
        return best

    def stress(self, x: ArrayLike, z: ArrayLike, state: int, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)`` at the end ``state``: pressure, :meth:`shear`, ``sigma_bulk``."""
        n = self.normals[k := self._state(state)]
        _in_range(x, z)
        return stress(x, z, pressure=n.pressure, shear=lambda t: self.shear(t, k), ends=(-n.a, n.c),
                      sigma_bulk=self.states[k][3], nu=nu, kinks=interior_kinks(n.punch.b, -n.a, n.c, *self.stick_zone))


def _in_range(x: ArrayLike, z: ArrayLike) -> None:
    """Refuse points past :data:`threepart.problem.checks.LENGTH_RANGE`, whose squares overflow, naming the coordinate."""
    for name, v in (("x", x), ("z", z)):
        big = float(np.max(np.abs(np.asarray(v, dtype=float)), initial=0.0))
        if big > LENGTH_RANGE[1]:
            raise InputError(f"`{name}` = {big:g} is outside [-{LENGTH_RANGE[1]:g}, {LENGTH_RANGE[1]:g}], the range "
                             "of lengths this library computes in double precision")


@dataclass(frozen=True)
class _End:
    """One end ``k`` of a steady cycle, seen as a partial-slip answer by :func:`~threepart.results.answer.check_coulomb`."""

    cycle: SteadyStateResult
    k: int

    @property
    def a(self) -> float:
        return self.cycle.normals[self.k].a

    @property
    def c(self) -> float:
        return self.cycle.normals[self.k].c

    @property
    def P(self) -> float:
        return self.cycle.states[self.k][0]

    @property
    def Q(self) -> float:
        return self.cycle.states[self.k][2]

    @property
    def f(self) -> float:
        return self.cycle.f

    @property
    def method(self) -> str:
        return f"{self.cycle.method} steady state, end {self.k},"

    @property
    def diagnostics(self) -> Diagnostics:
        return self.cycle.diagnostics

    @property
    def stick_zone(self) -> tuple[float, float]:
        return self.cycle.stick_zone

    def pressure(self, x: np.ndarray) -> np.ndarray:
        return self.cycle.normals[self.k].pressure(x)

    def shear(self, x: np.ndarray) -> np.ndarray:
        return self.cycle.shear(x, self.k)


@dataclass(frozen=True)
class HistoryResult(Answer):
    """A contact marched through a load history ``(P, s, Q, sigma_bulk)_k`` with the memory of slip.

    Attributes
    ----------
    punch, f
        Geometry and coefficient of friction.
    P, s, Q, sigma_bulk
        The states, one value each.
    normals
        The normal solution of each state (contact ``[-a_k, c_k]``, ``alpha_k``, ``p_k``).
    stick
        Per state, the stick intervals ``((left, right), ...)``: where the contact
        did not slip in the step to that state (the whole contact at a state
        that repeats its predecessor).
    energy
        Friction work per completed cycle, per unit length (:meth:`History.cycles
        <threepart.halfplane.load_history.History.cycles>`, the cycles in :attr:`cycles`).
    cycles
        ``(start, end)`` state indices of each completed cycle.
    work
        Friction work of each step (``work[0]``: from the unloaded body to the first state).
    method
        ``"sie"`` or ``"fem"``.
    x_nodes, q_nodes, slip_nodes
        The points that carry the shear and the slip, and their values per state
        (``(states, points)``): the SIE's element midpoints (the shear constant
        over each element between ``edges``), the FEM's interface nodes (linear between them).
    edges
        The SIE's element edges; ``None`` for nodal values (the FEM).
    delta
        The rigid tangential shift of each state, the punch against the substrate (the
        relative tangential displacement of the points that stick, less the bulk strain's
        share; the SIE's is defined up to a term linear in ``Q``, the log kernel's length
        scale): ``Q`` against it is the hysteresis loop (:meth:`loop`).
    diagnostics, info
        Discretisation, iterations and timings; what is particular to the method.
    """

    punch: Punch
    f: float
    P: np.ndarray
    s: np.ndarray
    Q: np.ndarray
    sigma_bulk: np.ndarray
    normals: tuple[NormalResult, ...]
    stick: tuple[tuple[tuple[float, float], ...], ...]
    energy: np.ndarray
    cycles: tuple[tuple[int, int], ...]
    work: np.ndarray
    method: str
    x_nodes: np.ndarray = field(repr=False)
    q_nodes: np.ndarray = field(repr=False)
    slip_nodes: np.ndarray = field(repr=False)
    edges: np.ndarray | None = field(default=None, repr=False)
    delta: np.ndarray | None = field(default=None, repr=False)
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    info: Mapping[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.P)

    def _state(self, k: int) -> int:
        n = len(self.P)
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not -n <= k < n:
            raise InputError(f"`k` = {k!r} must be a state index in [{-n}, {n - 1}]")
        return int(k) % n

    def _field(self, values: np.ndarray, x: ArrayLike, k: int) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        if self.edges is not None:      # constant on each element, 0 outside the grid
            i = np.searchsorted(self.edges, x, side="right") - 1
            inside = (i >= 0) & (i < len(values))
            return np.where(inside, values[np.clip(i, 0, len(values) - 1)], 0.0)
        nrm = self.normals[k]           # linear between the nodes over the contact, 0 at its ends
        inside = (self.x_nodes > -nrm.a) & (self.x_nodes < nrm.c)
        xs = np.concatenate([[-nrm.a], self.x_nodes[inside], [nrm.c]])
        vs = np.concatenate([[0.0], values[inside], [0.0]])
        return np.interp(x, xs, vs, left=0.0, right=0.0)

    def shear(self, x: ArrayLike, k: int) -> np.ndarray:
        """Shear traction ``q(x)`` the punch exerts on the substrate in state ``k`` (0 out of contact)."""
        k = self._state(k)
        return self._field(self.q_nodes[k], x, k)

    def slip(self, x: ArrayLike, k: int) -> np.ndarray:
        """Accumulated relative slip (punch minus substrate) at ``x`` up to state ``k``.

        The sum of the slip increments of the steps in which ``x`` was in
        contact at both ends of the step; where ``q`` slips it has the sign of ``q``'s.
        """
        k = self._state(k)
        return self._field(self.slip_nodes[k], x, k)

    def loop(self, cycle: int = -1) -> tuple[np.ndarray, np.ndarray]:
        """``(delta, Q)`` over the states of a completed cycle (the last by default): the hysteresis loop.

        Its area is the friction work of the cycle where no bulk stress changes
        (``∮ Q dδ``; under a changing bulk stress the bulk stress works too, B9).

        Raises
        ------
        ValueError
            If the history has no completed cycle, or no rigid shift (``delta``), or ``cycle`` is
            out of range; ``TypeError`` if it is not an int.
        """
        if self.delta is None or not self.cycles:
            raise InputError("the history has no completed cycle with a rigid shift `delta` to draw a loop of")
        n = len(self.cycles)
        if isinstance(cycle, (bool, np.bool_)) or not isinstance(cycle, (int, np.integer)):
            raise InputTypeError(f"`cycle` = {show(cycle)} must be an int, the index of a completed cycle")
        if not -n <= cycle < n:
            raise InputError(f"`cycle` = {cycle} must index one of the {n} completed cycles, in [{-n}, {n - 1}]")
        i, j = self.cycles[cycle]
        return self.delta[i:j + 1], self.Q[i:j + 1]

    def stick_zone(self, k: int) -> tuple[float, float]:
        """The widest stick interval of state ``k``.

        Raises
        ------
        ValueError
            If nothing stuck in the step to state ``k`` (every point of the contact slipped).
        """
        zones = self.stick[k := self._state(k)]
        if not zones:
            raise InputError(f"state `k` = {k} has no stick interval: every point of its contact "
                             "slipped in the step to it")
        return max(zones, key=lambda z: z[1] - z[0])


def _intersect(runs: tuple[tuple[tuple[float, float], ...], ...]) -> tuple[tuple[float, float], ...]:
    """The points in every one of several sets of intervals, as intervals."""
    out = list(runs[0]) if runs else []
    for zones in runs[1:]:
        out = [(max(lo, l2), min(hi, h2)) for lo, hi in out for l2, h2 in zones if min(hi, h2) > max(lo, l2)]
    return tuple(out)


@dataclass(frozen=True)
class MarchedSteadyResult(SteadyStateResult):
    """The steady state of a cycle marched by a load history until two cycles agree (``method="auto"``).

    Where the superposition of docs/STEADY_STATE.md refuses (one end slips and the
    other shakes down, the ends slip in opposite senses, or the end contacts do not
    overlap), the load history (:func:`sie.load_history`) is marched cycle after
    cycle; its last cycle is the steady state.

    Attributes (beyond :class:`SteadyStateResult`)
    ----------
    history
        The marched :class:`HistoryResult`; its last cycle is the steady one.
    ends
        The history's state indices of the cycle's ends 0 and 1 in its last cycle.
    stick_intervals
        The permanent stick intervals: what stuck in every step of the last cycle
        (on the history's element edges; possibly reaching one contact edge, or
        none where the end contacts do not overlap). ``d``, ``e`` describe the
        widest; with none, ``d = e = 0`` and :attr:`stick_zone` raises.
    """

    history: HistoryResult | None = field(default=None, repr=False, compare=False)
    ends: tuple[int, int] = (0, 0)
    stick_intervals: tuple[tuple[float, float], ...] = ()

    @property
    def stick_zone(self) -> tuple[float, float]:
        if not self.stick_intervals:
            (l0, r0), (l1, r1) = ((-n.a, n.c) for n in self.normals)
            raise DisjointContactsError(
                f"no point stuck all through the marched cycle between the contacts [{l0:.6g}, {r0:.6g}] and "
                f"[{l1:.6g}, {r1:.6g}]: the cycle has no permanent stick zone (`stick_intervals` is empty)")
        return max(self.stick_intervals, key=lambda z: z[1] - z[0])

    def check(self) -> None:
        """The stick intervals inside both end contacts; Coulomb's law held in every state of the march
        (:func:`threepart.halfplane.coulomb.coulomb_state` refuses a shear past its bound)."""
        if self.stick_intervals:
            self.check_stick_zone()

    @classmethod
    def from_history(cls, history: HistoryResult, states: tuple[Any, Any], f: float, steps: int,
                     shakedown_share: float, method: str, info: dict[str, Any]) -> "MarchedSteadyResult":
        """The steady state of ``history``'s last cycle (``steps`` states a half-cycle, ending at state 0).

        ``shakedown``: the last cycle's energy is at most ``shakedown_share`` of the largest cycle's.
        """
        i, j = history.cycles[-1]
        ends = (j, i + steps)
        # the elements' stick intervals, cut to what is in contact all cycle (an end element may overhang it)
        lo = max(-history.normals[k].a for k in range(i, j + 1))
        touch = (((lo, min(history.normals[k].c for k in range(i, j + 1))),),)
        zones = _intersect(touch + tuple(history.stick[k] for k in range(i + 1, j + 1)))
        widest = max(zones, key=lambda z: z[1] - z[0]) if zones else (0.0, 0.0)
        energy = float(history.energy[-1])
        shakedown = energy <= shakedown_share * float(np.max(history.energy))
        return cls(normals=(history.normals[ends[0]], history.normals[ends[1]]), states=states, f=f,
                   d=0.5 * (widest[1] - widest[0]), e=-0.5 * (widest[0] + widest[1]),
                   energy=0.0 if shakedown else energy, shakedown=shakedown, method=method,
                   diagnostics=history.diagnostics, info=info, history=history, ends=ends,
                   stick_intervals=zones)

    def _cycle_states(self) -> range:
        assert self.history is not None
        i, j = self.history.cycles[-1]
        return range(i, j + 1)

    def shear(self, x: ArrayLike, state: int) -> np.ndarray:
        """Shear ``q(x)`` at the end ``state`` of the last marched cycle: the elements' values, linear
        between their midpoints over the end's contact, 0 at its ends (the march's shear, history and all)."""
        assert self.history is not None
        k = self.ends[self._state(state)]
        n = self.history.normals[k]
        xs, vs = self.history.x_nodes, self.history.q_nodes[k]
        inside = (xs > -n.a) & (xs < n.c)
        return np.interp(np.asarray(x, dtype=float), np.concatenate([[-n.a], xs[inside], [n.c]]),
                         np.concatenate([[0.0], vs[inside], [0.0]]), left=0.0, right=0.0)

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        """Half the range of the accumulated slip over the last marched cycle (eq. S7's amplitude)."""
        assert self.history is not None
        slips = np.array([self.history.slip(x, k) for k in self._cycle_states()])
        return 0.5 * (slips.max(axis=0) - slips.min(axis=0))

    def stress(self, x: ArrayLike, z: ArrayLike, state: int, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)`` at the end ``state``: pressure, :meth:`shear`, ``sigma_bulk``."""
        n = self.normals[k := self._state(state)]
        _in_range(x, z)
        cuts = [t for zone in self.stick_intervals for t in zone]
        return stress(x, z, pressure=n.pressure, shear=lambda t: self.shear(t, k), ends=(-n.a, n.c),
                      sigma_bulk=self.states[k][3], nu=nu, kinks=interior_kinks(n.punch.b, -n.a, n.c, *cuts))

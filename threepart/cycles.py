"""The results of load cycles: the periodic steady state and the marched load history.

Both build on the one result shape of :mod:`threepart.results` (their normal
solutions are :class:`~threepart.results.NormalResult` records) and share its
coordinate checks: every ``shear``, ``slip``, ``slip_amplitude`` and ``stress``
checks its ``x`` (and ``z``), and a steady state's shear at both ends is checked
against Coulomb's law when it is built (:mod:`threepart.answer`).

Names
-----
SteadyStateResult -- the periodic steady state of an in-phase cycle (docs/STEADY_STATE.md)
HistoryResult     -- a contact marched through a load history with the memory of slip
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
from numpy.typing import ArrayLike

from .answer import check_coulomb
from .punch import Punch
from .results import NU, Diagnostics, NormalResult, _Answer, _Edged, _kinks
from .stress import Stress, stress
from threepart.errors import InputError

__all__ = ["SteadyStateResult", "HistoryResult"]


@dataclass(frozen=True)
class SteadyStateResult(_Edged, _Answer):
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
        """Coulomb's law at both ends of the cycle (:func:`threepart.answer.check_coulomb`); none in shakedown."""
        if not self.shakedown:
            for k in (0, 1):
                check_coulomb(_End(self, k))

    def _state(self, state: Any) -> int:
        if isinstance(state, bool) or state not in (0, 1):
            raise InputError(f"`state` = {state!r} must be 0 or 1 (an end of the cycle)")
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

    def stress(self, x: ArrayLike, z: ArrayLike, state: int, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)`` at the end ``state``: pressure, :meth:`shear`, ``sigma_bulk``."""
        n = self.normals[k := self._state(state)]
        return stress(x, z, pressure=n.pressure, shear=lambda t: self.shear(t, k), ends=(-n.a, n.c),
                      sigma_bulk=self.states[k][3], nu=nu, kinks=_kinks(n.punch.b, -n.a, n.c, *self.stick_zone))


@dataclass(frozen=True)
class _End:
    """One end ``k`` of a steady cycle, seen as a partial-slip answer by :func:`~threepart.answer.check_coulomb`."""

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
class HistoryResult(_Answer):
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
        <threepart.history.History.cycles>`, the cycles in :attr:`cycles`).
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
            If the history has no completed cycle, or no rigid shift (``delta``).
        """
        if self.delta is None or not self.cycles:
            raise InputError("the history has no completed cycle with a rigid shift `delta` to draw a loop of")
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

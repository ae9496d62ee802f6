"""A worn profile's contact and fretting cycle on nodes: the wear march's discretisation (issue 39).

Eq. (0.1) of docs/WEAR.md, the displacement form of eq. (integral_equation), is
collocated at nodes with the pressure linear between them
(:func:`threepart.halfplane.surface.influence`) and solved by the core's active set
(:func:`threepart.halfplane.surface.solve_contact`). The partial slip is
Ciavarella–Jäger's on the same nodes: the corrective contact of the same profile at
the normal tilt under ``P - u/f`` (eqs. integral_equation_2, horizontal_equilibrium),
whose active nodes are the stick zone; ``q = f (p - p*)`` and a node outside the stick
zone slips by ``f G*``, ``G*`` the corrective contact's gap. A cycle follows by Masing's
rule (:class:`threepart.results.slip.MasingCycle`).

The global series of :mod:`sie.profile` resolves neither a pressure that falls to 0 over
the slip zones of a worn profile nor the singular ends that form at its stick zone's;
the nodes resolve both to their spacing.

NodeState          -- one state of the march: the normal and the corrective contact at Q_max
node_state         -- solve it
NodeNormalResult   -- the normal contact on nodes as the shared result shape
NodeFrettingResult -- the fretting cycle on nodes (WearResult.final of the SIE's march)
node_fretting      -- build it from a state
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from threepart.errors import InputError, StickSeparationError
from threepart.halfplane.surface import ContactSolution, solve_contact
from threepart.results import Diagnostics, NormalResult
from threepart.results.fields import stick_ends
from threepart.results.slip import MasingCycle

__all__ = ["NodeState", "node_state", "NodeNormalResult", "NodeFrettingResult", "node_fretting",
           "COULOMB_FLOOR"]

#: Coulomb's check on nodes: p* - p may exceed 0 by this fraction of the peak (the active sets' rounding)
COULOMB_FLOOR = 1e-6

_EDGES = ("a worn profile's edges are not the punch's: its pressure is singular at the stick zone's ends "
          "(closedform.wear_limit's K); no K_N, K_T record is built on nodes")


@dataclass(frozen=True)
class NodeState:
    """One marched state on the nodes: the normal contact and the corrective contact at ``Q_max``.

    ``p`` and ``p_star`` are the nodes' pressures; ``travel`` is ``∮|ds| = 4 f G*`` at the
    nodes that slip, ``G*`` the corrective contact's gap; ``rate = p travel``; ``work`` the
    friction work per cycle ``f Σ rate Δx``; ``stick`` and ``contact`` their ends.
    """

    normal: ContactSolution
    corrective: ContactSolution
    p: np.ndarray
    p_star: np.ndarray
    travel: np.ndarray
    rate: np.ndarray
    work: float
    stick: tuple[float, float]
    contact: tuple[float, float]


def _corrective(C: np.ndarray, x: np.ndarray, g: np.ndarray, alpha: float, P_star: float,
                start: ContactSolution | None) -> ContactSolution:
    """The corrective contact: the profile ``g`` at the tilt ``alpha`` under ``P_star`` (approach free)."""
    return solve_contact(C, x, g + alpha * x, P_star, 0.0, free_tilt=False,
                         active=None if start is None else start.active.copy())


def _stick(x: np.ndarray, p_star: np.ndarray, f: float) -> tuple[float, float]:
    """The corrective contact's ends, from ``p*^2 -> 0`` (:func:`threepart.results.fields.stick_ends`)."""
    return stick_ends(x, p_star, np.zeros(x.size), f)


def node_state(C: np.ndarray, x: np.ndarray, w: np.ndarray, g: np.ndarray, P: float, s: float, Q_max: float,
               f: float, free_tilt: bool, start: tuple[ContactSolution, ContactSolution] | None = None
               ) -> NodeState:
    """The normal contact of the worn profile ``g`` (at the nodes ``x``) and its corrective contact at ``Q_max``.

    ``C`` and ``w`` are :func:`threepart.halfplane.surface.influence`'s. A node of the contact
    outside the stick zone slips by ``f G*`` at ``Q_max`` (Masing:
    ``∮|ds| = 4 f G*`` per cycle). ``start``: the previous state's, whose active sets
    start the iterations.

    Raises
    ------
    StickSeparationError
        The corrective pressure exceeds the pressure at a node (the stick zone is not one
        interval of the contact).
    NoConvergenceError
        An active set that does not settle.
    """
    normal = solve_contact(C, x, g, P, s, free_tilt=free_tilt,
                           active=None if start is None else start[0].active.copy())
    cor = _corrective(C, x, g, normal.alpha, P - Q_max / f, None if start is None else start[1])
    p, p_star = normal.f / w, cor.f / w
    excess = p_star - p
    if np.max(excess) > COULOMB_FLOOR * np.max(p):
        i = int(np.argmax(excess))
        raise StickSeparationError(f"`Q_max`/(f P) = {Q_max / (f * P):.6g} on the worn profile: the corrective "
                                   f"pressure exceeds p by {excess[i]:.4g} at x = {x[i]:.6g}; the stick zone "
                                   "is not one interval")
    slips = normal.active & ~cor.active
    travel = np.where(slips, 4.0 * f * np.maximum(cor.gap, 0.0), 0.0)
    rate = p * travel
    on = np.flatnonzero(normal.active)
    return NodeState(normal=normal, corrective=cor, p=p, p_star=p_star, travel=travel, rate=rate,
                     work=f * float(np.sum(rate * w)), stick=_stick(x, p_star, f),
                     contact=(float(x[max(on[0] - 1, 0)]), float(x[min(on[-1] + 1, x.size - 1)])))


@dataclass(frozen=True)
class NodeNormalResult(NormalResult):
    """The normal contact of a worn profile on nodes, as the shared result shape.

    ``pressure(x)`` is linear between the nodes ``x_nodes`` (their values ``p_nodes``),
    0 outside the contact ``[-a, c]``.
    """

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    p_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        inside = (x > -self.a) & (x < self.c)
        return np.where(inside, np.interp(x, self.x_nodes, self.p_nodes), 0.0)

    def edges(self) -> Any:
        raise InputError(_EDGES)


@dataclass(frozen=True)
class NodeFrettingResult(MasingCycle):
    """The fretting cycle on a worn profile's nodes (:func:`node_fretting`), by Masing's rule.

    The loading state at ``u`` is the corrective contact under ``P - u/f`` on the same
    nodes, solved when first asked for.
    """

    nodes: Any = field(default=None, compare=False, repr=False)

    def _state(self, u: float) -> ContactSolution:
        return self.nodes(float(u))

    def _stick_load(self, u: float) -> tuple[float, float]:
        nrm = self.normal
        assert isinstance(nrm, NodeNormalResult)
        cor = self._state(u)
        return _stick(nrm.x_nodes, cor.f / self.info["weights"], self.f)

    def _q_load(self, x: np.ndarray, u: float) -> np.ndarray:
        if u == 0:
            return np.zeros(x.shape)
        nrm = self.normal
        assert isinstance(nrm, NodeNormalResult)
        p_star = self._state(u).f / self.info["weights"]
        q = self.f * (nrm.p_nodes - p_star)
        return np.where((x > -nrm.a) & (x < nrm.c), np.interp(x, nrm.x_nodes, q), 0.0)

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        if u == 0:
            return np.zeros(x.shape)
        nrm = self.normal
        assert isinstance(nrm, NodeNormalResult)
        cor = self._state(u)
        s = np.where(cor.active, 0.0, self.f * np.maximum(cor.gap, 0.0))
        return np.where((x > -nrm.a) & (x < nrm.c), np.interp(x, nrm.x_nodes, s), 0.0)

    def edges(self) -> Any:
        raise InputError(_EDGES)


def node_fretting(state: NodeState, C: np.ndarray, x: np.ndarray, w: np.ndarray, g: np.ndarray, *, punch: Any,
                  A: float, P: float, s: float, Q_max: float, f: float, tilt: str,
                  states: int = 21) -> NodeFrettingResult:
    """The fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of a marched state on its nodes.

    ``energy`` is the state's friction work ``f Σ p ∮|ds| Δx`` (eq. W15's local route);
    ``delta`` at the loading state ``u`` is ``f (D - D*(u))``, the approaches of the normal
    and the corrective contacts.
    """
    normal = NodeNormalResult(punch=punch, A=A, a=-state.contact[0], c=state.contact[1],
                              alpha=state.normal.alpha, P=P, s=s, tilt=tilt, method="sie",
                              diagnostics=Diagnostics(n=x.size, scheme="nodes"),
                              x_nodes=x, p_nodes=state.p)

    @lru_cache(maxsize=64)
    def corrective(u: float) -> ContactSolution:
        return _corrective(C, x, g, state.normal.alpha, P - u / f, state.corrective)

    u = np.linspace(0.0, Q_max, states)
    stick = np.array([_stick(x, corrective(float(v)).f / w, f) if v > 0 else normal_ends(state)
                      for v in u])
    delta = np.array([f * (state.normal.delta - corrective(float(v)).delta) if v > 0 else 0.0 for v in u])
    return NodeFrettingResult.from_loading(normal, Q_max, f, u, stick, delta, energy=state.work, method="sie",
                                           diagnostics=Diagnostics(n=x.size, scheme="nodes", steps=states),
                                           info={"weights": w}, nodes=corrective)


def normal_ends(state: NodeState) -> tuple[float, float]:
    """The stick zone at ``u = 0``: the whole contact."""
    return state.contact

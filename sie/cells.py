"""A worn profile's contact and fretting cycle on cells: the wear march's discretisation (issue 39).

Eq. (0.1) of docs/WEAR.md, the displacement form of eq. (integral_equation), is
collocated at the centres of uniform cells with the pressure uniform on each cell
(:func:`threepart.halfplane.surface.influence`) and solved by the core's active set
(:func:`threepart.halfplane.surface.solve_contact`). The partial slip is
Ciavarella–Jäger's on the same cells: the corrective contact of the same profile at
the normal tilt under ``P - u/f`` (eqs. integral_equation_2, horizontal_equilibrium),
whose active cells are the stick zone; ``q = f (p - p*)`` and a cell outside the stick
zone slips by ``f G*``, ``G*`` the corrective contact's gap. A cycle follows by Masing's
rule (:class:`threepart.results.slip.MasingCycle`).

The global series of :mod:`sie.profile` resolves neither a pressure that falls to 0 over
the slip zones of a worn profile nor the singular ends that form at its stick zone's;
the cells resolve both to their width.

CellState        -- one state of the march: the normal and the corrective contact at Q_max
cell_state       -- solve it
CellNormalResult -- the normal contact on cells as the shared result shape
CellFrettingResult -- the fretting cycle on cells (WearResult.final of the SIE's march)
cell_fretting    -- build it from a state
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

__all__ = ["CellState", "cell_state", "CellNormalResult", "CellFrettingResult", "cell_fretting",
           "COULOMB_FLOOR"]

#: Coulomb's check on cells: p* - p may exceed 0 by this fraction of the peak (the active sets' rounding)
COULOMB_FLOOR = 1e-6

_EDGES = ("a worn profile's edges are not the punch's: its pressure is singular at the stick zone's ends "
          "(closedform.wear_limit's K); no K_N, K_T record is built on cells")


@dataclass(frozen=True)
class CellState:
    """One marched state on the cells: the normal contact and the corrective contact at ``Q_max``.

    ``p`` and ``p_star`` are the cells' pressures; ``travel`` is ``∮|ds| = 4 f G*`` on the
    cells that slip, ``G*`` the corrective contact's gap; ``rate = p travel``; ``work`` the
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


def cell_state(C: np.ndarray, edges: np.ndarray, g: np.ndarray, P: float, s: float, Q_max: float,
               f: float, free_tilt: bool, start: tuple[ContactSolution, ContactSolution] | None = None
               ) -> CellState:
    """The normal contact of the worn profile ``g`` (at the cell centres) and its corrective contact at ``Q_max``.

    A cell of the contact outside the stick zone slips by ``f G*`` at ``Q_max`` (Masing:
    ``∮|ds| = 4 f G*`` per cycle). ``start``: the previous state's, whose active sets
    start the iterations.

    Raises
    ------
    StickSeparationError
        The corrective pressure exceeds the pressure on a cell (the stick zone is not one
        interval of the contact).
    NoConvergenceError
        An active set that does not settle.
    """
    x, width = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    normal = solve_contact(C, x, g, P, s, free_tilt=free_tilt,
                           active=None if start is None else start[0].active.copy())
    cor = _corrective(C, x, g, normal.alpha, P - Q_max / f, None if start is None else start[1])
    p, p_star = normal.f / width, cor.f / width
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
    return CellState(normal=normal, corrective=cor, p=p, p_star=p_star, travel=travel, rate=rate,
                     work=f * float(np.sum(rate * width)), stick=_stick(x, p_star, f),
                     contact=(float(edges[on[0]]), float(edges[on[-1] + 1])))


@dataclass(frozen=True)
class CellNormalResult(NormalResult):
    """The normal contact of a worn profile on cells, as the shared result shape.

    ``pressure(x)`` is linear between the cell centres ``x_cells`` (their values ``p_cells``),
    0 outside the contact ``[-a, c]``.
    """

    x_cells: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    p_cells: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        inside = (x > -self.a) & (x < self.c)
        return np.where(inside, np.interp(x, self.x_cells, self.p_cells), 0.0)

    def edges(self) -> Any:
        raise InputError(_EDGES)


@dataclass(frozen=True)
class CellFrettingResult(MasingCycle):
    """The fretting cycle on a worn profile's cells (:func:`cell_fretting`), by Masing's rule.

    The loading state at ``u`` is the corrective contact under ``P - u/f`` on the same
    cells, solved when first asked for.
    """

    cells: Any = field(default=None, compare=False, repr=False)

    def _state(self, u: float) -> ContactSolution:
        return self.cells(float(u))

    def _stick_load(self, u: float) -> tuple[float, float]:
        nrm = self.normal
        assert isinstance(nrm, CellNormalResult)
        cor = self._state(u)
        return _stick(nrm.x_cells, cor.f / np.diff(self.info["cell_edges"]), self.f)

    def _q_load(self, x: np.ndarray, u: float) -> np.ndarray:
        if u == 0:
            return np.zeros(x.shape)
        nrm = self.normal
        assert isinstance(nrm, CellNormalResult)
        p_star = self._state(u).f / np.diff(self.info["cell_edges"])
        q = self.f * (nrm.p_cells - p_star)
        return np.where((x > -nrm.a) & (x < nrm.c), np.interp(x, nrm.x_cells, q), 0.0)

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        if u == 0:
            return np.zeros(x.shape)
        nrm = self.normal
        assert isinstance(nrm, CellNormalResult)
        cor = self._state(u)
        s = np.where(cor.active, 0.0, self.f * np.maximum(cor.gap, 0.0))
        return np.where((x > -nrm.a) & (x < nrm.c), np.interp(x, nrm.x_cells, s), 0.0)

    def edges(self) -> Any:
        raise InputError(_EDGES)


def cell_fretting(state: CellState, C: np.ndarray, edges: np.ndarray, g: np.ndarray, *, punch: Any,
                  A: float, P: float, s: float, Q_max: float, f: float, tilt: str,
                  states: int = 21) -> CellFrettingResult:
    """The fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of a marched state on its cells.

    ``energy`` is the state's friction work ``f Σ p ∮|ds| Δx`` (eq. W15's local route);
    ``delta`` at the loading state ``u`` is ``f (D - D*(u))``, the approaches of the normal
    and the corrective contacts.
    """
    x = 0.5 * (edges[1:] + edges[:-1])
    normal = CellNormalResult(punch=punch, A=A, a=-state.contact[0], c=state.contact[1],
                              alpha=state.normal.alpha, P=P, s=s, tilt=tilt, method="sie",
                              diagnostics=Diagnostics(n=x.size, scheme="cells"),
                              x_cells=x, p_cells=state.p)

    @lru_cache(maxsize=64)
    def corrective(u: float) -> ContactSolution:
        return _corrective(C, x, g, state.normal.alpha, P - u / f, state.corrective)

    u = np.linspace(0.0, Q_max, states)
    width = np.diff(edges)
    stick = np.array([_stick(x, corrective(float(v)).f / width, f) if v > 0 else normal_ends(state)
                      for v in u])
    delta = np.array([f * (state.normal.delta - corrective(float(v)).delta) if v > 0 else 0.0 for v in u])
    return CellFrettingResult.from_loading(normal, Q_max, f, u, stick, delta, energy=state.work, method="sie",
                                           diagnostics=Diagnostics(n=x.size, scheme="cells", steps=states),
                                           info={"cell_edges": edges}, cells=corrective)


def normal_ends(state: CellState) -> tuple[float, float]:
    """The stick zone at ``u = 0``: the whole contact."""
    return state.contact

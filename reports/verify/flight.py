"""The flight cycle's marched history: the steady state reached by marching the load path.

A steady case of the catalogue (two ``states``, :attr:`Case.kind
<threepart.problem.catalogue.Case.kind>` ``"steady"``) is solved by every method with
a steady state (:mod:`reports.verify.runs`); this module adds the independent
reference of docs/STEADY_STATE.md §6: the load history marched with the memory
of slip over a few cycles (``sie.load_history``), whose last cycle must have
settled on the steady state. Its checks (the permanent stick zone's ends in
elements, the energy of the last cycle) go through the tolerance table under
``"<method>-history"`` like every other check of the run.

Names
-----
HISTORY_METHODS  -- the methods whose marched history the run adds, and why
load_path        -- the states of the march: state 0, then cycles of linear half-cycles
march            -- one method's marched history of a steady case
history_figures  -- (reference, obtained, error) of the last cycle against a steady state
history_checks   -- those figures judged against the tolerance table
last_cycle       -- the state indices of the last completed cycle
slip_amplitude   -- half the range of the slip over the last cycle
"""
from __future__ import annotations

import math
from importlib import import_module
from typing import Any

import numpy as np

from threepart import registry
from threepart.problem.catalogue import Case
from threepart.results.cycles import HistoryResult
from threepart.tolerances import tolerance

from ..compare import Check
from threepart.errors import InputError

__all__ = ["HISTORY_METHODS", "HISTORY_ELEMENTS", "HISTORY_STEPS", "HISTORY_CYCLES", "load_path", "march",
           "history_figures", "history_checks", "last_cycle", "slip_amplitude", "HISTORY_QUANTITIES"]

#: the methods whose marched history the verification run adds: the SIE's is seconds at
#: :data:`HISTORY_ELEMENTS`; the FEM's (``fem.load_history``) is minutes a cycle on the quick
#: mesh and is checked against the SIE's in tests/test_fem_history.py instead
HISTORY_METHODS = ("sie",)
#: shear elements over the union of the contacts: the flight case's slip zones are 0.006 and
#: 0.02 mm of a 3.2 mm contact, two and six elements at 1024 (energy 9e-4 off; 3.4 % at 512)
HISTORY_ELEMENTS = 1024
#: load steps a half-cycle and cycles marched (the first cycle settles it, the last is judged)
HISTORY_STEPS = 10
HISTORY_CYCLES = 3
#: the figures of a marched history against the steady state, in report order
HISTORY_QUANTITIES = ("stick_end", "cycle_energy")


def load_path(case: Case, steps: int = HISTORY_STEPS, cycles: int = HISTORY_CYCLES) -> list[tuple[float, ...]]:
    """State 0 (applied from the unloaded body in one step), then ``cycles`` cycles 0 -> 1 -> 0 in
    ``steps`` linear steps a half-cycle: the in-phase path of docs/STEADY_STATE.md §0."""
    if case.states is None:
        raise InputError(f"case {case.name!r} has no cycle (`states`)")
    s0, s1 = (np.asarray(st, float) for st in case.states)
    lam = np.linspace(0.0, 1.0, steps + 1)[1:]
    path = [tuple(s0)]
    for _ in range(cycles):
        for a, b in ((s0, s1), (s1, s0)):
            path += [tuple(a + t * (b - a)) for t in lam]
    return path


def march(method: str, case: Case) -> HistoryResult:
    """The history of ``case``'s cycle marched by ``method``'s ``load_history`` (its package's)."""
    if case.f is None:
        raise InputError(f"case {case.name!r} has no coefficient of friction `f`")
    load_history = getattr(import_module(registry.BUILTIN[method]), "load_history")
    return load_history(case.punch, load_path(case), case.f, A=case.A, n=HISTORY_ELEMENTS,
                        period=2 * HISTORY_STEPS)


def last_cycle(history: HistoryResult) -> range:
    """The state indices of the last completed cycle, its first state (a turning point) included."""
    start, end = history.cycles[-1]
    return range(start, end + 1)


def _element(history: HistoryResult) -> float:
    """The largest element (SIE) or node spacing (FEM) of the marched grid."""
    grid = history.edges if history.edges is not None else history.x_nodes
    return float(np.max(np.diff(np.asarray(grid, float))))


def history_figures(steady: Any, history: HistoryResult) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, error)``: the last marched cycle against ``steady``.

    ``stick_end``: the larger difference of the permanent stick zone's ends (the
    points that stick in every step of the last cycle) in the grid's elements
    ``h``; ``cycle_energy``: ``|ΔW|/W`` of the friction work of the last cycle.
    """
    states = last_cycle(history)[1:]     # each state: the step into it
    zones = [history.stick_zone(k) for k in states]
    left, right = max(z[0] for z in zones), min(z[1] for z in zones)
    (rl, rr) = steady.stick_zone
    dev = max(abs(left - rl), abs(right - rr))
    out = {"stick_end": (float(steady.d), 0.5 * (right - left),
                         dev / _element(history) if math.isfinite(dev) else math.inf),
           "cycle_energy": (float(steady.energy), float(history.energy[-1]),
                            abs(float(history.energy[-1]) - steady.energy) / steady.energy
                            if steady.energy > 0 else abs(float(history.energy[-1])))}
    return out


def history_checks(steady: Any, history: HistoryResult, method: str) -> list[Check]:
    """:func:`history_figures` judged against the tolerance table's ``"<method>-history"`` rows."""
    comparison = f"{method}-history"
    checks = []
    for q, (r, o, err) in history_figures(steady, history).items():
        tol = tolerance(comparison, q)
        checks.append(Check(comparison, q, r, o, err if math.isfinite(err) else math.inf, tol.limit,
                            tol.reason))
    return checks


def slip_amplitude(history: HistoryResult, x: Any) -> np.ndarray:
    """Half the range of the accumulated slip over the last cycle at ``x``."""
    slips = np.array([history.slip(x, k) for k in last_cycle(history)])
    return 0.5 * (slips.max(axis=0) - slips.min(axis=0))

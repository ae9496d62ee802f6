"""Load histories: the states ``(P, s, Q, sigma_bulk)`` a contact is marched through, and their cycles.

What the SIE and the FEM load histories (:func:`sie.load_history`,
:func:`fem.load_history`) share: the one reader and check of a history
(a sequence of states or a CSV file), the cycles it completes, and the
friction work of one step.

read_history    -- the states of a CSV file with the columns ``P, s, Q, sigma_bulk``
check_history   -- a sequence of states (or a CSV path) as a checked :class:`History`
check_period    -- the states per cycle, when a history gives them
History         -- the checked states, with their completed cycles
stuck           -- the points that did not slip in a step (the stick intervals' points)
step_work       -- the friction work of one step, ``Σ |Δslip| (f p_(k-1) + f p_k)/2``
MAX_HISTORY     -- the most states of a history
"""
from __future__ import annotations

import csv
import io
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from .steady import state_values
from ..problem.checks import finite, integer, positive, show
from threepart.errors import InputError, InputTypeError, ReaderError
from threepart.textfile import read_text

__all__ = ["History", "read_history", "check_history", "check_period", "stuck", "step_work", "MAX_HISTORY", "COLUMNS"]

#: the columns of a history, in the order of a state tuple
COLUMNS = ("P", "s", "Q", "sigma_bulk")
#: the most states of a history (each costs a normal solve and a Coulomb state)
MAX_HISTORY = 100_000
#: two states are the same point of the cycle when all four values agree to this fraction
#: of each column's largest magnitude (states typed in decimals, or computed by a sine)
SAME_STATE = 1e-12


@dataclass(frozen=True)
class History:
    """Checked load states, in order.

    Attributes
    ----------
    P, s, Q, sigma_bulk
        One value per state: normal load (> 0), its lever arm, the shear force
        the punch exerts on the substrate along +x and the substrate's bulk stress.
    """

    P: np.ndarray
    s: np.ndarray
    Q: np.ndarray
    sigma_bulk: np.ndarray

    def __len__(self) -> int:
        return len(self.P)

    def state(self, k: int) -> tuple[float, float, float, float]:
        """The ``k``-th state ``(P, s, Q, sigma_bulk)``."""
        return float(self.P[k]), float(self.s[k]), float(self.Q[k]), float(self.sigma_bulk[k])

    def cycles(self, period: int | None = None) -> tuple[tuple[int, int], ...]:
        """The completed cycles ``(start, end)`` of state indices.

        A history closes its cycles where it ends (a flight cycle ends on the
        ground, a fretting cycle at its turning point). With ``period`` the
        cycles are the blocks of ``period`` steps that end at the last state.
        Without it a cycle ends at each state equal to the last one (to
        :data:`SAME_STATE` of each column's largest magnitude) that is reached
        the way the last one is (each column rising, falling or held as in the
        last step); the first state starts one if it equals the last (a
        history that starts where it ends). A state passed twice in a cycle
        (a zero crossing, up and then down) closes it once.
        """
        K = len(self.P)
        if period is not None:
            ends = np.arange(K - 1, -1, -period)[::-1]
        else:
            cols = np.column_stack([self.P, self.s, self.Q, self.sigma_bulk])
            scale = np.maximum(np.abs(cols).max(axis=0), 1e-300)

            step = np.diff(cols, axis=0)
            way = np.where(np.abs(step) <= SAME_STATE * scale, 0.0, np.sign(step))   # up, down or held

            def same(i: int, j: int) -> bool:
                return bool(np.all(np.abs(cols[i] - cols[j]) <= SAME_STATE * scale))

            ends = np.array([k for k in range(K) if same(k, K - 1)
                             and (k == 0 or np.array_equal(way[k - 1], way[K - 2]))], dtype=int)
        return tuple((int(i), int(j)) for i, j in zip(ends[:-1], ends[1:]))


def _value(where: str, column: str, text: Any) -> float:
    """One entry as a float; ``ValueError`` naming where it is and the column."""
    try:
        v = float(text)
    except (TypeError, ValueError):
        raise InputError(f"{where}, column `{column}`: {show(text)} is not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{where}, column `{column}`: {show(text)} must be a finite number")
    if column == "P" and v <= 0:
        raise InputError(f"{where}, column `P`: {show(text)} must be > 0 (a compressive normal load)")
    return v


def read_history(path: str | os.PathLike[str]) -> History:
    """The states of a CSV file with a header naming the columns ``P, s, Q, sigma_bulk`` (any order).

    Other columns are ignored. Rows are counted as the file's lines (the header is row 1).
    The file is UTF-8 text; a byte-order mark (as spreadsheets write one) is dropped.

    Raises
    ------
    ReaderError
        One line naming the file and, where it applies, the row and the column
        (a ValueError): an unreadable, binary or non-UTF-8 file
        (:func:`threepart.textfile.read_text`), a missing column, a short row, an
        entry that is not a finite number (``nan``, ``inf``, ``1e400``), a ``P``
        that is not > 0, no states, more than :data:`MAX_HISTORY`.
    """
    name = os.fspath(path)
    label = f"history file {name!r}"
    try:
        rows = list(csv.reader(io.StringIO(read_text(name, label), newline="")))
    except csv.Error as exc:
        raise ReaderError(f"{label} cannot be read as CSV: {exc}") from None
    if not rows:
        raise ReaderError(f"{label} is empty: it needs a header {', '.join(COLUMNS)}")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in COLUMNS if c not in header]
    if missing:
        raise ReaderError(f"{label} has no column `{missing[0]}` (its header is "
                          f"{', '.join(header)}; it needs {', '.join(COLUMNS)})")
    index = [header.index(c) for c in COLUMNS]
    states = []
    try:
        for line, row in enumerate(rows[1:], start=2):
            if not any(cell.strip() for cell in row):
                continue                     # a blank line
            where = f"{label}, row {line}"
            if len(row) < len(header):
                raise ReaderError(f"{where}: {len(row)} entries, the header has {len(header)}")
            states.append(tuple(_value(where, c, row[i]) for c, i in zip(COLUMNS, index)))
        if not states:
            raise ReaderError(f"{label} has no states below its header")
        return _history(states, label)
    except InputError as exc:           # an entry's (or the count's) check: the file is at fault
        raise ReaderError(str(exc)) from None


def _history(states: Sequence[tuple[float, ...]], what: str) -> History:
    if len(states) > MAX_HISTORY:
        raise InputError(f"{what} has {len(states)} states, more than MAX_HISTORY = {MAX_HISTORY}")
    P, s, Q, sb = (np.array(col, dtype=float) for col in zip(*states))
    return History(P=P, s=s, Q=Q, sigma_bulk=sb)


def check_history(history: Any) -> History:
    """``history`` as a :class:`History`: a sequence of ``(P, s, Q, sigma_bulk)`` states, a CSV path or a History.

    Raises
    ------
    TypeError
        ``history`` is none of these, a state is neither a sequence of four nor a mapping with the
        keys ``P, s, Q, sigma_bulk``, or a value is not a real number (a bool, a string, a Decimal:
        as :func:`threepart.halfplane.steady.check_cycle_states`, through :mod:`threepart.problem.checks`).
    ValueError
        Naming the state (counted from 0) and the value: ``P`` not > 0, a value not finite or past
        double precision, more than :data:`MAX_HISTORY` states.
    """
    if isinstance(history, History):
        return history
    if isinstance(history, (str, Path)):
        return read_history(history)
    if not isinstance(history, (Sequence, np.ndarray)):
        raise InputTypeError(f"`history` must be a sequence of (P, s, Q, sigma_bulk) states or a CSV path, "
                        f"not {type(history).__name__}")
    if len(history) == 0:
        raise InputError("`history` has no states")
    if len(history) > MAX_HISTORY:
        raise InputError(f"`history` has {len(history)} states, more than MAX_HISTORY = {MAX_HISTORY}")
    states = []
    for k, state in enumerate(history):
        P, s, Q, sb = state_values(state, f"`history` state {k}", InputTypeError)   # as a steady state's
        states.append((positive(f"history[{k}].P", P), *(finite(f"history[{k}].{c}", v)
                                                            for c, v in zip(COLUMNS[1:], (s, Q, sb)))))
    return _history(states, "`history`")


def check_period(period: Any, history: History) -> int | None:
    """``period`` (states per cycle) as an int in ``[1, len(history) - 1]``, or None."""
    if period is None:
        return None
    return integer("period", period, 1, max(1, len(history) - 1))


#: a point whose slip increment is below this fraction of the largest ``|w|`` has not slipped
#: (a point held at its bound with no increment slips by rounding, ~1e-12 of ``|w|``)
STUCK = 1e-9


def stuck(stick: np.ndarray, touch: np.ndarray, w: np.ndarray, dw: np.ndarray) -> np.ndarray:
    """The points in contact that did not slip in a step: the active set's stick points and the
    slip points whose increment ``dw`` is rounding (below :data:`STUCK` of the largest ``|w|``)."""
    scale = float(np.abs(w[touch]).max(initial=0.0))
    return touch & (stick | (np.abs(dw) <= STUCK * scale))


def step_work(bound_prev: np.ndarray, bound: np.ndarray, dslip: np.ndarray) -> float:
    """Friction work of one step, ``Σ_i |Δslip_i| (bound_(k-1),i + bound_k,i)/2``.

    On a slipping point ``|q| = f p``, and the shear opposes the slip, so the
    work ``q · Δslip`` is the slip times the Coulomb bound; the bound is
    averaged over the step (the trapezoid rule in the state index). ``dslip``
    must be zero where a point sticks or is out of contact at either state.
    """
    return float(np.sum(np.abs(dslip) * 0.5 * (bound_prev + bound)))

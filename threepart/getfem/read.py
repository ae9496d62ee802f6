"""The one reader of what a GetFEM script writes (``name.getfem.json``), and the figures drawn from it.

The sidecar holds every recorded state's loads, the cap's displacement, the
multiplier's resultants and the surface fields; its VTU files carry the same
fields for other tools (and are read by :mod:`threepart.readers.meshfile`).

Names
-----
State        -- one recorded state: loads, cap displacement, resultants, x, p, q, slip
GetfemRun    -- a whole run: its states, Newton's steps, its parameters and time
read_run     -- read a ``.getfem.json`` sidecar
loop_energy  -- the energy per cycle, the area of the ``Q``-``delta`` loop (Simpson's rule per branch)
slip_ends    -- the stick zone's ends from the slip field: where it starts, ``slip^(2/3)`` extrapolated
SLIP_NOISE   -- the slip below which a node counts as sticking, of the largest slip
last_cycle   -- the last complete cycle of recorded states (any code's: P, s, Q, sigma_bulk, x, q, slip)
friction_work -- the friction work of recorded states, ``Σ ∫ (q_k + q_k+1)/2 (slip_k+1 - slip_k) dx``
slip_amplitude -- half the range of each node's slip over recorded states
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from threepart.errors import ReaderError

__all__ = ["State", "GetfemRun", "read_run", "loop_energy", "slip_ends", "SLIP_NOISE", "FORMAT", "last_cycle",
           "friction_work", "slip_amplitude"]

#: the sidecar's format tag (the script writes it)
FORMAT = "threepart-getfem-1"
#: a node sticks where its slip is below this fraction of the largest slip in the contact: the
#: sticking nodes' slip is Newton's noise, <= 3e-3 of the largest (Hertz, W/h = 128)
SLIP_NOISE = 1e-2


@dataclass(frozen=True)
class State:
    """One recorded state of a GetFEM run (the substrate's surface nodes, sorted by ``x``).

    Attributes
    ----------
    P, Q, branch
        The loads and the cycle's branch (``"loading"``, ``"unloading"``, ``"reloading"``).
    delta
        The cap's tangential displacement since the normal load (the punch's, relative to the clamped base).
    resultant
        ``(∫p, ∫q, ∫x p)`` integrated from the multiplier itself.
    x, p, q, slip
        Nodes, pressure (compressive positive), shear on the substrate along +x, and
        the punch's tangential displacement relative to the substrate since the normal load.
    file
        The state's VTU file.
    s, sigma_bulk
        The lever arm of ``P`` and the substrate's bulk stress (a sidecar before them: NaN, 0).
    """

    P: float
    Q: float
    branch: str
    delta: float
    resultant: tuple[float, float, float]
    x: np.ndarray
    p: np.ndarray
    q: np.ndarray
    slip: np.ndarray
    file: str = ""
    s: float = float("nan")
    sigma_bulk: float = 0.0


@dataclass(frozen=True)
class GetfemRun:
    """What a GetFEM script wrote: its states in order, Newton's steps, its parameters and time."""

    states: list[State]
    steps: list[dict[str, Any]]
    params: dict[str, Any]
    time: float
    dofs: int
    model: str = ""
    path: Path | None = None
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def last(self) -> State:
        """The last recorded state (what ``name.vtu`` holds)."""
        return self.states[-1]


def read_run(path: str | Path, *, arg: str = "path") -> GetfemRun:
    """Read a GetFEM run's sidecar ``name.getfem.json``.

    Raises
    ------
    ReaderError
        A file that is not JSON, not a threepart GetFEM sidecar, or has no state.
    """
    path = Path(path)
    try:
        data = json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ReaderError(f"`{arg}` = {str(path)!r} is not a readable JSON file: {exc}") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ReaderError(f"`{arg}` = {str(path)!r} is not a threepart GetFEM sidecar (no format {FORMAT!r})")
    try:
        states = [State(P=float(s["P"]), Q=float(s["Q"]), branch=str(s["branch"]), delta=float(s["delta"]),
                        resultant=tuple(float(v) for v in s["resultant"]),  # type: ignore[arg-type]
                        x=np.asarray(s["x"], float), p=np.asarray(s["p"], float),
                        q=np.asarray(s["q"], float), slip=np.asarray(s["slip"], float),
                        file=str(s.get("file", "")),
                        s=float(s.get("s", data["params"].get("s", float("nan")))),
                        sigma_bulk=float(s.get("sigma_bulk", 0.0))) for s in data["states"]]
        run = GetfemRun(states=states, steps=list(data["steps"]), params=dict(data["params"]),
                        time=float(data["time"]), dofs=int(data["dofs"]), model=str(data.get("model", "")),
                        path=path, info={"grid": data.get("grid"), "getfem": data.get("getfem")})
    except (KeyError, TypeError, ValueError) as exc:
        raise ReaderError(f"`{arg}` = {str(path)!r}: a malformed GetFEM sidecar ({type(exc).__name__}: {exc})") from None
    if not states:
        raise ReaderError(f"`{arg}` = {str(path)!r} holds no state")
    bad = [k for k, s in enumerate(states) if not (np.all(np.isfinite(s.p)) and np.all(np.isfinite(s.q)))]
    if bad:
        raise ReaderError(f"`{arg}` = {str(path)!r}: the fields of state {bad[0] + 1} are not finite")
    return run


def _simpson(Q: np.ndarray, y: np.ndarray) -> float:
    """``∫ y dQ`` over equal steps: Simpson's rule on an even number of steps (trapezoids else)."""
    n = len(Q) - 1
    if n < 2 or n % 2:
        return float(np.trapezoid(y, Q))
    dQ = (Q[-1] - Q[0]) / n
    return float(dQ / 3 * (y[0] + y[-1] + 4 * y[1:-1:2].sum() + 2 * y[2:-1:2].sum()))


def loop_energy(run: GetfemRun) -> dict[str, float]:
    """The energy dissipated per cycle: the area of the ``Q``-``delta`` loop of a fretting run.

    The unloading and reloading branches (each from its reversal) are integrated
    as ``∮ delta dQ`` (the area, whatever the elastic part) by Simpson's rule
    and by trapezoids; their difference is the integration's error estimate.

    Raises
    ------
    ReaderError
        For a run without both reversal branches.
    """
    last_load = [s for s in run.states if s.branch == "loading"]
    branches = {}
    for name in ("unloading", "reloading"):
        states = [s for s in run.states if s.branch == name]
        if not states or not last_load:
            raise ReaderError(f"the run has no {name} branch: it is not a fretting cycle")
        start = last_load[-1] if name == "unloading" else [s for s in run.states if s.branch == "unloading"][-1]
        Q = np.array([start.Q] + [s.Q for s in states])
        delta = np.array([start.delta] + [s.delta for s in states])
        branches[name] = (Q, delta)
    # ∮ delta dQ: down the unloading branch (Q decreasing, so its integral is signed) and up the
    # reloading one; the area is ∫(delta_unloading - delta_reloading) dQ over [-Q_max, Q_max]
    simpson = -(_simpson(*branches["unloading"]) + _simpson(*branches["reloading"]))
    trap = -sum((float(np.trapezoid(branches[k][1], branches[k][0])) for k in ("unloading", "reloading")), 0.0)
    return {"energy": abs(simpson), "trapezoid": abs(trap)}


def slip_ends(x: np.ndarray, slip: np.ndarray, inside: tuple[float, float],
              noise: float = SLIP_NOISE) -> tuple[float, float]:
    """The stick zone's ends ``(left, right)`` from the slip field of a partial-slip state.

    A node of the contact ``inside = (left end, right end)`` sticks where
    ``|slip|`` is below ``noise`` of the largest; the stick zone is the
    longest run of them. Past a stick-slip end the slip grows as the distance
    to the power 3/2 (the shear's square-root kink integrated), so each end is
    where ``|slip|^(2/3)``, linear through the first two slipping nodes outside,
    reaches zero -- exact for a pure 3/2 power, and free of the traction's
    node-to-node noise that the ratio ``|q|/(f p)`` carries near the end.

    Raises
    ------
    ReaderError
        When no node of the contact sticks, or the stick zone reaches an end
        of the contact (no slip zone on that side to extrapolate from).
    """
    x, slip = np.asarray(x, float), np.abs(np.asarray(slip, float))
    on = np.flatnonzero((x > inside[0]) & (x < inside[1]))
    if on.size < 5:
        raise ReaderError(f"fewer than 5 nodes lie in the contact {inside}")
    stick = slip[on] < noise * float(np.max(slip[on]))
    if not np.any(stick) or stick[0] or stick[-1]:
        raise ReaderError("no node sticks, or the stick zone reaches an end of the contact: no slip "
                          "zone on each side")
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stick.astype(int), [0]]))).reshape(-1, 2)
    lo, hi = max(edges, key=lambda r: r[1] - r[0])
    first, last = on[lo], on[hi - 1]

    def root(near: int, far: int) -> float:
        s2 = slip[[near, far]] ** (2.0 / 3.0)
        return float(x[near] - s2[0] * (x[far] - x[near]) / (s2[1] - s2[0]))

    return root(first - 1, first - 2), root(last + 1, last + 2)


def _loads(st: Any) -> tuple[float, float, float, float]:
    """A recorded state's ``(P, s, Q, sigma_bulk)``; a code that records no ``s`` or bulk stress: 0
    (no ``P`` or ``Q``: NaN, which closes no cycle)."""
    def value(name: str, missing: float) -> float:
        v = getattr(st, name, None)
        v = missing if v is None else float(v)
        return missing if math.isnan(v) else v

    return value("P", math.nan), value("s", 0.0), value("Q", math.nan), value("sigma_bulk", 0.0)


def last_cycle(states: Sequence[Any]) -> tuple[int, int] | None:
    """``(start, end)``: the indices of the last complete cycle of recorded states, or None.

    A cycle ends at the last state and starts at the state before it that has the
    same loads ``(P, s, Q, sigma_bulk)`` reached the same way
    (:meth:`threepart.halfplane.load_history.History.cycles`): a fretting run's ``Q_max`` at the end
    of loading, a flight cycle's second-last ``state1``. Any code's states that carry
    ``P`` and ``Q`` (``s``, ``sigma_bulk`` where recorded).
    """
    from threepart.halfplane.load_history import History

    if len(states) < 2:
        return None
    P, s, Q, sb = (np.array(col) for col in zip(*(_loads(st) for st in states)))
    cycles = History(P=P, s=s, Q=Q, sigma_bulk=sb).cycles()
    return cycles[-1] if cycles else None


def _fields(states: Sequence[Any]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``x`` (the first state's nodes) and every state's ``q`` and ``slip`` on them, ``(K, n)``."""
    x = np.asarray(states[0].x, float)
    q, w = [], []
    for st in states:
        xs = np.asarray(st.x, float)
        same = xs.shape == x.shape and np.array_equal(xs, x)
        q.append(np.asarray(st.q, float) if same else np.interp(x, xs, st.q, left=0.0, right=0.0))
        w.append(np.asarray(st.slip, float) if same else np.interp(x, xs, st.slip))
    return x, np.array(q), np.array(w)


def friction_work(states: Sequence[Any], stride: int = 1) -> float:
    """The friction work of ``states`` in order, ``Σ_k ∫ (q_k + q_k+1)/2 (slip_k+1 - slip_k) dx``.

    ``q`` the shear the punch exerts on the substrate along +x and ``slip`` the punch's
    tangential displacement relative to the substrate: a slipping point's shear has
    the sign of its slip increment, so the work is positive. Per unit length (N mm/mm),
    the trapezoid rule in the state index (``stride``: every so many states, the
    first and last kept when they fall on it) and over the nodes.
    """
    x, q, w = _fields(states[::stride])
    rate = 0.5 * (q[1:] + q[:-1]) * np.diff(w, axis=0)
    return float(np.sum(np.trapezoid(rate, x, axis=1)))


def slip_amplitude(states: Sequence[Any]) -> tuple[np.ndarray, np.ndarray]:
    """``(x, amplitude)``: half the range of each node's slip over ``states`` (those of one cycle)."""
    x, _, w = _fields(states)
    return x, 0.5 * (w.max(axis=0) - w.min(axis=0))

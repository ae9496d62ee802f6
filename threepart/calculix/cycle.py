"""CalculiX load histories with friction: a flight cycle, and every recorded state of a run (issue 38).

A load history is a sequence of states ``(P, s, Q, sigma_bulk)``
(:func:`threepart.halfplane.load_history.check_history`): the deck of :func:`~.friction.friction_deck`
loads the first state's ``P`` at its ``s``, then reaches each state in turn in a step of
equal increments, the corners' forces, ``Q`` and the block's sides' forces moving linearly.
A flight cycle is ``[state0, state1, state0, state1]``; its steady state is the
reference (:func:`threepart.steady_state`).

Names
-----
load_history -- mesh, write, run and read a load history: every recorded state, the energy of its last cycle
CcxState     -- one recorded increment of a friction run: its loads, ``x``, ``p``, ``q`` and the slip
frd_states   -- every recorded increment of a friction run's ``.frd`` as ``CcxState`` (the reader's ``info["states"]``)
step_loads   -- each step's target ``(P, s, Q, sigma_bulk)`` from the deck beside a ``.frd``
printed_displacements -- a node set's displacements at each increment from a run's ``.dat``
read_traction -- ``(x, p, q, info)`` of a friction run's ``.frd``, last increment (threepart.readers.read uses it)
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from threepart.errors import InputError, ReaderError

from .friction import (FrictionResult, contact_rows, step_increments, run_steps, traction_state, contact_traction,
                       cycle_energy, read_frd_states, side_weights)

if TYPE_CHECKING:   # pragma: no cover
    from ..problem.punch import Punch

__all__ = ["load_history", "CcxState", "frd_states", "step_loads", "printed_displacements", "read_traction"]

#: the friction deck's header line of each state (``friction_deck``)
_STATE_LINE = re.compile(r"^\*\* state (\d+) \(step (\d+)\): P = (\S+), s = (\S+), Q = (\S+), "
                         r"sigma_bulk = (\S+)$", re.M)


@dataclass(frozen=True)
class CcxState:
    """One recorded increment of a CalculiX friction run (the block's slave nodes, sorted by ``x``).

    Attributes
    ----------
    P, s, Q, sigma_bulk
        The loads the deck applied at this increment (linear within a step between its
        targets, :func:`step_loads`); ``None`` where no deck lies beside the ``.frd``.
    step, time
        ccx's step and total time (each step one unit).
    x, p, q
        As :func:`~.friction.contact_traction`: undeformed ``x``, CPRESS, and the shear the
        punch exerts on the block along ``+x`` (``-CSHEAR1``).
    slip
        The punch's tangential displacement relative to the block along ``+x`` since the
        run's start (``-CSLIP1`` of CDIS: a slipping node's ``q`` has its increment's sign).
    """

    P: float | None
    s: float | None
    Q: float | None
    sigma_bulk: float | None
    step: int
    time: float
    x: np.ndarray
    p: np.ndarray
    q: np.ndarray
    slip: np.ndarray


def step_loads(inp: Path) -> list[tuple[float, float, float, float]] | None:
    """Each step's target ``(P, s, Q, sigma_bulk)`` (step 1 the normal load: ``Q = sigma_bulk = 0``)
    from the header of threepart's friction deck ``inp``; ``None`` if it is absent or not one."""
    if not inp.is_file():
        return None
    text = inp.read_text(errors="replace")
    rows = _STATE_LINE.findall(text)
    if not rows:
        return None
    try:
        states = [tuple(float(v) for v in r[2:]) for r in rows]
    except ValueError:
        return None
    P0, s0 = states[0][0], states[0][1]
    return [(P0, s0, 0.0, 0.0), *states]      # type: ignore[list-item]


def _loads_at(targets: list[tuple[float, float, float, float]], time: float
              ) -> tuple[float, float, float, float]:
    """The loads at total ``time``: step ``k`` (time ``k - 1`` to ``k``) moves its targets linearly
    from the last step's (from zero in step 1); ``s`` from the interpolated moment ``P s``."""
    ends = np.arange(len(targets) + 1, dtype=float)
    rows = np.array([[0.0, 0.0, 0.0, 0.0]] + [[P, P * s, Q, sb] for P, s, Q, sb in targets])
    P, Ps, Q, sb = (float(np.interp(time, ends, rows[:, j])) for j in range(4))
    return P, (Ps / P if P > 0 else targets[0][1]), Q, sb


def frd_states(path: str | Path, *, arg: str = "path") -> list[CcxState]:
    """Every recorded increment of a surface-to-surface friction run's ``.frd`` as :class:`CcxState`.

    The loads come from threepart's friction deck beside it (``.inp``, :func:`step_loads`);
    without it they are ``None``. An increment whose CONTACT block is missing (the normal
    step of a run that wrote none) is left out.
    """
    from .read import read_frd_nodes

    path = Path(path)
    stem = path.with_suffix("")
    xy = read_frd_nodes(path, arg=arg)
    targets = step_loads(stem.with_suffix(".inp"))
    out = []
    for step, time, blocks in read_frd_states(stem):
        if not blocks.get("CONTACT"):
            continue
        try:
            x, v = contact_rows(blocks, xy)
        except InputError as exc:
            raise ReaderError(f"`{arg}` = {str(path)!r}, step {step} at time {time:g}: {exc}") from None
        P, s, Q, sb = _loads_at(targets, time) if targets else (None, None, None, None)
        out.append(CcxState(P=P, s=s, Q=Q, sigma_bulk=sb, step=step, time=time, x=x, p=v[:, 3],
                            q=-v[:, 4], slip=-v[:, 1]))
    if not out:
        raise ReaderError(f"`{arg}` = {str(path)!r} holds no increment with contact output (CSTR, CDIS)")
    return out


def printed_displacements(stem: Path, nset: str) -> tuple[np.ndarray, dict[int, np.ndarray]]:
    """``(t, {node: (K, 2) displacements})`` of the node set ``nset`` at each of the ``K`` increments
    ``*NODE PRINT`` wrote to ``stem.dat`` (the rows follow the header until a blank line)."""
    times: list[float] = []
    rows: dict[int, list[list[float]]] = {}
    lines = Path(f"{stem}.dat").read_text().splitlines()
    for i, ln in enumerate(lines):
        if ln.strip().startswith("displacements") and f"set {nset} " in ln + " ":
            times.append(float(ln.split()[-1]))
            for row in lines[i + 2:]:
                if not row.strip():
                    break
                v = row.split()
                rows.setdefault(int(v[0]), []).append([float(v[1]), float(v[2])])
    return np.array(times), {k: np.array(v) for k, v in rows.items()}


def load_history(punch: Punch, history: Any, f: float, E: float, nu: float, *, n: float = 100.0,
                 tilt: str = "free", workdir: Path, increments: int = 8, slope: float | None = None,
                 name: str = "history") -> list[FrictionResult]:
    """A load history by CalculiX: the first state's normal load, then each state in turn.

    Parameters
    ----------
    punch, f, E, nu
        The punch (eq. 2), the coefficient of friction and both bodies' material.
    history
        The states ``(P, s, Q, sigma_bulk)`` (:func:`threepart.halfplane.load_history.check_history`: states,
        a CSV path or a ``History``); a flight cycle is ``[state0, state1, state0, state1]``.
    n, tilt, workdir, increments, slope
        As :func:`~.friction.partial_slip`: ``W / h`` of the mesh (sized for the first state's
        contact), the lid, where ccx runs, increments per state, the stick slope.

    Returns
    -------
    list of FrictionResult
        Every recorded state (as :func:`~.friction.fretting_cycle`'s), ``info["s"]`` and
        ``info["sigma_bulk"]`` its loads; ``info["energy"]`` the energy dissipated over the
        history's last complete cycle (``-∮ u·dF`` of the punch's top and the block's sides,
        :func:`~.friction.cycle_energy`; ``None`` if it closes none), ``info["cycle"]`` its
        state indices.
    """
    from threepart.halfplane.load_history import check_history

    from .read import read_frd_nodes

    hist = check_history(history)
    P0, s0 = float(hist.P[0]), float(hist.s[0])
    model, stem, info = run_steps(punch, P0, s0, [], f, E, nu, n=n, increments=increments, slope=slope,
                             tilt=tilt, workdir=workdir, name=name, history=hist)
    targets = step_loads(stem.with_suffix(".inp"))
    if targets is None:
        raise ReaderError(f"{stem}.inp lists no states: not threepart's friction deck")
    cycles = hist.cycles()
    energy = None
    if cycles:
        start, end = cycles[-1]
        energy = _history_energy(model, stem, targets, tilt, (start + 2, end + 2))
    info = dict(info, energy=energy, cycle=cycles[-1] if cycles else None)
    xy = read_frd_nodes(stem)
    out = []
    for step, tt, blk in read_frd_states(stem):
        P, s, Q, sb = _loads_at(targets, tt)
        out.append(traction_state(blk, xy, P=P, Q=Q, f=f, info=dict(info, time=tt, step=step, s=s, sigma_bulk=sb)))
    return out


def _history_energy(model: Any, stem: Path, targets: list[tuple[float, float, float, float]], tilt: str,
                    span: tuple[int, int]) -> float:
    """The work of the punch's top's loads and the block's sides' over the total times ``span``."""
    tl, tr = model.control_nodes()
    xL, xR = model.xy[tl - 1, 0], model.xy[tr - 1, 0]
    T = float(model.xy[tl - 1, 1])
    t, ctrl = printed_displacements(stem, "NCTRL")
    cols = [ctrl[tl][:, 0], ctrl[tl][:, 1], ctrl[tr][:, 0], ctrl[tr][:, 1]]
    bulk = any(st[3] != 0.0 for st in targets)
    if bulk:                       # the sides' generalised displacement: sum of w_i u_x,i
        ts, sides = printed_displacements(stem, "NSIDES")
        w = side_weights(model)
        if len(ts) != len(t):
            raise ReaderError(f"{stem}.dat: {len(t)} prints of NCTRL but {len(ts)} of NSIDES")
        cols.append(np.sum([w[k] * sides[k][:, 0] for k in w], axis=0))
    u = np.column_stack(cols)

    def loads(tt: np.ndarray) -> np.ndarray:
        """The generalised forces ``(Fx_L, Fy_L, Fx_R, Fy_R[, sigma_bulk])`` at the total times ``tt``."""
        out = []
        for time in np.atleast_1d(tt):
            P, s, Q, sb = _loads_at(targets, float(time))
            FR = (P * s - T * Q - P * xL) / (xR - xL) if tilt == "free" else 0.0
            out.append([Q, -(P - FR), 0.0, -FR] + ([sb] if bulk else []))
        return np.array(out)

    return cycle_energy(t, u, loads, span=span)


def read_traction(path: str | Path, *, arg: str = "path"
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, Any]] | None:
    """``(x, p, q, info)`` at the last increment of a surface-to-surface run's ``.frd``, or ``None``
    if the file's contact output is node-to-surface (written on the expanded nodes, numbered past
    the plane model's: :func:`threepart.calculix.contact_pressure` reads those).

    ``q`` as :func:`~.friction.contact_traction`; ``info`` holds the source, the states' count and the
    increments (``.sta`` beside it).
    """
    from .read import read_frd, read_frd_nodes

    path = Path(path)
    if path.suffix.lower() != ".frd":
        return None
    last = read_frd(path, arg=arg)          # the checked reader, the file as given
    if not last.get("CONTACT"):
        return None
    xy = read_frd_nodes(path, arg=arg)
    contact = last["CONTACT"]
    if max(contact) > max(xy):
        return None
    try:
        x, p, q = contact_traction(last, xy)
    except InputError as exc:
        raise ReaderError(f"`{arg}` = {str(path)!r}: {exc}") from None
    return x, p, q, {"source": "frd (surface to surface)", "increments": step_increments(path.with_suffix(""))}

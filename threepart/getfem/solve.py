"""One call per problem: write the GetFEM script, run it, read it back.

Names
-----
GetfemSlip     -- partial slip by GetFEM: x, p, q and slip at Q, with the run
GetfemCycle    -- a fretting cycle or a load history by GetFEM: its states, the energy per cycle, the run
partial_slip   -- the normal load, then Q (and sigma_bulk) in steps (two similar bodies, Coulomb friction)
fretting_cycle -- the normal load, then Q: 0 -> Q_max -> -Q_max -> Q_max
load_history   -- the first state's normal load, then each state (P, s, Q, sigma_bulk) in turn
"""
from __future__ import annotations

import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..cache import restored
from ..cache import restored
from ..problem.checks import positive
from ..problem.material import similar_pair
from ..methods import solve
from ..problem.punch import Punch
from ..halfplane.load_history import check_history
from .read import GetfemRun, friction_work, last_cycle, loop_energy, read_run, slip_amplitude
from .run import run_getfem
from .script import JobSettings, write_script

__all__ = ["GetfemSlip", "GetfemCycle", "partial_slip", "fretting_cycle", "load_history"]


@dataclass(frozen=True)
class GetfemSlip:
    """Partial slip computed by GetFEM (the substrate's surface nodes at the last state).

    Attributes
    ----------
    x, p, q, slip
        Nodes, pressure, shear on the substrate along +x, and the relative slip since the normal load.
    a, c
        The closed form's (half-plane) contact ends the mesh was graded to.
    run
        Everything the script wrote (:class:`threepart.getfem.GetfemRun`).
    info
        ``h``, ``dofs``, ``time`` (s of the script), ``P_integral``, ``Q_integral``,
        ``newton`` (each step's leg, loads, fraction and iterations), ``workdir``.
    """

    x: np.ndarray
    p: np.ndarray
    q: np.ndarray
    slip: np.ndarray
    a: float
    c: float
    run: GetfemRun
    info: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class GetfemCycle:
    """A fretting cycle or a load history computed by GetFEM: every recorded state, the energy per cycle.

    A fretting cycle's ``energy`` is the area of the ``Q``-``delta`` loop (Simpson's rule
    per branch); ``info["trapezoid"]`` is the same area by trapezoids (their difference
    bounds the integration's error). A load history's is the friction work over its last
    cycle (:func:`threepart.getfem.friction_work`), ``info["cycle"]`` the cycle's state
    indices, ``info["slip_amplitude"]`` ``(x, amplitude)`` over it.
    """

    states: list[Any]
    energy: float
    a: float
    c: float
    run: GetfemRun
    info: dict[str, Any] = field(default_factory=dict)


def _run(punch: Punch, P: float | None, s: float, f: float, E: float, nu: float, tilt: str,
         settings: JobSettings, h: float | None, workdir: str | Path | None, name: str, timeout: float,
         title: str, **shear: Any) -> tuple[GetfemRun, float, float]:
    """Write, run and read one job; ``(run, a, c)`` with the closed form's contact ends (a
    history's: the widest over its states)."""
    loads = [(P, s)] if shear.get("history") is None else \
        [(float(Pk), float(sk)) for Pk, sk in zip(shear["history"].P, shear["history"].s)]
    normals = [solve(punch, positive("P", Pk), sk, A=similar_pair(E, nu), tilt=tilt) for Pk, sk in dict.fromkeys(loads)]
    a, c = max(n.a for n in normals), max(n.c for n in normals)
    if h is not None:
        settings = replace(settings, n=(a + c) / positive("h", h))
    script = write_script(punch, P, s, a=a, c=c, E=E, nu=nu, f=f, tilt=tilt,
                          settings=settings, title=title, name=name, **shear)
    if workdir is None:
        with tempfile.TemporaryDirectory(prefix="threepart-getfem-") as tmp:
            return read_run(run_getfem(script, Path(tmp), name, timeout)), a, c
    return read_run(run_getfem(script, Path(workdir), name, timeout)), a, c


def _info(run: GetfemRun) -> dict[str, Any]:
    return {"h": run.params["h"], "dofs": run.dofs, "time": run.time, "newton": run.steps,
            "P_integral": run.last.resultant[0], "Q_integral": run.last.resultant[1],
            "workdir": None if run.path is None else str(run.path.parent),
            "cached": run.path is not None and restored(run.path.parent)}


def partial_slip(punch: Punch, P: float, s: float, Q: float, f: float, E: float, nu: float, *,
                 sigma_bulk: float = 0.0, tilt: str = "free", n: float | None = None, h: float | None = None,
                 settings: JobSettings | None = None,
                 workdir: str | Path | None = None, name: str = "job", timeout: float = 3600.0,
                 title: str = "") -> GetfemSlip:
    """Partial slip of two similar bodies by GetFEM: ``P`` at ``s``, then ``Q`` (and ``sigma_bulk``) in steps.

    Parameters
    ----------
    punch, P, s, tilt
        The problem (eq. 2; the load and its lever arm).
    Q, f
        The shear force (``|Q| < f P``) and the coefficient of friction.
    sigma_bulk
        The substrate's bulk stress at ``Q`` (tension positive), rising with ``Q`` in
        proportion after the normal load, as the closed form's (docs/BULK_STRESS.md); the
        substrate's base then moves with the bulk strain.
    E, nu
        The bodies' material (plane strain).
    n, h
        Elements across W, or the element size at the contact (mm): either overrides ``settings.n``.
    settings
        The model's settings (:class:`JobSettings`).
    workdir
        Where the script and its files go (default: a temporary folder, removed).

    Raises
    ------
    GetfemMissing, GetfemError
        No interpreter imports getfem; the run failed (the step Newton did not converge at).
    """
    settings = JobSettings() if settings is None else settings
    if n is not None:
        settings = replace(settings, n=n)
    run, a, c = _run(punch, P, s, f, E, nu, tilt, settings, h, workdir, name, timeout, title, Q=Q,
                     sigma_bulk=sigma_bulk)
    st = run.last
    return GetfemSlip(x=st.x, p=st.p, q=st.q, slip=st.slip, a=a, c=c, run=run, info=_info(run))


def fretting_cycle(punch: Punch, P: float, s: float, Q_max: float, f: float, E: float, nu: float, *,
                   tilt: str = "free", n: float | None = None, h: float | None = None,
                 settings: JobSettings | None = None,
                   workdir: str | Path | None = None, name: str = "job", timeout: float = 3600.0,
                   title: str = "") -> GetfemCycle:
    """A fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of two similar bodies by GetFEM.

    Arguments as :func:`partial_slip`; ``settings.steps`` steps from 0 to ``Q_max``
    and twice as many on each reversal, every step recorded.
    """
    settings = JobSettings() if settings is None else settings
    if n is not None:
        settings = replace(settings, n=n)
    run, a, c = _run(punch, P, s, f, E, nu, tilt, settings, h, workdir, name, timeout, title, Q_max=Q_max)
    energy = loop_energy(run)
    return GetfemCycle(states=run.states, energy=energy["energy"], a=a, c=c, run=run,
                       info={**_info(run), "trapezoid": energy["trapezoid"]})


def load_history(punch: Punch, history: Any, f: float, E: float, nu: float, *, n: float | None = None,
                 h: float | None = None, tilt: str = "free", steps: int | None = None,
                 settings: JobSettings | None = None, workdir: str | Path | None = None, name: str = "job",
                 timeout: float = 7200.0, title: str = "") -> GetfemCycle:
    """A load history of two similar bodies by GetFEM: the first state's normal load, then each state.

    The arguments not listed below are as :func:`partial_slip`'s.

    Parameters
    ----------
    history
        The states ``(P, s, Q, sigma_bulk)`` in turn (:func:`threepart.halfplane.load_history.check_history`:
        states, a CSV path or a History); the four move linearly together between states,
        each reached in ``steps`` steps. A flight cycle is ``[state0, state1, state0, state1]``.
    steps
        Steps per state (default ``settings.steps``).

    Returns
    -------
    GetfemCycle
        Every recorded state (``P``, ``s``, ``Q``, ``sigma_bulk``, ``x``, ``p``, ``q``, ``slip``);
        ``energy`` the friction work over the last complete cycle (NaN when the history
        closes none), ``info["cycle"]`` its state indices, ``info["slip_amplitude"]``
        ``(x, amplitude)`` over it.
    """
    hist = check_history(history)
    settings = JobSettings() if settings is None else settings
    if n is not None:
        settings = replace(settings, n=n)
    if steps is not None:
        settings = replace(settings, steps=steps)
    run, a, c = _run(punch, None, float(hist.s[0]), f, E, nu, tilt, settings, h, workdir, name, timeout, title,
                     history=hist)
    info = _info(run)
    cycle = last_cycle(run.states)
    energy = float("nan")
    if cycle is not None:
        states = run.states[cycle[0]:cycle[1] + 1]
        energy = friction_work(states)
        info.update(cycle=cycle, slip_amplitude=slip_amplitude(states))
    return GetfemCycle(states=run.states, energy=energy, a=a, c=c, run=run, info=info)

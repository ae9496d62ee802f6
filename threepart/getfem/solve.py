"""One call per problem: write the GetFEM script, run it, read it back.

Names
-----
GetfemSlip     -- partial slip by GetFEM: x, p, q and slip at Q, with the run
GetfemCycle    -- a fretting cycle by GetFEM: its states, the energy per cycle, the run
partial_slip   -- the normal load, then Q in steps (two similar bodies, Coulomb friction)
fretting_cycle -- the normal load, then Q: 0 -> Q_max -> -Q_max -> Q_max
"""
from __future__ import annotations

import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import positive
from ..material import similar_pair
from ..methods import solve
from ..punch import Punch
from .read import GetfemRun, loop_energy, read_run
from .run import run_getfem
from .script import JobSettings, write_script

__all__ = ["GetfemSlip", "GetfemCycle", "partial_slip", "fretting_cycle"]


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
    """A fretting cycle computed by GetFEM: every recorded state, the energy per cycle.

    ``energy`` is the area of the ``Q``-``delta`` loop (Simpson's rule per branch);
    ``info["trapezoid"]`` is the same area by trapezoids (their difference bounds
    the integration's error).
    """

    states: list[Any]
    energy: float
    a: float
    c: float
    run: GetfemRun
    info: dict[str, Any] = field(default_factory=dict)


def _run(punch: Punch, P: float, s: float, f: float, E: float, nu: float, tilt: str,
         settings: JobSettings, h: float | None, workdir: str | Path | None, name: str, timeout: float,
         title: str, **shear: float) -> tuple[GetfemRun, float, float]:
    """Write, run and read one job; ``(run, a, c)`` with the closed form's contact ends."""
    normal = solve(punch, P, s, A=similar_pair(E, nu), tilt=tilt)
    if h is not None:
        settings = replace(settings, n=(normal.a + normal.c) / positive("h", h))
    script = write_script(punch, P, s, a=normal.a, c=normal.c, E=E, nu=nu, f=f, tilt=tilt,
                          settings=settings, title=title, name=name, **shear)
    if workdir is None:
        with tempfile.TemporaryDirectory(prefix="threepart-getfem-") as tmp:
            return read_run(run_getfem(script, Path(tmp), name, timeout)), normal.a, normal.c
    return read_run(run_getfem(script, Path(workdir), name, timeout)), normal.a, normal.c


def _info(run: GetfemRun) -> dict[str, Any]:
    return {"h": run.params["h"], "dofs": run.dofs, "time": run.time, "newton": run.steps,
            "P_integral": run.last.resultant[0], "Q_integral": run.last.resultant[1],
            "workdir": None if run.path is None else str(run.path.parent)}


def partial_slip(punch: Punch, P: float, s: float, Q: float, f: float, E: float, nu: float, *,
                 tilt: str = "free", n: float | None = None, h: float | None = None,
                 settings: JobSettings | None = None,
                 workdir: str | Path | None = None, name: str = "job", timeout: float = 3600.0,
                 title: str = "") -> GetfemSlip:
    """Partial slip of two similar bodies by GetFEM: ``P`` at ``s``, then ``Q`` in steps.

    Parameters
    ----------
    punch, P, s, tilt
        The problem (eq. 2; the load and its lever arm).
    Q, f
        The shear force (``|Q| < f P``) and the coefficient of friction.
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
    run, a, c = _run(punch, P, s, f, E, nu, tilt, settings, h, workdir, name, timeout, title, Q=Q)
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

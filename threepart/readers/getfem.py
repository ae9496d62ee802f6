"""GetFEM's sidecar ``name.getfem.json``: the last state's pressure and shear, every state in ``info``.

The script of :mod:`threepart.getfem` writes, beside its VTU files (read by
:mod:`.meshfile`: ``contact_pressure``, ``contact_shear``), one sidecar holding
the loads of every recorded state; :func:`threepart.getfem.read_run` is the one
reader of it. ``info["states"]`` lists each state's ``P``, ``Q``, branch, the
cap's displacement ``delta`` and its fields, so that a cycle is judged from one file.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from threepart.getfem.read import read_run

from . import Record, no_options, register_reader

__all__ = ["read_getfem"]


def read_getfem(path: Path, *, arg: str = "path", **options: Any) -> Record:
    """The last state of a GetFEM run's sidecar: ``x``, ``p``, ``q``; every state in ``info["states"]``."""
    no_options(path, arg, options, "a GetFEM sidecar takes")
    run = read_run(path, arg=arg)
    last = run.last
    info = {"source": "getfem", "states": run.states, "steps": run.steps, "params": run.params,
            "time": run.time, "dofs": run.dofs, "f": run.params.get("f"), "P": last.P, "Q": last.Q}
    return Record(last.x, last.p, last.q, info)


register_reader("getfem", (".getfem.json",), read_getfem,
                "GetFEM, the sidecar threepart's GetFEM script writes (every state's loads and fields)")

"""Running CalculiX: whether ``ccx`` is installed, one run of a deck, and its two errors.

Names
-----
ccx_available -- whether ``ccx`` is on the PATH
run_ccx       -- run ``ccx`` on a deck in a directory (one thread); the job's stem
CcxError      -- ``ccx`` ran but failed, or wrote no result (a RuntimeError)
CcxMissing    -- ``ccx`` is not on the PATH (an OSError)
"""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from ..errors import CcxError, CcxMissing

__all__ = ["ccx_available", "run_ccx", "CcxError", "CcxMissing"]


def ccx_available() -> bool:
    """Whether ``ccx`` (CalculiX) is on the PATH."""
    return shutil.which("ccx") is not None


def run_ccx(deck: str, workdir: str | Path, name: str = "job", timeout: float = 900.0) -> Path:
    """Write ``deck`` to ``workdir/name.inp`` and run ``ccx`` on one thread; the job's stem.

    Raises
    ------
    CcxMissing
        If ``ccx`` is not installed.
    CcxError
        If ``ccx`` fails, or writes no result.
    """
    if not ccx_available():
        raise CcxMissing("`ccx` (CalculiX) is not on the PATH: apt-get install calculix-ccx")
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / f"{name}.inp").write_text(deck)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    proc = subprocess.run(["ccx", "-i", name], cwd=workdir, env=env, capture_output=True,
                          text=True, timeout=timeout)
    frd = workdir / f"{name}.frd"
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not frd.exists():
        err = [ln.strip() for ln in proc.stdout.splitlines() if "ERROR" in ln][:2]
        raise CcxError(f"ccx failed on {name}.inp in {workdir}: {' | '.join(err) or proc.stdout[-200:]}")
    return workdir / name

"""Running CalculiX: whether ``ccx`` is installed, one run of a deck, and its two errors.

Names
-----
ccx_available -- whether ``ccx`` is on the PATH
run_ccx       -- run ``ccx`` on a deck in a directory (one thread), or the files of the same run from
                 threepart's cache; the job's stem
ccx_version   -- ``ccx -v``'s answer, part of a cached run's key
CcxError      -- ``ccx`` ran but failed, or wrote no result (a RuntimeError)
CcxMissing    -- ``ccx`` is not on the PATH (an OSError)
"""
from __future__ import annotations

import functools
import os
import shutil
import subprocess
from pathlib import Path

from ..cache import cached_run
from ..errors import CcxError, CcxMissing

__all__ = ["ccx_available", "run_ccx", "ccx_version", "CcxError", "CcxMissing"]


def ccx_available() -> bool:
    """Whether ``ccx`` (CalculiX) is on the PATH."""
    return shutil.which("ccx") is not None


def run_ccx(deck: str, workdir: str | Path, name: str = "job", timeout: float = 900.0, *,
            cached: bool = True) -> Path:
    """Write ``deck`` to ``workdir/name.inp`` and run ``ccx`` on one thread; the job's stem.

    With ``cached`` (default) a deck ccx already ran (the same text, name and ccx version) is
    not run again: the files it wrote come back from threepart's cache
    (:func:`threepart.cache.cached_run`; ``threepart cache --clear`` empties it).

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

    def run() -> None:
        env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
        proc = subprocess.run(["ccx", "-i", name], cwd=workdir, env=env, capture_output=True,
                              text=True, timeout=timeout)
        if proc.returncode != 0 or "*ERROR" in proc.stdout or not (workdir / f"{name}.frd").exists():
            err = [ln.strip() for ln in proc.stdout.splitlines() if "ERROR" in ln][:2]
            raise CcxError(f"ccx failed on {name}.inp in {workdir}: {' | '.join(err) or proc.stdout[-200:]}")

    if cached:
        cached_run("ccx", {"deck": deck, "name": name, "ccx": ccx_version()}, workdir, run)
    else:
        run()
    return workdir / name


@functools.lru_cache(maxsize=1)
def ccx_version() -> str:
    """``ccx -v``'s answer (``Version 2.20``): part of a cached run's key."""
    proc = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=60)
    return (proc.stdout + proc.stderr).strip()

"""Running GetFEM: the interpreter that imports ``getfem``, one run of a script, and its two errors.

GetFEM's Python interface is usually the system's (Debian's ``python3-getfem``),
not the environment threepart runs in; the script runs in a process of its own.

Names
-----
PYTHON_VARIABLE  -- the environment variable naming the interpreter: ``THREEPART_GETFEM_PYTHON``
getfem_python    -- the interpreter that imports ``getfem`` (the variable, else ``python3`` on the PATH, else /usr/bin/python3)
getfem_available -- whether one does
run_getfem       -- write a script to ``workdir/name.py``, run it there (one thread), or the files of the same
                    run from threepart's cache; the sidecar's path
getfem_version   -- the interpreter and its GetFEM version, part of a cached run's key
GetfemError      -- the script ran but failed, or wrote no result (a RuntimeError)
GetfemMissing    -- no interpreter imports ``getfem`` (an OSError)
"""
from __future__ import annotations

import functools
import os
import shutil
import subprocess
from pathlib import Path

from ..cache import cached_run
from ..errors import GetfemError, GetfemMissing

__all__ = ["PYTHON_VARIABLE", "getfem_python", "getfem_available", "run_getfem", "getfem_version",
           "GetfemError", "GetfemMissing"]

#: the environment variable that names the interpreter with ``getfem``
PYTHON_VARIABLE = "THREEPART_GETFEM_PYTHON"
#: the interpreters tried when the variable is not set, in order
CANDIDATES = ("python3", "/usr/bin/python3")
#: one thread for BLAS and OpenMP: the runs share two cores with the rest (the trial: sequential MUMPS)
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


@functools.lru_cache(maxsize=None)
def _imports_getfem(python: str) -> bool:
    try:
        proc = subprocess.run([python, "-c", "import getfem"], capture_output=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return False
    return proc.returncode == 0


def getfem_python() -> str:
    """The interpreter that imports ``getfem``: ``$THREEPART_GETFEM_PYTHON``, else the first of
    ``python3`` on the PATH and ``/usr/bin/python3`` that does.

    Raises
    ------
    GetfemMissing
        If the variable names an interpreter that does not import ``getfem``, or none does.
    """
    named = os.environ.get(PYTHON_VARIABLE)
    if named:
        if not _imports_getfem(named):
            raise GetfemMissing(f"`{PYTHON_VARIABLE}` = {named!r} does not import getfem")
        return named
    for candidate in CANDIDATES:
        path = shutil.which(candidate)
        if path and _imports_getfem(path):
            return path
    raise GetfemMissing(f"no interpreter imports getfem (tried {', '.join(CANDIDATES)}): "
                        f"apt-get install python3-getfem, or set {PYTHON_VARIABLE}")


def getfem_available() -> bool:
    """Whether an interpreter imports ``getfem`` (:func:`getfem_python` finds one)."""
    try:
        getfem_python()
    except GetfemMissing:
        return False
    return True


def run_getfem(script: str, workdir: Path, name: str = "job", timeout: float = 3600.0, *,
               cached: bool = True) -> Path:
    """Write ``script`` to ``workdir/name.py``, run it there on one thread; the path of ``name.getfem.json``.

    With ``cached`` (default) a script GetFEM already ran (the same text, name, interpreter and
    GetFEM version) is not run again: the files it wrote come back from threepart's cache
    (:func:`threepart.cache.cached_run`; ``threepart cache --clear`` empties it).

    Raises
    ------
    GetfemMissing
        If no interpreter imports ``getfem``.
    GetfemError
        If the script fails (its reason, e.g. the load step Newton did not converge at),
        runs past ``timeout`` seconds, or writes no result.
    """
    python = getfem_python()
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / f"{name}.py").write_text(script)
    out = workdir / f"{name}.getfem.json"

    def run() -> None:
        try:
            proc = subprocess.run([python, f"{name}.py"], cwd=workdir, env=dict(os.environ, **ONE_THREAD),
                                  capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            raise GetfemError(f"GetFEM ran {name}.py in {workdir} past the timeout of {timeout:g} s") from None
        if proc.returncode != 0 or not out.exists():
            failed = [ln for ln in proc.stderr.splitlines() if ln.startswith("GETFEM-FAILED")]
            why = failed[0].removeprefix("GETFEM-FAILED: ") if failed else \
                " | ".join(proc.stderr.strip().splitlines()[-2:]) or f"exit status {proc.returncode}, no result"
            raise GetfemError(f"GetFEM failed on {name}.py in {workdir}: {why}")

    if cached:
        cached_run("getfem", {"script": script, "name": name, "getfem": getfem_version(python)}, workdir, run)
    else:
        run()
    return out


@functools.lru_cache(maxsize=4)
def getfem_version(python: str) -> str:
    """The interpreter ``python`` and its ``getfem.__version__``: part of a cached run's key."""
    proc = subprocess.run([python, "-c", "import getfem; print(getattr(getfem, '__version__', '?'))"],
                          capture_output=True, text=True, timeout=60)
    return f"{python}: {proc.stdout.strip()}"

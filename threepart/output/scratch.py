"""Scratch directories (e.g. for gmsh): marked with their process, cleaned once it is gone.

Names
-----
SCRATCH_MARKER -- file name of a scratch directory's marker
scratch_dir    -- context manager: a marked temporary directory, stale ones cleaned
"""
from __future__ import annotations

import json
import os
import shutil
import socket
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

from .keys import sign, signature_holds
from .markers import writer_running

__all__ = ["SCRATCH_MARKER", "scratch_dir"]

#: file name of the marker of a scratch directory (:func:`scratch_dir`)
SCRATCH_MARKER = ".threepart-scratch.json"


def _clean_scratch(prefix: str, root: Path) -> list[Path]:
    """Remove the scratch directories ``root/<prefix>*`` whose marker is ours and whose process is gone."""
    removed: list[Path] = []
    try:
        entries = [e for e in os.scandir(root) if e.name.startswith(prefix)]
    except OSError:
        return removed
    for e in entries:
        if not e.is_dir(follow_symlinks=False):
            continue
        path = Path(e.path)
        try:
            doc = json.loads((path / SCRATCH_MARKER).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        if (not isinstance(doc, dict) or doc.get("tool") != "threepart"
                or not signature_holds(doc, path) or writer_running(doc)):
            continue
        shutil.rmtree(path, ignore_errors=True)
        if not path.exists():
            removed.append(path)
    return removed


@contextmanager
def scratch_dir(prefix: str = "threepart-") -> Iterator[Path]:
    """A temporary working directory, removed on exit; the ones killed runs left are removed first.

    It is made under the system's temporary directory with ``prefix`` and
    carries a signed marker with this process's pid and host, so that the
    next call recognises it as threepart's once that process is gone (e.g. a
    kill during meshing) and removes it.

    Parameters
    ----------
    prefix
        The start of the directory's name, e.g. ``"threepart-mesh-"``.

    Yields
    ------
    Path
        The directory.
    """
    root = Path(tempfile.gettempdir())
    _clean_scratch(prefix, root)
    path = Path(tempfile.mkdtemp(prefix=prefix, dir=root))
    try:
        doc = sign({"tool": "threepart", "kind": "scratch", "pid": os.getpid(),
                       "host": socket.gethostname()}, path)
        (path / SCRATCH_MARKER).write_text(json.dumps(doc) + "\n", encoding="utf-8")
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)



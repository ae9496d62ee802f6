"""A directory written atomically: checked before any work, filled aside, renamed into place.

See :mod:`threepart.output` for the three steps (leftovers, the check, the
write) and what counts as threepart's own.

Names
-----
State       -- what :func:`check_out` found: ``"new"``, ``"empty"`` or ``"ours"``
check_dir   -- the checks of an output path common to every writer of a directory
check_out   -- check that a directory may be written, before any work
clean_stale -- remove the leftovers of killed runs beside a directory
atomic_dir  -- context manager: a temporary directory that replaces ``out`` on success
"""
from __future__ import annotations

import os
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator, Literal

from .atomic import OutputExistsError, current_umask, digest, reraise
from .keys import signature_holds
from .markers import (MARKER, MARKER_FORMAT, entries, new_marker, read_marker, remove_owned,
                      remove_tmp, why_not_ours, write_marker, writer_running)

__all__ = ["State", "check_dir", "check_out", "clean_stale", "atomic_dir"]

State = Literal["new", "empty", "ours"]


def clean_stale(out: str | Path) -> list[Path]:
    """Remove the temporary and ``.old-`` siblings of ``out`` left by killed runs.

    A leftover is removed only if it is provably threepart's and the process
    that made it is gone:

    * a temporary directory still being written (``.<name>.*.tmp``, marker
      state ``"writing"``) whose marker is signed for that very (random) path
      and names ``out`` as its target: threepart made it with ``mkdtemp`` and
      marked it at once, so it holds only what that run wrote, and it is
      removed as a whole;
    * a complete output (a sealed temporary directory, or an ``.old-``
      directory being replaced) whose marker is signed for ``out``: only if it
      holds nothing but the files its marker lists, with their checksums.

    Parameters
    ----------
    out
        The output directory whose siblings are cleaned.

    Returns
    -------
    list of Path
        The directories removed.
    """
    out = Path(os.path.abspath(out))
    prefix = f".{out.name}."
    removed: list[Path] = []
    try:
        siblings = list(os.scandir(out.parent))
    except OSError:
        return removed
    for e in siblings:
        name = e.name
        is_tmp = name.endswith(".tmp")
        is_old = name.startswith(prefix + "old-")
        if not name.startswith(prefix) or not (is_tmp or is_old) or not e.is_dir(follow_symlinks=False):
            continue
        path = Path(e.path)
        marker = read_marker(path)
        if marker is None or marker.get("target") != out.name or writer_running(marker):
            continue
        if is_tmp and marker.get("state") == "writing":
            if marker.get("format") == MARKER_FORMAT and signature_holds(marker, path):
                remove_tmp(path)
        else:
            remove_owned(path, out)
        if not path.exists():
            removed.append(path)
    return removed


# ---------------------------------------------------------------------------------------
# the check and the atomic write of a directory
# ---------------------------------------------------------------------------------------
def _contains_cwd(out: Path) -> bool:
    try:
        cwd = Path.cwd().resolve()
        target = out.resolve()
    except OSError:
        return False
    return cwd == target or target in cwd.parents


def check_dir(out: Path, q: str) -> bool:
    """The checks of ``out`` common to every writer of a directory; whether it exists."""
    if not out.name:
        raise OutputExistsError(f"{q} is a filesystem root; choose a directory to write into")
    if not os.path.lexists(out):
        return False
    if out.is_symlink():
        raise OutputExistsError(f"{q} is a symbolic link; threepart writes only a real directory")
    if not out.is_dir():
        raise OutputExistsError(f"{q} exists and is not a directory; choose another --out")
    return True


def check_out(out: str | Path, force: bool = False, *, command: str | None = None) -> State:
    """Check that ``out`` may be written, before any work.

    Parameters
    ----------
    out
        The output directory.
    force
        Kept for the callers' signatures; threepart's own earlier output is
        replaced without it, and nothing else is replaced with it.
    command
        The command about to write ``out`` (e.g. ``"verify"``): the output of
        another command is not its own, and is refused.

    Returns
    -------
    {"new", "empty", "ours"}
        ``out`` does not exist, is an empty directory, or is threepart's own
        unchanged earlier output (replaced by :func:`atomic_dir`).

    Raises
    ------
    OutputExistsError
        If ``out`` is not a directory, or holds anything that is not
        threepart's own unchanged output (see :mod:`threepart.output`). The
        message is one line and names the directory and the first foreign or
        edited file.
    """
    out = Path(os.path.abspath(out))
    q = f"`out` = {str(out)!r}"
    if not check_dir(out, q):
        return "new"
    if read_marker(out) is None and not os.listdir(out):
        return "empty"
    problem = why_not_ours(out)
    if problem is not None:
        raise OutputExistsError(f"{q} {problem}")
    other = (read_marker(out) or {}).get("command")
    if command is not None and other != command:
        raise OutputExistsError(f"{q} holds the output of `threepart {other}`, not of `threepart "
                                f"{command}`; refusing to replace it, choose another --out")
    if _contains_cwd(out):
        raise OutputExistsError(f"{q} is (or holds) the current directory; run from another "
                                "directory to replace it")
    return "ours"


def _walk(root: Path) -> tuple[list[str], list[str]]:
    """Every entry under ``root`` except its marker: (non-directories, directories), relative, sorted.

    Symbolic links count as files and are never followed.
    """
    files: list[str] = []
    dirs: list[str] = []

    def visit(d: Path, rel: str) -> None:
        for name, e in entries(d, rel, skip=(MARKER, MARKER + ".part")):
            if e.is_dir(follow_symlinks=False):
                dirs.append(name)
                visit(Path(e.path), name + "/")
            else:
                files.append(name)

    visit(root, "")
    return files, dirs


def _seal(tmp: Path, marker: dict[str, Any], out: Path) -> None:
    """List every file written, with its checksum, in a marker signed for ``out``; normal permissions."""
    files, dirs = _walk(tmp)
    links = [f for f in files if (tmp / f).is_symlink() or not (tmp / f).is_file()]
    if links:
        raise OutputExistsError(f"{links[0]!r} in {str(tmp)!r} is not a regular file; threepart "
                                "writes only regular files")
    umask = current_umask()
    dmode, fmode = 0o777 & ~umask, 0o666 & ~umask
    for f in files:
        os.chmod(tmp / f, fmode)
    digests = {f: digest(tmp / f) for f in files}
    write_marker(tmp, {**marker, "state": "complete", "files": digests, "dirs": dirs}, where=out)
    os.chmod(tmp / MARKER, fmode)
    for d in [*dirs, ""]:
        os.chmod(tmp / d, dmode)


def _fill(tmp: Path, out: Path) -> None:
    """Move the contents of ``tmp`` into the empty directory ``out``, the marker first.

    Were this interrupted, ``out`` would hold the marker and some of the files
    it lists: still threepart's own output, which the next run replaces.
    """
    os.rename(tmp / MARKER, out / MARKER)
    for e in sorted(os.listdir(tmp)):
        os.rename(tmp / e, out / e)
    os.rmdir(tmp)


@contextmanager
def atomic_dir(out: str | Path, force: bool = False, *, command: str = "threepart") -> Iterator[Path]:
    """Yield a temporary directory that becomes ``out`` only if the block succeeds.

    Parameters
    ----------
    out
        The output directory: missing, empty, or threepart's own unchanged
        earlier output (which is replaced).
    force
        Kept for the callers' signatures (see :func:`check_out`).
    command
        The command recorded in the marker, e.g. ``"verify"``.

    Yields
    ------
    Path
        The temporary directory to write into (a sibling of ``out``).

    Raises
    ------
    OutputExistsError
        If ``out`` may not be written (see :func:`check_out`); checked before
        the block runs, and again before ``out`` is replaced.
    OSError
        If the directory cannot be created, written or renamed (one line,
        naming ``out``).
    """
    out = Path(os.path.abspath(out))
    what = f"`out` = {str(out)!r}"
    clean_stale(out)
    check_out(out, force, command=command)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent))
    except OSError as exc:
        reraise(exc, what)
    marker = new_marker(out, command)
    try:
        write_marker(tmp, marker)   # at once, so that a killed run's leftover is recognised
        yield tmp
        _seal(tmp, marker, out)
        state = check_out(out, force, command=command)   # the run may have taken long: check again
        if state == "new":
            os.rename(tmp, out)
        elif state == "empty":
            _fill(tmp, out)
        else:
            old = out.parent / f".{out.name}.old-{os.getpid()}-{time.time_ns()}"
            os.rename(out, old)
            try:
                os.rename(tmp, out)
            except BaseException:
                os.rename(old, out)
                raise
            remove_owned(old, out)
    except OSError as exc:
        remove_tmp(tmp)
        reraise(exc, f"{what} ({exc.filename or tmp})")
    except BaseException:
        remove_tmp(tmp)   # this run's own temporary directory (gone already if renamed)
        raise



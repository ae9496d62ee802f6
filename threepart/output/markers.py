"""The marker of a directory threepart wrote, and what it proves.

The marker :data:`MARKER` (format :data:`MARKER_FORMAT`) lists every file with
its size and SHA-256 and is signed for the directory (:mod:`.keys`). Here it is
written and read, a directory is judged threepart's own or not
(:func:`why_not_ours`), and what is provably threepart's is removed, file by
file, never with ``shutil.rmtree``.

Names
-----
MARKER          -- file name of a directory's marker, ``.threepart-output.json``
MARKER_FORMAT   -- version of the marker's and the ledger's layout
write_marker    -- sign a marker for a directory and write it there
read_marker     -- the marker of a directory, or None
entries         -- the entries of a directory walked from its top, sorted, its marker left out
new_marker      -- the marker of a run that starts writing a directory
leftover_parts  -- the temporary files a marker announces
why_not_ours    -- why a directory is not provably threepart's own output, or None
foreign_entries -- the entries of a directory that its marker does not list
remove_listed   -- remove the files and directories a marker lists
remove_owned    -- remove a directory that is provably threepart's own
remove_tmp      -- remove a temporary directory of this (or a killed) run, its marker last
writer_running  -- whether the process a marker names is still running
"""
from __future__ import annotations

import datetime as _dt
import json
import os
import shutil
import socket
from pathlib import Path
from typing import Any, Iterator

from .atomic import unchanged, write_json
from .keys import sign, signature_holds

__all__ = ["MARKER", "MARKER_FORMAT", "write_marker", "read_marker", "entries", "new_marker",
           "leftover_parts", "why_not_ours", "foreign_entries", "remove_listed", "remove_owned", "remove_tmp",
           "writer_running"]

#: file name of the marker that every directory written by threepart carries
MARKER = ".threepart-output.json"
#: version of the marker's and the ledger's layout (2: checksums and a signature)
MARKER_FORMAT = 2


def write_marker(directory: Path, doc: dict[str, Any], where: Path | None = None) -> dict[str, Any]:
    """Sign ``doc`` for ``where`` (default ``directory``) and write it as the marker of ``directory``."""
    signed = sign(doc, Path(os.path.abspath(where or directory)))
    write_json(directory / MARKER, signed)
    return signed


def read_marker(directory: str | Path) -> dict[str, Any] | None:
    """The marker of ``directory``, or None if it has none or the file is not threepart's.

    The marker is read, not trusted: whether the directory is threepart's own
    is decided by the signature and the checksums (see :mod:`threepart.output`).

    Parameters
    ----------
    directory
        A directory that threepart may have written.

    Returns
    -------
    dict or None
        The marker's contents: ``tool``, ``format``, ``command``, ``state``
        (``"writing"`` or ``"complete"``), ``target``, ``pid``, ``host``,
        ``created``, ``files`` (relative path: ``{"sha256", "size"}``),
        ``dirs``, ``path`` and ``mac``. A marker of format 1 has ``files`` as a list.
    """
    path = Path(directory) / MARKER
    try:
        if path.is_symlink() or not path.is_file():
            return None
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(doc, dict) or doc.get("tool") != "threepart":
        return None
    files, dirs = doc.get("files"), doc.get("dirs")
    if not isinstance(dirs, list) or not all(isinstance(x, str) for x in dirs):
        return None
    if isinstance(files, list):
        ok = all(isinstance(x, str) for x in files)
    else:
        ok = isinstance(files, dict) and all(isinstance(v, dict) for v in files.values())
    return doc if ok else None


def entries(d: Path, rel: str, skip: tuple[str, ...] = (MARKER,)) -> Iterator[tuple[str, os.DirEntry[str]]]:
    """The entries of the directory ``d``, sorted by name, each with its path ``rel + name``.

    ``rel`` is ``d``'s path relative to the directory walked (``""`` at its
    top, where the names in ``skip``, its marker, are left out).
    """
    with os.scandir(d) as it:
        found = sorted(it, key=lambda e: e.name)
    for e in found:
        if rel or e.name not in skip:
            yield f"{rel}{e.name}", e


def leftover_parts(marker: dict[str, Any]) -> set[str]:
    """The temporary files the marker announces (a run killed while writing them leaves them)."""
    pending = marker.get("pending", [])
    return {MARKER + ".part", *(p for p in pending if isinstance(p, str))} if isinstance(pending, list) \
        else {MARKER + ".part"}


def why_not_ours(directory: Path, where: Path | None = None) -> str | None:
    """Why ``directory`` is not provably threepart's own output, as the end of a sentence; None if it is.

    ``where`` is the path the marker must be signed for (default ``directory``).
    """
    marker = read_marker(directory)
    if marker is None:
        with os.scandir(directory) as it:
            first = min((e.name for e in it), default=None)
        if first is None:
            return None
        return (f"holds {first!r} and no valid {MARKER}: threepart did not write it; refusing to "
                "touch it, choose another --out")
    if marker.get("format") != MARKER_FORMAT:
        return (f"holds a {MARKER} of an older threepart (format {marker.get('format')}, no "
                "checksums), which is not trusted; check its files and remove it yourself, or "
                "choose another --out")
    if not signature_holds(marker, Path(os.path.abspath(where or directory))):
        return (f"holds a {MARKER} that threepart did not write there (hand-written, edited or "
                "copied from elsewhere); refusing to touch it: remove it yourself or choose "
                "another --out")
    files, dirs = marker["files"], set(marker["dirs"])
    parts = leftover_parts(marker)

    def visit(d: Path, rel: str) -> str | None:
        for name, e in entries(d, rel):
            if name in files:
                if e.is_symlink():
                    return (f"holds {name!r}, a symbolic link where threepart wrote a file; "
                            "refusing to replace it (move it away or choose another --out)")
                if not unchanged(Path(e.path), files[name]):
                    return (f"holds {name!r}, which was changed after threepart wrote it; refusing "
                            "to replace it (move it away or choose another --out)")
            elif name in dirs and e.is_dir(follow_symlinks=False):
                found = visit(Path(e.path), name + "/")
                if found:
                    return found
            elif name in parts and e.is_file(follow_symlinks=False):
                continue
            else:
                shown = name + "/" if e.is_dir(follow_symlinks=False) else name
                return (f"holds {shown!r}, which threepart did not write; refusing to replace it "
                        "(move it away or choose another --out)")
        return None

    return visit(directory, "")


def _foreign(directory: Path) -> Iterator[str]:
    """The entries under ``directory`` that its marker does not list, in sorted order, lazily."""
    marker = read_marker(directory)
    if marker is None:
        with os.scandir(directory) as it:
            yield from sorted(e.name for e in it)
        return
    files, dirs = set(marker["files"]), set(marker["dirs"])

    def visit(d: Path, rel: str) -> Iterator[str]:
        for name, e in entries(d, rel):
            if e.is_dir(follow_symlinks=False):
                if name not in dirs:
                    yield name + "/"
                else:
                    yield from visit(Path(e.path), name + "/")
            elif name not in files:
                yield name

    yield from visit(directory, "")


def foreign_entries(directory: str | Path) -> list[str]:
    """The entries under ``directory`` that its marker does not list (all of them without a marker).

    Parameters
    ----------
    directory
        An existing directory.

    Returns
    -------
    list of str
        Relative paths, sorted (a directory with a trailing ``/``); empty if
        the marker lists everything in it (checksums are not checked here).
    """
    return list(_foreign(Path(directory)))


def remove_listed(directory: Path, marker: dict[str, Any]) -> None:
    """Remove the files and directories ``marker`` lists (checked by :func:`why_not_ours` before)."""
    for f in [*marker["files"], *leftover_parts(marker)]:
        p = directory / f
        if os.path.lexists(p) and not p.is_dir():
            os.unlink(p)
    for d in sorted(marker["dirs"], key=lambda s: s.count("/"), reverse=True):
        try:
            os.rmdir(directory / d)
        except OSError:   # not empty: something appeared since the check; left alone
            pass


def remove_owned(directory: Path, where: Path | None = None) -> bool:
    """Remove ``directory`` if it is provably threepart's own (:func:`why_not_ours`); return whether it was.

    Only the listed files and directories are removed, one by one (never
    ``shutil.rmtree``); anything else leaves the whole directory in place.
    """
    try:
        if directory.is_symlink() or not directory.is_dir() or why_not_ours(directory, where) is not None:
            return False
        marker = read_marker(directory)
        assert marker is not None
        remove_listed(directory, marker)
        os.unlink(directory / MARKER)
        os.rmdir(directory)
    except OSError:
        return False
    return True


def remove_tmp(tmp: Path) -> None:
    """Remove a temporary directory of this run's (or a killed run's, proven ours), its marker last.

    The marker goes last so that, were this interrupted too, the rest would
    still be recognised (and removed) by the next run. Symbolic links are
    removed, never followed.
    """
    if tmp.is_symlink() or not tmp.is_dir():
        return
    for e in sorted(os.listdir(tmp)):
        if e == MARKER:
            continue
        path = tmp / e
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path, ignore_errors=True)
        else:
            path.unlink(missing_ok=True)
    (tmp / MARKER).unlink(missing_ok=True)
    try:
        os.rmdir(tmp)
    except OSError:
        pass


def writer_running(marker: dict[str, Any]) -> bool:
    """Whether the process that wrote ``marker`` may still be running (on this host)."""
    pid = marker.get("pid")
    if os.name != "posix" or not isinstance(pid, int) or pid <= 0:
        return False
    if marker.get("host") != socket.gethostname():
        return False
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # e.g. PermissionError: the process exists, owned by someone else
        return True
    return True



def new_marker(out: Path, command: str, **extra: Any) -> dict[str, Any]:
    return {"tool": "threepart", "format": MARKER_FORMAT, "command": command, "state": "writing",
            "target": out.name, "pid": os.getpid(), "host": socket.gethostname(),
            "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            **extra, "files": {}, "dirs": []}



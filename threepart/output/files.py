"""Single files: written atomically over nothing but threepart's own unchanged earlier file.

The files threepart wrote into a directory are recorded, with their
checksums, in that directory's signed ledger :data:`LEDGER`.

Names
-----
LEDGER     -- file name of a directory's ledger of single files, ``.threepart-files.json``
check_file -- the check of :func:`write_file` alone, before any work
write_file -- write one file atomically, over nothing but threepart's own unchanged file
"""
from __future__ import annotations

import json
import os
import secrets
from pathlib import Path
from typing import Callable

from .atomic import Digest, OutputExistsError, digest, fill_file, fsync_dir, reraise, unchanged, write_json
from .keys import sign, signature_holds
from .markers import MARKER, MARKER_FORMAT
from threepart.errors import InputError

__all__ = ["LEDGER", "check_file", "write_file"]

#: file name of the ledger of single files that threepart wrote into a directory
LEDGER = ".threepart-files.json"


def _read_ledger(directory: Path) -> tuple[dict[str, Digest] | None, bool]:
    """The files recorded in ``directory``'s ledger, and whether a ledger file exists at all.

    A ledger that is not threepart's (unsigned, signed for another directory,
    of another format) counts as no ledger: ``(None, True)``.
    """
    path = directory / LEDGER
    if not os.path.lexists(path):
        return {}, False
    try:
        if path.is_symlink() or not path.is_file():
            return None, True
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None, True
    if (not isinstance(doc, dict) or doc.get("tool") != "threepart"
            or doc.get("format") != MARKER_FORMAT or not isinstance(doc.get("files"), dict)
            or not signature_holds(doc, Path(os.path.abspath(directory)))):
        return None, True
    return doc["files"], True


def check_file(path: str | Path, *, arg: str = "path", overwrite: bool = False,
               how: str = "choose another name") -> bool:
    """Check that :func:`write_file` may write ``path``, changing nothing; return whether it exists.

    Parameters
    ----------
    path
        The file to write.
    arg
        The name of the caller's argument, for the messages (e.g. ``"--csv"``).
    overwrite
        Replace an existing regular file even if threepart did not write it.
    how
        What the refusal tells the user to do instead.

    Raises
    ------
    OutputExistsError
        ``path`` exists and is not threepart's own unchanged file (nor
        ``overwrite``), or is not a regular file, or its directory holds a
        :data:`LEDGER` that threepart did not write.
    ValueError
        Its directory does not exist (or is not a directory).
    """
    path = Path(path)
    q = f"`{arg}` = {str(path)!r}"
    directory = Path(os.path.abspath(path)).parent
    if not path.name or path.name in (".", ".."):
        raise InputError(f"{q} is not a file name")
    if path.name in (LEDGER, MARKER) or path.name.endswith(".part"):
        raise InputError(f"{q}: the name is threepart's own bookkeeping; choose another name")
    if not directory.is_dir():
        raise InputError(f"{q}: directory does not exist" if not os.path.lexists(directory)
                         else f"{q}: {str(directory)!r} is not a directory")
    recorded, has_ledger = _read_ledger(directory)
    if recorded is None:
        raise OutputExistsError(f"{q}: {str(directory / LEDGER)!r} is not threepart's (edited, "
                                "copied or hand-written); refusing to overwrite it: remove it "
                                "yourself or write elsewhere")
    if not os.path.lexists(path):
        return False
    if path.is_symlink() or not path.is_file():
        raise OutputExistsError(f"{q} exists and is not a regular file; threepart never writes "
                                "through it: choose another name")
    if overwrite or unchanged(path, recorded.get(path.name)):
        return True
    why = ("was changed after threepart wrote it" if path.name in recorded
           else "was not written by threepart")
    raise OutputExistsError(f"{q} exists and {why}; refusing to overwrite it: {how}")


def write_file(path: str | Path, data: str | bytes | Callable[[Path], None], *, arg: str = "path",
               overwrite: bool = False, how: str = "choose another name") -> Path:
    """Write one file atomically; create it, or replace threepart's own unchanged earlier file.

    The data go to a temporary sibling, which is fsynced and renamed over
    ``path`` (``os.replace``); the file and its checksum are then recorded in
    the directory's signed ledger :data:`LEDGER`, which is rewritten
    atomically too. A failure (a full disk) leaves no temporary file and
    ``path`` as it was.

    Parameters
    ----------
    path, arg, overwrite, how
        As for :func:`check_file`: the file, the caller's argument named in
        the messages, whether to replace a file threepart did not write, and
        what a refusal tells the user to do instead.
    data
        Text (written as UTF-8), bytes, or a function that writes the file at
        the path it is given (e.g. a meshio writer).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    OutputExistsError, ValueError
        See :func:`check_file`; nothing is written.
    OSError
        The file cannot be written (one line naming the argument and ``path``).
    """
    path = Path(path)
    check_file(path, arg=arg, overwrite=overwrite, how=how)
    directory = Path(os.path.abspath(path)).parent
    q = f"`{arg}` = {str(path)!r}"
    part = directory / f".{path.name}.{secrets.token_hex(4)}.part"
    def record(files: dict[str, Digest]) -> None:
        write_json(directory / LEDGER, sign({"tool": "threepart", "format": MARKER_FORMAT,
                                                  "files": files}, directory))

    try:
        recorded, _ = _read_ledger(directory)
        files = {k: v for k, v in (recorded or {}).items() if os.path.lexists(directory / k)}
        try:
            fill_file(part, data)
            new = digest(part)
            was = files.get(path.name)
            was = None if was is None else {k: v for k, v in was.items() if k != "was"}
            if was is not None:   # either content is ours until the record below
                record({**files, path.name: {**new, "was": was}})
            os.replace(part, path)
        finally:
            part.unlink(missing_ok=True)
        fsync_dir(directory)
        record({**files, path.name: new})
    except OSError as exc:
        reraise(exc, q)
    return path



"""One file written atomically, and the checksums that tell whether it changed since.

The primitives of every writer in :mod:`threepart.output`: a one-line
``OSError`` naming what could not be written, a file's SHA-256 and size,
whether a file still matches a recorded digest, and a file filled, fsynced and
renamed into place.

Names
-----
OutputExistsError -- a path may not be written or replaced (a ``ValueError``)
Digest            -- a recorded ``{"sha256", "size"}`` (``"grows"``, ``"was"``: see :func:`unchanged`)
reraise           -- raise an ``OSError`` as one line naming what could not be written
digest            -- SHA-256 and size of a regular file (or of its first bytes)
unchanged         -- whether a file still matches its recorded digest
write_json        -- write a JSON document atomically (``.part``, fsync, rename)
fsync_dir         -- fsync a directory (its entries), ignoring what cannot be
fill_file         -- write text, bytes or a writer's output to a new file and fsync it
current_umask     -- the process's umask, read without changing it where possible
"""
from __future__ import annotations

import hashlib
import json
import os
import threading
from pathlib import Path
from typing import Any, Callable, NoReturn

from ..errors import OutputExistsError, ThreepartError

__all__ = ["OutputExistsError", "Digest", "reraise", "digest", "unchanged", "write_json",
           "fsync_dir", "fill_file", "current_umask"]

_UMASK_LOCK = threading.Lock()
_CHUNK = 1 << 20

Digest = dict[str, Any]


class _WriteError(ThreepartError, OSError):
    """An ``OSError`` whose one-line message already names what could not be written."""


def _os_error(exc: OSError, what: str) -> OSError:
    """A one-line ``OSError`` that names ``what`` (e.g. a path) and keeps the errno."""
    if isinstance(exc, _WriteError):
        return exc
    err = _WriteError(f"cannot write {what}: {exc.strerror or exc}")
    err.errno = exc.errno
    return err


def reraise(exc: OSError, what: str) -> NoReturn:
    """Raise ``exc`` as a one-line error naming ``what`` (unchanged if it names a path already)."""
    if isinstance(exc, _WriteError):
        raise exc
    raise _os_error(exc, what) from exc



def digest(path: Path, size: int | None = None) -> Digest:
    """SHA-256 and size of the regular file ``path`` (of its first ``size`` bytes if given)."""
    h = hashlib.sha256()
    n = 0
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    with os.fdopen(fd, "rb") as fh:
        while size is None or n < size:
            block = fh.read(_CHUNK if size is None else min(_CHUNK, size - n))
            if not block:
                break
            h.update(block)
            n += len(block)
    return {"sha256": h.hexdigest(), "size": n}


def unchanged(path: Path, recorded: Any) -> bool:
    """Whether ``path`` is a regular file that still matches the ``recorded`` digest.

    A recorded digest with ``"grows": True`` (a log that is appended to) must
    match the file's first ``size`` bytes; the file may have grown since. One
    with ``"was"`` (recorded just before a file is replaced) also accepts the
    content it replaces, for a run killed between the rename and the record.
    """
    if isinstance(recorded, dict) and "was" in recorded and unchanged(path, recorded["was"]):
        return True
    if not isinstance(recorded, dict) or not isinstance(recorded.get("size"), int):
        return False
    try:
        if path.is_symlink() or not path.is_file():
            return False
        size = path.stat().st_size
        if recorded.get("grows"):
            if size < recorded["size"]:
                return False
            return digest(path, recorded["size"]) == {k: recorded[k] for k in ("sha256", "size")}
        return size == recorded["size"] and digest(path)["sha256"] == recorded.get("sha256")
    except OSError:
        return False


def write_json(path: Path, doc: dict[str, Any]) -> None:
    """Write ``doc`` to ``path`` atomically: ``path.part``, fsync, rename; no ``.part`` left on error."""
    part = path.with_name(path.name + ".part")
    try:
        if part.is_symlink():
            part.unlink()
        fd = os.open(part, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0), 0o666)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(json.dumps(doc, indent=1, allow_nan=False) + "\n")
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(part, path)
    except BaseException as exc:
        try:
            part.unlink()
        except OSError:
            pass
        if isinstance(exc, OSError):
            reraise(exc, repr(str(path)))
        raise


def fsync_dir(directory: Path) -> None:
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def fill_file(part: Path, data: str | bytes | Callable[[Path], None]) -> None:
    """Write ``data`` to the new file ``part`` and fsync it."""
    if callable(data):
        data(part)
    else:
        raw = data.encode("utf-8") if isinstance(data, str) else data
        fd = os.open(part, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o666)
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
            fh.flush()
            os.fsync(fh.fileno())
        return
    fd = os.open(part, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    try:
        os.fsync(fd)
    finally:
        os.close(fd)



def current_umask() -> int:
    """The process's umask, read without changing it where the system allows (Linux)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _UMASK_LOCK:  # os.umask can only be read by setting it
        mask = os.umask(0o022)
        os.umask(mask)
    return mask



"""Everything threepart writes: atomic, marked with checksums, and never over anyone else's files.

Directories
-----------
A command that writes a directory (``threepart verify``, ``threepart figures``)
writes it through :func:`atomic_dir`:

1. Leftovers of an earlier run that was killed (``.<name>.*.tmp`` and
   ``.<name>.old-*`` beside ``out``) are removed, but only those that are
   provably threepart's (below) and whose process is gone.
2. ``out`` is checked before any work. It may be missing, an empty
   directory, or threepart's own earlier output, which is replaced (no
   ``--force`` needed). Anything else is refused with
   :class:`OutputExistsError`, whose one-line message names the directory and
   the first foreign or edited file.
3. The files are written into a temporary sibling directory that carries the
   marker from its creation. When the block succeeds, the marker is rewritten
   with every file written, its size and SHA-256, the permissions are set to
   ``0o777 & ~umask`` (directories) and ``0o666 & ~umask`` (files), and the
   directory is renamed into place. When the block fails, or is interrupted,
   the temporary directory is removed and ``out`` is left as it was.

A directory written in place, file by file, and resumed after an interrupt
(``threepart map``) is a :class:`ResumableDir`: the same marker, kept up to
date after every file it writes.

What is threepart's own
-----------------------
The marker :data:`MARKER` (format :data:`MARKER_FORMAT`) lists every file with
its size and SHA-256, and is signed: an HMAC-SHA-256, with a per-user secret
key (:func:`state_dir`), of its contents and the absolute path of the
directory it belongs to. A directory is threepart's own only if its marker's
signature holds for that very path (so a hand-written, edited or copied
marker does not count), every listed file is a regular file (not a symbolic
link) whose checksum still matches, and it holds nothing else. Anything less
is refused and nothing is removed; a marker of an older format (no checksums)
is refused with a message that says how to proceed.

Single files
------------
:func:`write_file` writes one file atomically (a temporary sibling, fsync,
``os.replace``). It creates a new file, or replaces one that threepart wrote
there earlier and that is unchanged: such files are recorded, with their
checksums, in a signed ledger :data:`LEDGER` in their directory. Anything else
is refused with a one-line message that names the caller's argument (e.g.
``--csv``).

Scratch directories
-------------------
:func:`scratch_dir` makes a temporary working directory (e.g. for gmsh) that
carries a marker naming its process; ones left by killed processes are removed
by the next call.

Names
-----
MARKER              -- file name of a directory's marker, ``.threepart-output.json``
LEDGER              -- file name of a directory's ledger of single files, ``.threepart-files.json``
MARKER_FORMAT       -- version of the marker's and the ledger's layout
OutputExistsError   -- a path may not be written or replaced (a ``ValueError``)
atomic_dir          -- context manager: a temporary directory that replaces ``out`` on success
check_out           -- the check of step 2 alone
clean_stale         -- step 1 alone; returns the leftovers it removed
ResumableDir        -- a marked directory written in place and resumed (``threepart map``)
write_file          -- write one file atomically, over nothing but threepart's own unchanged file
check_file          -- the check of :func:`write_file` alone, before any work
scratch_dir         -- context manager: a marked temporary directory, stale ones cleaned
read_marker         -- the marker of a directory, or None
writer_running      -- whether the process a marker names is still running
foreign_entries     -- the entries of a directory that its marker does not list
state_dir           -- where the per-user key lives (``$THREEPART_STATE_DIR`` or ``~/.local/state/threepart``)
json_safe           -- a JSON-safe copy: non-finite floats as None, numpy scalars as Python numbers
strict_json         -- ``json.dumps`` that writes non-finite numbers as null, never NaN/Infinity
validate_json       -- check a document against a JSON schema file (jsonschema)
"""
from __future__ import annotations

import datetime as _dt
import errno as _errno
import hashlib
import hmac
import json
import math
import os
import secrets
import shutil
import socket
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Callable, Iterator, Literal, NoReturn

__all__ = ["MARKER", "LEDGER", "MARKER_FORMAT", "OutputExistsError", "atomic_dir", "check_out",
           "clean_stale", "ResumableDir", "write_file", "check_file", "scratch_dir", "read_marker",
           "writer_running", "foreign_entries", "state_dir", "json_safe", "strict_json",
           "validate_json", "current_umask"]

#: file name of the marker that every directory written by threepart carries
MARKER = ".threepart-output.json"
#: file name of the ledger of single files that threepart wrote into a directory
LEDGER = ".threepart-files.json"
#: file name of the marker of a scratch directory (:func:`scratch_dir`)
SCRATCH_MARKER = ".threepart-scratch.json"
#: version of the marker's and the ledger's layout (2: checksums and a signature)
MARKER_FORMAT = 2
_UMASK_LOCK = threading.Lock()
_KEY_LOCK = threading.Lock()
_KEY: dict[str, bytes] = {}
_CHUNK = 1 << 20

State = Literal["new", "empty", "ours"]
Digest = dict[str, Any]


class OutputExistsError(ValueError):
    """A path may not be written: it holds something threepart did not write, or that was changed."""


class _WriteError(OSError):
    """An ``OSError`` whose one-line message already names what could not be written."""


def _os_error(exc: OSError, what: str) -> OSError:
    """A one-line ``OSError`` that names ``what`` (e.g. a path) and keeps the errno."""
    if isinstance(exc, _WriteError):
        return exc
    err = _WriteError(f"cannot write {what}: {exc.strerror or exc}")
    err.errno = exc.errno
    return err


def _reraise(exc: OSError, what: str) -> NoReturn:
    """Raise ``exc`` as a one-line error naming ``what`` (unchanged if it names a path already)."""
    if isinstance(exc, _WriteError):
        raise exc
    raise _os_error(exc, what) from exc


# ---------------------------------------------------------------------------------------
# the signature: a per-user key, and an HMAC bound to the directory's absolute path
# ---------------------------------------------------------------------------------------
def state_dir() -> Path:
    """Where threepart keeps its per-user key: ``$THREEPART_STATE_DIR``, else ``$XDG_STATE_HOME/threepart``."""
    env = os.environ.get("THREEPART_STATE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_STATE_HOME") or os.path.join(os.path.expanduser("~"), ".local", "state")
    return Path(base) / "threepart"


def _key() -> bytes:
    """The per-user secret that signs markers and ledgers (made on first use, mode 0600).

    If it cannot be kept on disk, a key of this process alone is used: what it
    writes is then its own only until it exits (a later run refuses it).
    """
    where = str(state_dir())
    with _KEY_LOCK:
        if where in _KEY:
            return _KEY[where]
        path = Path(where) / "key"
        key = None
        try:
            path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
            try:
                fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0),
                             0o600)
            except FileExistsError:
                text = path.read_text(encoding="ascii").strip()
                if len(text) == 64 and not path.is_symlink():
                    key = bytes.fromhex(text)
            else:
                new = secrets.token_bytes(32)
                with os.fdopen(fd, "w", encoding="ascii") as fh:
                    fh.write(new.hex() + "\n")
                    fh.flush()
                    os.fsync(fh.fileno())
                key = new
        except (OSError, ValueError):
            key = None
        _KEY[where] = key if key is not None else secrets.token_bytes(32)
        return _KEY[where]


def _mac(doc: dict[str, Any]) -> str:
    body = json.dumps({k: v for k, v in doc.items() if k != "mac"}, sort_keys=True,
                      separators=(",", ":"), allow_nan=False)
    return hmac.new(_key(), body.encode("utf-8"), hashlib.sha256).hexdigest()


def _signed(doc: dict[str, Any], where: Path) -> dict[str, Any]:
    signed = {**{k: v for k, v in doc.items() if k != "mac"}, "path": str(where)}
    signed["mac"] = _mac(signed)
    return signed


def _signature_holds(doc: dict[str, Any], where: Path) -> bool:
    """Whether ``doc`` was signed by threepart (this user's key) for the directory ``where``."""
    mac = doc.get("mac")
    return (isinstance(mac, str) and doc.get("path") == str(where)
            and hmac.compare_digest(mac, _mac(doc)))


def _digest(path: Path, size: int | None = None) -> Digest:
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


def _unchanged(path: Path, recorded: Any) -> bool:
    """Whether ``path`` is a regular file that still matches the ``recorded`` digest.

    A recorded digest with ``"grows": True`` (a log that is appended to) must
    match the file's first ``size`` bytes; the file may have grown since. One
    with ``"was"`` (recorded just before a file is replaced) also accepts the
    content it replaces, for a run killed between the rename and the record.
    """
    if isinstance(recorded, dict) and "was" in recorded and _unchanged(path, recorded["was"]):
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
            return _digest(path, recorded["size"]) == {k: recorded[k] for k in ("sha256", "size")}
        return size == recorded["size"] and _digest(path)["sha256"] == recorded.get("sha256")
    except OSError:
        return False


def _write_json(path: Path, doc: dict[str, Any]) -> None:
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
            _reraise(exc, repr(str(path)))
        raise


def _fsync_dir(directory: Path) -> None:
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


# ---------------------------------------------------------------------------------------
# the marker
# ---------------------------------------------------------------------------------------
def _write_marker(directory: Path, doc: dict[str, Any], where: Path | None = None) -> dict[str, Any]:
    """Sign ``doc`` for ``where`` (default ``directory``) and write it as the marker of ``directory``."""
    signed = _signed(doc, Path(os.path.abspath(where or directory)))
    _write_json(directory / MARKER, signed)
    return signed


def read_marker(directory: str | Path) -> dict[str, Any] | None:
    """The marker of ``directory``, or None if it has none or the file is not threepart's.

    The marker is read, not trusted: whether the directory is threepart's own
    is decided by the signature and the checksums (see the module docstring).

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


def _leftover_parts(marker: dict[str, Any]) -> set[str]:
    """The temporary files the marker announces (a run killed while writing them leaves them)."""
    pending = marker.get("pending", [])
    return {MARKER + ".part", *(p for p in pending if isinstance(p, str))} if isinstance(pending, list) \
        else {MARKER + ".part"}


def _problem(directory: Path, where: Path | None = None) -> str | None:
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
    if not _signature_holds(marker, Path(os.path.abspath(where or directory))):
        return (f"holds a {MARKER} that threepart did not write there (hand-written, edited or "
                "copied from elsewhere); refusing to touch it: remove it yourself or choose "
                "another --out")
    files, dirs = marker["files"], set(marker["dirs"])
    parts = _leftover_parts(marker)

    def visit(d: Path, rel: str) -> str | None:
        with os.scandir(d) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            name = f"{rel}{e.name}"
            if not rel and e.name == MARKER:
                continue
            if name in files:
                if e.is_symlink():
                    return (f"holds {name!r}, a symbolic link where threepart wrote a file; "
                            "refusing to replace it (move it away or choose another --out)")
                if not _unchanged(Path(e.path), files[name]):
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
        with os.scandir(d) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            name = f"{rel}{e.name}"
            if not rel and e.name == MARKER:
                continue
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


def _remove_listed(directory: Path, marker: dict[str, Any]) -> None:
    """Remove the files and directories ``marker`` lists (checked by :func:`_problem` before)."""
    for f in [*marker["files"], *_leftover_parts(marker)]:
        p = directory / f
        if os.path.lexists(p) and not p.is_dir():
            os.unlink(p)
    for d in sorted(marker["dirs"], key=lambda s: s.count("/"), reverse=True):
        try:
            os.rmdir(directory / d)
        except OSError:   # not empty: something appeared since the check; left alone
            pass


def _remove_owned(directory: Path, where: Path | None = None) -> bool:
    """Remove ``directory`` if it is provably threepart's own (:func:`_problem`); return whether it was.

    Only the listed files and directories are removed, one by one (never
    ``shutil.rmtree``); anything else leaves the whole directory in place.
    """
    try:
        if directory.is_symlink() or not directory.is_dir() or _problem(directory, where) is not None:
            return False
        marker = read_marker(directory)
        assert marker is not None
        _remove_listed(directory, marker)
        os.unlink(directory / MARKER)
        os.rmdir(directory)
    except OSError:
        return False
    return True


def _remove_tmp(tmp: Path) -> None:
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


# ---------------------------------------------------------------------------------------
# leftovers of interrupted runs
# ---------------------------------------------------------------------------------------
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
            if marker.get("format") == MARKER_FORMAT and _signature_holds(marker, path):
                _remove_tmp(path)
        else:
            _remove_owned(path, out)
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


def _check_dir(out: Path, q: str) -> bool:
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
        threepart's own unchanged output (see the module docstring). The
        message is one line and names the directory and the first foreign or
        edited file.
    """
    out = Path(os.path.abspath(out))
    q = f"`out` = {str(out)!r}"
    if not _check_dir(out, q):
        return "new"
    if read_marker(out) is None and not os.listdir(out):
        return "empty"
    problem = _problem(out)
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


def _walk(root: Path) -> tuple[list[str], list[str]]:
    """Every entry under ``root`` except its marker: (non-directories, directories), relative, sorted.

    Symbolic links count as files and are never followed.
    """
    files: list[str] = []
    dirs: list[str] = []

    def visit(d: Path, rel: str) -> None:
        with os.scandir(d) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            name = f"{rel}{e.name}"
            if not rel and e.name in (MARKER, MARKER + ".part"):
                continue
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
    digests = {f: _digest(tmp / f) for f in files}
    _write_marker(tmp, {**marker, "state": "complete", "files": digests, "dirs": dirs}, where=out)
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


def _new_marker(out: Path, command: str, **extra: Any) -> dict[str, Any]:
    return {"tool": "threepart", "format": MARKER_FORMAT, "command": command, "state": "writing",
            "target": out.name, "pid": os.getpid(), "host": socket.gethostname(),
            "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            **extra, "files": {}, "dirs": []}


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
        _reraise(exc, what)
    marker = _new_marker(out, command)
    try:
        _write_marker(tmp, marker)   # at once, so that a killed run's leftover is recognised
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
            _remove_owned(old, out)
    except OSError as exc:
        _remove_tmp(tmp)
        _reraise(exc, f"{what} ({exc.filename or tmp})")
    except BaseException:
        _remove_tmp(tmp)   # this run's own temporary directory (gone already if renamed)
        raise


# ---------------------------------------------------------------------------------------
# a directory written in place and resumed
# ---------------------------------------------------------------------------------------
class ResumableDir:
    """A marked output directory written in place, file by file, and resumed after an interrupt.

    Open it with :meth:`open`. Every file goes through :meth:`write` (a
    temporary sibling announced in the marker, then a rename) or
    :meth:`append` (a log), and the marker is rewritten, signed, with the
    file's checksum after each, so that the directory is threepart's own at
    every moment, even after a kill. :meth:`seal` marks it ``"complete"``.

    Attributes
    ----------
    out
        The directory.
    marker
        Its marker (``mode`` tells apart variants of one command, e.g. quick and full).
    action
        ``"new"``, ``"resumed"`` or ``"replaced"``.
    """

    def __init__(self, out: Path, marker: dict[str, Any], action: str) -> None:
        self.out, self.marker, self.action = out, marker, action
        self._logs: dict[str, Any] = {}

    @classmethod
    def check(cls, out: str | Path, *, command: str, mode: str, force: bool = False) -> str:
        """What :meth:`open` would do with ``out`` (``"new"``, ``"resumed"``, ``"replaced"``), changing nothing.

        ``out`` may be missing or empty (new), an unfinished output of
        ``command`` and ``mode`` (resumed, with or without ``force``), or with
        ``force`` a finished one or one of another mode (replaced).

        Raises
        ------
        OutputExistsError
            Anything else: a foreign or edited file, another command's
            output, an output still being written by a live process, or a
            finished one without ``force`` (one line, naming ``out``).
        """
        out = Path(os.path.abspath(out))
        q = f"`out` = {str(out)!r}"
        if not _check_dir(out, q) or (read_marker(out) is None and not os.listdir(out)):
            return "new"
        problem = _problem(out)
        if problem is not None:
            raise OutputExistsError(f"{q} {problem}")
        existing = read_marker(out)
        assert existing is not None
        what, state = existing.get("command"), existing.get("state")
        if what != command:
            raise OutputExistsError(f"{q} holds the output of `threepart {what}`, not a {command}; "
                                    "refusing to touch it, choose another --out")
        if state != "complete" and existing.get("pid") != os.getpid() and writer_running(existing):
            raise OutputExistsError(f"{q} is being written by process {existing['pid']}; "
                                    "wait for it or choose another --out")
        if state != "complete" and existing.get("mode") == mode:
            return "resumed"
        if not force:
            found = (f"a finished {command}" if state == "complete" else
                     f"an unfinished {existing.get('mode')} {command} (resume it with the same mode)")
            raise OutputExistsError(f"{q} holds {found}; pass --force to replace it")
        return "replaced"

    @classmethod
    def open(cls, out: str | Path, *, command: str, mode: str, force: bool = False) -> ResumableDir:
        """Check ``out`` (:meth:`check`) and make it this run's: new, resumed or replaced.

        Resuming removes the temporary files of a killed run; replacing
        removes the files the old marker lists (checked unchanged) first.
        """
        out = Path(os.path.abspath(out))
        action = cls.check(out, command=command, mode=mode, force=force)
        existing = read_marker(out) if out.is_dir() else None
        try:
            if existing is not None and action == "replaced":
                _remove_listed(out, existing)
            out.mkdir(parents=True, exist_ok=True)
            if existing is not None and action == "resumed":
                for p in _leftover_parts(existing):
                    if os.path.lexists(out / p) and not (out / p).is_dir():
                        os.unlink(out / p)
                marker = {**existing, "pid": os.getpid(), "host": socket.gethostname(), "pending": []}
            else:
                marker = _new_marker(out, command, mode=mode, pending=[])
            marker = _write_marker(out, marker)
        except OSError as exc:
            _reraise(exc, f"`out` = {str(out)!r}")
        return cls(out, marker, action)

    def _save(self) -> None:
        self.marker = _write_marker(self.out, self.marker)

    def mkdir(self, rel: str) -> Path:
        """Make the subdirectory ``rel`` (listed first)."""
        if rel not in self.marker["dirs"]:
            self.marker["dirs"] = sorted({*self.marker["dirs"], rel})
            self._save()
        (self.out / rel).mkdir(exist_ok=True)
        return self.out / rel

    def write(self, rel: str, data: str | bytes | Callable[[Path], None]) -> Path:
        """Write the file ``rel`` atomically: text, bytes, or ``data(path)`` writes a temporary path.

        Raises
        ------
        OSError
            One line naming the file; nothing half-written is left.
        """
        target = self.out / rel
        part_rel = f"{Path(rel).parent / ('.' + Path(rel).name)}.{secrets.token_hex(4)}.part"
        part_rel = part_rel[2:] if part_rel.startswith("./") else part_rel
        self.marker["pending"] = [*self.marker.get("pending", []), part_rel]
        self._save()   # announced before it exists: a kill leaves nothing unlisted
        part = self.out / part_rel
        try:
            _fill_file(part, data)
            was = self.marker["files"].get(rel)
            was = None if was is None else {k: v for k, v in was.items() if k != "was"}
            new = _digest(part)
            if was is not None:   # either content is ours until the record below
                self.marker["files"] = {**self.marker["files"], rel: {**new, "was": was}}
                self._save()
            os.replace(part, target)
            self.marker["files"] = {**self.marker["files"], rel: new}
        except BaseException as exc:
            part.unlink(missing_ok=True)
            if isinstance(exc, OSError):
                _reraise(exc, repr(str(target)))
            raise
        finally:
            self.marker["pending"] = [p for p in self.marker["pending"] if p != part_rel]
            self._save()
        return target

    def remove(self, rel: str) -> None:
        """Remove the listed file ``rel`` if it is unchanged (an edited one is kept and stays listed)."""
        rec = self.marker["files"].get(rel)
        if rec is None:
            return
        if os.path.lexists(self.out / rel):
            if not _unchanged(self.out / rel, rec):
                return
            os.unlink(self.out / rel)
        self.marker["files"] = {k: v for k, v in self.marker["files"].items() if k != rel}
        self._save()

    def log_lines(self, rel: str) -> bytes:
        """The whole lines of the log ``rel`` (a line torn by a kill is cut off the file)."""
        path = self.out / rel
        if not os.path.lexists(path):
            return b""
        data = path.read_bytes()
        end = data.rfind(b"\n") + 1
        if end < len(data):            # killed in the middle of a line: drop the fragment
            os.truncate(path, end)
            data = data[:end]
        rec = self.marker["files"].get(rel)
        if rec is not None and end < rec.get("size", 0):
            raise OutputExistsError(f"{str(path)!r} is shorter than threepart wrote it; refusing "
                                    "to resume (move the directory away)")
        self.marker["files"] = {**self.marker["files"], rel: {**_digest(path), "grows": True}}
        self._save()
        return data

    def append(self, rel: str, line: str) -> None:
        """Append ``line`` (and a newline) to the log ``rel``: flushed, fsynced, then recorded."""
        path = self.out / rel
        try:
            fh = self._logs.get(rel)
            if fh is None:
                if rel not in self.marker["files"]:
                    self.marker["files"] = {**self.marker["files"],
                                            rel: {"sha256": hashlib.sha256().hexdigest(), "size": 0,
                                                  "grows": True}}
                    self._save()
                fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0),
                             0o666)
                fh = self._logs[rel] = os.fdopen(fd, "a", encoding="utf-8")
            fh.write(line + "\n")
            fh.flush()
            os.fsync(fh.fileno())
            self.marker["files"] = {**self.marker["files"], rel: {**_digest(path), "grows": True}}
            self._save()
        except OSError as exc:
            _reraise(exc, repr(str(path)))

    def close(self) -> None:
        """Close the open logs."""
        for fh in self._logs.values():
            fh.close()
        self._logs.clear()

    def seal(self, finished: bool) -> None:
        """Record every listed file's final checksum; ``"complete"`` only when nothing is left to do."""
        self.close()
        files = {rel: _digest(self.out / rel) for rel in self.marker["files"]
                 if (self.out / rel).is_file() and not (self.out / rel).is_symlink()}
        self.marker.update({"state": "complete" if finished else "writing", "files": files,
                            "dirs": [d for d in self.marker["dirs"] if (self.out / d).is_dir()],
                            "pending": []})
        self._save()


def _fill_file(part: Path, data: str | bytes | Callable[[Path], None]) -> None:
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


# ---------------------------------------------------------------------------------------
# single files
# ---------------------------------------------------------------------------------------
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
            or not _signature_holds(doc, Path(os.path.abspath(directory)))):
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
        raise ValueError(f"{q} is not a file name")
    if path.name in (LEDGER, MARKER) or path.name.endswith(".part"):
        raise ValueError(f"{q}: the name is threepart's own bookkeeping; choose another name")
    if not directory.is_dir():
        raise ValueError(f"{q}: directory does not exist" if not os.path.lexists(directory)
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
    if overwrite or _unchanged(path, recorded.get(path.name)):
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
    path
        The file to write.
    data
        Text (written as UTF-8), bytes, or a function that writes the file at
        the path it is given (e.g. a meshio writer).
    arg
        The name of the caller's argument, for the messages (e.g. ``"--csv"``).
    overwrite
        Replace an existing regular file even if threepart did not write it.
    how
        What a refusal tells the user to do instead.

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
        _write_json(directory / LEDGER, _signed({"tool": "threepart", "format": MARKER_FORMAT,
                                                  "files": files}, directory))

    try:
        recorded, _ = _read_ledger(directory)
        files = {k: v for k, v in (recorded or {}).items() if os.path.lexists(directory / k)}
        try:
            _fill_file(part, data)
            new = _digest(part)
            was = files.get(path.name)
            was = None if was is None else {k: v for k, v in was.items() if k != "was"}
            if was is not None:   # either content is ours until the record below
                record({**files, path.name: {**new, "was": was}})
            os.replace(part, path)
        finally:
            part.unlink(missing_ok=True)
        _fsync_dir(directory)
        record({**files, path.name: new})
    except OSError as exc:
        _reraise(exc, q)
    return path


# ---------------------------------------------------------------------------------------
# scratch directories
# ---------------------------------------------------------------------------------------
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
                or not _signature_holds(doc, path) or writer_running(doc)):
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
        doc = _signed({"tool": "threepart", "kind": "scratch", "pid": os.getpid(),
                       "host": socket.gethostname()}, path)
        (path / SCRATCH_MARKER).write_text(json.dumps(doc) + "\n", encoding="utf-8")
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def json_safe(v: Any) -> Any:
    """A JSON-safe copy of ``v``: non-finite floats become None, numpy scalars Python numbers.

    The one sanitiser of every JSON that threepart writes (reports, studies,
    the command line's ``--json``). Dict keys become strings; anything that is
    not a JSON scalar, list or dict becomes its ``str``.
    """
    if isinstance(v, dict):
        return {str(k): json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [json_safe(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, (str, bytes)):
        try:
            v = v.item()
        except (ValueError, AttributeError):
            return str(v)
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if v is None or isinstance(v, (bool, int, str)):
        return v
    return str(v)


def strict_json(doc: Any, **kwargs: Any) -> str:
    """``json.dumps(doc)`` as strict JSON: infinite and NaN floats become ``null``.

    Parameters
    ----------
    doc
        Nested dicts, lists and JSON scalars (numpy scalars are converted).
    **kwargs
        Passed on to :func:`json.dumps` (e.g. ``indent``).

    Returns
    -------
    str
        Text that any JSON parser reads; never ``NaN`` or ``Infinity``.
    """
    return json.dumps(json_safe(doc), allow_nan=False, **kwargs)


def validate_json(doc: Any, schema_file: str | Path) -> None:
    """Validate ``doc`` against the JSON schema in ``schema_file`` (skipped without ``jsonschema``).

    Raises
    ------
    jsonschema.ValidationError
        If ``doc`` does not match the schema.
    """
    try:
        import jsonschema
    except ImportError:  # pragma: no cover - jsonschema is in the test extra
        return
    jsonschema.validate(doc, json.loads(Path(schema_file).read_text(encoding="utf-8")))

"""Output directories written by threepart: atomic, marked, and never over anyone else's files.

A command that writes a directory (``threepart verify``, ``threepart figures``)
writes it through :func:`atomic_dir`:

1. Leftovers of an earlier run that was killed (``.<name>.*.tmp`` and
   ``.<name>.old-*`` beside ``out``) are removed, but only those that carry
   threepart's marker and whose process is gone.
2. ``out`` is checked before any work. It may be missing or an empty
   directory. An existing directory is replaced only with ``force``, and only
   if it carries the marker :data:`MARKER` and holds nothing but the files the
   marker lists; anything else is refused with :class:`OutputExistsError`,
   whose one-line message names the directory and the first foreign file.
3. The files are written into a temporary sibling directory that carries the
   marker from its creation. When the block succeeds, the marker is rewritten
   with the list of every file written, the permissions are set to
   ``0o777 & ~umask`` (directories) and ``0o666 & ~umask`` (files), and the
   directory is renamed into place. When the block fails, or is interrupted,
   the temporary directory is removed and ``out`` is left as it was.

Nothing is ever removed that the marker does not show threepart wrote.

Names
-----
MARKER              -- file name of the marker, ``.threepart-output.json``
OutputExistsError   -- ``out`` may not be written or replaced (a ``ValueError``)
atomic_dir          -- context manager: a temporary directory that replaces ``out`` on success
check_out           -- the check of step 2 alone
clean_stale         -- step 1 alone; returns the leftovers it removed
read_marker         -- the marker of a directory, or None
write_marker        -- write a directory's marker (a resumable output keeps its own up to date)
writer_running      -- whether the process a marker names is still running
foreign_entries     -- the entries of a directory that its marker does not list
json_safe           -- a JSON-safe copy: non-finite floats as None, numpy scalars as Python numbers
strict_json         -- ``json.dumps`` that writes non-finite numbers as null, never NaN/Infinity
validate_json       -- check a document against a JSON schema file (jsonschema)
"""
from __future__ import annotations

import datetime as _dt
import json
import math
import os
import shutil
import socket
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator, Literal

__all__ = ["MARKER", "OutputExistsError", "atomic_dir", "check_out", "clean_stale", "read_marker",
           "write_marker", "writer_running",
           "foreign_entries", "json_safe", "strict_json", "validate_json", "current_umask"]

#: file name of the marker that every directory written by threepart carries
MARKER = ".threepart-output.json"
#: version of the marker's layout
MARKER_FORMAT = 1
_UMASK_LOCK = threading.Lock()

State = Literal["new", "empty", "ours"]


class OutputExistsError(ValueError):
    """``out`` may not be written: it exists without ``force``, or holds files threepart did not write."""


# ---------------------------------------------------------------------------------------
# the marker
# ---------------------------------------------------------------------------------------
def write_marker(directory: Path, doc: dict[str, Any]) -> None:
    """Write the marker of ``directory`` atomically (a sibling file, then a rename)."""
    part = directory / (MARKER + ".part")
    part.write_text(json.dumps(doc, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    os.replace(part, directory / MARKER)


def read_marker(directory: str | Path) -> dict[str, Any] | None:
    """The marker of ``directory``, or None if it has none or the file is not threepart's.

    Parameters
    ----------
    directory
        A directory that threepart may have written.

    Returns
    -------
    dict or None
        The marker's contents: ``tool``, ``format``, ``command``, ``state``
        (``"writing"`` or ``"complete"``), ``target``, ``pid``, ``host``,
        ``created``, ``files`` and ``dirs`` (paths relative to ``directory``).
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
    for key in ("files", "dirs"):
        items = doc.get(key)
        if not isinstance(items, list) or not all(isinstance(x, str) for x in items):
            return None
    return doc


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
            if not rel and e.name == MARKER:
                continue
            if e.is_dir(follow_symlinks=False):
                dirs.append(name)
                visit(Path(e.path), name + "/")
            else:
                files.append(name)

    visit(root, "")
    return files, dirs


def _foreign(directory: Path) -> Iterator[str]:
    """The entries under ``directory`` that its marker does not list, in sorted order, lazily.

    Without a marker every top-level entry is foreign. An unlisted directory is
    reported once; its contents are not visited.
    """
    marker = read_marker(directory)
    if marker is None:
        with os.scandir(directory) as it:
            yield from sorted(e.name for e in it)
        return
    listed_files, listed_dirs = set(marker["files"]), set(marker["dirs"])

    def visit(d: Path, rel: str) -> Iterator[str]:
        with os.scandir(d) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            name = f"{rel}{e.name}"
            if not rel and e.name == MARKER:
                continue
            if e.is_dir(follow_symlinks=False):
                if name not in listed_dirs:
                    yield name + "/"
                else:
                    yield from visit(Path(e.path), name + "/")
            elif name not in listed_files:
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
        threepart wrote everything in it.
    """
    return list(_foreign(Path(directory)))


def _remove_owned(directory: Path) -> bool:
    """Remove ``directory`` if its marker lists everything in it; return whether it was removed.

    Only the listed files and directories are removed, one by one (never
    ``shutil.rmtree``); anything unlisted leaves the whole directory in place.
    """
    try:
        if directory.is_symlink() or read_marker(directory) is None or next(_foreign(directory), None):
            return False
        files, dirs = _walk(directory)
        for f in files:
            os.unlink(directory / f)
        for d in sorted(dirs, key=lambda s: s.count("/"), reverse=True):
            os.rmdir(directory / d)
        os.unlink(directory / MARKER)
        os.rmdir(directory)
    except OSError:
        return False
    return True


def _remove_tmp(tmp: Path) -> None:
    """Remove a temporary directory of threepart's, its marker last.

    The marker goes last so that, were this interrupted too, the rest would
    still be recognised (and removed) by the next run.
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

    A leftover is removed only if it carries threepart's marker for the target
    ``out`` and the process that made it is gone. A temporary directory
    (``.<name>.*.tmp``, marker state ``"writing"``) holds only what that run
    had written, so it is removed as a whole; an ``.old-`` directory (a
    complete earlier output) loses only the files its marker lists.

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
        if marker is None or writer_running(marker):
            continue
        if is_tmp and marker.get("state") == "writing":
            # created by threepart for this very `out` (the marker is written right at its
            # creation); it holds what that run wrote before it was killed, not yet listed
            if marker.get("target") != out.name:
                continue
            _remove_tmp(path)
            if not path.exists():
                removed.append(path)
        elif _remove_owned(path):    # a complete output: only the files its marker lists
            removed.append(path)
    return removed


# ---------------------------------------------------------------------------------------
# the check and the atomic write
# ---------------------------------------------------------------------------------------
def _contains_cwd(out: Path) -> bool:
    try:
        cwd = Path.cwd().resolve()
        target = out.resolve()
    except OSError:
        return False
    return cwd == target or target in cwd.parents


def check_out(out: str | Path, force: bool = False) -> State:
    """Check that ``out`` may be written, before any work.

    Parameters
    ----------
    out
        The output directory.
    force
        Replace a directory that threepart wrote earlier.

    Returns
    -------
    {"new", "empty", "ours"}
        ``out`` does not exist, is an empty directory, or is threepart's own
        output that ``force`` allows to replace.

    Raises
    ------
    OutputExistsError
        If ``out`` is not a directory, holds a file threepart did not write, or
        is threepart's output and ``force`` is false. The message is one line
        and names the directory (and the first foreign file).
    """
    out = Path(os.path.abspath(out))
    q = f"`out` = {str(out)!r}"
    if not out.name:
        raise OutputExistsError(f"{q} is a filesystem root; choose a directory to write into")
    if not os.path.lexists(out):
        return "new"
    if out.is_symlink():
        raise OutputExistsError(f"{q} is a symbolic link; threepart writes only a real directory")
    if not out.is_dir():
        raise OutputExistsError(f"{q} exists and is not a directory; choose another --out")
    first = next(_foreign(out), None)   # sorted order; stops at the first
    if read_marker(out) is None:
        if first is None:
            return "empty"
        raise OutputExistsError(f"{q} holds {first!r} and no valid {MARKER}: threepart did not "
                                "write it; refusing to touch it, choose another --out")
    if first is not None:
        raise OutputExistsError(f"{q} holds {first!r}, which threepart did not write; refusing "
                                "to replace it (move it away or choose another --out)")
    if not force:
        raise OutputExistsError(f"{q} exists; pass --force to replace it")
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


def _seal(tmp: Path, marker: dict[str, Any]) -> None:
    """List every file written in the marker and give everything normal permissions."""
    stale = tmp / (MARKER + ".part")
    if stale.exists():
        stale.unlink()
    files, dirs = _walk(tmp)
    write_marker(tmp, {**marker, "state": "complete", "files": files, "dirs": dirs})
    umask = current_umask()
    dmode, fmode = 0o777 & ~umask, 0o666 & ~umask
    for f in [*files, MARKER]:
        if not (tmp / f).is_symlink():
            os.chmod(tmp / f, fmode)
    for d in [*dirs, ""]:
        os.chmod(tmp / d, dmode)


def _fill(tmp: Path, out: Path) -> None:
    """Move the contents of ``tmp`` into the empty directory ``out``, the marker first.

    Were this interrupted, ``out`` would hold the marker and some of the files
    it lists: still threepart's own output, which ``force`` replaces.
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
        The output directory: missing, empty, or (with ``force``) threepart's
        own earlier output.
    force
        Replace threepart's own earlier output in ``out``.
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
        If the directory cannot be created or renamed.
    """
    out = Path(os.path.abspath(out))
    clean_stale(out)
    check_out(out, force)
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(exc.errno, f"cannot write `out` = {str(out)!r}: {exc.strerror}") from exc
    marker: dict[str, Any] = {
        "tool": "threepart", "format": MARKER_FORMAT, "command": command, "state": "writing",
        "target": out.name, "pid": os.getpid(), "host": socket.gethostname(),
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "files": [], "dirs": [],
    }
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent))
    except OSError as exc:
        raise OSError(exc.errno, f"cannot write `out` = {str(out)!r}: {exc.strerror}") from exc
    try:
        write_marker(tmp, marker)   # at once, so that a killed run's leftover is recognised
        yield tmp
        _seal(tmp, marker)
        state = check_out(out, force)   # the run may have taken long: check again
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
            _remove_owned(old)
    except BaseException:
        _remove_tmp(tmp)   # this run's own temporary directory (gone already if renamed)
        raise


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

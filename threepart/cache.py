"""threepart's cache of results that depend only on their input: one file per entry, on disk.

The FEM's condensed surface compliance (:func:`fem.elasticity.condense`) is the
costly part of every rigid-punch solve, and depends only on the mesh, the
material and the element; it is kept here, keyed by a hash of all of that
(:func:`key`), so that every solve, load step, cycle and map point on the same
mesh, in this process or a later one, condenses once.

Where
-----
``$THREEPART_CACHE``, else ``$XDG_CACHE_HOME/threepart``, else
``~/.cache/threepart`` (:func:`cache_dir`). A directory that cannot be made or
written leaves the cache in memory only: :func:`store` returns False, nothing
is raised, and nothing is written anywhere else.

Entries
-------
One NumPy ``.npz`` file ``threepart-<kind>-<key>.npz`` per entry, holding the
arrays and a header: the tool, :data:`FORMAT`, the kind, the key and the
SHA-256 of every array (its dtype, shape and bytes). :func:`load` returns an
entry only if all of that holds and every array is finite; anything else (a
truncated file, flipped bytes, a NaN written into it, another format, the
wrong shape the caller's ``check`` finds) is removed, being the file of that
very name in threepart's own directory, and the caller builds the entry again.
Writes are atomic: a temporary sibling ``.threepart-<kind>-<key>.<pid>.<random>.tmp``,
then ``os.replace`` (no fsync: an entry a crash left short fails its checksum and is made again); so concurrent processes (pytest-xdist workers, the
map's dask workers) never read half a file, and the last complete write wins.

What is threepart's own
-----------------------
:func:`entries` lists the directory: an entry is threepart's if its name has
the pattern above and its header and checksums hold. :func:`clear` removes
those, and threepart's own temporary files whose process is gone; it leaves
every other file (a stranger's, or one whose checksum no longer holds) alone.

Names
-----
CACHE_VARIABLE -- ``THREEPART_CACHE``, the environment variable naming the directory
FORMAT         -- version of the entries' layout (part of every key)
cache_dir      -- the cache's directory
key            -- the SHA-256 key of the parts that determine an entry
load           -- an entry's arrays, or None (a damaged entry removed)
store          -- write an entry atomically; False if the directory cannot be written
Entry          -- one file of the cache: path, kind, size, whether it is threepart's own
entries        -- the files of the cache directory, threepart's and others
clear          -- remove threepart's entries; the number removed
cached_run     -- run another code in a directory, or write back the files an identical run wrote
restored       -- whether a directory's files came from the cache in this process
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import secrets
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from threepart.errors import InputError

__all__ = ["CACHE_VARIABLE", "FORMAT", "cache_dir", "key", "load", "store", "Entry", "entries",
           "clear", "cached_run", "restored"]

#: the environment variable that names the cache directory
CACHE_VARIABLE = "THREEPART_CACHE"
#: version of the entries' layout; part of every key, so a new layout never reads an old one
FORMAT = 1
_NAME = re.compile(r"^threepart-([a-z][a-z0-9_]*)-([0-9a-f]{64})\.npz$")
_TMP = re.compile(r"^\.threepart-[a-z][a-z0-9_]*-[0-9a-f]{64}\.(\d+)\.[0-9a-f]{8}\.tmp$")
_HEADER = "__threepart__"


def cache_dir() -> Path:
    """``$THREEPART_CACHE``, else ``$XDG_CACHE_HOME/threepart``, else ``~/.cache/threepart``."""
    env = os.environ.get(CACHE_VARIABLE)
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "threepart"


def _feed(h: Any, name: str, value: Any) -> None:
    h.update(name.encode("utf-8") + b"\0")
    if isinstance(value, np.ndarray):
        a = np.ascontiguousarray(value)
        h.update(f"{a.dtype.str}{a.shape}".encode("ascii"))
        h.update(a.tobytes())
    else:
        h.update(repr(value).encode("utf-8"))
    h.update(b"\1")


def key(parts: Mapping[str, Any]) -> str:
    """The SHA-256 (hex) of ``parts`` (arrays by dtype, shape and bytes; other values by ``repr``)
    and :data:`FORMAT`, in the order of the names."""
    h = hashlib.sha256()
    _feed(h, "format", FORMAT)
    for name in sorted(parts):
        _feed(h, name, parts[name])
    return h.hexdigest()


def _digest(a: np.ndarray) -> str:
    h = hashlib.sha256()
    _feed(h, "array", a)
    return h.hexdigest()


def _path(kind: str, k: str) -> Path:
    name = f"threepart-{kind}-{k}.npz"
    if not _NAME.match(name):
        raise InputError(f"cache entry name {name!r} lacks the pattern of threepart's entries")
    return cache_dir() / name


def _read(path: Path, kind: str | None = None, k: str | None = None) -> dict[str, np.ndarray] | None:
    """The arrays of the entry at ``path`` if its header and checksums hold, else None."""
    try:
        with np.load(path, allow_pickle=False) as z:
            header = json.loads(str(z[_HEADER][()]))
            if (not isinstance(header, dict) or header.get("tool") != "threepart"
                    or header.get("format") != FORMAT
                    or (kind is not None and header.get("kind") != kind)
                    or (k is not None and header.get("key") != k)
                    or not isinstance(header.get("arrays"), dict)
                    or set(header["arrays"]) != set(z.files) - {_HEADER}):
                return None
            arrays = {name: z[name] for name in header["arrays"]}
    except Exception:   # noqa: BLE001 -- any damage (zip, npy, json, truncation) means: not an entry
        return None
    for name, a in arrays.items():
        if _digest(a) != header["arrays"][name]:
            return None
        if a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
            return None
    return arrays


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass


def load(kind: str, k: str, check: Callable[[dict[str, np.ndarray]], bool] | None = None
         ) -> dict[str, np.ndarray] | None:
    """The arrays of entry ``kind``/``k``, or None when there is none or it is damaged.

    An entry whose header, checksums or finiteness fail, or that ``check`` (the
    caller's test of its shapes) rejects, is removed: it is the file of that
    very name in threepart's own directory. A directory that cannot be read
    counts as an empty cache.
    """
    path = _path(kind, k)
    if not path.is_file():
        return None
    arrays = _read(path, kind, k)
    if arrays is None or (check is not None and not check(arrays)):
        _remove(path)
        return None
    return arrays


def store(kind: str, k: str, arrays: Mapping[str, np.ndarray]) -> bool:
    """Write entry ``kind``/``k`` atomically (a temporary sibling, then ``os.replace``).

    Returns False, writing nothing, if the directory cannot be made or written:
    the caller keeps its result in memory only.
    """
    path = _path(kind, k)
    header = {"tool": "threepart", "format": FORMAT, "kind": kind, "key": k,
              "arrays": {name: _digest(np.asarray(a)) for name, a in arrays.items()}}
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.{secrets.token_hex(4)}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o666)
        try:
            with os.fdopen(fd, "wb") as fh:
                members: dict[str, Any] = {_HEADER: np.array(json.dumps(header))}
                members.update((name, np.asarray(a)) for name, a in arrays.items())
                np.savez(fh, **members)   # no fsync: a file a crash cut short fails its checksum
            os.replace(tmp, path)
        except BaseException:
            _remove(tmp)
            raise
    except OSError:
        return False
    return True


@dataclass(frozen=True)
class Entry:
    """One file of the cache directory.

    Attributes
    ----------
    path
        The file.
    kind
        The entry's kind (``"compliance"``), or ``""`` for a file that is not threepart's.
    size
        Bytes.
    ours
        Whether it is threepart's own: the name's pattern, the header and every checksum hold.
    """

    path: Path
    kind: str
    size: int
    ours: bool


def entries() -> list[Entry]:
    """The files in the cache directory (none if it does not exist), threepart's and others, by name."""
    out = []
    try:
        listing = sorted(os.scandir(cache_dir()), key=lambda e: e.name)
    except OSError:
        return []
    for e in listing:
        if e.is_symlink() or not e.is_file():
            continue
        m = _NAME.match(e.name)
        ours = m is not None and _read(Path(e.path), m.group(1), m.group(2)) is not None
        out.append(Entry(Path(e.path), m.group(1) if m else "", e.stat().st_size, ours))
    return out


def _pid_gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:
        return False
    return False


def clear() -> int:
    """Remove threepart's own entries and its dead processes' temporary files; the number removed.

    Any other file in the directory (not of threepart's pattern, or whose header
    or checksums do not hold) is left alone, as is the directory itself.
    """
    removed = 0
    for e in entries():
        if e.ours:
            _remove(e.path)
            removed += 1
    try:
        listing = list(os.scandir(cache_dir()))
    except OSError:
        return removed
    for d in listing:
        m = _TMP.match(d.name)
        if m and not d.is_symlink() and d.is_file() and _pid_gone(int(m.group(1))):
            _remove(Path(d.path))
            removed += 1
    return removed


#: directories :func:`cached_run` filled from the cache in this process
_RESTORED: set[Path] = set()


def cached_run(kind: str, parts: Mapping[str, Any], workdir: Path, run: Callable[[], None]) -> bool:
    """Run another code in ``workdir`` (``run()``), or write back the files an identical run wrote.

    ``parts`` is everything the run's files depend on (its input's text, the code and
    its version: :func:`key`). On a miss ``run()`` runs and every file it wrote or
    changed in ``workdir`` is stored as one entry (its bytes, checksummed); a run
    that raises stores nothing. On a hit those files are written into ``workdir``
    as they were, and ``run()`` is not called: the readers read them as they would
    the run's. True on a hit (:func:`restored` then names ``workdir``).
    """
    workdir = Path(workdir)
    k = key(parts)
    entry = load(kind, k)
    if entry is not None:
        for name, data in entry.items():
            (workdir / name).write_bytes(np.asarray(data, dtype=np.uint8).tobytes())
        _RESTORED.add(workdir.resolve())
        return True
    before = {f.name: f.stat().st_mtime_ns for f in workdir.iterdir() if f.is_file()}
    run()
    wrote = {f.name: np.frombuffer(f.read_bytes(), dtype=np.uint8) for f in sorted(workdir.iterdir())
             if f.is_file() and not f.is_symlink() and before.get(f.name) != f.stat().st_mtime_ns}
    store(kind, k, wrote)
    _RESTORED.discard(workdir.resolve())
    return False


def restored(workdir: Path) -> bool:
    """Whether :func:`cached_run` wrote ``workdir``'s files from the cache (in this process)."""
    return Path(workdir).resolve() in _RESTORED

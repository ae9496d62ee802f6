"""A marked directory written in place, file by file, and resumed after an interrupt (``threepart map``).

Names
-----
ResumableDir -- open, write, append to a log, remove and seal such a directory
"""
from __future__ import annotations

import hashlib
import os
import secrets
import socket
from pathlib import Path
from typing import Any, Callable

from .atomic import OutputExistsError, digest, fill_file, reraise, unchanged
from .dirs import check_dir
from .markers import (leftover_parts, new_marker, read_marker, remove_listed, why_not_ours,
                      write_marker, writer_running)

__all__ = ["ResumableDir"]


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
        if not check_dir(out, q) or (read_marker(out) is None and not os.listdir(out)):
            return "new"
        problem = why_not_ours(out)
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
                remove_listed(out, existing)
            out.mkdir(parents=True, exist_ok=True)
            if existing is not None and action == "resumed":
                for p in leftover_parts(existing):
                    if os.path.lexists(out / p) and not (out / p).is_dir():
                        os.unlink(out / p)
                marker = {**existing, "pid": os.getpid(), "host": socket.gethostname(), "pending": []}
            else:
                marker = new_marker(out, command, mode=mode, pending=[])
            marker = write_marker(out, marker)
        except OSError as exc:
            reraise(exc, f"`out` = {str(out)!r}")
        return cls(out, marker, action)

    def _save(self) -> None:
        self.marker = write_marker(self.out, self.marker)

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
            fill_file(part, data)
            was = self.marker["files"].get(rel)
            was = None if was is None else {k: v for k, v in was.items() if k != "was"}
            new = digest(part)
            if was is not None:   # either content is ours until the record below
                self.marker["files"] = {**self.marker["files"], rel: {**new, "was": was}}
                self._save()
            os.replace(part, target)
            self.marker["files"] = {**self.marker["files"], rel: new}
        except BaseException as exc:
            part.unlink(missing_ok=True)
            if isinstance(exc, OSError):
                reraise(exc, repr(str(target)))
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
            if not unchanged(self.out / rel, rec):
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
        self.marker["files"] = {**self.marker["files"], rel: {**digest(path), "grows": True}}
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
            self.marker["files"] = {**self.marker["files"], rel: {**digest(path), "grows": True}}
            self._save()
        except OSError as exc:
            reraise(exc, repr(str(path)))

    def close(self) -> None:
        """Close the open logs."""
        for fh in self._logs.values():
            fh.close()
        self._logs.clear()

    def seal(self, finished: bool) -> None:
        """Record every listed file's final checksum; ``"complete"`` only when nothing is left to do."""
        self.close()
        files = {rel: digest(self.out / rel) for rel in self.marker["files"]
                 if (self.out / rel).is_file() and not (self.out / rel).is_symlink()}
        self.marker.update({"state": "complete" if finished else "writing", "files": files,
                            "dirs": [d for d in self.marker["dirs"] if (self.out / d).is_dir()],
                            "pending": []})
        self._save()



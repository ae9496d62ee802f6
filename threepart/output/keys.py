"""The signature: a per-user key, and an HMAC bound to the absolute path of what it signs.

A marker or a ledger is threepart's own only if its signature holds for the
very directory it lies in, so a hand-written, edited or copied one does not
count.

Names
-----
state_dir       -- where the per-user key lives (``$THREEPART_STATE_DIR`` or ``~/.local/state/threepart``)
sign            -- a copy of a document with its path and its HMAC-SHA-256
signature_holds -- whether a document was signed by this user's key for a path
"""
from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
import threading
from pathlib import Path
from typing import Any

__all__ = ["state_dir", "sign", "signature_holds"]

_KEY_LOCK = threading.Lock()
_KEY: dict[str, bytes] = {}


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


def sign(doc: dict[str, Any], where: Path) -> dict[str, Any]:
    signed = {**{k: v for k, v in doc.items() if k != "mac"}, "path": str(where)}
    signed["mac"] = _mac(signed)
    return signed


def signature_holds(doc: dict[str, Any], where: Path) -> bool:
    """Whether ``doc`` was signed by threepart (this user's key) for the directory ``where``."""
    mac = doc.get("mac")
    return (isinstance(mac, str) and doc.get("path") == str(where)
            and hmac.compare_digest(mac, _mac(doc)))


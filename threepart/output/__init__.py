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
key (:func:`state_dir`, :mod:`.keys`), of its contents and the absolute path of the
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

Modules
-------
atomic     -- one file written atomically; checksums; one-line write errors
keys       -- the per-user key and the signature bound to a path
markers    -- a directory's marker: written, read, judged, and what it proves removed
dirs       -- check_out, clean_stale and atomic_dir
resumable  -- ResumableDir
files      -- single files and their ledger: check_file, write_file
scratch    -- scratch_dir
jsonio     -- json_safe, strict_json, validate_json

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
SCRATCH_MARKER      -- file name of a scratch directory's marker
read_marker         -- the marker of a directory, or None
writer_running      -- whether the process a marker names is still running
foreign_entries     -- the entries of a directory that its marker does not list
state_dir           -- where the per-user key lives (``$THREEPART_STATE_DIR`` or ``~/.local/state/threepart``)
json_safe           -- a JSON-safe copy: non-finite floats as None, numpy scalars as Python numbers
strict_json         -- ``json.dumps`` that writes non-finite numbers as null, never NaN/Infinity
validate_json       -- check a document against a JSON schema file (jsonschema)
current_umask       -- the process's umask, read without changing it where the system allows
"""
from __future__ import annotations

from .atomic import OutputExistsError, current_umask
from .dirs import atomic_dir, check_out, clean_stale
from .files import LEDGER, check_file, write_file
from .jsonio import json_safe, strict_json, validate_json
from .keys import state_dir
from .markers import MARKER, MARKER_FORMAT, foreign_entries, read_marker, writer_running
from .resumable import ResumableDir
from .scratch import SCRATCH_MARKER, scratch_dir

__all__ = ["MARKER", "LEDGER", "MARKER_FORMAT", "SCRATCH_MARKER", "OutputExistsError", "atomic_dir",
           "check_out", "clean_stale", "ResumableDir", "write_file", "check_file", "scratch_dir",
           "read_marker", "writer_running", "foreign_entries", "state_dir", "json_safe", "strict_json",
           "validate_json", "current_umask"]

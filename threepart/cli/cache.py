"""``threepart cache``: threepart's cache of condensed FE compliances, shown or cleared.

The cache (:mod:`threepart.cache`) lives in ``$THREEPART_CACHE``, else the
user's cache directory (``~/.cache/threepart``). ``threepart cache`` prints the
directory, each entry with its kind and size, and the total; ``--clear``
removes threepart's own entries (their name, header and checksums hold) and
nothing else: any other file in the directory is named and left alone.
"""
from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``cache`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("cache", help="the cache of condensed FE compliances: its directory, entries "
                                     "and sizes; --clear removes threepart's own entries")
    p.add_argument("--clear", action="store_true",
                   help="remove threepart's own entries (never a file threepart did not write)")
    p.set_defaults(func=run)


def _size(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB"):
        if n < 1000 or unit == "GB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n:.1f} GB"


def run(args: argparse.Namespace) -> int:
    """Show the cache, or clear threepart's entries from it; the exit status (0)."""
    from threepart import cache

    where = cache.cache_dir()
    if args.clear:
        removed = cache.clear()
        print(f"cache: {where}: removed {removed} of threepart's entries")
    listing = cache.entries()
    ours = [e for e in listing if e.ours]
    print(f"cache: {where}" + ("" if where.is_dir() else " (not made yet)"))
    for e in ours:
        print(f"  {e.kind:12s} {_size(e.size):>9s}  {e.path.name}")
    print(f"{len(ours)} entries, {_size(sum(e.size for e in ours))}")
    for e in listing:
        if not e.ours:
            print(f"  not threepart's, left alone: {e.path.name}")
    return 0

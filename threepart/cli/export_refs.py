"""``threepart export-refs``: the catalogue's reference solutions as a versioned dataset.

JSON and CSV with a JSON schema (docs/REFERENCE_DATA.md), written by
:func:`threepart.reports.refs.main`.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import FORCE_HELP

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``export-refs`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("export-refs", help="the catalogue's reference solutions as a versioned "
                                           "dataset (docs/REFERENCE_DATA.md)")
    p.add_argument("--out", default="refs",
                   help="output directory: new, empty, or threepart's own earlier export, which is "
                        "replaced (default: ./refs)")
    p.add_argument("--cases", metavar="NAME,...", type=lambda t: t.split(","),
                   help="export only these catalogue cases (default: every case)")
    p.add_argument("--force", action="store_true", help=FORCE_HELP)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Export the reference solutions into ``--out``; the exit status."""
    from threepart.reports.refs import main as refs_main

    return int(refs_main(out=args.out, force=args.force, cases=args.cases))

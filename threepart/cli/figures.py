"""``threepart figures``: the paper's result figures, with the SIE solution as markers.

The figures are drawn by :func:`threepart.reports.figures.main`.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import FORCE_HELP

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``figures`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("figures", help="reproduce the paper's result figures")
    p.add_argument("--out", default="figures",
                   help="output directory: new, empty, or threepart's own earlier figures, which "
                        "are replaced (default: ./figures)")
    p.add_argument("--force", action="store_true", help=FORCE_HELP)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Draw the figures into ``--out``; the exit status."""
    from threepart.reports.figures import main as figures_main

    return int(figures_main(out=args.out, force=args.force))

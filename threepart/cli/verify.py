"""``threepart verify``: the verification run, closed form against SIE and FEM, and its tolerance report.

The run itself is :func:`threepart.reports.verify.report.main`; the exit status is 0
when every tolerance holds, 1 when one fails.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import FORCE_HELP

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``verify`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("verify", help="closed form against SIE and FEM; writes a tolerance report")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="coarse meshes, small n (<= 2 min)")
    mode.add_argument("--full", action="store_true", help="adds the slow convergence studies")
    p.add_argument("--out", default="report",
                   help="output directory: new, empty, or threepart's own earlier report, which is "
                        "replaced (default: ./report)")
    p.add_argument("--force", action="store_true", help=FORCE_HELP)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run the verification in the mode asked for; 0 if every tolerance holds, else 1."""
    from threepart.reports.verify.report import main as verify_main

    mode = "quick" if args.quick else "full" if args.full else "default"
    return int(verify_main(mode=mode, out=args.out, force=args.force))

"""``threepart map``: where the half-plane formulas stop, the finite-body validity map.

The sweep runs on dask.distributed (:func:`threepart.reports.map.main`); the
exit status is 0 when every point is done and the control within 1e-3, 1
otherwise, 130 when interrupted (run it again to resume).
"""
from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_parser", "run"]


class _MapHelp(argparse.HelpFormatter):
    """The help of ``map``: the quick grid's size and the CPUs counted, only when help is shown."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        if text and "{quick_points}" in text:
            from threepart.reports.map.validity import map_points

            text = text.replace("{quick_points}", str(len(map_points(True))))
        if text and "{max_workers}" in text:
            from threepart.reports.map.sweep import MAX_WORKERS

            text = text.replace("{max_workers}", str(MAX_WORKERS))
        return text


def add_parser(sub: Any) -> None:
    """Add ``map`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("map", help="where the half-plane formulas stop: finite-body validity map",
                       formatter_class=_MapHelp)
    p.add_argument("--quick", action="store_true",
                   help="the quick grid ({quick_points} points and the control, quick meshes)")
    p.add_argument("--out", default="map",
                   help="output directory: new or empty, or an unfinished map to resume; see "
                        "--force (default: ./map)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a running dask scheduler, e.g. tcp://host:8786 (default: a local cluster)")
    p.add_argument("--workers", type=int, metavar="N",
                   help="worker processes of the local cluster, 1 to the CPUs of this machine "
                        "({max_workers} here) (default: 2)")
    p.add_argument("--force", action="store_true",
                   help="replace a finished map in --out (a map is expensive: never without "
                        "--force; only one threepart wrote, unchanged); an unfinished map of the "
                        "same mode is resumed, with or without it")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run (or resume) the map into ``--out``; the exit status."""
    from threepart.reports.map.sweep import main as map_main

    return int(map_main(out=args.out, quick=args.quick, scheduler=args.scheduler,
                        workers=args.workers, force=args.force))

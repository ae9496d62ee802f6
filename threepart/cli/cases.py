"""``threepart cases``: the catalogue's cases (threepart/problem/cases.json), each with its kind and description.

Every command that takes a problem takes one of them by name (``--case NAME``);
this lists them, and the commands that take ``--case``. ``--json`` prints each
case's inputs (:meth:`threepart.problem.catalogue.Case.as_dict`).

Building the parser loads no numpy: the catalogue is read inside ``run``.
"""
from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_parser", "run", "KINDS"]

#: the kinds of case (:attr:`threepart.problem.catalogue.Case.kind`), each with what it holds
KINDS = {"normal": "P and s", "slip": "P, s, Q, f (and a bulk stress)",
         "fretting": "P, s and the amplitude Q_max of Q = 0 -> Q_max -> -Q_max -> Q_max",
         "steady": "a flight cycle's two states (P, s, Q, sigma_bulk) and f"}
#: the keys of :meth:`Case.as_dict` that are ratios (the others' units are threepart.problem.units.UNITS')
RATIOS = ("s_lift_off_fraction", "load_4PA_over_b", "Q_over_fP")


def add_parser(sub: Any) -> None:
    """Add ``cases`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("cases", help="list the catalogue's cases, for --case NAME",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kind", choices=tuple(KINDS),
                   help="only the cases of this kind: " + "; ".join(f"{k}: {v}" for k, v in KINDS.items()))
    p.add_argument("--json", action="store_true", help="print each case's inputs as strict JSON")
    p.set_defaults(func=run)


def _commands() -> list[str]:
    """The sub-commands that take ``--case``, read from the parser itself."""
    from ._main import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return [name for name, p in sub.choices.items()
            if any("--case" in a.option_strings for a in p._actions)]


def run(args: argparse.Namespace) -> int:
    """Print the cases (of ``--kind``), as text or ``--json``; the exit status."""
    from threepart.problem.catalogue import load_cases
    from threepart.problem.units import UNITS

    from ._output import print_json

    cases = [c for c in load_cases(None) if args.kind is None or c.kind == args.kind]
    if args.json:
        units = {**{k: UNITS[k] for k in ("R1", "R2", "b", "R", "E", "nu", "A", "P", "s", "f", "Q",
                                          "sigma_bulk")}, **{k: "1" for k in RATIOS}}
        print_json({"cases": [c.as_dict() for c in cases]}, units)
        return 0
    width = max(len(c.name) for c in load_cases(None))
    print(f"{'NAME':<{width}}  {'KIND':<8}  DESCRIPTION")
    for c in cases:
        print(f"{c.name:<{width}}  {c.kind:<8}  {c.description}")
    print(f"\n{len(cases)} case{'' if len(cases) == 1 else 's'}; give one as --case NAME to: {', '.join(_commands())}")
    return 0

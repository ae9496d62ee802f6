"""``threepart compare``: judge another code's contact pressure (and, with ``--Q --f``, its shear) against threepart.

The pressure is read by its file's suffix (:mod:`threepart.readers`: CSV, CalculiX
.frd/.dat, VTU/XDMF/MED/Exodus through meshio); the judging and its
report are :func:`threepart.reports.referee.main`, against the normal problem
that :func:`threepart.solve` answers for ``--case`` or the punch and loads, or,
given ``--Q`` and ``--f``, against its partial slip: the file's shear ``q`` too
(its stick zone, ``∫q = Q``, Coulomb's bound and the friction pitfalls).
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import labelled, problem, problem_args
from threepart.errors import InputError

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``compare`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("compare", help="judge another code's contact pressure (and shear) against threepart")
    from threepart import readers

    p.add_argument("--pressure", required=True, metavar="FILE",
                   help="another code's contact pressure (p >= 0 compressive), read by its suffix: "
                        + readers.describe() + "; a mesh file's field and surface: --field, --surface")
    p.add_argument("--field", help="a mesh file's point field of the pressure (default: the first of "
                                   "contact_pressure, CPRESS, pressure, ...)")
    p.add_argument("--surface", help="a mesh file's node set (or marker field) of the contact surface "
                                     "(default: the nodes at y = 0)")
    problem_args(p, compliance_option=True)
    g = p.add_argument_group("partial slip: judge the shear q too (the file must carry it)")
    g.add_argument("--Q", type=float, help=labelled("the shear force the model applied after P, |Q| < f P", "Q"))
    g.add_argument("--f", type=float, help="the model's coefficient of friction")
    g.add_argument("--shear", help="a mesh file's point field of the shear the punch exerts on the substrate "
                                   "along +x (GetFEM's deck: contact_shear)")
    g.add_argument("--stick-slope", type=float, metavar="K_T",
                   help="the model's stick slope (tangential penalty) [MPa/mm], for its diagnosis")
    p.add_argument("--alpha", type=float, help=labelled("the model's tilt, if known", "alpha"))
    p.add_argument("--penalty", type=float, metavar="K",
                   help="the model's penalty stiffness [MPa/mm], for the penalty diagnosis")
    p.add_argument("--out", default="compare",
                   help="report directory: new, empty, or threepart's own earlier report "
                        "(default: ./compare)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Judge ``--pressure`` and write the report into ``--out``; the referee's exit status."""
    from threepart.methods import solve
    from threepart.reports.referee import main as referee_main
    from threepart.results import NormalResult, SlipResult

    _compare_iv(args)
    pr = problem(args)
    A = args.A if args.A is not None else pr["A"]
    shear = {} if args.Q is None else {"Q": args.Q, "f": args.f}
    ref = solve(pr["punch"], pr["P"], pr["s"], A=A, tilt=pr["tilt"], **shear)
    assert isinstance(ref, NormalResult if args.Q is None else SlipResult)
    options = {k: v for k, v in (("field", args.field), ("surface", args.surface), ("shear", args.shear))
               if v is not None}
    return int(referee_main(args.pressure, ref, out=args.out, alpha=args.alpha, penalty=args.penalty,
                            stick_slope=args.stick_slope, **options))


def _compare_iv(args: argparse.Namespace) -> None:
    """Check ``compare``'s own options before any numerics or any file is written."""
    from threepart.validate import SLOPE_LIMIT, finite, positive

    if args.alpha is not None and not abs(finite("--alpha", args.alpha)) <= SLOPE_LIMIT:
        raise InputError(f"`--alpha` = {args.alpha!r} rad exceeds the small-slope limit "
                         f"{SLOPE_LIMIT:g} of half-plane theory in magnitude: no model judged "
                         "against it tilts that far")
    if args.penalty is not None:
        positive("--penalty", args.penalty)
    if (args.Q is None) != (args.f is None):
        raise InputError("give both `--Q` and `--f` (a partial slip), or neither (the normal problem)")
    for name, value in (("--stick-slope", args.stick_slope),):
        if value is not None:
            positive(name, value)
    if args.Q is None and (args.shear is not None or args.stick_slope is not None):
        raise InputError("`--shear` and `--stick-slope` judge a partial slip: give `--Q` and `--f` too")

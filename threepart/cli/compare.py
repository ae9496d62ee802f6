"""``threepart compare``: judge another code's contact pressure (and, with ``--Q --f``, its shear) against threepart.

The pressure is read by its file's suffix (:mod:`threepart.readers`: CSV, CalculiX
.frd/.dat, VTU/XDMF/MED/Exodus through meshio); the judging and its
report are :func:`threepart.reports.referee.main`, against the normal problem
that :func:`threepart.solve` answers for ``--case`` or the punch and loads, or,
given ``--Q`` and ``--f``, against its partial slip: the file's shear ``q`` too
(its stick zone, ``∫q = Q``, Coulomb's bound and the friction pitfalls). Given
``--Q-max --f`` (a fretting cycle) or ``--state0 --state1 --f`` (a flight cycle),
a file that records every state (a GetFEM sidecar, a CalculiX friction ``.frd``) is
judged over its last cycle: the friction energy per cycle and the slip amplitude
(:func:`threepart.reports.referee.friction_cycle.main_cycle`).
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import labelled, problem, problem_args, state_args
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
    g.add_argument("--sigma-bulk", type=float, dest="sigma_bulk",
                   help=labelled("the substrate's bulk stress at Q (or Q_max), rising with it in proportion "
                                 "(tension positive)", "sigma_bulk"))
    c = p.add_argument_group("a load cycle: judge the file's states over its last cycle (a GetFEM sidecar "
                             "job.getfem.json, a CalculiX friction .frd), with --f")
    c.add_argument("--Q-max", type=float, dest="Q_max",
                   help=labelled("a fretting cycle 0 -> Q_max -> -Q_max -> Q_max at P: its friction energy "
                                 "per cycle and slip amplitude", "Q"))
    state_args(c, "--P and --s", "the file's last cycle against the periodic steady state (docs/STEADY_STATE.md)")
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

    cycle = _compare_iv(args)
    if args.state0 is not None and args.case is None:     # the states give the normal load
        args.P, args.s = args.state0[0], args.state0[1]
    pr = problem(args)
    A = args.A if args.A is not None else pr["A"]
    if cycle:
        from threepart.reports.referee import friction_cycle

        ref_cycle = (friction_cycle.flight_reference(pr["punch"], args.state0, args.state1, A=A, f=args.f)
                     if cycle == "flight" else
                     friction_cycle.fretting_reference(pr["punch"], pr["P"], pr["s"], A=A, Q_max=args.Q_max, f=args.f,
                                                       tilt=pr["tilt"], sigma_bulk=args.sigma_bulk or 0.0))
        return int(friction_cycle.main_cycle(args.pressure, ref_cycle, out=args.out))
    shear = {} if args.Q is None else {"Q": args.Q, "f": args.f, "sigma_bulk": args.sigma_bulk or 0.0}
    ref = solve(pr["punch"], pr["P"], pr["s"], A=A, tilt=pr["tilt"], **shear)
    assert isinstance(ref, NormalResult if args.Q is None else SlipResult)
    options = {k: v for k, v in (("field", args.field), ("surface", args.surface), ("shear", args.shear))
               if v is not None}
    return int(referee_main(args.pressure, ref, out=args.out, alpha=args.alpha, penalty=args.penalty,
                            stick_slope=args.stick_slope, **options))


def _compare_iv(args: argparse.Namespace) -> str:
    """Check ``compare``'s own options before any numerics or any file is written; the cycle judged
    (``"fretting"``, ``"flight"``) or ``""``."""
    from threepart.problem.checks import finite, positive
    from threepart.problem.validate import SLOPE_LIMIT

    cycle = _cycle_iv(args)
    if args.alpha is not None and not abs(finite("--alpha", args.alpha)) <= SLOPE_LIMIT:
        raise InputError(f"`--alpha` = {args.alpha!r} rad exceeds the small-slope limit "
                         f"{SLOPE_LIMIT:g} of half-plane theory in magnitude: no model judged "
                         "against it tilts that far")
    if args.penalty is not None:
        positive("--penalty", args.penalty)
    if not cycle and (args.Q is None) != (args.f is None):
        raise InputError("give both `--Q` and `--f` (a partial slip), or neither (the normal problem)")
    for name, value in (("--stick-slope", args.stick_slope),):
        if value is not None:
            positive(name, value)
    if args.Q is None and (args.shear is not None or args.stick_slope is not None):
        raise InputError("`--shear` and `--stick-slope` judge a partial slip: give `--Q` and `--f` too")
    return cycle


def _cycle_iv(args: argparse.Namespace) -> str:
    """The cycle judged (``"fretting"`` for ``--Q-max``, ``"flight"`` for ``--state0 --state1``) or ``""``;
    one line naming the option for a combination that judges nothing."""
    from threepart.problem.checks import finite, positive

    states = [k for k in (0, 1) if getattr(args, f"state{k}") is not None]
    if states and len(states) < 2:
        raise InputError(f"a flight cycle needs both `--state0` and `--state1` (got only `--state{states[0]}`)")
    modes = [name for name, given in (("--Q", args.Q is not None), ("--Q-max", args.Q_max is not None),
                                      ("--state0/--state1", bool(states))) if given]
    if len(modes) > 1:
        raise InputError(f"give one of `--Q` (partial slip), `--Q-max` (a fretting cycle) or `--state0/--state1` "
                         f"(a flight cycle), not {' and '.join(f'`{m}`' for m in modes)}")
    if args.sigma_bulk is not None:
        finite("--sigma-bulk", args.sigma_bulk)
        if args.Q is None and args.Q_max is None:
            raise InputError("`--sigma-bulk` rises with the shear: give it with `--Q` or `--Q-max` (a flight "
                             "cycle's states carry their own)")
    if not modes or modes[0] == "--Q":
        return ""
    if args.f is None:
        raise InputError(f"a cycle ({modes[0]}) needs the coefficient of friction `--f`")
    positive("--f", args.f)
    for name, value in (("--alpha", args.alpha), ("--penalty", args.penalty), ("--stick-slope", args.stick_slope),
                        ("--shear", args.shear), ("--field", args.field), ("--surface", args.surface)):
        if value is not None:
            raise InputError(f"`{name}` judges one state's points; a cycle ({modes[0]}) is judged from the "
                             "file's recorded states")
    if args.Q_max is not None:
        positive("--Q-max", args.Q_max)
        return "fretting"
    if args.P is not None or args.s is not None:
        raise InputError("a flight cycle's `--state0`/`--state1` give P and s: leave out `--P` and `--s`")
    return "flight"

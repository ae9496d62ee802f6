"""``threepart deck``: a ready-to-run CalculiX input deck of a catalogue case or of a punch and loads.

The deck is built by :mod:`threepart.calculix` around the contact that
:func:`threepart.solve` predicts; its title carries the compliance to judge it
with (``threepart compare --A``). See docs/CALCULIX.md.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import labelled, problem, problem_args
from threepart.errors import InputError

__all__ = ["add_parser", "run"]


def add_parser(sub: Any) -> None:
    """Add ``deck`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    from threepart.calculix import W_OVER_H

    p = sub.add_parser("deck", help="write a ready-to-run CalculiX deck of a case or a punch",
                       epilog="Units: mm, N/mm, MPa, or any consistent set. See docs/CALCULIX.md.")
    p.add_argument("--format", default="calculix", help="the deck's format: calculix (default)")
    problem_args(p, compliance_option=False)
    p.add_argument("--out", required=True, metavar="FILE.inp",
                   help="the deck to write (a new file, or one threepart wrote there, unchanged)")
    p.add_argument("--h", type=float, help=labelled(
        f"element size at the contact (default W/200; from W/{W_OVER_H[1]:g} to W/{W_OVER_H[0]:g}, "
        "W = a + c the contact width)", "a"))
    p.add_argument("--penalty", type=float, metavar="K",
                   help="penalty stiffness K [MPa/mm] (default 200 E/h)")
    p.add_argument("--pair", action="store_true",
                   help="two similar elastic bodies instead of a stiff punch")
    p.add_argument("--stiffening", type=float,
                   help="the stiff punch's modulus over the block's (default 1000)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Write the deck to ``--out`` and say what it holds; the exit status."""
    from threepart import calculix
    from threepart.material import compliance, rigid_punch_modulus, similar_pair_modulus
    from threepart.methods import solve
    from threepart.output import write_file

    if args.format != "calculix":
        raise InputError(f"`--format` = {args.format!r}: only calculix is written")
    pr = problem(args)
    settings = calculix.DeckSettings(h=args.h, penalty=args.penalty, pair=args.pair,
                                     tilt=pr["tilt"], **({} if args.stiffening is None
                                                         else {"stiffening": args.stiffening}))
    # the problem's A (both bodies of --E/--nu, or the case's) onto the model by threepart.material's
    # one mapping: two similar bodies of 4(1 - nu^2)/A each, or the block of 2(1 - nu^2)/A under the
    # stiff punch (E/2 for two similar bodies of E); A is then the model's own, stiffening included
    nu = pr["nu"]
    E = similar_pair_modulus(pr["A"], nu) if args.pair else rigid_punch_modulus(pr["A"], nu)
    A = compliance(E, nu) if args.pair else compliance(E, nu, E * settings.stiffening, nu)
    ref = solve(pr["punch"], pr["P"], pr["s"], A=A, tilt=pr["tilt"])
    model = calculix.build_model(pr["punch"], ref.a, ref.c, settings)
    deck = calculix.write_deck(model, P=pr["P"], s=pr["s"], E=E, nu=nu, settings=settings,
                               title=(pr["name"] or "a punch from the command line")
                               + f"; judge it with A = {A:.10g}")
    write_file(args.out, deck, arg="--out")
    print(f"wrote {args.out}: {model.n_nodes} nodes, {model.n_elements} elements, h = {model.h0:.4g}, "
          f"K = {settings.K(E, ref.a + ref.c):.4g}; the model's compliance A = {A:.10g} "
          f"(give it to `threepart compare --A`); expected contact [{-ref.a:.6g}, {ref.c:.6g}]")
    return 0

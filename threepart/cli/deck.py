"""``threepart deck``: a ready-to-run CalculiX deck or GetFEM script of a catalogue case or of a punch and loads.

The model is built around the contact that :func:`threepart.solve` predicts; its
title carries the compliance to judge it with (``threepart compare --A``).
Without a shear it is the normal problem (CalculiX: a stiff punch or, with
``--pair``, two similar bodies); with ``--Q --f`` (partial slip: the normal load
first, then ``Q`` in steps) or ``--Q-max --f`` (the fretting cycle
``0 -> Q -> -Q -> Q``) it is two similar elastic bodies with Coulomb friction
(:mod:`threepart.calculix.friction`, :mod:`threepart.getfem`), which every
format writes. See docs/CALCULIX.md and docs/GETFEM.md.
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

    p = sub.add_parser("deck", help="write a ready-to-run CalculiX deck or GetFEM script of a case or a punch",
                       epilog="Units: mm, N/mm, MPa, or any consistent set. See docs/CALCULIX.md and "
                              "docs/GETFEM.md.")
    p.add_argument("--format", default="calculix", choices=FORMATS,
                   help="calculix (an .inp deck, default) or getfem (a Python script run by the "
                        "interpreter that imports getfem; friction only: --Q or --Q-max, and --f)")
    problem_args(p, compliance_option=False)
    g = p.add_argument_group("friction: two similar elastic bodies with Coulomb friction")
    g.add_argument("--Q", type=float, help=labelled("partial slip: the shear force after P, in steps, "
                                                    "|Q| < f P", "Q"))
    g.add_argument("--Q-max", type=float, dest="Q_max",
                   help=labelled("a fretting cycle 0 -> Q_max -> -Q_max -> Q_max instead", "Q"))
    g.add_argument("--f", type=float, help="the coefficient of friction")
    p.add_argument("--out", required=True, metavar="FILE",
                   help="the deck to write (FILE.inp for calculix, FILE.py for getfem: a new file, "
                        "or one threepart wrote there, unchanged)")
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


#: the formats ``--format`` writes
FORMATS = ("calculix", "getfem")


def run(args: argparse.Namespace) -> int:
    """Write the deck to ``--out`` and say what it holds; the exit status."""
    from threepart import calculix
    from threepart.material import compliance, rigid_punch_modulus, similar_pair_modulus
    from threepart.methods import solve
    from threepart.output import write_file

    pr = problem(args)
    shear = _shear_iv(args)
    if shear:
        return _friction(args, pr, shear)
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


def _shear_iv(args: argparse.Namespace) -> dict[str, float]:
    """``{"Q": ...}`` or ``{"Q_max": ...}`` with ``f`` for a friction deck, ``{}`` for the normal one."""
    if args.Q is not None and args.Q_max is not None:
        raise InputError("give `--Q` (partial slip) or `--Q-max` (a fretting cycle), not both")
    given = args.Q is not None or args.Q_max is not None
    if not given and args.f is None and args.case is not None:   # a case's own shear load, if any
        from threepart.catalogue import get_case

        case = get_case(args.case).resolved()
        if case.kind in ("slip", "fretting") and case.Q is not None and case.f is not None:
            return {"Q" if case.kind == "slip" else "Q_max": float(case.Q), "f": float(case.f)}
    if given != (args.f is not None):
        raise InputError("a friction deck needs `--f` with `--Q` or `--Q-max`; a normal one neither")
    if not given and args.format == "getfem":
        raise InputError("`--format getfem` writes friction only: give `--Q` or `--Q-max`, and `--f`")
    if given and args.pair is False and args.stiffening is not None:
        raise InputError("`--stiffening` is the normal deck's stiff punch; a friction deck is two "
                         "similar bodies")
    if not given:
        return {}
    return {"Q": float(args.Q), "f": float(args.f)} if args.Q is not None else \
        {"Q_max": float(args.Q_max), "f": float(args.f)}


def _friction(args: argparse.Namespace, pr: dict[str, Any], shear: dict[str, float]) -> int:
    """Write the friction deck (two similar bodies of the problem's A) and say what it holds."""
    from threepart import calculix, getfem
    from threepart.calculix.friction import friction_deck
    from threepart.errors import full_sliding
    from threepart.material import similar_pair_modulus
    from threepart.methods import solve
    from threepart.output import write_file

    nu, f = pr["nu"], shear["f"]
    E = similar_pair_modulus(pr["A"], nu)
    name = "Q" if "Q" in shear else "Q_max"
    amplitude = shear[name]
    if not abs(amplitude) < f * pr["P"]:
        raise full_sliding(name, amplitude, f, pr["P"], "the deck would slide")
    ref = solve(pr["punch"], pr["P"], pr["s"], A=pr["A"], tilt=pr["tilt"])
    title = (pr["name"] or "a punch from the command line") + f"; judge it with A = {pr['A']:.10g}"
    path = "partial slip 0 -> Q" if "Q" in shear else "fretting cycle 0 -> Q -> -Q -> Q"
    if args.format == "getfem":
        from pathlib import Path

        stem = Path(args.out).name.split(".")[0]
        if not stem.isidentifier():
            raise InputError(f"`--out` = {args.out!r}: a GetFEM script's name must be a plain stem "
                             "(letters, digits, _), as its files are named after it")
        text = getfem.write_script(pr["punch"], pr["P"], pr["s"], a=ref.a, c=ref.c, E=E, nu=nu, f=f,
                                   Q=shear.get("Q"), Q_max=shear.get("Q_max"), tilt=pr["tilt"],
                                   title=title, name=stem)
        write_file(args.out, text, arg="--out")
        print(f"wrote {args.out}: GetFEM, two similar bodies of E = {E:.6g} MPa, nu = {nu:g}, "
              f"{path} at {name} = {amplitude:g}, f = {f:g}; run it with the interpreter that imports "
              f"getfem in its folder (it writes {stem}.vtu and {stem}.getfem.json); expected contact "
              f"[{-ref.a:.6g}, {ref.c:.6g}]")
        return 0
    settings = calculix.DeckSettings(h=args.h, penalty=args.penalty, pair=True, tilt=pr["tilt"])
    model = calculix.build_model(pr["punch"], ref.a, ref.c, settings)
    Qs = [amplitude] if "Q" in shear else [amplitude, -amplitude, amplitude]
    deck = friction_deck(model, P=pr["P"], s=pr["s"], E=E, nu=nu, f=f, Q=Qs, settings=settings,
                         title=title)
    write_file(args.out, deck, arg="--out")
    print(f"wrote {args.out}: CalculiX, two similar bodies of E = {E:.6g} MPa, nu = {nu:g}, {path} "
          f"at {name} = {amplitude:g}, f = {f:g}: {model.n_nodes} nodes, h = {model.h0:.4g}; judge its "
          f".frd with `threepart compare --Q {amplitude:g} --f {f:g} --A {pr['A']:.10g}`; expected contact "
          f"[{-ref.a:.6g}, {ref.c:.6g}]")
    return 0

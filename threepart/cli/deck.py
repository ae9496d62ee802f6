"""``threepart deck``: a ready-to-run CalculiX deck or GetFEM script of a catalogue case or of a punch and loads.

The model is built around the contact that :func:`threepart.solve` predicts; its
title carries the compliance to judge it with (``threepart compare --A``).
Without a shear it is the normal problem (CalculiX: a stiff punch or, with
``--pair``, two similar bodies); with ``--Q --f`` (partial slip: the normal load
first, then ``Q`` in steps, with ``--sigma-bulk`` the substrate's bulk stress
rising with it), ``--Q-max --f`` (the fretting cycle ``0 -> Q -> -Q -> Q``),
``--state0 --state1 --f`` (a flight cycle, ``[state0, state1, state0, state1]``)
or ``--history FILE.csv --f`` (a load history) it is two similar elastic bodies
with Coulomb friction (:mod:`threepart.calculix.friction`, :mod:`threepart.getfem`),
which every format writes. A ``--case`` with a shear, a bulk stress or two states
gives its own. See docs/CALCULIX.md and docs/GETFEM.md.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import catalogue_case, labelled, problem, problem_args, state_args
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
    g.add_argument("--sigma-bulk", type=float, dest="sigma_bulk",
                   help=labelled("the substrate's bulk stress at Q (or Q_max), rising with it in proportion "
                                 "after P (tension positive; docs/BULK_STRESS.md)", "sigma_bulk"))
    state_args(g, "--P, --s and --Q", "the deck loads state0's P, then state0, state1, state0, state1 (the four "
                                      "moving linearly together); judge it with `threepart compare --state0 --state1`")
    g.add_argument("--history", metavar="FILE.csv",
                   help="a load history instead: a CSV file with the columns P, s, Q, sigma_bulk, each "
                        "state reached in turn after the first state's P")
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
    from threepart.problem.material import compliance, rigid_punch_modulus, similar_pair_modulus
    from threepart.methods import solve
    from threepart.output import write_file

    shear = _shear_iv(args)
    pr = problem(args)
    if shear:
        return _friction(args, pr, shear)
    settings = calculix.DeckSettings(h=args.h, penalty=args.penalty, pair=args.pair,
                                     tilt=pr["tilt"], **({} if args.stiffening is None
                                                         else {"stiffening": args.stiffening}))
    # the problem's A (both bodies of --E/--nu, or the case's) onto the model by threepart.problem.material's
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


def _shear_iv(args: argparse.Namespace) -> dict[str, Any]:
    """The friction deck's loads with ``f``: ``{"Q"}`` or ``{"Q_max"}`` (with ``sigma_bulk``), or
    ``{"history"}`` (a flight cycle's four states or a CSV file's); ``{}`` for the normal one."""
    states = [k for k in (0, 1) if getattr(args, f"state{k}") is not None]
    if len(states) == 1:
        raise InputError(f"a flight cycle needs both `--state0` and `--state1` (got only `--state{states[0]}`)")
    modes = [m for m, given in (("--Q", args.Q is not None), ("--Q-max", args.Q_max is not None),
                                ("--state0/--state1", bool(states)), ("--history", args.history is not None))
             if given]
    if args.Q is not None and args.Q_max is not None:
        raise InputError("give `--Q` (partial slip) or `--Q-max` (a fretting cycle), not both")
    if len(modes) > 1:
        raise InputError(f"give one load of a friction deck, not {' and '.join(f'`{m}`' for m in modes)}")
    if args.sigma_bulk is not None:
        from threepart.problem.checks import finite

        finite("--sigma-bulk", args.sigma_bulk)
        if args.Q is None and args.Q_max is None:
            raise InputError("`--sigma-bulk` rises with the shear: give it with `--Q` or `--Q-max` (a history's "
                             "states carry their own)")
    if not modes and args.f is None and args.case is not None:   # a case's own shear load, if any
        return _case_shear(args)
    if bool(modes) != (args.f is not None):
        raise InputError("a friction deck needs `--f` with `--Q`, `--Q-max`, `--state0/--state1` or "
                         "`--history`; a normal one neither")
    if not modes and args.format == "getfem":
        raise InputError("`--format getfem` writes friction only: give `--Q`, `--Q-max`, `--state0/--state1` "
                         "or `--history`, and `--f`")
    if modes and args.pair is False and args.stiffening is not None:
        raise InputError("`--stiffening` is the normal deck's stiff punch; a friction deck is two "
                         "similar bodies")
    if not modes:
        return {}
    f = float(args.f)
    if modes[0] in ("--state0/--state1", "--history"):
        if args.P is not None or args.s is not None:
            raise InputError(f"`{modes[0]}` gives P and s: leave out `--P` and `--s`")
        from threepart.halfplane.load_history import check_history

        hist = check_history(args.history if args.history is not None else
                             [args.state0, args.state1, args.state0, args.state1])
        if args.case is None:
            args.P, args.s = float(hist.P[0]), float(hist.s[0])      # the first state's normal load
        return {"history": hist, "f": f, "flight": bool(states)}
    bulk = {"sigma_bulk": float(args.sigma_bulk)} if args.sigma_bulk else {}
    return ({"Q": float(args.Q)} if args.Q is not None else {"Q_max": float(args.Q_max)}) | {"f": f} | bulk


def _case_shear(args: argparse.Namespace) -> dict[str, Any]:
    """A catalogue case's own friction loads: its shear (and bulk stress), or its two states (a flight cycle)."""
    from threepart.halfplane.load_history import check_history

    case = catalogue_case(args, own=())      # a name the catalogue does not hold is refused, its names listed
    if case.f is None:
        return {}
    if case.kind == "steady" and case.states is not None:
        st0, st1 = case.states
        return {"history": check_history([st0, st1, st0, st1]), "f": float(case.f), "flight": True}
    if case.kind in ("slip", "fretting") and case.Q is not None:
        bulk = {"sigma_bulk": float(case.sigma_bulk)} if case.sigma_bulk else {}
        return {"Q" if case.kind == "slip" else "Q_max": float(case.Q), "f": float(case.f)} | bulk
    return {}


def _friction(args: argparse.Namespace, pr: dict[str, Any], shear: dict[str, Any]) -> int:
    """Write the friction deck (two similar bodies of the problem's A) and say what it holds."""
    from threepart import calculix
    from threepart.errors import full_sliding
    from threepart.problem.material import similar_pair_modulus
    from threepart.methods import solve
    from threepart.output import write_file

    nu, f = pr["nu"], shear["f"]
    E = similar_pair_modulus(pr["A"], nu)
    hist = shear.get("history")
    loads = [(pr["P"], pr["s"])] if hist is None else list(dict.fromkeys(zip(hist.P.tolist(), hist.s.tolist())))
    if hist is None:
        name = "Q" if "Q" in shear else "Q_max"
        if not abs(shear[name]) < f * pr["P"]:
            raise full_sliding(name, shear[name], f, pr["P"], "the deck would slide")
        bulk = f", sigma_bulk = {shear['sigma_bulk']:g} MPa rising with it" if shear.get("sigma_bulk") else ""
        path = ("partial slip 0 -> Q" if name == "Q" else "fretting cycle 0 -> Q -> -Q -> Q") + \
            f" at {name} = {shear[name]:g}{bulk}"
        judge = f"--{name.replace('_', '-')} {shear[name]:g}" + (f" --sigma-bulk {shear['sigma_bulk']:g}" if bulk else "")
    else:
        for k in range(len(hist)):
            if not abs(hist.Q[k]) < f * hist.P[k]:
                raise full_sliding(f"state {k}: Q", float(hist.Q[k]), f, float(hist.P[k]), "the deck would slide")
        path = (f"flight cycle state0 -> state1 -> state0 -> state1 ({', '.join(map('{:g}'.format, hist.state(0)))} "
                f"<-> {', '.join(map('{:g}'.format, hist.state(1)))})" if shear.get("flight") else
                f"load history of {len(hist)} states (P, s, Q, sigma_bulk)")
        judge = (f"--state0 {','.join(map('{:.10g}'.format, hist.state(0)))} "
                 f"--state1 {','.join(map('{:.10g}'.format, hist.state(1)))}") if shear.get("flight") else ""
    normals = [solve(pr["punch"], P, s, A=pr["A"], tilt=pr["tilt"]) for P, s in loads]
    a, c = max(n.a for n in normals), max(n.c for n in normals)
    title = (pr["name"] or "a punch from the command line") + f"; judge it with A = {pr['A']:.10g}"
    case = f"--case {pr['name']} " if pr["name"] else ""
    how = f"`threepart compare {case}{judge} --f {f:g} --A {pr['A']:.10g}`" if judge else \
        f"`threepart compare {case}--A {pr['A']:.10g}`"
    if args.format == "getfem":
        return _getfem(args, pr, shear, E, a, c, title, path, how)
    settings = calculix.DeckSettings(h=args.h, penalty=args.penalty, pair=True, tilt=pr["tilt"])
    model = calculix.build_model(pr["punch"], a, c, settings)
    from threepart.calculix.friction import friction_deck

    if hist is None:
        Qs = [shear[name]] if name == "Q" else [shear[name], -shear[name], shear[name]]
        deck = friction_deck(model, P=pr["P"], s=pr["s"], E=E, nu=nu, f=f, Q=Qs, settings=settings, title=title,
                             sigma_bulk=shear.get("sigma_bulk", 0.0))
    else:
        deck = friction_deck(model, E=E, nu=nu, f=f, settings=settings, title=title, history=hist)
    write_file(args.out, deck, arg="--out")
    print(f"wrote {args.out}: CalculiX, two similar bodies of E = {E:.6g} MPa, nu = {nu:g}, {path}, f = {f:g}: "
          f"{model.n_nodes} nodes, h = {model.h0:.4g}; judge its .frd with {how}; expected contact "
          f"[{-a:.6g}, {c:.6g}]")
    return 0


def _getfem(args: argparse.Namespace, pr: dict[str, Any], shear: dict[str, Any], E: float, a: float, c: float,
            title: str, path: str, how: str) -> int:
    """Write the GetFEM script of the friction deck and say what it holds."""
    from pathlib import Path

    from threepart import getfem
    from threepart.output import write_file

    stem = Path(args.out).name.split(".")[0]
    if not stem.isidentifier():
        raise InputError(f"`--out` = {args.out!r}: a GetFEM script's name must be a plain stem "
                         "(letters, digits, _), as its files are named after it")
    hist = shear.get("history")
    loads: dict[str, Any] = {"history": hist} if hist is not None else {
        "Q": shear.get("Q"), "Q_max": shear.get("Q_max"), "sigma_bulk": shear.get("sigma_bulk", 0.0)}
    text = getfem.write_script(pr["punch"], None if hist is not None else pr["P"], pr["s"], a=a, c=c, E=E,
                               nu=pr["nu"], f=shear["f"], tilt=pr["tilt"], title=title, name=stem, **loads)
    write_file(args.out, text, arg="--out")
    print(f"wrote {args.out}: GetFEM, two similar bodies of E = {E:.6g} MPa, nu = {pr['nu']:g}, {path}, "
          f"f = {shear['f']:g}; run it with the interpreter that imports getfem in its folder (it writes "
          f"{stem}.vtu and {stem}.getfem.json; judge the sidecar with {how}); expected contact "
          f"[{-a:.6g}, {c:.6g}]")
    return 0

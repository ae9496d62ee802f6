"""``threepart match``: the Hertzian pad test that reproduces one edge of a flank (issue 32; docs/EDGES.md).

The flank is a catalogue case with a shear load (``--case``) or a punch, material
and loads; ``--edge`` picks its edge. The pad (a cylinder of radius ``R`` on a flat,
the same material and ``f``, under the flank's bulk stress) gets the load ``P`` and
shear ``Q`` whose edge has the flank's ``K_N`` and ``K_T``, hence its slip zone
(:func:`threepart.studies.matching.match`). Give the pad's radius (``--pad-R``) or its
load (``--pad-P``), or neither for the pad whose surface σxx over the slip zone is
closest to the flank's. It prints
both edges' multipliers, the pad's loads, the surface σxx agreement over the slip
zone and the fatigue parameters near the edge, flank against pad.

Building the parser loads no numpy: every numerical import is inside ``run``.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import case_arg, catalogue_case, given_punch_and_material
from threepart.errors import InputError

__all__ = ["add_parser", "run"]

#: the methods that may solve the flank (the pad is solved by the closed form)
METHODS = ("auto", "closedform", "sie", "fem")


def add_parser(sub: Any) -> None:
    """Add the ``match`` sub-command to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    from threepart.problem.units import UNITS

    def unit(text: str, key: str) -> str:
        return f"{text} [{UNITS[key]}]"

    p = sub.add_parser("match", help="the Hertzian pad test that reproduces one edge of a flank: "
                                     "its K_N, K_T and slip zone",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                       epilog="Units: mm, N/mm, MPa, 1/MPa, or any consistent set. See docs/EDGES.md.")
    g = p.add_argument_group("the flank: --case NAME (with Q and f), or the punch (eq. 2), material and loads")
    case_arg(g, "a catalogue case with a shear load (e.g. fan_blade_flank_bulk)",
             "`threepart cases` lists them; the punch, material and loads beside it are refused")
    g.add_argument("--R1", type=float, help=unit("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, help=unit("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, help=unit("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float, help=unit("central radius (default inf: flat)", "R"))
    g.add_argument("--E", type=float, help=unit("Young's modulus of both bodies", "E"))
    g.add_argument("--nu", type=float, help="Poisson's ratio of both bodies")
    g.add_argument("--A", type=float, help=unit("compliance of the similar pair, 4(1 - nu^2)/E (eq. 4)", "A"))
    g.add_argument("--P", type=float, help=unit("normal load of the flank, > 0", "P"))
    g.add_argument("--s", type=float, help=unit("its lever arm (default 0)", "s"))
    g.add_argument("--Q", type=float, help=unit("its shear load, |Q| < f P", "Q"))
    g.add_argument("--f", type=float, help="coefficient of friction, > 0")
    g.add_argument("--sigma-bulk", dest="sigma_bulk", type=float,
                   help=unit("bulk stress in the substrate, tension > 0 (default 0)", "sigma_bulk"))
    m = p.add_argument_group("the match")
    m.add_argument("--edge", required=True, choices=("left", "right"),
                   help="the flank's edge to reproduce: left (-a) or right (c)")
    m.add_argument("--pad-R", dest="pad_R", type=float,
                   help=unit("the pad's radius; or --pad-P; neither: the radius of least surface-stress "
                             "error over the slip zone", "R"))
    m.add_argument("--pad-P", dest="pad_P", type=float, help=unit("the pad's normal load", "P"))
    m.add_argument("--method", choices=METHODS, default="auto",
                   help="the method that solves the flank (default auto: the closed form where it holds)")
    m.add_argument("--no-fatigue", dest="fatigue", action="store_false",
                   help="skip the fatigue parameters (a fretting cycle of each, a few seconds)")
    p.set_defaults(func=run)


def _flank_problem(args: argparse.Namespace) -> dict[str, Any]:
    """The flank's punch, compliance, Poisson ratio and loads, checked before any numerics."""
    from threepart.problem.catalogue import load_cases
    from threepart.problem.material import NU, similar_pair
    from threepart.problem.checks import finite, positive

    own = ("R1", "R2", "b", "R", "E", "nu", "A", "P", "s", "Q", "f", "sigma_bulk")
    if args.case is not None:
        c = catalogue_case(args, own)
        if c.Q is None or c.f is None or c.states is not None:
            shear = ", ".join(k.name for k in load_cases(None) if k.Q is not None and k.states is None
                              and not k.beyond)
            raise InputError(f"case {c.name!r} has no partial-slip load (cases with one: {shear})")
        nu = c.material[1] if c.material is not None else NU
        return {"punch": c.punch, "A": c.A, "nu": nu, "P": c.P, "s": c.s, "Q": c.Q, "f": c.f,
                "sigma_bulk": c.sigma_bulk}
    punch, given_nu = given_punch_and_material(args, ("R1", "R2", "b", "P", "Q", "f"))
    nu = NU if given_nu is None else given_nu
    A = positive("--A", args.A) if args.A is not None else similar_pair(positive("--E", args.E), nu)
    return {"punch": punch, "A": A, "nu": nu, "P": positive("--P", args.P),
            "s": 0.0 if args.s is None else finite("--s", args.s), "Q": finite("--Q", args.Q),
            "f": positive("--f", args.f),
            "sigma_bulk": 0.0 if args.sigma_bulk is None else finite("--sigma-bulk", args.sigma_bulk)}


def _problem(args: argparse.Namespace) -> dict[str, Any]:
    """Every check of the input, before anything is solved: the flank's problem and the pad's size."""
    from threepart.problem.checks import positive
    from threepart.problem.validate import shear_load

    if args.pad_R is not None and args.pad_P is not None:
        raise InputError("give `--pad-R` or `--pad-P` (or neither: the pad of least surface-stress "
                         "error), not both")
    pr = _flank_problem(args)
    shear_load(pr["Q"], pr["f"], pr["P"])
    pr["pad"] = ({"R": positive("--pad-R", args.pad_R)} if args.pad_R is not None else
                 {"P": positive("--pad-P", args.pad_P)} if args.pad_P is not None else {})
    return pr


def _line(label: str, value: float, key: str) -> str:
    from threepart.problem.units import UNITS
    return f"  {label:<28} {value:.6g} {UNITS[key]}"


def _print(pr: dict[str, Any], flank: Any, m: Any) -> None:
    """The flank's and the pad's edges, the pad's loads and how well the edge field agrees."""
    from threepart.fatigue.table import parameter
    from threepart.problem.units import UNITS
    from threepart.results.edges import exact_slip

    print(f"flank: {flank.method}, contact [{-flank.a:.6g}, {flank.c:.6g}] {UNITS['a']}, "
          f"Q = {flank.Q:.6g} {UNITS['Q']}, f = {flank.f:g}, sigma_bulk = {flank.sigma_bulk:g} {UNITS['sigma_bulk']}")
    print(f"pad: Punch(R1=R2={m.R:.6g}, b=0), P = {m.P:.6g} {UNITS['P']}, Q = {m.Q:.6g} {UNITS['Q']}, "
          f"sigma_bulk = {m.sigma_bulk:g} {UNITS['sigma_bulk']}, contact half-width a = {m.result.a:.6g} "
          f"{UNITS['a']}")
    print(f"the {m.side} edge          {'flank':>14} {'pad':>14}")
    for label, key in (("K_N", "K_N"), ("K_T", "K_T"), ("K_T bulk share", "K_sigma"),
                       ("slip zone (asymptotic)", "slip_zone")):
        a, b = getattr(m.flank, key) + 0.0, getattr(m.pad, key) + 0.0   # + 0.0: no "-0"
        print(f"  {label:<24} {a:14.6g} {b:14.6g} {UNITS[key]}")
    k = ("left", "right").index(m.side)
    exact = [exact_slip(r, k) for r in (flank, m.result)]
    print(f"  {'slip zone (exact)':<24} {exact[0]:14.6g} {exact[1]:14.6g} {UNITS['slip_zone']}")
    print(f"surface sigma_xx over the slip zone: largest difference {m.sxx_error:.3g} of the flank's largest")
    for name, (a, b) in m.fatigue.items():
        label, unit = parameter(name).label, parameter(name).unit
        print(f"  {label:<24} {a:14.6g} {b:14.6g} {unit}  ({(b - a) / abs(a):+.2e})")


def run(args: argparse.Namespace) -> int:
    """Run ``threepart match``: check the input, solve the flank and the pad, print; the exit status."""
    from threepart import solve
    from threepart.studies.matching import match

    pr = _problem(args)
    options: dict[str, Any] = {"nu": pr["nu"]} if args.method == "fem" else {}
    flank = solve(pr["punch"], pr["P"], pr["s"], A=pr["A"], Q=pr["Q"], f=pr["f"],
                  sigma_bulk=pr["sigma_bulk"], method=args.method, **options)
    m = match(flank, args.edge, **pr["pad"], fatigue=args.fatigue, nu=pr["nu"])
    _print(pr, flank, m)
    return 0

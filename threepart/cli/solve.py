"""``threepart solve`` and ``threepart slip``: the normal and the partial-slip problem.

``solve`` prints a, c, alpha, the peak pressures, the segments in contact and
the lift-off lever arms; ``slip`` adds the stick zone for a shear load Q and
friction f. The problem is a catalogue case (``--case NAME``) or the punch,
material and loads given as options. Both call :func:`threepart.solve` (its
``auto`` fallback says why on the first line); ``--x``/``--grid`` add p(x) (and
q(x)) at points, ``--csv`` writes them, ``--json`` prints strict JSON.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import (E_HELP, NU_HELP, case_arg, catalogue_case, given_R, labelled, method_args,
                    method_options, need_options, number_list, punch_args)
from ._output import print_result, write_points_csv
from threepart.errors import InputError

__all__ = ["add_parser", "run", "MAX_GRID"]

#: the most points ``--grid`` prints
MAX_GRID = 1_000_000
#: what ``--case`` refuses beside it: the options of the problem (their ``dest``), and of slip's shear load
PROBLEM_OPTIONS = ("R1", "R2", "b", "R", "A", "E", "nu", "rigid", "P", "s", "tilt")
SHEAR_OPTIONS = ("Q", "f", "sigma_bulk")
_EPILOG = ("Units: mm, N/mm, MPa, 1/MPa, rad; --E in MPa (a unit slip is refused), or in any "
           "consistent set give --A.")


def add_parser(sub: Any) -> None:
    """Add ``solve`` and ``slip`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("solve", help="normal problem (closed form where it holds, else SIE)",
                       epilog=_EPILOG)
    _geometry_args(p, "a catalogue case: its punch, material and loads (a case with a shear load: its "
                      "normal problem)")
    p.set_defaults(func=run, Q=None, f=None, sigma_bulk=None)

    p = sub.add_parser("slip", help="partial slip (Ciavarella-Jaeger; closed form or SIE)",
                       epilog=_EPILOG)
    _geometry_args(p, "a catalogue case with a shear load Q and f (a cycle's: its running load)")
    sh = p.add_argument_group("shear load, unless --case")
    sh.add_argument("--Q", type=float, help=labelled("shear force, |Q| < f P", "Q"))
    sh.add_argument("--f", type=float, help="coefficient of friction, > 0")
    sh.add_argument("--sigma-bulk", type=float, dest="sigma_bulk",
                    help=labelled("bulk stress along x in the substrate at Q, MPa, tension positive; "
                                  "rises with Q in proportion (default 0)", "sigma_bulk"))
    p.set_defaults(func=run)


def _geometry_args(p: argparse.ArgumentParser, case_help: str) -> None:
    case_arg(p.add_argument_group("the problem: --case NAME, or the punch, material and loads below"),
             case_help, "`threepart cases` lists them; the punch, material and loads beside it are refused")
    punch_args(p)
    m = p.add_argument_group("material (eq. 4, plane strain), unless --case")
    m.add_argument("--A", type=float, help=labelled("compliance A; or give --E/--nu", "A"))
    m.add_argument("--E", type=float, help=E_HELP + "; with --rigid, of the half-plane alone")
    m.add_argument("--nu", type=float, help=NU_HELP + " (with --rigid, of the half-plane)")
    m.add_argument("--rigid", action="store_true",
                   help="a rigid punch on an elastic half-plane of --E/--nu, A = 2(1 - nu^2)/E")
    ld = p.add_argument_group("loads, unless --case")
    ld.add_argument("--P", type=float, help=labelled("compressive normal load per unit length, > 0", "P"))
    ld.add_argument("--s", type=float,
                    help=labelled("lever arm of P, positive to the right (default 0)", "s"))
    ld.add_argument("--tilt", choices=("free", "suppressed"), help="free (default) or suppressed")
    method_args(p)
    pt = p.add_argument_group("fields at points")
    pt.add_argument("--x", type=number_list, metavar="X1,X2,...",
                    help=labelled("points at which to print p(x) (and q(x) for slip)", "x"))
    pt.add_argument("--grid", type=int, metavar="N",
                    help="print p(x) (and q(x)) at N >= 2 points spread evenly over [-a, c]")
    pt.add_argument("--csv", metavar="FILE",
                    help="write those points to FILE as CSV (a new file, or one threepart wrote "
                         "there and that is unchanged; never over anything else)")
    p.add_argument("--json", action="store_true",
                   help='print strict JSON instead of text: plain numbers in the units of its "units" '
                        "object; an infinite R (flat centre) is null")


def run(args: argparse.Namespace) -> int:
    """Run ``threepart solve`` or ``threepart slip``: solve, write ``--csv``, print; the exit status."""
    out = _figures(args, slip=args.command == "slip")
    if args.csv is not None:
        write_points_csv(args.csv, out["points"])
    print_result(out, args.json)
    return 0


def _finite_body(args: argparse.Namespace) -> Any:
    """The registered method ``--method`` names if it models a finite body (takes ``nu``), else None."""
    from threepart import registry

    if args.method == "auto":
        return None
    m = registry.get(args.method)
    return m if m.default_nu is not None else None


def _compliance(args: argparse.Namespace) -> float:
    """The compliance A (eq. 4) from ``--A``, or from ``--E``/``--nu`` (and ``--rigid``)."""
    from threepart.problem.material import compliance, rigid_punch

    if args.A is not None:
        if args.E is not None:
            raise InputError("give either `--A` or `--E`/`--nu`, not both")
        if args.rigid:
            raise InputError("`--rigid` applies to `--E`/`--nu`; with `--A` the compliance is "
                             "given, so drop `--rigid`")
        if args.nu is not None and _finite_body(args) is None:
            raise InputError("`--nu` with `--A` is used only by a method that models a finite "
                             "body (`--method fem`); drop it or give `--E` and `--nu` instead")
        return float(args.A)
    if args.E is None or args.nu is None:
        raise InputError("the material needs `--A`, or both `--E` and `--nu`")
    return rigid_punch(args.E, args.nu) if args.rigid else compliance(args.E, args.nu)


def _options(args: argparse.Namespace, nu: float | None) -> tuple[dict[str, Any], str | None]:
    """The method's options from ``--mesh`` and ``nu`` (``--nu`` or the case's, a finite body's), and
    the note on an assumed nu."""
    finite_body = _finite_body(args)
    if finite_body is None or nu is not None:
        return method_options(args, nu), None
    how = "the case gives only A" if args.case is not None else "give --nu to set it"
    nu_note = (f"the FE model needs Poisson's ratio; nu = {finite_body.default_nu} "
               f"assumed ({how}; in half-plane theory only A matters)")
    return method_options(args, finite_body.default_nu), nu_note


def _problem(args: argparse.Namespace, slip: bool) -> dict[str, Any]:
    """The checked problem of ``--case`` or of the options, before any numerics: ``name``, ``punch``,
    ``A``, ``nu`` (None: not given), ``P``, ``s``, ``tilt`` and for ``slip`` the ``loads`` Q, f, sigma_bulk."""
    from threepart.problem.catalogue import load_cases
    from threepart.problem.punch import Punch

    if args.case is not None:
        c = catalogue_case(args, PROBLEM_OPTIONS + (SHEAR_OPTIONS if slip else ()))
        if slip and (c.Q is None or c.f is None):
            shear = ", ".join(k.name for k in load_cases(None) if k.Q is not None)
            raise InputError(f"case {c.name!r} has no shear load `Q` and `f` (cases with one: {shear})")
        loads = {"Q": c.Q, "f": c.f, "sigma_bulk": c.sigma_bulk} if slip else {}
        return {"name": c.name, "punch": c.punch, "A": c.A, "nu": None if c.material is None else c.material[1],
                "P": c.P, "s": c.s_load, "tilt": c.tilt, "loads": loads}
    need_options(args, ("R1", "R2", "b", "P", *(("Q", "f") if slip else ())))
    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=given_R(args))
    A = _compliance(args)
    sigma_bulk = 0.0 if args.sigma_bulk is None else args.sigma_bulk
    if slip and sigma_bulk and args.rigid:
        raise InputError(f"`--sigma-bulk` = {sigma_bulk:g} needs elastically similar bodies (its "
                         "strain is A sigma_bulk/4 with A of eq. (4) for one material): drop `--rigid`")
    loads = {"Q": args.Q, "f": args.f, "sigma_bulk": sigma_bulk} if slip else {}
    return {"name": None, "punch": punch, "A": A, "nu": args.nu, "P": args.P,
            "s": 0.0 if args.s is None else args.s, "tilt": args.tilt or "free", "loads": loads}


def _figures(args: argparse.Namespace, slip: bool) -> dict[str, Any]:
    """Solve by ``--method`` (:func:`threepart.solve`, its ``auto`` fallback) and collect the figures
    to print, in print order."""
    from threepart.methods import describe, solve
    from threepart.results import SlipResult

    pr = _problem(args, slip)
    punch, A = pr["punch"], pr["A"]
    _points_iv(args)
    options, nu_note = _options(args, pr["nu"])
    res = solve(punch, pr["P"], pr["s"], A=A, tilt=pr["tilt"], method=args.method, **pr["loads"], **options)
    normal = res.normal if isinstance(res, SlipResult) else res
    left, right = normal.peaks()
    out: dict[str, Any] = {
        "method": res.method,
        **({"method_note": res.info["auto"]} if "auto" in res.info else {}),
        **({"case": pr["name"]} if pr["name"] else {}),
        "punch": {"R1": punch.R1, "R2": punch.R2, "b": punch.b, "R": punch.R, "case": punch.case},
        "A": A, **({"nu": options["nu"]} if "nu" in options else {}),
        **({"nu_note": nu_note} if nu_note else {}),
        # s as given; with the tilt suppressed, the lever arm s* that holds alpha = 0
        "P": float(pr["P"]), "s": float(pr["s"]) if normal.tilt == "free" else normal.s,
        "tilt": normal.tilt,
        "a": normal.a, "c": normal.c, "alpha": normal.alpha, "slope": normal.slope,
        **_slope_note(normal.slope),
        "contact": {"left": -normal.a, "right": normal.c},
        "segments": list(normal.segments), "within_paper": normal.within_paper,
        "peak_left": _peak(left, "left"), "peak_right": _peak(right, "right"),
    }
    limits = _lift_off(punch, normal.P, A)
    if limits is not None:
        out["lift_off"] = limits
    if isinstance(res, SlipResult):
        lo, hi = res.stick_zone
        out.update({"Q": res.Q, "f": res.f, "sigma_bulk": res.sigma_bulk, "d": res.d, "e": res.e,
                    "stick_zone": {"left": lo, "right": hi},
                    "stick_segments": list(res.stick_segments), "within_paper": res.within_paper})
    points = _points(args, res)
    if points is not None:
        out["points"] = points
    out["_describe"] = describe(res)
    return out


def _slope_note(slope: float) -> dict[str, str]:
    """A note past the slope where half-plane theory's measured error reaches 5 %."""
    from threepart.problem.validate import SLOPE_LIMIT, SLOPE_WARNING

    if slope <= SLOPE_WARNING:
        return {}
    return {"slope_note": f"slope {slope:.3g} > {SLOPE_WARNING:g}: half-plane theory's small-slope "
                          "error in the peak pressure may exceed 5 % here (about 0.43 slope^1.1 "
                          f"against finite deformation; refused past {SLOPE_LIMIT:g}; see "
                          "docs/SMALL_SLOPE.md)"}


def _peak(peak: Any, side: str) -> dict[str, Any]:
    """A peak as printed: its x and p, or a note that this half has no interior peak."""
    if peak.interior:
        return {"x": peak.x, "p": peak.p}
    other = "right" if side == "left" else "left"
    return {"none": f"no interior peak: p rises monotonically from the {side} end into the "
                    f"{other} half"}


def _lift_off(punch: Any, P: float, A: float) -> dict[str, float] | None:
    """The closed form's admissible lever arms at ``P`` (through the registry), or None where it has none."""
    from threepart.registry import REFERENCE, lift_off

    try:
        s_min, s_max = lift_off(REFERENCE, punch, P, A)
    except ValueError:
        return None
    return {"s_min": s_min, "s_max": s_max}


def _points_iv(args: argparse.Namespace) -> None:
    """Check ``--x``, ``--grid`` and ``--csv`` before any numerics."""
    import math

    if args.x is not None and args.grid is not None:
        raise InputError("give `--x` or `--grid`, not both")
    if args.x is not None and not all(math.isfinite(v) for v in args.x):
        raise InputError(f"`--x` = {args.x} must hold finite numbers")
    if args.grid is not None and not 2 <= args.grid <= MAX_GRID:
        raise InputError(f"`--grid` = {args.grid} must lie in [2, {MAX_GRID}]")
    if args.csv is not None:
        if args.x is None and args.grid is None:
            raise InputError("`--csv` needs the points: give `--x` or `--grid`")
        from threepart.output import check_file

        check_file(args.csv, arg="--csv")   # a new file, or threepart's own unchanged one


def _points(args: argparse.Namespace, res: Any) -> dict[str, list[float]] | None:
    """``x``, ``p`` (and ``q``) at ``--x`` or ``--grid``, or None."""
    import numpy as np

    if args.x is None and args.grid is None:
        return None
    x = np.asarray(args.x, float) if args.x is not None else np.linspace(-res.a, res.c, args.grid)
    out = {"x": x.tolist(), "p": np.asarray(res.pressure(x), float).tolist()}
    if hasattr(res, "shear"):
        out["q"] = np.asarray(res.shear(x), float).tolist()
    return out

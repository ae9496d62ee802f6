"""``threepart solve`` and ``threepart slip``: the normal and the partial-slip problem.

``solve`` prints a, c, alpha, the peak pressures, the segments in contact and
the lift-off lever arms; ``slip`` adds the stick zone for a shear load Q and
friction f. Both call :func:`threepart.solve` (its ``auto`` fallback says why on
the first line); ``--x``/``--grid`` add p(x) (and q(x)) at points, ``--csv``
writes them, ``--json`` prints strict JSON.
"""
from __future__ import annotations

import argparse
from typing import Any

from ._args import labelled, method_args, method_options, number_list, punch_args, state_args
from ._output import print_result, write_points_csv
from threepart.errors import InputError

__all__ = ["add_parser", "run", "MAX_GRID"]

#: the most points ``--grid`` prints
MAX_GRID = 1_000_000
_EPILOG = "Units: mm, N/mm, MPa, 1/MPa, rad, or any consistent set."


def add_parser(sub: Any) -> None:
    """Add ``solve`` and ``slip`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("solve", help="normal problem (closed form where it holds, else SIE)",
                       epilog=_EPILOG)
    _geometry_args(p)
    p.set_defaults(func=run, Q=None, f=None)

    p = sub.add_parser("slip", help="partial slip (Ciavarella-Jaeger; closed form or SIE)",
                       epilog=_EPILOG)
    _geometry_args(p)
    p.add_argument("--Q", type=float, required=True, help=labelled("shear force, |Q| < f P", "Q"))
    p.add_argument("--f", type=float, required=True, help="coefficient of friction, > 0")
    p.add_argument("--sigma-bulk", type=float, default=0.0, dest="sigma_bulk",
                   help=labelled("bulk stress along x in the substrate at Q, MPa, tension positive; "
                                 "rises with Q in proportion (default 0)", "sigma_bulk"))
    p.set_defaults(func=run)


def _geometry_args(p: argparse.ArgumentParser) -> None:
    punch_args(p)
    m = p.add_argument_group("material (eq. 4, plane strain)")
    m.add_argument("--A", type=float, help=labelled("compliance A; or give --E/--nu", "A"))
    m.add_argument("--E", type=float,
                   help=labelled("Young's modulus of the half-plane (and punch, see --rigid)", "E"))
    m.add_argument("--nu", type=float, help="Poisson's ratio")
    m.add_argument("--rigid", action="store_true", help="rigid punch on an elastic half-plane")
    ld = p.add_argument_group("loads")
    ld.add_argument("--P", type=float, required=True,
                    help=labelled("compressive normal load per unit length, > 0", "P"))
    ld.add_argument("--s", type=float, default=0.0,
                    help=labelled("lever arm of P, positive to the right", "s"))
    ld.add_argument("--tilt", choices=("free", "suppressed"), default="free")
    state_args(ld)
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
    from threepart.material import compliance, rigid_punch

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


def _options(args: argparse.Namespace) -> tuple[dict[str, Any], str | None]:
    """The method's options from ``--mesh`` and ``--nu`` (a finite body's), and the note on an assumed nu."""
    finite_body = _finite_body(args)
    if finite_body is None or args.nu is not None:
        return method_options(args, args.nu), None
    nu_note = (f"the FE model needs Poisson's ratio; nu = {finite_body.default_nu} "
               "assumed (give --nu to set it; in half-plane theory only A matters)")
    return method_options(args, finite_body.default_nu), nu_note


def _figures(args: argparse.Namespace, slip: bool) -> dict[str, Any]:
    """Solve by ``--method`` (:func:`threepart.solve`, its ``auto`` fallback) and collect the figures
    to print, in print order."""
    from threepart.methods import describe, solve
    from threepart.punch import Punch
    from threepart.results import SlipResult

    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=args.R)
    A = _compliance(args)
    _points_iv(args)
    options, nu_note = _options(args)
    if slip and args.sigma_bulk and args.rigid:
        raise InputError(f"`--sigma-bulk` = {args.sigma_bulk:g} needs elastically similar bodies (its "
                         "strain is A sigma_bulk/4 with A of eq. (4) for one material): drop `--rigid`")
    loads = {"Q": args.Q, "f": args.f, "sigma_bulk": args.sigma_bulk} if slip else {}
    res = solve(punch, args.P, args.s, A=A, tilt=args.tilt, method=args.method, **loads, **options)
    normal = res.normal if isinstance(res, SlipResult) else res
    left, right = normal.peaks()
    out: dict[str, Any] = {
        "method": res.method,
        **({"method_note": res.info["auto"]} if "auto" in res.info else {}),
        "punch": {"R1": punch.R1, "R2": punch.R2, "b": punch.b, "R": punch.R, "case": punch.case},
        "A": A, **({"nu": options["nu"]} if "nu" in options else {}),
        **({"nu_note": nu_note} if nu_note else {}),
        # s as given; with the tilt suppressed, the lever arm s* that holds alpha = 0
        "P": float(args.P), "s": float(args.s) if normal.tilt == "free" else normal.s,
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
    from threepart.validate import SLOPE_LIMIT, SLOPE_WARNING

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
    from threepart.catalogue import LIFT_OFF_METHOD
    from threepart.registry import lift_off

    try:
        s_min, s_max = lift_off(LIFT_OFF_METHOD, punch, P, A)
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

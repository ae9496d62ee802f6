"""The ``threepart`` command line.

Sub-commands
------------
solve    closed-form normal problem: a, c, alpha, peak pressures, lift-off lever arms
slip     closed-form partial slip: adds the stick zone for a shear load Q and friction f
verify   verification run: closed form against SIE and FEM, tolerance report
figures  the paper's result figures, with the SIE solution as markers
"""
from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any, Sequence

__all__ = ["main"]


def _geometry_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("punch geometry (eq. 2)")
    g.add_argument("--R1", type=float, required=True, help="left edge radius, > 0")
    g.add_argument("--R2", type=float, required=True, help="right edge radius, > 0")
    g.add_argument("--b", type=float, required=True, help="half-width of the central segment, >= 0")
    g.add_argument("--R", type=float, default=math.inf,
                   help="central radius: inf (flat, case A, default), negative for concave (case B)")
    m = p.add_argument_group("material (eq. 4, plane strain)")
    m.add_argument("--A", type=float, help="compliance A; or give --E/--nu")
    m.add_argument("--E", type=float, help="Young's modulus of the half-plane (and punch, see --rigid)")
    m.add_argument("--nu", type=float, help="Poisson's ratio")
    m.add_argument("--rigid", action="store_true", help="rigid punch on an elastic half-plane")
    ld = p.add_argument_group("loads")
    ld.add_argument("--P", type=float, required=True, help="compressive normal load per unit length, > 0")
    ld.add_argument("--s", type=float, default=0.0, help="lever arm of P, positive to the right")
    ld.add_argument("--tilt", choices=("free", "suppressed"), default="free")
    p.add_argument("--json", action="store_true", help="print JSON instead of text")


def _compliance(args: argparse.Namespace) -> float:
    from threepart.closedform import compliance, rigid_punch

    if args.A is not None:
        if args.E is not None or args.nu is not None:
            raise ValueError("give either `--A` or `--E`/`--nu`, not both")
        return float(args.A)
    if args.E is None or args.nu is None:
        raise ValueError("the material needs `--A`, or both `--E` and `--nu`")
    return rigid_punch(args.E, args.nu) if args.rigid else compliance(args.E, args.nu)


def _normal_summary(args: argparse.Namespace) -> tuple[Any, dict[str, Any]]:
    from threepart.closedform import Punch, lift_off, solve_normal

    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=args.R)
    A = _compliance(args)
    sol = solve_normal(punch, args.P, s=args.s, A=A, tilt=args.tilt)
    left, right = sol.peaks()
    lim = lift_off(punch, args.P, A)
    out = {
        "punch": {"R1": punch.R1, "R2": punch.R2, "b": punch.b, "R": punch.R, "case": punch.case},
        "A": A, "P": sol.P, "s": sol.s, "tilt": sol.tilt,
        "a": sol.a, "c": sol.c, "alpha": sol.alpha,
        "peak_left": {"x": left.x, "p": left.p},
        "peak_right": {"x": right.x, "p": right.p},
        "lift_off": {"s_min": lim.s_min, "s_max": lim.s_max},
    }
    return sol, out


def _print(out: dict[str, Any], as_json: bool) -> None:
    if as_json:
        print(json.dumps(out, indent=2, default=float))
        return

    def walk(d: dict[str, Any], indent: str = "") -> None:
        for k, v in d.items():
            if isinstance(v, dict):
                print(f"{indent}{k}:")
                walk(v, indent + "  ")
            elif isinstance(v, float):
                print(f"{indent}{k:<10} {v:.10g}")
            else:
                print(f"{indent}{k:<10} {v}")

    walk(out)


def _cmd_solve(args: argparse.Namespace) -> int:
    _, out = _normal_summary(args)
    _print(out, args.json)
    return 0


def _cmd_slip(args: argparse.Namespace) -> int:
    from threepart.closedform import solve_partial_slip

    sol, out = _normal_summary(args)
    slip = solve_partial_slip(sol, args.Q, args.f)
    lo, hi = slip.stick_zone
    out.update({"Q": slip.Q, "f": slip.f, "d": slip.d, "e": slip.e,
                "stick_zone": {"left": lo, "right": hi}})
    _print(out, args.json)
    return 0


def _cmd_verify(args: argparse.Namespace) -> int:
    from threepart.reports.verify import main as verify_main

    mode = "quick" if args.quick else "full" if args.full else "default"
    return int(verify_main(mode=mode, out=args.out, force=args.force))


def _cmd_figures(args: argparse.Namespace) -> int:
    from threepart.reports.figures import main as figures_main

    return int(figures_main(out=args.out, force=args.force))


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="threepart", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("solve", help="closed-form normal problem")
    _geometry_args(p)
    p.set_defaults(func=_cmd_solve)

    p = sub.add_parser("slip", help="closed-form partial slip (Ciavarella-Jaeger)")
    _geometry_args(p)
    p.add_argument("--Q", type=float, required=True, help="shear force, |Q| < f P")
    p.add_argument("--f", type=float, required=True, help="coefficient of friction, > 0")
    p.set_defaults(func=_cmd_slip)

    p = sub.add_parser("verify", help="closed form against SIE and FEM; writes a tolerance report")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="coarse meshes, small n (<= 2 min)")
    mode.add_argument("--full", action="store_true", help="adds the slow convergence studies")
    p.add_argument("--out", default="report", help="output directory (default: ./report)")
    p.add_argument("--force", action="store_true", help="overwrite an existing report directory")
    p.set_defaults(func=_cmd_verify)

    p = sub.add_parser("figures", help="reproduce the paper's result figures")
    p.add_argument("--out", default="figures", help="output directory (default: ./figures)")
    p.add_argument("--force", action="store_true", help="overwrite existing figures")
    p.set_defaults(func=_cmd_figures)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``threepart`` console script."""
    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args))
    except ValueError as exc:  # bad input: a clear message, no traceback
        print(f"threepart {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

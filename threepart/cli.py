"""The ``threepart`` command line.

Sub-commands
------------
solve    closed-form normal problem: a, c, alpha, peak pressures, lift-off lever arms
slip     closed-form partial slip: adds the stick zone for a shear load Q and friction f
verify   verification run: closed form against SIE and FEM, tolerance report
figures  the paper's result figures, with the SIE solution as markers

Units: the library works in any consistent set of units. The command line
labels lengths mm, loads per unit length N/mm, pressures and moduli MPa,
compliance 1/MPa and the tilt rad; give the input in a consistent set and read
the labels accordingly. Negative numbers may follow their option (--s -0.1).

--json prints strict JSON: plain numbers, a top-level "units" object, and an
infinite R (flat centre) as null.

Exit status: 0 done (verify: every tolerance holds), 1 a tolerance failed,
2 an error (one line on stderr), 130 interrupted.
"""
from __future__ import annotations

import argparse
import sys
from typing import Any, NoReturn, Sequence

__all__ = ["main", "build_parser", "UNITS", "NUMERIC_OPTIONS", "UsageError"]

#: the unit printed with each quantity, by its key in the output ("1": dimensionless).
#: The library is unit-agnostic; these are the labels of one consistent set.
UNITS: dict[str, str] = {
    "R1": "mm", "R2": "mm", "b": "mm", "R": "mm",     # punch geometry
    "A": "1/MPa", "E": "MPa",                         # compliance, eq. (4); modulus
    "P": "N/mm", "Q": "N/mm",                         # loads per unit length
    "s": "mm", "s_min": "mm", "s_max": "mm",          # lever arms
    "a": "mm", "c": "mm", "x": "mm",                  # contact edges, peak positions
    "d": "mm", "e": "mm", "left": "mm", "right": "mm",  # stick zone
    "alpha": "rad",                                   # tilt, eq. (2)
    "p": "MPa",                                       # pressure
    "f": "1",                                         # coefficient of friction
}
#: options that take a number; ``--s -1e-3`` is read as ``--s=-1e-3`` (argparse alone
#: would take ``-1e-3`` for an option)
NUMERIC_OPTIONS = ("--R1", "--R2", "--b", "--R", "--A", "--E", "--nu", "--P", "--s", "--Q", "--f")


class UsageError(Exception):
    """A command-line usage error, already formatted as one line."""


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (raised, so that main returns 2)."""

    def error(self, message: str) -> NoReturn:
        msg = " ".join(message.split())
        raise UsageError(f"{self.prog}: error: {msg} (see `{self.prog} --help`)")


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _join_negative_numbers(argv: Sequence[str]) -> list[str]:
    """Rewrite ``--opt -1e-3`` as ``--opt=-1e-3`` for the options in :data:`NUMERIC_OPTIONS`."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        tok = argv[i]
        if tok == "--":
            out.extend(argv[i:])
            break
        nxt = argv[i + 1] if i + 1 < len(argv) else None
        if tok in NUMERIC_OPTIONS and nxt is not None and nxt.startswith("-") and _is_number(nxt):
            out.append(f"{tok}={nxt}")
            i += 2
        else:
            out.append(tok)
            i += 1
    return out


def _labelled(help_text: str, quantity: str) -> str:
    return f"{help_text} [{UNITS[quantity]}]"


def _geometry_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("punch geometry (eq. 2)")
    g.add_argument("--R1", type=float, required=True, help=_labelled("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, required=True, help=_labelled("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, required=True,
                   help=_labelled("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float, default=float("inf"),
                   help=_labelled("central radius: inf (flat, case A, default), negative for "
                                  "concave (case B)", "R"))
    m = p.add_argument_group("material (eq. 4, plane strain)")
    m.add_argument("--A", type=float, help=_labelled("compliance A; or give --E/--nu", "A"))
    m.add_argument("--E", type=float,
                   help=_labelled("Young's modulus of the half-plane (and punch, see --rigid)", "E"))
    m.add_argument("--nu", type=float, help="Poisson's ratio")
    m.add_argument("--rigid", action="store_true", help="rigid punch on an elastic half-plane")
    ld = p.add_argument_group("loads")
    ld.add_argument("--P", type=float, required=True,
                    help=_labelled("compressive normal load per unit length, > 0", "P"))
    ld.add_argument("--s", type=float, default=0.0,
                    help=_labelled("lever arm of P, positive to the right", "s"))
    ld.add_argument("--tilt", choices=("free", "suppressed"), default="free")
    p.add_argument("--json", action="store_true",
                   help='print strict JSON instead of text: plain numbers in the units of its "units" '
                        "object; an infinite R (flat centre) is null")


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


def _quantities(d: dict[str, Any]) -> set[str]:
    """The keys of every number in the nested dict ``d``."""
    keys: set[str] = set()
    for k, v in d.items():
        if isinstance(v, dict):
            keys |= _quantities(v)
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            keys.add(k)
    return keys


def _print(out: dict[str, Any], as_json: bool) -> None:
    if as_json:
        from threepart.output import strict_json

        units = {k: UNITS[k] for k in UNITS if k in _quantities(out)}
        print(strict_json({**out, "units": units}, indent=2))
        return

    def walk(d: dict[str, Any], indent: str = "") -> None:
        for k, v in d.items():
            if isinstance(v, dict):
                print(f"{indent}{k}:")
                walk(v, indent + "  ")
            elif isinstance(v, (int, float)) and not isinstance(v, bool):
                unit = UNITS[k]   # every number has a unit: a missing entry is a bug
                print(f"{indent}{k:<10} {float(v):.10g} {'(dimensionless)' if unit == '1' else unit}")
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


_FORCE_HELP = ("replace --out if threepart wrote it (it carries .threepart-output.json and nothing "
               "else); a directory holding anything else is never replaced")


def build_parser() -> argparse.ArgumentParser:
    """The parser of every sub-command; its usage errors raise :class:`UsageError`."""
    parser = _Parser(prog="threepart", description=__doc__,
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = sub.add_parser("solve", help="closed-form normal problem",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, rad, or any consistent set.")
    _geometry_args(p)
    p.set_defaults(func=_cmd_solve)

    p = sub.add_parser("slip", help="closed-form partial slip (Ciavarella-Jaeger)",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, rad, or any consistent set.")
    _geometry_args(p)
    p.add_argument("--Q", type=float, required=True, help=_labelled("shear force, |Q| < f P", "Q"))
    p.add_argument("--f", type=float, required=True, help="coefficient of friction, > 0")
    p.set_defaults(func=_cmd_slip)

    p = sub.add_parser("verify", help="closed form against SIE and FEM; writes a tolerance report")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="coarse meshes, small n (<= 2 min)")
    mode.add_argument("--full", action="store_true", help="adds the slow convergence studies")
    p.add_argument("--out", default="report",
                   help="output directory: new or empty, or see --force (default: ./report)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.set_defaults(func=_cmd_verify)

    p = sub.add_parser("figures", help="reproduce the paper's result figures")
    p.add_argument("--out", default="figures",
                   help="output directory: new or empty, or see --force (default: ./figures)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.set_defaults(func=_cmd_figures)
    return parser


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``threepart`` console script.

    Parameters
    ----------
    argv
        The arguments after the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 done, 1 a verification tolerance failed, 2 an error (one line on
        stderr, no traceback), 130 interrupted (Ctrl-C).
    """
    from threepart.errors import ContactZoneError, NoConvergenceError

    argv = list(sys.argv[1:] if argv is None else argv)
    prog = "threepart"
    try:
        try:
            args, extra = build_parser().parse_known_args(_join_negative_numbers(argv))
        except SystemExit as exc:  # --help
            return exc.code if isinstance(exc.code, int) else 0
        prog = f"threepart {args.command}"
        if extra:   # named here, so that the message names the sub-command
            raise UsageError(f"{prog}: error: unrecognized arguments: {' '.join(extra)} "
                             f"(see `{prog} --help`)")
        return int(args.func(args))
    except UsageError as exc:
        print(exc, file=sys.stderr)
        return 2
    except (ValueError, NoConvergenceError, ContactZoneError, OSError) as exc:
        print(f"{prog}: error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())

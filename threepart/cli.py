"""The ``threepart`` command line.

Sub-commands
------------
solve    normal problem: a, c, alpha, peak pressures, segments in contact, lift-off lever arms
slip     partial slip: adds the stick zone for a shear load Q and friction f
verify   verification run: closed form against SIE and FEM, tolerance report
figures  the paper's result figures, with the SIE solution as markers
map      where the half-plane formulas stop: the finite-body validity map, on dask.distributed
export-refs  the catalogue's reference solutions as a versioned dataset (JSON + CSV, JSON schema)
fatigue  fretting-fatigue parameters of a fretting cycle: hot spots, CSV, VTU and a contour plot
cycle    the flight cycle: steady state of an in-phase cycle (or a load history), CSV and plot
deck     a ready-to-run CalculiX input deck of a catalogue case or of a punch and loads
compare  judge another code's contact pressure (CSV x, p or CalculiX .frd/.dat) against threepart

--method auto (default) uses the paper's closed form where it holds and the SIE
where it does not (past lift-off, the punch on one corner, a stick zone that
ends on the central segment), and says so on the first line of the output and
as "method" in --json; closedform, sie or fem ask for one method. A contact
that would separate into two zones is refused by every method.

--x X1,X2,... or --grid N add the pressure p(x) (and the shear q(x) for slip)
at those points, or at N points spread evenly over the contact; --csv FILE
writes them to a new file, or over the file an earlier run wrote there if it is
unchanged (never over anything else).

Units: the library works in any consistent set of units. The command line
labels lengths mm, loads per unit length N/mm, pressures and moduli MPa,
compliance 1/MPa and the tilt rad; give the input in a consistent set and read
the labels accordingly. Negative numbers may follow their option (--s -0.1).

--json prints strict JSON: plain numbers, a top-level "units" object, and an
infinite R (flat centre) as null.

Exit status: 0 done (verify: every tolerance holds; map: every point done and
the control within 1e-3), 1 a tolerance or a map point failed, 2 an error (one
line on stderr), 130 interrupted (map: run it again to resume).
"""
from __future__ import annotations

import argparse
import math
import os
import select
import signal
import sys
import threading
from typing import Any, Iterator, NoReturn, Sequence

from threepart import cli_cycle
from threepart.__main__ import COMMANDS, INTERRUPTED, program
from threepart.progress import heartbeat
from threepart.units import UNITS

__all__ = ["main", "build_parser", "real_arg", "UNITS", "NUMERIC_OPTIONS", "LIST_OPTIONS", "UsageError"]

#: options that take a number; ``--s -1e-3`` is read as ``--s=-1e-3`` (argparse alone
#: would take ``-1e-3`` for an option)
NUMERIC_OPTIONS = ("--R1", "--R2", "--b", "--R", "--A", "--E", "--nu", "--P", "--s", "--Q", "--f",
                   "--Q-max", "--sigma-bulk", "--k", "--depth",   # --Q-max, --k, --depth: fatigue
                   "--alpha", "--h", "--penalty", "--stiffening")   # deck and compare
#: options that take a comma-separated list of numbers (``--x -0.5,0.2`` is read as ``--x=-0.5,0.2``)
LIST_OPTIONS = ("--x",)
#: the most points ``--grid`` prints
MAX_GRID = 1_000_000




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


def _is_number_list(token: str) -> bool:
    return all(_is_number(t) for t in token.split(","))


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
        negative = nxt is not None and nxt.startswith("-")
        if negative and ((tok in NUMERIC_OPTIONS and _is_number(nxt))            # type: ignore[arg-type]
                         or (tok in LIST_OPTIONS and _is_number_list(nxt))):   # type: ignore[arg-type]
            out.append(f"{tok}={nxt}")
            i += 2
        else:
            out.append(tok)
            i += 1
    return out


def _labelled(help_text: str, quantity: str) -> str:
    return f"{help_text} [{UNITS[quantity]}]"


def _punch_args(p: argparse.ArgumentParser) -> None:
    """``--R1 --R2 --b --R``: the punch of eq. (2), for every command that takes one."""
    g = p.add_argument_group("punch geometry (eq. 2)")
    g.add_argument("--R1", type=float, required=True, help=_labelled("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, required=True, help=_labelled("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, required=True,
                   help=_labelled("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float, default=float("inf"),
                   help=_labelled("central radius: inf (flat, case A, default), negative for "
                                  "concave (case B)", "R"))


def _method_args(p: argparse.ArgumentParser) -> Any:
    """``--method`` (from the registry) and ``--mesh``, for every command that solves; the group."""
    from threepart import registry

    mt = p.add_argument_group("method")
    mt.add_argument("--method", choices=("auto", *registry.names()), default="auto",
                    help="auto (default): the closed form where it holds, else the SIE; or one method")
    mt.add_argument("--mesh", choices=("quick", "default", "fine"), default="default",
                    help="FE mesh preset for --method fem (default: default)")
    return mt


def _geometry_args(p: argparse.ArgumentParser) -> None:
    _punch_args(p)
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
    for k in (0, 1):
        ld.add_argument(f"--state{k}", type=cli_cycle.state_arg, metavar="P,s,Q,SIGMA",
                        help=f"end {k} of an in-phase flight cycle (N/mm, mm, N/mm, MPa), instead of "
                             "--P, --s, --Q-max and --sigma-bulk: the fatigue of its periodic steady "
                             "state at its two ends (docs/STEADY_STATE.md, docs/FATIGUE.md)")
    mt = _method_args(p)
    pt = p.add_argument_group("fields at points")
    pt.add_argument("--x", type=_number_list, metavar="X1,X2,...",
                    help=_labelled("points at which to print p(x) (and q(x) for slip)", "x"))
    pt.add_argument("--grid", type=int, metavar="N",
                    help="print p(x) (and q(x)) at N >= 2 points spread evenly over [-a, c]")
    pt.add_argument("--csv", metavar="FILE",
                    help="write those points to FILE as CSV (a new file, or one threepart wrote "
                         "there and that is unchanged; never over anything else)")
    p.add_argument("--json", action="store_true",
                   help='print strict JSON instead of text: plain numbers in the units of its "units" '
                        "object; an infinite R (flat centre) is null")


def real_arg(text: str) -> float:
    """The value of a number option (the type of every one): ``float(text)``, or a one-line refusal.

    A number that double precision cannot hold is refused, not rounded: one that
    underflows to 0 (``--b 1e-400`` would be solved as a punch without a flat) or
    overflows to inf (``inf`` itself, where an option takes it, is given as such).
    """
    from decimal import Decimal, InvalidOperation

    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid float value: {text!r}") from None
    try:
        exact = Decimal(text.strip().replace("_", ""))
    except InvalidOperation:   # a form float() reads and Decimal does not: nothing lost
        return v
    if v == 0.0 and exact.is_finite() and exact != 0:
        raise argparse.ArgumentTypeError(f"{text} underflows to 0 in double precision (the smallest "
                                         f"positive number is {math.ulp(0.0):.2g})")
    if math.isinf(v) and exact.is_finite():
        raise argparse.ArgumentTypeError(f"{text} overflows to inf in double precision (the largest "
                                         f"number is {sys.float_info.max:.3g})")
    return v


def _number_list(text: str) -> list[float]:
    """``"1,-2.5,3e-1"`` as a list of floats (the type of ``--x``), each read by :func:`real_arg`."""
    try:
        return [real_arg(t) for t in text.split(",")]
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"invalid list of numbers: {text!r} ({exc}; write "
                                         "X1,X2,...)") from None


def _method(args: argparse.Namespace) -> Any:
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
            raise ValueError("give either `--A` or `--E`/`--nu`, not both")
        if args.rigid:
            raise ValueError("`--rigid` applies to `--E`/`--nu`; with `--A` the compliance is "
                             "given, so drop `--rigid`")
        if args.nu is not None and _method(args) is None:
            raise ValueError("`--nu` with `--A` is used only by a method that models a finite "
                             "body (`--method fem`); drop it or give `--E` and `--nu` instead")
        return float(args.A)
    if args.E is None or args.nu is None:
        raise ValueError("the material needs `--A`, or both `--E` and `--nu`")
    return rigid_punch(args.E, args.nu) if args.rigid else compliance(args.E, args.nu)


def _solve(args: argparse.Namespace, slip: bool) -> tuple[Any, dict[str, Any]]:
    """Solve by ``--method`` and collect the figures to print, in print order."""
    from threepart import registry
    from threepart.methods import describe, solve
    from threepart.punch import Punch
    from threepart.results import SlipResult

    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=args.R)
    A = _compliance(args)
    _points_iv(args)
    takes = () if args.method == "auto" else registry.get(args.method).options
    options: dict[str, Any] = {"mesh": args.mesh} if "mesh" in takes else {}
    finite_body, nu_note = _method(args), None
    if finite_body is not None:   # a finite body needs Poisson's ratio besides A
        options["nu"] = finite_body.default_nu if args.nu is None else args.nu
        if args.nu is None:
            nu_note = (f"the FE model needs Poisson's ratio; nu = {finite_body.default_nu} "
                       "assumed (give --nu to set it; in half-plane theory only A matters)")
    if slip and args.sigma_bulk and args.rigid:
        raise ValueError(f"`--sigma-bulk` = {args.sigma_bulk:g} needs elastically similar bodies (its "
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
    return res, out


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
        raise ValueError("give `--x` or `--grid`, not both")
    if args.x is not None and not all(math.isfinite(v) for v in args.x):
        raise ValueError(f"`--x` = {args.x} must hold finite numbers")
    if args.grid is not None and not 2 <= args.grid <= MAX_GRID:
        raise ValueError(f"`--grid` = {args.grid} must lie in [2, {MAX_GRID}]")
    if args.csv is not None:
        if args.x is None and args.grid is None:
            raise ValueError("`--csv` needs the points: give `--x` or `--grid`")
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


def _write_csv(path: str, points: dict[str, list[float]]) -> None:
    """Write the points to ``path`` atomically: a new file, or threepart's own unchanged earlier one.

    Anything else is refused (:func:`threepart.output.write_file`).
    """
    from threepart.output import write_file

    cols = list(points)
    lines = [",".join(f"{k} [{UNITS[k]}]" for k in cols)]
    lines += [",".join(f"{points[k][i]:.17g}" for k in cols) for i in range(len(points["x"]))]
    write_file(path, "\n".join(lines) + "\n", arg="--csv")


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
    headline = out.pop("_describe", None)
    points = out.pop("points", None)
    if as_json:
        from threepart.output import strict_json

        doc = {**out, **({"points": points} if points is not None else {})}
        units = {k: UNITS[k] for k in UNITS if k in _quantities(doc)}
        print(strict_json({**doc, "units": units}, indent=2))
        return
    if headline is not None:
        print(headline)

    def walk(d: dict[str, Any], indent: str = "") -> None:
        for k, v in d.items():
            if isinstance(v, dict):
                print(f"{indent}{k}:")
                walk(v, indent + "  ")
            elif isinstance(v, (int, float)) and not isinstance(v, bool):
                unit = UNITS[k]   # every number has a unit: a missing entry is a bug
                print(f"{indent}{k:<10} {float(v):.10g} {'(dimensionless)' if unit == '1' else unit}")
            elif isinstance(v, list):
                print(f"{indent}{k:<10} {', '.join(map(str, v))}")
            elif k not in ("method_note", "none"):
                print(f"{indent}{k:<10} {v}")
            elif k == "none":
                print(f"{indent}{v}")

    walk({k: v for k, v in out.items() if k != "method"})
    if points is not None:
        cols = list(points)
        print("points:")
        print("  " + "".join(f"{f'{k} [{UNITS[k]}]':>22}" for k in cols))
        for i in range(len(points["x"])):
            print("  " + "".join(f"{points[k][i]:>22.12g}" for k in cols))


def _cmd_solve(args: argparse.Namespace, slip: bool = False) -> int:
    _, out = _solve(args, slip)
    if args.csv is not None:
        _write_csv(args.csv, out["points"])
    _print(out, args.json)
    return 0


def _cmd_slip(args: argparse.Namespace) -> int:
    return _cmd_solve(args, slip=True)


def _cmd_verify(args: argparse.Namespace) -> int:
    from threepart.reports.verify.report import main as verify_main

    mode = "quick" if args.quick else "full" if args.full else "default"
    return int(verify_main(mode=mode, out=args.out, force=args.force))


def _cmd_figures(args: argparse.Namespace) -> int:
    from threepart.reports.figures import main as figures_main

    return int(figures_main(out=args.out, force=args.force))


def _cmd_map(args: argparse.Namespace) -> int:
    from threepart.reports.map.sweep import main as map_main

    return int(map_main(out=args.out, quick=args.quick, scheduler=args.scheduler,
                        workers=args.workers, force=args.force))


def _cmd_export_refs(args: argparse.Namespace) -> int:
    from threepart.reports.refs import main as refs_main

    return int(refs_main(out=args.out, force=args.force, cases=args.cases))


# --- threepart fatigue ---------------------------------------------------------------------

#: the most grid points ``threepart fatigue`` evaluates (each state costs a stress evaluation)
MAX_FATIGUE_POINTS = 100_000
#: the most recorded states per branch ``threepart fatigue`` takes: each distinct state costs a
#: stress evaluation at every grid point (README's example on its default grid, this project's
#: 2-core machine: 50 states 31 s at load 3, 20 states 29 s at load 8); 1000 ran past 5 minutes
MAX_FATIGUE_STATES = 50
#: units of the fatigue parameters in the command line's consistent set (mm, N/mm, MPa)


def _fatigue_units() -> dict[str, str]:
    """The fatigue parameters' units (their table's, :mod:`threepart.fatigue_parameters`) and the plane's."""
    from threepart.fatigue_parameters import parameters

    return {**{p.name: p.unit for p in parameters()}, "theta": "deg"}


def __getattr__(name: str) -> Any:
    if name == "FATIGUE_UNITS":   # read from the table when asked for: no numpy at start-up
        return _fatigue_units()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _fatigue_args(p: argparse.ArgumentParser) -> None:
    _punch_args(p)
    m = p.add_argument_group("material (two similar bodies, plane strain: A = 4(1 - nu^2)/E)")
    m.add_argument("--E", type=float, required=True,
                   help=_labelled("Young's modulus (also for the SWT strains)", "E"))
    m.add_argument("--nu", type=float, required=True, help="Poisson's ratio, in (-1, 0.5)")
    m.add_argument("--k", type=float,   # None: threepart.fatigue.K_FINDLEY, read when used
                   help="Findley's constant, in [0, 10] (default {k_findley})")
    ld = p.add_argument_group("loads: P at s, then the cycle Q = 0 -> Q_max -> -Q_max -> Q_max; or "
                              "a flight cycle's two ends, --state0 and --state1")
    ld.add_argument("--P", type=float,
                    help=_labelled("compressive normal load per unit length, > 0", "P"))
    ld.add_argument("--s", type=float, default=0.0,
                    help=_labelled("lever arm of P, positive to the right", "s"))
    ld.add_argument("--Q-max", dest="Q_max", type=float,
                    help=_labelled("amplitude of the shear force the punch exerts on the substrate "
                                   "along +x, 0 < Q_max < f P", "Q"))
    ld.add_argument("--f", type=float, required=True, help="coefficient of friction, > 0")
    ld.add_argument("--sigma-bulk", dest="sigma_bulk", type=float, default=0.0,
                    help="bulk stress sigma_xx in the substrate at Q_max, tension positive, in "
                         "phase with Q [MPa] (default 0)")
    ld.add_argument("--tilt", choices=("free", "suppressed"), default="free")
    for k in (0, 1):
        ld.add_argument(f"--state{k}", type=cli_cycle.state_arg, metavar="P,s,Q,SIGMA",
                        help=f"end {k} of an in-phase flight cycle (N/mm, mm, N/mm, MPa), instead of "
                             "--P, --s, --Q-max and --sigma-bulk: the fatigue of its periodic steady "
                             "state at its two ends (docs/STEADY_STATE.md, docs/FATIGUE.md)")
    mt = _method_args(p)
    mt.add_argument("--states", type=int, default=5,
                    help=f"recorded states per branch of the cycle, 2 to {MAX_FATIGUE_STATES} "
                         "(default 5; +-Q_max are always recorded); each distinct state costs one "
                         "stress evaluation")
    gr = p.add_argument_group("grid under the contact: x over [-a - W/4, c + W/4], z over [0, depth W]")
    gr.add_argument("--nx", type=int, default=41, help="points along x, >= 2 (default 41)")
    gr.add_argument("--nz", type=int, default=21, help="points in depth, >= 2 (default 21; the "
                                                      "first row is the surface, z = 0)")
    gr.add_argument("--ns", type=int, default=201,
                    help="surface points over the contact for Ruiz's parameters, >= 2 (default "
                         "201, at the midpoints of equal parts, with the grid's surface row)")
    gr.add_argument("--depth", type=float, default=1.0,
                    help="depth of the grid as a multiple of the contact width W = a + c, > 0 "
                         "(default 1)")
    out = p.add_argument_group("output files (each a new file, or one threepart wrote there and "
                               "that is unchanged; never over anything else)")
    out.add_argument("--csv", metavar="FILE", help="the fields at the grid points, as CSV")
    out.add_argument("--vtu", metavar="FILE",
                     help="the fields as a VTU structured grid of quads for ParaView (y = -z)")
    out.add_argument("--plot", metavar="FILE.png", help="contour plots under the contact, as PNG")
    p.add_argument("--json", action="store_true", help="print strict JSON instead of text")


class _FatigueHelp(argparse.HelpFormatter):
    """The help of ``fatigue``: Findley's default constant read only when help is shown.

    Building the parser loads no numpy (see :data:`threepart._HOMES`).
    """

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        if text and "{k_findley}" in text:
            from threepart.fatigue import K_FINDLEY

            text = text.replace("{k_findley}", f"{K_FINDLEY:g}")
        return text


def _fatigue_iv(args: argparse.Namespace) -> None:
    """Check the fatigue command's own options before any numerics (``--k`` gets its default)."""
    import math

    from threepart.fatigue import K_FINDLEY, findley_k
    from threepart.output import check_file
    from threepart.validate import finite, integer, poisson, positive

    positive("--E", args.E)
    poisson(args.nu)
    _fatigue_loads_iv(args)
    args.k = findley_k(K_FINDLEY if args.k is None else args.k)
    finite("--sigma-bulk", args.sigma_bulk)
    integer("--states", args.states, 2, MAX_FATIGUE_STATES)
    integer("--nx", args.nx, 2, MAX_FATIGUE_POINTS // 2)
    integer("--nz", args.nz, 2, MAX_FATIGUE_POINTS // 2)
    integer("--ns", args.ns, 2, MAX_FATIGUE_POINTS)
    if args.nx * args.nz > MAX_FATIGUE_POINTS:
        raise ValueError(f"`--nx` x `--nz` = {args.nx * args.nz} points exceeds "
                         f"{MAX_FATIGUE_POINTS}, the most this command evaluates")
    depth = positive("--depth", args.depth)
    if not depth <= 100:
        raise ValueError(f"`--depth` = {args.depth!r} must be <= 100 contact widths")
    files = [(a, getattr(args, a)) for a in ("csv", "vtu", "plot") if getattr(args, a) is not None]
    seen: dict[str, str] = {}
    for arg, path in files:
        import os

        key = os.path.abspath(path)
        if key in seen:
            raise ValueError(f"`--{arg}` and `--{seen[key]}` name the same file {path!r}")
        seen[key] = arg
        check_file(path, arg=f"--{arg}")
    if not math.isfinite(args.s):
        raise ValueError(f"`--s` = {args.s!r} must be a finite number")


def _fretting(args: argparse.Namespace, punch: Any, A: float) -> Any:
    """The fretting cycle by ``--method`` (``auto``: the closed form, else the SIE where it refuses)."""
    from threepart import registry
    from threepart.methods import AUTO, FALLBACK_ON

    def run(name: str) -> Any:
        m = registry.get(name)
        if m.fretting is None:
            raise ValueError(f"method {name!r} has no fretting cycle")
        options: dict[str, Any] = {"mesh": args.mesh} if "mesh" in m.options else {}
        if m.default_nu is not None:
            options["nu"] = args.nu
        if args.sigma_bulk != 0.0:   # passed only when asked for, to methods that take it
            options["sigma_bulk"] = args.sigma_bulk
        try:
            return m.fretting(punch, args.P, args.s, A=A, tilt=args.tilt, Q_max=args.Q_max, f=args.f,
                              states=args.states, normal=None, **options)
        except TypeError as exc:
            if "sigma_bulk" in str(exc):
                raise ValueError(f"`--sigma-bulk` = {args.sigma_bulk:g}: method {name!r} does not "
                                 "take a bulk stress in its fretting cycle; give --sigma-bulk 0 "
                                 "or another --method") from None
            raise

    if args.method != "auto":
        return run(args.method)
    first, fallback = AUTO
    try:
        return run(first)
    except FALLBACK_ON as refusal:
        why = f"the closed form does not hold here: {' '.join(str(refusal).split())}"
    cycle = run(fallback)
    cycle.info["auto"] = why
    return cycle


def _fatigue_loads_iv(args: argparse.Namespace) -> None:
    """A fretting cycle (``--P`` and ``--Q-max``) or a flight cycle (``--state0`` and ``--state1``), not both."""
    flight = [f"--state{k}" for k in (0, 1) if getattr(args, f"state{k}") is not None]
    fretting = [o for o, v in (("--P", args.P), ("--Q-max", args.Q_max)) if v is not None]
    if flight and (fretting or args.sigma_bulk != 0.0 or args.s != 0.0):
        raise ValueError("give a fretting cycle (`--P`, `--s`, `--Q-max`, `--sigma-bulk`) or a flight "
                         "cycle's ends (`--state0`, `--state1`), not both")
    if flight and len(flight) < 2:
        raise ValueError(f"a flight cycle needs both ends: `--state{1 if flight == ['--state0'] else 0}` "
                         "is missing")
    if not flight and len(fretting) < 2:
        missing = " and ".join(f"`{o}`" for o in ("--P", "--Q-max") if o not in fretting)
        raise ValueError(f"give {missing} (a fretting cycle), or `--state0` and `--state1` (a flight cycle)")


def _flight(args: argparse.Namespace, punch: Any, A: float) -> Any:
    """The steady state of the flight cycle ``--state0`` -> ``--state1`` by ``--method`` (``auto``: falls back)."""
    from threepart import registry, steady_state

    m = None if args.method == "auto" else registry.get(args.method)
    finite = m is not None and m.default_nu is not None      # the FEM: the material's nu, its mesh
    return steady_state(punch, (args.state0, args.state1), args.f, A=A, method=args.method,
                        **({"nu": args.nu, "mesh": args.mesh} if finite else {}))


def _wider_normal(cycle: Any) -> Any:
    """The normal solution of a fretting cycle, or the wider of a steady cycle's two ends."""
    normals = getattr(cycle, "normals", None)
    return cycle.normal if normals is None else max(normals, key=lambda n: float(n.a + n.c))


def _fatigue_grid(args: argparse.Namespace, normal: Any) -> tuple[Any, Any]:
    import numpy as np

    W = normal.a + normal.c
    x = np.linspace(-normal.a - 0.25 * W, normal.c + 0.25 * W, args.nx)
    z = np.linspace(0.0, args.depth * W, args.nz)
    return x[None, :], z[:, None]   # fields of shape (nz, nx): row 0 the surface


def _cmd_fatigue(args: argparse.Namespace) -> int:
    import numpy as np

    from threepart.fatigue import fatigue
    from threepart.material import similar_pair
    from threepart.methods import describe
    from threepart.punch import Punch

    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=args.R)
    _fatigue_iv(args)
    A = similar_pair(args.E, args.nu)
    # a long run says it is still running every 15 s on stderr, as the verification run does

    def say(msg: str) -> None:
        print(f"threepart fatigue: {msg}", file=sys.stderr, flush=True)

    steady = args.state0 is not None
    with heartbeat(say, lambda: "the flight cycle's steady state" if steady else
                    f"the fretting cycle ({args.states} states per branch)"):
        cycle = _flight(args, punch, A) if steady else _fretting(args, punch, A)
    normal = _wider_normal(cycle)
    x, z = _fatigue_grid(args, normal)
    a, c = normal.a, normal.c
    line = -a + (a + c) * (np.arange(args.ns) + 0.5) / args.ns   # inside: never on a contact end
    with heartbeat(say, lambda: f"the stresses of {2 if steady else cycle.Q.size} recorded states "
                                 f"at {args.nx * args.nz + args.ns} points"):
        res = fatigue(cycle, x, z, E=args.E, nu=args.nu, k=args.k,
                      surface=np.union1d(np.ravel(x), line))
    if args.csv is not None:
        _fatigue_csv(args.csv, res)
    if args.vtu is not None:
        _fatigue_vtu(args.vtu, res)
    if args.plot is not None:
        _fatigue_plot(args.plot, res, cycle)
    _fatigue_print(args, res, cycle, A, describe(cycle))
    return 0


def _hot_spots(res: Any) -> dict[str, dict[str, Any]]:
    import math

    out = {}
    for par in res.parameters.values():
        h = par.hot
        row: dict[str, Any] = {"value": h.value, "x": h.x, "z": h.z}
        if h.theta is not None:
            row["theta"] = math.degrees(h.theta)
        out[par.name] = row
    return out


def _fatigue_print(args: argparse.Namespace, res: Any, cycle: Any, A: float, headline: str) -> None:
    normal = _wider_normal(cycle)
    hot = _hot_spots(res)
    steady = args.state0 is not None
    loads: dict[str, Any] = (
        {"states": [list(args.state0), list(args.state1)], "stick_zone": list(cycle.stick_zone),
         "energy": cycle.energy, "shakedown": cycle.shakedown} if steady else
        {"P": args.P, "s": args.s, "Q_max": args.Q_max, "sigma_bulk": args.sigma_bulk})
    doc = {"method": cycle.method, "A": A, "E": args.E, "nu": args.nu, "k": args.k,
           **loads, "f": args.f, "a": normal.a, "c": normal.c,
           "states": res.states, "grid": {"nx": args.nx, "nz": args.nz, "depth_W": args.depth},
           "hot_spots": hot}
    if args.json:
        from threepart.output import strict_json

        units = {"A": "1/MPa", "E": "MPa", "P": "N/mm", "s": "mm", "Q_max": "N/mm", "a": "mm",
                 "c": "mm", "sigma_bulk": "MPa", "x": "mm", "z": "mm", "states": "N/mm, mm, N/mm, MPa",
                 "stick_zone": "mm", "energy": "N*mm/mm", **_fatigue_units()}
        print(strict_json({**doc, "units": units}, indent=2))
        return
    print(headline)
    print(f"contact    [{-normal.a:.6g}, {normal.c:.6g}] mm (a = {normal.a:.6g}, c = {normal.c:.6g})")
    if steady:
        (P0, s0, Q0, g0), (P1, s1, Q1, g1) = args.state0, args.state1
        print(f"cycle      in phase between (P, s, Q, sigma_bulk) = ({P0:g}, {s0:g}, {Q0:g}, {g0:g}) and "
              f"({P1:g}, {s1:g}, {Q1:g}, {g1:g}) [N/mm, mm, N/mm, MPa], f {args.f:g}; its steady state: "
              f"stick zone [{cycle.stick_zone[0]:.6g}, {cycle.stick_zone[1]:.6g}] mm, energy "
              f"{cycle.energy:.6g} N*mm/mm per cycle" + (", shaken down" if cycle.shakedown else ""))
    else:
        print(f"cycle      Q_max {args.Q_max:g} N/mm, f {args.f:g}, sigma_bulk {args.sigma_bulk:g} MPa, "
              f"{res.states} distinct states")
    print(f"grid       {args.nx} x {args.nz} points, x over [-a - W/4, c + W/4], z over "
          f"[0, {args.depth:g} W]; Ruiz also at {args.ns} surface points over the contact")
    print("hot spots (units: mm, N/mm, MPa, or any consistent set):")
    from threepart.fatigue_parameters import parameter

    for name, row in hot.items():
        unit = _fatigue_units()[name]
        where = f"x = {row['x']:.6g} mm, z = {row['z']:.6g} mm"
        plane = f", plane theta = {row['theta']:.2f} deg" if "theta" in row else ""
        if parameter(name).zero and row["value"] == 0.0:
            where = parameter(name).zero
        print(f"  {parameter(name).label:<26} {row['value']:.6g} {unit}  at {where}{plane}")


def _fatigue_columns(res: Any) -> dict[str, Any]:
    import numpy as np

    from threepart.fatigue_parameters import parameters as fatigue_parameters

    fields = [p for p in fatigue_parameters() if not p.surface]
    cols = {"x": res.parameters[fields[0].name].x, "z": res.parameters[fields[0].name].z}
    cols.update({p.name: res.parameters[p.name].value for p in fields})
    cols.update({f"theta_{p.name}": np.degrees(res.parameters[p.name].theta)
                 for p in fields if p.critical_plane})
    return cols


def _fatigue_csv(path: str, res: Any) -> None:
    """The fields at the grid points, one row each; Ruiz's (surface) columns only where z = 0."""
    import numpy as np

    from threepart.fatigue_parameters import parameters as fatigue_parameters
    from threepart.output import write_file

    cols = _fatigue_columns(res)
    tops = [p.name for p in fatigue_parameters() if p.surface]
    units = {"x": "mm", "z": "mm", **{k: "deg" for k in cols if k.startswith("theta_")}, **_fatigue_units()}
    names = [*cols, *tops]
    flat = {k: np.ravel(v) for k, v in cols.items()}
    top = res.parameters[tops[0]] if tops else None
    surface = {float(x): i for i, x in enumerate(top.x)} if top is not None else {}
    lines = [",".join(f"{k} [{units[k]}]" for k in names)]
    for i in range(flat["x"].size):
        row = [f"{flat[k][i]:.17g}" for k in cols]
        j = surface.get(float(flat["x"][i])) if flat["z"][i] == 0 else None
        row += [f"{res.parameters[k].value[j]:.17g}" if j is not None else "" for k in tops]
        lines.append(",".join(row))
    write_file(path, "\n".join(lines) + "\n", arg="--csv")


def _fatigue_vtu(path: str, res: Any) -> None:
    """The fields as a VTU grid of quads (points ``(x, -z, 0)``: the surface at y = 0, depth down)."""
    import meshio
    import numpy as np

    from threepart.output import write_file

    cols = _fatigue_columns(res)
    nz, nx = cols["x"].shape
    pts = np.column_stack([np.ravel(cols["x"]), -np.ravel(cols["z"]), np.zeros(nx * nz)])
    i, j = np.meshgrid(np.arange(nz - 1), np.arange(nx - 1), indexing="ij")
    n0 = (i * nx + j).ravel()
    quads = np.column_stack([n0, n0 + 1, n0 + nx + 1, n0 + nx])
    data = {k: np.ravel(v).astype(float) for k, v in cols.items() if k not in ("x", "z")}
    data["depth"] = np.ravel(cols["z"]).astype(float)
    mesh = meshio.Mesh(pts, [("quad", quads)], point_data=data)
    write_file(path, lambda p: meshio.write(p, mesh, file_format="vtu"), arg="--vtu")


def _fatigue_plot(path: str, res: Any, cycle: Any) -> None:
    """Contours of the three field parameters under the contact (z downward) and Ruiz on the surface."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from threepart.fatigue_parameters import parameter, parameters as fatigue_parameters
    from threepart.output import write_file

    units = _fatigue_units()
    normal = _wider_normal(cycle)
    fields = [p for p in fatigue_parameters() if not p.surface]
    rows = (len(fields) + 2) // 2   # the fields, then Ruiz on the surface
    fig, axes = plt.subplots(rows, 2, figsize=(11, 4 * rows), constrained_layout=True)
    for ax, par in zip(axes.flat, (res.parameters[p.name] for p in fields)):
        cs = ax.contourf(par.x, par.z, par.value, levels=20, cmap="viridis")
        fig.colorbar(cs, ax=ax, label=f"{parameter(par.name).label} [{units[par.name]}]")
        ax.plot([-normal.a, normal.c], [0, 0], color="red", lw=4, solid_capstyle="butt",
                label="contact")
        ax.plot(par.hot.x, par.hot.z, "w*", ms=12, mec="k", label="hot spot")
        ax.set_ylim(float(par.z.max()), 0.0)   # z downward
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("depth z [mm]")
        ax.set_title(parameter(par.name).label)
        ax.legend(loc="lower right", fontsize=8)
    ax = axes.flat[len(fields)]
    for spare in axes.flat[len(fields) + 1:]:
        spare.set_visible(False)
    r = res.ruiz
    ax.plot(r.x, r.ffdp.value, "C0", label="FFDP s_xx q delta")
    ax.set_ylabel(f"FFDP [{units['ruiz_ffdp']}]", color="C0")
    ax.axvspan(-normal.a, normal.c, color="red", alpha=0.1, label="contact")
    twin = ax.twinx()   # FDP has other units
    twin.plot(r.x, r.fdp.value, "C1--", label="FDP q delta")
    twin.set_ylabel(f"FDP [{units['ruiz_fdp']}]", color="C1")
    ax.set_xlabel("x [mm]")
    ax.set_title("Ruiz at the surface")
    ax.legend(handles=[*ax.get_legend_handles_labels()[0], *twin.get_legend_handles_labels()[0]],
              fontsize=8, loc="upper center")
    try:
        write_file(path, lambda p: fig.savefig(p, format="png", dpi=110), arg="--plot")
    finally:
        plt.close(fig)


def _problem_args(p: argparse.ArgumentParser, *, compliance_option: bool) -> None:
    """``--case NAME``, or the punch, the loads and the material on the command line."""
    g = p.add_argument_group("the problem: --case NAME, or the punch and the loads (eq. 2)")
    g.add_argument("--case", metavar="NAME", help="a case of the catalogue (threepart/cases.json)")
    for name, text in (("--R1", "left edge radius"), ("--R2", "right edge radius"),
                       ("--b", "half-width of the central segment")):
        g.add_argument(name, type=float, help=_labelled(text, name[2:]))
    g.add_argument("--R", type=float, default=None,
                   help=_labelled("central radius (default inf: flat)", "R"))
    g.add_argument("--P", type=float, help=_labelled("normal load per unit length", "P"))
    g.add_argument("--s", type=float, default=None, help=_labelled("lever arm of P (default 0)", "s"))
    g.add_argument("--E", type=float, help=_labelled("Young's modulus of the block", "E"))
    g.add_argument("--nu", type=float, help="Poisson's ratio of the block")
    if compliance_option:
        g.add_argument("--A", type=float,
                       help=_labelled("compliance of the model judged (eq. 4); default: the case's, "
                                      "or 2(1 - nu^2)/E (a rigid punch)", "A"))
    g.add_argument("--tilt", choices=("free", "suppressed"), default=None,
                   help="free (default, or the case's) or suppressed")


def _problem(args: argparse.Namespace) -> dict[str, Any]:
    """The punch, loads and material of ``--case`` or of the command line's options."""
    from threepart.catalogue import get_case, load_cases
    from threepart.punch import Punch

    given = [o for o in ("R1", "R2", "b", "R", "P", "s") if getattr(args, o) is not None]
    if args.case is not None:
        if given:
            raise ValueError(f"give `--case` or the punch and loads, not both (also got "
                             f"`--{given[0]}`)")
        if args.case not in {c.name for c in load_cases(None)}:
            names = ", ".join(c.name for c in load_cases(None))
            raise ValueError(f"`--case` = {args.case!r} is not in the catalogue ({names})")
        case = get_case(args.case).resolved()
        if case.material is None and (args.E is None or args.nu is None):
            raise ValueError(f"case {case.name!r} gives only A; add `--E` and `--nu`")
        E, nu = case.material if case.material is not None else (args.E, args.nu)
        E = E if args.E is None else args.E
        nu = nu if args.nu is None else args.nu
        return {"name": case.name, "punch": case.punch, "P": case.P, "s": float(case.s or 0.0),
                "E": E, "nu": nu, "A": case.A if args.E is None and args.nu is None else None,
                "tilt": args.tilt or case.tilt}
    missing = [o for o in ("R1", "R2", "b", "P", "E", "nu") if getattr(args, o) is None]
    if missing:
        raise ValueError(f"give `--case NAME`, or the punch and the loads: `--{missing[0]}` is missing")
    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=float("inf") if args.R is None else args.R)
    return {"name": "", "punch": punch, "P": args.P, "s": 0.0 if args.s is None else args.s,
            "E": args.E, "nu": args.nu, "A": None, "tilt": args.tilt or "free"}


def _cmd_deck(args: argparse.Namespace) -> int:
    from threepart import calculix
    from threepart.material import compliance, similar_pair
    from threepart.methods import solve
    from threepart.output import write_file

    if args.format != "calculix":
        raise ValueError(f"`--format` = {args.format!r}: only calculix is written")
    pr = _problem(args)
    settings = calculix.DeckSettings(h=args.h, penalty=args.penalty, pair=args.pair,
                                     tilt=pr["tilt"], **({} if args.stiffening is None
                                                         else {"stiffening": args.stiffening}))
    E, nu = pr["E"], pr["nu"]
    A = similar_pair(E, nu) if args.pair else compliance(E, nu, E * settings.stiffening, nu)
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


def _cmd_compare(args: argparse.Namespace) -> int:
    from threepart.material import rigid_punch
    from threepart.methods import solve
    from threepart.reports.referee import main as referee_main
    from threepart.results import NormalResult

    _compare_iv(args)
    pr = _problem(args)
    A = args.A if args.A is not None else pr["A"] if pr["A"] is not None else rigid_punch(pr["E"], pr["nu"])
    ref = solve(pr["punch"], pr["P"], pr["s"], A=A, tilt=pr["tilt"])
    assert isinstance(ref, NormalResult)           # no Q: the normal problem
    return int(referee_main(args.pressure, ref, out=args.out, alpha=args.alpha, penalty=args.penalty))


def _compare_iv(args: argparse.Namespace) -> None:
    """Check ``compare``'s own options before any numerics or any file is written."""
    from threepart.validate import SLOPE_LIMIT, finite, positive

    if args.alpha is not None and not abs(finite("--alpha", args.alpha)) <= SLOPE_LIMIT:
        raise ValueError(f"`--alpha` = {args.alpha!r} rad exceeds the small-slope limit "
                         f"{SLOPE_LIMIT:g} of half-plane theory in magnitude: no model judged "
                         "against it tilts that far")
    if args.penalty is not None:
        positive("--penalty", args.penalty)


_FORCE_HELP = ("no longer needed: a rerun replaces threepart's own earlier output in --out (its "
               ".threepart-output.json lists every file with a checksum, and nothing else is there); "
               "a directory holding anything else, or an edited file, is never replaced, with or "
               "without --force")


class _MapHelp(argparse.HelpFormatter):
    """The help of ``map``: the quick grid's size and the CPUs counted, only when help is shown."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        if text and "{quick_points}" in text:
            from threepart.reports.map.validity import map_points

            text = text.replace("{quick_points}", str(len(map_points(True))))
        if text and "{max_workers}" in text:
            from threepart.reports.map.sweep import MAX_WORKERS

            text = text.replace("{max_workers}", str(MAX_WORKERS))
        return text


def build_parser() -> argparse.ArgumentParser:
    """The parser of every sub-command; its usage errors raise :class:`UsageError`."""
    parser = _Parser(prog="threepart", description=__doc__,
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = sub.add_parser("solve", help="normal problem (closed form where it holds, else SIE)",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, rad, or any consistent set.")
    _geometry_args(p)
    p.set_defaults(func=_cmd_solve, Q=None, f=None)

    p = sub.add_parser("slip", help="partial slip (Ciavarella-Jaeger; closed form or SIE)",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, rad, or any consistent set.")
    _geometry_args(p)
    p.add_argument("--Q", type=float, required=True, help=_labelled("shear force, |Q| < f P", "Q"))
    p.add_argument("--f", type=float, required=True, help="coefficient of friction, > 0")
    p.add_argument("--sigma-bulk", type=float, default=0.0, dest="sigma_bulk",
                   help=_labelled("bulk stress along x in the substrate at Q, MPa, tension positive; "
                                  "rises with Q in proportion (default 0)", "sigma_bulk"))
    p.set_defaults(func=_cmd_slip)

    p = sub.add_parser("verify", help="closed form against SIE and FEM; writes a tolerance report")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true", help="coarse meshes, small n (<= 2 min)")
    mode.add_argument("--full", action="store_true", help="adds the slow convergence studies")
    p.add_argument("--out", default="report",
                   help="output directory: new, empty, or threepart's own earlier report, which is "
                        "replaced (default: ./report)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.set_defaults(func=_cmd_verify)

    p = sub.add_parser("figures", help="reproduce the paper's result figures")
    p.add_argument("--out", default="figures",
                   help="output directory: new, empty, or threepart's own earlier figures, which "
                        "are replaced (default: ./figures)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.set_defaults(func=_cmd_figures)

    p = sub.add_parser("map", help="where the half-plane formulas stop: finite-body validity map",
                       formatter_class=_MapHelp)
    p.add_argument("--quick", action="store_true",
                   help="the quick grid ({quick_points} points and the control, quick meshes)")
    p.add_argument("--out", default="map",
                   help="output directory: new or empty, or an unfinished map to resume; see "
                        "--force (default: ./map)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a running dask scheduler, e.g. tcp://host:8786 (default: a local cluster)")
    p.add_argument("--workers", type=int, metavar="N",
                   help="worker processes of the local cluster, 1 to the CPUs of this machine "
                        "({max_workers} here) (default: 2)")
    p.add_argument("--force", action="store_true",
                   help="replace a finished map in --out (a map is expensive: never without "
                        "--force; only one threepart wrote, unchanged); an unfinished map of the "
                        "same mode is resumed, with or without it")
    p.set_defaults(func=_cmd_map)

    p = sub.add_parser("export-refs", help="the catalogue's reference solutions as a versioned "
                                           "dataset (docs/REFERENCE_DATA.md)")
    p.add_argument("--out", default="refs",
                   help="output directory: new, empty, or threepart's own earlier export, which is "
                        "replaced (default: ./refs)")
    p.add_argument("--cases", metavar="NAME,...", type=lambda t: t.split(","),
                   help="export only these catalogue cases (default: every case)")
    p.add_argument("--force", action="store_true", help=_FORCE_HELP)
    p.set_defaults(func=_cmd_export_refs)
    p = sub.add_parser("fatigue", help="fretting-fatigue parameters of a fretting cycle: hot spots, "
                                       "CSV, VTU, contour plot",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, or any consistent set (the parameters "
                              "then follow: SWT, Findley and the von Mises range in the stress "
                              "unit, Ruiz's FDP in stress x length, FFDP in stress^2 x length). "
                              "Definitions: docs/FATIGUE.md.", formatter_class=_FatigueHelp)
    _fatigue_args(p)
    p.set_defaults(func=_cmd_fatigue)
    cli_cycle.add_parser(sub)   # threepart cycle: its own module

    p = sub.add_parser("deck", help="write a ready-to-run CalculiX deck of a case or a punch",
                       epilog="Units: mm, N/mm, MPa, or any consistent set. See docs/CALCULIX.md.")
    p.add_argument("--format", default="calculix", help="the deck's format: calculix (default)")
    _problem_args(p, compliance_option=False)
    p.add_argument("--out", required=True, metavar="FILE.inp",
                   help="the deck to write (a new file, or one threepart wrote there, unchanged)")
    from threepart.calculix import W_OVER_H
    p.add_argument("--h", type=float, help=_labelled(
        f"element size at the contact (default W/200; from W/{W_OVER_H[1]:g} to W/{W_OVER_H[0]:g}, "
        "W = a + c the contact width)", "a"))
    p.add_argument("--penalty", type=float, metavar="K",
                   help="penalty stiffness K [MPa/mm] (default 200 E/h)")
    p.add_argument("--pair", action="store_true",
                   help="two similar elastic bodies instead of a stiff punch")
    p.add_argument("--stiffening", type=float,
                   help="the stiff punch's modulus over the block's (default 1000)")
    p.set_defaults(func=_cmd_deck)

    p = sub.add_parser("compare", help="judge another code's contact pressure against threepart")
    p.add_argument("--pressure", required=True, metavar="FILE",
                   help="a CSV of x, p (p >= 0 compressive), or CalculiX's .frd or .dat (with the deck .inp beside it) holding the contact output CDIS, CSTR, CELS")
    _problem_args(p, compliance_option=True)
    p.add_argument("--alpha", type=float, help=_labelled("the model's tilt, if known", "alpha"))
    p.add_argument("--penalty", type=float, metavar="K",
                   help="the model's penalty stiffness [MPa/mm], for the penalty diagnosis")
    p.add_argument("--out", default="compare",
                   help="report directory: new, empty, or threepart's own earlier report "
                        "(default: ./compare)")
    p.set_defaults(func=_cmd_compare)
    for action in _actions(parser):   # one reader of numbers: every `type=float` option's
        if action.type is float:
            action.type = real_arg
    return parser


def _actions(parser: argparse.ArgumentParser) -> Iterator[argparse.Action]:
    """Every option of ``parser`` and of its sub-commands."""
    for action in parser._actions:
        yield action
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                yield from _actions(sub)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


#: the exit status when the reader of standard output went away (``threepart slip | head``):
#: 128 + SIGPIPE, what a program killed by the signal reports, and silent, as ``git`` and coreutils are
PIPE_CLOSED = 141


def _stdout_closed() -> bool:
    """Whether standard output is a pipe whose reader has gone (then nothing more can be printed).

    Its buffer is pointed at ``os.devnull`` so that the interpreter's flush at exit
    does not fail a second time.
    """
    try:
        fd = sys.stdout.fileno()
        poll = select.poll()
        poll.register(fd, select.POLLOUT)
        closed = any(ev & select.POLLERR for _, ev in poll.poll(0))
    except (OSError, ValueError, AttributeError):   # no file descriptor (a test's capture)
        return False
    if closed:
        os.dup2(os.open(os.devnull, os.O_WRONLY), fd)
    return closed


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
        stderr, no traceback), 130 interrupted (Ctrl-C), 141 (silently) when
        the reader of standard output has gone.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    # named before parsing, so that Ctrl-C while the parser is built names the command too
    prog = program(argv)
    interrupted, previous = _watch_interrupts()
    args = None
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
    except BaseException as exc:
        # Ctrl-C inside a C extension's import (numpy's) comes out as an ImportError, or any
        # other error, with the KeyboardInterrupt lost: the flag, not the class, tells
        if not (isinstance(exc, KeyboardInterrupt) or interrupted.is_set()):
            return _error_status(_units_hint(exc, args), prog)
        resume = "; run it again to resume" if prog == "threepart map" else ""
        print(f"{prog}: interrupted{resume}", file=sys.stderr)
        return INTERRUPTED
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def _watch_interrupts() -> tuple[threading.Event, Any]:
    """An event that SIGINT sets, and the handler it replaced (None: none replaced).

    The new handler still raises KeyboardInterrupt, as Python's default does. It
    is installed only where Python's own handler is (not where SIGINT is ignored,
    nor off the main thread).
    """
    event = threading.Event()
    if (threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGINT) is not signal.default_int_handler):
        return event, None

    def on_sigint(signum: int, frame: Any) -> None:
        event.set()
        raise KeyboardInterrupt

    return event, signal.signal(signal.SIGINT, on_sigint)


#: a modulus below this (MPa) with a contact past the slope limit is likely given in GPa
#: (the metals' moduli lie between about 45 and 410 GPa; steel's is 210 GPa = 210000 MPa)
GPA_SUSPECT_E = 1000.0


def _units_hint(exc: BaseException, args: argparse.Namespace | None) -> BaseException:
    """``exc``, or for a slope past the limit (or a contact past an arc) with a small ``--E``,
    the same error pointing at the modulus and its units.

    ``--E 210`` (steel in GPa, not MPa) makes the contact a thousand times too
    compliant and its slope absurd; the slope-limit error alone would send the
    user to the load or the lever arm.
    """
    from threepart.errors import ArcExtentError, SlopeLimitError

    E = getattr(args, "E", None)
    if (not isinstance(exc, (SlopeLimitError, ArcExtentError)) or E is None
            or getattr(args, "A", None) is not None or not 0 < E < GPA_SUSPECT_E):
        return exc
    what = _one_line(exc).replace("; reduce the load or the lever arm `s`", "")
    return type(exc)(f"is `--E` = {E:g} in MPa (steel: 210000, not 210)? With it, {what}; "
                     "else reduce the load or the lever arm `s`")


def _error_status(exc: BaseException, prog: str) -> int:
    """The exit status of an error that ended a command (its one line on stderr), or re-raise it."""
    from threepart.errors import ContactZoneError, NoConvergenceError

    try:
        raise exc
    except UsageError as exc:
        print(exc, file=sys.stderr)
        return 2
    except BrokenPipeError as exc:
        if not _stdout_closed():
            print(f"{prog}: error: {_one_line(exc)}", file=sys.stderr)
            return 2
        return PIPE_CLOSED
    except (ValueError, NoConvergenceError, ContactZoneError, OSError) as exc:
        print(f"{prog}: error: {_one_line(exc)}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

"""``threepart fatigue``: fretting-fatigue parameters of a fretting cycle or of a flight cycle.

A fretting cycle ``Q = 0 -> Q_max -> -Q_max -> Q_max`` at ``P`` (:func:`threepart.fretting`,
its ``auto`` fallback), or the periodic steady state of an in-phase flight cycle
between ``--state0`` and ``--state1`` (:func:`threepart.steady_state`), or either of a
catalogue case (``--case``); then the
fatigue parameters on a grid under the contact (:func:`threepart.fatigue.fatigue`):
their hot spots printed (or ``--json``), the fields as CSV (``--csv``), as a VTU
grid for ParaView (``--vtu``) and as contour plots (``--plot``). Definitions:
docs/FATIGUE.md.
"""
from __future__ import annotations

import argparse
from typing import Any

from threepart.progress import heartbeat

from ._args import (case_arg, catalogue_case, constant_arg, given_R, labelled, method_args, method_options,
                    need_options, punch_args, state_args)
from ._output import print_json, say_for, write_csv, write_grid_vtu
from threepart.errors import InputError

__all__ = ["add_parser", "run", "MAX_FATIGUE_POINTS", "MAX_FATIGUE_STATES"]

#: the most grid points ``threepart fatigue`` evaluates (each state costs a stress evaluation)
MAX_FATIGUE_POINTS = 100_000
#: the most recorded states per branch ``threepart fatigue`` takes: each distinct state costs a
#: stress evaluation at every grid point (README's example on its default grid, this project's
#: 2-core machine: 50 states 31 s at load 3, 20 states 29 s at load 8); 1000 ran past 5 minutes
MAX_FATIGUE_STATES = 50
#: what ``--case`` refuses beside it: the options of the problem (their ``dest``)
PROBLEM_OPTIONS = ("R1", "R2", "b", "R", "E", "nu", "P", "s", "Q_max", "f", "sigma_bulk", "tilt",
                   "state0", "state1")


def _fatigue_units() -> dict[str, str]:
    """The fatigue parameters' units (their table's, :mod:`threepart.fatigue.table`) and the plane's."""
    from threepart.fatigue.table import parameters

    return {**{p.name: p.unit for p in parameters()}, "theta": "deg"}


def add_parser(sub: Any) -> None:
    """Add ``fatigue`` to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("fatigue", help="fretting-fatigue parameters of a fretting cycle: hot spots, "
                                       "CSV, VTU, contour plot",
                       epilog="Units: mm, N/mm, MPa, 1/MPa, or any consistent set (the parameters "
                              "then follow: SWT, Findley and the von Mises range in the stress "
                              "unit, Ruiz's FDP in stress x length, FFDP in stress^2 x length). "
                              "Definitions: docs/FATIGUE.md.", formatter_class=_FatigueHelp)
    _fatigue_args(p)
    p.set_defaults(func=run)


def _fatigue_args(p: argparse.ArgumentParser) -> None:
    case_arg(p.add_argument_group("the problem: --case NAME, or the punch, material and loads below"),
             "a catalogue case with a material, f and a shear load (its Q the amplitude Q_max of the "
             "fretting cycle) or a flight cycle's `states`",
             "`threepart cases` lists them; the punch, material and loads beside it are refused")
    punch_args(p)
    m = p.add_argument_group("material (two similar bodies, plane strain: A = 4(1 - nu^2)/E), unless --case")
    m.add_argument("--E", type=float, help=labelled("Young's modulus (also for the SWT strains)", "E"))
    m.add_argument("--nu", type=float, help="Poisson's ratio, in (-1, 0.5)")
    m.add_argument("--k", type=float,   # None: threepart.fatigue.K_FINDLEY, read when used
                   help="Findley's constant, in [0, 10] (default {k_findley})")
    m.add_argument("--constant", action="append", default=[], type=constant_arg, metavar="NAME=VALUE",
                   help="another fatigue parameter's constant, by the name its row of "
                        "threepart.fatigue.table gives it, e.g. kappa=0.5 (Crossland's, in [0, 10]; "
                        "default {kappa_crossland}); repeatable")
    ld = p.add_argument_group("loads, unless --case: P at s, then the cycle Q = 0 -> Q_max -> -Q_max -> "
                              "Q_max; or a flight cycle's two ends, --state0 and --state1")
    ld.add_argument("--P", type=float,
                    help=labelled("compressive normal load per unit length, > 0", "P"))
    ld.add_argument("--s", type=float,
                    help=labelled("lever arm of P, positive to the right (default 0)", "s"))
    ld.add_argument("--Q-max", dest="Q_max", type=float,
                    help=labelled("amplitude of the shear force the punch exerts on the substrate "
                                   "along +x, 0 < Q_max < f P", "Q"))
    ld.add_argument("--f", type=float, help="coefficient of friction, > 0")
    ld.add_argument("--sigma-bulk", dest="sigma_bulk", type=float,
                    help="bulk stress sigma_xx in the substrate at Q_max, tension positive, in "
                         "phase with Q [MPa] (default 0)")
    ld.add_argument("--tilt", choices=("free", "suppressed"), help="free (default) or suppressed")
    state_args(ld)
    mt = method_args(p)
    mt.add_argument("--states", type=int, default=5,
                    help=f"recorded states per branch of the cycle, 2 to {MAX_FATIGUE_STATES} "
                         "(default 5; +-Q_max are always recorded); each distinct state costs one "
                         "stress evaluation")
    gr = p.add_argument_group("grid under the contact: x over [-a - W/4, c + W/4], z over [0, depth W]")
    # None: threepart.fatigue.table.GRID, read when used (as --k)
    gr.add_argument("--nx", type=int, help="points along x, >= 2 (default {nx})")
    gr.add_argument("--nz", type=int, help="points in depth, >= 2 (default {nz}; the "
                                           "first row is the surface, z = 0)")
    gr.add_argument("--ns", type=int,
                    help="surface points over the contact for Ruiz's parameters, >= 2 (default "
                         "{ns}, at the midpoints of equal parts, with the grid's surface row)")
    gr.add_argument("--depth", type=float,
                    help="depth of the grid as a multiple of the contact width W = a + c, > 0 "
                         "(default {depth})")
    out = p.add_argument_group("output files (each a new file, or one threepart wrote there and "
                               "that is unchanged; never over anything else)")
    out.add_argument("--csv", metavar="FILE", help="the fields at the grid points, as CSV")
    out.add_argument("--vtu", metavar="FILE",
                     help="the fields as a VTU structured grid of quads for ParaView (y = -z)")
    out.add_argument("--plot", metavar="FILE.png", help="contour plots under the contact, as PNG")
    p.add_argument("--json", action="store_true", help="print strict JSON instead of text")


class _FatigueHelp(argparse.HelpFormatter):
    """The help of ``fatigue``: Findley's and Crossland's default constants and the default grid read
    only when help is shown (their one home, threepart.fatigue.table).

    Building the parser loads no numpy (see :data:`threepart._HOMES`).
    """

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        if text and "{" in text:
            from threepart.fatigue import K_FINDLEY
            from threepart.fatigue.table import GRID, KAPPA_CROSSLAND

            text = text.replace("{k_findley}", f"{K_FINDLEY:g}").replace("{kappa_crossland}", f"{KAPPA_CROSSLAND:.3g}")
            for key, value in GRID.items():
                text = text.replace(f"{{{key}}}", f"{value:g}")
        return text


def _problem_iv(args: argparse.Namespace) -> float | None:
    """The problem of ``--case`` written into ``args`` (its compliance returned), or the options'
    defaults (None returned: A from ``--E``/``--nu``); before any numerics."""
    if args.case is None:
        need_options(args, ("R1", "R2", "b", "E", "nu", "f"))
        args.s = 0.0 if args.s is None else args.s
        args.sigma_bulk = 0.0 if args.sigma_bulk is None else args.sigma_bulk
        args.tilt = args.tilt or "free"
        return None
    c = catalogue_case(args, PROBLEM_OPTIONS)
    if c.material is None or c.f is None or (c.Q is None and c.states is None):
        from threepart.problem.catalogue import load_cases

        fit = ", ".join(k.name for k in load_cases(None) if k.material is not None and k.f is not None)
        raise InputError(f"case {c.name!r} has no material (E, nu), f and shear load or `states` for a "
                         f"fatigue cycle (cases with them: {fit})")
    args.R1, args.R2, args.b, args.R = c.punch.R1, c.punch.R2, c.punch.b, c.punch.R
    (args.E, args.nu), args.f, args.tilt = c.material, c.f, c.tilt
    args.s, args.sigma_bulk = 0.0, 0.0
    if c.states is not None:
        args.state0, args.state1 = c.states
    else:
        args.P, args.s, args.Q_max, args.sigma_bulk = c.P, c.s_load, c.Q, c.sigma_bulk
    return float(c.A)


def _fatigue_iv(args: argparse.Namespace) -> None:
    """Check the fatigue command's own options before any numerics (``--k`` gets its default)."""
    import math

    from threepart.fatigue import K_FINDLEY, findley_k
    from threepart.fatigue.table import GRID
    from threepart.output import check_file
    from threepart.problem.checks import finite, integer, poisson, positive

    positive("--E", args.E)
    poisson(args.nu)
    _fatigue_loads_iv(args)
    args.k = findley_k(K_FINDLEY if args.k is None else args.k)
    for key, value in GRID.items():
        if getattr(args, key) is None:
            setattr(args, key, value)
    args.constants = _constants_iv(args.constant)
    finite("--sigma-bulk", args.sigma_bulk)
    _bulk_stress_iv(args)
    integer("--states", args.states, 2, MAX_FATIGUE_STATES)
    integer("--nx", args.nx, 2, MAX_FATIGUE_POINTS // 2)
    integer("--nz", args.nz, 2, MAX_FATIGUE_POINTS // 2)
    integer("--ns", args.ns, 2, MAX_FATIGUE_POINTS)
    if args.nx * args.nz > MAX_FATIGUE_POINTS:
        raise InputError(f"`--nx` x `--nz` = {args.nx * args.nz} points exceeds "
                         f"{MAX_FATIGUE_POINTS}, the most this command evaluates")
    depth = positive("--depth", args.depth)
    if not depth <= 100:
        raise InputError(f"`--depth` = {args.depth!r} must be <= 100 contact widths")
    files = [(a, getattr(args, a)) for a in ("csv", "vtu", "plot") if getattr(args, a) is not None]
    seen: dict[str, str] = {}
    for arg, path in files:
        import os

        key = os.path.abspath(path)
        if key in seen:
            raise InputError(f"`--{arg}` and `--{seen[key]}` name the same file {path!r}")
        seen[key] = arg
        check_file(path, arg=f"--{arg}")
    if not math.isfinite(args.s):
        raise InputError(f"`--s` = {args.s!r} must be a finite number")


def _constants_iv(given: list[tuple[str, float]]) -> dict[str, float]:
    """``--constant`` as ``{name: value}``: each a constant some row of the table names, once; not ``k``."""
    from threepart.fatigue.table import parameters

    known = sorted({c for p in parameters() for c in p.constants} - {"k"})
    out: dict[str, float] = {}
    for name, value in given:
        if name == "k":
            raise InputError("`--constant k=...`: Findley's constant is `--k`")
        if name not in known:
            raise InputError(f"`--constant {name}=...`: no fatigue parameter has a constant `{name}` "
                             f"(theirs: {', '.join(known) or 'none'}; Findley's k is `--k`)")
        if name in out:
            raise InputError(f"`--constant {name}` is given twice")
        out[name] = value
    return out


def _fretting(args: argparse.Namespace, punch: Any, A: float) -> Any:
    """The fretting cycle by ``--method`` (:func:`threepart.fretting`: ``auto`` falls back to the SIE)."""
    from threepart.methods import fretting

    return fretting(punch, args.P, args.s, A=A, tilt=args.tilt, Q_max=args.Q_max, f=args.f,
                    states=args.states, method=args.method, sigma_bulk=args.sigma_bulk,
                    **method_options(args, args.nu))


def _bulk_stress_iv(args: argparse.Namespace) -> None:
    """A nonzero ``--sigma-bulk`` only for a method that declares it takes one (``Method.bulk_stress``)."""
    from threepart import registry

    if args.sigma_bulk != 0.0 and args.method != "auto" and not registry.get(args.method).bulk_stress:
        raise InputError(f"`--sigma-bulk` = {args.sigma_bulk:g}: method {args.method!r} does not "
                         "take a bulk stress in its fretting cycle; give --sigma-bulk 0 or another "
                         "--method")


def _fatigue_loads_iv(args: argparse.Namespace) -> None:
    """A fretting cycle (``--P`` and ``--Q-max``) or a flight cycle (``--state0`` and ``--state1``), not both."""
    flight = [f"--state{k}" for k in (0, 1) if getattr(args, f"state{k}") is not None]
    fretting = [o for o, v in (("--P", args.P), ("--Q-max", args.Q_max)) if v is not None]
    if flight and (fretting or args.sigma_bulk != 0.0 or args.s != 0.0):
        raise InputError("give a fretting cycle (`--P`, `--s`, `--Q-max`, `--sigma-bulk`) or a flight "
                         "cycle's ends (`--state0`, `--state1`), not both")
    if flight and len(flight) < 2:
        raise InputError(f"a flight cycle needs both ends: `--state{1 if flight == ['--state0'] else 0}` "
                         "is missing")
    if not flight and len(fretting) < 2:
        missing = " and ".join(f"`{o}`" for o in ("--P", "--Q-max") if o not in fretting)
        raise InputError(f"give {missing} (a fretting cycle), or `--state0` and `--state1` (a flight cycle)")


def _flight(args: argparse.Namespace, punch: Any, A: float) -> Any:
    """The steady state of the flight cycle ``--state0`` -> ``--state1`` by ``--method`` (``auto``: falls back)."""
    from threepart import steady_state

    return steady_state(punch, (args.state0, args.state1), args.f, A=A, method=args.method,
                        **method_options(args, args.nu))


def _wider_normal(cycle: Any) -> Any:
    """The normal solution of a fretting cycle, or the wider of a steady cycle's two ends."""
    normals = getattr(cycle, "normals", None)
    return cycle.normal if normals is None else max(normals, key=lambda n: float(n.a + n.c))


def run(args: argparse.Namespace) -> int:
    """Run ``threepart fatigue``: check, solve the cycle, evaluate the parameters, write, print."""
    from threepart.fatigue.table import fatigue, grid
    from threepart.problem.material import similar_pair
    from threepart.methods import describe
    from threepart.problem.punch import Punch

    case_A = _problem_iv(args)
    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=given_R(args))
    _fatigue_iv(args)
    A = similar_pair(args.E, args.nu) if case_A is None else case_A
    say = say_for("fatigue")   # a long run says it is still running every 15 s on stderr, as verify does

    steady = args.state0 is not None
    with heartbeat(say, lambda: "the flight cycle's steady state" if steady else
                    f"the fretting cycle ({args.states} states per branch)"):
        cycle = _flight(args, punch, A) if steady else _fretting(args, punch, A)
    normal = _wider_normal(cycle)
    x, z, surface = grid(-normal.a, normal.c, nx=args.nx, nz=args.nz, ns=args.ns, depth=args.depth)
    with heartbeat(say, lambda: f"the stresses of {2 if steady else cycle.Q.size} recorded states "
                                 f"at {args.nx * args.nz + args.ns} points"):
        res = fatigue(cycle, x, z, E=args.E, nu=args.nu, k=args.k, surface=surface,
                      **args.constants)
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
    doc = {"method": cycle.method, **({"case": args.case} if args.case else {}), "A": A, "E": args.E, "nu": args.nu, "k": args.k, "constants": args.constants,
           **loads, "f": args.f, "a": normal.a, "c": normal.c,
           "stress_states": res.states, "grid": {"nx": args.nx, "nz": args.nz, "depth_W": args.depth},
           "hot_spots": hot}
    if args.json:
        print_json(doc, {"A": "1/MPa", "E": "MPa", "P": "N/mm", "s": "mm", "Q_max": "N/mm", "a": "mm",
                         "c": "mm", "sigma_bulk": "MPa", "x": "mm", "z": "mm",
                         "states": "N/mm, mm, N/mm, MPa", "stick_zone": "mm", "energy": "N*mm/mm",
                         **_fatigue_units()})
        return
    print(headline)
    if args.case:
        print(f"case       {args.case}")
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
    constants = ", ".join(f"{name} {value:g}" for name, value in {"k": args.k, **args.constants}.items())
    print(f"constants  {constants} (the parameters' own defaults for the others)")
    print("hot spots (units: mm, N/mm, MPa, or any consistent set):")
    from threepart.fatigue.table import parameter

    for name, row in hot.items():
        unit = _fatigue_units()[name]
        where = f"x = {row['x']:.6g} mm, z = {row['z']:.6g} mm"
        plane = f", plane theta = {row['theta']:.2f} deg" if "theta" in row else ""
        if parameter(name).zero and row["value"] == 0.0:
            where = parameter(name).zero
        print(f"  {parameter(name).label:<26} {row['value']:.6g} {unit}  at {where}{plane}")


def _fatigue_columns(res: Any) -> dict[str, Any]:
    import numpy as np

    from threepart.fatigue.table import parameters as fatigue_parameters

    fields = [p for p in fatigue_parameters() if not p.surface]
    cols = {"x": res.parameters[fields[0].name].x, "z": res.parameters[fields[0].name].z}
    cols.update({p.name: res.parameters[p.name].value for p in fields})
    cols.update({f"theta_{p.name}": np.degrees(res.parameters[p.name].theta)
                 for p in fields if p.critical_plane})
    return cols


def _fatigue_csv(path: str, res: Any) -> None:
    """The fields at the grid points, one row each; Ruiz's (surface) columns only where z = 0."""
    import numpy as np

    from threepart.fatigue.table import parameters as fatigue_parameters

    cols = _fatigue_columns(res)
    tops = [p.name for p in fatigue_parameters() if p.surface]
    units = {"x": "mm", "z": "mm", **{k: "deg" for k in cols if k.startswith("theta_")}, **_fatigue_units()}
    names = [*cols, *tops]
    flat = {k: np.ravel(v) for k, v in cols.items()}
    top = res.parameters[tops[0]] if tops else None
    surface = {float(x): i for i, x in enumerate(top.x)} if top is not None else {}
    rows = []
    for i in range(flat["x"].size):
        row = [f"{flat[k][i]:.17g}" for k in cols]
        j = surface.get(float(flat["x"][i])) if flat["z"][i] == 0 else None
        row += [f"{res.parameters[k].value[j]:.17g}" if j is not None else "" for k in tops]
        rows.append(row)
    write_csv(path, [f"{k} [{units[k]}]" for k in names], rows, arg="--csv")


def _fatigue_vtu(path: str, res: Any) -> None:
    """The fields as a VTU grid of quads (points ``(x, -z, 0)``: the surface at y = 0, depth down)."""
    cols = _fatigue_columns(res)
    write_grid_vtu(path, cols["x"], cols["z"], {k: v for k, v in cols.items() if k not in ("x", "z")})


def _fatigue_plot(path: str, res: Any, cycle: Any) -> None:
    """Contours of the three field parameters under the contact (z downward) and Ruiz on the surface."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from threepart.fatigue.table import parameter, parameters as fatigue_parameters
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


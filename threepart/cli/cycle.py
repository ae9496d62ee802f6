"""``threepart cycle``: the flight cycle at the command line (issue 31; docs/STEADY_STATE.md).

The periodic steady state of an in-phase cycle between two states ``(P, s, Q,
sigma_bulk)`` (:func:`threepart.steady_state`): the permanent stick zone
``[-(d+e), d-e]`` (eqs. S5, S6), shakedown (eq. S12), the energy per cycle
(eq. S11), the slip amplitude (eq. S7) and the fatigue hot spots of the steady
cycle (:func:`threepart.fatigue.fatigue`); or a load history of any shape read
from a CSV file and marched with the memory of slip (:func:`sie.load_history`,
:func:`fem.load_history`). ``--out DIR`` writes a CSV and a PNG through
:func:`threepart.output.atomic_dir`.

Building the parser loads no numpy: every numerical import is inside ``run``.
"""
from __future__ import annotations

import argparse
import math
from typing import Any

from threepart.progress import heartbeat

from ._args import given_punch_and_material, labelled, method_options, state_arg
from ._output import say_for
from threepart.errors import InputError

__all__ = ["add_parser", "run"]

#: points over the larger contact at which the slip amplitude is sampled (its largest value, the CSV)
PROFILE_POINTS = 2001
#: two cycles' energies agree when they differ by at most this fraction of the larger: the
#: history's active-set march repeats its states, so a settled cycle repeats its work to round-off
ENERGY_AGREE = 1e-6
#: the methods ``cycle`` takes (the steady state's: closed form, SIE, FEM; auto as ``solve``)
METHODS = ("auto", "closedform", "sie", "fem")


def add_parser(sub: Any) -> None:
    """Add the ``cycle`` sub-command to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("cycle", help="the flight cycle: steady state of an in-phase cycle, or a load "
                                     "history marched with the memory of slip",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                       epilog="Units: mm, N/mm, MPa, 1/MPa, or any consistent set. "
                              "See docs/STEADY_STATE.md.")
    g = p.add_argument_group("the problem: --case NAME, or the punch (eq. 2), material and friction")
    g.add_argument("--case", metavar="NAME",
                   help="a catalogue case with `states` (e.g. fan_blade_flight_cycle); with "
                        "--history, any case with a material or A and f")
    g.add_argument("--R1", type=float, help=labelled("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, help=labelled("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, help=labelled("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float, default=None, help=labelled("central radius (default inf: flat)", "R"))
    g.add_argument("--E", type=float, help=labelled("Young's modulus of both bodies", "E"))
    g.add_argument("--nu", type=float, help="Poisson's ratio of both bodies")
    g.add_argument("--A", type=float, help=labelled("compliance of the similar pair, 4(1 - nu^2)/E "
                                                     "(eq. 4); or give --E and --nu", "A"))
    g.add_argument("--f", type=float, help="coefficient of friction, > 0")
    ld = p.add_argument_group("loads: the two ends of the cycle, or a history")
    for k in (0, 1):
        ld.add_argument(f"--state{k}", type=state_arg, metavar="P,s,Q,SIGMA",
                        help=f"end {k} of the cycle: P [N/mm] > 0, s [mm], Q [N/mm] with |Q| < f P, "
                             "sigma_bulk [MPa]")
    ld.add_argument("--history", metavar="FILE.csv",
                    help="a load history: CSV with the columns P, s, Q, sigma_bulk, one state a row, "
                         "marched with the memory of slip (methods sie, fem)")
    mt = p.add_argument_group("method")
    mt.add_argument("--method", choices=METHODS, default="auto",
                    help="auto (default): the closed form where it holds, else the SIE, and where the "
                         "superposition refuses the cycle (one end shakes down, the ends slip in opposite senses, "
                         "the end contacts do not overlap) the SIE's load history marched until two cycles "
                         "agree; a history: the SIE")
    mt.add_argument("--mesh", choices=("quick", "default", "fine"), default="default",
                    help="FE mesh preset for --method fem (default: default)")
    mt.add_argument("--n", type=int, metavar="N",
                    help="the SIE's elements: of the shear grid of a --history (default 400; 8 to "
                         "4000; each cycle's energy converges as N grows), or of the SIE's steady state")
    p.add_argument("--out", metavar="DIR",
                   help="write cycle.csv (and for a history states.csv) and cycle.png into DIR: new, "
                        "empty, or threepart's own earlier output, which is replaced")
    p.set_defaults(func=run)


_say = say_for("cycle")


def _case(args: argparse.Namespace) -> dict[str, Any]:
    """Punch, compliance, material and friction (and states) of ``--case``; refuses a case without states."""
    from threepart.problem.catalogue import get_case, load_cases

    given = [o for o in ("R1", "R2", "b", "R", "E", "nu", "A", "f", "state0", "state1")
             if getattr(args, o) is not None]
    if given:
        raise InputError(f"give `--case` or the punch, material and loads, not both (also got `--{given[0]}`)")
    names = [c.name for c in load_cases(None)]
    if args.case not in names:
        raise InputError(f"`--case` = {args.case!r} is not in the catalogue ({', '.join(names)})")
    case = get_case(args.case).resolved()
    if case.states is None and args.history is None:
        with_states = ", ".join(c.name for c in load_cases(None) if c.states is not None)
        raise InputError(f"case {case.name!r} has no cycle `states` (cases with states: {with_states}); "
                         "give another case, or `--history FILE.csv`")
    if case.f is None:
        raise InputError(f"case {case.name!r} has no coefficient of friction `f`")
    A = case.A
    # the SWT strains use the case's own modulus; a compliance-only case is read as a similar pair
    E, nu = case.material if case.material is not None else (None, None)
    return {"name": case.name, "punch": case.punch, "A": A, "E": E, "nu": nu, "f": case.f,
            "states": None if args.history is not None else case.states}


def _given(args: argparse.Namespace) -> dict[str, Any]:
    """Punch, compliance, material, friction and states of the command line's options."""
    from threepart.problem.material import similar_pair
    from threepart.problem.checks import positive

    punch, nu = given_punch_and_material(args, ("R1", "R2", "b", "f"))
    if args.A is not None:
        A = positive("--A", args.A)
    else:
        assert nu is not None      # both --E and --nu, checked above
        A = similar_pair(positive("--E", args.E), nu)
    states = None
    if args.history is None:
        if args.state0 is None or args.state1 is None:
            raise InputError(f"give the two ends of the cycle, `--state0` and `--state1` "
                             f"(`--state{0 if args.state0 is None else 1}` is missing), or `--history FILE.csv`")
        states = (args.state0, args.state1)
    return {"name": "", "punch": punch, "A": A, "E": args.E, "nu": nu, "f": positive("--f", args.f),
            "states": states}


def _problem(args: argparse.Namespace) -> dict[str, Any]:
    """The checked problem, before any numerics: ``name``, ``punch``, ``A``, ``E``, ``nu``, ``f``, ``states``."""
    from threepart.errors import FullSlidingError
    from threepart.output import check_out
    from threepart.problem.material import NU

    if args.history is not None and (args.state0 is not None or args.state1 is not None):
        raise InputError("give the ends `--state0`/`--state1` or `--history`, not both")
    if args.history is not None and args.method == "closedform":
        raise InputError("`--history` is marched numerically: `--method closedform` has none; "
                         "use sie (auto) or fem")
    if args.n is not None and args.method in ("closedform", "fem"):
        raise InputError(f"`--n` = {args.n} sets the SIE's elements: drop it with `--method {args.method}`")
    pr = _case(args) if args.case is not None else _given(args)
    if pr["nu"] is None:    # only A given: a similar pair of the default Poisson ratio
        pr["nu"] = NU
    if pr["E"] is None:
        pr["E"] = 4 * (1 - pr["nu"] ** 2) / pr["A"]
    if pr["states"] is not None:
        f = pr["f"]
        for k, (P, _, Q, _) in enumerate(pr["states"]):
            if not abs(Q) < f * P:
                raise FullSlidingError(f"`--state{k}`: |Q| = {abs(Q):g} >= f P = {f * P:g} (`--f` = {f:g}, "
                                       f"P = {P:g}): the contact slides as a whole, there is no stick zone")
    else:
        from threepart.halfplane.load_history import read_history

        pr["history"] = read_history(args.history)
    if args.out is not None:
        check_out(args.out, command="cycle")
    return pr


def _steady(args: argparse.Namespace, pr: dict[str, Any]) -> Any:
    """The steady state by ``--method`` (the FEM with the problem's Poisson ratio)."""
    from threepart import steady_state

    return steady_state(pr["punch"], pr["states"], pr["f"], A=pr["A"], method=args.method,
                        **method_options(args, pr["nu"]))


def _march(args: argparse.Namespace, pr: dict[str, Any]) -> Any:
    """The history marched by the SIE (``auto``, ``sie``) or the FEM."""
    from threepart import registry
    from threepart.methods import AUTO

    m = registry.get(AUTO[1] if args.method == "auto" else args.method)
    if m.history is None:
        raise InputError(f"`--method` = {args.method}: it marches no load history (sie and fem do)")
    return m.history(pr["punch"], pr["history"], pr["f"], A=pr["A"], **method_options(args, pr["nu"]))


def run(args: argparse.Namespace) -> int:
    """Run ``threepart cycle``: check the input, solve, print, and write ``--out``; the exit status."""

    pr = _problem(args)
    history = "history" in pr
    what = (f"the load history ({len(pr['history'])} states, {args.method})" if history
            else f"the steady state ({args.method})")
    with heartbeat(_say, lambda: what):
        res = _march(args, pr) if history else _steady(args, pr)
    if history:
        figures = _history_figures(res)
        _print_history(pr, res, figures)
    else:
        figures = _steady_figures(res)
        with heartbeat(_say, lambda: "the fatigue hot spots"):
            hot = None if res.shakedown else _hot_spots(res, pr)
        _print_steady(pr, res, figures, hot)
    if args.out is not None:
        if history:
            figures["loop"] = res.loop()
        elif getattr(res, "history", None) is not None:     # a marched steady state: its own last cycle
            figures["loop"] = res.history.loop()
        else:
            with heartbeat(_say, lambda: "the hysteresis loop (the cycle marched by the SIE)"):
                figures["loop"] = _steady_loop(pr)
        _write_out(args.out, pr, res, figures)
    return 0


#: load states of the first loading (from rest to state 0) and of each half-cycle, and the
#: cycles marched, for the hysteresis loop of a steady state (the loop of the last cycle)
LOOP_STEPS, LOOP_CYCLES = 20, 2


def _steady_loop(pr: dict[str, Any]) -> Any:
    """``(delta, Q)`` of the steady cycle, marched by the SIE's load history (the loop's only source)."""
    from threepart import registry
    from threepart.halfplane.steady import cycle_states

    start, end = pr["states"]
    states = cycle_states(start, end, LOOP_STEPS, LOOP_CYCLES)
    march = registry.get("sie").history
    assert march is not None     # the SIE registers its load history (sie/method.py)
    return march(pr["punch"], states, pr["f"], A=pr["A"], period=2 * LOOP_STEPS).loop()


def _profile_x(normals: Any) -> Any:
    import numpy as np

    lo, hi = min(-n.a for n in normals), max(n.c for n in normals)
    return np.linspace(lo, hi, PROFILE_POINTS)


def _steady_figures(res: Any) -> dict[str, Any]:
    """x over the larger contact, q at both ends (None in shakedown), the slip amplitude."""
    import numpy as np

    x = _profile_x(res.normals)
    q = (None, None) if res.shakedown else (res.shear(x, 0), res.shear(x, 1))
    zones = list(getattr(res, "stick_intervals", ())) or ([] if _zoneless(res) else [res.stick_zone])
    return {"x": x, "q0": q[0], "q1": q[1], "slip": np.asarray(res.slip_amplitude(x), float),
            "stick": zones, "largest": res.largest_slip_amplitude()}


def _zoneless(res: Any) -> bool:
    """A marched steady state with no permanent stick zone (its end contacts do not overlap)."""
    return hasattr(res, "stick_intervals") and not res.stick_intervals


def _last_cycle(res: Any) -> tuple[int, int]:
    """The states of the last completed cycle, or all of them."""
    return res.cycles[-1] if res.cycles else (0, len(res) - 1)


def _history_figures(res: Any) -> dict[str, Any]:
    """Over the last cycle: q at its states of least and largest Q, the slip amplitude (half the slip's range)."""
    import numpy as np

    i, j = _last_cycle(res)
    ks = list(range(i, j + 1))
    x = _profile_x(res.normals)
    k0 = min(ks, key=lambda k: res.Q[k])
    k1 = max(ks, key=lambda k: res.Q[k])
    slips = np.array([res.slip(x, k) for k in ks])
    return {"x": x, "q0": res.shear(x, k0), "q1": res.shear(x, k1), "k": (k0, k1),
            "slip": 0.5 * (slips.max(axis=0) - slips.min(axis=0)), "stick": list(res.stick[-1])}


def _hot_spots(res: Any, pr: dict[str, Any]) -> dict[str, Any]:
    """The fatigue hot spots of the steady cycle on the default grid (:func:`threepart.fatigue.table.grid`)."""
    from threepart.fatigue.table import fatigue, grid

    x, z, surface = grid(min(-n.a for n in res.normals), max(n.c for n in res.normals))
    F = fatigue(res, x, z, E=pr["E"], nu=pr["nu"], surface=surface)
    out = {}
    for par in F.parameters.values():
        out[par.name] = par.hot
    return out


def _print_states(pr: dict[str, Any], states: Any) -> None:
    if pr["name"]:
        print(f"case       {pr['name']}")
    print(f"material   A = {pr['A']:.10g} 1/MPa, E = {pr['E']:.10g} MPa, nu = {pr['nu']:g}; f = {pr['f']:g}")
    for k, (P, s, Q, sigma) in enumerate(states):
        print(f"state {k}    P = {P:.10g} N/mm, s = {s:.10g} mm, Q = {Q:.10g} N/mm, "
              f"sigma_bulk = {sigma:.10g} MPa")


def _print_slip(figures: dict[str, Any]) -> None:
    """The largest slip amplitude: a steady state's where it lies (``largest_slip_amplitude``), a
    history's sampled on its elements."""
    import numpy as np

    if "largest" in figures:
        value, where = figures["largest"]
    else:
        i = int(np.argmax(figures["slip"]))
        value, where = float(figures["slip"][i]), float(figures["x"][i])
    if not value > 0:
        print("slip amplitude  0 mm everywhere: nothing slips")
        return
    print(f"slip amplitude  largest {value:.10g} mm at x = {where:.10g} mm")


def _print_steady(pr: dict[str, Any], res: Any, figures: dict[str, Any], hot: dict[str, Any] | None) -> None:
    why = res.info.get("auto")
    print(f"method: {res.method}" + (f" ({why})" if why else ""))
    _print_states(pr, res.states)
    if hasattr(res, "stick_intervals"):     # marched: the intervals that stuck all through the last cycle
        zones = ", ".join(f"[{lo:.10g}, {hi:.10g}]" for lo, hi in res.stick_intervals)
        print(f"stick zone {zones} mm (stuck all through the last marched cycle)" if zones else
              "stick zone none: no point stuck all through the last marched cycle")
    else:
        left, right = res.stick_zone
        print(f"stick zone [{left:.10g}, {right:.10g}] mm (d = {res.d:.10g} mm, e = {res.e:.10g} mm)")
    print(f"shakedown  {'yes: nothing slips in the steady state' if res.shakedown else 'no: the ends slip every cycle'}")
    print(f"energy     {res.energy:.10g} N*mm/mm per cycle")
    march = res.info.get("march")
    if march is not None and not march["resolved"]:
        print(f"note       a slip zone of the march spans only 1 or 2 of its {march['n']} elements: its share "
              "of the energy is coarse")
    _print_slip(figures)
    if hot is None:
        print("hot spots  none: the cycle has shaken down, its stresses are locked in by the load history")
        return
    print(f"hot spots of the steady cycle (E = {pr['E']:g} MPa, nu = {pr['nu']:g}):")
    from threepart.fatigue.table import parameter

    for name, h in hot.items():
        label, unit = parameter(name).label, parameter(name).unit
        plane = f", plane theta = {math.degrees(h.theta):.2f} deg" if h.theta is not None else ""
        where = (f"at x = {h.x:.6g} mm, z = {h.z:.6g} mm" if not (parameter(name).zero and h.value == 0.0)
                 else "(no surface point slips in tension)")
        print(f"  {label:<26} {h.value:.6g} {unit}  {where}{plane}")


def _intervals(stick: Any) -> str:
    return ", ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in stick) or "none (every point slipped)"


def _print_history(pr: dict[str, Any], res: Any, figures: dict[str, Any]) -> None:
    print(f"method: {res.method} (a load history of {len(res)} states, marched with the memory of slip)")
    if pr["name"]:
        print(f"case       {pr['name']}")
    print(f"material   A = {pr['A']:.10g} 1/MPa, E = {pr['E']:.10g} MPa, nu = {pr['nu']:g}; f = {pr['f']:g}")
    print(f"stick at the last state  {_intervals(res.stick[-1])} mm")
    if not res.cycles:
        print("cycles     none completed (a cycle ends at each return to the last state)")
    for n, ((i, j), w) in enumerate(zip(res.cycles, res.energy), start=1):
        print(f"cycle {n}    states {i} to {j}: energy {w:.10g} N*mm/mm")
    if len(res.energy) >= 2:
        a, b = float(res.energy[-2]), float(res.energy[-1])
        agree = abs(a - b) <= ENERGY_AGREE * max(abs(a), abs(b))
        print(f"last two cycles  {'agree' if agree else 'differ'} (relative difference "
              f"{abs(a - b) / max(abs(a), abs(b), 1e-300):.3g}; settled within {ENERGY_AGREE:g}: "
              f"{'yes' if agree else 'no'})")
    _print_slip(figures)


def _csv(cols: dict[str, Any]) -> str:
    names = list(cols)
    rows = [",".join(names)]
    n = len(cols[names[0]])
    rows += [",".join(v if isinstance(v := cols[k][i], str) else f"{v:.17g}" for k in names) for i in range(n)]
    return "\n".join(rows) + "\n"


def _profile_csv(figures: dict[str, Any], history: bool) -> str:
    k0, k1 = figures.get("k", (0, 1))
    cols: dict[str, Any] = {"x [mm]": figures["x"]}
    if figures["q0"] is not None:
        cols[f"q at state {k0} [MPa]"] = figures["q0"]
        cols[f"q at state {k1} [MPa]"] = figures["q1"]
    label = "slip amplitude over the last cycle [mm]" if history else "slip amplitude [mm]"
    cols[label] = figures["slip"]
    return _csv(cols)


def _states_csv(res: Any) -> str:
    n = len(res)
    return _csv({"k": [str(k) for k in range(n)], "P [N/mm]": res.P, "s [mm]": res.s, "Q [N/mm]": res.Q,
                 "sigma_bulk [MPa]": res.sigma_bulk,
                 "stick intervals [mm]": [" ".join(f"{lo:.10g}:{hi:.10g}" for lo, hi in res.stick[k])
                                          for k in range(n)],
                 "friction work of the step [N*mm/mm]": res.work})


def _write_out(out: str, pr: dict[str, Any], res: Any, figures: dict[str, Any]) -> None:
    """``cycle.csv`` (and ``states.csv``) and ``cycle.png`` into ``out``, atomically, marked."""
    from threepart.output import atomic_dir

    history = "history" in pr
    with atomic_dir(out, command="cycle") as tmp:
        (tmp / "cycle.csv").write_text(_profile_csv(figures, history), encoding="utf-8")
        if history:
            (tmp / "states.csv").write_text(_states_csv(res), encoding="utf-8")
        _plot(tmp / "cycle.png", figures, res, history)


def _plot(path: Any, figures: dict[str, Any], res: Any, history: bool) -> None:
    """The shear at both extreme states with the stick zone; the hysteresis loop Q against δ."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = figures["x"]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5), constrained_layout=True)
    k0, k1 = figures.get("k", (0, 1))
    if figures["q0"] is not None:
        ax.plot(x, figures["q0"], "C0", label=f"q at state {k0}")
        ax.plot(x, figures["q1"], "C1", label=f"q at state {k1}")
    else:
        ax.text(0.5, 0.5, "shakedown: the shear is locked in by the history", ha="center",
                transform=ax.transAxes)
    for n, (lo, hi) in enumerate(figures["stick"]):
        ax.axvspan(lo, hi, color="grey", alpha=0.2, label="stick zone" if n == 0 else None)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("q [MPa]")
    ax.set_title("shear at the extreme states" + (" of the last cycle" if history else
                                                  "\n(in the stick zone partly locked in by the history)"))
    ax.legend(fontsize=8)
    delta, Q = figures["loop"]
    bx.plot(delta, Q, "C2.-", ms=3)
    bx.set_xlabel("rigid tangential shift δ of the punch [mm] (up to a constant)")
    bx.set_ylabel("Q [N/mm]")
    bx.set_title("hysteresis loop" + (" of the last cycle" if history else " (the cycle marched by the SIE)"))
    try:
        fig.savefig(path, format="png", dpi=110)
    finally:
        plt.close(fig)

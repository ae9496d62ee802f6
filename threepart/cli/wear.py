"""``threepart wear``: fretting wear at constant P and s, Q between ±Q_max (issue 39; docs/WEAR.md).

The problem is a catalogue wear case (``--case fan_blade_flank_wear``, with its
law, ``k`` and cycles), a fretting case of the catalogue (``--case
fretting_Q0.4`` with ``--k`` and ``--cycles``), or the punch, material and loads.
The worn depth is marched by :func:`threepart.wear` (``--method sie``, the
default: the half-plane's contact on cells; ``--method fem``: two similar
bodies with Coulomb friction): each step solves the worn profile's contact, the
stick zone at ``Q_max`` and the slip, and grows the depth by Archard's or the
energy law with cycle jumping. It prints the energy per cycle at the start and
the end, the stick zone's drift and where it lies against the limit's placements,
the worn volume, and the distance of the last pressure to the closed-form worn
limit on the stick zone reached (:func:`threepart.closedform.wear_limit`, L2
over the stick zone less 10 % of it at each end). ``--out DIR`` writes ``wear.csv``
(cycle, energy, stick zone, volume), ``depths.csv`` (the worn depth at each
recorded cycle) and ``wear.png``.

The depth is the two bodies' wear together: the contact sees only the sum,
whatever fixed share each body takes (docs/WEAR.md, section 4).

Building the parser loads no numpy: every numerical import is inside ``run``.
"""
from __future__ import annotations

import argparse
from typing import Any

from threepart.errors import InputError
from threepart.progress import heartbeat

from ._args import E_HELP, NU_HELP, case_arg, catalogue_case, given_punch_and_material, labelled
from ._output import say_for

__all__ = ["add_parser", "run"]

#: the methods ``--method`` names; a method without a wear march is refused by name before any work
METHODS = ("sie", "fem")
#: the laws of :data:`threepart.fretting_wear.LAWS`, named here so that the parser loads no numpy
LAWS = ("archard", "energy")
#: the units of the figures this command prints beside :data:`threepart.problem.units.UNITS`'s
WEAR_UNITS = {"energy": "N*mm/mm per cycle", "volume": "mm^2", "depth": "mm", "k": "mm^2/N",
              "drift": "mm", "cycles": "1", "distance": "1"}


def add_parser(sub: Any) -> None:
    """Add the ``wear`` sub-command to ``sub`` (the sub-parsers of :func:`threepart.cli.build_parser`)."""
    p = sub.add_parser("wear", help="fretting wear: the worn profile, pressure, stick zone and energy per "
                                    "cycle marched over N cycles, against the closed-form worn limit",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                       epilog="Units: mm, N/mm, MPa, 1/MPa, or any consistent set. See docs/WEAR.md.")
    g = p.add_argument_group("the problem: --case NAME, or the punch (eq. 2), material and loads")
    case_arg(g, "a wear case of the catalogue (fan_blade_flank_wear: its law, k and cycles), or a "
                "fretting case (e.g. fretting_Q0.4; give --k and --cycles)",
             "the punch, material and loads beside it are refused")
    g.add_argument("--R1", type=float, help=labelled("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, help=labelled("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, help=labelled("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float, help=labelled("central radius (default inf: flat)", "R"))
    g.add_argument("--E", type=float, help=E_HELP)
    g.add_argument("--nu", type=float, help=NU_HELP)
    g.add_argument("--A", type=float, help=labelled("compliance of the similar pair, 4(1 - nu^2)/E (eq. 4)", "A"))
    g.add_argument("--P", type=float, help=labelled("normal load, > 0, constant", "P"))
    g.add_argument("--s", type=float, help=labelled("its lever arm (default 0), constant", "s"))
    g.add_argument("--Q-max", dest="Q_max", type=float,
                   help=labelled("the shear amplitude: Q runs 0 -> Q_max -> -Q_max -> Q_max, 0 < Q_max < f P", "Q"))
    g.add_argument("--f", type=float, help="coefficient of friction, > 0")
    w = p.add_argument_group("the wear march")
    w.add_argument("--law", choices=LAWS, default=None,
                   help="archard: depth k p |slip|; energy: k q.slip (Fouvry); default the case's, or archard")
    w.add_argument("--k", type=float, help="wear coefficient, > 0 [mm^2/N = mm^3/(N mm)]; default the case's")
    w.add_argument("--cycles", type=int, metavar="N", help="cycles to march in all, >= 1; default the case's")
    w.add_argument("--jump", type=int, metavar="DN",
                   help="cycles per step (cycle jumping); default: the march's step control (the depth per "
                        "jump 1e-2 of the elastic approach A P/pi, and Euler's stability bound per cell or node)")
    w.add_argument("--method", choices=METHODS, default="sie",
                   help="the march: sie (the half-plane's contact on cells; default) or fem (two similar "
                        "bodies with Coulomb friction; needs --E and --nu or a case's material)")
    p.add_argument("--json", action="store_true", help="print the figures as strict JSON")
    p.add_argument("--out", metavar="DIR",
                   help="write wear.csv, depths.csv and wear.png into DIR: new, empty, or threepart's own "
                        "earlier output, which is replaced")
    p.set_defaults(func=run)


_say = say_for("wear")


#: the options of the problem, refused beside ``--case``
OWN = ("R1", "R2", "b", "R", "E", "nu", "A", "P", "s", "Q_max", "f")


def _case(args: argparse.Namespace) -> dict[str, Any]:
    """The problem of ``--case``: a wear case (with its law, k, cycles) or a fretting case of the catalogue."""
    from threepart.problem.catalogue import load_cases
    from threepart.fretting_wear import WearCase

    case = catalogue_case(args, OWN)         # the options beside it, or a name not in the catalogue, refused
    if case.kind == "wear":
        wc = WearCase.of(case)
        c, law, k, n = wc.case, wc.law, wc.k, wc.cycles
    elif case.kind == "fretting":
        c, law, k, n = case, "archard", None, None
    else:
        worn = [x.name for x in load_cases(None) if x.kind in ("wear", "fretting")]
        raise InputError(f"`--case` = {args.case!r} is a {case.kind} case: give a wear case or a fretting "
                         f"case of the catalogue ({', '.join(worn)})")
    return {"name": c.name, "punch": c.punch, "A": c.A, "P": c.P, "s": c.s_load, "Q_max": c.Q, "f": c.f,
            "tilt": c.tilt, "law": law, "k": k, "cycles": n,
            "material": c.material if c.bodies == "similar pair" else None}


def _given(args: argparse.Namespace) -> dict[str, Any]:
    """The problem of the punch, material and load options."""
    from threepart.problem.material import NU, similar_pair
    from threepart.problem.checks import finite, positive

    punch, nu = given_punch_and_material(args, ("R1", "R2", "b", "P", "Q_max", "f"))
    A = positive("--A", args.A) if args.A is not None else similar_pair(positive("--E", args.E),
                                                                       NU if nu is None else nu)
    return {"name": "", "punch": punch, "A": A, "P": positive("--P", args.P),
            "s": 0.0 if args.s is None else finite("--s", args.s), "Q_max": positive("--Q-max", args.Q_max),
            "f": positive("--f", args.f), "tilt": "free", "law": "archard", "k": None, "cycles": None,
            "material": None if args.E is None else (positive("--E", args.E), NU if nu is None else nu)}


def _problem(args: argparse.Namespace) -> dict[str, Any]:
    """Every check of the input, before anything is solved; the problem and the march's settings."""
    from threepart.fretting_wear import MAX_CYCLES, has_marcher, needs_material
    from threepart.output import check_out
    from threepart.problem.checks import integer, positive

    if not has_marcher(args.method):
        raise InputError(f"`--method` = {args.method}: no wear march yet (not yet built for this method)")
    pr = _case(args) if args.case is not None else _given(args)
    if needs_material(args.method) and pr["material"] is None:
        raise InputError(f"`--method` = {args.method} marches two similar bodies of a material: give `--E` and "
                         "`--nu` (not `--A`), or a case with a material of a similar pair")
    if not pr["Q_max"] < pr["f"] * pr["P"]:
        raise InputError(f"`--Q-max` = {pr['Q_max']:g} must be below f P = {pr['f'] * pr['P']:g}: full "
                         "sliding, there is no stick zone to fret about")
    pr["law"] = args.law or pr["law"]
    for opt in ("k", "cycles"):
        if getattr(args, opt) is not None:
            pr[opt] = getattr(args, opt)
        elif pr[opt] is None:
            raise InputError(f"`--{opt}` is missing: the case or problem gives none")
    pr["k"] = positive("--k", pr["k"])
    pr["cycles"] = integer("--cycles", pr["cycles"], 1, MAX_CYCLES)
    pr["jump"] = None if args.jump is None else integer("--jump", args.jump, 1, MAX_CYCLES)
    if args.out is not None:
        check_out(args.out, command="wear")
    return pr


def run(args: argparse.Namespace) -> int:
    """Run ``threepart wear``: check the input, march, judge against the worn limit, print, write; the status."""
    from threepart import wear
    from threepart.fretting_wear import needs_material
    from threepart.reports.verify.wear_section import march_record

    pr = _problem(args)
    with heartbeat(_say, lambda: f"the wear march ({pr['cycles']} cycles, {args.method})"):
        res = wear(pr["punch"], pr["P"], pr["s"], pr["Q_max"], pr["f"], A=pr["A"], law=pr["law"], k=pr["k"],
                   cycles=pr["cycles"], method=args.method, jump=pr["jump"], tilt=pr["tilt"],
                   **(dict(zip(("E", "nu"), pr["material"])) if needs_material(args.method) else {}))
    with heartbeat(_say, lambda: "the closed-form worn limit"):
        rec = march_record(res)
    if args.json:
        _print_json(pr, res, rec)
    else:
        _print(pr, res, rec)
    if args.out is not None:
        _write_out(args.out, res, rec)
    return 0


def _summary(pr: dict[str, Any], res: Any, rec: dict[str, Any]) -> dict[str, Any]:
    """The printed figures, as one dict (the text and ``--json`` print the same)."""
    return {"case": pr["name"] or None, "method": res.method, "law": res.law, "k": res.k,
            "cycles_requested": int(res.info["requested"]), "cycles_reached": int(res.cycles[-1]),
            "steps": int(res.info["steps"]), "stopped": res.info["stopped"] or None,
            "energy_start": float(res.energy[0]), "energy_end": float(res.energy[-1]),
            "energy_peak": float(max(res.energy)), "energy_end_over_start": rec["energy_ratio"],
            "energy_monotone": rec["energy_monotone"], "energy_rise_past_peak": rec["figures"]["energy_monotone"],
            "stick_start": [float(v) for v in res.stick_zones[0]],
            "stick_end": [float(v) for v in res.stick_zones[-1]],
            "stick_drift_over_W": rec["stick_drift"], "stick_to_limit_over_W": rec["figures"]["stick_zone"],
            "volume": float(res.volume),
            "depth_max": float(res.depths[-1].max()),
            "limit_stick_zone": rec["limit"]["stick_zone"], "limit_distance": rec["distance"][-1],
            "identity_error": rec["identity"],
            "time_s": float(res.info["time"])}


def _print_json(pr: dict[str, Any], res: Any, rec: dict[str, Any]) -> None:
    from ._output import print_json

    doc = _summary(pr, res, rec)
    doc["records"] = {"cycles": [int(n) for n in res.cycles], "energy": [float(v) for v in res.energy],
                      "distance": rec["distance"], "volume": [float(v) for v in res.volumes]}
    print_json(doc, {"k": WEAR_UNITS["k"], "energy": WEAR_UNITS["energy"], "volume": WEAR_UNITS["volume"],
                     "stick": "mm", "depth_max": "mm", "time_s": "s"})


def _print(pr: dict[str, Any], res: Any, rec: dict[str, Any]) -> None:
    s = _summary(pr, res, rec)
    print(f"method: {res.method} ({res.law} law, k = {res.k:g} mm^2/N; the depth is both bodies' wear together)")
    if pr["name"]:
        print(f"case       {pr['name']}")
    print(f"loads      P = {res.P:.10g} N/mm, s = {res.s:.10g} mm, Q_max = {res.Q_max:.10g} N/mm, f = {res.f:g}, "
          f"A = {res.A:.10g} 1/MPa")
    print(f"cycles     {s['cycles_reached']} of {s['cycles_requested']} in {s['steps']} steps "
          f"({res.info['jump']} jumps), {s['time_s']:.3g} s")
    if s["stopped"]:
        print(f"stopped    {s['stopped']}")
    print(f"energy     {s['energy_start']:.6g} -> {s['energy_end']:.6g} N*mm/mm per cycle "
          f"({s['energy_end_over_start']:.4g} of the start; peak {s['energy_peak']:.6g}; "
          f"{'falls past its peak' if s['energy_monotone'] else 'rises past its peak'}: largest rise "
          f"{s['energy_rise_past_peak']:.2g} of the peak)")
    (a0, b0), (a1, b1) = s["stick_start"], s["stick_end"]
    print(f"stick zone [{a0:.6g}, {b0:.6g}] -> [{a1:.6g}, {b1:.6g}] mm (drift {s['stick_drift_over_W']:.3g} W)")
    bracket = "; ".join(f"{k} [{v[0]:.6g}, {v[1]:.6g}]" for k, v in rec["limit"]["bracket"].items())
    print(f"worn limit placements {bracket} mm: the march's stick zone lies {s['stick_to_limit_over_W']:.3g} W "
          f"outside them; pressure L2 distance {s['limit_distance']:.4g} to the limit on it "
          f"(stick zone less 10 % at each end)")
    print(f"worn       volume {s['volume']:.6g} mm^2, largest depth {s['depth_max']:.6g} mm; "
          f"volume per cycle against k' W: largest error {s['identity_error']:.3g}")


def _write_out(out: str, res: Any, rec: dict[str, Any]) -> None:
    """``wear.csv``, ``depths.csv`` and ``wear.png`` into ``out``, atomically, marked."""
    from threepart.output import atomic_dir
    from threepart.reports.verify.wear_section import draw

    cols = {"cycle": [str(int(n)) for n in res.cycles], "energy [N*mm/mm]": res.energy,
            "stick x1 [mm]": res.stick_zones[:, 0], "stick x2 [mm]": res.stick_zones[:, 1],
            "volume [mm^2]": res.volumes, "limit distance": rec["distance"]}
    depth_cols = {"x [mm]": res.x, **{f"depth at cycle {int(n)} [mm]": res.depths[j]
                                      for j, n in enumerate(res.cycles)}}
    with atomic_dir(out, command="wear") as tmp:
        (tmp / "wear.csv").write_text(_csv(cols), encoding="utf-8")
        (tmp / "depths.csv").write_text(_csv(depth_cols), encoding="utf-8")
        draw(res, rec, tmp / "wear.png")


def _csv(cols: dict[str, Any]) -> str:
    """Columns as CSV text: a header of the keys, each number to 17 digits (``cycle.py``'s layout)."""
    names = list(cols)
    rows = [",".join(names)]
    rows += [",".join(v if isinstance(v := cols[k][i], str) else f"{float(v):.17g}" for k in names)
             for i in range(len(cols[names[0]]))]
    return "\n".join(rows) + "\n"

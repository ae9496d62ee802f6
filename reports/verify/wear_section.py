"""The report's "Fretting wear" section: the catalogue's wear case marched and judged (issue 39; docs/WEAR.md).

The march of :data:`WEAR_CASE` (:func:`threepart.fretting_wear.wear_case`, the SIE)
is set against the closed-form worn limit (:func:`threepart.closedform.wear_limit`)
and its own identities, each judged by a row of the tolerance table:

* the pressure's approach to the limit on the stick zone the march reached (eqs. W3-W6
  there), L2 over it less :data:`INTERIOR` at each end, relative to the limit's
  (``("wear", "limit_L2")``), that distance's largest rise between records above its last
  value (it falls to the nodes' floor, :func:`rise_above_floor`, ``("wear", "limit_monotone")``),
  and its largest difference of the unworn peak (``("wear", "limit_p0")``);
* the stick zone at ``Q_max`` against the bracket of the limit's placements
  (:data:`LIMIT_RULES`, docs/WEAR.md section 3; a point where ``C1 = 0``), of the unworn
  contact's width W (``("wear", "stick_zone")``); the march's drift from its start beside;
* the energy per cycle past its early peak falling at every record (``("wear",
  "energy_monotone")``), below ``("wear", "energy_left")`` of its start;
* the volume identity, eq. W15: the worn area per cycle (the cells' increments) equals
  ``k W`` under the energy law; Archard's ``k`` is the energy law's ``k/f`` (docs/WEAR.md,
  section 5), so ``k/f`` there (``("wear", "identity")``).

Targets missed are shown as such, as the speed section does; they do not fail the run.

march_record  -- a march's figures against the limit and its identities, with each target judged
draw          -- the worn depth, the pressure, the energy per cycle and the distance to the limit (PNG)
wear_study    -- the catalogue case's march, its record and its plot (the verification run)
study_record  -- a march's record for report.json, its plot drawn
wear_section  -- the section, or None when the document has no wear record
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable

import numpy as np

from threepart.tolerances import tolerance

from .sections import Figure, Section, Status, Table, fmt

__all__ = ["rise_above_floor", "march_record", "draw", "wear_study", "study_record", "wear_section", "WEAR_CASE", "WEAR_PLOT", "INTERIOR", "EARLY",
           "depth_at", "peer_depth",
           "LIMIT_RULES", "TARGETS"]

#: the catalogue's wear case the verification run marches
WEAR_CASE = "fan_blade_flank_wear"
#: where the report draws its march
WEAR_PLOT = "plots/wear.png"
#: the fraction of the limit's stick zone left out at each end of the L2 distance (its singular ends)
INTERIOR = 0.1
#: the bracket of the limit's placements under a free tilt (closedform.wear.STICK_RULES, docs/WEAR.md §3)
LIMIT_RULES = ("pinned", "consistent")
#: target -> (label, tolerance row or None for a yes/no figure)
TARGETS: dict[str, tuple[str, tuple[str, str] | None]] = {
    "limit_L2": ("pressure's L2 distance to the worn limit at the last cycle", ("wear", "limit_L2")),
    "limit_monotone": ("that distance's largest rise between records above its last value (it falls to the nodes' floor)",
                       ("wear", "limit_monotone")),
    "limit_p0": ("largest pressure difference to the worn limit there, of the unworn peak", ("wear", "limit_p0")),
    "stick_zone": ("stick zone at Q_max outside the bracket of the limit's placements (pinned, consistent), of W",
                   ("wear", "stick_zone")),
    "energy_left": ("energy per cycle at the last cycle, of its start", ("wear", "energy_left")),
    "energy_monotone": ("largest rise of the energy per cycle past its peak, of the peak", ("wear", "energy_monotone")),
    "identity": ("worn area per cycle against k W (eq. W15), largest relative error", ("wear", "identity")),
    "peer_depth_early": ("another method's worn depth (the FEM's) against the SIE's after a tenth of the cycles, "
                         "largest, of the SIE's largest depth then", ("wear", "fem_depth")),
    "peer_depth": ("the same at the last cycle (the FE interface erodes the limit's marginal stick-zone end: "
                   "docs/WEAR.md section 8)", ("wear", "fem_depth")),
}
#: the fraction of the cycles after which the methods' depths are compared first
EARLY = 0.1
#: recorded cycles drawn in the depth and pressure panels
DRAWN = 7


def _limits(r: Any) -> tuple[Any, tuple[Any, ...]]:
    """The closed-form limit on the march's own last stick zone, and the bracket ``(pinned, consistent)``.

    Under a moment the limit's placement depends on the history (docs/WEAR.md, section 3):
    the march's stick zone is judged against the bracket, its pressure against the limit on
    the zone it reached (eqs. W3-W6 there). Where the zone cannot be given (an end off the
    outer segments), the bracket's ``"pinned"`` is the limit.
    """
    from threepart.closedform import solve_normal, wear_limit

    normal = solve_normal(r.punch, r.P, r.s, A=r.A, tilt=r.info.get("tilt", "free"))
    bracket = tuple(wear_limit(normal, r.Q_max, r.f, stick=rule) for rule in LIMIT_RULES)
    try:
        x1, x2 = (float(v) for v in r.stick_zones[-1])
        own = wear_limit(normal, r.Q_max, r.f, stick=(x1, x2))
    except ValueError:
        own = bracket[0]
    return own, bracket


def _inner(r: Any, limit: Any) -> np.ndarray:
    x1, x2 = limit.stick_zone
    return (r.x > x1 + INTERIOR * (x2 - x1)) & (r.x < x2 - INTERIOR * (x2 - x1))


def _distances(r: Any, limit: Any) -> list[float]:
    """L2 distance of each recorded pressure (at the cells) to the limit's, over the stick zone's interior."""
    inner = _inner(r, limit)
    ref = limit.pressure(r.x[inner])
    norm = float(np.sqrt(np.mean(ref ** 2)))
    return [float(np.sqrt(np.mean((p[inner] - ref) ** 2)) / norm) for p in r.pressures]


def rise_above_floor(distance: list[float] | np.ndarray) -> float:
    """The largest rise of the distance to the limit between records that ends above its last value.

    The march's distance falls towards the discrete long-run state's, its floor (the nodes'
    error), which its last record approaches; on the way it may pass nearer the limit than
    that floor and return to it. A rise that ends above the last value is a genuine one.
    """
    d = np.asarray(distance, dtype=float)
    return float(np.max(d[1:] - np.maximum(d[:-1], d[-1]), initial=0.0))


def _outside(zone: np.ndarray, bracket: tuple[Any, ...]) -> float:
    """How far the march's stick-zone ends lie outside the bracket of the limit's placements (0 inside)."""
    ends = np.array([lim.stick_zone for lim in bracket])
    lo, hi = ends.min(axis=0), ends.max(axis=0)
    return float(np.max(np.maximum(lo - zone, 0) + np.maximum(zone - hi, 0)))


def _identity(r: Any) -> float:
    """The largest relative error of the worn area per cycle against ``k' W`` over the steps (eq. W15)."""
    k = r.k if r.law == "energy" else r.k / r.f
    dN = np.diff(r.cycles)
    if not dN.size:
        return math.nan
    rate = np.diff(r.volumes) / dN
    return float(np.max(np.abs(rate - k * r.energy[:-1]) / (k * r.energy[:-1])))


def depth_at(r: Any, N: float) -> np.ndarray:
    """A march's worn depth at ``N`` cycles, linear in the cycles between its two records around ``N``."""
    i = int(np.clip(np.searchsorted(r.cycles, N), 1, len(r.cycles) - 1))
    t = float(np.clip((N - r.cycles[i - 1]) / (r.cycles[i] - r.cycles[i - 1]), 0.0, 1.0))
    return np.asarray((1.0 - t) * r.depths[i - 1] + t * r.depths[i])


def peer_depth(r: Any, peer: Any, N: float) -> float:
    """``peer``'s worn depth against ``r``'s after ``N`` cycles: largest difference at ``peer``'s points
    (``r``'s interpolated), of ``r``'s largest depth then."""
    mine = depth_at(r, N)
    return float(np.max(np.abs(np.interp(peer.x, r.x, mine) - depth_at(peer, N)))) / float(np.max(mine))


def peer_figures(r: Any, peer: Any) -> dict[str, Any]:
    """Another method's march of the same problem against ``r``: the depth, the volume, the energy, its run.

    ``depth_early`` compares the two after :data:`EARLY` of the cycles, before the limit's marginal
    stick-zone end forms (docs/WEAR.md section 8).
    """
    top = float(np.max(r.depths[-1]))
    depth = np.interp(peer.x, r.x, r.depths[-1])
    early = EARLY * float(min(r.cycles[-1], peer.cycles[-1]))
    return {"depth": float(np.max(np.abs(depth - peer.depths[-1]))) / top,
            "depth_early": peer_depth(r, peer, early), "early_cycles": int(round(early)),
            "depth_L2": float(np.sqrt(np.mean((depth - peer.depths[-1]) ** 2) / np.mean(depth ** 2))),
            "volume": float(peer.volumes[-1] / r.volumes[-1] - 1), "energy_ratio": float(peer.energy[-1] / peer.energy[0]),
            "stick_zone": [float(v) for v in peer.stick_zones[-1]], "reached": int(peer.cycles[-1]),
            "steps": int(peer.info["steps"]), "time_s": float(peer.info["time"]), "stopped": peer.info["stopped"],
            "method": peer.method}


def march_record(r: Any, peer: Any = None) -> dict[str, Any]:
    """A march's figures: the limit, the distances, the drift, the energy, the identity, each target judged.

    ``peer``, another method's march of the same problem and cycles, adds the target ``peer_depth``.
    """
    limit, bracket = _limits(r)
    distance = _distances(r, limit)
    W = float(r.contacts[0, 1] - r.contacts[0, 0])
    energy = np.asarray(r.energy)
    peak = int(np.argmax(energy))
    inner = _inner(r, limit)
    p0 = float(np.max(r.pressures[0]))
    figures = {"limit_L2": distance[-1], "limit_monotone": rise_above_floor(distance),
               "limit_p0": float(np.max(np.abs(r.pressures[-1][inner] - limit.pressure(r.x[inner])))) / p0,
               "stick_zone": _outside(np.asarray(r.stick_zones[-1]), bracket) / W,
               "energy_left": float(energy[-1] / energy[0]),
               "energy_monotone": float(np.max(np.diff(energy[peak:]), initial=0.0)) / float(energy[peak]),
               "identity": _identity(r)}
    peer_rec = None if peer is None else peer_figures(r, peer)
    if peer_rec is not None:
        figures["peer_depth"] = peer_rec["depth"]
        figures["peer_depth_early"] = peer_rec["depth_early"]
    targets: dict[str, dict[str, Any]] = {}
    for key, (_, row) in TARGETS.items():
        if key not in figures:
            continue
        value = figures[key]
        if row is None:
            targets[key] = {"limit": None, "met": bool(value)}
        else:
            lim = tolerance(*row).limit
            targets[key] = {"limit": lim, "met": bool(value <= lim)}
    return {"limit": {"rule": "the march's own stick zone", "stick_zone": [float(v) for v in limit.stick_zone],
                      "alpha": float(limit.alpha),
                      "bracket": {rule: [float(v) for v in b.stick_zone] for rule, b in zip(LIMIT_RULES, bracket)}},
            "distance": distance, "energy_ratio": figures["energy_left"],
            "energy_monotone": figures["energy_monotone"] <= tolerance("wear", "energy_monotone").limit,
            "energy_peak_cycle": int(r.cycles[peak]),
            "stick_drift": float(np.max(np.abs(r.stick_zones - r.stick_zones[0]))) / W,
            "identity": figures["identity"], "figures": figures, "targets": targets, "W": W,
            "peer": peer_rec, "_limit": limit}


def _picks(n: int) -> list[int]:
    return sorted(set(np.linspace(0, n - 1, min(DRAWN, n)).astype(int).tolist()))


def draw(r: Any, rec: dict[str, Any], path: Path) -> None:
    """The worn depth and the pressure at recorded cycles, the energy per cycle and the distance to the limit."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    limit = rec["_limit"]
    fig, ((ax, bx), (cx, dx)) = plt.subplots(2, 2, figsize=(12, 8.5), constrained_layout=True)
    cmap = plt.get_cmap("viridis")
    picks = _picks(len(r.cycles))
    for i, j in enumerate(picks):
        colour = cmap(i / max(len(picks) - 1, 1))
        label = f"N = {int(r.cycles[j]):,}"
        ax.plot(r.x, 1e3 * r.depths[j], color=colour, label=label)
        bx.plot(r.x, r.pressures[j], color=colour, label=label)
    x1, x2 = limit.stick_zone
    xl = np.linspace(x1, x2, 2001)[1:-1]
    xs = np.linspace(r.x[0], r.x[-1], 2001)
    ax.plot(xs, 1e3 * limit.depth(xs), "k--", label=f"worn limit ({rec['limit']['rule']})")
    bx.plot(xl, limit.pressure(xl), "k--", label="worn limit (eq. W3)")
    # the worn state's square-root ends run off the scale: the panel shows the body of the pressure
    bx.set_ylim(min(0.0, float(np.min(r.pressures))), 2.0 * float(np.max(r.pressures[0])))
    for axis, ylabel, title in ((ax, "worn depth [µm] (both bodies)", "worn profile"),
                                (bx, "p [MPa]", "pressure")):
        for k, v in enumerate(limit.stick_zone):
            axis.axvline(v, color="grey", lw=0.6, ls=":", label="limit's stick zone" if k == 0 else None)
        axis.set_xlabel("x [mm]")
        axis.set_ylabel(ylabel)
        axis.set_title(title + " at the recorded cycles")
        axis.legend(fontsize=7)
    N = np.maximum(r.cycles, 1)
    cx.semilogx(N, r.energy / r.energy[0], "C0.-")
    cx.axhline(rec["targets"]["energy_left"]["limit"], color="C3", ls="--", label="target")
    cx.set_xlabel("cycles N (0 drawn at 1)")
    cx.set_ylabel("energy per cycle / its start")
    cx.set_title("friction energy per cycle")
    cx.legend(fontsize=8)
    dx.loglog(N, rec["distance"], "C1.-")
    dx.axhline(rec["targets"]["limit_L2"]["limit"], color="C3", ls="--", label="target")
    dx.set_xlabel("cycles N (0 drawn at 1)")
    dx.set_ylabel(f"L2 distance of p to the limit (stick zone less {INTERIOR:.0%} at each end)")
    dx.set_title("approach to the worn limit")
    dx.legend(fontsize=8)
    fig.suptitle(f"fretting wear, {r.law} law, k = {r.k:g} mm²/N, {int(r.cycles[-1]):,} of "
                 f"{int(r.info['requested']):,} cycles ({r.method})")
    try:
        fig.savefig(path, format="png", dpi=100)
    finally:
        plt.close(fig)


def wear_study(root: Path, say: Callable[[str], None]) -> dict[str, Any]:
    """The catalogue's wear case marched, judged and drawn into ``root / WEAR_PLOT``: the report's record."""
    import time

    from threepart.fretting_wear import DEFAULT_MARCHER, marchers, needs_material, wear_case

    wc = wear_case(WEAR_CASE)
    t0 = time.perf_counter()
    r = wc.run()
    seconds = time.perf_counter() - t0
    peer = None
    for name in marchers():
        if name != DEFAULT_MARCHER and (wc.case.material is not None or not needs_material(name)):
            material = wc.case.material if needs_material(name) else None
            peer = wc.run(method=name, **({} if material is None else {"E": material[0], "nu": material[1]}))
            break
    rec = study_record(r, root, WEAR_CASE, seconds, peer)
    say(f"[study] wear: {WEAR_CASE}, {rec['reached']} of {rec['requested']} cycles in {rec['steps']} steps, "
        f"{rec['time_s']:.1f} s" + ("" if peer is None else f" ({peer.method}'s {rec['peer']['time_s']:.1f} s)"))
    return rec


def study_record(r: Any, root: Path, name: str, seconds: float, peer: Any = None) -> dict[str, Any]:
    """A march's record for ``report.json`` (:func:`march_record` and the run), its plot drawn into ``root``."""
    rec = march_record(r, peer)
    (root / WEAR_PLOT).parent.mkdir(parents=True, exist_ok=True)
    draw(r, rec, root / WEAR_PLOT)
    rec.pop("_limit")
    return {"case": name, "law": r.law, "k": r.k, "requested": int(r.info["requested"]),
            "reached": int(r.cycles[-1]), "steps": int(r.info["steps"]), "stopped": r.info["stopped"],
            "time_s": seconds, "cycles": [int(n) for n in r.cycles], "energy": [float(v) for v in r.energy],
            "plot": WEAR_PLOT, **rec}


def _peer_text(peer: dict[str, Any] | None) -> tuple[str, ...]:
    if not peer:
        return ()
    return (f"The {peer['method'].upper()}'s march of the same case (for the FEM: two similar bodies, its own Coulomb "
            "slip at Q_max; fem/wear.py) "
            f"reached {peer['reached']:,} cycles in {peer['steps']} steps ({peer['time_s']:.1f} s); its energy per "
            f"cycle ends at {fmt(peer['energy_ratio'])} of its start, its worn area {peer['volume']:+.3g} against "
            f"the SIE's, its depth {fmt(peer['depth_L2'])} off in L2 ({fmt(peer['depth_early'])} largest after "
            f"{peer['early_cycles']:,} cycles). Its stick zone ends at "
            f"[{peer['stick_zone'][0]:.6g}, {peer['stick_zone'][1]:.6g}] mm: the limit's receding end is marginal "
            "(q/p tends to f there), and the FE block's tangential compliance, not the normal one, erodes it "
            "node by node (docs/WEAR.md, section 8).",)


def wear_section(doc: dict[str, Any]) -> Section | None:
    """The report's section "Fretting wear", or None when ``doc`` holds no wear record."""
    rec = doc.get("wear")
    if not rec:
        return None
    rows = []
    for key, (label, _) in TARGETS.items():
        if key not in rec["targets"]:
            continue
        t, value = rec["targets"][key], rec["figures"][key]
        shown = ("yes" if value else "no") if t["limit"] is None else fmt(value)
        rows.append((label, shown, "yes" if t["limit"] is None else f"<= {t['limit']:g}",
                     "met" if t["met"] else "MISSED"))
    stopped = (f" The march stopped early: {rec['stopped'].rstrip('.')}." if rec["stopped"] else "")
    intro = (f"The catalogue's wear case {rec['case']} ({rec['law']} law, k = {rec['k']:g} mm²/N), marched "
             f"by the SIE over {rec['reached']:,} of its {rec['requested']:,} cycles in {rec['steps']} steps "
             f"({rec['time_s']:.1f} s), against the closed-form worn limit "
             f"(closedform.wear_limit on {rec['limit']['rule']}, "
             f"[{rec['limit']['stick_zone'][0]:.6g}, {rec['limit']['stick_zone'][1]:.6g}] mm; its placements "
             + ", ".join(f"{k} [{v[0]:.6g}, {v[1]:.6g}]" for k, v in rec["limit"]["bracket"].items())
             + " mm; docs/WEAR.md)."
             f"{stopped} The energy per cycle peaks at cycle {rec['energy_peak_cycle']:,}. The stick zone at "
             f"Q_max moved by {fmt(rec['stick_drift'])} W from its start. Each "
             "target is a row of the tolerance table; a target missed is shown, and does not fail the run.",)
    met = all(t["met"] for t in rec["targets"].values())
    return Section("Fretting wear", "wear", (intro, *((text,) for text in _peer_text(rec.get("peer")))),
                   (Table(("target", "measured", "limit", ""), tuple(rows)),),
                   (Figure(rec["plot"], "the worn depth and the pressure at recorded cycles, the energy per "
                                        "cycle and the pressure's distance to the worn limit"),),
                   status=Status.of(met))

"""The designer's reading of a validity map and its contour plots.

Every error here is signed, closed form minus finite body (over the finite
body's larger peak): positive where the closed form over-predicts the peak
pressure, which is conservative for the contact stress, and negative where it
under-predicts it, which is not.

Names
-----
LEVELS            -- the signed error levels drawn as contour lines and located as boundaries
LIMIT             -- the designer's limit, 1 % either way
BANDS             -- the filled bands of the contour maps, symmetric about zero
below_level       -- per ``b/R1``, the largest ``(a-b)/R1`` up to which ``|error|`` stays below a level
designer_sentence -- the sentence that says what one contour map means for a designer
level_paths       -- the contour lines of the signed field, as vertex arrays (what the plot draws)
contour           -- draw one contour map (with thin labelled iso-lines of the load level p0/E*)
stick_sentence    -- the sentence that says what the partial-slip plot of a group means for a designer
stick_zone        -- draw the stick zone's signed errors of one group against the overhang
slope_plot        -- draw the small-slope cost against the load level p0/E*, with the 1 % line
"""
from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any, Sequence

from threepart.tolerances import MAP_LIMIT

from .boundary import LEVELS, X
from .schema import finite, pct

__all__ = ["LEVELS", "LIMIT", "BANDS", "below_level", "designer_sentence", "level_paths", "contour",
           "stick_sentence", "stick_zone", "slope_plot", "LOAD_LINES"]

#: the designer's limit: the closed form within 1 % of the finite body's peak, either way
#: (threepart.tolerances.MAP_LIMIT, with its reason)
LIMIT = MAP_LIMIT
#: the filled bands of the contour maps (signed fractions of the peak pressure), symmetric about 0
BANDS = (-0.5, -0.25, -0.1, -0.05, -0.025, -0.01, -0.005, -0.0025, 0.0,
         0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5)
#: the diverging colour map, centred on zero: red where the closed form over-predicts the peak
CMAP = "RdBu_r"
#: the load levels p0/E* drawn as thin labelled iso-lines on each contour map (the load axis)
LOAD_LINES = (0.003, 0.01, 0.03, 0.1, 0.3)


def below_level(points: Sequence[dict[str, Any]], level: float = LIMIT) -> list[dict[str, Any]]:
    """Per ``b/R1``, how far in ``(a-b)/R1`` the peak-pressure error stays within ``± level``.

    Parameters
    ----------
    points
        Map points (dicts with ``b_over_R1``, ``a_minus_b_over_R1`` and the signed
        ``peak_rel_error``, None where the point failed) of one group.
    level
        The error level, a fraction of the peak pressure (a magnitude).

    Returns
    -------
    list of dict
        One per ``b/R1``, ascending: ``b_over_R1``; ``limit``, the largest
        ``(a-b)/R1`` such that every point up to it is within ``± level`` (None
        if the first is not); ``swept``, the largest ``(a-b)/R1`` swept;
        ``stop``, why the scan stopped: ``"level"`` (the next point reaches
        it), ``"failed"`` (the next point has no result) or ``"end"``;
        ``first`` and ``first_error``, the smallest ``(a-b)/R1`` and its
        signed error; ``inside`` and ``beyond``, the signed errors up to the
        limit and past it (failed points left out).
    """
    rows = []
    for b in sorted({p["b_over_R1"] for p in points}):
        line = sorted((p for p in points if p["b_over_R1"] == b), key=lambda p: p[X])
        limit: float | None = None
        stop = "end"
        inside: list[float] = []
        for p in line:
            e = p.get("peak_rel_error")
            if e is None or not finite(e):
                stop = "failed"
                break
            if abs(e) >= level:
                stop = "level"
                break
            limit = p[X]
            inside.append(e)
        beyond = [p["peak_rel_error"] for p in line[len(inside):] if finite(p.get("peak_rel_error"))]
        rows.append({"b_over_R1": b, "limit": limit, "swept": line[-1][X], "stop": stop,
                     "first": line[0][X], "first_error": line[0].get("peak_rel_error"),
                     "inside": inside, "beyond": beyond})
    return rows


def _sign_words(errors: Sequence[float]) -> str:
    """Whether the closed form is conservative over ``errors`` (signed peak errors)."""
    over = max((e for e in errors if e > 0), default=0.0)
    under = min((e for e in errors if e < 0), default=0.0)
    if under == 0:
        return f"over-predicts the peak by up to {pct(over)}: conservative"
    if over == 0:
        return f"under-predicts the peak by up to {pct(-under)}: not conservative"
    return (f"over-predicts the peak by up to {pct(over)} and under-predicts it by up to "
            f"{pct(-under)}: not conservative everywhere")


def _crossing(boundaries: Sequence[dict[str, Any]], b: float, lo: float, hi: float,
              level: float, sign: int = 0) -> dict[str, Any] | None:
    """The located ``± level`` crossing of the curve ``b/R1`` between the overhangs ``lo`` and ``hi``.

    ``sign`` +1 or -1 picks the level ``+level`` or ``-level``; 0 either.
    """
    found = [r for r in boundaries if r["b_over_R1"] == b and abs(r["level"]) == level
             and (sign == 0 or r["level"] * sign > 0) and r["status"] != "failed"
             and lo < r[X] < hi]
    return min(found, key=lambda r: r[X], default=None)


def _band(r: dict[str, Any]) -> str:
    """A located crossing with its FEM band."""
    return f"≈ {r[X]:.3g} (FEM band {r['band'][0]:.3g}–{r['band'][1]:.3g})"


def _end(boundaries: Sequence[dict[str, Any]], b: float, lo: float, hi: float, level: float) -> str:
    """One end of a range within ``± level``: the located crossing with its band, or the bracket."""
    r = _crossing(boundaries, b, lo, hi, level)
    return f"between {lo:g} and {hi:g}" if r is None else _band(r)


def _row(line: Sequence[dict[str, Any]], b: float, level: float,
         boundaries: Sequence[dict[str, Any]]) -> str:
    """The designer's words for one curve ``b/R1``: where it is within ``± level``, and its sign.

    A range within ``± level`` is a run of points inside it, or a window
    between two adjacent points that jump from above ``+level`` to below
    ``-level`` (or back) with both crossings located between them.
    """
    at = f"at b/R1 = {b:g}"
    xs = [p[X] for p in line]
    es: list[Any] = [p.get("peak_rel_error") for p in line]
    ok = [e is not None and finite(e) for e in es]
    if not any(ok):
        return f"unknown {at} (its points failed)"
    # (first, last) positions of each range in the points' indices (a window: i + 1/2)
    spans: list[tuple[float, float, str]] = []
    for i in range(len(line)):
        if not (ok[i] and abs(es[i]) < level):
            if (i + 1 < len(line) and ok[i] and ok[i + 1] and abs(es[i + 1]) >= level
                    and es[i] * es[i + 1] < 0):
                down = _crossing(boundaries, b, xs[i], xs[i + 1], level, +1)
                up = _crossing(boundaries, b, xs[i], xs[i + 1], level, -1)
                if down is not None and up is not None:
                    a, c = sorted((down, up), key=lambda r: r[X])
                    spans.append((i + 0.5, i + 0.5, f"(a−b)/R1 from {_band(a)} to {_band(c)} "
                                  "(changing sign there: not conservative everywhere)"))
            continue
        if spans and i <= spans[-1][1]:   # inside the run already written
            continue
        j = i
        while j + 1 < len(line) and ok[j + 1] and abs(es[j + 1]) < level:
            j += 1
        frm = (f"from the lightest load swept, {xs[0]:g}" if i == 0 else
               f"from {_end(boundaries, b, xs[i - 1], xs[i], level)}" if ok[i - 1] else
               f"from {xs[i]:g} (the point before failed)")
        to = (f"to the end of the sweep, {xs[-1]:g}" if j == len(line) - 1 else
              f"to {_end(boundaries, b, xs[j], xs[j + 1], level)}" if ok[j + 1] else
              f"to {xs[j]:g} (the next point failed)")
        # the run's signs: its points', and at each end the outside neighbour's (the error is
        # continuous, so next to a crossing of +level it is positive, of -level negative)
        run_e = es[i:j + 1] + [es[k] for k in (i - 1, j + 1) if 0 <= k < len(line) and ok[k]]
        sign = ("conservative" if min(run_e) >= 0 else "not conservative" if max(run_e) <= 0
                else "changing sign there: not conservative everywhere")
        spans.append((i, j, f"(a−b)/R1 {frm} {to} ({sign})"))
    if not spans:
        return f"at no load swept {at} (it {_sign_words([e for e, k in zip(es, ok) if k])})"
    words = f"{at} for {' and '.join(s[2] for s in spans)}"
    lighter = [es[k] for k in range(len(line)) if ok[k] and k < spans[0][0]]
    heavier = [es[k] for k in range(len(line)) if ok[k] and k > spans[-1][1]]
    between = [es[k] for s, t in zip(spans, spans[1:]) for k in range(len(line))
               if ok[k] and s[1] < k < t[0]]
    for errors, where in ((lighter, "at lighter loads"), (between, "in between"),
                          (heavier, "at heavier loads")):
        if errors:
            words += f"; {where} it {_sign_words(errors)}"
    return words


def _curve(points: Sequence[dict[str, Any]], boundaries: Sequence[dict[str, Any]],
           b: float) -> list[dict[str, Any]]:
    """The curve ``b/R1`` of one group: its grid points and its bisection steps, by overhang."""
    line = {p[X]: p for p in points if p["b_over_R1"] == b}
    for r in boundaries:
        if r["b_over_R1"] == b:
            for s in r["steps"]:
                line.setdefault(s[X], s)
    return [line[x] for x in sorted(line)]


def designer_sentence(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float,
                      s_over_lift: float = 0.0, level: float = LIMIT,
                      boundaries: Sequence[dict[str, Any]] = ()) -> str:
    """What the contour map of ``points`` (one group) means for a designer, in one sentence.

    For each ``b/R1`` (the grid points and the bisection's steps of
    ``boundaries``): over which ``(a-b)/R1`` the closed form's peak is
    within ``± level`` of the finite body's (each end the located boundary
    with its FEM band where the map bisected it, else the points' bracket),
    whether it is conservative there (a positive error: it over-predicts the
    peak), and by how much it over- or under-predicts the peak outside.
    """
    estimates = [p["fem_error_estimate"] for p in points if finite(p.get("fem_error_estimate"))]
    caveat = ""
    if estimates and max(estimates) > level / 3:
        caveat = (f" (the FEM's own error estimate reaches {pct(max(estimates))} here: differences "
                  "smaller than that are not resolved)")
    lever = "s = 0" if s_over_lift == 0 else f"s = {s_over_lift:g} of the lift-off lever arm"
    head = (f"For R2/R1 = {R2_over_R1:g}, H/b = {H_over_b:g} and {lever}, the closed form's "
            "peak pressure")
    lines = {b: _curve(points, boundaries, b) for b in sorted({p["b_over_R1"] for p in points})}
    parts = [_row(line, b, level, boundaries) for b, line in lines.items()]
    if all(p.startswith("at no load swept") for p in parts):
        firsts: list[Any] = [line[0].get("peak_rel_error") for line in lines.values()]
        every: list[Any] = [p.get("peak_rel_error") for line in lines.values() for p in line]
        lightest = ", ".join(f"{v:g}" for v in sorted({line[0][X] for line in lines.values()}))
        return (f"{head} is off by {pct(min(firsts, key=abs))} to {pct(max(firsts, key=abs))} "
                f"already at the lightest load swept, (a−b)/R1 = {lightest}, and more than "
                f"{pct(level)} everywhere (it {_sign_words(every)}): over this whole range, "
                f"design with a finite-body model{caveat}.")
    return (f"{head} is within {pct(level)} of the finite body's {'; '.join(parts)}. Elsewhere "
            f"design with a finite-body model{caveat}.")


def _lines(ax: Any, x: Any, y: Any, z: Any, levels: Sequence[float]) -> Any:
    """The contour lines of the signed field ``z`` at ``levels`` over the points ``(x, y)``, or None."""
    from matplotlib.tri import Triangulation

    try:
        tri = Triangulation(x, y)
        inside = sorted(lv for lv in levels if z.min() < lv < z.max())
        if not inside:
            return None
        return ax.tricontour(tri, z, levels=inside, colors="k",
                             linewidths=[0.8 if lv == 0 else 1.3 for lv in inside],
                             linestyles=["dotted" if lv == 0 else "solid" for lv in inside])
    except (ValueError, RuntimeError):   # collinear points: no triangulation, markers only
        return None


def level_paths(points: Sequence[dict[str, Any]], levels: Sequence[float] = (*LEVELS, 0.0),
                field: str = "peak_rel_error") -> dict[float, list[Any]]:
    """The contour lines that :func:`contour` draws, per level: vertex arrays in (log x, log y).

    ``field`` names the points' value (the signed ``peak_rel_error`` by default).
    """
    import numpy as np

    from ..verify.plots import new_figure

    _, axes = new_figure()
    ok = [p for p in points if finite(p.get(field))]
    x = np.log10([p[X] for p in ok])
    y = np.log10([p["b_over_R1"] for p in ok])
    z = np.array([p[field] for p in ok], dtype=float)
    cs = _lines(axes[0, 0], x, y, z, levels) if len(ok) >= 3 else None
    out: dict[float, list[Any]] = {lv: [] for lv in levels}
    if cs is not None:
        for lv, segs in zip(cs.levels, cs.allsegs):
            out[float(lv)] = [np.asarray(s) for s in segs if len(s)]
    return out


def _boundary_curves(ax: Any, boundaries: Sequence[dict[str, Any]], ys: Sequence[float]) -> bool:
    """Draw each level's located boundary over ``b/R1`` with its FEM band shaded; True if any."""
    import numpy as np

    colours = {-0.05: "navy", -0.01: "tab:blue", 0.01: "tab:red", 0.05: "darkred"}
    drawn = False
    for level in LEVELS:
        rows = sorted((r for r in boundaries if r["level"] == level and r["status"] != "failed"),
                      key=lambda r: (r["b_over_R1"], r[X]))
        if not rows:
            continue
        drawn = True
        colour = colours.get(level, "k")
        # a curve crossed more than once is drawn as markers; runs of adjacent b/R1 as a line
        runs: list[list[dict[str, Any]]] = []
        for r in rows:
            if not r["crossed_once"]:
                ax.plot(np.log10(r[X]), np.log10(r["b_over_R1"]), "D", color=colour, ms=5, zorder=4)
                continue
            k = ys.index(r["b_over_R1"])
            if runs and ys.index(runs[-1][-1]["b_over_R1"]) == k - 1:
                runs[-1].append(r)
            else:
                runs.append([r])
        for i, run in enumerate(runs):
            y = np.log10([r["b_over_R1"] for r in run])
            ax.fill_betweenx(y, np.log10([r["band"][0] for r in run]), np.log10([r["band"][1] for r in run]),
                             color=colour, alpha=0.25, lw=0, zorder=2)
            ax.plot(np.log10([r[X] for r in run]), y, "-D", color=colour, lw=2.0, ms=5, zorder=4,
                    label=f"boundary {level * 100:+g} % (band: FEM estimate)" if i == 0 else None)
            for r in run:   # the band of a single b/R1 as an error bar
                ax.plot(np.log10(r["band"]), [np.log10(r["b_over_R1"])] * 2, color=colour, lw=4,
                        alpha=0.35, zorder=3, solid_capstyle="butt")
    return drawn


def contour(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float, sentence: str,
            path: Path, s_over_lift: float = 0.0, boundaries: Sequence[dict[str, Any]] = ()) -> None:
    """The signed peak-pressure error over ``(a-b)/R1`` and ``b/R1`` (both log scale).

    A diverging colour map centred on zero (red: the closed form over-predicts
    the peak, conservative; blue: it under-predicts it), contour lines of the
    signed field at :data:`LEVELS` and a dotted zero line, every point marked
    with its signed error in %, and the located boundaries with their FEM bands.
    """
    import numpy as np
    from matplotlib.colors import BoundaryNorm

    from ..verify.plots import new_figure, save

    fig, axes = new_figure(size=(7.6, 5.6))
    ax = axes[0, 0]
    ok = [p for p in points if finite(p.get("peak_rel_error"))]
    bad = [p for p in points if not finite(p.get("peak_rel_error"))]
    norm = BoundaryNorm(BANDS, 256, extend="both")
    x = np.log10([p[X] for p in ok])
    y = np.log10([p["b_over_R1"] for p in ok])
    z = np.array([p["peak_rel_error"] for p in ok], dtype=float)
    filled = None
    if len(ok) >= 3:
        try:
            from matplotlib.tri import Triangulation

            filled = ax.tricontourf(Triangulation(x, y), z, levels=BANDS, cmap=CMAP, norm=norm,
                                    extend="both")
        except (ValueError, RuntimeError):   # collinear points: no triangulation, markers only
            filled = None
        cs = _lines(ax, x, y, z, (*LEVELS, 0.0))
        if cs is not None:
            ax.clabel(cs, fmt={lv: ("0" if lv == 0 else f"{100 * lv:+g} %") for lv in cs.levels},
                      fontsize=8)
    dots = ax.scatter(x, y, c=z, cmap=CMAP, norm=norm, edgecolors="k", s=28, zorder=5)
    for xi, yi, zi in zip(x, y, z):
        ax.annotate(f"{100 * zi:+.2g}", (xi, yi), textcoords="offset points", xytext=(4, 4),
                    fontsize=7, zorder=6)
    if bad:
        ax.scatter(np.log10([p[X] for p in bad]), np.log10([p["b_over_R1"] for p in bad]),
                   marker="x", color="k", s=40, zorder=5)
    _load_lines(ax, points)
    ys = sorted({p["b_over_R1"] for p in points})
    if _boundary_curves(ax, boundaries, ys):
        ax.legend(fontsize=7, loc="best", framealpha=0.85)
    cb = fig.colorbar(filled if filled is not None else dots, ax=ax)
    cb.set_label("closed form − finite body, over its peak (+: conservative)")
    cb.ax.yaxis.set_major_formatter(lambda v, _pos: f"{100 * v:+g} %")
    xs = sorted({p[X] for p in points})
    for ticks, setter, lim in ((np.log10(xs), ax.set_xticks, ax.set_xlim),
                               (np.log10(ys), ax.set_yticks, ax.set_ylim)):
        setter(ticks, [f"{10 ** v:.3g}" for v in ticks])
        pad = 0.05 * (ticks[-1] - ticks[0]) or 0.1   # the edge points' markers stay whole
        lim(ticks[0] - pad, ticks[-1] + pad)
    ax.set_xlabel("(a − b)/R1, the larger overhang of the contact onto an edge arc (log scale)")
    ax.set_ylabel("b/R1, half-width of the flat centre (log scale)")
    lever = "s = 0" if s_over_lift == 0 else f"s = {s_over_lift:g} s_lift-off"
    ax.set_title(f"Signed peak-pressure error of the closed form, R2/R1 = {R2_over_R1:g}, "
                 f"H/b = {H_over_b:g}, {lever}\nlines at "
                 f"{', '.join(f'{100 * lv:+g}' for lv in LEVELS)} % and 0 (dotted); dots: the "
                 f"points, signed error in %{'; ×: failed' if bad else ''}; grey: load p0/E*",
                 fontsize=9)
    ax.grid(True, color="0.85", lw=0.5)
    fig.supxlabel(textwrap.fill(sentence, 120), fontsize=7)
    save(fig, path)


def _load_lines(ax: Any, points: Sequence[dict[str, Any]]) -> None:
    """Thin grey iso-lines of the load level ``p0/E*`` at :data:`LOAD_LINES`, labelled."""
    import numpy as np
    from matplotlib.tri import Triangulation

    ok = [p for p in points if finite(p.get("load_level")) and p["load_level"] > 0]
    if len(ok) < 3:
        return
    z = np.log10([p["load_level"] for p in ok])
    inside = [lv for lv in LOAD_LINES if z.min() < np.log10(lv) < z.max()]
    if not inside:
        return
    try:
        cs = ax.tricontour(Triangulation(np.log10([p[X] for p in ok]),
                                         np.log10([p["b_over_R1"] for p in ok])),
                           z, levels=np.log10(inside), colors="0.45", linewidths=0.6, zorder=3)
    except (ValueError, RuntimeError):   # collinear points: no triangulation, no lines
        return
    ax.clabel(cs, fmt=lambda v: f"p0/E* = {10 ** v:.3g}", fontsize=6, colors="0.35")


def stick_sentence(points: Sequence[dict[str, Any]]) -> str:
    """What the partial-slip plot of one group means for a designer, from its points.

    ``d_rel_error > 0``: the closed form's stick zone is wider than the finite
    body's, so its slip zones (where fretting cracks start, at their inner end,
    the stick-slip boundary) are narrower: it under-predicts the slipping region
    and places that boundary too far out, which is NOT conservative for where
    cracks start. ``d_rel_error < 0`` is the other way round, conservative.
    """
    d = [p["d_rel_error"] for p in points if finite(p.get("d_rel_error"))]
    e = [p["e_rel_error"] for p in points if finite(p.get("e_rel_error"))]
    u = max((p["slip_fem_error_estimate"] for p in points if finite(p.get("slip_fem_error_estimate"))),
            default=None)
    if not d:
        return "No partial-slip point of this group has a result."
    lo, hi = min(d), max(d)
    if lo > 0:
        sign = ("the closed form's stick zone is WIDER than the finite body's at every point, so it "
                "under-predicts the slip zones and places the stick-slip boundary (where fretting "
                "cracks start) too far out: not conservative for the slip zones' extent")
    elif hi < 0:
        sign = ("the closed form's stick zone is NARROWER than the finite body's at every point, so "
                "it over-predicts the slip zones: conservative for the slip zones' extent")
    else:
        sign = ("the sign changes over the points (+: the closed form's stick zone is wider, its slip "
                "zones narrower, not conservative; −: the other way round, conservative)")
    blur = ("" if u is None else f"; the FEM's own estimate is up to {pct(u)}"
            + (", as large as the errors themselves" if u >= max(abs(lo), abs(hi)) else ""))
    per_b = []
    for b in sorted({p["b_over_R1"] for p in points if "b_over_R1" in p}):
        db = [p["d_rel_error"] for p in points if p.get("b_over_R1") == b and finite(p.get("d_rel_error"))]
        if db:
            per_b.append(f"{100 * min(db):+.2g} % to {100 * max(db):+.2g} % at b/R1 = {b:g}")
    where = f" ({'; '.join(per_b)})" if per_b else ""
    return (f"Partial slip at Q/fP = 0.4: the closed form's stick-zone half-width d is off by "
            f"{100 * lo:+.2g} % to {100 * hi:+.2g} % of the finite body's{where}, its offset e by "
            f"{100 * min(e):+.2g} % to {100 * max(e):+.2g} % of d; {sign}{blur}.")


def stick_zone(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float, sentence: str,
               path: Path, s_over_lift: float = 0.0) -> None:
    """The stick zone's signed errors ``d_rel_error`` and ``e_rel_error`` against ``(a-b)/R1``.

    One line per ``b/R1``, a zero line, the FEM's own estimate as error bars.
    """
    from ..verify.plots import new_figure, save

    fig, axes = new_figure(ncols=2, size=(5.4, 4.8))
    for ax, field, what in ((axes[0, 0], "d_rel_error", "d: (d_cf − d_fe)/|d_fe|"),
                            (axes[0, 1], "e_rel_error", "e: (e_cf − e_fe)/|d_fe|")):
        for b in sorted({p["b_over_R1"] for p in points}):
            line = sorted((p for p in points if p["b_over_R1"] == b and finite(p.get(field))),
                          key=lambda p: p[X])
            if not line:
                continue
            ax.errorbar([p[X] for p in line], [100 * p[field] for p in line],
                        yerr=[100 * (p.get("slip_fem_error_estimate") or 0.0) for p in line],
                        marker="o", ms=4, capsize=3, label=f"b/R1 = {b:g}")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel("(a − b)/R1 (log scale)")
        ax.set_ylabel(f"closed form − finite body, % ({what})")
        ax.grid(True, color="0.85", lw=0.5)
        ax.legend(fontsize=7)
    lever = "s = 0" if s_over_lift == 0 else f"s = {s_over_lift:g} s_lift-off"
    fig.suptitle(f"Stick zone at Q/fP = 0.4: closed form against the finite body, R2/R1 = "
                 f"{R2_over_R1:g}, H/b = {H_over_b:g}, {lever}\n+: the closed form's stick zone is "
                 f"wider (its slip zones narrower); bars: the FEM's own estimate", fontsize=9)
    fig.supxlabel(textwrap.fill(sentence, 140), fontsize=7)
    save(fig, path)


def slope_plot(points: Sequence[dict[str, Any]], section: dict[str, Any], path: Path) -> None:
    """The small-slope cost of the peak ``|slope_peak_rel_error|`` against ``p0/E*`` (log-log).

    One line per curve ``(R2/R1, b/R1, H/b)`` of the points, the level of
    ``section`` (1 %) as a line, and each curve's located crossing as a star.
    """
    from ..verify.plots import new_figure, save

    fig, axes = new_figure(size=(7.2, 5.0))
    ax = axes[0, 0]
    curves = sorted({(p["R2_over_R1"], p["b_over_R1"], p["H_over_b"]) for p in points})
    for r, b, h in curves:
        line = sorted((p for p in points if (p["R2_over_R1"], p["b_over_R1"], p["H_over_b"]) == (r, b, h)
                       and finite(p.get("slope_peak_rel_error")) and finite(p.get("load_level"))),
                      key=lambda p: p["load_level"])
        if not line:
            continue
        got = ax.plot([p["load_level"] for p in line],
                      [max(abs(p["slope_peak_rel_error"]), 1e-7) for p in line], "-o", ms=4,
                      label=f"R2/R1 = {r:g}, b/R1 = {b:g}, H/b = {h:g}")
        for c in section["curves"]:
            if (c["R2_over_R1"], c["b_over_R1"], c["H_over_b"]) == (r, b, h) and finite(c["load_level"]):
                ax.plot(c["load_level"], section["level"], "*", ms=12, color=got[0].get_color(),
                        zorder=5)
    ax.axhline(section["level"], color="k", lw=1.0, ls="--",
               label=f"{100 * section['level']:g} % (stars: located crossings)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("load level p0/E* of the closed form")
    ax.set_ylabel("|small slope − first order| / first order, larger peak")
    ax.set_title("What the small-slope kinematics cost the peak pressure (finite body)", fontsize=9)
    ax.grid(True, which="both", color="0.9", lw=0.5)
    ax.legend(fontsize=7)
    save(fig, path)

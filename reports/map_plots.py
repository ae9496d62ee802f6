"""The designer's reading of a validity map and its contour plots.

Names
-----
LEVELS            -- the error levels drawn as contour lines; the first is the designer's limit
BANDS             -- the filled bands of the contour maps
below_level       -- per ``b/R1``, the largest ``(a-b)/R1`` up to which the error stays below a level
designer_sentence -- the sentence that says what one contour map means for a designer
contour           -- draw one contour map
"""
from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any, Sequence

from .map_schema import finite, pct

__all__ = ["LEVELS", "BANDS", "below_level", "designer_sentence", "contour"]

#: the error levels drawn as contour lines (1 %, 5 %, 10 %); the first is the designer's limit
LEVELS = (0.01, 0.05, 0.10)
#: the filled bands of the contour maps (fractions of the peak pressure)
BANDS = (0.0, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5)


def below_level(points: Sequence[dict[str, Any]], level: float = LEVELS[0]) -> list[dict[str, Any]]:
    """Per ``b/R1``, how far in ``(a-b)/R1`` the peak-pressure error stays below ``level``.

    Parameters
    ----------
    points
        Map points (dicts with ``b_over_R1``, ``a_minus_b_over_R1`` and
        ``peak_rel_error``, None where the point failed) of one ``R2/R1`` and ``H/b``.
    level
        The error level, a fraction of the peak pressure.

    Returns
    -------
    list of dict
        One per ``b/R1``, ascending: ``b_over_R1``; ``limit``, the largest
        ``(a-b)/R1`` such that every point up to it is below ``level`` (None
        if the first is not); ``swept``, the largest ``(a-b)/R1`` swept;
        ``stop``, why the scan stopped: ``"level"`` (the next point reaches
        it), ``"failed"`` (the next point has no result) or ``"end"``; and
        ``first`` and ``first_error``, the smallest ``(a-b)/R1`` and its error.
    """
    rows = []
    for b in sorted({p["b_over_R1"] for p in points}):
        line = sorted((p for p in points if p["b_over_R1"] == b), key=lambda p: p["a_minus_b_over_R1"])
        limit: float | None = None
        stop = "end"
        for p in line:
            e = p.get("peak_rel_error")
            if e is None or not finite(e):
                stop = "failed"
                break
            if e >= level:
                stop = "level"
                break
            limit = p["a_minus_b_over_R1"]
        rows.append({"b_over_R1": b, "limit": limit, "swept": line[-1]["a_minus_b_over_R1"],
                     "stop": stop, "first": line[0]["a_minus_b_over_R1"],
                     "first_error": line[0].get("peak_rel_error")})
    return rows


def designer_sentence(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float,
                      level: float = LEVELS[0]) -> str:
    """What the contour map of ``points`` (one ``R2/R1`` and ``H/b``) means for a designer, in one sentence."""
    rows = below_level(points, level)
    estimates = [p["fem_error_estimate"] for p in points if finite(p.get("fem_error_estimate"))]
    caveat = ""
    if estimates and max(estimates) > level / 3:
        caveat = (f" (the FEM's own error estimate reaches {pct(max(estimates))} here: differences "
                  "smaller than that are not resolved)")
    head = f"For R2/R1 = {R2_over_R1:g} and H/b = {H_over_b:g}, the closed form's peak pressure"
    if rows and all(r["limit"] is None and r["stop"] == "level" for r in rows):
        first = [r["first_error"] for r in rows]
        lightest = ", ".join(f"{v:g}" for v in sorted({r["first"] for r in rows}))
        return (f"{head} is off by {pct(min(first))} to {pct(max(first))} already at the lightest "
                f"load swept, (a−b)/R1 = {lightest}, for every b/R1: over "
                f"this whole range, design with a finite-body model{caveat}.")
    parts = []
    for row in rows:
        at = f"at b/R1 = {row['b_over_R1']:g}"
        if row["limit"] is None and row["stop"] == "failed":
            parts.append(f"unknown {at} (its first point failed)")
        elif row["limit"] is None:
            parts.append(f"at no load swept {at} ({pct(row['first_error'])} already at "
                         f"(a−b)/R1 = {row['first']:g})")
        elif row["stop"] == "end":
            parts.append(f"over the whole sweep, (a−b)/R1 ≤ {row['swept']:g}, {at}")
        else:
            why = " (the next point failed)" if row["stop"] == "failed" else ""
            parts.append(f"up to (a−b)/R1 = {row['limit']:g} {at}{why}")
    return (f"{head} is within {pct(level)} of the finite body's {'; '.join(parts)}; "
            f"at larger (a−b)/R1, that is heavier loads, design with a finite-body model{caveat}.")


def contour(points: Sequence[dict[str, Any]], R2_over_R1: float, H_over_b: float, sentence: str,
             path: Path) -> None:
    """The peak-pressure error over ``(a-b)/R1`` and ``b/R1`` (both log scale), 1/5/10 % lines."""
    import numpy as np
    from matplotlib.colors import BoundaryNorm
    from matplotlib.tri import Triangulation

    from .plots import new_figure, save

    fig, axes = new_figure(size=(7.0, 5.2))
    ax = axes[0, 0]
    ok = [p for p in points if finite(p.get("peak_rel_error"))]
    bad = [p for p in points if not finite(p.get("peak_rel_error"))]
    norm = BoundaryNorm(BANDS, 256, extend="max")
    cmap = "viridis"
    x = np.log10([p["a_minus_b_over_R1"] for p in ok])
    y = np.log10([p["b_over_R1"] for p in ok])
    z = np.array([p["peak_rel_error"] for p in ok], dtype=float)
    filled = None
    if len(ok) >= 3:
        try:
            tri = Triangulation(x, y)
            filled = ax.tricontourf(tri, z, levels=BANDS, cmap=cmap, norm=norm, extend="max")
            lines = [lv for lv in LEVELS if z.min() < lv < z.max()]
            if lines:
                cs = ax.tricontour(tri, z, levels=lines, colors="k", linewidths=1.2)
                ax.clabel(cs, fmt={lv: pct(lv) for lv in lines}, fontsize=8)
        except (ValueError, RuntimeError):   # collinear points: no triangulation, markers only
            filled = None
    dots = ax.scatter(x, y, c=z, cmap=cmap, norm=norm, edgecolors="k", s=28, zorder=3)
    for xi, yi, zi in zip(x, y, z):
        ax.annotate(f"{100 * zi:.2g}", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7)
    if bad:
        ax.scatter(np.log10([p["a_minus_b_over_R1"] for p in bad]), np.log10([p["b_over_R1"] for p in bad]),
                   marker="x", color="tab:red", s=40, zorder=3)
    cb = fig.colorbar(filled if filled is not None else dots, ax=ax)
    cb.set_label("closed form's peak-pressure error vs finite body")
    cb.ax.yaxis.set_major_formatter(lambda v, _pos: pct(v))
    xs = sorted({p["a_minus_b_over_R1"] for p in points})
    ys = sorted({p["b_over_R1"] for p in points})
    for ticks, setter, lim in ((np.log10(xs), ax.set_xticks, ax.set_xlim),
                               (np.log10(ys), ax.set_yticks, ax.set_ylim)):
        setter(ticks, [f"{10 ** v:.3g}" for v in ticks])
        pad = 0.05 * (ticks[-1] - ticks[0]) or 0.1   # the edge points' markers stay whole
        lim(ticks[0] - pad, ticks[-1] + pad)
    ax.set_xlabel("(a − b)/R1, overhang of the contact onto the edge arc (log scale)")
    ax.set_ylabel("b/R1, half-width of the flat centre (log scale)")
    ax.set_title(f"Peak-pressure error of the closed form, R2/R1 = {R2_over_R1:g}, H/b = {H_over_b:g}\n"
                 f"lines at {', '.join(pct(lv) for lv in LEVELS)}; dots: the points, with their "
                 f"error in %{'; ×: failed points' if bad else ''}", fontsize=10)
    ax.grid(True, color="0.85", lw=0.5)
    fig.supxlabel(textwrap.fill(sentence, 110), fontsize=7.5)
    save(fig, path)

"""PNG plots of the verification report (matplotlib, Agg canvas, no pyplot state).

Each function takes numbers or results, draws one figure and writes it to
``path``; nothing here solves anything. Pressures are normalised by the
closed-form peak, positions by the closed-form contact width.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from threepart.convergence import ROUND_OFF, is_monotone

from .compare import field_errors, is_slip, normal_of
from .studies import Study

__all__ = ["new_figure", "save", "overlay", "error_curves", "sie_convergence", "fem_convergence",
           "step_convergence", "fretting", "STYLE"]

#: how each method is drawn
STYLE = {
    "closedform": dict(color="k", lw=1.6, ls="-", label="closed form"),
    "sie": dict(color="tab:red", marker="o", ms=3.5, ls="none", mfc="none", label="SIE"),
    "fem": dict(color="tab:blue", lw=1.2, ls="--", label="FEM"),
}


def new_figure(ncols: int = 1, nrows: int = 1, size: tuple[float, float] = (6.4, 4.0)) -> tuple[Figure, Any]:
    """A figure with an Agg canvas and its axes (no global pyplot state)."""
    fig = Figure(figsize=(size[0] * ncols, size[1] * nrows), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def save(fig: Figure, path: str | Path, dpi: int = 110) -> Path:
    """Write ``fig`` as PNG to ``path`` (parents created)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi, format="png")
    return path


def _grid(res: Any, n: int = 801) -> np.ndarray:
    return np.linspace(-res.a, res.c, n)


#: how the plots name a reference method
REFERENCE_NAME = {"closedform": "closed form", "sie": "SIE"}


def overlay(results: dict[str, Any], title: str, path: str | Path,
            reference: str = "closedform") -> Path:
    """Pressure (and, for partial slip, shear) of every method on one plot, scaled by the reference."""
    ref = results.get(reference) or next(iter(results.values()))
    name = REFERENCE_NAME.get(reference, reference)
    nref = normal_of(ref)
    W = nref.a + nref.c
    slip = is_slip(ref)
    fig, axes = new_figure(2 if slip else 1)
    ax = axes[0, 0]
    x = np.linspace(-1.05 * nref.a, 1.05 * nref.c, 1201)
    pscale = max(p.p for p in nref.peaks())
    for method, res in results.items():
        st = dict(STYLE.get(method, {"label": method}))
        xx = x
        if method == "sie":   # markers: few enough to see the other curves beneath
            xx = np.linspace(-nref.a, nref.c, 41)
        ax.plot(xx / W, normal_of(res).pressure(xx) / pscale, **st)
    b = nref.punch.b
    if b > 0:
        for xb in (-b, b):
            ax.axvline(xb / W, color="0.7", lw=0.8, ls=":")
    ax.set_xlabel("x / W  (W = a + c)")
    ax.set_ylabel(f"p / p_max ({name})")
    ax.set_title(f"{title}: pressure")
    ax.legend(loc="best", fontsize=8)
    if slip:
        ax = axes[0, 1]
        qscale = float(np.max(np.abs(ref.shear(x))))
        for method, res in results.items():
            if not is_slip(res):
                continue
            st = dict(STYLE.get(method, {"label": method}))
            xx = x if method != "sie" else np.linspace(-nref.a, nref.c, 41)
            ax.plot(xx / W, res.shear(xx) / qscale, **st)
        lo, hi = ref.stick_zone
        ax.axvspan(lo / W, hi / W, color="tab:green", alpha=0.1, label=f"stick zone ({name})")
        ax.set_xlabel("x / W  (W = a + c)")
        ax.set_ylabel(f"q / max|q| ({name})")
        ax.set_title(f"{title}: shear, Q/fP = {ref.Q / (ref.f * ref.P):.2g}")
        ax.legend(loc="best", fontsize=8)
    return save(fig, path)


def error_curves(results: dict[str, Any], title: str, path: str | Path,
                 reference: str = "closedform") -> Path:
    """|p_method - p_reference| / p_max against x / W (log scale), and the same for shear."""
    ref = results[reference]
    name = REFERENCE_NAME.get(reference, reference)
    nref = normal_of(ref)
    W = nref.a + nref.c
    slip = is_slip(ref) and any(is_slip(r) for m, r in results.items() if m != reference)
    fig, axes = new_figure(2 if slip else 1)
    fields = [("pressure", axes[0, 0])] + ([("shear", axes[0, 1])] if slip else [])
    for field, ax in fields:
        for method, res in results.items():
            if method == reference:
                continue
            if field == "pressure":
                fe = field_errors(nref, normal_of(res), "pressure")
            elif is_slip(res):
                fe = field_errors(ref, res, "shear")
            else:
                continue
            err = np.abs(fe.error)
            err = np.where(err > 0, err, np.nan)
            color = STYLE.get(method, {}).get("color")
            ax.semilogy(fe.x / W, err, color=color, lw=1.0, label=f"{method}")
        ax.axvspan(-nref.a / W, (-nref.a + 0.05 * W) / W, color="0.9")
        ax.axvspan((nref.c - 0.05 * W) / W, nref.c / W, color="0.9",
                   label="within 5 % of W of an end (left out of the interior error)")
        sym = "p" if field == "pressure" else "q"
        ax.set_xlabel("x / W  (W = a + c, the contact width)")
        ax.set_ylabel(f"|Δ{sym}| / max|{sym}|  ({field} error, fraction of its peak)")
        ax.set_title(f"{title}: {field} error against the {name}")
        ax.legend(loc="best", fontsize=8)
    return save(fig, path)


def _reference_slopes(ax: Any, x: np.ndarray, st: Study, inverse: bool) -> None:
    """Dashed first- and second-order lines through the largest first-level error."""
    first = [st.errors[q][0] for q in st.quantities if st.errors[q] and st.errors[q][0] > ROUND_OFF]
    if len(x) < 2 or not first:
        return
    e0 = max(first)
    for order, style in ((1, ":"), (2, "--")):
        ratio = (x[0] / x) if inverse else (x / x[0])   # n grows (SIE), h shrinks (FEM)
        ax.loglog(x, e0 * ratio**order, color="0.45", ls=style, lw=0.9,
                  label=f"reference slope: order {order}")


def _study_axes(st: Study, ax: Any, xlabel: str, inverse: bool) -> None:
    x = np.asarray(st.values, dtype=float)
    for q in st.quantities:
        e = np.asarray(st.errors[q], dtype=float)
        e = np.where(e > 0, e, np.nan)
        p = st.orders.get(q, math.nan)
        if math.isfinite(p):
            lab = f"{q}: order {p:.2f}"
        elif is_monotone(e) or not np.any(e > ROUND_OFF):
            lab = f"{q}: at round-off"
        else:
            lab = f"{q}: not monotone, no order"
        g = st.gci.get(q)
        if g is not None and math.isfinite(g):
            lab += f", GCI {g:.1e}"
        ax.loglog(x, e, marker="o", ms=3.5, lw=1.0, label=lab)
    _reference_slopes(ax, x, st, inverse)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("normalised error vs closed form")
    ax.grid(True, which="both", color="0.9", lw=0.6)
    ax.legend(loc="best", fontsize=7)
    if not inverse:
        ax.invert_xaxis()


def sie_convergence(st: Study, path: str | Path) -> Path:
    """SIE errors against n (log-log), with fitted orders in the legend."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], "n (Gauss–Chebyshev nodes)", inverse=True)
    axes[0, 0].set_title(f"SIE ({st.scheme}) convergence in n, case {st.case}")
    return save(fig, path)


def fem_convergence(st: Study, path: str | Path) -> Path:
    """FEM errors against h (log-log, h decreasing to the right), orders and GCI in the legend."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], "h at the contact (mm), refining →", inverse=False)
    axes[0, 0].set_title(f"FEM convergence in h, case {st.case}"
                         + (" (two bodies, Coulomb friction)" if "d" in st.quantities else ""))
    return save(fig, path)


def step_convergence(st: Study, path: str | Path) -> Path:
    """FE fretting energy error against the load step (log-log, step shrinking to the right)."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], "load step ΔQ (N/mm), refining →", inverse=False)
    axes[0, 0].set_title(f"FEM fretting cycle: energy in the load step, case {st.case}")
    return save(fig, path)


#: the states of a fretting cycle drawn by :func:`fretting`: (Q / Q_max, branch, label)
CYCLE_STATES = ((1.0, "loading", "Q = Q_max"), (0.0, "unloading", "Q = 0 after reversal"),
                (-1.0, "unloading", "Q = -Q_max"))


def fretting(results: dict[str, Any], title: str, path: str | Path,
             reference: str = "closedform") -> Path:
    """A fretting cycle by every method: the hysteresis loop, and the shear at three states.

    The loop is ``delta`` less the line through its tips (:meth:`FrettingResult.loop`),
    whose area is the energy per cycle; shears are scaled by ``f p_max`` of the reference.
    """
    ref = results.get(reference) or next(iter(results.values()))
    fig, axes = new_figure(2, 2)
    ax = axes[0, 0]
    for m, res in results.items():
        Q, h = res.loop()
        style = {k: v for k, v in STYLE[m].items() if k != "label"}
        ax.plot(Q / ref.Q_max, h, **style,
                label=f"{STYLE[m]['label']}: {res.energy:.5g} per cycle")
    ax.set_xlabel("Q / Q_max")
    ax.set_ylabel("tangential displacement less its elastic line (mm)")
    ax.set_title(f"{title}: hysteresis loop (area = energy per cycle)")
    ax.grid(True, color="0.9", lw=0.6)
    ax.legend(loc="upper left", fontsize=8)
    n = ref.normal
    x = np.linspace(-n.a, n.c, 801)
    scale = ref.f * max(p.p for p in n.peaks())
    for ax, (frac, branch, label) in zip((axes[0, 1], axes[1, 0], axes[1, 1]), CYCLE_STATES):
        for m, res in results.items():
            style = dict(STYLE[m])
            xm = x[::16] if m == "sie" else x
            ax.plot(xm / n.width, res.shear(xm, frac * res.Q_max, branch) / scale, **style)
        ax.set_xlabel("x / W")
        ax.set_ylabel("q / (f p_max)")
        ax.set_title(f"shear at {label} ({branch})")
        ax.grid(True, color="0.9", lw=0.6)
        ax.legend(loc="lower center", fontsize=8)
    return save(fig, path)

"""PNG plots of the verification report (matplotlib, Agg canvas, no pyplot state).

Each function takes numbers or results, draws one figure and writes it to
``path``; nothing here solves anything. A case with a material is drawn in
its units (:data:`threepart.problem.units.UNITS`: x in mm, p in MPa); a nondimensional
one as p over the reference's peak against x over its contact width. Every
title names the case, the methods and the reference; every axis its unit.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Mapping

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from threepart import registry
from threepart.registry import REFERENCE, Method
from threepart.problem.units import UNITS
from threepart.convergence import ROUND_OFF

from ..compare import EDGE_FRACTION, field_errors, is_slip, normal_of
from .sections import ENERGY_UNIT, method_name, order_text
from .studies import Study

if TYPE_CHECKING:
    from .stress import StressFields

__all__ = ["new_figure", "save", "fix_layout", "overlay", "error_curves", "stress_surface", "von_mises", "sie_convergence",
           "fem_convergence", "step_convergence", "fretting", "steady", "style", "friction_stick"]


def _method(method: str) -> Method | None:
    try:
        return registry.get(method)
    except ValueError:
        return None


def style(method: str) -> dict[str, Any]:
    """How ``method`` is drawn: its registry style, labelled with its name (:class:`threepart.registry.Method`)."""
    m = _method(method)
    return m.plot_style() if m is not None else {"label": method}


def _sparse(method: str) -> bool:
    """True for a method drawn as markers alone: sampled at :data:`N_MARKERS` points."""
    m = _method(method)
    return m is not None and m.markers


#: the plots' resolution: a one-panel plot (6.4 in) is 576 px wide, half the report's page,
#: a two-panel one 1152 px, the whole page, so that the HTML shows both at their own size
#: (7-point text 8.75 px high); at 110 dpi the report's HTML was 5.7 MB
DPI = 90


def new_figure(ncols: int = 1, nrows: int = 1, size: tuple[float, float] = (6.4, 4.0)) -> tuple[Figure, Any]:
    """A figure with an Agg canvas and its axes (no global pyplot state), at :data:`DPI`.

    Its constrained layout is computed once, by :func:`save`.
    """
    fig = Figure(figsize=(size[0] * ncols, size[1] * nrows), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes
#: colours of the PNG's palette: the plots' lines, fills and antialiasing fit in 256, and a
#: palette PNG is about 0.4 x the size of matplotlib's RGBA one
PALETTE = 256


def fix_layout(fig: Figure, dpi: float = DPI) -> None:
    """Run ``fig``'s layout engine once at ``dpi`` and keep the positions it gives.

    ``savefig`` with a layout engine draws the figure twice (once, unrendered, for the
    layout, then for the file) and runs the constrained layout each time; with the
    positions fixed it draws once. The layout is the same: the engine's own, at the
    saving resolution.
    """
    engine = fig.get_layout_engine()
    if engine is None or not fig.axes:
        return
    fig.set_dpi(dpi)
    engine.execute(fig)
    fig.set_layout_engine(None)    # no engine: savefig draws once, at these positions


def save(fig: Figure, path: str | Path, dpi: int = DPI) -> Path:
    """Write ``fig`` as a palette PNG (:data:`PALETTE` colours) to ``path`` (parents created).

    The layout is computed once (:func:`fix_layout`).
    """
    from io import BytesIO

    from PIL import Image

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fix_layout(fig, dpi)
    buf = BytesIO()
    fig.savefig(buf, dpi=dpi, format="png", facecolor="white")
    buf.seek(0)
    with Image.open(buf) as im:
        im.convert("RGB").quantize(PALETTE, method=Image.Quantize.MEDIANCUT).save(
            path, format="PNG", optimize=True)
    return path


#: markers of a method drawn as markers (the SIE) along its contact
N_MARKERS = 41


def _axis(nref: Any, physical: bool) -> tuple[float, str]:
    """Scale and label of the x axis: mm for a case with a material, else x / W."""
    if physical:
        return 1.0, f"x ({UNITS['x']})"
    return nref.width, "x / W  (W = a + c, the contact width; nondimensional)"


def _joins(ax: Any, b: float, xscale: float) -> None:
    """The joins x = ±b of the flat or curved centre and the edge radii, in the legend."""
    if b > 0:
        for i, xb in enumerate((-b, b)):
            ax.axvline(xb / xscale, color="0.6", lw=0.9, ls=":",
                       label="joins x = ±b (centre to edge radii)" if i == 0 else None)


def _field(res: Any, method: str, field: str) -> tuple[np.ndarray, np.ndarray]:
    """``field`` of one result over its own contact ``[-a, c]``, drawn to its ends where it is 0.

    Lines sample the whole contact and add the end points with zero traction;
    the SIE, drawn as markers, is sampled at :data:`N_MARKERS` points.
    """
    n = normal_of(res)
    f = n.pressure if field == "pressure" else res.shear
    if _sparse(method):
        x = np.linspace(-n.a, n.c, N_MARKERS)
        return x, np.asarray(f(x), dtype=float)
    x = np.linspace(-n.a, n.c, 1201)[1:-1]
    return (np.concatenate(([-n.a], x, [n.c])),
            np.concatenate(([0.0], np.asarray(f(x), dtype=float), [0.0])))


def _methods(methods: Iterable[str]) -> str:
    return " vs ".join(method_name(m) for m in methods)


def overlay(results: dict[str, Any], title: str, path: str | Path,
            reference: str = REFERENCE, physical: bool = False) -> Path:
    """Pressure (and, for partial slip, shear) of every method on one plot.

    A case with a material (``physical``) is drawn in its units, p in MPa
    against x in mm, with p over the reference's peak on the right axis; a
    nondimensional one as p / p_max against x / W. Every curve runs over its
    own contact to the ends, where the traction is zero.
    """
    ref = results.get(reference) or next(iter(results.values()))
    name = method_name(reference)
    nref = normal_of(ref)
    xscale, xlabel = _axis(nref, physical)
    slip = is_slip(ref)
    fig, axes = new_figure(2 if slip else 1)
    ax = axes[0, 0]
    pmax = max(p.p for p in nref.peaks())
    pscale = 1.0 if physical else pmax
    for method, res in results.items():
        x, p = _field(res, method, "pressure")
        ax.plot(x / xscale, p / pscale, **style(method))
    _joins(ax, nref.punch.b, xscale)
    ax.axhline(0.0, color="0.85", lw=0.8)
    ax.set_xlabel(xlabel)
    if physical:
        ax.set_ylabel(f"contact pressure p ({UNITS['p']})")
        right = ax.secondary_yaxis("right", functions=(lambda p: p / pmax, lambda r: r * pmax))
        right.set_ylabel(f"p / p_max  (peak of the {name})")
    else:
        ax.set_ylabel(f"p / p_max  (peak of the {name})")
    ax.set_title(f"{title}: contact pressure, {_methods(results)}\n"
                 f"(reference: the {name})", fontsize=10)
    ax.legend(loc="best", fontsize=7)
    if slip:
        ax = axes[0, 1]
        qmax = float(np.max(np.abs(ref.shear(np.linspace(-nref.a, nref.c, 2001)))))
        qscale = 1.0 if physical else qmax
        for method, res in results.items():
            if not is_slip(res):
                continue
            x, q = _field(res, method, "shear")
            ax.plot(x / xscale, q / qscale, **style(method))
        lo, hi = ref.stick_zone
        ax.axvspan(lo / xscale, hi / xscale, color="tab:green", alpha=0.1,
                   label=f"stick zone ({name})")
        _joins(ax, nref.punch.b, xscale)
        ax.axhline(0.0, color="0.85", lw=0.8)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"shear traction q ({UNITS['q']})" if physical
                      else f"q / max|q|  (of the {name})")
        ax.set_title(f"{title}: shear traction in partial slip, Q/fP = {ref.Q / (ref.f * ref.P):.2g}\n"
                     f"{_methods(r for r in results if is_slip(results[r]))}", fontsize=10)
        ax.legend(loc="best", fontsize=7)
    return save(fig, path)


def error_curves(results: dict[str, Any], title: str, path: str | Path,
                 reference: str = REFERENCE, physical: bool = False) -> Path:
    """|p_method - p_reference| / p_max against x (log scale), and the same for shear."""
    ref = results[reference]
    name = method_name(reference)
    nref = normal_of(ref)
    W = nref.width
    xscale, xlabel = _axis(nref, physical)
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
            color = style(method).get("color")
            ax.semilogy(fe.x / xscale, err, color=color, lw=1.0, label=method_name(method))
        ax.axvspan(-nref.a / xscale, (-nref.a + EDGE_FRACTION * W) / xscale, color="0.9")
        ax.axvspan((nref.c - EDGE_FRACTION * W) / xscale, nref.c / xscale, color="0.9",
                   label=f"within {EDGE_FRACTION:.0%} of W of an end (left out of the interior error)")
        _joins(ax, nref.punch.b, xscale)
        sym = "p" if field == "pressure" else "q"
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"|Δ{sym}| / max|{sym}|  ({field} error, fraction of its peak)")
        ax.set_title(f"{title}: {field} error of each method against the {name}", fontsize=10)
        ax.legend(loc="best", fontsize=7)
    return save(fig, path)


def _reference_slopes(ax: Any, x: np.ndarray, st: Study, inverse: bool) -> None:
    """Dashed first- and second-order lines through the largest first-level error."""
    first = [st.errors[q][0] for q in st.errors if st.errors[q] and st.errors[q][0] > ROUND_OFF]
    if len(x) < 2 or not first:
        return
    e0 = max(first)
    for order, style in ((1, ":"), (2, "--")):
        ratio = (x[0] / x) if inverse else (x / x[0])   # n grows (SIE), h shrinks (FEM)
        ax.loglog(x, e0 * ratio**order, color="0.45", ls=style, lw=0.9,
                  label=f"reference slope: order {order}")


def _study_axes(st: Study, ax: Any, xlabel: str, inverse: bool) -> None:
    """Errors per level; the legend gives an order only for errors that fall at every level."""
    x = np.asarray(st.sizes, dtype=float)
    for q in st.errors:
        e = np.asarray(st.errors[q], dtype=float)
        lab = f"{q}: {order_text(st.errors[q], st.orders.get(q))}"
        g = st.gci.get(q)
        if g is not None and math.isfinite(g):
            lab += f", GCI {g:.1e}"
        ax.loglog(x, np.where(e > 0, e, np.nan), marker="o", ms=3.5, lw=1.0, label=lab)
    _reference_slopes(ax, x, st, inverse)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("error against the closed form\n(normalised as in the tolerance table)")
    ax.grid(True, which="both", color="0.9", lw=0.6)
    ax.legend(loc="best", fontsize=7)
    if not inverse:
        ax.invert_xaxis()


def sie_convergence(st: Study, path: str | Path) -> Path:
    """SIE errors against n (log-log), with fitted orders in the legend."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], "n (Gauss–Chebyshev nodes)", inverse=True)
    axes[0, 0].set_title(f"SIE ({st.scheme}) convergence in n, case {st.case}:\n"
                         "errors of the SIE against the closed form", fontsize=10)
    return save(fig, path)


def fem_convergence(st: Study, path: str | Path) -> Path:
    """FEM errors against h (log-log, h decreasing to the right), orders and GCI in the legend."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], f"element size h at the contact ({UNITS['x']}), refining →",
                inverse=False)
    axes[0, 0].set_title(f"FEM convergence in h, case {st.case}"
                         + (" (two bodies, Coulomb friction)" if "d" in st.quantities else "")
                         + ":\nerrors of the FEM against the closed form", fontsize=10)
    return save(fig, path)


def step_convergence(st: Study, path: str | Path) -> Path:
    """FE fretting energy error against the load step (log-log, step shrinking to the right)."""
    fig, axes = new_figure()
    _study_axes(st, axes[0, 0], f"load step ΔQ ({UNITS['Q']}), refining →", inverse=False)
    axes[0, 0].set_title(f"FEM fretting cycle, case {st.case}: energy per cycle in the load step\n"
                         "relative error of the FEM's energy against the closed form", fontsize=10)
    return save(fig, path)


#: the states of a fretting cycle drawn by :func:`fretting`: (Q / Q_max, branch, label)
CYCLE_STATES = ((1.0, "loading", "Q = Q_max"), (0.0, "unloading", "Q = 0 after reversal"),
                (-1.0, "unloading", "Q = -Q_max"))


def fretting(results: dict[str, Any], title: str, path: str | Path,
             reference: str = REFERENCE, physical: bool = False) -> Path:
    """A fretting cycle by every method: the hysteresis loop, and the shear at three states.

    The loop is ``delta`` less the line through its tips (:meth:`FrettingResult.loop`),
    whose area is the energy per cycle (in N·mm per mm of contact length for a
    case with a material); shears are scaled by ``f p_max`` of the reference.
    """
    ref = results.get(reference) or next(iter(results.values()))
    name = method_name(reference)
    unit = ENERGY_UNIT if physical else "(nondimensional)"
    fig, axes = new_figure(2, 2)
    ax = axes[0, 0]
    for m, res in results.items():
        Q, h = res.loop()
        drawn = {k: v for k, v in style(m).items() if k != "label"}
        ax.plot(Q / ref.Q_max, h, **drawn,
                label=f"{method_name(m)}: {res.energy:.5g} {unit} per cycle")
    ax.set_xlabel("Q / Q_max")
    ax.set_ylabel("tangential displacement δ less its elastic line"
                  + (f" ({UNITS['d']})" if physical else ""))
    ax.set_title(f"{title}: hysteresis loop, {_methods(results)}\n"
                 f"area = energy dissipated per cycle" + (f" ({unit})" if physical else ""),
                 fontsize=10)
    ax.grid(True, color="0.9", lw=0.6)
    ax.legend(loc="upper left", fontsize=7)
    n = ref.normal
    xscale, xlabel = _axis(n, physical)
    x = np.linspace(-n.a, n.c, 801)
    scale = ref.f * max(p.p for p in n.peaks())
    for ax, (frac, branch, label) in zip((axes[0, 1], axes[1, 0], axes[1, 1]), CYCLE_STATES):
        for m, res in results.items():
            xm = x[::16] if _sparse(m) else x
            ax.plot(xm / xscale, res.shear(xm, frac * res.Q_max, branch) / scale, **style(m))
        _joins(ax, n.punch.b, xscale)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"q / (f p_max)  (p_max of the {name})")
        ax.set_title(f"{title}: shear traction at {label} ({branch})", fontsize=10)
        ax.grid(True, color="0.9", lw=0.6)
        ax.legend(loc="lower center", fontsize=7)
    return save(fig, path)


def _stick_lines(ax: Any, res: Any, xscale: float) -> None:
    """The permanent stick zone's ends of ``res`` as dotted vertical lines."""
    for xe in res.stick_zone:
        ax.axvline(xe / xscale, color="0.4", lw=0.8, ls=":")


#: how a method's marched history is drawn over the steady states (its label: the method's, "history")
HISTORY_STYLE = dict(color="tab:green", lw=1.0, ls="-.")


def _steady_shear(shear: Any, x: np.ndarray, k: int | None) -> np.ndarray:
    """``shear(x, k)``, or the range ``shear(x, 1) - shear(x, 0)`` for ``k = None``."""
    if k is None:
        return np.asarray(shear(x, 1), float) - np.asarray(shear(x, 0), float)
    return np.asarray(shear(x, k), float)


def steady(results: dict[str, Any], title: str, path: str | Path,
           reference: str = REFERENCE, physical: bool = False,
           histories: dict[str, Any] | None = None) -> Path:
    """The steady state of a flight cycle by every method with one: the shear range ``q_1 - q_0``
    (eq. S4) and the shear at state 1 (eq. S13), and the slip amplitude (eq. S7) at both contact
    ends, the permanent stick zone dotted.

    Shears are scaled by ``f p_max`` of the reference's wider end state; the slip
    amplitude is drawn over the slip zone at each end, widened threefold. A
    marched history (``histories``, :mod:`reports.verify.flight`) is drawn at the two
    end states of its last cycle, its slip amplitude half its slip's range there.
    """
    from .flight import last_cycle, slip_amplitude

    histories = histories or {}
    ref = results.get(reference) or next(iter(results.values()))
    name = method_name(reference)
    n = max(ref.normals, key=lambda m: float(m.a + m.c))
    xscale, xlabel = _axis(n, physical)
    scale = ref.f * max(p.p for p in n.peaks())
    fig, axes = new_figure(2, 2)
    x = np.linspace(-n.a, n.c, 801)
    for ax, k in zip(axes[0], (None, 1)):
        # k = None: the range q_1 - q_0, which the steady state fixes everywhere (eq. S4); the
        # shear of an end state carries in the stick zone a part locked in by the history (S13)
        for m, res in results.items():
            ax.plot(x / xscale, _steady_shear(res.shear, x, k) / scale, **style(m))
        for m, hist in histories.items():
            cyc = last_cycle(hist)
            at = {0: cyc[-1], 1: cyc[len(cyc) // 2]}
            ax.plot(x / xscale, _steady_shear(lambda t, j: hist.shear(t, at[j]), x, k) / scale,
                    **HISTORY_STYLE, label=f"{method_name(m)} history, cycle {len(hist.cycles)}")
        _stick_lines(ax, ref, xscale)
        _joins(ax, n.punch.b, xscale)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"q / (f p_max)  (p_max of the {name})")
        if k is None:
            ax.set_title(f"{title}: shear range q1 - q0 over the cycle\n(the same for any load history, "
                         "eq. S4)", fontsize=10)
        else:
            P, _, Q, sigma = ref.states[k]
            ax.set_title(f"{title}: shear at state {k} (P = {P:.5g}, Q = {Q:.5g}, σ_bulk = {sigma:.5g})"
                         "\nin the stick zone partly locked in by the load history", fontsize=10)
        ax.grid(True, color="0.9", lw=0.6)
        ax.legend(loc="lower center", fontsize=7)
    lo, hi = max(-float(m.a) for m in ref.normals), min(float(m.c) for m in ref.normals)
    left, right = ref.stick_zone
    unit = f" ({UNITS['d']})" if physical else ""
    for ax, (a, b), side in zip(axes[1], ((lo, left), (right, hi)), ("left", "right")):
        w = max(b - a, 1e-12 * (hi - lo))
        x = np.linspace(a - w, b + w, 401)
        x = x[(x >= lo) & (x <= hi)]
        for m, res in results.items():
            ax.plot(x / xscale, np.asarray(res.slip_amplitude(x)), **style(m))
        for m, hist in histories.items():
            ax.plot(x / xscale, slip_amplitude(hist, x), **HISTORY_STYLE,
                    label=f"{method_name(m)} history, cycle {len(hist.cycles)}")
        ax.axvline((left if side == "left" else right) / xscale, color="0.4", lw=0.8, ls=":")
        ax.set_xlim(x[0] / xscale, x[-1] / xscale)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("slip amplitude δ" + unit)
        ax.set_title(f"{title}: slip amplitude at the {side} end\n(energy per cycle "
                     f"{ref.energy:.4g}" + (f" {ENERGY_UNIT}" if physical else "") + ")", fontsize=10)
        ax.grid(True, color="0.9", lw=0.6)
        ax.legend(loc="upper center", fontsize=7)
    return save(fig, path)


def _stress_scales(results: dict[str, Any], reference: str,
                   physical: bool) -> tuple[Any, str, Any, tuple[float, str], float]:
    """The reference, its name, its normal result, the x axis and the stress scale of a stress plot.

    Stresses are drawn in MPa for a case with a material, else over the
    reference's peak pressure.
    """
    ref = results.get(reference) or next(iter(results.values()))
    nref = normal_of(ref)
    pmax = max(p.p for p in nref.peaks())
    return (ref, method_name(reference), nref, _axis(nref, physical),
            1.0 if physical else pmax)


def stress_surface(results: dict[str, Any], title: str, path: str | Path, *, nu: float,
                   reference: str = REFERENCE, physical: bool = False,
                   fields: Mapping[str, StressFields] | None = None) -> Path:
    """Surface stress ``σxx`` of every method along the contact and beyond its ends.

    In MPa against mm for a case with a material, else over the reference's
    peak pressure against x / W. The trailing edge's tension (x = -a for
    Q > 0) is where fretting cracks start. ``fields``: each method's stresses on
    the surface line, if computed already (:func:`reports.verify.stress.stress_fields`).
    """
    from .stress import surface_line

    ref, name, nref, (xscale, xlabel), sscale = _stress_scales(results, reference, physical)
    fig, axes = new_figure()
    ax = axes[0, 0]
    x = surface_line(ref)
    for method, res in results.items():
        every = max(len(x) // N_MARKERS, 1) if _sparse(method) else 1
        xs = x[::every]
        known = (fields or {}).get(method)
        sxx = (known.surface.sxx[::every] if known is not None
               else res.stress(xs, np.zeros_like(xs), nu=nu).sxx)
        ax.plot(xs / xscale, sxx / sscale, **style(method))
    for i, xe in enumerate((-nref.a, nref.c)):
        ax.axvline(xe / xscale, color="0.3", lw=0.8, ls="-.",
                   label="contact ends x = -a, c" if i == 0 else None)
    bulk = float(getattr(ref, "sigma_bulk", 0.0))
    ax.axhline(bulk / sscale, color="0.7", lw=0.8, label=f"bulk stress {fmt_stress(bulk, physical)}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"surface σxx ({UNITS['p']}, tension positive)" if physical
                  else f"σxx / p_max  (peak pressure of the {name}; tension positive)")
    Qr = f", Q/fP = {ref.Q / (ref.f * ref.P):.2g}" if is_slip(ref) else ""
    ax.set_title(f"{title}: surface stress σxx{Qr}\n"
                 f"{_methods(results)} (reference: the {name})", fontsize=10)
    ax.legend(loc="best", fontsize=7)
    return save(fig, path)


def fmt_stress(value: float, physical: bool) -> str:
    """A stress for a legend: in MPa for a case with a material, else in the case's units."""
    return f"{value:.4g} {UNITS['p']}" if physical else f"{value:.4g}"


def von_mises(results: dict[str, Any], title: str, path: str | Path, *, nu: float,
              reference: str = REFERENCE, physical: bool = False,
              fields: Mapping[str, StressFields] | None = None) -> Path:
    """Von Mises stress under the contact: the reference filled, every other method's contours on top.

    Depth ``z`` points down; the levels are the same for every method, so a
    displaced line is a difference in the field. ``fields``: each method's stresses
    on the field grid, if computed already (:func:`reports.verify.stress.stress_fields`).
    """
    from .stress import field_grid

    ref, name, nref, (xscale, xlabel), sscale = _stress_scales(results, reference, physical)
    x, z = field_grid(ref)
    fields = fields or {}

    def field(method: str, res: Any) -> Any:
        known = fields.get(method)
        return known.field if known is not None else res.stress(x, z, nu=nu)

    vm = field(reference, ref).von_mises / sscale
    levels = np.linspace(0.0, float(vm.max()), 11)[1:]
    fig, axes = new_figure(size=(6.4, 4.4))
    ax = axes[0, 0]
    filled = ax.contourf(x / xscale, z / xscale, vm, levels=np.linspace(0.0, float(vm.max()), 21),
                         cmap="viridis")
    fig.colorbar(filled, ax=ax, label=(f"von Mises ({UNITS['p']}), {name}" if physical
                                       else f"von Mises / p_max, {name}"))
    ax.contour(x / xscale, z / xscale, vm, levels=levels, colors="k", linewidths=0.9)
    handles = [ax.plot([], [], color="k", lw=0.9, label=f"{name} (filled and black lines)")[0]]
    for method, res in results.items():
        if method == reference:
            continue
        other = field(method, res).von_mises / sscale
        m = _method(method)
        colour = m.contour_color if m is not None else "w"
        ax.contour(x / xscale, z / xscale, other, levels=levels, colors=colour, linewidths=1.0,
                   linestyles="--")
        handles.append(ax.plot([], [], color=colour, lw=1.0, ls="--", label=method_name(method))[0])
    ax.plot([-nref.a / xscale, nref.c / xscale], [0, 0], color="w", lw=4, solid_capstyle="butt")
    ax.invert_yaxis()
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"depth z ({UNITS['x']})" if physical else "depth z / W")
    ax.set_title(f"{title}: von Mises stress in the substrate (ν = {nu:g})\n{_methods(results)}, "
                 "the same levels for every method;\nthe white bar is the contact", fontsize=10)
    ax.legend(handles=handles, loc="lower right", fontsize=7)
    return save(fig, path)


def friction_stick(columns: list[dict[str, Any]], target: float, path: str | Path) -> Path:
    """The friction referee columns' stick zone against W/h (log-log): the worst end's error
    (``stick_ends``, of W) per code and problem (:mod:`reports.verify.friction`), the target dashed."""
    fig, axes = new_figure()
    ax = axes[0, 0]
    for col in columns:
        errs = col["errors"]
        if col["status"] != "run" or "stick_ends" not in errs:
            continue
        n = np.asarray([float(v) for v in col["levels"]])
        e = np.asarray([math.nan if v is None else v for v in errs["stick_ends"]], dtype=float)
        ax.loglog(n, np.where(e > 0, e, np.nan), marker="o", ms=4, lw=1.0,
                  label=f"{method_name(col['code'] + '-friction')}, {col['problem']}")
    ax.axhline(target, color="0.3", ls="--", lw=0.9, label=f"issue 38 target {target:g} W")
    ax.set_xlabel("elements across the contact width, W/h")
    ax.set_ylabel("worst stick-zone end's error (of W)")
    ax.set_title("friction referees: the stick zone's ends against the closed form", fontsize=10)
    ax.grid(True, which="both", color="0.9", lw=0.6)
    ax.legend(loc="best", fontsize=7)
    return save(fig, path)

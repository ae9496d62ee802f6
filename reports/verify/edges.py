"""The report's "Edge multipliers" section: K_N, K_T and the slip zone of every case's edges, by method.

:func:`edge_rows` computes the rows from a run's results (each result's
``edges()``, :mod:`threepart.results.edges`, docs/EDGES.md) into ``report.json``'s
``edges``; :func:`edges_section` turns them into the section. K_N of each method
is set against the reference's (the closed form, or the SIE past it); the FEM's
fit error is shown beside its own error, which it must cover; where a result has
a stick zone its exact slip zone stands beside the asymptotic one (E5, E7).
"""
from __future__ import annotations

from typing import Any, Sequence

from threepart import registry
from threepart.results.edges import SIDES, exact_slip

from .sections import Cell, Figure, Section, Status, Table, fmt, head_unit, unit_of, with_unit, words

__all__ = ["edge_rows", "edges_section", "asymptote_study", "draw_asymptote", "ASYMPTOTE_CASES",
           "ASYMPTOTE_RATIOS", "ASYMPTOTE_PLOT"]

#: the cases of the asymptote's study: Hertz (its error is slip/W exactly) and the normal loads of
#: three-part punches, each sheared by the closed form with the catalogue's f = 0.5
ASYMPTOTE_CASES = ("hertz", "caseA_sym", "caseA_moment", "fan_blade_flank")
#: the study's shear loads Q/(fP), from a slip zone of about 1e-5 of the contact to about 0.2
ASYMPTOTE_RATIOS = tuple(float(r) for r in (1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 0.4))
#: the study's friction coefficient
ASYMPTOTE_F = 0.5
#: where the report draws it
ASYMPTOTE_PLOT = "plots/edge_asymptote.png"


def edge_rows(runs: Sequence[Any]) -> list[dict[str, Any]]:
    """One row per case, method and edge: K_N, its error against the reference, fit error, K_T, slip zones.

    A method whose result has no multipliers (no ``edges`` in its registry entry, or
    an FE mesh too coarse at an edge for the fit) gives a row with its ``error`` message.
    """
    rows: list[dict[str, Any]] = []
    for run in runs:
        ref_name = run.case.reference
        found: dict[str, Any] = {}
        for method, res in run.results.items():
            try:
                found[method] = res.edges()
            except (ValueError, TypeError, RuntimeError) as exc:
                found[method] = str(exc).splitlines()[0]
        ref = found.get(ref_name)
        for method, edges in found.items():
            if isinstance(edges, str):
                rows.append({"case": run.case.name, "method": method, "error": edges})
                continue
            for k, e in enumerate(edges):
                K_ref = ref[k].K_N if ref is not None and not isinstance(ref, str) else None
                rows.append({"case": run.case.name, "method": method, "side": e.side, "kind": e.kind,
                             "K_N": e.K_N, "K_N_error": None if K_ref is None else abs(e.K_N - K_ref) / K_ref,
                             "fit_error": None if e.fit_error is None else e.fit_error / e.K_N,
                             "K_T": e.K_T, "slip_zone": e.slip_zone,
                             "exact_slip": exact_slip(run.results[method], k)})
    return rows


def edges_section(doc: dict[str, Any]) -> Section | None:
    """The multipliers table by method, from ``doc["edges"]``; None when the document has none."""
    rows = doc.get("edges") or []
    if not rows:
        return None
    cases = {c["name"]: c for c in doc["cases"]}
    table: list[tuple[Cell, ...]] = []
    covered = True
    for r in rows:
        case = cases.get(r["case"], {})
        if "error" in r:
            table.append((r["case"], registry.get(r["method"]).title, "–", words(r["error"]),
                          "–", "–", "–", "–", "–"))
            continue
        if r["fit_error"] is not None and r["K_N_error"] is not None and r["K_N_error"] > r["fit_error"]:
            covered = False
        table.append((r["case"], registry.get(r["method"]).title, r["side"],
                      with_unit(r["K_N"], unit_of(case, "K_N")), fmt(r["K_N_error"]), fmt(r["fit_error"]),
                      with_unit(r["K_T"], unit_of(case, "K_T")), with_unit(r["slip_zone"], unit_of(case, "slip_zone")),
                      with_unit(r["exact_slip"], unit_of(case, "slip_zone"))))
    head = ("case", "method", "edge", "K_N", "K_N error", "fit error", "K_T", head_unit("slip zone", "asymptotic"),
            head_unit("slip zone", "exact"))
    intro = (("At a distance r inside an edge the pressure is p ≈ K_N √r and the fully stuck shear "
              "q ≈ K_T/√r (for a cycle: of the change of shear); the asymptotic slip zone is 2|K_T|/(f K_N) "
              "(a cycle's |ΔK_T|/(f K_N)). K_N error is against the reference method's, fit error the "
              "FEM's own bound (both relative to K_N), which must cover it. See docs/EDGES.md.",),)
    tables = (Table(head, tuple(table), f"{len(table)} edges of {len(cases)} cases", fold=True),)
    figures: tuple[Figure, ...] = ()
    study = doc.get("edge_asymptote")
    if study and study["curves"]:
        orders = [c["order"] for c in study["curves"] if c["order"] is not None]
        consts = [c["constant"] for c in study["curves"] if c["constant"] is not None]
        figures = (Figure(study["plot"], (
            f"The asymptotic slip zone against the closed form's exact one, Q/fP from "
            f"{min(study['Q_over_fP']):g} to {max(study['Q_over_fP']):g} (f = {study['f']:g}): its error "
            f"falls in proportion to the slip zone (fitted orders {min(orders):.2f}–{max(orders):.2f} "
            f"below 1 % of W), with constants up to {max(consts):.2f} (Hertz's is 1): it is within 1 % "
            f"of the exact slip zone where the slip zone is under {1.0 / max(consts):.2g} % of W.")),)
    return Section("Edge multipliers", "edges", intro, tables, figures, status=Status.of(covered))


def asymptote_study() -> dict[str, Any]:
    """The asymptotic slip zone (E5) against the closed form's exact one, as Q/fP -> 0.

    For each case of :data:`ASYMPTOTE_CASES` and edge, at each Q/fP of
    :data:`ASYMPTOTE_RATIOS`: the exact slip zone over the contact width, and the asymptote's
    relative error. ``order`` is the fitted slope of log error against log (slip/W) over the
    slip zones under 1e-2 W (1: a first-order asymptote), ``constant`` the largest error per
    slip/W there: the asymptote is within 1 % of the exact slip zone where slip/W < 1 %/constant.
    """
    import numpy as np

    from threepart.problem.catalogue import get_case
    from threepart.registry import REFERENCE, get

    out, failed = [], []
    for name in ASYMPTOTE_CASES:
        case = get_case(name).resolved()
        try:
            normal = get(REFERENCE).normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
            normal.edges()
        except (ValueError, TypeError) as exc:   # the reference refuses it (or a stand-in method)
            failed.append(f"{name}: {exc}")
            continue
        W = normal.a + normal.c
        shear = get(REFERENCE).slip
        assert shear is not None           # the reference method computes partial slip
        for k, side in enumerate(SIDES):
            slip, error = [], []
            for ratio in ASYMPTOTE_RATIOS:
                try:
                    res = shear(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt,
                                Q=ratio * ASYMPTOTE_F * case.P, f=ASYMPTOTE_F, normal=normal)
                except ValueError as exc:   # a stick zone the reference refuses: named, not drawn
                    failed.append(f"{name}, Q/fP = {ratio:g}: {exc}")
                    continue
                exact, estimate = exact_slip(res, k), res.edges()[k].slip_zone
                if exact is None or exact <= 0 or estimate is None:
                    continue
                slip.append(exact / W)
                error.append(abs(estimate - exact) / exact)
            x, y = np.log(slip), np.log(np.maximum(error, 1e-300))
            small = np.asarray(slip) < 1e-2
            order = float(np.polyfit(x[small], y[small], 1)[0]) if small.sum() >= 2 else None
            constant = float(np.max(np.asarray(error)[small] / np.asarray(slip)[small])) if small.any() else None
            out.append({"case": name, "side": side, "slip_over_W": slip, "error": error,
                        "order": order, "constant": constant})
    return {"Q_over_fP": list(ASYMPTOTE_RATIOS), "f": ASYMPTOTE_F, "curves": out, "failed": failed}


def draw_asymptote(study: dict[str, Any], path: Any) -> None:
    """The asymptote's relative error against slip/W, log-log, with the first-order line."""
    import numpy as np

    from .plots import new_figure, save

    if not study["curves"]:
        return
    fig, axes = new_figure(size=(6.4, 4.4))
    ax = axes[0, 0]
    for k, c in enumerate(study["curves"]):
        ax.loglog(c["slip_over_W"], c["error"], "o-" if c["side"] == "left" else "s--", ms=3.5,
                  color=f"C{k // 2}", label=f"{c['case']}, {c['side']} edge")
    s = np.logspace(-5, 0, 20)
    ax.loglog(s, s, "k:", lw=1.2, label="error = slip/W (Hertz exactly)")
    ax.axhline(1e-2, color="0.6", lw=0.8)
    ax.axvline(1e-2, color="0.6", lw=0.8)
    ax.set_xlabel("exact slip zone / contact width W")
    ax.set_ylabel("relative error of 2|K_T|/(f K_N)")
    ax.set_title("asymptotic slip zone (E5) against the exact one")
    ax.legend(fontsize=7, ncol=2)
    save(fig, path)

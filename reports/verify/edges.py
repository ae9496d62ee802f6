"""The report's "Edge multipliers" section: K_N, K_T and the slip zone of every case's edges, by method.

:func:`edge_rows` computes the rows from a run's results (each result's
``edges()``, :mod:`threepart.asymptotics`, docs/EDGES.md) into ``report.json``'s
``edges``; :func:`edges_section` turns them into the section. K_N of each method
is set against the reference's (the closed form, or the SIE past it); the FEM's
fit error is shown beside its own error, which it must cover; where a result has
a stick zone its exact slip zone stands beside the asymptotic one (E5, E7).
"""
from __future__ import annotations

from typing import Any, Sequence

from threepart import registry

from .sections import Cell, Section, Status, Table, _head, _u, _with_unit, fmt, words

__all__ = ["edge_rows", "edges_section"]


def _exact_slip(res: Any, k: int) -> float | None:
    """The result's own slip zone at edge ``k`` (0 left, 1 right), or None without a stick zone."""
    zone = getattr(res, "stick_zone", None)
    if zone is None or getattr(res, "shakedown", False):
        return None
    normal = res.normals[0] if hasattr(res, "normals") else getattr(res, "normal", res)
    if not hasattr(res, "d"):
        return None
    lo, hi = zone
    return float(lo + normal.a) if k == 0 else float(normal.c - hi)


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
                             "exact_slip": _exact_slip(run.results[method], k)})
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
                      _with_unit(r["K_N"], _u(case, "K_N")), fmt(r["K_N_error"]), fmt(r["fit_error"]),
                      _with_unit(r["K_T"], _u(case, "K_T")), _with_unit(r["slip_zone"], _u(case, "slip_zone")),
                      _with_unit(r["exact_slip"], _u(case, "slip_zone"))))
    head = ("case", "method", "edge", "K_N", "K_N error", "fit error", "K_T", _head("slip zone", "asymptotic"),
            _head("slip zone", "exact"))
    intro = (("At a distance r inside an edge the pressure is p ≈ K_N √r and the fully stuck shear "
              "q ≈ K_T/√r (for a cycle: of the change of shear); the asymptotic slip zone is 2|K_T|/(f K_N) "
              "(a cycle's |ΔK_T|/(f K_N)). K_N error is against the reference method's, fit error the "
              "FEM's own bound (both relative to K_N), which must cover it. See docs/EDGES.md.",),)
    return Section("Edge multipliers", "edges", intro,
                   (Table(head, tuple(table), f"{len(table)} edges of {len(cases)} cases", fold=True),),
                   status=Status.of(covered))

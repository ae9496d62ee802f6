"""The report's "Stress and fatigue" section: the hot spots by each method, and the stress plots.

Part of :func:`reports.verify.sections.build` (kept apart for its size): every number
is read from the ``report.json`` document, each with its unit (the report's
:data:`threepart.problem.units.UNITS`; the fatigue parameters' from their table, :mod:`threepart.fatigue.table`)
and :data:`SPOT_DIGITS` significant digits.
"""
from __future__ import annotations

import math
from typing import Any

from threepart.fatigue.table import parameter, parameters

from .sections import (method_name, PLOT_KINDS, Block, Code, Figure, Section, Status, Table, plot_kind,
                       unit_of, with_unit, fmt, physical)

__all__ = ["stress_section", "sig", "SPOT_DIGITS", "HOT_SPOTS", "FATIGUE_NAMES", "fatigue_names"]

#: the stress quantities of a hot spot, as the report names them
HOT_SPOTS = {"sxx": "largest surface σxx", "von_mises": "largest von Mises", "max_shear": "largest Tresca shear"}


def fatigue_names() -> dict[str, str]:
    """The fatigue parameters of a fretting case's hot spots, as the report names them: their table's
    rows with ``in_report``, read when the section is built (a row registered later is in it)."""
    return {p.name: p.short for p in parameters() if p.in_report}


#: :func:`fatigue_names` at import
FATIGUE_NAMES = fatigue_names()
#: significant digits of a hot spot's value and position in the report
SPOT_DIGITS = 4


def sig(v: Any, digits: int = 4) -> str:
    """``v`` to ``digits`` significant digits, without an exponent from 1e-3 to 1e6 ("–" for none)."""
    if v is None or not math.isfinite(v):
        return fmt(v)
    if v == 0:
        return "0"
    e = math.floor(math.log10(abs(v)))
    if not -3 <= e < 6:
        return f"{v:.{digits - 1}e}"
    d = digits - 1 - e
    return f"{round(v, d):.{max(d, 0)}f}"


def _spot(h: dict[str, Any], unit: str, length: str, depth: bool = True) -> str:
    """A hot spot: its value and where, to :data:`SPOT_DIGITS` significant digits, with units."""
    where = f"x = {sig(h['x'], SPOT_DIGITS)}" + (f", z = {sig(h['z'], SPOT_DIGITS)}" if depth else "")
    return f"{sig(h['value'], SPOT_DIGITS)}{' ' + unit if unit else ''} at {where}{' ' + length if length else ''}"


def stress_section(doc: dict[str, Any]) -> tuple[Section | None, set[str]]:
    """Hot spots of the stress field by each method, and the stress plots of every partial-slip case."""
    cases = [c for c in doc["cases"] if "stress" in c]
    cycles = [c for c in doc["cases"] if "fatigue" in c]
    if not cases and not cycles:
        return None, set()
    rows = [(c["name"], method_name(m), *(_spot(h, unit_of(c, "p"), unit_of(c, "x"), q != "sxx")
                                                  for q, h in spots.items()))
            for c in cases for m, spots in c["stress"]["hot_spots"].items()]
    head = ("case", "method", *(HOT_SPOTS[q] for q in ("sxx", "von_mises", "max_shear")))
    figs = tuple(Figure(p, f"{c['name']}: {PLOT_KINDS[plot_kind(p, c['name'])]}", f"#{c['name']}",
                        Status.of(c["passed"]))
                 for c in cases for p in c["plots"] if plot_kind(p, c["name"]) in ("stress", "von_mises"))
    bulk = ", ".join(f"{c['name']} {with_unit(c['stress']['sigma_bulk'], unit_of(c, 'sigma_bulk'))}" for c in cases)
    intro: tuple[Block, ...] = (
        ("The stress in the substrate under every partial-slip case, by each method from its own "
         "tractions (the FEM from its displacement field): x along the surface, z the depth, "
         "tension positive, plane strain. The comparison checks the surface σxx, its peak at the "
         "trailing edge and the stresses at depth (rows sxx_surface, sxx_peak and stress_depth of "
         "each case); the hot spots below are where a designer looks for crack nucleation.",),
        (f"Bulk stress σxx in the substrate: {bulk}.",),
    )
    tables = [Table(head, tuple(rows), "hot spots")] if rows else []
    if not cases:
        intro = ()
    if cycles:
        names = fatigue_names()
        fat_rows = [(c["name"], method_name(m),
                     *(_spot(spots[q], parameter(q).unit.replace("^2 ", "²·") if physical(c) else "",
                             unit_of(c, "x")) for q in names))
                    for c in cycles for m, spots in c["fatigue"]["hot_spots"].items()]
        tables.append(Table(("case", "method", *names.values()),
                            tuple(fat_rows), "fatigue hot spots over the fretting and flight cycles"))
        intro = (*intro, (
            "Fretting fatigue: over each fretting cycle, from the stress history at the cycle's "
            "states, and over each flight cycle, from its steady state at its two end states, the "
            f"fatigue parameters ({', '.join(names.values())}; SWT and Findley on the critical "
            "plane, Ruiz's FFDP σxx·q·δ at the surface), by each method on the same points and states (",
            Code("threepart fatigue"), ", ", Code("docs/FATIGUE.md"), ").",))
    return (Section("Stress and fatigue", "stress", intro, tuple(tables), figs,
                    Status.of(all(c["passed"] for c in cases + cycles))),
            {f.path for f in figs})

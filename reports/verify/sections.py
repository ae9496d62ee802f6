"""The verification report as one ordered list of sections, built from ``report.json``.

:func:`build` turns a ``report.json`` document into a :class:`Document`: a
title, the verdict and an ordered list of :class:`Section` objects, each with
its intro text, tables, figures and a typed :class:`Status`. Markdown and HTML
(:mod:`reports.verify.render`) are two renderings of that one list; neither holds a
section of its own, and neither matches strings to decide what passed.

Text is typed, not marked up: a paragraph is a tuple of plain strings,
:class:`Code` (rendered as ``<code>``) and :class:`Link`, so that no literal
markup can reach the page. Every fact about the cases (names, loads,
materials, peak pressures) is read from the document, never written here.

The report reads top-down: the verdict, how to read the numbers, the tightest
margins, the pressure of every case by the three methods (visible, not
folded), one line per case, then the details, whose tables fold away in HTML.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import Enum
from typing import Any, Sequence, Union

from threepart.problem.units import UNITS
from threepart import registry
from threepart.registry import REFERENCE
from threepart.tolerances import ERROR_UNITS, NORMALISATION, VALUE_UNITS, error_unit

from .cells import fmt, head_unit, physical, unit_of, with_unit
from threepart.errors import InputError

__all__ = ["Status", "Verdict", "Code", "Link", "Item", "Bullets", "Table", "Figure", "Section",
           "Document", "build", "words", "fmt", "order_text", "plot_path", "study_plot_path", "PLOT_KINDS",
           "ENERGY_UNIT", "ENERGY_UNIT_TEXT", "method_name", "REFEREE_NAMES", "MAP_JSON", "MAP_COMMAND",
           "with_unit", "unit_of", "head_unit", "physical", "plot_kind"]   # the cells from .cells

#: energy dissipated per cycle and unit length: the shear force per unit length Q [N/mm]
#: times a slip [mm], i.e. N·mm per mm of contact length (a force, N)
ENERGY_UNIT = f"N·{UNITS['d']}/{UNITS['b']}"
ENERGY_UNIT_TEXT = f"N·{UNITS['d']} per {UNITS['b']} of contact length, per cycle"
#: how the report names a referee that is not a method of the registry (another code's results)
REFEREE_NAMES = {"calculix": "CalculiX", "calculix-friction": "CalculiX with friction",
                 "getfem-friction": "GetFEM with friction"}


def method_name(method: str) -> str:
    """How the report names ``method``: its registry label (:attr:`threepart.registry.Method.label`),
    a referee's name, else the name itself."""
    try:
        return registry.get(method).title
    except ValueError:
        return REFEREE_NAMES.get(method, method)
#: the validity map's file beside the report (written by ``threepart map``) and the command
MAP_JSON = "../map/map.json"
MAP_COMMAND = "threepart map --quick"
#: the plots of a case, by kind: what each shows
PLOT_KINDS = {
    "overlay": "pressure (and shear) of every method, the reference as a line",
    "errors": "pointwise error of each method against the reference, as a fraction of its peak",
    "cycle": "fretting cycle: hysteresis loop and the shear at three states",
    "steady": "flight cycle's steady state: the shear at both end states and the slip amplitude at "
              "both contact ends, the permanent stick zone dotted; the marched history's last cycle "
              "(dash-dot) slips as the steady state, and in the permanent stick zone carries the shear "
              "its load path locked in (the steady state fixes only the change, eq. S13)",
    "stress": "surface stress σxx of every method, along the contact and beyond its ends",
    "von_mises": "von Mises stress under the contact: the reference filled, every method's contours",
}


# -- the typed pieces -----------------------------------------------------------------------
class Status(Enum):
    """The verdict of a check, a case or the whole report."""

    PASS = "pass"
    FAIL = "FAIL"

    @classmethod
    def of(cls, passed: bool) -> Status:
        return cls.PASS if passed else cls.FAIL


@dataclass(frozen=True)
class Verdict:
    """A table cell that is a judgement: its status and the words shown (default: the status)."""

    status: Status
    text: str = ""

    def __str__(self) -> str:
        return self.text or self.status.value


@dataclass(frozen=True)
class Code:
    """Inline code (a command, a file name)."""

    text: str


@dataclass(frozen=True)
class Link:
    """A link: ``href`` is a relative path or ``#anchor`` of a section."""

    text: str
    href: str


Inline = Union[str, Code, Link]
Para = tuple[Inline, ...]
Cell = Union[str, Verdict, Link, Para]


def words(text: str) -> Para:
    """Free text from the document (a message, a reason, a note) with its ```code``` spans typed.

    The house's messages name an argument in backticks (```s` = 0.41 exceeds ...``);
    they become :class:`Code`, so no backtick reaches the page.
    """
    parts = text.split("`")
    if len(parts) % 2 == 0:          # an unpaired backtick: plain text
        return (text,)
    return tuple(Code(p) if i % 2 else p for i, p in enumerate(parts) if p)


@dataclass(frozen=True)
class Item:
    """One bullet, with an optional sub-list."""

    text: Para
    sub: tuple[Para, ...] = ()


@dataclass(frozen=True)
class Bullets:
    """A bulleted list."""

    items: tuple[Item, ...]


Block = Union[Para, Bullets]


@dataclass(frozen=True)
class Table:
    """A table; ``fold`` puts it behind a summary line in HTML (``<details>``)."""

    head: tuple[str, ...]
    rows: tuple[tuple[Cell, ...], ...]
    summary: str = ""
    fold: bool = False


@dataclass(frozen=True)
class Figure:
    """A PNG under the report directory, its caption and, optionally, its section's anchor."""

    path: str
    caption: str
    link: str | None = None
    status: Status | None = None


@dataclass(frozen=True)
class Section:
    """One section: title, intro blocks, tables, figures, status and sub-sections.

    ``fold`` folds the whole body away in HTML (a case's details), open when
    the status is a failure; ``anchor`` is the HTML id.
    """

    title: str
    anchor: str
    intro: tuple[Block, ...] = ()
    tables: tuple[Table, ...] = ()
    figures: tuple[Figure, ...] = ()
    status: Status | None = None
    fold: bool = False
    children: tuple[Section, ...] = ()


@dataclass(frozen=True)
class Document:
    """The whole report: title, verdict line and status, and the ordered sections."""

    title: str
    verdict: str
    status: Status
    sections: tuple[Section, ...] = field(default_factory=tuple)


# -- formatting -------------------------------------------------------------------------------
def _used(ratio: Any) -> str:
    """``error/limit`` as a percentage of the limit used."""
    return "–" if ratio is None else f"{100 * ratio:.3g} %"


def order_text(errors: Sequence[float | None], order: float | None) -> str:
    """The observed order as printed: a number only for errors that fall at every level.

    A fit through errors that rise and fall again would print a rate the
    discretisation does not have, so such a sequence reads ``"not monotone"``
    (:func:`threepart.convergence.is_monotone`); errors that reach round-off
    after one level read ``"at round-off"``.
    """
    from threepart.convergence import ROUND_OFF, is_monotone

    e = [math.nan if x is None else float(x) for x in errors]
    finite = order is not None and math.isfinite(order)
    if is_monotone(e):
        return f"order {order:.2f}" if finite else "no order"
    if not any(x > ROUND_OFF for x in e if math.isfinite(x)):
        return "at round-off"
    return "not monotone"


# -- plot names (one home: verify writes them, the sections show them) ------------------------
def plot_path(case: str, kind: str) -> str:
    """The report-relative path of a case's plot of ``kind`` (:data:`PLOT_KINDS`)."""
    if kind not in PLOT_KINDS:
        raise InputError(f"`kind` = {kind!r} is not one of {sorted(PLOT_KINDS)}")
    return f"plots/{case}_{kind}.png"


def study_plot_path(method: str, scheme: str | None, case: str) -> str:
    """The report-relative path of a convergence study's plot."""
    return f"plots/{method}{'_' + scheme if scheme else ''}_{case}_convergence.png"


def plot_kind(path: str, case: str) -> str:
    """The kind (a key of :data:`PLOT_KINDS`) of the case's plot at ``path``; ``""`` if none."""
    return next((k for k in PLOT_KINDS if path == plot_path(case, k)), "")


# -- the blocks, from the document ------------------------------------------------------------
def _verdict(doc: dict[str, Any]) -> str:
    s = doc["summary"]
    word = "PASSED" if doc["passed"] else "FAILED"
    total = doc["timings"].get("total_s")
    return (f"{word}: {s['checks'] - s['failed_checks']}/{s['checks']} checks within tolerance, "
            f"{s['errors']} solver errors, {s['cases']} cases (mode {doc['mode']}"
            + (f", {total:.0f} s)" if total is not None else ")"))


def _beyond(case: dict[str, Any]) -> bool:
    """True for a case past the closed form's framework: its reference is another method."""
    return (case.get("reference") or REFERENCE) != REFERENCE


def _peaks(case: dict[str, Any]) -> list[float]:
    ref = case["results"].get(case.get("reference") or REFERENCE, {})
    return [ref[k]["p"] for k in ("peak_left", "peak_right") if k in ref]


def _span(values: Sequence[float], unit: str, digits: int = 6) -> str:
    """``lo–hi unit`` of ``values`` to ``digits`` significant digits (one value if all agree)."""
    lo, hi = (f"{v:.{digits}g}" for v in (min(values), max(values)))
    return f"{lo} {unit}" if lo == hi else f"{lo}–{hi} {unit}"


def _loads(doc: dict[str, Any]) -> list[Para]:
    """Where the loads come from: the paper's dimensionless load, and every case at another load."""
    cases = doc["cases"]
    paper = [c for c in cases if c.get("load_4PA_over_b") is not None
             and math.isclose(c["load_4PA_over_b"], 1.0, rel_tol=1e-3)]
    out: list[Para] = []
    if paper:
        mats = sorted({(c["E"], c["nu"]) for c in paper if physical(c)})
        mat = "; ".join(f"E = {fmt(E / 1000)} GPa, ν = {fmt(nu)}" for E, nu in mats) or "nondimensional"
        peaks = [max(_peaks(c)) for c in paper if physical(c) and _peaks(c)]
        txt = (f"Loads: {len(paper)} cases are at the paper's dimensionless load 4PA/b = 1 "
               f"(P = {_span([c['P'] for c in paper], UNITS['P'])} with b = "
               f"{_span([c['punch']['b'] for c in paper], UNITS['b'])}; {mat}, rigid punch).")
        if peaks:
            txt += (f" That is why their peak pressures are {_span([p / 1000 for p in peaks], 'GPa', 2)}, "
                    "far beyond what the material carries: the check is linear elastic and its "
                    "relative errors do not depend on the load's size.")
        out.append((txt,))
    for c in cases:
        if c in paper or c.get("load_4PA_over_b") is None:
            continue
        peaks = _peaks(c)
        unit = UNITS["p"] if physical(c) else ""
        txt = (f"At another load: {c['name']}, {c['description']} (P = "
               f"{with_unit(c['P'], unit_of(c, 'P'))}, 4PA/b = {c['load_4PA_over_b']:.3g}")
        if peaks:
            txt += f"; peak pressures {' and '.join(f'{p:.3g} {unit}'.strip() for p in peaks)}"
        out.append((txt + ").",))
    return out


def _how_to_read(doc: dict[str, Any]) -> tuple[Block, ...]:
    used = {ERROR_UNITS[c["quantity"]] for case in doc["cases"] for c in case["checks"]}
    units = [(f"{unit}: {NORMALISATION[unit]}",) for unit in NORMALISATION if unit in used]
    items = [
        Item(("Each case is solved by the closed form, the SIE and the FEM. Inside the paper's "
              "framework the closed form is the reference and the SIE and the FEM are compared "
              "with it; past it (\"beyond the closed form\") the SIE is the reference, the FEM "
              "checks it, and the closed form must refuse with the named error.",)),
        Item(("An error is the absolute difference from the reference as a fraction of a scale, "
              "named in its unit column:",), tuple(units)),
        Item((f"Units: lengths {UNITS['a']}, loads {UNITS['P']} (per unit length of the contact), "
              f"pressures {UNITS['p']}, the tilt {UNITS['alpha']}; the energy dissipated by a "
              f"fretting cycle is in {ENERGY_UNIT} ({ENERGY_UNIT_TEXT}). A case without a "
              "material is nondimensional.",)),
    ]
    items += [Item(p) for p in _loads(doc)]
    return (Bullets(tuple(items)),)


def _case_link(name: str) -> Link:
    return Link(name, f"#{name}")


def _tightest(doc: dict[str, Any]) -> Table:
    head = ("case", "comparison", "quantity", "error", "limit", "limit used")
    rows = tuple((_case_link(t["case"]), t["comparison"], t["quantity"],
                  with_unit(t["error"], t["unit"]), with_unit(t["limit"], t["unit"]),
                  _used(t["ratio"])) for t in doc["summary"].get("tightest", []))
    return Table(head, rows)


def _refused(case: dict[str, Any]) -> Verdict:
    ok = bool(case.get("refusals")) and all(k["passed"] for k in case["checks"]
                                           if k["comparison"] == "refusal")
    return (Verdict(Status.PASS, f"refuses, correctly ({case['closedform_refuses']})") if ok
            else Verdict(Status.FAIL, "did not refuse as it must"))


def _case_lines(doc: dict[str, Any], beyond: bool) -> Table:
    cases = [c for c in doc["cases"] if _beyond(c) == beyond]
    rows: tuple[tuple[Cell, ...], ...]
    if beyond:
        head = ("case", "what", "closed form", "SIE vs FEM", "largest limit used")
        rows = tuple((_case_link(c["name"]), c["description"], _refused(c),
                      Verdict(Status.of(c["passed"])), _used(c.get("worst_ratio"))) for c in cases)
    else:
        head = ("case", "what", "verdict", "largest limit used", "methods")
        rows = tuple((_case_link(c["name"]), c["description"], Verdict(Status.of(c["passed"])),
                      _used(c.get("worst_ratio")), ", ".join(c["results"])) for c in cases)
    return Table(head, rows)


def _load(case: dict[str, Any]) -> str:
    """The case's input in one sentence, with units (or "nondimensional")."""
    p = case["punch"]
    L = unit_of(case, "b")
    R = "∞" if p["R"] is None else with_unit(p["R"], L)
    material = (f"E = {case['E']:.6g} {UNITS['E']}, ν = {fmt(case['nu'])}; " if physical(case)
                else f"nondimensional, A = {fmt(case.get('A'))}; ")
    txt = (f"R1 = {with_unit(p['R1'], L)}, R2 = {with_unit(p['R2'], L)}, b = {with_unit(p['b'], L)}, "
           f"R = {R}; {material}P = {with_unit(case['P'], unit_of(case, 'P'))}, "
           f"s = {with_unit(case['s'], L)}, tilt {case['tilt']}")
    if case["Q_over_fP"] is not None:
        txt += f"; f = {fmt(case['f'])}, Q/fP = {fmt(case['Q_over_fP'])}"
    return txt + f". Reference: the {method_name(case.get('reference') or REFERENCE)}."


def energy_unit(case: dict[str, Any]) -> str:
    """The unit of a case's energy per cycle: :data:`ENERGY_UNIT`, or "" when nondimensional."""
    return ENERGY_UNIT if physical(case) else ""


def _results(case: dict[str, Any]) -> Table:
    L = unit_of(case, "a")
    head = [head_unit("a", L), head_unit("c", L), head_unit("α", unit_of(case, "alpha")), head_unit("s", L),
            head_unit("p_left", unit_of(case, "p")), head_unit("p_right", unit_of(case, "p")), head_unit("d", L),
            head_unit("e", L)]
    fretting = any("energy" in r for r in case["results"].values())
    if fretting:
        head.append(head_unit("energy per cycle", energy_unit(case)))
    head.append("time [s]")
    rows = []
    for m, r in case["results"].items():
        row = [m, fmt(r["a"]), fmt(r["c"]), fmt(r["alpha"]), fmt(r["s"]), fmt(r["peak_left"]["p"]),
               fmt(r["peak_right"]["p"]), fmt(r.get("d")), fmt(r.get("e"))]
        if fretting:
            row.append(fmt(r.get("energy")))
        rows.append(tuple(row + [fmt(r["time_s"])]))
    return Table(tuple(["method"] + head), tuple(rows), "results of each method", fold=True)


def _checks(case: dict[str, Any]) -> Table:
    head = ("comparison", "quantity", "reference", "obtained", "error", "limit", "limit used",
            "verdict")
    rows = []
    for c in case["checks"]:
        unit, vunit = ERROR_UNITS[c["quantity"]], VALUE_UNITS[c["quantity"]]
        if not physical(case) and vunit in UNITS.values():
            vunit = ""
        ratio = c["error"] / c["limit"] if c["error"] is not None and c["limit"] else None
        rows.append((c["comparison"], c["quantity"], with_unit(c["reference"], vunit),
                     with_unit(c["obtained"], vunit), with_unit(c["error"], unit),
                     with_unit(c["limit"], unit), _used(ratio), Verdict(Status.of(c["passed"]))))
    return Table(head, tuple(rows), f"{len(rows)} checks against the tolerance table", fold=True)


def _energy(case: dict[str, Any]) -> Para | None:
    energies = [(m, r["energy"]) for m, r in case["results"].items() if "energy" in r]
    if not energies:
        return None
    unit = energy_unit(case)
    return (("Energy dissipated per cycle: "
             + ", ".join(f"{method_name(m)} {with_unit(e, unit)}" for m, e in energies)
             + (f" ({ENERGY_UNIT_TEXT})." if unit else " (nondimensional).")),)


def _cycle(case: dict[str, Any]) -> Para | None:
    """A flight cycle's two end states and each method's permanent stick zone ``[-(d+e), d-e]``."""
    if "states" not in case:
        return None
    L, F, S = unit_of(case, "b"), unit_of(case, "P"), (UNITS["E"] if physical(case) else "")
    ends = "; ".join(f"state {k}: P = {with_unit(P, F)}, s = {with_unit(s, L)}, Q = {with_unit(Q, F)}, "
                     f"σ_bulk = {with_unit(g, S)}" for k, (P, s, Q, g) in enumerate(case["states"]))
    zones = ", ".join(
        f"{method_name(m)} [{fmt(-(r['d'] + r['e']))}, {fmt(r['d'] - r['e'])}]"
        + (" (shakedown)" if r.get("shakedown") else "")
        for m, r in case["results"].items() if r.get("d") is not None)
    return (f"The cycle moves linearly and in phase between {ends}. Permanent stick zone"
            f"{f' ({L})' if L else ''}: {zones}.",)


def _case_section(case: dict[str, Any], shown: set[str]) -> Section:
    intro: list[Block] = [(_load(case),)]
    cycle = _cycle(case)
    if cycle:
        intro.append(cycle)
    energy = _energy(case)
    if energy:
        intro.append(energy)
    intro += [(f"{m}: ", *words(x)) for m, x in case.get("refusals", {}).items()]
    intro += [(f"error, {m}: ", *words(x)) for m, x in case["errors"].items()]
    tables = [_results(case)] + ([_checks(case)] if case["checks"] else [])
    figures = tuple(Figure(p, f"{case['name']}: {PLOT_KINDS.get(plot_kind(p, case['name']), p)}")
                    for p in case["plots"] if p not in shown)
    return Section(f"{case['name']}: {case['description']}", case["name"], tuple(intro),
                   tuple(tables), figures, Status.of(case["passed"]), fold=True)


def _study(st: dict[str, Any]) -> Table:
    """Errors per level, then the observed order (monotone errors only) and the GCI."""
    head = (st["param"], "label", *(f"{q} error" for q in st["errors"]))
    rows: list[tuple[Cell, ...]] = [
        (fmt(v), lab, *(fmt(st["errors"][q][i]) for q in st["errors"]))
        for i, (v, lab) in enumerate(zip(st["sizes"], st["labels"]))]
    rows.append(("observed order", "", *(_order_cell(st, q) for q in st["errors"])))
    if st["gci"]:
        rows.append(("GCI", "", *(fmt(st["gci"].get(q)) for q in st["errors"])))
    return Table(head, tuple(rows), "errors per level, observed orders", fold=True)


def _order_cell(st: dict[str, Any], q: str) -> str:
    text = order_text(st["errors"][q], st["orders"].get(q))
    return fmt(st["orders"][q]) if text.startswith("order ") else text


def _study_title(st: dict[str, Any]) -> str:
    scheme = f" ({st['scheme']})" if st.get("scheme") else ""
    what = {"n": "in n", "h": "in h", "dQ": "in the load step ΔQ",
            "1/K": "in the penalty 1/K"}.get(st["param"], f"in {st['param']}")
    return f"{method_name(st['method'])}{scheme} convergence {what}, case {st['case']}"


def _studies(doc: dict[str, Any]) -> Section:
    children = []
    for st in doc["studies"]:
        if st["method"].endswith("-friction"):    # the friction referees' own section (.friction)
            continue
        path = study_plot_path(st["method"], st.get("scheme"), st["case"])
        figs = (Figure(path, _study_title(st)),) if path in doc["plots"] else ()
        children.append(Section(_study_title(st), f"study-{path.split('/')[-1][:-4]}",
                                tuple(("note: ", *words(n)) for n in st["notes"]), (_study(st),), figs))
    intro: Para = ("Errors against the closed form as the discretisation is refined (log-log). "
                   "An observed order is given only where the errors fall at every level; "
                   "the dotted and dashed lines are slopes of order 1 and 2.",)
    return Section("Convergence studies", "studies", (intro,), children=tuple(children))


def _map(map_link: str | None) -> Section:
    intro: list[Inline] = [
        "Every check above compares idealisations of one model: a parabolic profile on "
        "half-planes. The validity map (", Code("threepart map"), ", ", Code("docs/MAP.md"),
        ") solves punches of real shape, with exact arcs, flanks and a finite height, and maps the "
        "closed form's peak-pressure error over the overhang (a-b)/R1 and b/R1. "]
    if map_link:
        intro += ["It is written beside this report: ", Link(map_link, map_link), "."]
    else:
        intro += ["There is no map beside this report; make one with ", Code(MAP_COMMAND),
                  " (7.5 minutes on 2 idle cores) or ", Code("threepart map"), " (the full grid "
                  "with its studies and CalculiX points, 30 minutes), run "
                  "in the directory that holds this report's directory."]
    return Section("Where the half-plane formulas stop", "map", (tuple(intro),))


def _tolerances(doc: dict[str, Any]) -> Table:
    head = ("comparison", "quantity", "limit", "unit", "reason")
    rows = tuple((t["comparison"], t["quantity"], fmt(t["limit"]), error_unit(t["comparison"], t["quantity"]),
                  words(t["reason"])) for t in doc["tolerances"])
    return Table(head, rows, f"{len(rows)} entries, each with its reason", fold=True)


def _environment(doc: dict[str, Any]) -> Table:
    env = doc["environment"]
    git = env["git"]
    rows = (
        ("created", doc["created"]),
        ("git commit", f"{git['commit']}{' (dirty tree)' if git['dirty'] else ''}"),
        ("python / platform", f"{env['python']} / {env['platform']}"),
        ("packages", ", ".join(f"{k} {v}" for k, v in env["packages"].items() if v)),
        ("timings", ", ".join(f"{k} {v:.1f} s" for k, v in doc["timings"].items() if v is not None)),
    )
    return Table(("item", "value"), rows, "commit, versions, timings", fold=True)


def _overlays(doc: dict[str, Any]) -> tuple[Section, set[str]]:
    """The first plot of every case (its pressure overlay or fretting cycle), unfolded."""
    figs = []
    for c in doc["cases"]:
        if not c["plots"]:
            continue
        p = c["plots"][0]
        figs.append(Figure(p, f"{c['name']}: {c['description']}", f"#{c['name']}",
                           Status.of(c["passed"])))
    intro: Para = ("The pressure of every case by each method: the closed form as a black line, "
                   "the SIE as red circles and the FEM as a blue dashed line (past the closed form "
                   "the SIE is the reference); dotted lines are the joins x = ±b. Cases with a "
                   f"material are drawn in {UNITS['x']} and {UNITS['p']}. Click a plot for the "
                   "case's numbers.",)
    return (Section("Pressure by the three methods", "overlays", (intro,), figures=tuple(figs)),
            {f.path for f in figs})


def build(doc: dict[str, Any], map_link: str | None = None) -> Document:
    """The report's sections, in reading order, from a ``report.json`` document.

    Parameters
    ----------
    doc
        The ``report.json`` document (:func:`reports.verify.report.build_report`).
    map_link
        The report-relative path of the validity map, linked only when given
        (it exists); otherwise the section says how to make one.
    """
    from .edges import edges_section
    from .friction import friction_section
    from .speed import speed_section
    from .stress_section import stress_section

    overlays, shown = _overlays(doc)
    stress, stress_plots = stress_section(doc)
    shown |= stress_plots
    inside = [c for c in doc["cases"] if not _beyond(c)]
    beyond = [c for c in doc["cases"] if _beyond(c)]
    sections = [
        Section("How to read it", "how", _how_to_read(doc)),
        Section("Tightest margins", "tightest",
                (("The checks closest to their limits, worst first; every check is in the "
                  "case's details.",),), (_tightest(doc),)),
        overlays,
        Section("Cases inside the paper's framework", "inside", (), (_case_lines(doc, False),),
                status=Status.of(all(c["passed"] for c in inside)) if inside else None),
        Section("Beyond the closed form", "beyond", (), (_case_lines(doc, True),),
                status=Status.of(all(c["passed"] for c in beyond)) if beyond else None),
        *((stress,) if stress else ()),
        *((edges,) if (edges := edges_section(doc)) else ()),
        Section("Details of each case", "details",
                (("Each case's input, the results of each method, every check and the error "
                  "plots.",),), children=tuple(_case_section(c, shown) for c in doc["cases"])),
        _studies(doc),
        *filter(None, (friction_section(doc),)),   # issue 38: the friction referee columns
        _map(map_link),
        Section("Tolerance table", "tolerances", (), (_tolerances(doc),)),
        *filter(None, (speed_section(doc),)),   # issue 33: the speed ratios against their targets
        Section("Environment", "environment", (), (_environment(doc),)),
    ]
    return Document(f"threepart verification report ({doc['mode']})", _verdict(doc),
                    Status.of(bool(doc["passed"])), tuple(sections))

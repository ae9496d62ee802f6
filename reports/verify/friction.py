"""The friction referee columns in the verification report: their verdict, record and section.

The columns (:func:`reports.referee.friction_studies.friction_studies`) are studies in h;
each one that ran is judged at its finest level (:func:`reports.referee.verdict.column_verdict`)
and its rows become a run of checks (:func:`friction_runs`), counted in the report's
PASSED/FAILED total as every case's checks are. A code that is not installed, a problem
it cannot run yet, or one of ``--full`` in the default mode is named, not failed.

Names
-----
friction_runs    -- one CaseRun of checks per judged column (its finest level against issue 38)
friction_record  -- the report's ``friction_referees`` record of the studies
friction_section -- the report's section of that record
FRICTION_PLOT    -- the stick zone's error against W/h, per code and problem (report-relative)
"""
from __future__ import annotations

import math
from typing import Any, Sequence

from threepart.tolerances import ERROR_UNITS, tolerance

from ..compare import Check
from ..referee.friction_problems import FRICTION_PROBLEMS
from ..referee.friction_studies import FRICTION_METHOD, NOT_RUN, REFEREES, RUN_SCHEME
from ..referee.studies import SLOPE_SCALE
from ..referee.verdict import FRICTION_TARGETS, column_verdict
from .cells import fmt
from .runs import CaseRun
from .sections import Bullets, Figure, Item, Section, Status, Table, Verdict, method_name, order_text, words

__all__ = ["friction_runs", "friction_record", "friction_section", "FRICTION_PLOT"]

#: the plot of the stick zone's error against W/h (report-relative)
FRICTION_PLOT = "plots/friction_referees_stick_zone.png"


def _code(method: str) -> str:
    return method[: -len(FRICTION_METHOD)]


def _documented(code: str) -> dict[str, tuple[str, str]]:
    ref = REFEREES.get(code)
    return dict(ref.documented) if ref is not None else {}


def _case(problem: str, code: str, level: str) -> Any:
    """The catalogue-shaped case of a judged column: its problem's punch, loads and material."""
    from threepart.problem.catalogue import Case

    row = next(p for p in FRICTION_PROBLEMS if p.name == problem)
    pr = row.build()
    P, s = (pr["P"], pr["s"]) if "P" in pr else pr["states"][0][:2]
    return Case(name=f"{code}{FRICTION_METHOD}_{problem}",
                description=(f"{method_name(code + FRICTION_METHOD)} on {pr['title']}: the finest level "
                             f"W/h = {float(level):g} judged against issue 38's targets (or the code's "
                             "documented rows, the target shown beside them)"),
                punch=pr["punch"], P=P, s=s, material=(pr["E"], pr["nu"]), tilt=pr["tilt"])


def friction_runs(studies: Sequence[Any]) -> list[CaseRun]:
    """One run of checks per friction column that ran: its finest level's verdict rows as checks
    (an unmet issue target judged by the code's documented row says so in the check's reason)."""
    out = []
    for st in studies:
        if not st.method.endswith(FRICTION_METHOD) or st.scheme != RUN_SCHEME or not st.sizes:
            continue
        d = st.as_dict()
        code = _code(st.method)
        rows = column_verdict(d, _documented(code))
        run = CaseRun(_case(st.case, code, d["labels"][-1]))
        run.checks = [Check(r["comparison"], r["quantity"], _num(r["reference"]), _num(r["obtained"]),
                            _num(r["error"]), r["limit"], _reason(r)) for r in rows]
        out.append(run)
    return out


def _num(x: Any) -> float:
    return math.nan if x is None else float(x)


def _reason(r: dict[str, Any]) -> str:
    unit = ERROR_UNITS.get(r["quantity"], "")
    if r["by_target"]:
        return f"issue 38's target at W/h = {float(r['level']):g}: {r['reason']}"
    return (f"issue 38's target {r['target']:g} {unit} is "
            f"{'met' if r['target_met'] else 'unmet'} at W/h = {float(r['level']):g}; judged by the "
            f"code's documented row ({r['comparison']}, {r['row']}): {r['reason']}")


def friction_record(studies: Sequence[Any], plot: str | None = None) -> dict[str, Any] | None:
    """The report's ``friction_referees`` record: every column (run or not, why), its errors per
    level, orders, time and verdict rows; None when the run had no friction column."""
    cols = []
    for st in studies:
        if not st.method.endswith(FRICTION_METHOD):
            continue
        d = st.as_dict()
        code = _code(st.method)
        rows = column_verdict(d, _documented(code)) if st.scheme == RUN_SCHEME else []
        cols.append({"code": code, "problem": st.case, "status": "run" if st.scheme == RUN_SCHEME else st.scheme,
                     "levels": d["labels"], "sizes": d["sizes"], "errors": d["errors"], "orders": d["orders"],
                     "time_s": float(sum(t for t in d["times"] if t is not None)), "notes": d["notes"],
                     "rows": rows, "passed": all(r["passed"] for r in rows) if rows else None})
    if not cols:
        return None
    return {"columns": cols, "plot": plot,
            "problems": [{"name": p.name, "kind": p.kind, "mode": p.mode, "needs": p.needs}
                         for p in FRICTION_PROBLEMS]}


def _per_level(r: dict[str, Any], col: dict[str, Any]) -> str:
    pairs = zip(col["levels"], r["errors"])
    return ", ".join(f"{float(n):g}: {fmt(e)}" for n, e in pairs)


def friction_section(doc: dict[str, Any]) -> Section | None:
    """The friction referees' section: what ran, the verdict of each column's finest level
    against issue 38's targets, the errors per level and their order, the time; what did not run."""
    rec = doc.get("friction_referees")
    if not rec:
        return None
    head = ("code", "problem", "quantity", "W/h", "error", "issue 38 target", "judged by", "limit",
            "target", "verdict", "errors per W/h", "order", "time")
    rows = []
    for col in rec["columns"]:
        r: dict[str, Any]
        for r in col["rows"]:
            unit = ERROR_UNITS.get(r["quantity"], "")
            by = "target" if r["by_target"] else f"{r['comparison']} {r['row']}"
            rows.append((method_name(col["code"] + FRICTION_METHOD), col["problem"], r["quantity"],
                         f"{float(r['level']):g}", fmt(r["error"]), f"{r['target']:g} {unit}", by,
                         f"{r['limit']:g} {unit}", "met" if r["target_met"] else "UNMET",
                         Verdict(Status.of(r["passed"])), _per_level(r, col),
                         order_text(r["errors"], r["order"]) if len(col["levels"]) > 1 else "one level",
                         f"{col['time_s']:.0f} s"))
    skipped = [Item(words(f"{method_name(c['code'] + FRICTION_METHOD)}, {c['problem']}: {c['status']}: "
                          + "; ".join(c["notes"])))
               for c in rec["columns"] if c["status"] != "run"]
    target = {q: tolerance(*key).limit for q, key in FRICTION_TARGETS.items()}
    intro: list[Any] = [words(
        "Two outside finite-element codes with Coulomb friction solve the closed form's friction "
        f"problems, two similar elastic bodies scaled to small slopes (radii x {SLOPE_SCALE:g}, loads "
        f"/ {SLOPE_SCALE:g}). Each column's finest level is judged against issue 38's targets: each "
        f"stick-zone end within {target['stick_ends']:g} W (`stick_ends`, and so its half-width "
        f"`stick_width` and its centre `stick_shift`, of W), ∫q within {target['q_integral']:g} of Q, the shear within "
        f"{target['q_interior_max']:g} of its peak away from the ends (5 % of W in from the contact's "
        "and the stick zone's ends, as the codes' documented rows measure it), the fretting energy within "
        f"{target['energy']:g}; where a code is documented not to meet a target, by its documented "
        "row, the target shown beside it (UNMET where the level misses it). The verdict counts in "
        "the report's total; each column's errors per level and their order show its convergence in h.")]
    if skipped:
        intro.append(Bullets(tuple(skipped)))
    judged = [c for c in rec["columns"] if c["rows"]]
    figs = (Figure(rec["plot"], "the stick zone's worst end against W/h, per code and problem"),) \
        if rec.get("plot") else ()
    return Section("Friction referees (CalculiX, GetFEM)", "friction-referees", tuple(intro),
                   (Table(head, tuple(rows)),) if rows else (), figs,
                   status=Status.of(all(c["passed"] for c in judged)) if judged else None)

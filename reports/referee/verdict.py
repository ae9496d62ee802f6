"""The referee's verdict: another code's points compared and diagnosed, as a document and a report.

Names
-----
COMPARISON   -- the tolerance table's rows a pressure from outside is judged by
judge        -- compare and diagnose: the JSON-safe document of the report (a pressure, or
                a partial slip: the shear too, and the friction pitfalls)
document     -- that document as the report's sections (checks, pitfalls)
write_report -- the report directory (md, html, json) through threepart.output
main         -- read, judge and report (``threepart compare``); 0 when all holds, else 1
column_verdict   -- a friction column's finest level judged, quantity by quantity (verify)
FRICTION_TARGETS -- issue 38's targets of the friction columns: the tolerance table's rows
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable, Mapping

from threepart.results.edges import SIDES
from threepart.errors import MeshResolutionError
from threepart.results.fields import edge_multipliers
from threepart.output import atomic_dir, json_safe, strict_json
from threepart.errors import InputError
from threepart.results import NormalResult, SlipResult
from threepart.tolerances import tolerance

from ..compare import compare, normal_of
from ..verify.sections import Bullets, Document, Item, Section, Status, Table, Verdict, fmt, words
from .friction import SlipPointsResult, friction_pitfalls, slip_from_points
from .pitfalls import diagnose
from .points import PointsResult, from_points

__all__ = ["COMPARISON", "FRICTION_COMPARISON", "judge", "edges", "document", "write_report", "main", "column_verdict",
           "FRICTION_TARGETS"]

#: the tolerance table's rows a pressure from outside is judged by
COMPARISON = "referee"
#: the rows a file of partial slip is judged by: the referee's, its contact ends and peaks as a
#: friction model's nodal tractions give them (threepart/tolerances/outside.py)
FRICTION_COMPARISON = "referee-friction"
#: issue 38's targets of the friction columns, by the quantity judged (units: ERROR_UNITS): the
#: stick zone's ends, and its half-width and centre by the ends' row
FRICTION_TARGETS = {"stick_ends": (COMPARISON, "stick_ends"), "stick_width": (COMPARISON, "stick_ends"),
                    "stick_shift": (COMPARISON, "stick_ends"),
                    **{q: (COMPARISON, q) for q in ("q_interior_max", "q_integral", "energy")}}
#: the value a judged quantity's error is of, in the column's ``values`` and ``reference``
FRICTION_VALUES = {"stick_ends": "d", "stick_width": "d", "stick_shift": "e", "q_integral": "q_integral",
                   "energy": "energy"}


def column_verdict(study: Mapping[str, Any], documented: Mapping[str, tuple[str, str]]
                   ) -> list[dict[str, Any]]:
    """A friction column's finest level judged, one row per quantity of :data:`FRICTION_TARGETS`.

    ``study`` is the column's :meth:`Study.as_dict <threepart.convergence.Study.as_dict>`
    (:mod:`.friction_studies`); ``documented`` maps a quantity (or ``"problem/quantity"``, the
    study's ``case`` the problem) to the tolerance row of the code's own documented figure. A quantity is judged by issue 38's target, or, where the
    code is documented not to meet it (its row wider than the target), by that row, with
    the target shown beside it and ``target_met`` false unless the level meets it anyway.
    A level whose run failed has no error (None) and fails. A column without levels has no rows.
    """
    if not study["sizes"]:
        return []
    i = len(study["sizes"]) - 1
    rows = []
    for q, key in FRICTION_TARGETS.items():
        if q not in study["errors"]:
            continue
        error = study["errors"][q][i]
        target = tolerance(*key)
        own = documented.get(f"{study.get('case', '')}/{q}", documented.get(q))
        row = own if own is not None and tolerance(*own).limit > target.limit else key
        judged, by_target = tolerance(*row), row == key
        known = error is not None and math.isfinite(error)
        v = FRICTION_VALUES.get(q, "")
        rows.append({"quantity": q, "level": study["labels"][i], "error": error if known else None,
                     "reference": study.get("reference", {}).get(v),
                     "obtained": study.get("values", {}).get(v, [None] * (i + 1))[i],
                     "target": target.limit, "target_met": bool(known and error <= target.limit),
                     "comparison": row[0], "row": row[1], "limit": judged.limit, "by_target": by_target,
                     "passed": bool(known and error <= judged.limit),
                     "reason": target.reason if by_target else judged.reason,
                     "errors": study["errors"][q], "order": study["orders"].get(q)})
    return rows


def edges(res: PointsResult, ref: NormalResult) -> list[dict[str, Any]]:
    """Each edge's ``K_N`` (docs/EDGES.md) of the points, fitted over their nodes
    (:func:`threepart.results.fields.edge_multipliers`), against the reference's own.

    An edge agrees when its relative error is within the tolerance table's
    ``("referee", "K_N")`` limit widened by the fit's own error. Too few points near
    an edge for the fit: the record says so instead of a number.
    """
    limit = tolerance(COMPARISON, "K_N").limit
    reference = ref.edges()
    try:
        fitted = edge_multipliers(res.x_nodes, res.p_nodes, res.a, res.c, ref.punch.b)
    except MeshResolutionError as exc:
        return [{"side": side, "reference": e.K_N, "obtained": None, "fit_error": None,
                 "error": None, "limit": limit, "passed": False, "note": str(exc)}
                for side, e in zip(SIDES, reference)]
    out = []
    for side, (K, fit_error), e in zip(SIDES, fitted, reference):
        error = (K - e.K_N) / e.K_N
        out.append({"side": side, "reference": e.K_N, "obtained": K, "fit_error": fit_error,
                    "error": error, "limit": limit,
                    "passed": bool(abs(error) <= limit + fit_error / e.K_N), "note": ""})
    return out


def judge(res: PointsResult | SlipPointsResult, ref: NormalResult | SlipResult, *,
          penalty: float | None = None, stick_slope: float | None = None,
          source: str = "") -> dict[str, Any]:
    """The comparison and the diagnosis of ``res`` against ``ref``, as a JSON-safe document.

    A partial slip (both slip results) is compared by the same comparison as the
    verification run's (its stick zone, shear, ``∫q = Q`` and Coulomb's bound)
    and diagnosed for the friction pitfalls besides the pressure's. The
    stresses are left out: between a file's last loaded point and the end
    fitted to it the tractions are not known, and a jump there is a logarithmic
    peak of the surface σxx that belongs to the interpolation, not to the code.
    """
    normal, ref_normal = normal_of(res), normal_of(ref)
    slip = (ref, res) if isinstance(ref, SlipResult) and isinstance(res, SlipPointsResult) else None
    checks = [c for c in compare(ref, res, COMPARISON if slip is None else FRICTION_COMPARISON, stresses=False)
              if c.quantity != "alpha" or res.info.get("alpha_given")]
    pitfalls = diagnose(normal, ref_normal, penalty=penalty)
    reference = {"method": ref.method, "a": ref.a, "c": ref.c, "alpha": ref.alpha,
                 "P": ref.P, "s": ref.s, "note": ref.info.get("auto", "")}
    obtained = {"a": res.a, "c": res.c, "P": normal.P, "s": normal.s,
                "points": int(normal.x_nodes.size)}
    if slip is not None:
        sref, sres = slip
        pitfalls += friction_pitfalls(sres, sref, stick_slope=stick_slope)
        reference.update(Q=sref.Q, f=sref.f, d=sref.d, e=sref.e, stick_zone=list(sref.stick_zone))
        obtained.update(d=sres.d, e=sres.e, stick_zone=list(sres.stick_zone))
    return json_safe({
        "tool": "threepart compare", "source": source,
        "reference": reference, "obtained": obtained,
        "passed": all(c.passed for c in checks) and not pitfalls,
        "checks": [c.as_dict() for c in checks],
        "pitfalls": [q.as_dict() for q in pitfalls],
        "edges": edges(normal, ref_normal),
    })


def document(doc: dict[str, Any]) -> Document:
    """The document of :func:`judge` as the report's two sections: the checks, the pitfalls."""
    ok = bool(doc["passed"])
    rows = tuple((c["quantity"], fmt(c["reference"]), fmt(c["obtained"]), fmt(c["error"]),
                  fmt(c["limit"]), Verdict(Status.of(bool(c["passed"]))), words(c["reason"]))
                 for c in doc["checks"])
    table = Table(("quantity", "reference", "obtained", "error", "limit", "verdict", "reason"), rows)
    items = tuple(Item(words(f"{q['name']}: {q['message']}")) for q in doc["pitfalls"]) or \
        (Item(("none of the known pitfalls was found",)),)
    ref = doc["reference"]
    intro = (words(f"`{doc['source']}` ({doc['obtained']['points']} points) against the "
                   f"{ref['method']} reference" + (f" ({ref['note']})" if ref["note"] else "") +
                   "; errors normalised as in the verification report, limits from the tolerance "
                   f"table's `{COMPARISON}` rows."),)
    return Document("threepart compare", "PASSED" if ok else "FAILED", Status.of(ok), (
        Section("Checks", "checks", intro, (table,), status=Status.of(all(c["passed"] for c in doc["checks"]))),
        Section("Pitfalls", "pitfalls", (Bullets(items),), status=Status.of(not doc["pitfalls"])),
        _edges_section(doc["edges"])))


def _edges_section(records: list[dict[str, Any]]) -> Section:
    """The edges' ``K_N``, fitted against the reference's: informative, not part of the verdict."""
    rows = tuple((r["side"], fmt(r["reference"]), fmt(r["obtained"]), fmt(r["fit_error"]),
                  fmt(r["error"]), fmt(r["limit"]), Verdict(Status.of(bool(r["passed"]))),
                  words(r["note"])) for r in records)
    table = Table(("edge", "K_N reference [MPa/√mm]", "K_N obtained", "fit error", "error",
                   "limit", "verdict", "note"), rows)
    intro = (words("The bounded pressure's multiplier K_N at each edge (p ≈ K_N √r at r inside "
                   "it, docs/EDGES.md), fitted over the points near the edge; it agrees when its "
                   "error is within the limit widened by the fit's own error. Shown so that an "
                   "edge that is wrong while the peak is right (or the reverse) is seen; it does "
                   "not change the verdict."),)
    return Section("Edges", "edges", intro, (table,),
                   status=Status.of(all(r["passed"] for r in records)))


def write_report(doc: dict[str, Any], out: str | Path) -> None:
    """Write ``report.md``, ``report.html`` and ``report.json`` into the new directory ``out``."""
    from ..verify.render import render_html, render_markdown

    with atomic_dir(out, command="compare") as tmp:
        d = document(doc)
        (tmp / "report.json").write_text(strict_json(doc, indent=1), encoding="utf-8")
        (tmp / "report.md").write_text(render_markdown(d), encoding="utf-8")
        (tmp / "report.html").write_text(render_html(d, tmp), encoding="utf-8")


def main(pressure: str | Path, ref: NormalResult | SlipResult, *, out: str | Path,
         alpha: float | None = None, penalty: float | None = None, stick_slope: float | None = None,
         say: Callable[[str], None] = print, **options: Any) -> int:
    """Read (``options``: the reader's, :func:`threepart.readers.read`), judge and report;
    0 when every check holds and no pitfall shows, else 1.

    Against a partial slip (``ref`` a :class:`~threepart.results.SlipResult`) the
    file must carry the shear ``q`` as well (CalculiX's CSTR, a mesh file's
    ``contact_shear``, a CSV's third column).
    """
    from threepart import readers

    record = readers.read(pressure, arg="--pressure", **options)
    info = {k: v for k, v in record.info.items()
            if k in ("source", "penalty", "increments", "stick_slope")}
    res: PointsResult | SlipPointsResult
    if isinstance(ref, SlipResult):
        if record.q is None:
            raise InputError(f"`--pressure` {pressure}: the file carries no shear q, which a partial "
                             "slip (--Q, --f) is judged by (CalculiX: CSTR; a mesh file: a point "
                             "field contact_shear; a CSV: a third column q)")
        res = slip_from_points(record.x, record.p, record.q, ref, alpha=alpha, info=info)
    else:
        res = from_points(record.x, record.p, ref, alpha=alpha, info=info)
    doc = judge(res, ref, penalty=penalty, stick_slope=stick_slope, source=str(pressure))
    write_report(doc, out)
    failed = [c for c in doc["checks"] if not c["passed"]]
    say(f"{'PASSED' if doc['passed'] else 'FAILED'}: {len(doc['checks']) - len(failed)}/"
        f"{len(doc['checks'])} checks within tolerance, {len(doc['pitfalls'])} pitfalls -> "
        f"{Path(out) / 'report.html'}")
    for c in failed:
        say(f"  failed: {c['quantity']}: error {c['error']:.3g} > {c['limit']:.3g}")
    for q in doc["pitfalls"]:
        say(f"  pitfall {q['name']}: {q['message']}")
    for e in doc["edges"]:
        say(f"  {e['side']} edge K_N: " + (f"{e['obtained']:.6g} against {e['reference']:.6g}, error "
            f"{e['error']:.3g} (fit {e['fit_error'] / e['reference']:.2g})"
            if e["obtained"] is not None else f"not fitted: {e['note']}"))
    return 0 if doc["passed"] else 1

"""Render a ``report.json`` document as Markdown and as self-contained HTML.

The report reads top-down: the verdict, how to read the numbers (the
normalisation, stated once, and where the loads come from), the tightest
margins, one line per case, and then the details, which fold away in HTML
(``<details>``) and stay complete in ``report.json``. The HTML embeds every PNG
as a base64 data URI, so that it opens in a browser from a single file.
"""
from __future__ import annotations

import base64
import html as _html
from pathlib import Path
from typing import Any, Callable

from threepart.tolerances import ERROR_UNITS, NORMALISATION, VALUE_UNITS

__all__ = ["markdown", "html", "fmt"]

#: the validity map (``threepart map``): what it is, and where it is written beside the report
MAP_TEXT = ("Every check above compares idealisations of one model: a parabolic profile on "
            "half-planes. The validity map (`threepart map`, docs/MAP.md) solves punches of real "
            "shape, with exact arcs, flanks and a finite height, and maps the closed form's "
            "peak-pressure error over the overhang (a-b)/R1 and b/R1. By default it is written "
            "beside this report:")
MAP_LINK = "../map/map.json"

Table = tuple[list[str], list[list[str]]]


def fmt(v: Any) -> str:
    """Short numeric format for tables."""
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.3e}" if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e5) else f"{v:.6g}"
    return str(v)


def _with_unit(v: Any, unit: str) -> str:
    return fmt(v) if v is None else f"{fmt(v)} {unit}"


def _used(ratio: Any) -> str:
    """``error/limit`` as a percentage of the limit used."""
    return "–" if ratio is None else f"{100 * ratio:.3g} %"


# -- the blocks of the report, as data -----------------------------------------------------
def _verdict(doc: dict[str, Any]) -> str:
    s = doc["summary"]
    word = "PASSED" if doc["passed"] else "FAILED"
    total = doc["timings"].get("total_s")
    return (f"{word}: {s['checks'] - s['failed_checks']}/{s['checks']} checks within tolerance, "
            f"{s['errors']} solver errors, {s['cases']} cases (mode {doc['mode']}"
            + (f", {total:.0f} s)" if total is not None else ")"))


def _how_to_read(doc: dict[str, Any]) -> list[str]:
    used = {ERROR_UNITS[c["quantity"]] for case in doc["cases"] for c in case["checks"]}
    lines = [
        "Each case is solved by the closed form, the SIE and the FEM. Inside the paper's framework "
        "the closed form is the reference and the SIE and the FEM are compared with it; past it "
        "(\"beyond the closed form\") the SIE is the reference, the FEM checks it, and the closed "
        "form must refuse with the named error.",
        "An error is the absolute difference from the reference as a fraction of a scale, named in "
        "its unit column:",
    ]
    lines += [f"  - {unit}: {NORMALISATION[unit]}" for unit in NORMALISATION if unit in used]
    paper = [c["name"] for c in doc["cases"] if c.get("load_4PA_over_b") is not None
             and abs(c["load_4PA_over_b"] - 1.0) < 1e-3]
    if paper:
        lines.append(
            f"Loads: {len(paper)} cases use P = 28846 N/mm, which gives the paper's dimensionless "
            "load 4PA/b = 1 for b = 1 mm on steel (E = 210 GPa, ν = 0.3, rigid punch). That is why "
            "their peak pressures are 9–15 GPa, far beyond what steel carries: the check is linear "
            "elastic and its relative errors do not depend on the load's size.")
    eng = [c for c in doc["cases"] if c["name"] == "fan_blade_flank"]
    if eng:
        c = eng[0]
        peaks = c["results"].get("closedform", {})
        txt = (f"A realistic case: {c['name']}, {c['description']} (P = {fmt(c['P'])} N/mm")
        if peaks:
            txt += (f"; closed-form peaks {fmt(peaks['peak_left']['p'])} and "
                    f"{fmt(peaks['peak_right']['p'])} MPa")
        lines.append(txt + ").")
    return lines


def _tightest(doc: dict[str, Any]) -> Table:
    head = ["case", "comparison", "quantity", "error", "limit", "limit used"]
    rows = [[t["case"], t["comparison"], t["quantity"], _with_unit(t["error"], t["unit"]),
             _with_unit(t["limit"], t["unit"]), _used(t["ratio"])]
            for t in doc["summary"].get("tightest", [])]
    return head, rows


def _case_lines(doc: dict[str, Any], beyond: bool) -> Table:
    cases = [c for c in doc["cases"] if (c.get("reference") == "sie") == beyond]
    if beyond:
        head = ["case", "what", "closed form", "SIE vs FEM", "largest limit used"]
        rows = [[c["name"], c["description"],
                 (f"refuses, correctly ({c['closedform_refuses']})" if c.get("refusals")
                  and all(k["passed"] for k in c["checks"] if k["comparison"] == "refusal")
                  else "did not refuse as it must"),
                 "pass" if c["passed"] else "FAIL", _used(c.get("worst_ratio"))] for c in cases]
    else:
        head = ["case", "what", "verdict", "largest limit used", "methods"]
        rows = [[c["name"], c["description"], "pass" if c["passed"] else "FAIL",
                 _used(c.get("worst_ratio")), ", ".join(c["results"])] for c in cases]
    return head, rows


def _load(case: dict[str, Any]) -> str:
    p = case["punch"]
    R = "∞" if p["R"] is None else fmt(p["R"])
    material = (f"E = {fmt(case['E'])} MPa, ν = {fmt(case['nu'])}; " if case.get("E") is not None
                else "")
    txt = (f"R1 = {fmt(p['R1'])} mm, R2 = {fmt(p['R2'])} mm, b = {fmt(p['b'])} mm, R = {R} mm; "
           f"{material}P = {fmt(case['P'])} N/mm, s = {fmt(case['s'])} mm, tilt {case['tilt']}")
    if case["Q_over_fP"] is not None:
        txt += f"; f = {fmt(case['f'])}, Q/fP = {fmt(case['Q_over_fP'])}"
    ref = case.get("reference", "closedform")
    return txt + f". Reference: {'the SIE' if ref == 'sie' else 'the closed form'}."


_RES_HEAD = ["method", "a [mm]", "c [mm]", "α [rad]", "s [mm]", "p_left [MPa]", "p_right [MPa]",
             "d [mm]", "e [mm]", "time [s]"]


def _results(case: dict[str, Any]) -> Table:
    rows = [[m, fmt(r["a"]), fmt(r["c"]), fmt(r["alpha"]), fmt(r["s"]),
             fmt(r["peak_left"]["p"]), fmt(r["peak_right"]["p"]),
             fmt(r.get("d")), fmt(r.get("e")), fmt(r["time_s"])]
            for m, r in case["results"].items()]
    return _RES_HEAD, rows


def _checks(case: dict[str, Any]) -> Table:
    head = ["comparison", "quantity", "reference", "obtained", "error", "limit", "limit used",
            "verdict"]
    rows = []
    for c in case["checks"]:
        unit, vunit = ERROR_UNITS[c["quantity"]], VALUE_UNITS[c["quantity"]]
        ratio = c["error"] / c["limit"] if c["error"] is not None and c["limit"] else None
        rows.append([c["comparison"], c["quantity"], _with_unit(c["reference"], vunit),
                     _with_unit(c["obtained"], vunit), _with_unit(c["error"], unit),
                     _with_unit(c["limit"], unit), _used(ratio), "pass" if c["passed"] else "FAIL"])
    return head, rows


def _study(st: dict[str, Any]) -> Table:
    """Errors per level, then the observed order and GCI where they mean something."""
    head = [st["param"], "label"] + [f"{q} error" for q in st["errors"]]
    rows = [[fmt(v), lab] + [fmt(st["errors"][q][i]) for q in st["errors"]]
            for i, (v, lab) in enumerate(zip(st["values"], st["labels"]))]
    rows.append(["observed order", ""] + [fmt(st["orders"].get(q)) if st["orders"].get(q) is not None
                                           else "not monotone" for q in st["errors"]])
    if st["gci"]:
        rows.append(["GCI", ""] + [fmt(st["gci"].get(q)) for q in st["errors"]])
    return head, rows


def _environment(doc: dict[str, Any]) -> list[tuple[str, str]]:
    env = doc["environment"]
    git = env["git"]
    return [
        ("created", doc["created"]),
        ("git commit", f"{git['commit']}{' (dirty tree)' if git['dirty'] else ''}"),
        ("python / platform", f"{env['python']} / {env['platform']}"),
        ("packages", ", ".join(f"{k} {v}" for k, v in env["packages"].items() if v)),
        ("timings", ", ".join(f"{k} {v:.1f} s" for k, v in doc["timings"].items() if v is not None)),
    ]


def _tolerances(doc: dict[str, Any]) -> Table:
    head = ["comparison", "quantity", "limit", "unit", "reason"]
    rows = [[t["comparison"], t["quantity"], fmt(t["limit"]), ERROR_UNITS.get(t["quantity"], ""),
             t["reason"]] for t in doc["tolerances"]]
    return head, rows


# -- Markdown --------------------------------------------------------------------------------
def _md_table(head: list[str], rows: list[list[str]]) -> list[str]:
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return out + [""]


def markdown(doc: dict[str, Any]) -> str:
    """The report as Markdown (plots linked, not embedded)."""
    out = [f"# threepart verification report ({doc['mode']})", "", f"**{_verdict(doc)}**", "",
           "## How to read it", ""]
    out += [("- " + line if not line.startswith("  -") else line) for line in _how_to_read(doc)] + [""]
    out += ["## Tightest margins", ""] + _md_table(*_tightest(doc))
    out += ["## Cases inside the paper's framework", ""] + _md_table(*_case_lines(doc, False))
    out += ["## Beyond the closed form", ""] + _md_table(*_case_lines(doc, True))
    out += ["## Details of each case", ""]
    for c in doc["cases"]:
        out += [f"### {c['name']}: {c['description']}", "", _load(c), ""]
        out += _md_table(*_results(c))
        if c["checks"]:
            out += _md_table(*_checks(c))
        out += [f"- {m}: {x}" for m, x in c.get("refusals", {}).items()]
        out += [f"- error, {m}: {x}" for m, x in c["errors"].items()]
        out += [f"![{p}]({p})" for p in c["plots"]] + [""]
    out += ["## Convergence studies", ""]
    for st in doc["studies"]:
        out += [f"### {st['method']} {st.get('scheme') or ''} in {st['param']} (case {st['case']})", ""]
        out += _md_table(*_study(st))
        out += [f"- note: {n}" for n in st["notes"]]
    out += [f"![{p}]({p})" for p in doc["plots"]] + [""]
    out += ["## Where the half-plane formulas stop", "", MAP_TEXT + f" [{MAP_LINK}]({MAP_LINK})", ""]
    out += ["## Tolerance table", ""]
    out += _md_table(*_tolerances(doc))
    out += ["## Environment", ""] + [f"- **{k}**: {v}" for k, v in _environment(doc)]
    return "\n".join(out) + "\n"


# -- HTML ------------------------------------------------------------------------------------
_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1150px;margin:1em auto;
     padding:0 1em;color:#222;line-height:1.35}
h1{font-size:1.5em;margin:.3em 0} h2{font-size:1.2em;margin:1.1em 0 .3em}
table{border-collapse:collapse;margin:.4em 0 1em;font-size:.84em}
th,td{border:1px solid #ccc;padding:.15em .45em;text-align:right}
th{background:#f0f0f0} td.text{text-align:left}
.pass{color:#137333;font-weight:600} .fail{color:#c5221f;font-weight:700}
.banner{padding:.5em 1em;border-radius:6px;font-size:1.15em;font-weight:700;margin:.4em 0}
.banner.pass{background:#e6f4ea} .banner.fail{background:#fce8e6}
.how{font-size:.85em;color:#333} .how li{margin:.1em 0}
details{margin:.3em 0} summary{cursor:pointer;font-weight:600}
img{max-width:100%;border:1px solid #eee;margin:.3em 0}
dl{display:grid;grid-template-columns:max-content auto;gap:.2em 1em;font-size:.85em} dt{font-weight:600}
"""


def _numeric(x: str) -> bool:
    head = x.split(" ")[0]
    try:
        float(head)
    except ValueError:
        return x in ("–", "")
    return True


def _img(path: Path, rel: str) -> str:
    data = base64.b64encode((path / rel).read_bytes()).decode("ascii")
    return f'<img alt="{_html.escape(rel)}" src="data:image/png;base64,{data}">'


def _html_table(head: list[str], rows: list[list[str]], verdict: Callable[[str], bool] | None = None,
                link: bool = False) -> str:
    e = _html.escape
    h = "".join(f"<th>{e(x)}</th>" for x in head)
    body = []
    for r in rows:
        cells = []
        for i, x in enumerate(r):
            cls = "" if _numeric(x) else ' class="text"'
            if x in ("pass", "FAIL") or x.startswith("refuses, correctly"):
                cls = ' class="pass"' if x != "FAIL" else ' class="fail"'
            elif x == "did not refuse as it must":
                cls = ' class="fail"'
            text = f"<a href='#{e(x)}'>{e(x)}</a>" if i == 0 and link else e(x)
            cells.append(f"<td{cls}>{text}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><tr>{h}</tr>{''.join(body)}</table>"


def html(doc: dict[str, Any], root: Path) -> str:
    """The report as one HTML file with the PNGs under ``root`` embedded."""
    e = _html.escape
    ok = doc["passed"]
    how = _how_to_read(doc)
    items: list[str] = []
    sub: list[str] = []
    for line in how:   # "  - " lines are a sub-list of the line before
        if line.startswith("  - "):
            sub.append(f"<li>{e(line[4:])}</li>")
            continue
        if sub:
            items[-1] = items[-1][:-5] + f"<ul>{''.join(sub)}</ul></li>"
            sub = []
        items.append(f"<li>{e(line)}</li>")
    if sub:
        items[-1] = items[-1][:-5] + f"<ul>{''.join(sub)}</ul></li>"
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
             f"<title>threepart verification ({e(doc['mode'])})</title><style>{_CSS}</style></head><body>",
             f"<h1>threepart verification report ({e(doc['mode'])})</h1>",
             f"<div class='banner {'pass' if ok else 'fail'}'>{e(_verdict(doc))}</div>",
             "<h2>Tightest margins</h2>", _html_table(*_tightest(doc), link=True),
             f"<details class='how' open><summary>How to read it: units, normalisation, loads</summary>"
             f"<ul>{''.join(items)}</ul></details>",
             "<h2>Cases inside the paper's framework</h2>", _html_table(*_case_lines(doc, False), link=True),
             "<h2>Beyond the closed form</h2>", _html_table(*_case_lines(doc, True), link=True),
             "<h2>Details of each case</h2>"]
    for c in doc["cases"]:
        verdict = "pass" if c["passed"] else "FAIL"
        inner = [f"<p>{e(_load(c))}</p>", _html_table(*_results(c))]
        if c["checks"]:
            inner.append(_html_table(*_checks(c)))
        inner += [f"<p>{e(m)}: {e(x)}</p>" for m, x in c.get("refusals", {}).items()]
        inner += [f"<p class='fail'>{e(m)}: {e(x)}</p>" for m, x in c["errors"].items()]
        inner += [_img(root, p) for p in c["plots"]]
        parts.append(f"<details id='{e(c['name'])}'{'' if c['passed'] else ' open'}><summary>"
                     f"{e(c['name'])}: {e(c['description'])} <span class='{verdict.lower()}'>"
                     f"{verdict}</span></summary>{''.join(inner)}</details>")
    studies = []
    for st in doc["studies"]:
        studies.append(f"<h3>{e(st['method'])} {e(st.get('scheme') or '')} in {e(st['param'])} "
                       f"(case {e(st['case'])})</h3>" + _html_table(*_study(st))
                       + "".join(f"<p>note: {e(n)}</p>" for n in st["notes"]))
    studies += [_img(root, p) for p in doc["plots"]]
    parts.append(f"<h2>Convergence studies</h2><details><summary>{len(doc['studies'])} studies, "
                 f"errors per level, observed orders and plots</summary>{''.join(studies)}</details>")
    parts.append(f"<h2>Where the half-plane formulas stop</h2><p>{e(MAP_TEXT)} "
                 f"<a href='{MAP_LINK}'>{MAP_LINK}</a></p>")
    tol = _html_table(*_tolerances(doc))
    parts.append(f"<h2>Tolerance table</h2><details><summary>{len(doc['tolerances'])} entries, "
                 f"each with its reason</summary>{tol}</details>")
    env = "<dl>" + "".join(f"<dt>{e(k)}</dt><dd>{e(v)}</dd>" for k, v in _environment(doc)) + "</dl>"
    parts.append(f"<h2>Environment</h2><details><summary>commit, versions, timings</summary>{env}</details>")
    parts.append("</body></html>")
    return "\n".join(parts)

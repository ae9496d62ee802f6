"""Render a ``report.json`` document as Markdown and as self-contained HTML.

The HTML embeds every PNG as a base64 data URI, so that it opens in a
browser from a single file with no server.
"""
from __future__ import annotations

import base64
import html as _html
from pathlib import Path
from typing import Any

__all__ = ["markdown", "html", "fmt"]



def fmt(v: Any) -> str:
    """Short numeric format for tables."""
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.3e}" if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e5) else f"{v:.6g}"
    return str(v)


def _study_table(st: dict) -> tuple[list[str], list[list[str]]]:
    """Header and rows of a convergence-study table: errors per level, then order and GCI."""
    head = [st["param"], "label"] + list(st["errors"])
    rows = [[fmt(v), lab] + [fmt(st["errors"][q][i]) for q in st["errors"]]
            for i, (v, lab) in enumerate(zip(st["values"], st["labels"]))]
    rows.append(["order", ""] + [fmt(st["orders"].get(q)) for q in st["errors"]])
    if st["gci"]:
        rows.append(["GCI", ""] + [fmt(st["gci"].get(q)) for q in st["errors"]])
    return head, rows

def _header(doc: dict[str, Any]) -> list[tuple[str, str]]:
    env = doc["environment"]
    git = env["git"]
    s = doc["summary"]
    t = doc["timings"]
    return [
        ("verdict", "PASSED" if doc["passed"] else "FAILED"),
        ("mode", doc["mode"]),
        ("checks", f"{s['checks'] - s['failed_checks']}/{s['checks']} within tolerance, "
                   f"{s['errors']} solver errors"),
        ("created", doc["created"]),
        ("git commit", f"{git['commit']}{' (dirty tree)' if git['dirty'] else ''}"),
        ("python / platform", f"{env['python']} / {env['platform']}"),
        ("packages", ", ".join(f"{k} {v}" for k, v in env["packages"].items() if v)),
        ("timings", ", ".join(f"{k} {v:.1f} s" for k, v in t.items() if v is not None)),
    ]


def _case_rows(case: dict[str, Any]) -> list[list[str]]:
    return [[c["comparison"], c["quantity"], fmt(c["reference"]), fmt(c["obtained"]), fmt(c["error"]),
             fmt(c["limit"]), "pass" if c["passed"] else "FAIL"] for c in case["checks"]]


def _load(case: dict[str, Any]) -> str:
    p = case["punch"]
    R = "∞" if p["R"] is None else fmt(p["R"])
    txt = (f"R1 = {fmt(p['R1'])}, R2 = {fmt(p['R2'])}, b = {fmt(p['b'])}, R = {R} mm; "
           f"P = {fmt(case['P'])} N/mm, s = {fmt(case['s'])} mm, tilt {case['tilt']}")
    if case["Q_over_fP"] is not None:
        txt += f"; f = {fmt(case['f'])}, Q/fP = {fmt(case['Q_over_fP'])}"
    return txt


def _results_rows(case: dict[str, Any]) -> list[list[str]]:
    rows = []
    for m, r in case["results"].items():
        rows.append([m, fmt(r["a"]), fmt(r["c"]), fmt(r["alpha"]), fmt(r["s"]),
                     fmt(r["peak_left"]["p"]), fmt(r["peak_right"]["p"]),
                     fmt(r.get("d")), fmt(r.get("e")), fmt(r["time_s"])])
    return rows


_RES_HEAD = ["method", "a", "c", "α", "s", "p_left", "p_right", "d", "e", "time (s)"]
_CHK_HEAD = ["comparison", "quantity", "closed form", "obtained", "error", "limit", "verdict"]


def markdown(doc: dict[str, Any]) -> str:
    """The report as Markdown (plots linked, not embedded)."""
    out = [f"# threepart verification report ({doc['mode']})", ""]
    out += [f"- **{k}**: {v}" for k, v in _header(doc)]
    out.append("")

    def table(head: list[str], rows: list[list[str]]) -> None:
        out.append("| " + " | ".join(head) + " |")
        out.append("|" + "---|" * len(head))
        out.extend("| " + " | ".join(r) + " |" for r in rows)
        out.append("")

    out += ["## Summary", ""]
    table(["case", "description", "verdict", "failed checks"],
          [[c["name"], c["description"], "pass" if c["passed"] else "FAIL",
            ", ".join(f"{k['comparison']}:{k['quantity']}" for k in c["checks"] if not k["passed"])
            + ("; errors: " + "; ".join(f"{m}: {e}" for m, e in c["errors"].items()) if c["errors"] else "")]
           for c in doc["cases"]])
    for c in doc["cases"]:
        out += [f"## {c['name']}: {c['description']}", "", _load(c), ""]
        table(_RES_HEAD, _results_rows(c))
        if c["checks"]:
            table(_CHK_HEAD, _case_rows(c))
        out += [f"![{p}]({p})" for p in c["plots"]] + [""]
    out += ["## Convergence studies", ""]
    for st in doc["studies"]:
        out += [f"### {st['method']} {st.get('scheme') or ''} in {st['param']} (case {st['case']})", ""]
        head, rows = _study_table(st)
        table(head, rows)
        out += [f"- note: {n}" for n in st["notes"]]
    out += [f"![{p}]({p})" for p in doc["plots"]] + [""]
    out += ["## Tolerance table", ""]
    table(["comparison", "quantity", "limit", "reason"],
          [[t["comparison"], t["quantity"], fmt(t["limit"]), t["reason"]] for t in doc["tolerances"]])
    return "\n".join(out)


_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1150px;margin:1.5em auto;
     padding:0 1em;color:#222}
table{border-collapse:collapse;margin:.6em 0 1.2em;font-size:.86em}
th,td{border:1px solid #ccc;padding:.2em .5em;text-align:right}
th{background:#f0f0f0} td.text{text-align:left}
.pass{color:#137333;font-weight:600} .fail{color:#c5221f;font-weight:700}
.banner{padding:.6em 1em;border-radius:6px;font-size:1.3em;font-weight:700;margin:.5em 0}
.banner.pass{background:#e6f4ea} .banner.fail{background:#fce8e6}
img{max-width:100%;border:1px solid #eee;margin:.3em 0}
dl{display:grid;grid-template-columns:max-content auto;gap:.2em 1em;font-size:.9em}
dt{font-weight:600}
"""


def _numeric(x: str) -> bool:
    try:
        float(x)
    except ValueError:
        return x in ("–", "")
    return True


def _img(path: Path, rel: str) -> str:
    data = base64.b64encode((path / rel).read_bytes()).decode("ascii")
    return f'<img alt="{_html.escape(rel)}" src="data:image/png;base64,{data}">'


def html(doc: dict[str, Any], root: Path) -> str:
    """The report as one HTML file with the PNGs under ``root`` embedded."""
    e = _html.escape

    def table(head: list[str], rows: list[list[str]], verdict_col: int | None = None,
              link: bool = False) -> str:
        h = "".join(f"<th>{e(x)}</th>" for x in head)
        body = []
        for r in rows:
            cells = []
            for i, x in enumerate(r):
                cls = "" if _numeric(x) else ' class="text"'
                if i == verdict_col:
                    cls = ' class="pass"' if x == "pass" else ' class="fail"'
                text = e(x)
                if i == 0 and link:
                    text = f"<a href='#{text}'>{text}</a>"
                cells.append(f"<td{cls}>{text}</td>")
            body.append("<tr>" + "".join(cells) + "</tr>")
        return f"<table><tr>{h}</tr>{''.join(body)}</table>"

    ok = doc["passed"]
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
             f"<title>threepart verification ({e(doc['mode'])})</title><style>{_CSS}</style></head><body>",
             f"<h1>threepart verification report ({e(doc['mode'])})</h1>",
             f"<div class='banner {'pass' if ok else 'fail'}'>{'PASSED' if ok else 'FAILED'}</div>",
             "<dl>" + "".join(f"<dt>{e(k)}</dt><dd>{e(v)}</dd>" for k, v in _header(doc)) + "</dl>",
             "<h2>Summary</h2>"]
    parts.append(table(["case", "description", "verdict", "failed checks / errors"],
                       [[c["name"], c["description"], "pass" if c["passed"] else "FAIL",
                         ", ".join(f"{k['comparison']}:{k['quantity']}" for k in c["checks"]
                                   if not k["passed"])
                         + "; ".join(f"{m}: {x}" for m, x in c["errors"].items())]
                        for c in doc["cases"]], verdict_col=2, link=True))
    for c in doc["cases"]:
        parts.append(f"<h2 id='{e(c['name'])}'>{e(c['name'])}: {e(c['description'])} "
                     f"<span class='{'pass' if c['passed'] else 'fail'}'>"
                     f"{'pass' if c['passed'] else 'FAIL'}</span></h2><p>{e(_load(c))}</p>")
        parts.append(table(_RES_HEAD, _results_rows(c)))
        if c["checks"]:
            parts.append(table(_CHK_HEAD, _case_rows(c), verdict_col=6))
        for m, x in c["errors"].items():
            parts.append(f"<p class='fail'>{e(m)}: {e(x)}</p>")
        parts += [_img(root, p) for p in c["plots"]]
    parts.append("<h2>Convergence studies</h2>")
    for st in doc["studies"]:
        parts.append(f"<h3>{e(st['method'])} {e(st.get('scheme') or '')} in {e(st['param'])} "
                     f"(case {e(st['case'])})</h3>")
        head, rows = _study_table(st)
        parts.append(table(head, rows))
        parts += [f"<p>note: {e(n)}</p>" for n in st["notes"]]
    parts += [_img(root, p) for p in doc["plots"]]
    parts.append("<h2>Tolerance table</h2>")
    parts.append(table(["comparison", "quantity", "limit", "reason"],
                       [[t["comparison"], t["quantity"], fmt(t["limit"]), t["reason"]]
                        for t in doc["tolerances"]]))
    parts.append("</body></html>")
    return "\n".join(parts)

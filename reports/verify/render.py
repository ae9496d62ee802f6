"""Render a ``report.json`` document as Markdown and as self-contained HTML.

Both are renderings of the one ordered list of sections that
:func:`reports.verify.sections.build` makes from the document: the same sections, in
the same order, with the same text. Pass and fail are styled from the typed
:class:`~reports.verify.sections.Status`, never from a cell's words. The HTML embeds
every PNG as a base64 data URI, so that it opens in a browser from a single
file; its plots are visible without unfolding anything, while the long tables
fold away (``<details>``) and stay complete in ``report.json``.
"""
from __future__ import annotations

import base64
import dataclasses
import html as _html
from pathlib import Path
from typing import Any

from .sections import (Block, Bullets, Code, Document, Figure, Link, Section, Status, Table,
                       Verdict, build, fmt)
from threepart.errors import InputError

__all__ = ["markdown", "html", "fmt", "png_width", "WIDE_PX", "PAGE_PX"]


# -- Markdown --------------------------------------------------------------------------------
def _md_inline(piece: Any) -> str:
    if isinstance(piece, Code):
        return f"`{piece.text}`"
    if isinstance(piece, Link):   # an anchor of the HTML page has no Markdown target
        return piece.text if piece.href.startswith("#") else f"[{piece.text}]({piece.href})"
    return str(piece)


def _md_para(para: tuple[Any, ...]) -> str:
    return "".join(_md_inline(p) for p in para)


def _md_block(block: Block) -> list[str]:
    if isinstance(block, Bullets):
        out = []
        for item in block.items:
            out.append("- " + _md_para(item.text))
            out += ["  - " + _md_para(s) for s in item.sub]
        return out + [""]
    return [_md_para(block), ""]


def _md_cell(cell: Any) -> str:
    text = _md_para(cell) if isinstance(cell, tuple) else _md_inline(cell)
    return text.replace("|", "\\|")


def _md_table(t: Table) -> list[str]:
    out = ["| " + " | ".join(t.head) + " |", "|" + "---|" * len(t.head)]
    out += ["| " + " | ".join(_md_cell(c) for c in r) + " |" for r in t.rows]
    return out + [""]


def _md_figure(f: Figure) -> list[str]:
    status = f" ({f.status.value})" if f.status else ""
    return [f"![{f.caption}]({f.path})", "", f"{f.caption}{status}", ""]


def _md_section(sec: Section, level: int) -> list[str]:
    status = f" — {sec.status.value}" if sec.status else ""
    out = [f"{'#' * level} {sec.title}{status}", ""]
    for b in sec.intro:
        out += _md_block(b)
    for t in sec.tables:
        out += _md_table(t)
    for f in sec.figures:
        out += _md_figure(f)
    for child in sec.children:
        out += _md_section(child, level + 1)
    return out


def render_markdown(d: Document) -> str:
    """A :class:`~reports.verify.sections.Document` as Markdown (plots linked, not embedded)."""
    out = [f"# {d.title}", "", f"**{d.verdict}**", ""]
    for sec in d.sections:
        out += _md_section(sec, 2)
    return "\n".join(out).rstrip("\n") + "\n"


def _document(doc: dict[str, Any], map_link: str | None = None) -> Document:
    """:func:`build`'s sections, the fretting-wear section (issue 39) before the environment's."""
    from .wear_section import wear_section

    d = build(doc, map_link)
    wear = wear_section(doc)
    if wear is None:
        return d
    at = next((i for i, sec in enumerate(d.sections) if sec.anchor == "environment"), len(d.sections))
    return dataclasses.replace(d, sections=(*d.sections[:at], wear, *d.sections[at:]))


def markdown(doc: dict[str, Any], map_link: str | None = None) -> str:
    """The report as Markdown (plots linked, not embedded); see :func:`reports.verify.sections.build`."""
    return render_markdown(_document(doc, map_link))


# -- HTML ------------------------------------------------------------------------------------
#: the page's width (px): a two-panel plot (1152 px at the plots' 90 dpi) is shown at its own size
PAGE_PX = 1180
_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:%dpx;margin:1em auto;
     padding:0 1em;color:#222;line-height:1.35}
h1{font-size:1.5em;margin:.3em 0} h2{font-size:1.2em;margin:1.1em 0 .3em} h3{font-size:1.05em}
p,ul{font-size:.9em} li{margin:.1em 0}
code{background:#f3f3f3;padding:0 .25em;border-radius:3px;font-size:.95em}
table{border-collapse:collapse;margin:.4em 0 1em;font-size:.84em}
th,td{border:1px solid #ccc;padding:.15em .45em;text-align:right}
th{background:#f0f0f0} td.text{text-align:left}
.pass{color:#137333;font-weight:600} .fail{color:#c5221f;font-weight:700}
.banner{padding:.5em 1em;border-radius:6px;font-size:1.15em;font-weight:700;margin:.4em 0}
.banner.pass{background:#e6f4ea} .banner.fail{background:#fce8e6}
details{margin:.3em 0} summary{cursor:pointer;font-weight:600}
.figs{display:grid;grid-template-columns:repeat(auto-fill,minmax(480px,1fr));gap:.6em}
figure{margin:0} figure.wide{grid-column:1/-1} figcaption{font-size:.8em;color:#444}
img{max-width:100%%;border:1px solid #eee;margin:.3em 0}
""" % PAGE_PX
_CLASS = {Status.PASS: "pass", Status.FAIL: "fail"}


def _h_inline(piece: Any) -> str:
    e = _html.escape
    if isinstance(piece, Code):
        return f"<code>{e(piece.text)}</code>"
    if isinstance(piece, Link):
        return f"<a href='{e(piece.href)}'>{e(piece.text)}</a>"
    if isinstance(piece, Verdict):
        return f"<span class='{_CLASS[piece.status]}'>{e(str(piece))}</span>"
    return e(str(piece))


def _h_para(para: tuple[Any, ...]) -> str:
    return "".join(_h_inline(p) for p in para)


def _h_block(block: Block) -> str:
    if isinstance(block, Bullets):
        items = []
        for item in block.items:
            sub = "".join(f"<li>{_h_para(s)}</li>" for s in item.sub)
            items.append(f"<li>{_h_para(item.text)}{f'<ul>{sub}</ul>' if sub else ''}</li>")
        return f"<ul>{''.join(items)}</ul>"
    return f"<p>{_h_para(block)}</p>"


def _numeric(x: str) -> bool:
    head = x.split(" ")[0]
    try:
        float(head)
    except ValueError:
        return x in ("–", "")
    return True


def _h_cell(cell: Any) -> str:
    if isinstance(cell, Verdict):
        return f"<td class='{_CLASS[cell.status]}'>{_html.escape(str(cell))}</td>"
    if isinstance(cell, tuple):
        return f"<td class='text'>{_h_para(cell)}</td>"
    text = cell.text if isinstance(cell, Link) else str(cell)
    cls = "" if _numeric(text) else " class='text'"
    return f"<td{cls}>{_h_inline(cell)}</td>"


def _h_table(t: Table) -> str:
    e = _html.escape
    head = "".join(f"<th>{e(x)}</th>" for x in t.head)
    body = "".join("<tr>" + "".join(_h_cell(c) for c in r) + "</tr>" for r in t.rows)
    table = f"<table><tr>{head}</tr>{body}</table>"
    return f"<details><summary>{e(t.summary)}</summary>{table}</details>" if t.fold else table


#: a plot wider than this (px) spans the whole row of the figure grid: a multi-panel plot
#: (1152 px at the plots' 90 dpi; a one-panel plot is 576 px) squeezed into a half-row cell
#: (about 560 px) showed its text about 5 px high
WIDE_PX = 800


def png_width(data: bytes) -> int:
    """The width in pixels of a PNG, from its IHDR chunk (bytes 16-20)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise InputError("not a PNG file")
    return int.from_bytes(data[16:20], "big")


def _h_figures(figures: tuple[Figure, ...], root: Path) -> str:
    if not figures:
        return ""
    out = []
    for f in figures:
        data = (root / f.path).read_bytes()
        img = (f"<img alt='{_html.escape(f.path)}' "
               f"src='data:image/png;base64,{base64.b64encode(data).decode('ascii')}'>")
        if f.link:
            img = f"<a href='{_html.escape(f.link)}'>{img}</a>"
        status = (f"<span class='{_CLASS[f.status]}'>{f.status.value}</span> " if f.status else "")
        wide = " class='wide'" if png_width(data) > WIDE_PX else ""
        out.append(f"<figure{wide}>{img}<figcaption>{status}{_html.escape(f.caption)}</figcaption></figure>")
    return f"<div class='figs'>{''.join(out)}</div>"


def _badge(status: Status | None) -> str:
    return "" if status is None else f" <span class='{_CLASS[status]}'>{status.value}</span>"


def _h_section(sec: Section, level: int, root: Path) -> str:
    e = _html.escape
    body = ("".join(_h_block(b) for b in sec.intro) + "".join(_h_table(t) for t in sec.tables)
            + _h_figures(sec.figures, root) + "".join(_h_section(c, level + 1, root) for c in sec.children))
    if sec.fold:
        opened = " open" if sec.status is Status.FAIL else ""
        return (f"<details id='{e(sec.anchor)}'{opened}><summary>{e(sec.title)}{_badge(sec.status)}"
                f"</summary>{body}</details>")
    return f"<section id='{e(sec.anchor)}'><h{level}>{e(sec.title)}{_badge(sec.status)}</h{level}>{body}</section>"


def render_html(d: Document, root: Path) -> str:
    """A :class:`~reports.verify.sections.Document` as one HTML page, the PNGs under ``root`` embedded."""
    e = _html.escape
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{e(d.title)}</title>"
             f"<style>{_CSS}</style></head><body>", f"<h1>{e(d.title)}</h1>",
             f"<div class='banner {_CLASS[d.status]}'>{e(d.verdict)}</div>"]
    parts += [_h_section(sec, 2, root) for sec in d.sections]
    parts.append("</body></html>")
    return "\n".join(parts)


def html(doc: dict[str, Any], root: Path, map_link: str | None = None) -> str:
    """The report as one HTML file with the PNGs under ``root`` embedded; see :func:`reports.verify.sections.build`."""
    return render_html(_document(doc, map_link), root)

"""Sphinx configuration of threepart's documentation: the API reference and the derivations.

Build it from the repository root (the ``docs`` extra: ``pip install -e ".[docs]"``)::

    python -m sphinx -W -b html docs docs/_build/html

``-W`` turns every warning into an error; ``tests/test_docs.py`` builds it so.
"""
from __future__ import annotations

import re
import sys
from typing import Any

from sphinx.pycode import ModuleAnalyzer, PycodeError

project = "threepart"
author = "threepart's authors"
copyright = "2026, threepart's authors"

extensions = [
    "sphinx.ext.autodoc",       # the API reference from the docstrings
    "sphinx.ext.napoleon",      # numpydoc-style sections (Parameters, Returns, Raises, ...)
    "sphinx.ext.mathjax",
    "myst_parser",              # the derivations docs/*.md (ERRATA, STEADY_STATE, WEAR, ...)
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]

# the docstrings are numpydoc; types live in the signatures (STYLE.md), not in the sections
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_default_options = {"members": True, "show-inheritance": True}
# the derivations' own headings, as anchors for links such as ERRATA.md#eq-4
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
# docs/MAP.md opens at a level-2 heading ("## The validity map"), as a part of a larger page
suppress_warnings = ["myst.header"]

html_theme = "alabaster"
html_title = "threepart"

#: an underlined heading of a package docstring's listing (scipy's style: ``name -- one line``)
_HEADING = re.compile(r"^[-=~]{3,}\s*$")


def _listing_as_rubrics(app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    """A package docstring's underlined headings as rubrics, and each listing under one as a literal block.

    The packages' docstrings list their names as scipy's do (``name -- one line``
    under an underlined heading); read as reStructuredText those headings would be
    sections inside the page and the listings run-on paragraphs. A paragraph
    with a ``--`` line is a listing, kept verbatim; any other stays prose.
    """
    if what != "module":
        _foreign_headings_as_rubrics(lines)
        return
    out: list[str] = []
    paragraph: list[str] = []

    def flush() -> None:
        if any(" -- " in line for line in paragraph):
            out.extend(["::", "", *(f"    {line}" for line in paragraph), ""])
        elif paragraph:
            out.extend([*paragraph, ""])
        paragraph.clear()

    i = 0
    while i < len(lines):
        if i + 1 < len(lines) and lines[i].strip() and _HEADING.match(lines[i + 1]):
            flush()
            out.extend([f".. rubric:: {lines[i].strip()}", ""])
            i += 2
            continue
        if lines[i].strip():
            paragraph.append(lines[i])
        else:
            flush()
        i += 1
    flush()
    lines[:] = out


#: the section headings napoleon reads as its own (sphinx.ext.napoleon.docstring.NumpyDocstring)
_NAPOLEON_SECTIONS = frozenset((
    "args", "arguments", "attention", "attributes", "caution", "danger", "error", "example",
    "examples", "hint", "important", "keyword args", "keyword arguments", "methods", "note", "notes",
    "other parameters", "parameters", "receive", "receives", "return", "returns", "raise", "raises",
    "references", "see also", "tip", "todo", "warning", "warnings", "warn", "warns", "yield", "yields",
))


def _foreign_headings_as_rubrics(lines: list[str]) -> None:
    """An underlined heading napoleon does not know (``Attributes (beyond NormalResult)``) as a rubric.

    reStructuredText would read it as a section title inside an object's
    description, which it refuses.
    """
    for i in range(len(lines) - 1):
        title = lines[i].strip()
        if title and _HEADING.match(lines[i + 1]) and title.lower() not in _NAPOLEON_SECTIONS:
            lines[i], lines[i + 1] = f".. rubric:: {title}", ""


def _constant_comment(app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    """A re-exported constant's ``#:`` comment, read from the module that defines it.

    autodoc reads ``#:`` comments of the module it documents only (and else
    falls back on the docstring of the value's class, ``dict``'s say); a package
    re-exports its constants from the modules beside it.
    """
    if what != "data":
        return
    package, _, attr = name.rpartition(".")
    for modname, module in sorted(sys.modules.items()):
        if not modname.startswith(f"{package}.") or getattr(module, attr, None) is not obj:
            continue
        try:
            comment = ModuleAnalyzer.for_module(modname).find_attr_docs().get(("", attr))
        except PycodeError:
            continue
        if comment:
            lines[:] = list(comment)
            return
    if type(obj).__doc__ and getattr(obj, "__doc__", None) == type(obj).__doc__:
        lines.clear()      # a dict's or a tuple's class docstring says nothing of this constant


def setup(app: Any) -> None:
    # before napoleon's handler (priority 500), which would read "Errors" or "Notes" as its own sections
    app.connect("autodoc-process-docstring", _listing_as_rubrics, priority=100)
    app.connect("autodoc-process-docstring", _constant_comment)

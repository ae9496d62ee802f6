"""The documentation (``docs/``): its API pages name what exists, and the site builds with ``-W``.

The fast tests read the pages' directives and import every name they
document, so a renamed or removed public name fails here without Sphinx;
the slow test builds the site as ``docs/conf.py`` says (the ``docs`` extra)
and finds every public name of every page in the HTML.
"""
from __future__ import annotations

import importlib
import re
import subprocess
import sys
import types
from pathlib import Path

import pytest

import threepart

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: each API page and the package it documents: threepart's own and every public sub-package
PAGES = {"threepart": "threepart", "closedform": "threepart.closedform", "sie": "threepart.sie",
         "fem": "threepart.fem", "meshes": "threepart.meshes", "readers": "threepart.readers",
         "calculix": "threepart.calculix", "getfem": "threepart.getfem",
         "reports": "threepart.reports", "results": "threepart.results", "stress": "threepart.stress",
         "fatigue": "threepart.fatigue", "studies": "threepart.studies", "wear": "threepart.fretting_wear"}
#: the build command of the docs (conf.py's docstring, the index and the README say it)
BUILD = "python -m sphinx -W -b html docs docs/_build/html"


def _page(name: str) -> str:
    return (DOCS / "api" / f"{name}.rst").read_text(encoding="utf-8")


def _directives(text: str, kind: str) -> list[str]:
    return re.findall(rf"^\.\. {kind}:: (\S+)", text, flags=re.M)


def _excluded(text: str) -> list[str]:
    found = re.findall(r"^\s+:exclude-members: (.+)$", text, flags=re.M)
    return [n.strip() for line in found for n in line.split(",")]


def _resolve(dotted: str) -> object:
    """The object a dotted name documents: the longest importable module, then attributes."""
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj: object = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(dotted)


def _anchor(package: str, name: str, obj: object) -> str:
    """The HTML id Sphinx gives a documented name (a module: its own page section)."""
    return f"module-{obj.__name__}" if isinstance(obj, types.ModuleType) else f"{package}.{name}"


def _is_constant(obj: object) -> bool:
    return not (callable(obj) or isinstance(obj, types.ModuleType))


def _commented_here(package: types.ModuleType, name: str) -> bool:
    """Whether ``name`` is set in the package's own source under a ``#:`` comment (autodoc's)."""
    source = Path(package.__file__ or "").read_text(encoding="utf-8")
    return re.search(rf"^#:.*\n(?:#:.*\n)*{name}\s*[:=]", source, flags=re.M) is not None


def test_every_public_package_has_a_page_in_the_index():
    assert set(PAGES.values()) >= {"threepart", *(f"threepart.{p}" for p in threepart._SUBPACKAGES)}
    index = (DOCS / "index.rst").read_text(encoding="utf-8")
    for name, package in PAGES.items():
        assert f"api/{name}" in index.split(), f"docs/index.rst does not list api/{name}"
        assert _directives(_page(name), "automodule")[0] == package
    assert sorted(p.stem for p in (DOCS / "api").glob("*.rst")) == sorted(PAGES)


def test_every_derivation_is_linked_from_the_index():
    index = (DOCS / "index.rst").read_text(encoding="utf-8").split()
    missing = [p.name for p in DOCS.glob("*.md") if p.stem not in index]
    assert not missing, f"docs/index.rst's toctree does not list {missing}"


@pytest.mark.parametrize("name", sorted(PAGES))
def test_every_documented_name_imports(name):
    """Each page's package's ``__all__``, and every name its directives give, exists.

    A re-export left out of a page (``:exclude-members:``) must be the very object of
    ``threepart``'s own name, which the threepart page documents; a constant (no
    docstring of its own) needs its ``autodata`` line unless the package sets it under a
    ``#:`` comment, a module in ``__all__`` its
    ``automodule``: autodoc documents neither by itself.
    """
    text = _page(name)
    package = importlib.import_module(PAGES[name])
    public = {n: getattr(package, n) for n in package.__all__}    # AttributeError: a stale __all__
    for dotted in _directives(text, "automodule") + _directives(text, "autodata"):
        _resolve(dotted)
    for n in _excluded(text):
        assert n in public and public[n] is getattr(threepart, n), (
            f"{PAGES[name]}.{n} is left out of its page but is not threepart.{n}")
    duplicated = [n for n, obj in public.items() if name != "threepart" and n in threepart.__all__
                  and obj is getattr(threepart, n) and n not in _excluded(text)]
    assert not duplicated, f"re-exports of threepart's names, documented twice: {duplicated}"
    data = {d.rpartition(".")[2] for d in _directives(text, "autodata")}
    modules = set(_directives(text, "automodule"))
    for n, obj in public.items():
        if isinstance(obj, types.ModuleType):
            assert obj.__name__ in modules, f"{obj.__name__} needs an automodule on api/{name}.rst"
        elif _is_constant(obj) and not _commented_here(package, n):
            assert n in data, f"{PAGES[name]}.{n} needs an autodata on api/{name}.rst"


def test_every_cross_reference_of_the_pages_resolves():
    roles = re.compile(r":(?:func|class|mod|data|exc|meth|attr):`~?([\w.]+)`")
    for page in [DOCS / "index.rst", *(DOCS / "api").glob("*.rst")]:
        for dotted in roles.findall(page.read_text(encoding="utf-8")):
            _resolve(dotted)


def test_the_readme_and_the_index_give_the_build_command():
    assert BUILD in (ROOT / "README.md").read_text(encoding="utf-8")
    assert BUILD in (DOCS / "index.rst").read_text(encoding="utf-8")
    assert BUILD in (DOCS / "conf.py").read_text(encoding="utf-8")


@pytest.mark.slow
def test_the_docs_build_with_warnings_as_errors_and_document_every_public_name(tmp_path):
    """``sphinx-build -W`` (the ``docs`` extra); every page's ``__all__`` is an anchor of its HTML."""
    pytest.importorskip("sphinx", reason='sphinx is the docs extra: pip install -e ".[docs]"')
    pytest.importorskip("myst_parser", reason='myst-parser is the docs extra: pip install -e ".[docs]"')
    out = tmp_path / "html"
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html", "-d",
                           str(tmp_path / "doctrees"), str(DOCS), str(out)],
                          cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    for name, package in PAGES.items():
        html = (out / "api" / f"{name}.html").read_text(encoding="utf-8")
        module = importlib.import_module(package)
        absent = [n for n in module.__all__ if n not in _excluded(_page(name))
                  and f'id="{_anchor(package, n, getattr(module, n))}"' not in html]
        assert not absent, f"api/{name}.html does not document {absent}"

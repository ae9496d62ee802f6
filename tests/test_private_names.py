"""No private name crosses a module (issue 40): what two modules share is public, named in ``__all__`` or its docstring.

``from .x import _y`` makes ``_y`` an API that its module does not know it has. The package's
modules (not the tests, which may reach into a module to check it) import only public names of
one another; a shared helper drops its underscore where it lives.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("threepart", "closedform", "sie", "fem", "meshes", "reports")


def _modules() -> list[Path]:
    return sorted(f for top in PACKAGES for f in (ROOT / top).rglob("*.py") if "build" not in f.parts)


def _private_imports(path: Path) -> list[str]:
    """``line: from module import _name`` for every private name ``path`` imports (in functions too)."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            module = "." * node.level + (node.module or "")
            out += [f"{node.lineno}: from {module} import {a.name}" for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")]
    return out


def test_the_scan_sees_the_package():
    assert len(_modules()) > 100


@pytest.mark.parametrize("top", PACKAGES)
def test_no_private_name_is_imported_across_modules(top):
    found = {str(f.relative_to(ROOT)): hits for f in _modules()
             if f.relative_to(ROOT).parts[0] == top and (hits := _private_imports(f))}
    assert found == {}


def test_the_scan_finds_a_private_import(tmp_path):
    """The scan can fail: a module importing a private name is found, in a function too."""
    bad = tmp_path / "m.py"
    bad.write_text("def f():\n    from .results import _kinks\n    return _kinks\n", encoding="utf-8")
    assert _private_imports(bad) == ["2: from .results import _kinks"]

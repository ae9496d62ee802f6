"""One home each (issue 30): the material defaults and the map's levels are defined once, in the core.

The reference is the source itself, read as a syntax tree (not imported): no
module outside ``threepart/material.py`` and ``threepart/tolerances.py`` binds
a module-level name to Poisson's default 0.3 under the name ``NU``, to the
steel modulus, or to the map's 1 % level.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from threepart import material, tolerances

ROOT = Path(__file__).resolve().parent.parent
#: the packages whose modules must take these values from their homes
PACKAGES = ("threepart", "reports", "fem", "sie", "closedform", "meshes")
HOMES = {"threepart/material.py", "threepart/tolerances.py"}


def _bindings(path: Path):
    """``(line, name, value)`` of each module-level ``NAME = <number>`` (tuple targets too)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in tree.body:
        if not isinstance(node, ast.Assign):
            continue
        for target in node.targets:
            names = target.elts if isinstance(target, ast.Tuple) else [target]
            values = node.value.elts if isinstance(node.value, ast.Tuple) and isinstance(target, ast.Tuple) \
                else [node.value]
            for n, v in zip(names, values):
                if isinstance(n, ast.Name) and isinstance(v, ast.Constant) and isinstance(v.value, float):
                    yield node.lineno, n.id, v.value


def _files():
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            if rel not in HOMES:
                yield rel, path


@pytest.mark.parametrize("name, value, home", [
    ("NU", material.NU, "threepart.material.NU"),
    ("E", material.E_STEEL, "threepart.material.E_STEEL"),
    ("LIMIT", tolerances.MAP_LIMIT, "threepart.tolerances.MAP_LIMIT"),
    ("LEVEL", tolerances.MAP_LIMIT, "threepart.tolerances.MAP_LIMIT"),
])
def test_a_default_is_bound_in_its_home_only(name, value, home):
    found = [f"{rel}:{line}: {n} = {v!r} (take {home})" for rel, path in _files()
             for line, n, v in _bindings(path) if name in n and v == value]
    assert found == []


def test_the_scan_finds_a_second_home():
    """The scan itself: a tuple binding and a plain one are both found."""
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "m.py"
        p.write_text("R1, E, NU = 10.0, 1.0, 0.3\nSLOPE_LEVEL = 0.01\nf(NU=0.3)\n", encoding="utf-8")
        assert sorted(_bindings(p)) == [(1, "E", 1.0), (1, "NU", 0.3), (1, "R1", 10.0),
                                        (2, "SLOPE_LEVEL", 0.01)]

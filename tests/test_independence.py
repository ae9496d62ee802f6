"""sie/, fem/ and meshes/ never import the closed-form solution, only its geometry and result shape."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
ALLOWED = {"closedform.geometry", "closedform.results"}


@pytest.mark.parametrize("package", ["sie", "fem", "meshes"])
def test_independent_solvers_import_only_geometry_and_results(package):
    files = sorted((ROOT / package).glob("*.py"))
    assert files
    for path in files:
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            for name in names:
                if name == "closedform" or name.startswith("closedform."):
                    assert name in ALLOWED, f"{path.name} imports {name}"


def test_the_check_can_fail(tmp_path):
    bad = "from closedform import solve_normal\n"
    tree = ast.parse(bad)
    mods = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert mods == ["closedform"] and "closedform" not in ALLOWED

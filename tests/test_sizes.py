"""No module over 600 lines and no function over 80 lines outside tests/ (issue 30, the house style).

The reference is the source itself, read as a syntax tree: every ``*.py`` of the
repository outside ``tests/``, one test per file, so that each offender is named
with its length.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: the most lines of a module (the house style, stated in ARCHITECTURE.md: one idea per module, usually 100-400 lines)
MAX_MODULE_LINES = 600
#: the most lines of a function or method, its docstring and decorators included
MAX_FUNCTION_LINES = 80
#: the source folders at the repository's root (tests/ is not among them)
FOLDERS = ("threepart", "reports", "closedform", "sie", "fem", "meshes", "benchmarks", "examples")
FILES = sorted(p.relative_to(ROOT).as_posix() for folder in FOLDERS for p in (ROOT / folder).rglob("*.py"))


def oversized(source: str) -> list[str]:
    """The module's length if over :data:`MAX_MODULE_LINES` and each function over :data:`MAX_FUNCTION_LINES`."""
    lines = source.count("\n") + (not source.endswith("\n") and bool(source))
    found = [f"module: {lines} lines > {MAX_MODULE_LINES}"] if lines > MAX_MODULE_LINES else []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = min([node.lineno, *(d.lineno for d in node.decorator_list)])
            n = node.end_lineno - first + 1
            if n > MAX_FUNCTION_LINES:
                found.append(f"{node.name} (line {node.lineno}): {n} lines > {MAX_FUNCTION_LINES}")
    return found


@pytest.mark.parametrize("path", FILES)
def test_no_module_over_600_lines_and_no_function_over_80(path):
    assert oversized((ROOT / path).read_text(encoding="utf-8")) == []


def test_the_size_check_finds_a_long_function_and_a_long_module():
    """The scan itself: an 81-line function (its decorator counted) and a 601-line module."""
    body = "".join(f"    x{i} = {i}\n" for i in range(79))
    source = "@staticmethod\ndef f():\n" + body
    assert oversized(source) == ["f (line 2): 81 lines > 80"]
    assert oversized(source[len("@staticmethod\n"):]) == []
    assert oversized("x = 1\n" * 601) == ["module: 601 lines > 600"]
    assert oversized("x = 1\n" * 600) == []
    assert len(FILES) > 100

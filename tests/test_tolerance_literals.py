"""Every limit in the tests is named: a table entry of :mod:`threepart.tolerances` or a constant with its reason.

A bare number in an assertion hides why it is that number. This scan of
``tests/*.py`` finds

* a non-zero number in a tolerance argument (``rtol``, ``atol``, ``rel``,
  ``abs``, ``rel_tol``, ``abs_tol``) of ``pytest.approx``, ``np.allclose``,
  ``np.isclose``, ``math.isclose`` or ``assert_allclose``, and
* a non-integer number on either side of an ordered comparison (``<``, ``<=``,
  ``>``, ``>=``) in an ``assert``, alone or in arithmetic (``1e-9 * W``), but not
  inside a call's arguments (``f(x, 0.5)`` is an input, not a limit);

and requires every name that such a limit uses, when set to a non-integer
number (a module constant, or a local named as a limit, ``tol = 1e-9 * L``), to say why: a comment
on its line or a ``#`` line above it. A limit is then written
``tolerance(comparison, quantity).limit`` or as such a constant.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

HERE = Path(__file__).parent
#: keyword arguments that carry a tolerance
TOLERANCE_ARGS = frozenset({"rtol", "atol", "rel", "abs", "rel_tol", "abs_tol"})
#: the calls whose tolerance arguments are limits of a test (a solver's ``rtol`` is an input)
CLOSENESS = frozenset({"approx", "allclose", "isclose", "assert_allclose"})
#: a local variable named with one of these words holds a limit
LIMIT_WORDS = ("tol", "limit", "slack", "bound", "margin", "eps")
FILES = sorted(HERE.glob("*.py"))


def _name(func: ast.AST) -> str:
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def _walk_limit(node: ast.AST):
    """The nodes of a limit expression: through arithmetic, tuples, conditionals and subscripts,
    not into a call's arguments (``f(x, 0.5)`` is an input, not a limit)."""
    stack = [node]
    while stack:
        n = stack.pop()
        yield n
        if isinstance(n, ast.BinOp):
            stack += [n.left, n.right]
        elif isinstance(n, ast.UnaryOp):
            stack.append(n.operand)
        elif isinstance(n, (ast.Tuple, ast.List)):
            stack += n.elts
        elif isinstance(n, ast.IfExp):
            stack += [n.body, n.orelse]
        elif isinstance(n, ast.Subscript):
            stack.append(n.value)


def _limits(tree: ast.AST):
    """``(expression, floats_only)`` of every limit: tolerance arguments and sides of ordered asserts."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _name(node.func) in CLOSENESS:
            for k in node.keywords:
                if k.arg in TOLERANCE_ARGS:
                    yield k.value, False
        if isinstance(node, ast.Assert):
            for cmp in ast.walk(node.test):
                if isinstance(cmp, ast.Compare) and any(
                        isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE)) for op in cmp.ops):
                    for side in (cmp.left, *cmp.comparators):
                        yield side, True


def _is_number(n: ast.AST, floats_only: bool) -> bool:
    kinds = (float,) if floats_only else (int, float)
    return isinstance(n, ast.Constant) and type(n.value) in kinds and n.value != 0


def bare_limits(source: str) -> list[tuple[int, str]]:
    """``(line, literal)`` of every unnamed limit in a test module's ``source``."""
    found = {(n.lineno, ast.unparse(n)) for expr, floats in _limits(ast.parse(source))
             for n in _walk_limit(expr) if _is_number(n, floats)}
    return sorted(found)


def unexplained_constants(source: str) -> list[tuple[int, str]]:
    """``(line, name)`` of names used in limits and set to a number without a comment (module or function)."""
    tree = ast.parse(source)
    used = {n.id for expr, _ in _limits(tree) for n in _walk_limit(expr) if isinstance(n, ast.Name)}
    lines = source.splitlines()
    out = []
    module = set(map(id, tree.body))
    for node in ast.walk(tree):
        if not isinstance(node, ast.Assign):
            continue
        names = {t.id for t in node.targets if isinstance(t, ast.Name)}
        if id(node) not in module:      # a local: only a name that says it is a limit
            names = {n for n in names if any(w in n.lower() for w in LIMIT_WORDS)}
        if names & used and any(_is_number(n, True) for n in _walk_limit(node.value)):
            here = lines[node.lineno - 1:node.end_lineno]
            above = lines[node.lineno - 2].strip() if node.lineno > 1 else ""
            if not any("#" in line for line in here) and not above.startswith("#"):
                out.append((node.lineno, ", ".join(sorted(names & used))))
    return out


def test_the_scan_finds_bare_limits_and_passes_named_ones():
    bad = ("def test():\n    assert abs(x - y) < 1e-9 * W\n    assert x == pytest.approx(y, rel=1e-12)\n"
           "    np.testing.assert_allclose(x, y, rtol=0, atol=(1e-12, 1e-8)[k])\n"
           "    assert 4**1.3 < r\n")
    assert [line for line, _ in bare_limits(bad)] == [2, 3, 4, 4, 5]
    good = ("ROUND_OFF = 1e-12  # double precision of a closed-form identity\n"
            "def test():\n    assert abs(x - y) < ROUND_OFF * W and n >= 12\n"
            "    assert x == pytest.approx(y, rel=tolerance('sie', 'a').limit, abs=0)\n"
            "    assert f(x, 0.5) < LIMIT\n")
    assert bare_limits(good) == [] and unexplained_constants(good) == []
    assert unexplained_constants("SAME = 1e-10\nassert x < SAME\n") == [(1, "SAME")]
    local = "def test():\n    f = 0.5\n    tol = 1e-9 * L\n    assert abs(q) <= f * p + tol\n"
    assert unexplained_constants(local) == [(3, "tol")]


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_no_bare_limit_in_the_tests(path):
    source = path.read_text(encoding="utf-8")
    bare = bare_limits(source)
    assert not bare, (f"{path.name}: limits without a name (use tolerance(...) or a constant with "
                      f"its reason): " + ", ".join(f"line {n}: {lit}" for n, lit in bare))
    unexplained = unexplained_constants(source)
    assert not unexplained, f"{path.name}: constants without a reason: {unexplained}"

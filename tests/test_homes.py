"""One home each (issue 30): the material defaults and the map's levels are defined once, in the core.

The reference is the source itself, read as a syntax tree (not imported): no
module outside ``threepart/problem/material.py`` and ``threepart/tolerances/`` binds
a module-level name to Poisson's default 0.3 under the name ``NU``, to the
steel modulus, or to the map's 1 % level.
"""
from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

from threepart.problem import material
from threepart import tolerances

ROOT = Path(__file__).resolve().parent.parent
#: the packages whose modules must take these values from their homes
PACKAGES = ("threepart", "reports", "fem", "sie", "closedform", "meshes")
HOMES = {"threepart/problem/material.py", "threepart/tolerances/__init__.py", "threepart/tolerances/outside.py"}


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
    ("NU", material.NU, "threepart.problem.material.NU"),
    ("E", material.E_STEEL, "threepart.problem.material.E_STEEL"),
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


# --- the peak of a nodal field: threepart.results.fields.peak ----------------------------------------------
#: a parabola's vertex and a polynomial's even fit are exact up to rounding
ROUNDING = 1e-12


def test_the_peak_of_a_parabola_s_nodes_is_its_vertex():
    """p = 3 - 2 (x - 0.37)^2 at uneven nodes: the vertex (0.37, 3), wherever the nodes fall."""
    from threepart.results.fields import peak

    x = np.sort(np.random.default_rng(1).uniform(-1.0, 1.0, 40))
    xp, pp = peak(x, 3.0 - 2.0 * (x - 0.37) ** 2)
    assert xp == pytest.approx(0.37, abs=ROUNDING) and pp == pytest.approx(3.0, rel=ROUNDING)
    # the largest node at an end: that node
    assert peak(x, x) == (x[-1], x[-1])


def test_the_windowed_peak_of_a_quartic_is_its_maximum_to_the_sampling():
    """An exact quartic over its window: the fit is exact and its maximum is found to the sample step."""
    from threepart.results.fields import FIT_SAMPLES, peak

    x = np.linspace(-1.0, 1.0, 201)
    p = 5.0 - (x - 0.123) ** 2 - 0.5 * (x - 0.123) ** 4
    window = 0.3
    xp, pp = peak(x, p, half_width=window, degree=4)
    step = 2 * window / (FIT_SAMPLES - 1)
    assert abs(xp - 0.123) <= step and abs(pp - 5.0) <= step ** 2
    with pytest.raises(ValueError, match=r"`half_width` = 0\.001 holds 1 nodes; the degree-4 fit needs at least 6"):
        peak(x, p, half_width=0.001)


def test_the_symmetric_peak_is_the_even_fit_at_the_centre():
    from threepart.results.fields import peak

    x = np.linspace(-1.0, 1.0, 101)
    assert peak(x, 2.0 - x ** 2 + 0.25 * x ** 4, half_width=0.5, degree=4, symmetric=True)[1] == \
        pytest.approx(2.0, rel=ROUNDING)
    with pytest.raises(ValueError, match="`symmetric` needs a `half_width`"):
        peak(x, x, symmetric=True)


@pytest.mark.parametrize("path, function", [
    ("reports/map/referee.py", "fitted_peak"),
    ("reports/map/validity_slope.py", "_peak"),
    ("threepart/calculix/read.py", "centre_pressure"),
    ("benchmarks/small_slope_calculix.py", "peak_pressure"),
])
def test_every_peak_of_nodal_values_is_read_by_the_one_rule(path, function):
    """Each former home of a nodal peak now calls threepart.results.fields.peak (syntax tree)."""
    tree = ast.parse((ROOT / path).read_text(encoding="utf-8"))
    body = next(n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name == function)
    calls = {getattr(c.func, "id", getattr(c.func, "attr", "")) for c in ast.walk(body) if isinstance(c, ast.Call)}
    assert "peak" in calls

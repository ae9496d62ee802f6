"""One home per concept (issue 20): the shared package reaches the methods through the registry only.

The references are independent of the code under test: the shared package's
own source (read as a syntax tree, not imported), the SIE's lift-off root (an
independent solution of the same equations as the closed form's) and a
method's declared options.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from threepart import catalogue, registry
from threepart.registry import Method
from threepart.reports.verify.runs import Mode
from threepart.tolerances import tolerance

SHARED = Path(catalogue.__file__).resolve().parent
SOLVERS = ("closedform", "sie", "fem")


def _imports(path: Path) -> set[str]:
    """Every module ``path`` imports, at any depth (lazy imports inside functions too), made absolute."""
    package = ["threepart", *path.parent.relative_to(SHARED).parts]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = package[:len(package) - node.level + 1] if node.level else []
            module = ".".join([*base, *(node.module.split(".") if node.module else [])])
            found |= {module, *(f"{module}.{a.name}" for a in node.names)}
    return found


def test_the_shared_package_imports_no_solver():
    """threepart/*.py (and threepart/output/) name no solver package, even lazily: they ask the registry."""
    files = sorted(SHARED.rglob("*.py"))
    assert len(files) > 10
    solvers = [f"threepart.{s}" for s in SOLVERS] + list(SOLVERS)
    offending = sorted(f"{path.relative_to(SHARED.parent)}: {name}" for path in files
                       for name in _imports(path)
                       if any(name == s or name.startswith(s + ".") for s in solvers))
    assert offending == []


def test_catalogue_lift_off_fractions_resolve_to_the_SIE_s_own_lift_off_root():
    """A case given as a fraction of its lift-off arm (and no stored arm) resolves through the registry."""
    cases = [c for c in catalogue.load_cases(None)
             if c.s_lift_off_fraction is not None and c.s_max is None]
    assert cases
    rtol = tolerance("sie-exact", "lift_off").limit
    for case in cases:
        s_min, s_max = registry.lift_off("sie", case.punch, case.P, case.A)
        frac = case.s_lift_off_fraction
        assert case.resolved().s == pytest.approx(frac * (s_max if frac >= 0 else -s_min), rel=rtol), \
            case.name


def test_a_method_without_lift_off_says_so_by_name(monkeypatch):
    toy = Method("toy_no_lift_off", lambda *a, **k: None)
    monkeypatch.setitem(registry._REGISTRY, toy.name, toy)
    case = catalogue.get_case("caseA_sym")
    with pytest.raises(ValueError, match=r"^`method` = 'toy_no_lift_off' does not compute lift-off "
                                         r"lever arms$"):
        registry.lift_off(toy.name, case.punch, case.P, case.A)


def test_a_mode_passes_a_method_the_options_it_declares(monkeypatch):
    """Mode.options follows Method.options: a new method gets its settings with no change to the mode."""
    mode = Mode("m", 7, "quick", (), ())
    for name, declared, expected in (("toy_n_mesh", ("n", "mesh"), {"n": 7, "mesh": "quick"}),
                                     ("toy_mesh", ("mesh", "progress"), {"mesh": "quick"}),
                                     ("toy_none", (), {})):
        monkeypatch.setitem(registry._REGISTRY, name, Method(name, lambda *a, **k: None,
                                                             options=declared))
        assert mode.options(name) == expected
    assert Mode("m", None, "fine", (), ()).options("toy_n_mesh") == {"mesh": "fine"}


def test_no_test_imports_a_solver_folder_as_a_top_level_package():
    """``import closedform`` from the repository's root loads the solver a second time, under another
    name, whose import registers its method again: the registry then holds the copy's functions."""
    offending = []
    for path in sorted(Path(__file__).parent.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module] if isinstance(node, ast.ImportFrom) and not node.level else [])
            offending += [f"{path.name}: {n}" for n in names if n and n.split(".")[0] in SOLVERS]
    assert offending == []

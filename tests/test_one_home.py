"""One home per concept (issue 20): the shared package reaches the methods through the registry only.

The references are independent of the code under test: the shared package's
own source (read as a syntax tree, not imported), the SIE's lift-off root (an
independent solution of the same equations as the closed form's) and a
method's declared options.
"""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import threepart
from threepart.problem import catalogue
from threepart import registry
from threepart.registry import Method
from threepart.reports.verify.runs import Mode
from threepart.tolerances import tolerance

SHARED = Path(threepart.__file__).resolve().parent
SOLVERS = ("closedform", "sie", "fem")


def _imports(path: Path, package: list[str] | None = None) -> set[str]:
    """Every module ``path`` imports, at any depth (lazy imports inside functions too), made absolute.

    ``package`` is the dotted package ``path`` belongs to (default: its place under ``threepart/``).
    """
    if package is None:
        package = ["threepart", *path.parent.relative_to(SHARED).parts]
    return _imports_of(list(ast.walk(ast.parse(path.read_text(encoding="utf-8")))), package)


#: what sits above the core inside ``threepart/``: the command line and the foreign codes' toolkits
#: (``__main__`` is the command line's entry)
ABOVE_CORE = ("cli", "calculix", "getfem", "readers", "__main__")
#: the layers, bottom up: each folder's package may import those below it, never those above
LAYERS = {"core": 0, "meshes": 1, "solvers": 1, "foreign": 2, "reports": 3, "cli": 4}


def _layer(module: str) -> str | None:
    """The layer of a threepart module (``None``: not threepart's)."""
    parts = module.split(".")
    if parts[0] != "threepart":
        return None
    top = parts[1] if len(parts) > 1 else ""
    if top in SOLVERS:
        return "solvers"
    if top in ("meshes", "reports"):
        return top
    if top in ("calculix", "getfem", "readers"):
        return "foreign"
    if top in ("cli", "__main__"):
        return "cli"
    return "core"


def _core_files() -> list[Path]:
    return [p for p in sorted(SHARED.rglob("*.py"))
            if p.relative_to(SHARED).parts[0].removesuffix(".py") not in ABOVE_CORE]


def test_the_core_imports_no_layer_above_it():
    """threepart's core (its modules but the command line and CalculiX) names no solver, no mesh,
    no report, no command line and no foreign code, even lazily: it asks the registry."""
    files = _core_files()
    assert len(files) > 10
    offending = sorted(f"{path.relative_to(SHARED.parent)}: {name}" for path in files
                       for name in _imports(path) if _layer(name) not in (None, "core"))
    assert offending == []


@pytest.mark.parametrize("folder, layer", [("closedform", "solvers"), ("sie", "solvers"),
                                           ("fem", "solvers"), ("meshes", "meshes"),
                                           ("reports", "reports")])
def test_each_folder_imports_only_layers_below_it(folder, layer):
    """A solver or the meshes import only the core (and the FEM the meshes); the reports never the
    command line. Read from the syntax tree, imports inside functions included."""
    root = SHARED.parent / folder
    files = sorted(root.rglob("*.py"))
    assert files
    allowed = {"solvers": {"core", "meshes"}, "meshes": {"core"}, "reports": {"core", "meshes", "solvers", "foreign"}}[layer]
    offending = []
    for path in files:
        own = "threepart." + ".".join(path.relative_to(SHARED.parent).with_suffix("").parts)
        for name in _imports(path, package=own.rsplit(".", 1)[0].split(".")):
            found = _layer(name)
            same = found == layer and (layer != "solvers" or name.split(".")[1] == folder)
            if found is not None and not same and found not in allowed:
                offending.append(f"{path.relative_to(SHARED.parent)}: {name}")
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


def _module_name(path: Path) -> str:
    """``threepart/results/contact.py`` -> ``threepart.results.contact`` (a package: its ``__init__``)."""
    parts = path.relative_to(SHARED.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _core_graph(module_level: bool) -> dict[str, set[str]]:
    """Each core module and the core modules it imports (at module level only, or at any depth:
    imports inside functions too; never those under ``if TYPE_CHECKING``)."""
    modules = {_module_name(p): p for p in _core_files()}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        tree = ast.parse(path.read_text(encoding="utf-8"))
        nodes = [n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))] if module_level \
            else [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))
                  and not any(n in ast.walk(t) for t in _type_checking_blocks(tree))]
        found: set[str] = set()
        for imported in _imports_of(nodes, package):
            parts = imported.split(".")
            home = next((".".join(parts[:k]) for k in range(len(parts), 0, -1)
                         if ".".join(parts[:k]) in modules), None)
            if home is not None and home != name:
                found.add(home)
        graph[name] = found
    return graph


def _type_checking_blocks(tree: ast.AST) -> list[ast.If]:
    return [n for n in ast.walk(tree) if isinstance(n, ast.If) and "TYPE_CHECKING" in ast.unparse(n.test)]


def _imports_of(nodes: list[ast.AST], package: list[str]) -> set[str]:
    """The absolute names the import statements ``nodes`` of a module of ``package`` import."""
    found: set[str] = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = package[:len(package) - node.level + 1] if node.level else []
            module = ".".join([*base, *(node.module.split(".") if node.module else [])])
            found |= {module, *(f"{module}.{a.name}" for a in node.names)}
    return found


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of ``graph`` (its modules in order, the first repeated at the end), or None."""
    done: set[str] = set()

    def visit(node: str, path: tuple[str, ...]) -> list[str] | None:
        if node in path:
            return [*path[path.index(node):], node]
        if node in done:
            return None
        for nxt in sorted(graph.get(node, ())):
            if (found := visit(nxt, (*path, node))) is not None:
                return found
        done.add(node)
        return None

    for start in sorted(graph):
        if (found := visit(start, ())) is not None:
            return found
    return None


def test_the_core_has_no_import_circle_at_module_level():
    """No chain of module-level imports among the core's modules leads back to where it started
    (issue 30: punch, validate, results and stress once imported each other in a circle)."""
    graph = _core_graph(module_level=True)
    assert len(graph) > 20
    cycle = _cycle(graph)
    assert cycle is None, " -> ".join(cycle or ())


@pytest.mark.parametrize("module", ["problem/punch", "results/contact", "stress/flamant", "stress/grid",
                                    "problem/checks"])
def test_the_problem_types_check_their_input_with_the_leaf_checks_only(module):
    """punch, results and stress take their argument checks from threepart.problem.checks (which imports no
    threepart module but the leaf errors), never from threepart.problem.validate (which imports them), even
    lazily."""
    names = _imports(SHARED / f"{module}.py")
    assert not any(n == "threepart.problem.validate" or n.startswith("threepart.problem.validate.") for n in names)
    if module == "problem/checks":
        leaf = {"threepart.errors"} | {f"threepart.errors.{e}" for e in ("InputError", "InputTypeError")}
        assert not any(n.startswith("threepart") and n not in leaf for n in names), names
        assert not any(n.startswith("threepart") for n in _imports(SHARED / "errors.py"))


def test_the_scan_sees_lazy_and_relative_imports(tmp_path):
    """The layer checks' scanner itself: imports inside functions, relative ones, and of a subpackage."""
    path = tmp_path / "m.py"
    path.write_text("def f():\n    from .calculix import read\n    import threepart.readers\n"
                    "def g():\n    from ..reports.map import sweep\n", encoding="utf-8")
    found = _imports(path, package=["threepart", "output"])
    assert {"threepart.output.calculix", "threepart.readers", "threepart.reports.map.sweep"} <= found
    assert [_layer(n) for n in ("threepart.calculix.read", "threepart.reports.map", "threepart.cli",
                                "threepart.sie.normal", "threepart.results.fields", "numpy")] == \
        ["foreign", "reports", "cli", "solvers", "core", None]


def test_the_core_has_no_import_cycle_at_any_depth():
    """No chain of imports among the core's modules, counting imports inside functions, leads back to
    where it started (issue 40): the data flow problem -> results -> stress -> fatigue -> methods ->
    studies runs one way. The failure names the cycle."""
    graph = _core_graph(module_level=False)
    assert len(graph) > 30
    cycle = _cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle or ())


def test_the_core_s_packages_import_one_another_one_way():
    """Between the core's sub-packages too the imports run one way (problem -> halfplane -> stress ->
    results -> fatigue -> methods -> studies): a module of one package never needs a package that
    needs it. The failure names the packages' cycle."""
    packages: dict[str, set[str]] = {}
    for module, found in _core_graph(module_level=False).items():
        own = module.split(".")[1] if "." in module else module
        packages.setdefault(own, set()).update(m.split(".")[1] for m in found if "." in m and m.split(".")[1] != own)
    assert {"problem", "results", "halfplane", "stress", "fatigue", "studies"} <= set(packages)
    cycle = _cycle(packages)
    assert cycle is None, "packages' import cycle: " + " -> ".join(cycle or ())


def test_the_cycle_check_finds_a_cycle_through_a_function():
    """The check itself: two modules of which one imports the other inside a function."""
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert _cycle({"a": {"b"}, "b": {"a"}}) == ["a", "b", "a"]
    graph = _core_graph(module_level=False)
    assert "threepart.results.contact" in graph["threepart.results.cycles"]


def test_the_plain_value_checks_are_imported_from_their_one_home():
    """finite, positive, integer, poisson, ... live in threepart.problem.checks; validate (the checks of
    a problem) uses them but does not re-export them, and no module imports them through it (issue 40:
    one concept, two homes)."""
    from threepart.problem import checks, validate

    assert not set(checks.__all__) & set(validate.__all__)
    root = SHARED.parent
    through = [f"{path.relative_to(root)}:{node.lineno}" for top in ("threepart", "closedform", "sie", "fem", "reports")
               for path in (root / top).rglob("*.py") if "build" not in path.parts
               for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
               if isinstance(node, ast.ImportFrom) and (node.module or "").endswith("validate")
               and any(a.name in checks.__all__ for a in node.names)]
    assert not through, through


#: the packages of the commands (``threepart verify``, ``compare``, ``map``, ``figures``' reports), each
#: imported first in a fresh interpreter, where no earlier import has set the order: an import
#: cycle shows only there (``threepart compare`` once failed so, once ``threepart.reports`` loaded
#: its names on first use)
COMMAND_PACKAGES = ("threepart.reports.verify", "threepart.reports.referee", "threepart.reports.map",
                    "threepart.reports.figures")


@pytest.mark.parametrize("name", COMMAND_PACKAGES)
def test_each_command_s_package_imports_first_in_a_fresh_interpreter(name):
    done = subprocess.run([sys.executable, "-c", f"import {name}"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]

"""The one registry of methods: every caller dispatches through it, and a new method is one module."""
from __future__ import annotations

import json

import numpy as np
import pytest

import threepart
from threepart import Punch, registry, rigid_punch, similar_pair
from threepart.cli import main
from threepart.errors import LiftOffError
from threepart.tolerances import tolerance

A = rigid_punch(210e3, 0.3)
HERTZ = Punch(10.0, 10.0, 0.0)
#: the toy's Hertz against the closed form's (both exact): rounding; the moduli's inversion
ROUND_OFF = tolerance("closedform", "round_off").limit
EXACT = tolerance("closedform", "exact").limit
#: the toy's Hertz pressure (a series of its `terms`) against the closed form's, of the peak
TOY_PRESSURE = 1e-10


@pytest.fixture
def toy(monkeypatch):
    """The toy method of tests/toy_method.py, registered for one test only."""
    monkeypatch.setattr(registry, "_REGISTRY", dict(registry._REGISTRY))
    from . import toy_method
    return registry.register(toy_method.METHOD)


def test_the_built_in_methods_come_from_the_registry():
    assert registry.names()[:3] == ("closedform", "sie", "fem")
    for name in registry.BUILTIN:
        m = registry.get(name)
        assert m.name == name and callable(m.normal)
    with pytest.raises(ValueError, match=r"`method` = 'nope' must be one of closedform, sie, fem"):
        registry.get("nope")


def test_a_toy_method_is_one_module_and_every_caller_finds_it(toy, capsys):
    # threepart.solve: the toy's Hertz against the closed form's Hertz (eq. 2 with b = 0)
    r = threepart.solve(HERTZ, 400.0, 0.0, A=A, method="toy")
    ref = threepart.solve(HERTZ, 400.0, 0.0, A=A, method="closedform")
    assert r.method == "toy"
    assert abs(r.a - ref.a) <= ROUND_OFF * ref.width and abs(r.c - ref.c) <= ROUND_OFF * ref.width
    x = np.linspace(-ref.a, ref.c, 101)
    assert np.max(np.abs(r.pressure(x) - ref.pressure(x))) <= TOY_PRESSURE * ref.pressure(0.0)
    # its options are checked like any method's
    with pytest.raises(ValueError, match=r"`n` is not an option of method 'toy' \(its options: terms\)"):
        threepart.solve(HERTZ, 400.0, 0.0, A=A, method="toy", n=8)
    with pytest.raises(ValueError, match="has no partial-slip model"):
        threepart.solve(HERTZ, 400.0, 0.0, A=A, method="toy", Q=10.0, f=0.5)
    # the verification run's adapter: a catalogue case in, the shared result out
    from threepart.problem import catalogue
    from threepart.reports import solvers
    from threepart.reports.compare import normal_figures
    case = next(c for c in catalogue.load_cases() if c.name == "hertz")
    got, want = solvers.normal("toy", case), solvers.normal("closedform", case)
    figures = normal_figures(want, got)
    assert figures["a"][2] <= ROUND_OFF and figures["c"][2] <= ROUND_OFF and figures["p_L2"][2] <= TOY_PRESSURE
    # the command line
    assert main(["solve", "--R1", "10", "--R2", "10", "--b", "0", "--A", str(A), "--P", "400",
                 "--method", "toy", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["method"] == "toy" and abs(out["a"] - ref.a) <= ROUND_OFF * ref.width


def test_the_verification_run_judges_a_method_by_the_group_it_names(toy, monkeypatch):
    """``reports.verify.runs.run_case`` asks the method for its tolerance group: no method is special-cased."""
    from dataclasses import replace

    from threepart.problem import catalogue
    from threepart.reports.verify.runs import MODES, run_case
    from threepart.tolerances import TOLERANCES, fem_comparison

    case = next(c for c in catalogue.load_cases() if c.name == "hertz")
    run = run_case(case, MODES["quick"], methods=("closedform", "toy"))
    assert run.checks and {c.comparison for c in run.checks} == {"sie"} and run.passed
    # the built-in groups are rows of the table; the FEM's follows its mesh
    assert registry.get("sie").comparison({}) == "sie"
    for mesh in ("quick", "default", "fine"):
        assert registry.get("fem").comparison({"mesh": mesh}) == fem_comparison(mesh)
        assert any(k[0] == fem_comparison(mesh) for k in TOLERANCES)
    # a method that names no group is an error of the run, not a silent pass
    registry.register(replace(toy, comparison=None))
    run = run_case(case, MODES["quick"], methods=("closedform", "toy"))
    assert not run.passed and "names no tolerance group" in run.errors["compare-toy"]


def test_nu_is_refused_by_a_half_plane_method_and_used_by_the_fem():
    with pytest.raises(ValueError, match="`nu` is not used by method 'closedform'"):
        threepart.solve(HERTZ, 400.0, 0.0, A=A, method="closedform", nu=0.3)
    from threepart.fem.method import pair_modulus, rigid_punch_modulus
    # the FE moduli invert eq. (4): a rigid punch on E, and two similar bodies of 2E
    assert rigid_punch_modulus(A, 0.3) == pytest.approx(210e3, rel=EXACT)
    assert pair_modulus(A, 0.3) == pytest.approx(420e3, rel=EXACT)
    with pytest.raises(ValueError, match=r"`nu` = 0.5 must lie in \(-1, 0.5\)"):
        rigid_punch_modulus(A, 0.5)


def test_a_method_without_a_steady_state_model_is_refused_by_name(toy):
    states = [(300.0, 0.0, 0.0, 0.0), (400.0, 0.0, 60.0, 0.0)]
    with pytest.raises(ValueError, match="method 'toy' has no steady-state model of a cycle"):
        threepart.steady_state(Punch(10.0, 10.0, 1.0), states, 0.5, A=rigid_punch(E=210e3, nu=0.3),
                               method="toy")


def test_fretting_auto_is_the_closed_form_inside_its_framework_and_the_sie_past_it_saying_why():
    """threepart.fretting's ``auto`` (methods._auto, as solve's): inside the framework, the closed form's
    own cycle; past lift-off (s = 0.9 beyond the closed form's lever arm), the SIE's own cycle, and
    ``info["auto"]`` quotes the refusal the closed form raises when called directly."""
    punch, loads = Punch(10.0, 5.0, 1.0), {"A": similar_pair(210e3, 0.3), "Q_max": 60.0, "f": 0.5,
                                            "states": 3}
    inside = threepart.fretting(punch, 400.0, 0.2, **loads)
    own = registry.get("closedform").fretting(punch, 400.0, 0.2, **loads)
    assert inside.method == "closedform" and "auto" not in inside.info
    assert np.array_equal(inside.Q, own.Q) and np.array_equal(inside.stick, own.stick)
    with pytest.raises(LiftOffError) as refusal:
        registry.get("closedform").fretting(punch, 400.0, 0.9, **loads)
    past = threepart.fretting(punch, 400.0, 0.9, **loads)
    sie = registry.get("sie").fretting(punch, 400.0, 0.9, **loads)
    assert past.method == "sie"
    assert past.info["auto"] == f"the closed form does not hold here: {refusal.value}"
    assert np.array_equal(past.Q, sie.Q) and np.array_equal(past.stick, sie.stick)


def test_a_method_that_declares_no_bulk_stress_is_refused_one_by_name_before_it_is_called(monkeypatch):
    """``Method.bulk_stress=False``: a nonzero ``sigma_bulk`` is refused by name (never a TypeError from
    the call); at 0 the method is reached without one; a method without a fretting call is named."""
    def never(*args, **kwargs):
        raise AssertionError(f"called with {sorted(kwargs)}")

    monkeypatch.setattr(registry, "_REGISTRY", dict(registry._REGISTRY))
    registry.register(registry.Method("nobulk", never, slip=never, fretting=never, bulk_stress=False))
    registry.register(registry.Method("normal_only", never))
    cycle = {"A": A, "Q_max": 60.0, "f": 0.5}
    with pytest.raises(ValueError, match=r"^`sigma_bulk` = 300: method 'nobulk' does not take a bulk "
                                         r"stress in its fretting cycle; give sigma_bulk=0 or another method$"):
        threepart.fretting(HERTZ, 400.0, 0.0, **cycle, method="nobulk", sigma_bulk=300.0)
    with pytest.raises(ValueError, match=r"^`sigma_bulk` = -20: method 'nobulk' does not take a bulk "
                                         r"stress in its partial slip"):
        threepart.solve(HERTZ, 400.0, 0.0, A=A, Q=60.0, f=0.5, method="nobulk", sigma_bulk=-20.0)
    with pytest.raises(AssertionError, match=r"called with \['A', 'Q_max', 'f', 'normal', 'nu', "
                                             r"'states', 'tilt'\]"):
        threepart.fretting(HERTZ, 400.0, 0.0, **cycle, method="nobulk")
    with pytest.raises(ValueError, match=r"^method 'normal_only' has no fretting cycle$"):
        threepart.fretting(HERTZ, 400.0, 0.0, **cycle, method="normal_only")
def test_a_toy_method_s_label_and_style_reach_the_report_without_edits(toy, monkeypatch, tmp_path):
    """The toy's label (Method.label) heads its rows and its legend entry, drawn in its style."""
    from threepart.problem import catalogue
    from threepart.reports import solvers
    from threepart.reports.verify import plots
    from threepart.reports.verify.sections import method_name
    from threepart.reports.verify.stress_section import stress_section

    case = next(c for c in catalogue.load_cases() if c.name == "hertz")
    results = {"closedform": solvers.normal("closedform", case), "toy": solvers.normal("toy", case)}
    drawn = []
    monkeypatch.setattr(plots, "save", lambda fig, path, dpi=None: drawn.append(fig) or path)
    plots.overlay(results, "hertz", tmp_path / "overlay.png")
    lines = {ln.get_label(): ln for ax in drawn[0].axes for ln in ax.get_lines()}
    line = lines["toy Hertz"]
    assert (line.get_color(), line.get_linestyle(), line.get_linewidth()) == ("tab:purple", ":", 2.0)
    assert lines["closed form"].get_color() == "k"
    spot = {"x": 0.0, "z": 0.0, "value": 1.0}
    doc = {"cases": [{"name": "hertz", "passed": True, "plots": [], "E": None,
                      "stress": {"sigma_bulk": 0.0,
                                 "hot_spots": {m: {q: spot for q in ("sxx", "von_mises", "max_shear")}
                                               for m in results}}}]}
    section, _ = stress_section(doc)
    assert [row[1] for row in section.tables[0].rows] == ["closed form", "toy Hertz"]
    assert method_name("toy") == "toy Hertz" and method_name("calculix") == "CalculiX"


def _method_names_compared(tree, names):
    """``(line, name)`` of every string constant equal to a method's name in a comparison
    (``==``, ``!=``, ``in``, ``not in``, either side, alone or in a tuple, list or set) or as a
    key of a dict literal."""
    import ast

    def consts(node):
        if isinstance(node, ast.Constant) and node.value in names:
            yield node
        elif isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            for elt in node.elts:
                yield from consts(elt)

    for node in ast.walk(tree):
        if isinstance(node, ast.Compare) and any(isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn))
                                                 for op in node.ops):
            for side in (node.left, *node.comparators):
                yield from ((c.lineno, c.value) for c in consts(side))
        elif isinstance(node, ast.Dict):
            yield from ((k.lineno, k.value) for k in node.keys if k is not None for k in consts(k))


def test_no_module_of_reports_branches_on_a_method_s_name():
    """reports/ (syntax tree, not imported) compares no string with a registered method's name and
    keys no dict by one: a method's label, style, study parameter and reference role are
    fields of registry.Method (or registry.REFERENCE)."""
    import ast
    from pathlib import Path

    import threepart.reports as reports

    root = Path(reports.__file__).resolve().parent
    names = set(registry.names())
    files = sorted(root.rglob("*.py"))
    assert len(files) > 20
    found = [f"{p.relative_to(root.parent)}:{line}: {name!r}" for p in files
             for line, name in _method_names_compared(ast.parse(p.read_text(encoding="utf-8")), names)]
    assert found == []


def test_the_name_scan_finds_a_branch_on_a_name():
    """The scan itself: each form it must catch, and a call argument it must not."""
    import ast

    src = ('a = m == "sie"\nb = "fem" in ms\nc = m in ("x", "closedform")\nd = {"sie": 1}\n'
           'e = f("sie")\n')
    got = sorted(_method_names_compared(ast.parse(src), {"closedform", "sie", "fem"}))
    assert got == [(1, "sie"), (2, "fem"), (3, "closedform"), (4, "sie")]

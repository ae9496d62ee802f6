"""threepart's pytest plugin (``reports/plugin.py``), run on toy codes through ``pytester``.

The code under test in each inner run answers with the SIE (a method
independent of the closed form that is the reference), or with a result
deliberately wrong by a known amount: the SIE passes at the SIE's limits, a
quantity pushed 3x past its limit fails naming exactly that quantity, and 0.3x
passes (as tests/test_compare.py proves for the verification run).
"""
from __future__ import annotations

import subprocess
import sys
import types
from importlib import metadata

import pytest

import threepart.reports.verify.runs  # noqa: F401 - loaded before pytester's in-process runs, which
import threepart.sie  # noqa: F401      unload what they import (numpy's extensions load only once)
import threepart.closedform  # noqa: F401
from threepart import registry
from threepart.problem.catalogue import get_case
from threepart.reports.plugin import check
from threepart.tolerances import tolerance

from .test_install import isolated, wheel  # noqa: F401 - fixtures: the fresh environment of test_install

pytest_plugins = ["pytester"]

#: the toy code of the inner runs: the SIE, optionally perturbed
TOY = '''
import types
import pytest
from threepart import registry


def sie(case):
    m = registry.get("sie")
    res = m.normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
    if case.kind == "slip":
        res = m.slip(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt, Q=case.Q, f=case.f,
                     normal=res)
    return res
'''


def test_the_entry_point_loads_the_plugin(request):
    eps = [e for e in metadata.entry_points(group="pytest11") if e.name == "threepart"]
    assert [e.value for e in eps] == ["threepart.reports.plugin"]
    assert request.config.pluginmanager.has_plugin("threepart")


def test_loading_the_plugin_loads_no_solver_and_no_numpy():
    """pytest loads the plugin in every run of any project in this environment (issue 41): it
    loads the errors it names and nothing of the solvers, numpy or scipy (the fixtures load the
    catalogue when a test asks for a case)."""
    code = ("import sys, threepart.reports.plugin; print(' '.join(sorted(m for m in sys.modules "
            "if m.split('.')[0] in ('threepart', 'numpy', 'scipy', 'matplotlib', 'dask'))))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["threepart", "threepart.errors", "threepart.lazy", "threepart.reports",
                                   "threepart.reports.plugin"]


def test_the_sie_passes_and_the_margins_are_printed(pytester):
    pytester.makepyfile(TOY + '''
@pytest.mark.threepart_cases("caseA_moment", "slip_Q0.4")
def test_sie(threepart_case, threepart_check):
    checks = threepart_check(sie(threepart_case), threepart_case, comparison="sie")
    from threepart.tolerances import NORMAL_QUANTITIES, SLIP_QUANTITIES, STRESS_QUANTITIES
    slip = SLIP_QUANTITIES + STRESS_QUANTITIES if threepart_case.kind == "slip" else ()
    assert [c.quantity for c in checks] == list(NORMAL_QUANTITIES + slip)
''')
    result = pytester.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(passed=2)
    result.stdout.fnmatch_lines(["*threepart margins*", "*test_sie?slip_Q0.4?*",
                                 "*quantity*value*reference*error*limit*margin*",
                                 "*q_interior_max*max|q|"])


def test_a_wrong_pressure_fails_naming_the_quantity(pytester):
    pytester.makepyfile(TOY + '''
@pytest.mark.threepart_cases("general")
def test_wrong(threepart_case, threepart_check):
    res = sie(threepart_case)
    toy = types.SimpleNamespace(a=res.a, c=res.c, pressure=lambda x: 1.01 * res.pressure(x))
    threepart_check(toy, threepart_case)
''')
    result = pytester.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*threepart_check general: out of tolerance: p_left error *> limit*",
                                 "*p_right*FAILED*"])
    assert "a error" not in result.stdout.str()


def test_only_tests_that_ask_for_a_case_are_parametrised(pytester):
    pytester.makepyfile('''
import pytest

def test_plain():
    pass

def test_every_case(threepart_case):
    assert threepart_case.name

@pytest.mark.threepart_cases(kinds="slip", suite="verify")
def test_slip_cases(threepart_case):
    assert threepart_case.kind == "slip"
''')
    from threepart.problem.catalogue import load_cases

    cases = load_cases(None)
    slips = [c for c in cases if c.kind == "slip" and "verify" in c.suites]
    result = pytester.runpytest("-p", "no:cacheprovider")
    result.assert_outcomes(passed=1 + len(cases) + len(slips))
    assert "threepart margins" not in result.stdout.str()


def test_an_unknown_case_is_a_usage_error(pytester):
    pytester.makepyfile('''
import pytest

@pytest.mark.threepart_cases("no_such_case")
def test_x(threepart_case):
    pass
''')
    result = pytester.runpytest("-p", "no:cacheprovider")
    assert result.ret != 0
    result.stdout.fnmatch_lines(["*'no_such_case' is not a catalogue case*"])


def _sie(case):
    m = registry.get("sie")
    return m.normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)


@pytest.mark.parametrize("factor, fails", [(3.0, True), (0.3, False)])
def test_each_limit_can_fail_and_only_that_one(factor, fails):
    """``a`` moved by 3x (0.3x) its limit in units of W fails (passes) exactly that check."""
    case = get_case("caseA_moment")
    res = _sie(case)
    W = res.a + res.c
    shift = factor * tolerance("fem-default", "a").limit * W
    toy = types.SimpleNamespace(a=res.a + shift, c=res.c, alpha=res.alpha, pressure=res.pressure)
    checks = check(toy, case)
    assert [c.quantity for c in checks if not c.passed] == (["a"] if fails else [])


def test_given_tolerances_replace_the_table():
    case = get_case("general")
    res = _sie(case)
    toy = types.SimpleNamespace(a=res.a, c=res.c, pressure=lambda x: 1.001 * res.pressure(x))
    assert not all(c.passed for c in check(toy, case))
    loose = {q: 2e-3 for q in ("p_left", "p_right", "p_interior_max", "p_L2")}
    checks = check(toy, case, tolerances=loose)
    assert all(c.passed for c in checks)
    assert {c.quantity for c in checks if c.reason == "given by the test"} == set(loose)
    # alpha, P and s are not compared for a result that does not give them
    assert {c.quantity for c in checks} & {"alpha", "P", "s"} == set()


def test_bad_input_is_named():
    case = get_case("general")
    res = _sie(case)
    with pytest.raises(TypeError, match="no attribute `a`"):
        check(types.SimpleNamespace(c=1.0, pressure=res.pressure), case)
    with pytest.raises(TypeError, match="callable `pressure"):
        check(types.SimpleNamespace(a=1.0, c=1.0, pressure=None), case)
    with pytest.raises(ValueError, match=r"`result.a` = nan must be finite"):
        check(types.SimpleNamespace(a=float("nan"), c=1.0, pressure=res.pressure), case)
    with pytest.raises(ValueError, match="`comparison` = 'nope'"):
        check(res, case, comparison="nope")
    with pytest.raises(ValueError, match="`tolerances` names 'd'"):
        check(res, case, tolerances={"d": 1e-3})
    with pytest.raises(ValueError, match=r"`tolerances\['a'\]` = -1"):
        check(res, case, tolerances={"a": -1})


@pytest.mark.slow
def test_the_plugin_works_from_an_outside_project(isolated, tmp_path):
    """threepart's wheel and pytest in an isolated venv: an outside project's test uses the plugin."""
    env = isolated
    python = env / "bin" / "python"
    done = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q",
                           "--no-compile", "pytest"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    project = tmp_path / "outside"
    project.mkdir()
    (project / "test_outside.py").write_text(TOY + '''
@pytest.mark.threepart_cases("caseA_moment")
def test_sie(threepart_case, threepart_check):
    threepart_check(sie(threepart_case), threepart_case, comparison="sie")


@pytest.mark.threepart_cases("caseA_moment")
def test_wrong(threepart_case, threepart_check):
    res = sie(threepart_case)
    threepart_check(types.SimpleNamespace(a=1.01 * res.a, c=res.c, pressure=res.pressure), threepart_case)
''', encoding="utf-8")
    run = subprocess.run([str(python), "-m", "pytest", "-p", "no:cacheprovider", "-rA"], cwd=project,
                         capture_output=True, text=True)
    out = run.stdout
    assert "1 failed, 1 passed" in out, out[-3000:]
    assert "threepart margins" in out and "out of tolerance: a error" in out, out[-3000:]
    assert str(env) in subprocess.run([str(python), "-c", "import threepart; print(threepart.__file__)"],
                                      capture_output=True, text=True, cwd=project).stdout

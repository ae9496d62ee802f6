"""The examples (``examples/``): each gallery script run as a script, what it prints against an
independent reference (a formula, a limit, another method); the tamaas one where its extra is missing."""
from __future__ import annotations

import math
import os
import re
import runpy
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Callable

import pytest
from scipy.optimize import minimize_scalar

from threepart.tolerances import tolerance

ROOT = Path(__file__).resolve().parents[1]

#: pytest on the two pytest examples in one fresh interpreter where ``import tamaas`` fails, as it
#: does without the bench extra (whether or not this environment has it); the SIE plugin example
#: does not import tamaas. One interpreter and one pytest start-up for both (3 s of CPU each)
PYTEST_EXAMPLES = """
import sys
sys.modules["tamaas"] = None      # import tamaas -> ModuleNotFoundError
import pytest
sys.exit(pytest.main(["-p", "no:cacheprovider", "-n", "0", "-q", "-rA", "--continue-on-collection-errors",
                      "examples/test_plugin_sie.py", "examples/test_tamaas_plugin.py"]))
"""
#: the run's exit statuses where every collected test ran: all passed, or some failed
RAN = (pytest.ExitCode.OK, pytest.ExitCode.TESTS_FAILED)


def _naming(run: subprocess.CompletedProcess, example: str) -> list[str]:
    """The lines of the run's output that name the example file ``example``."""
    return [ln for ln in run.stdout.splitlines() if f"examples/{example}" in ln]


@pytest.fixture(scope="module")
def pytest_examples() -> subprocess.CompletedProcess:
    """The run of :data:`PYTEST_EXAMPLES`, shared by the two tests of what it prints."""
    return subprocess.run([sys.executable, "-c", PYTEST_EXAMPLES], cwd=ROOT, capture_output=True,
                          text=True, start_new_session=True, timeout=600)


def test_the_tamaas_example_without_the_bench_extra_is_one_skip_that_names_it(pytest_examples):
    """Not a ModuleNotFoundError traceback per case: one skip whose reason names the extra."""
    run = pytest_examples
    # a module-level skip collects no test of the file: the file's one line is its skip, no case
    # of it passed, failed or errored (a collection error would be an ERROR line naming it)
    assert run.returncode in RAN, run.stdout[-3000:] + run.stderr[-2000:]
    lines = _naming(run, "test_tamaas_plugin.py")
    assert len(lines) == 1 and lines[0].startswith("SKIPPED [1] examples/test_tamaas_plugin.py"), lines
    summary = run.stdout.strip().splitlines()[-1]
    assert "1 skipped" in summary and "error" not in summary, summary
    assert 'tamaas is the bench extra: pip install -e ".[bench]"' in run.stdout
    assert "ModuleNotFoundError" not in run.stdout + run.stderr


# -- the gallery: each script run as a newcomer runs it, what it prints against a formula ---------

#: the examples' material and loads, as each script sets them (asserted on its text below)
E, NU, P, R = 210e3, 0.3, 400.0, 10.0
#: the compliance of two steel bodies, eq. (4), written out here rather than taken from threepart
A = 4 * (1 - NU**2) / E
#: Hertz's half-width of the cylinder R under P, the formula the examples' limits reduce to
HERTZ_A = math.sqrt(2 * A * R * P / math.pi)
#: a figure printed to 9 decimals is within half a unit of its last digit
PRINTED_9 = 5e-10
#: one printed to 6 decimals
PRINTED_6 = 5e-7
#: one printed to 12 decimals (the contact ends compared between methods)
PRINTED_12 = 5e-13
#: two figures printed with 10 significant digits (``.9e``) each: their ratio, within the rounding
TWO_PRINTED = 1e-9
#: Mindlin's energy against the closed form's, printed with 10 significant digits: the rounding
#: of the print (5e-10) and the closed form's own round-off (tests/test_fretting.py, 1e-12)
MINDLIN = 1e-9
#: ∫q dx by adaptive quadrature (epsrel 1e-12) on panels ending at every kink, printed to 9
#: decimals of Q = 100: the identity ∫q = Q to 1e-11 of Q (measured 0 at the printed digits)
SHEAR_INTEGRAL = 1e-11
#: |q| - f p is zero on the slip zones up to round-off of f p (measured exactly 0), of f p_max
COULOMB_ROUNDING = 1e-12
#: the loop area by the trapezoid rule on 401 states a branch against the energy by the Gauss rule:
#: the trapezoid's O(h^2) error (measured 6.3e-6 of the energy)
LOOP_TRAPEZOID = 1e-4
#: ∫p dx of 81 nodes by the trapezoid rule, whose square-root ends it overestimates (measured
#: 8.7e-4 of P): the referee's load error of a pressure scaled by 1.05 is 0.05 within it
NODES_81 = 2e-3


def run_example(name: str, tmp_path: Path) -> str:
    """Run ``examples/<name>`` as a script (``python examples/<name>``) from an empty directory; it
    must write nothing there nor leave anything in its temporary directory.

    The one example run in a fresh interpreter, as a newcomer runs it; the others run in this
    one (:func:`run_in_process`), which spares an interpreter's start and threepart's import each.
    """
    work, temp = tmp_path / "work", tmp_path / "tmp"
    work.mkdir()
    temp.mkdir()
    env = {**os.environ, "TMPDIR": str(temp), "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, str(ROOT / "examples" / name)], cwd=work, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-3000:]
    assert list(work.iterdir()) == [], f"{name} wrote into the working directory"
    assert list(temp.iterdir()) == [], f"{name} left files in its temporary directory"
    return done.stdout


@pytest.fixture
def run_in_process(tmp_path, monkeypatch, capfd) -> Callable[[str], str]:
    """:func:`run_example` in this interpreter: ``examples/<name>`` run as ``__main__`` by runpy,
    with a fresh namespace, its own directory on ``sys.path``, an empty working directory and an
    empty temporary directory (``TMPDIR`` and :mod:`tempfile`'s cached one), its output (file
    descriptors 1 and 2, a child's included) captured; a ``sys.exit`` other than 0 fails."""
    def run(name: str) -> str:
        work, temp = tmp_path / "work", tmp_path / "tmp"
        work.mkdir()
        temp.mkdir()
        script = ROOT / "examples" / name
        monkeypatch.chdir(work)
        monkeypatch.setenv("TMPDIR", str(temp))
        monkeypatch.setenv("MPLBACKEND", "Agg")
        monkeypatch.setattr(tempfile, "tempdir", str(temp))
        monkeypatch.setattr(sys, "argv", [str(script)])
        monkeypatch.syspath_prepend(str(script.parent))
        capfd.readouterr()
        try:
            runpy.run_path(str(script), run_name="__main__")
        except SystemExit as stop:
            assert stop.code in (None, 0), f"{name} exited with {stop.code}"
        out = capfd.readouterr().out
        assert list(work.iterdir()) == [], f"{name} wrote into the working directory"
        assert list(temp.iterdir()) == [], f"{name} left files in its temporary directory"
        return out
    return run


def number(pattern: str, text: str) -> float:
    found = re.search(pattern, text)
    assert found, f"{pattern!r} not in the output:\n{text}"
    return float(found.group(1))


def test_every_example_script_is_run_by_a_test():
    scripts = {p.name for p in (ROOT / "examples").glob("*.py") if not p.name.startswith("test_")}
    assert scripts == set(EXAMPLES), scripts ^ set(EXAMPLES)
    for name in scripts - set(OWN_PROBLEM):
        text = (ROOT / "examples" / name).read_text(encoding="utf-8")
        assert "A = similar_pair(E=210e3, nu=0.3)" in text and "400.0" in text, name


def test_normal_contact_meets_hertz_and_the_methods_agree(run_in_process):
    out = run_in_process("normal_contact.py")
    assert abs(number(r"Hertz: a = (\S+) mm", out) - HERTZ_A) <= PRINTED_9
    p0 = 2 * P / (math.pi * HERTZ_A)
    assert abs(number(r"Hertz: a = \S+ mm, p0 = (\S+) MPa", out) - p0) <= PRINTED_6
    ends = {m: (number(rf"{m}: a = (\S+)", out), number(rf"{m}: a = \S+ c = (\S+)", out))
            for m in ("closedform", "sie", "fem")}
    W = sum(ends["closedform"])
    for method, comparison in (("sie", "sie"), ("fem", "fem-quick")):
        for k, quantity in enumerate(("a", "c")):
            error = abs(ends[method][k] - ends["closedform"][k])
            assert error <= tolerance(comparison, quantity).limit * W + PRINTED_12, (method, quantity, error)


def test_partial_slip_is_cattaneo_mindlin_for_a_cylinder_and_balances_Q(run_in_process):
    out = run_in_process("partial_slip.py")
    Q, f = 100.0, 0.5
    d = HERTZ_A * math.sqrt(1 - Q / (f * P))
    assert abs(number(r"cylinder: .*stick zone \[(\S+),", out) + d) <= PRINTED_9
    assert abs(number(r"cylinder: .*stick zone \[\S+, (\S+)\]", out) - d) <= PRINTED_9
    zones = {m: (number(rf"{m}: .*stick zone \[(\S+),", out), number(rf"{m}: .*stick zone \[\S+, (\S+)\]", out))
             for m in ("closedform", "sie")}
    width = zones["closedform"][1] - zones["closedform"][0]
    for k in (0, 1):
        assert abs(zones["sie"][k] - zones["closedform"][k]) <= tolerance("sie", "d").limit * width / 2 + PRINTED_12
    assert abs(number(r"integral of q\(x\) = (\S+) N/mm", out) - Q) <= SHEAR_INTEGRAL * Q + PRINTED_9
    f_p_max = number(r"f p_max = (\S+) MPa", out)
    assert number(r"largest \|q\| - f p = (\S+) MPa", out) <= COULOMB_ROUNDING * f_p_max


def test_fretting_energy_is_mindlins_for_a_cylinder_and_the_loop_area(run_in_process):
    out = run_in_process("fretting_cycle.py")
    f = 0.5
    q = 0.4
    W = 2 * A / math.pi * (f * P) ** 2 * ((1 - q) * math.log1p(-q) + q - q * q / 2)
    assert number(r"cylinder: energy per cycle = (\S+) N", out) == pytest.approx(W, rel=MINDLIN)
    energy = {m: number(rf"{m}: energy per cycle = (\S+) N", out) for m in ("closedform", "sie")}
    assert energy["sie"] == pytest.approx(energy["closedform"],
                                          rel=tolerance("sie", "energy").limit + TWO_PRINTED)
    for m in energy:
        assert number(rf"{m}: .*loop area = (\S+),", out) == pytest.approx(energy[m], rel=LOOP_TRAPEZOID)


def test_judging_a_csv_passes_hertz_and_catches_a_five_percent_load_error(run_in_process):
    out = run_in_process("judge_a_csv.py")
    good, bad = out.split("hertz_thick.csv")
    assert "PASSED" in good and "exit status 0" in good and "  pitfall " not in good
    assert "FAILED" in bad and "exit status 1" in bad and "pitfall load" in bad
    assert abs(number(r"failed: P: error (\S+) >", bad) - 0.05) <= NODES_81


def test_the_steady_state_at_constant_load_is_the_fretting_cycle(tmp_path):
    """At P, s constant a cycle between +-Q_max is Masing's fretting cycle: its energy and zone."""
    out = run_example("flight_cycle.py", tmp_path)
    fretting = number(r"fretting cycle: energy per cycle = (\S+) N", out)
    steady = number(r"steady state between \+-Q_max: energy per cycle = (\S+) N", out)
    assert steady == pytest.approx(fretting, rel=tolerance("steady", "round_off").limit + TWO_PRINTED)
    for end in (r"\[(\S+), \S+\] mm", r"\[\S+, (\S+)\] mm"):
        zone_f, zone_s = number(r"fretting cycle:.*" + end, out), number(r"steady state.*" + end, out)
        assert abs(zone_s - zone_f) <= PRINTED_9 * 2 + tolerance("steady", "round_off").limit
    assert "shaken down: False" in out


def test_stresses_are_mcewens_and_the_hot_spots_sit_at_an_edge(run_in_process):
    """McEwen's axis stresses (Johnson, Contact Mechanics, eq. 4.49), and fretting's hot spots."""
    out = run_in_process("stresses_and_fatigue.py")
    assert number(r"\|szz - McEwen\| on the axis = (\S+) p0", out) <= tolerance("refs", "stress").limit
    # the shear on the axis, (sxx - szz)/2 = (p0/a) (z - z^2/sqrt(a^2 + z^2)), largest at z = 0.786 a
    best = minimize_scalar(lambda t: -(t - t * t / math.sqrt(1 + t * t)), bounds=(0.1, 2.0),
                           method="bounded", options={"xatol": 1e-10})
    assert abs(number(r"largest shear on the axis = (\S+) p0", out) + best.fun) <= PRINTED_5 + AXIS_GRID**2
    assert abs(number(r"p0 at z = (\S+) a", out) - best.x) <= AXIS_GRID
    contact = (number(r"contact \[(\S+),", out), number(r"contact \[\S+, (\S+)\] mm, grid", out))
    spots = re.findall(r"(\w+): hot spot x = (\S+) mm, z = (\S+) mm", out)
    assert {name for name, _, _ in spots} >= {"von_mises_range", "swt", "findley"}
    for name, x, z in spots:
        assert float(z) == 0.0 and min(abs(float(x) - end) for end in contact) <= HOT_GRID, name


def test_edges_of_a_cylinder_are_hertz_and_mindlins_and_the_methods_agree(run_in_process):
    """K_N = p0 sqrt(2/a), K_T = Q/(pi sqrt(2a)); the slip zone tends to Cattaneo's as Q -> 0."""
    out = run_in_process("edges.py")
    p0 = 2 * P / (math.pi * HERTZ_A)
    f = 0.5
    errors = []
    for Q in (100.0, 10.0, 1.0):
        line = re.search(rf"cylinder, Q = +{Q}:.*", out)
        assert line, out
        K_N, K_T = number(r"K_N = (\S+),", line.group()), number(r"K_T = (\S+),", line.group())
        assert K_N == pytest.approx(p0 * math.sqrt(2 / HERTZ_A), rel=TWO_PRINTED)
        assert K_T == pytest.approx(Q / (math.pi * math.sqrt(2 * HERTZ_A)), rel=TWO_PRINTED)
        cattaneo = HERTZ_A * (1 - math.sqrt(1 - Q / (f * P)))
        errors.append(abs(number(r"slip zone (\S+) mm", line.group()) / cattaneo - 1))
    # the asymptotic zone's error falls with Q/(fP) = 0.5, 0.05, 0.005: about q/4 (1 - sqrt(1-q) = q/2 + q^2/8 ...)
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] <= MINDLIN_LIMIT
    for side in ("left", "right"):
        values = {m: re.search(rf"{m} +{side} edge .*", out) for m in ("closedform", "sie")}
        cf, si = (v.group() if v else "" for v in values.values())
        for key in ("K_N", "K_T"):
            assert number(rf"{key} = (\S+),", si) == pytest.approx(number(rf"{key} = (\S+),", cf),
                                                                  rel=tolerance("edges", "K_N_exact").limit + TWO_PRINTED)


def test_the_load_history_repeats_the_fretting_cycles_energy(run_in_process):
    """Each marched cycle of +-Q_max at constant P is Masing's cycle: the closed form's energy."""
    out = run_in_process("load_history.py")
    exact = number(r"fretting cycle \(closed form\): energy per cycle = (\S+) N", out)
    marched = [float(e) for e in re.findall(r"marched cycle \d+: energy = (\S+) N", out)]
    assert len(marched) == 2                   # five states: the first loading, then two cycles
    for energy in marched:
        assert energy == pytest.approx(exact, rel=tolerance("steady", "march_energy").limit)


def test_the_plugin_example_judges_the_sie_by_the_closed_form(pytest_examples):
    """pytest on ``examples/test_plugin_sie.py``: its four cases pass against the closed form."""
    done = pytest_examples
    assert done.returncode in RAN, done.stdout[-3000:] + done.stderr[-2000:]
    summary = [ln for ln in _naming(done, "test_plugin_sie.py") if not ln.startswith("examples/")]
    assert len(summary) == 4 and all(ln.startswith("PASSED ") for ln in summary), summary
    assert "threepart margins" in done.stdout


#: the asymptotic slip zone against Cattaneo's exact one at Q/(fP) = 0.005: their ratio is
#: 1 - q/4 + O(q^2), so 1.3e-3 (measured 1.25e-3), and a wrong factor of the zone fails
MINDLIN_LIMIT = 1.3e-3
#: the examples' grids: the axis sampled every 3a/3000 (a maximum flat to second order in the step),
#: the fatigue grid every 0.025 mm along the surface
AXIS_GRID, HOT_GRID = 1e-3, 0.025
#: a figure printed to 5 decimals
PRINTED_5 = 5e-6

#: each example script and its test above
EXAMPLES = ("normal_contact.py", "partial_slip.py", "fretting_cycle.py", "judge_a_csv.py",
            "flight_cycle.py", "stresses_and_fatigue.py", "edges.py", "load_history.py",
            "judge_a_calculix_file.py", "match_a_pad.py", "validity_map.py")
#: the examples whose problem is their own (a kept file's, the map's scale-free points), not the shared one above
OWN_PROBLEM = ("judge_a_calculix_file.py", "validity_map.py")


#: the kept CalculiX run's load (its deck: ``--P 72.115``) and element size (``--h 0.16``)
CCX_P, CCX_H = 72.115, 0.16
#: ∫p dx of that coarse run's nodes (trapezoidal, W/h about 14) against P: each square-root end
#: spans about two elements (measured 1.2e-2; tests/test_referee.py's COARSE_LOAD)
CCX_COARSE_LOAD = 5e-2


def test_judging_a_calculix_file_reads_its_load_and_names_its_coarse_ends(run_in_process):
    """The kept .frd's ∫p is the deck's P to the coarse mesh's error, its contact the closed form's
    within an element, and the judge fails it naming the unresolved ends (exit status 1)."""
    out = run_in_process("judge_a_calculix_file.py")
    load = number(r"integral of p by the trapezoid rule: (\S+) N/mm", out)
    assert abs(load - CCX_P) <= CCX_COARSE_LOAD * CCX_P
    # Hertz-like ends of the closed form (b = 1, R = 200: a flat with rounded corners), written out:
    first, last = number(r"from x = (\S+) to", out), number(r"from x = \S+ to (\S+) mm", out)
    left, right = number(r"closed form: contact \[(\S+),", out), number(r"closed form: contact \[\S+, (\S+)\]", out)
    assert abs(first - left) <= CCX_H and abs(last - right) <= CCX_H   # measured 0.035 and 0.054 mm
    assert "pitfall end-resolution: the left end is resolved by 2 nodes" in out
    assert out.rstrip().endswith("exit status 1")


#: K_N and K_T of Hertz's cylinder from the pad's R, P and Q printed with 10 significant digits,
#: against the flank's: the print's rounding carried through a and p0 (measured 1.8e-10)
PAD_FROM_PRINT = 1e-9


def test_the_matched_pads_are_hertz_cylinders_with_the_flanks_edge_multipliers(run_in_process):
    """E9: each pad's own K_N = p0 sqrt(2/a) and K_T = Q/(pi sqrt(2a)), by Hertz's formulas from
    its printed R, P and Q, are the flank's at that edge (docs/EDGES.md §6)."""
    out = run_in_process("match_a_pad.py")
    for edge in ("left", "right"):
        line = next(ln for ln in out.splitlines() if ln.startswith(f"{edge} edge:"))
        K_N, K_T = number(r"flank K_N = (\S+),", line), number(r"flank K_N = \S+, K_T = (\S+);", line)
        R, P_pad = number(r"pad R = (\S+) mm", line), number(r"P = (\S+) N/mm, Q", line)
        Q = number(r"Q = (\S+) N/mm;", line)
        a = math.sqrt(2 * A * R * P_pad / math.pi)
        p0 = 2 * P_pad / (math.pi * a)
        assert abs(p0 * math.sqrt(2 / a) / K_N - 1) <= PAD_FROM_PRINT, edge
        assert abs(Q / (math.pi * math.sqrt(2 * a)) / abs(K_T) - 1) <= PAD_FROM_PRINT, edge


#: the map's control limit on the closed form against a model of its own assumptions (``threepart
#: map``: the control within 1e-3), here on the contact's extent at the small overhang
MAP_CONTROL = 1e-3
#: how far past the FE model's own error estimate the large overhang's error must lie to be the
#: formulas' (measured 44 x)
MAP_RESOLVED = 10.0


def test_the_validity_map_sees_the_formulas_hold_at_small_slopes_and_stop_at_large(run_in_process):
    """Against the finite-body FEM (another method): at (a - b)/R1 = 0.01 the closed form's a is within
    the map's control limit (plus the FE estimate); at 0.3 its error is 10 x past the FE estimate."""
    out = run_in_process("validity_map.py")
    small, large = (next(ln for ln in out.splitlines() if ln.startswith(f"overhang (a - b)/R1 = {o}:"))
                    for o in ("0.01", "0.3"))
    for line, bound in ((small, None), (large, MAP_RESOLVED)):
        err, fe = number(r"error in a (\S+),", line), number(r"own error estimate (\S+)", line)
        if bound is None:
            assert abs(err) <= MAP_CONTROL + fe
        else:
            assert abs(err) >= bound * fe

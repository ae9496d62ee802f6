"""GetFEM as the outside referee of friction (issue 38): the script's text, its run, its reader.

Without GetFEM every check but the slow one runs: the script is compiled and
its parameters read back, its gap is checked against the profile of eq. 2,
the error paths of a run are driven by stand-in interpreters, and the loop's
energy is checked on a Masing loop of known area. With an interpreter that
imports ``getfem`` the slow test runs Hertz's partial slip of two similar
bodies and checks Mindlin's stick zone and ``∫q = Q``.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import threepart
from threepart import Punch, getfem, readers
from threepart.errors import (FullSlidingError, GetfemError, GetfemMissing, InputError, ReaderError,
                              ThreepartError)
from threepart.getfem import run as getfem_run
from threepart.getfem.read import FORMAT, GetfemRun, State, loop_energy, read_run
from threepart.problem.material import similar_pair
from threepart.tolerances import tolerance

#: sums of a few floats: exact up to rounding (the table's closed-form entry)
EXACT = tolerance("closedform", "exact").limit
#: the catalogue's material and the CalculiX column's small-slope scaling (radii x 20, P / 20)
E, NU, SCALE = 210000.0, 0.3, 20.0
HERTZ = Punch(R1=10.0 * SCALE, R2=10.0 * SCALE, b=0.0)
P_HERTZ = 28846.0 / SCALE


#: the contact ends the scripts of the fast tests are graded to (mm)
A_TEST, C_TEST = 1.0, 1.2


def _script(**kw) -> str:
    args = dict(a=A_TEST, c=C_TEST, E=E, nu=NU, f=0.5, Q=0.4 * 0.5 * 1442.3)
    args.update(kw)
    P, s = (None, 0.0) if kw.get("history") is not None and kw.get("Q", 0) is None else (1442.3, 0.2)
    return getfem.write_script(Punch(R1=200.0, R2=100.0, b=1.0), P, s, **args)


def test_the_script_states_what_it_models_compiles_and_carries_its_loads():
    text = _script(settings=getfem.JobSettings(n=64, steps=5), title="slip_Q0.4 x20")
    compile(text, "job.py", "exec")
    head = text[:text.index("HEADER = __doc__")]
    for phrase in ("Two similar elastic bodies", "plane strain", "P2 triangles", "v(x) of eq. 2",
                   "fixed normal [0; 1]", "Coulomb_friction_coupled_projection", "f = 0.5",
                   "P = 1442.3 N/mm at x = s = 0.2 mm (tilt free)", "contact_pressure is",
                   "compressive positive", "along\n  +x", "slip_Q0.4 x20", "halved"):
        assert phrase in head, phrase
    params = getfem.params_of(text)
    assert (params["P"], params["s"], params["f"], params["E"], params["nu"]) == (1442.3, 0.2, 0.5, E, NU)
    assert params["h"] == pytest.approx(2.2 / 64, rel=EXACT)
    assert params["zone"][0] < -A_TEST and params["zone"][1] > C_TEST   # the zone holds the contact
    assert params["legs"] == [{"branch": "loading", "P": 1442.3, "s": 0.2, "Q": 0.4 * 0.5 * 1442.3,
                               "sigma_bulk": 0.0, "steps": 5}]
    assert "The substrate's base is clamped" in head
    assert params["ktheta"] == 0.0 and getfem.params_of(_script(tilt="suppressed"))["ktheta"] > 0


def test_a_cycle_runs_zero_to_Q_max_to_minus_Q_max_and_back_with_twice_the_steps_per_reversal():
    path = getfem.params_of(_script(Q=None, Q_max=100.0, settings=getfem.JobSettings(steps=3)))["legs"]
    assert [(leg["branch"], leg["Q"], leg["steps"]) for leg in path] == [
        ("loading", 100.0, 3), ("unloading", -100.0, 6), ("reloading", 100.0, 6)]


def test_the_bulk_stress_rises_with_the_shear_and_frees_the_substrates_base():
    """docs/BULK_STRESS.md's load path: P first, then Q and sigma_bulk together; in a cycle in phase."""
    text = _script(sigma_bulk=80.0)
    compile(text, "job.py", "exec")
    head = text[:text.index("HEADER = __doc__")]
    assert "sigma_bulk together, in proportion" in head and "moves with the uniform" in head
    assert [(leg["Q"], leg["sigma_bulk"]) for leg in getfem.params_of(text)["legs"]] == [(0.4 * 0.5 * 1442.3, 80.0)]
    cycle = getfem.params_of(_script(Q=None, Q_max=100.0, sigma_bulk=20.0))["legs"]
    assert [(leg["Q"], leg["sigma_bulk"]) for leg in cycle] == [(100.0, 20.0), (-100.0, -20.0), (100.0, 20.0)]
    with pytest.raises(InputError, match="`sigma_bulk`"):
        _script(sigma_bulk=float("nan"))


#: a flight cycle of slip_Q0.4 x 20's punch: P, Q and the bulk stress swing in phase (both ends slip)
FLIGHT = [(0.9 * 1442.3, 0.2, -0.3 * 0.5 * 1442.3, -30.0), (1442.3, 0.2, 0.4 * 0.5 * 1442.3, 40.0)]


def test_a_load_history_is_each_state_in_turn_from_the_first_states_normal_load(tmp_path):
    text = _script(Q=None, history=FLIGHT * 2, settings=getfem.JobSettings(steps=4))
    compile(text, "job.py", "exec")
    params = getfem.params_of(text)
    assert (params["P"], params["s"]) == FLIGHT[0][:2]
    assert [(leg["P"], leg["s"], leg["Q"], leg["sigma_bulk"], leg["steps"]) for leg in params["legs"]] == \
        [(*st, 4) for st in FLIGHT * 2]
    assert "state 3: P = 1442.3, s = 0.2, Q = 288.46, sigma_bulk = 40 (4 steps)" in text
    csv = tmp_path / "h.csv"
    csv.write_text("P,s,Q,sigma_bulk\n" + "\n".join(",".join(map(repr, st)) for st in FLIGHT * 2) + "\n")
    assert getfem.params_of(_script(Q=None, history=str(csv), settings=getfem.JobSettings(steps=4)))["legs"] \
        == params["legs"]
    with pytest.raises(InputError, match="`history` alone"):
        _script(history=FLIGHT)
    with pytest.raises(FullSlidingError, match=r"`history\[1\].Q`"):
        _script(Q=None, history=[FLIGHT[0], (100.0, 0.2, 60.0, 0.0)])


@pytest.mark.parametrize("punch", [Punch(R1=10.0, R2=5.0, b=1.0), Punch(R1=10.0, R2=6.0, b=1.0, R=40.0),
                                   Punch(R1=10.0, R2=10.0, b=1.0, R=-200.0), Punch(R1=10.0, R2=5.0, b=0.0)])
def test_the_gap_is_the_profile_of_eq_2(punch):
    """The weak-form text, evaluated by numpy, is eq. 2's piecewise profile on all three segments."""
    expr = getfem.gap_text(punch).replace("sqr(", "np.square(").replace("pos_part(", "np.maximum(0.0, ")
    x = np.linspace(-3.0, 3.0, 601)
    value = eval(expr.replace("X(1)", "x"), {"np": np, "x": x})   # noqa: S307 - our own text
    assert np.max(np.abs(value - punch.profile(x))) <= EXACT * np.max(np.abs(punch.profile(x)))


def test_bad_input_is_refused_by_name():
    with pytest.raises(FullSlidingError, match="`Q`"):
        _script(Q=0.5 * 1442.3)
    with pytest.raises(InputError, match="`n` = 4"):
        getfem.JobSettings(n=4)
    with pytest.raises(InputError, match="`name`"):
        _script(name="../job")
    with pytest.raises(InputError, match="`Q`.*`Q_max`"):
        _script(Q_max=10.0)
    with pytest.raises(InputError, match="`nu`"):
        _script(nu=0.7)


def test_the_errors_belong_to_the_family_and_keep_their_builtin_bases():
    assert issubclass(GetfemError, ThreepartError) and issubclass(GetfemError, RuntimeError)
    assert issubclass(GetfemMissing, ThreepartError) and issubclass(GetfemMissing, OSError)


def test_an_interpreter_without_getfem_is_named(monkeypatch, tmp_path):
    monkeypatch.setenv(getfem_run.PYTHON_VARIABLE, str(tmp_path / "no-python"))
    with pytest.raises(GetfemMissing, match="THREEPART_GETFEM_PYTHON"):
        getfem.run_getfem("print()", tmp_path)
    assert not getfem.getfem_available()


@pytest.fixture
def stub_getfem(monkeypatch, tmp_path):
    """A stand-in ``getfem`` module (an empty file) that this interpreter imports, named as the
    interpreter of the scripts: the script's error paths run here without GetFEM."""
    stub = tmp_path / "stub"
    stub.mkdir()
    (stub / "getfem.py").write_text("")
    monkeypatch.setenv("PYTHONPATH", str(stub))
    monkeypatch.setenv(getfem_run.PYTHON_VARIABLE, sys.executable)
    getfem_run._imports_getfem.cache_clear()
    yield
    getfem_run._imports_getfem.cache_clear()


def test_a_failed_run_is_a_getfem_error_with_its_reason(stub_getfem, tmp_path):
    """A stand-in ``getfem`` module lets this interpreter run the script's error paths."""
    failing = "import sys\nsys.stderr.write('GETFEM-FAILED: Newton did not converge at Q = 3\\n')\nsys.exit(3)\n"
    with pytest.raises(GetfemError, match="Newton did not converge at Q = 3"):
        getfem.run_getfem(failing, tmp_path / "a")
    with pytest.raises(GetfemError, match="no result"):
        getfem.run_getfem("pass\n", tmp_path / "b")
    with pytest.raises(GetfemError, match="timeout"):
        getfem.run_getfem("import time\ntime.sleep(30)\n", tmp_path / "c", timeout=1.0)


def test_partial_slip_writes_the_script_of_its_problem_before_running_it(stub_getfem, tmp_path):
    """The one call grades the mesh to the closed form's contact at the ``h`` asked; a stand-in
    ``getfem`` fails the run by name, and the script stays in the folder."""
    with pytest.raises(GetfemError, match="job.py"):
        getfem.partial_slip(HERTZ, P_HERTZ, 0.0, 0.2 * P_HERTZ, 0.5, E, NU, h=0.05, workdir=tmp_path / "run")
    params = getfem.params_of((tmp_path / "run" / "job.py").read_text())
    a = threepart.solve(HERTZ, P_HERTZ, 0.0, A=similar_pair(E, NU), method="closedform").a
    assert params["h"] == pytest.approx(0.05, rel=EXACT) and params["W"] == pytest.approx(2 * a, rel=EXACT)
    with pytest.raises(FullSlidingError, match="`Q`"):
        getfem.partial_slip(HERTZ, P_HERTZ, 0.0, 0.6 * P_HERTZ, 0.5, E, NU, workdir=tmp_path / "never")
    assert not (tmp_path / "never").exists()


def _state(Q: float, branch: str, delta: float) -> State:
    x = np.linspace(-1.0, 1.0, 5)
    return State(P=10.0, Q=Q, branch=branch, delta=delta, resultant=(10.0, Q, 0.0), x=x,
                 p=1.0 - x * x, q=Q / 10.0 * (1.0 - x * x), slip=0.0 * x)


def test_the_loop_energy_is_the_area_of_a_masing_loop():
    """Loading delta = k u + c u^2: by Masing's rule the loop is c (Q_max^2 - Q^2) wide, its area
    4/3 c Q_max^3; Simpson's rule is exact on it, the trapezoids are not."""
    k, c, Qm, n = 2.0, 0.3, 1.5, 4
    load = lambda u: k * u + c * u * u                                        # noqa: E731
    states = [_state(Q, "loading", load(Q)) for Q in np.linspace(0.0, Qm, n + 1)[1:]]
    states += [_state(Q, "unloading", load(Qm) - 2 * load((Qm - Q) / 2)) for Q in np.linspace(Qm, -Qm, 2 * n + 1)[1:]]
    states += [_state(Q, "reloading", -load(Qm) + 2 * load((Qm + Q) / 2)) for Q in np.linspace(-Qm, Qm, 2 * n + 1)[1:]]
    run = GetfemRun(states=states, steps=[], params={}, time=0.0, dofs=0)
    area = loop_energy(run)
    assert area["energy"] == pytest.approx(4.0 / 3.0 * c * Qm ** 3, rel=EXACT)
    assert abs(area["trapezoid"] / area["energy"] - 1.0) > 100 * EXACT
    with pytest.raises(ReaderError, match="unloading"):
        loop_energy(GetfemRun(states=states[:n], steps=[], params={}, time=0.0, dofs=0))


def _sidecar(path: Path, states: list[State]) -> Path:
    path.write_text(json.dumps({
        "format": FORMAT, "model": "test", "params": {"f": 0.5}, "steps": [], "grid": [1, 1], "dofs": 1,
        "time": 0.0, "states": [{"P": s.P, "Q": s.Q, "branch": s.branch, "delta": s.delta,
                                 "resultant": list(s.resultant), "x": s.x.tolist(), "p": s.p.tolist(),
                                 "q": s.q.tolist(), "slip": s.slip.tolist()} for s in states]}))
    return path


def test_the_sidecar_is_read_through_the_readers_table(tmp_path):
    path = _sidecar(tmp_path / "job.getfem.json", [_state(1.0, "loading", 0.1), _state(2.0, "loading", 0.2)])
    rec = readers.read(path)
    assert rec.info["source"] == "getfem" and rec.info["Q"] == 2.0 and len(rec.info["states"]) == 2
    np.testing.assert_array_equal(rec.q, 0.2 * (1.0 - rec.x ** 2))
    bad = tmp_path / "other.getfem.json"
    bad.write_text(json.dumps({"states": []}))
    with pytest.raises(ReaderError, match="other.getfem.json.*not a threepart GetFEM sidecar"):
        readers.read(bad)
    with pytest.raises(InputError, match="no options"):
        readers.read(path, shear="q")


def _mindlin(x: np.ndarray, a: float, c: float, p0: float, f: float) -> np.ndarray:
    """Mindlin's shear of the Hertz pair: ``f p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2))``."""
    return f * p0 * (np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
                     - c / a * np.sqrt(np.clip(1 - (x / c) ** 2, 0, None)))


@pytest.mark.slow
def test_getfem_hertz_partial_slip_gives_mindlins_stick_zone_and_carries_Q(tmp_path):
    """Two similar bodies at nu = 0.3, Q = 0.4 fP, W/h = 64: the stick zone within 5e-3 W of Mindlin's
    c = a sqrt(1 - Q/fP) at both ends (from the tractions, ``|q| < (1 - margin) f p``, and from the
    slip), ∫q = Q, q within 2 % of its peak away from the ends."""
    if not getfem.getfem_available():
        pytest.skip("no interpreter imports getfem (apt-get install python3-getfem, or set "
                    "THREEPART_GETFEM_PYTHON)")
    from threepart.results.fields import stick_ends

    f, P = 0.5, P_HERTZ
    Q = 0.4 * f * P
    res = getfem.partial_slip(HERTZ, P, 0.0, Q, f, E, NU, n=64, settings=getfem.JobSettings(steps=5),
                              workdir=tmp_path)
    a = threepart.solve(HERTZ, P, 0.0, A=similar_pair(E, NU), method="closedform").a
    W, c = 2 * a, a * math.sqrt(1 - Q / (f * P))
    limit = tolerance("getfem", "stick_end").limit
    for left, right in (stick_ends(res.x, res.p, res.q, f), getfem.slip_ends(res.x, res.slip, (-a, a))):
        assert max(abs(left + c), abs(right - c)) / W <= limit, (left / a, right / a)
    assert abs(res.info["Q_integral"] / Q - 1) <= tolerance("getfem", "q_integral").limit
    assert abs(res.info["P_integral"] / P - 1) <= tolerance("getfem", "P").limit
    away = (np.abs(res.x) < a - 0.05 * W) & (np.abs(np.abs(res.x) - c) > 0.05 * W)
    q_ref = _mindlin(res.x, a, c, 2 * P / (math.pi * a), f)
    assert np.max(np.abs(res.q - q_ref)[away]) / np.max(q_ref) <= tolerance("getfem", "q_interior_max").limit
    vtu = readers.read(tmp_path / "job.vtu", shear="contact_shear")
    np.testing.assert_array_equal(vtu.q, res.q)
    assert all(step["converged"] for step in res.info["newton"])


def test_slip_ends_recover_the_stick_zone_of_a_three_halves_power_slip():
    """Past a stick-slip end the slip grows as the distance to the power 3/2: the ends are found
    exactly from nodes that never fall on them, whatever noise the sticking nodes carry below the margin."""
    x = np.linspace(-1.0, 1.0, 81)
    left, right = -0.6137, 0.4521
    slip = 3e-4 * (np.maximum(left - x, 0.0) ** 1.5 - np.maximum(x - right, 0.0) ** 1.5)
    noisy = slip + np.where((x > left) & (x < right), 1e-7 * np.cos(40 * x), 0.0)
    lo, hi = getfem.slip_ends(x, noisy, (-0.99, 0.99))
    assert max(abs(lo - left), abs(hi - right)) <= 100 * EXACT   # the slipping nodes are exact: rounding
    with pytest.raises(ReaderError, match="reaches an end"):
        getfem.slip_ends(x, np.where(x < left, slip, 0.0), (-0.99, 0.99))


def _need_getfem() -> None:
    if not getfem.getfem_available():
        pytest.skip("no interpreter imports getfem (apt-get install python3-getfem, or set "
                    "THREEPART_GETFEM_PYTHON)")


#: slip_Q0.4 x 20 (caseA_moment's punch, radii x 20, P / 20, tilt free) and its bulk tension (MPa):
#: about half the slip-direction margin 8 Q/(pi W) = 167 MPa at the start of the load path (eq. B8)
SLIP_PUNCH, SLIP_P, SLIP_S, SIGMA_BULK = Punch(R1=200.0, R2=100.0, b=1.0), 28846.0 / SCALE, 0.2, 80.0


@pytest.mark.slow
def test_getfem_partial_slip_under_a_bulk_stress_moves_the_stick_zone_as_the_closed_form(tmp_path):
    """slip_Q0.4 x 20 with sigma_bulk = 80 MPa rising with Q (docs/BULK_STRESS.md), W/h = 64: the stick
    zone, its centre moved by 0.036 W towards +x by the bulk stress, within 5e-3 W of the closed
    form's at both ends (read from the slip), ∫q = Q, q within 2 % of its peak away from the ends."""
    _need_getfem()
    f = 0.5
    Q = 0.4 * f * SLIP_P
    res = getfem.partial_slip(SLIP_PUNCH, SLIP_P, SLIP_S, Q, f, E, NU, sigma_bulk=SIGMA_BULK, n=64, workdir=tmp_path)
    ref = threepart.solve(SLIP_PUNCH, SLIP_P, SLIP_S, A=similar_pair(E, NU), Q=Q, f=f, sigma_bulk=SIGMA_BULK,
                          method="closedform")
    W, (lo, hi) = ref.a + ref.c, ref.stick_zone
    left, right = getfem.slip_ends(res.x, res.slip, (-ref.a, ref.c))
    assert max(abs(left - lo), abs(right - hi)) / W <= tolerance("getfem", "stick_end").limit, (left, right)
    assert abs(res.info["Q_integral"] / Q - 1) <= tolerance("getfem", "q_integral").limit
    away = ((res.x > -ref.a + 0.05 * W) & (res.x < ref.c - 0.05 * W) & (np.abs(res.x - lo) > 0.05 * W)
            & (np.abs(res.x - hi) > 0.05 * W))
    q_ref = ref.shear(res.x)
    assert np.max(np.abs(res.q - q_ref)[away]) / np.max(q_ref) <= tolerance("getfem", "q_interior_max").limit
    assert "moves with the uniform" in (tmp_path / "job.py").read_text()


@pytest.mark.slow
def test_getfem_flight_cycle_dissipates_the_steady_states_energy(tmp_path):
    """The flight cycle [state0, state1, state0, state1] of slip_Q0.4 x 20's punch (P, Q and the bulk
    stress in phase), W/h = 64, 16 steps a state: over its last cycle the friction energy and the
    largest slip amplitude within issue 38's 2 % of the closed form's periodic steady state
    (docs/STEADY_STATE.md), judged by `threepart compare`'s own judge of a file's states, with no
    pitfall (16 states per half-cycle resolve the reversal)."""
    _need_getfem()
    from threepart.reports.referee.friction_cycle import flight_reference, judge_cycle

    f = 0.5
    states = [(0.9 * SLIP_P, SLIP_S, -0.3 * f * SLIP_P, -30.0), (SLIP_P, SLIP_S, 0.4 * f * SLIP_P, 40.0)]
    run = getfem.load_history(SLIP_PUNCH, states * 2, f, E, NU, n=64, steps=16, workdir=tmp_path)
    ref = flight_reference(SLIP_PUNCH, *states, A=similar_pair(E, NU), f=f)
    doc = judge_cycle(run.states, ref, source="flight")
    assert doc["passed"], (doc["checks"], doc["pitfalls"])
    assert run.energy == pytest.approx(doc["obtained"]["energy"], rel=EXACT)
    assert abs(run.energy / ref.energy - 1) <= tolerance("referee", "energy").limit
    assert all(step["converged"] for step in run.info["newton"])

"""``threepart compare`` of a load cycle from a file of every state (issue 38, "what to build" 2).

The file is a GetFEM sidecar written here from the closed form's own fretting cycle (Masing's
rule: ``shear`` and ``slip`` at each state) sampled at nodes: its friction work summed over
the states must give the closed form's energy per cycle (an identity of the sampled fields,
not the code's output), so compare passes; with the shear's sign flipped, the slip's flipped,
a stage missing or steps too coarse it fails and names which. The same file judged as the flight
cycle ``(P, s, -Q_max, 0) <-> (P, s, Q_max, 0)`` passes against the steady state of
:func:`threepart.steady_state`, an independent formula (docs/STEADY_STATE.md).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import threepart
from threepart import Punch
from threepart.cli import main
from threepart.getfem import friction_work, last_cycle, slip_amplitude
from threepart.getfem.read import FORMAT, State
from threepart.problem.material import similar_pair
from threepart.tolerances import tolerance

E, NU, F = 210000.0, 0.3, 0.5
PUNCH = Punch(R1=200.0, R2=100.0, b=1.0)
P, S = 28846.0 / 20.0, 0.2
Q_MAX = 0.4 * F * P
A = similar_pair(E, NU)
PROBLEM = ["--R1", "200", "--R2", "100", "--b", "1", "--E", str(E), "--nu", str(NU), "--f", str(F)]
#: nodes over the contact and W/8 past each end: the trapezoids over them miss 2e-3 of the energy,
#: and 16 states per half-cycle another 3.7e-3 (the pitfall's step error)
NODES = 1281
#: the share of the energy's limit that the sampled fields' trapezoids (nodes and states) may take
SAMPLING = 0.5
#: sums of a few floats: exact up to rounding (the table's closed-form entry)
EXACT = tolerance("closedform", "exact").limit


@pytest.fixture(scope="module")
def cycle():
    return threepart.fretting(PUNCH, P, S, A=A, Q_max=Q_MAX, f=F, method="closedform")


def _states(cf, steps: int = 8, nodes: int = NODES) -> list[State]:
    """The cycle's states, ``steps`` per Q_max and twice as many per reversal, as GetFEM records them."""
    n = cf.normal
    W = n.a + n.c
    x = np.linspace(-n.a - W / 8, n.c + W / 8, nodes)
    out = []
    for branch, Qs in (("loading", np.linspace(0.0, Q_MAX, steps + 1)[1:]),
                       ("unloading", np.linspace(Q_MAX, -Q_MAX, 2 * steps + 1)[1:]),
                       ("reloading", np.linspace(-Q_MAX, Q_MAX, 2 * steps + 1)[1:])):
        for Q in Qs:
            out.append(State(P=P, Q=float(Q), branch=branch, delta=0.0, resultant=(P, float(Q), P * S), x=x,
                             p=n.pressure(x), q=cf.shear(x, float(Q), branch), slip=cf.slip(x, float(Q), branch),
                             s=S, sigma_bulk=0.0))
    return out


def _sidecar(path: Path, states: list[State]) -> Path:
    path.write_text(json.dumps({
        "format": FORMAT, "model": "the closed form's cycle sampled", "params": {"f": F, "s": S}, "steps": [],
        "grid": [1, 1], "dofs": 1, "time": 0.0,
        "states": [{"P": st.P, "s": st.s, "Q": st.Q, "sigma_bulk": st.sigma_bulk, "branch": st.branch,
                    "delta": st.delta, "resultant": list(st.resultant), "x": st.x.tolist(), "p": st.p.tolist(),
                    "q": st.q.tolist(), "slip": st.slip.tolist()} for st in states]}))
    return path


def _compare(path: Path, out: Path, *extra: str) -> int:
    return main(["compare", "--pressure", str(path), *PROBLEM, "--out", str(out), *extra])


def test_the_sampled_cycles_friction_work_is_the_closed_forms_energy(cycle):
    """The identity the judging rests on: Σ ∫ (q_k + q_k+1)/2 Δslip dx over the last cycle is the
    Q-delta loop's area (Masing), to the nodes' and the steps' trapezoids; the slip amplitude's
    half-range is the closed form's amplitude at every node."""
    states = _states(cycle)
    start, end = last_cycle(states)
    assert (states[start].Q, states[start].branch, end) == (Q_MAX, "loading", len(states) - 1)
    work = friction_work(states[start:end + 1])
    assert abs(work / cycle.energy - 1) <= SAMPLING * tolerance("referee", "energy").limit
    x, amp = slip_amplitude(states[start:end + 1])
    assert np.max(np.abs(amp - cycle.slip_amplitude(x))) <= 100 * EXACT * np.max(amp)
    assert last_cycle(states[: len(states) // 2]) is None        # no reloading: no cycle closes


def test_compare_passes_the_closed_forms_own_fretting_cycle(cycle, tmp_path, capsys):
    path = _sidecar(tmp_path / "job.getfem.json", _states(cycle))
    assert _compare(path, tmp_path / "report", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 0
    out = capsys.readouterr().out
    assert out.startswith("PASSED") and "energy:" in out and "slip_amplitude:" in out
    doc = json.loads((tmp_path / "report" / "report.json").read_text())
    assert [c["quantity"] for c in doc["checks"]] == ["cycle", "energy", "slip_amplitude"]
    assert doc["obtained"]["states_per_half_cycle"] == 16
    assert doc["obtained"]["step_error"] <= tolerance("referee-pitfall", "cycle_step").limit
    assert (tmp_path / "report" / "report.html").exists()


def test_the_same_file_passes_as_the_flight_cycle_between_its_turning_states(cycle, tmp_path, capsys):
    path = _sidecar(tmp_path / "job.getfem.json", _states(cycle))
    state = lambda Q: f"{P!r},{S!r},{Q!r},0"                                    # noqa: E731
    assert _compare(path, tmp_path / "report", "--state0", state(-Q_MAX), "--state1", state(Q_MAX)) == 0
    doc = json.loads((tmp_path / "report" / "report.json").read_text())
    assert doc["reference"]["kind"] == "flight" and doc["passed"]


@pytest.mark.parametrize("spoil, name", [
    (lambda st: State(**{**st.__dict__, "q": -st.q}), "shear-sign"),
    (lambda st: State(**{**st.__dict__, "slip": -st.slip}), "slip-sign"),
])
def test_a_flipped_sign_fails_and_is_named(cycle, tmp_path, capsys, spoil, name):
    path = _sidecar(tmp_path / "job.getfem.json", [spoil(st) for st in _states(cycle)])
    assert _compare(path, tmp_path / "report", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 1
    out = capsys.readouterr().out
    assert out.startswith("FAILED") and f"pitfall {name}" in out


def test_a_stage_missing_fails_and_names_it(cycle, tmp_path, capsys):
    """Unloading stopped half-way (to -Q_max/2 and back): the cycle misses -Q_max; without the
    reloading branch no cycle closes at all."""
    states = _states(cycle, steps=4)
    half = [st for st in states if st.branch != "unloading" or st.Q >= 0]
    back = [State(**{**st.__dict__, "branch": "reloading"}) for st in half if st.branch == "unloading"][::-1][1:]
    short = [st for st in half if st.branch != "reloading"] + back + [half[3]]
    path = _sidecar(tmp_path / "short.getfem.json", short)
    assert _compare(path, tmp_path / "r1", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 1
    out = capsys.readouterr().out
    assert "failed: cycle" in out and "misses Q = -Q_max" in out
    path = _sidecar(tmp_path / "open.getfem.json", [st for st in states if st.branch != "reloading"])
    assert _compare(path, tmp_path / "r2", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 1
    assert "close no cycle" in capsys.readouterr().out


def test_steps_too_coarse_for_the_reversal_are_named_with_their_number(cycle, tmp_path, capsys):
    path = _sidecar(tmp_path / "job.getfem.json", _states(cycle, steps=2))
    assert _compare(path, tmp_path / "report", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 1
    out = capsys.readouterr().out
    assert "pitfall step: 4 states per half-cycle" in out


@pytest.mark.parametrize("extra, match", [
    (["--Q", "10", "--Q-max", "10"], "not `--Q` and `--Q-max`"),
    (["--state0", "1442,0.2,-10,0"], "needs both `--state0` and `--state1`"),
    (["--state0", "1442,0.2,-10,0", "--state1", "1442,0.2,10"], "4 numbers"),
    (["--Q-max", "-10"], "`--Q-max`"),
    (["--Q-max", "10", "--penalty", "1e6"], "`--penalty` judges one state's points"),
    (["--sigma-bulk", "20"], "`--sigma-bulk` rises with the shear"),
    (["--state0", "1442,0.2,-10,0", "--state1", "1442,0.2,10,0", "--P", "1442"], "leave out `--P`"),
])
def test_bad_cycle_options_are_one_line_and_exit_2(tmp_path, capsys, extra, match):
    args = ["compare", "--pressure", str(tmp_path / "none.getfem.json"), *PROBLEM, "--out", str(tmp_path / "r"),
            *extra]
    if "--state0" not in extra and "--P" not in extra:
        args += ["--P", "1442"]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and match in err[0], err
    assert not (tmp_path / "r").exists()


def test_a_file_without_states_is_refused_by_name(tmp_path, capsys):
    csv = tmp_path / "p.csv"
    csv.write_text("x,p,q\n-1,0,0\n0,1,0.1\n1,0,0\n")
    assert _compare(csv, tmp_path / "r", "--Q-max", repr(Q_MAX), "--P", repr(P), "--s", repr(S)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "records no states" in err[0]

"""``threepart deck`` of a bulk stress, a flight cycle and a load history (GetFEM and CalculiX).

Checked without running either code: the GetFEM script's ``PARAMS`` (read as a literal) and the
CalculiX deck's cards carry the loads asked, in the order of docs/BULK_STRESS.md (P first, then Q
and sigma_bulk together) and of a flight cycle (state0's P, then state0, state1, state0, state1).
"""
from __future__ import annotations

import pytest

from threepart.calculix import parse_deck
from threepart.problem.catalogue import get_case
from threepart.cli import main
from threepart.getfem.script import params_of

PUNCH = ["--R1", "200", "--R2", "100", "--b", "1", "--E", "210000", "--nu", "0.3"]
STATE0, STATE1 = (1298.07, 0.2, -216.345, -30.0), (1442.3, 0.2, 288.46, 40.0)
FLIGHT = ["--state0", ",".join(map(repr, STATE0)), "--state1", ",".join(map(repr, STATE1)), "--f", "0.5"]


def _legs(path) -> list[tuple[float, ...]]:
    return [(leg["P"], leg["s"], leg["Q"], leg["sigma_bulk"]) for leg in params_of(path.read_text())["legs"]]


def test_the_getfem_script_of_partial_slip_under_a_bulk_stress(tmp_path, capsys):
    out = tmp_path / "job.py"
    assert main(["deck", "--format", "getfem", *PUNCH, "--P", "1442.3", "--s", "0.2", "--Q", "288.46",
                 "--f", "0.5", "--sigma-bulk", "80", "--out", str(out)]) == 0
    assert _legs(out) == [(1442.3, 0.2, 288.46, 80.0)]
    assert "sigma_bulk together, in proportion" in out.read_text()
    assert "--Q 288.46 --sigma-bulk 80" in capsys.readouterr().out     # how to judge it


def test_a_flight_cycle_is_state0_state1_state0_state1_from_state0s_normal_load(tmp_path, capsys):
    out = tmp_path / "job.py"
    assert main(["deck", "--format", "getfem", *PUNCH, *FLIGHT, "--out", str(out)]) == 0
    params = params_of(out.read_text())
    assert (params["P"], params["s"]) == STATE0[:2]
    assert _legs(out) == [STATE0, STATE1, STATE0, STATE1]
    said = capsys.readouterr().out
    assert "flight cycle" in said and "compare --state0 1298.07,0.2,-216.345,-30 --state1" in said
    csv = tmp_path / "h.csv"
    csv.write_text("P,s,Q,sigma_bulk\n" + "\n".join(",".join(map(repr, st)) for st in (STATE0, STATE1, STATE0)))
    assert main(["deck", "--format", "getfem", *PUNCH, "--history", str(csv), "--f", "0.5",
                 "--out", str(tmp_path / "h.py")]) == 0
    assert _legs(tmp_path / "h.py") == [STATE0, STATE1, STATE0]


def test_the_calculix_deck_of_a_flight_cycle_has_a_step_per_state(tmp_path):
    out = tmp_path / "flight.inp"
    assert main(["deck", *PUNCH, *FLIGHT, "--out", str(out)]) == 0
    text = out.read_text()
    assert [c.name for c in parse_deck(text)].count("STEP") == 5     # the normal load, then four states
    assert "state 4 (step 5): P = 1442.3, s = 0.2, Q = 288.46, sigma_bulk = 40" in text


def test_a_flight_case_gives_its_own_states(tmp_path):
    case = get_case("fan_blade_flight_cycle").resolved()
    out = tmp_path / "fan.py"
    assert main(["deck", "--format", "getfem", "--case", case.name, "--out", str(out)]) == 0
    st0, st1 = (tuple(map(float, st)) for st in case.states)
    assert _legs(out) == [st0, st1, st0, st1] and params_of(out.read_text())["f"] == case.f


@pytest.mark.parametrize("extra, match", [
    (["--state0", "1298,0.2,-216,-30", "--f", "0.5"], "needs both `--state0` and `--state1`"),
    (["--P", "1442", "--Q", "100", "--f", "0.5", "--sigma-bulk", "nan"], "`--sigma-bulk`"),
    (["--P", "1442", "--sigma-bulk", "20", "--format", "getfem"], "`--sigma-bulk` rises with the shear"),
    ([*FLIGHT, "--P", "1442"], "leave out `--P`"),
    ([*FLIGHT, "--Q", "10"], "not `--Q` and `--state0/--state1`"),
    (["--state0", "1298,0.2,-216,-30", "--state1", "1442,0.2,900,40", "--f", "0.5"], "state 1"),
])
def test_a_bad_cycle_deck_is_one_line_and_exit_2(tmp_path, capsys, extra, match):
    assert main(["deck", "--format", "getfem", *PUNCH, *extra, "--out", str(tmp_path / "d.py")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and match in err[0], err
    assert not (tmp_path / "d.py").exists()

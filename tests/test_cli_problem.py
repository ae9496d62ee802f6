"""The command line a new user meets (issue 37 section 7): ``--case`` on every command that takes a
problem, ``threepart cases``, no options that do nothing, and an unknown option named first.

References, each independent of the code under test: the catalogue file itself (read here as
plain JSON), Hertz's contact of a cylinder (``a = sqrt(2 A R P/pi)``, centred under an eccentric
load), horizontal equilibrium (the integral of q is Q), and the same problem typed out as options.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from threepart.cli import COMMANDS, main
from threepart.tolerances import tolerance

ROUND_OFF = tolerance("closedform", "round_off").limit
#: the trapezoid rule on the shear of a partial slip at 8001 points: square-root ends and kinks at
#: the stick-zone ends, the error falls as h^1.5 (tests/test_cli.py measures the pressure's below this)
TRAPEZOID_LEVEL = 3e-5
#: the catalogue file, read as plain JSON (not through threepart.problem.catalogue)
CATALOGUE = json.loads((Path(__file__).resolve().parents[1] / "threepart" / "problem" / "cases.json").read_text("utf-8"))
RAW = {c["name"]: c for c in CATALOGUE["cases"]}
#: the commands that take a problem (issue 37: solve, slip and fatigue lacked --case)
PROBLEM_COMMANDS = ("solve", "slip", "fatigue", "cycle", "match", "deck", "compare", "wear")
#: a minimal problem of each command besides --case, for the refusal beside --case
REQUIRED = {"match": ["--edge", "left"], "deck": ["--out", "x.inp"], "compare": ["--pressure", "p.csv"]}


def _one_line_error(capsys, command: str) -> str:
    cap = capsys.readouterr()
    assert cap.err.count("\n") == 1 and cap.err.startswith(f"threepart {command}: error: "), cap.err
    assert "Traceback" not in cap.err
    return cap.err


def _json(capsys, argv: list[str]) -> dict:
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


# --- --case on every command that takes a problem ---------------------------------------------------
def test_solve_case_gives_hertz_contact_of_the_catalogues_cylinder(capsys):
    """nd_hertz: a cylinder R = 2 under an eccentric load; its contact is Hertz's, 2 sqrt(2 A R P/pi)
    wide and centred under the load (the tilt free), from the file's numbers alone."""
    c = RAW["nd_hertz"]
    R, A, P, s = c["punch"]["R1"], c["A"], c["P"], c["s"]
    assert c["punch"]["R2"] == R and c["punch"]["b"] == 0.0
    out = _json(capsys, ["solve", "--case", "nd_hertz", "--json"])
    half = math.sqrt(2 * A * R * P / math.pi)
    assert out["case"] == "nd_hertz" and out["P"] == P and out["s"] == s
    assert -out["a"] == pytest.approx(s - half, rel=ROUND_OFF)
    assert out["c"] == pytest.approx(s + half, rel=ROUND_OFF)


def test_slip_case_carries_the_catalogues_shear_and_integrates_to_it(capsys):
    """slip_Q0.4: Q = 0.4 f P of the file; the shear at 8001 points integrates to Q (equilibrium),
    and the case gives what the same problem typed out gives."""
    from threepart.problem.catalogue import get_case

    c = RAW["slip_Q0.4"]
    Q = c["Q_over_fP"] * c["f"] * c["P"]
    out = _json(capsys, ["slip", "--case", "slip_Q0.4", "--grid", "8001", "--json"])
    assert out["Q"] == pytest.approx(Q, rel=ROUND_OFF) and out["f"] == c["f"]
    x, q = out["points"]["x"], out["points"]["q"]
    integral = sum(0.5 * (q[i] + q[i + 1]) * (x[i + 1] - x[i]) for i in range(len(x) - 1))
    assert abs(integral - Q) <= TRAPEZOID_LEVEL * Q, (integral, Q)
    p = c["punch"]
    typed = _json(capsys, ["slip", "--R1", str(p["R1"]), "--R2", str(p["R2"]), "--b", str(p["b"]),
                           "--A", repr(get_case("slip_Q0.4").A), "--P", str(c["P"]), "--s", str(c["s"]),
                           "--Q", repr(Q), "--f", str(c["f"]), "--json"])
    for key in ("a", "c", "alpha", "d", "e"):
        assert out[key] == pytest.approx(typed[key], rel=ROUND_OFF, abs=ROUND_OFF), key


def test_fatigue_case_is_the_flight_cycle_of_the_catalogue(capsys):
    """fan_blade_flight_cycle: the ends and f of the file, and the hot spots of the same cycle typed out."""
    c = RAW["fan_blade_flight_cycle"]
    grid = ["--nx", "9", "--nz", "5", "--ns", "21", "--json"]
    out = _json(capsys, ["fatigue", "--case", "fan_blade_flight_cycle", *grid])
    assert out["case"] == "fan_blade_flight_cycle" and out["f"] == c["f"]
    p, m = c["punch"], c["material"]
    typed = _json(capsys, ["fatigue", "--R1", str(p["R1"]), "--R2", str(p["R2"]), "--b", str(p["b"]),
                           "--E", str(m["E"]), "--nu", str(m["nu"]), "--f", str(c["f"]),
                           "--state0", ",".join(map(str, c["states"][0])),
                           "--state1", ",".join(map(str, c["states"][1])), *grid])
    assert out["A"] == pytest.approx(typed["A"], rel=ROUND_OFF)
    assert out["hot_spots"].keys() == typed["hot_spots"].keys()
    for name, hot in out["hot_spots"].items():
        assert hot == pytest.approx(typed["hot_spots"][name], rel=ROUND_OFF, abs=ROUND_OFF), name


@pytest.mark.parametrize("command", PROBLEM_COMMANDS)
def test_every_command_that_takes_a_problem_takes_case_and_names_a_wrong_one(capsys, command):
    assert main([command, "--help"]) == 0
    assert "--case NAME" in capsys.readouterr().out
    assert main([command, "--case", "nowhere", *REQUIRED.get(command, [])]) == 2
    assert "`--case` = 'nowhere' is not in the catalogue" in _one_line_error(capsys, command)


@pytest.mark.parametrize("argv, given", [
    (["solve", "--case", "hertz", "--P", "3"], "--P"),
    (["solve", "--case", "hertz", "--tilt", "suppressed"], "--tilt"),
    (["solve", "--case", "hertz", "--rigid"], "--rigid"),
    (["solve", "--case", "hertz", "--A", "1e-5"], "--A"),
    (["slip", "--case", "slip_Q0.4", "--f", "0.3"], "--f"),
    (["slip", "--case", "slip_Q0.4", "--sigma-bulk", "10"], "--sigma-bulk"),
    (["fatigue", "--case", "fretting_Q0.4", "--Q-max", "10"], "--Q-max"),
    (["fatigue", "--case", "fretting_Q0.4", "--nu", "0.3"], "--nu"),
    (["fatigue", "--case", "fretting_Q0.4", "--state0", "400,0,0,0"], "--state0"),
])
def test_the_problem_beside_case_is_refused_by_name(capsys, argv, given):
    """The rule --help states: the punch, material and loads beside --case are refused, never mixed."""
    assert main([argv[0], "--help"]) == 0
    assert "beside it are refused" in " ".join(capsys.readouterr().out.split())
    assert main(argv) == 2
    assert f"give `--case` or the punch, material and loads, not both (also got `{given}`)" in \
        _one_line_error(capsys, argv[0])


@pytest.mark.parametrize("argv, match", [
    (["slip", "--case", "hertz"], r"case 'hertz' has no shear load `Q` and `f` \(cases with one: .*slip_Q0\.4"),
    (["fatigue", "--case", "nd_A"], r"case 'nd_A' has no material \(E, nu\), f and shear load"),
    (["solve", "--R1", "10", "--R2", "5", "--b", "1", "--A", "1e-5"], r"`--P` is missing"),
    (["slip", "--R1", "10", "--R2", "5", "--b", "1", "--A", "1e-5", "--P", "400"], r"`--Q` is missing"),
    (["fatigue", "--R1", "10", "--R2", "5", "--b", "1", "--nu", "0.3", "--f", "0.5"], r"`--E` is missing"),
])
def test_a_case_that_does_not_fit_or_a_problem_half_given_is_one_line(capsys, argv, match):
    assert main(argv) == 2
    assert re.search(match, _one_line_error(capsys, argv[0]))


# --- threepart cases ------------------------------------------------------------------------------
def test_cases_lists_every_case_of_the_file_with_its_description(capsys):
    assert main(["cases"]) == 0
    lines = capsys.readouterr().out.splitlines()
    for name, c in RAW.items():
        row = [line for line in lines if line.split()[:1] == [name]]
        assert len(row) == 1 and row[0].endswith(c.get("description", "")), name
    assert lines[-1] == (f"{len(RAW)} cases; give one as --case NAME to: " + ", ".join(PROBLEM_COMMANDS))


def test_cases_of_a_kind_and_as_json(capsys):
    steady = {n for n, c in RAW.items() if "states" in c}
    assert main(["cases", "--kind", "steady"]) == 0
    listed = capsys.readouterr().out.splitlines()[1:-2]
    assert {line.split()[0] for line in listed} == steady
    out = _json(capsys, ["cases", "--json"])
    assert [c["name"] for c in out["cases"]] == list(RAW)
    assert all(c["P"] == RAW[c["name"]]["P"] for c in out["cases"])


# --- no options that do nothing; an unknown option named first -------------------------------------
@pytest.mark.parametrize("command", ["solve", "slip"])
def test_solve_and_slip_have_no_cycle_ends(capsys, command):
    """--state0/--state1 changed nothing in solve and slip: they are gone (fatigue and cycle use them)."""
    assert main([command, "--help"]) == 0
    assert "--state" not in capsys.readouterr().out
    extra = ["--Q", "80", "--f", "0.5"] if command == "slip" else []
    argv = [command, "--R1", "10", "--R2", "5", "--b", "1", "--A", "1e-5", "--P", "400", *extra,
            "--state0", "400,0.1,0,0"]
    assert main(argv) == 2
    assert "unrecognized arguments: --state0 400,0.1,0,0" in _one_line_error(capsys, command)
    for other in ("fatigue", "cycle"):
        assert main([other, "--help"]) == 0
        assert "--state0" in capsys.readouterr().out


@pytest.mark.parametrize("command", COMMANDS)
def test_an_unknown_option_is_named_before_a_missing_one(capsys, command):
    """`--load 400` for `--P 400`: the unknown option is named, not "--P is required" (or any other
    missing option of the command)."""
    assert main([command, "--load", "400"]) == 2
    err = _one_line_error(capsys, command)
    assert "unrecognized arguments: --load 400" in err and "required" not in err, err

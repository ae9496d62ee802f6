"""The ``threepart cycle`` command: the flight cycle's steady state, a load history, --out, errors."""
from __future__ import annotations

import contextlib
import csv
import re
from pathlib import Path
from typing import Any, Iterator

import numpy as np
import pytest

from threepart.problem import catalogue
from threepart import closedform as cf
from threepart.cli import main
from threepart.tolerances import tolerance

CASE = "fan_blade_flight_cycle"
#: the command prints the stick zone and the energy with 10 significant digits: each within
#: half a unit in the 10th digit, 5e-10 of its own magnitude
PRINTED = 5e-10
#: the marched history's last cycle against the closed form's steady state (eq. S11): the
#: table's entry for the march (measured here 9.3e-4 with --n 1024, 10 steps a half-cycle)
MARCH = tolerance("steady", "march_energy").limit
#: the trapezoid rule on the CSV's 2001 points of q, whose ends rise as square roots and which
#: kinks at the stick-slip boundaries: the error falls as h^1.5, measured <= 2.9e-5 of f P
TRAPEZOID_LIMIT = 2e-4
#: a punch on the command line: case A with a moment, similar steel bodies, a cycle that slips
PUNCH_ARGS = ["--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--f", "0.5"]
STATES = ((400.0, 0.1, -60.0, -10.0), (420.0, 0.12, 60.0, 10.0))
#: a symmetric punch (equal radii, no moment) and steel
SYMMETRIC = ["--R1", "10", "--R2", "10", "--b", "1", "--A", "1e-5", "--f", "0.5"]
#: f ΔP of the shakedown test's cycle below: f = 0.5, P from 400 to 500 N/mm
F_DP = 0.5 * (500.0 - 400.0)
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _state(st: tuple[float, ...]) -> str:
    return ",".join(f"{v:g}" for v in st)


def _run(capsys: Any, argv: list[str]) -> str:
    assert main(["cycle", *argv]) == 0
    return str(capsys.readouterr().out)


def _number(text: str, pattern: str) -> list[float]:
    m = re.search(pattern, text)
    assert m is not None, f"{pattern!r} not in the output:\n{text}"
    return [float(g) for g in m.groups()]


NUM = r"(-?[0-9.]+(?:e[-+]?\d+)?)"


def _printed(text: str) -> tuple[float, float, float]:
    left, right = _number(text, rf"stick zone \[{NUM}, {NUM}\] mm")
    (energy,) = _number(text, rf"energy\s+{NUM} N\*mm/mm per cycle")
    return left, right, energy


def _agrees(printed: float, ref: float) -> bool:
    return abs(printed - ref) <= PRINTED * abs(ref)


def test_the_flight_case_prints_the_closed_forms_stick_zone_and_energy(capsys):
    text = _run(capsys, ["--case", CASE])
    case = catalogue.get_case(CASE)
    ref = cf.steady_state(case.punch, case.states, case.f, A=case.A)
    left, right, energy = _printed(text)
    assert text.startswith("method: closedform\n")
    assert _agrees(left, ref.stick_zone[0]) and _agrees(right, ref.stick_zone[1])
    assert _agrees(energy, ref.energy) and "shakedown  no" in text
    for label in ("von Mises range", "SWT", "Findley", "Ruiz FFDP", "Ruiz FDP", "slip amplitude"):
        assert label in text


def test_a_punch_on_the_command_line_prints_the_closed_forms_stick_zone_and_energy(capsys):
    text = _run(capsys, [*PUNCH_ARGS, "--state0", _state(STATES[0]), "--state1", _state(STATES[1])])
    from threepart.problem.punch import Punch

    A = 4 * (1 - 0.3 ** 2) / 210000.0    # similar bodies, eq. (4)
    ref = cf.steady_state(Punch(R1=10.0, R2=5.0, b=1.0), STATES, 0.5, A=A)
    left, right, energy = _printed(text)
    assert _agrees(left, ref.stick_zone[0]) and _agrees(right, ref.stick_zone[1])
    assert _agrees(energy, ref.energy) and energy > 0


@pytest.mark.parametrize("dQ,shakes_down", [(30.0, True), (70.0, False)])
def test_shakedown_is_reported_when_the_shear_swings_less_than_f_times_the_normal_load(capsys, dQ, shakes_down):
    """Eq. S12 on a symmetric punch: nothing slips in the steady state iff |ΔQ| < f ΔP (here f ΔP = 50)."""
    text = _run(capsys, [*SYMMETRIC, "--state0", "400,0,0,0", "--state1", f"500,0,{dQ:g},0"])
    assert abs(dQ) < F_DP if shakes_down else abs(dQ) > F_DP
    assert ("shakedown  yes" in text) is shakes_down
    (_, _, energy) = _printed(text)
    assert (energy == 0.0) is shakes_down


def _history_rows(states: Any, steps: int, cycles: int) -> list[tuple[float, ...]]:
    """Up to state 1, then ``cycles`` times to state 0 and back, ``steps`` linear steps a half-cycle."""
    s0, s1 = (np.asarray(s, float) for s in states)
    lam = np.linspace(0.0, 1.0, steps + 1)
    up = [tuple(s0 + t * (s1 - s0)) for t in lam]
    down = [tuple(s1 + t * (s0 - s1)) for t in lam[1:]]
    return up + (down + up[1:]) * cycles


def _write_history(path: Path, rows: list[tuple[float, ...]]) -> None:
    path.write_text("P,s,Q,sigma_bulk\n" + "".join(",".join(f"{v:.15g}" for v in r) + "\n" for r in rows),
                    encoding="utf-8")


def test_a_history_is_marched_and_its_last_cycle_has_the_steady_states_energy(capsys, tmp_path):
    case = catalogue.get_case(CASE)
    path = tmp_path / "flight.csv"
    _write_history(path, _history_rows(case.states, steps=10, cycles=2))
    text = _run(capsys, ["--case", CASE, "--history", str(path), "--n", "1024"])
    energies = [float(v) for v in re.findall(rf"cycle \d+\s+states \d+ to \d+: energy {NUM} N\*mm/mm", text)]
    ref = cf.steady_state(case.punch, case.states, case.f, A=case.A).energy
    assert len(energies) == 2 and abs(energies[-1] - ref) <= MARCH * ref
    assert "last two cycles  agree" in text and "stick at the last state  [" in text


def _csv(path: Path) -> dict[str, np.ndarray]:
    with path.open(encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


def test_out_holds_the_csv_and_the_plot_and_a_rerun_replaces_only_its_own(capsys, tmp_path):
    out, beside = tmp_path / "flight", tmp_path / "notes.txt"
    beside.write_text("mine", encoding="utf-8")
    _run(capsys, ["--case", CASE, "--out", str(out)])
    assert sorted(p.name for p in out.iterdir()) == [".threepart-output.json", "cycle.csv", "cycle.png"]
    assert (out / "cycle.png").read_bytes().startswith(PNG_SIGNATURE)
    cols = _csv(out / "cycle.csv")
    case = catalogue.get_case(CASE)
    for k in (0, 1):   # horizontal equilibrium: the shear at each end integrates to its Q
        P, _, Q, _ = case.states[k]
        q = cols[f"q at state {k} [MPa]"]
        assert abs(np.trapezoid(q, cols["x [mm]"]) - Q) <= TRAPEZOID_LIMIT * case.f * P
    assert np.all(cols["slip amplitude [mm]"] >= 0)
    # a rerun (now a history) replaces the whole directory, and leaves the file beside it alone
    path = tmp_path / "h.csv"
    rows = _history_rows(case.states, steps=2, cycles=1)
    _write_history(path, rows)
    _run(capsys, ["--case", CASE, "--history", str(path), "--out", str(out)])
    assert sorted(p.name for p in out.iterdir()) == [".threepart-output.json", "cycle.csv", "cycle.png",
                                                      "states.csv"]
    states = _csv_rows(out / "states.csv")
    assert len(states) == 1 + len(rows) and states[0][:5] == ["k", "P [N/mm]", "s [mm]", "Q [N/mm]", "sigma_bulk [MPa]"]
    assert beside.read_text(encoding="utf-8") == "mine"


def _csv_rows(path: Path) -> list[list[str]]:
    with path.open(encoding="utf-8") as fh:
        return list(csv.reader(fh))


def test_a_foreign_directory_is_refused_and_left_alone(capsys, tmp_path):
    out = tmp_path / "theirs"
    out.mkdir()
    (out / "data.txt").write_text("theirs", encoding="utf-8")
    assert main(["cycle", "--case", CASE, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert re.search(r"holds 'data.txt' .*threepart did not write it", err) and err.count("\n") == 1
    assert sorted(p.name for p in out.iterdir()) == ["data.txt"]


def _bad_history(tmp_path: Path, text: str | None) -> str:
    path = tmp_path / "h.csv"
    if text is not None:
        path.write_text(text, encoding="utf-8")
    return str(path)


BAD = [
    (["--history", "P,s,Q,sigma_bulk\n400,0,nan,0\n"], r"history file .*row 2, column `Q`: 'nan' must be a finite number"),
    (["--history", "P,s,Q,sigma_bulk\n-400,0,10,0\n"], r"row 2, column `P`: '-400' must be > 0"),
    (["--history", None], r"history file .*h.csv' cannot be read"),
    (["--history", "P,s,sigma_bulk\n400,0,0\n"], r"history file .* has no column `Q`"),
    (["--history", "P,s,Q,sigma_bulk\n400,0,100,0\n400,0,250,0\n"], r"`history` state 1: \|`Q`\| = 250 >= f P = 200"),
    (["--state0", "400,0,0", "--state1", "500,0,30,0"], r"argument --state0: '400,0,0' must be 4 numbers P,s,Q,sigma_bulk"),
    (["--state0", "400,0,x,0", "--state1", "500,0,30,0"], r"argument --state0: .*invalid float value: 'x'"),
    (["--state0", "400,0,300,0", "--state1", "500,0,30,0"], r"`--state0`: \|Q\| = 300 >= f P = 200"),
    (["--state0", "400,0,0,0", "--state1", "500,0,-250,0"], r"`--state1`: \|Q\| = 250 >= f P = 250"),
    (["--state0", "400,0,0,0"], r"`--state1` is missing"),
]


@pytest.mark.parametrize("extra,match", BAD)
def test_bad_input_is_one_line_and_exit_status_2(capsys, tmp_path, extra, match):
    if extra[0] == "--history":
        extra = ["--history", _bad_history(tmp_path, extra[1])]
    assert main(["cycle", *SYMMETRIC, *extra]) == 2
    err = capsys.readouterr().err
    assert re.search(match, err) and err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.parametrize("argv,match", [
    (["--case", "no_such_case"], r"`--case` = 'no_such_case' is not in the catalogue"),
    (["--case", "caseA_moment"], r"case 'caseA_moment' has no cycle `states` \(cases with states: .*fan_blade_flight_cycle"),
    (["--case", CASE, "--f", "0.5"], r"give `--case` or the punch, material and loads, not both"),
])
def test_a_bad_case_is_one_line_and_exit_status_2(capsys, argv, match):
    assert main(["cycle", *argv]) == 2
    err = capsys.readouterr().err
    assert re.search(match, err) and err.count("\n") == 1


#: a cycle whose permanent stick zone ends on the flat centre (P* = 2846 at case A's P = 28846)
ON_CENTRE = ["--R1", "10", "--R2", "5", "--b", "1", "--A", "1e-5", "--f", "0.5",
             "--state0", "28846,0.2,-13000,0", "--state1", "28846,0.2,13000,0"]


def test_the_closed_forms_refusal_is_one_line_and_auto_falls_back_to_the_sie_saying_why(capsys):
    assert main(["cycle", *ON_CENTRE, "--method", "closedform"]) == 2
    err = capsys.readouterr().err
    assert re.search(r"permanent stick zone .* would end inside the central segment", err)
    assert err.count("\n") == 1
    text = _run(capsys, ON_CENTRE)
    assert re.match(r"method: sie \(the closed form does not hold here: the permanent stick zone", text)
    # an end of the SIE's stick zone lies inside the central segment (-b, b) = (-1, 1), as the refusal says
    left, right, _ = _printed(text)
    assert left < right and (-1 < left < 1 or -1 < right < 1)


def test_the_numerical_methods_say_they_are_still_running(capsys, tmp_path, monkeypatch):
    """The SIE's march runs inside the heartbeat (threepart.progress), its stage named."""
    from threepart.cli import cycle as cli_cycle

    stages: list[str] = []

    @contextlib.contextmanager
    def record(say: Any, stage: Any, every: float | None = None) -> Iterator[None]:
        stages.append(stage())
        yield

    monkeypatch.setattr(cli_cycle, "heartbeat", record)
    path = tmp_path / "h.csv"
    _write_history(path, _history_rows(catalogue.get_case(CASE).states, steps=2, cycles=1))
    _run(capsys, ["--case", CASE, "--history", str(path)])
    assert stages == ["the load history (7 states, auto)"]
    _run(capsys, ["--case", CASE, "--method", "sie"])
    assert stages[1:] == ["the steady state (sie)", "the fatigue hot spots"]


def test_help_lists_the_options(capsys):
    assert main(["cycle", "--help"]) == 0
    text = capsys.readouterr().out
    for option in ("--case", "--R1", "--R2", "--b", "--R", "--E", "--nu", "--A", "--f", "--state0",
                   "--state1", "--history", "--method", "--mesh", "--n", "--out"):
        assert re.search(rf"{option}\b", text), option
    assert "closedform" in text and "fem" in text


@pytest.mark.slow
def test_the_fem_answers_the_flight_case_near_the_closed_form(capsys):
    text = _run(capsys, ["--case", CASE, "--method", "fem", "--mesh", "quick"])
    case = catalogue.get_case(CASE)
    ref = cf.steady_state(case.punch, case.states, case.f, A=case.A)
    left, right, _ = _printed(text)
    W = min(n.c for n in ref.normals) - max(-n.a for n in ref.normals)
    limit = tolerance("fem-quick", "stick_ends").limit
    assert abs(left - ref.stick_zone[0]) <= limit * W and abs(right - ref.stick_zone[1]) <= limit * W
    assert text.startswith("method: fem")


#: the issue-37 cycle the superposition refuses (one end shakes down): case A, its compliance as given
ONE_SIDED = ["--R1", "10", "--R2", "5", "--b", "1", "--A", "1.7333e-5", "--f", "0.5",
             "--state0", "1000,0.05,20,20", "--state1", "1400,0.15,320,60"]


def test_auto_marches_a_cycle_the_superposition_refuses_and_says_so(capsys):
    """The stick zone printed reaches the right edge of the contacts' common part (the normals alone)."""
    from threepart import sie
    from threepart.problem.punch import Punch

    text = _run(capsys, ONE_SIDED)
    assert re.match(r"method: sie-march \(the superposition does not model this cycle: .* would reach the right "
                    r"edge .*; marched by the SIE's load history, \d+ cycles", text)
    ends = [sie.solve_normal(Punch(10.0, 5.0, 1.0), P, s, A=1.7333e-5) for P, s in ((1000, 0.05), (1400, 0.15))]
    lo, hi = max(-n.a for n in ends), min(n.c for n in ends)
    left, right = _number(text, rf"stick zone \[{NUM}, {NUM}\] mm \(stuck all through the last marched cycle\)")
    assert lo < left < right and abs(right - hi) <= PRINTED * abs(hi)
    (energy,) = _number(text, rf"energy\s+{NUM} N\*mm/mm per cycle")
    assert energy > 0 and "shakedown  no" in text


def test_the_slip_amplitude_printed_is_the_largest(capsys):
    """fan_blade_flight_cycle: at least the largest of a dense sample of the closed form's, where it lies."""
    text = _run(capsys, ["--case", CASE])
    value, where = _number(text, rf"slip amplitude  largest {NUM} mm at x = {NUM} mm")
    case = catalogue.get_case(CASE)
    ref = cf.steady_state(case.punch, case.states, case.f, A=case.A)
    lo, hi = min(-n.a for n in ref.normals), max(n.c for n in ref.normals)
    x = np.linspace(lo, hi, 200_001)
    dense = ref.slip_amplitude(x)
    assert value >= dense.max() * (1 - PRINTED) and abs(where - x[np.argmax(dense)]) <= 2 * (x[1] - x[0])

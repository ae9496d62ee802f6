"""``threepart wear``: refusals by name, a short march against the closed-form worn limit, its files.

References: the closed-form worn limit's stick zone (closedform.wear_limit, eq. W3: a
symmetric contact's stick zone does not move), the march's own records read back
from the CSV it wrote, and the catalogue's fretting case from which the wear case
takes its punch and loads.
"""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from threepart import Punch
from threepart.problem.catalogue import get_case
from threepart.cli import main
from threepart.closedform import solve_normal, wear_limit
from threepart.fretting_wear import wear_case, wear_cases
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3
HERTZ = ["--R1", "10", "--R2", "10", "--b", "0", "--A", repr(A), "--P", "400", "--Q-max", "100", "--f", "0.5"]
#: a short march: the energy law at k = 1e-5, 12 cycles (a dose k N of 1.2e-4, the early rise)
SHORT = [*HERTZ, "--law", "energy", "--k", "1e-5", "--cycles", "12"]
#: Archard coefficients of titanium alloys in fretting span about 1e-9 to 1e-7 mm^3/(N mm) (the case's source)
TITANIUM_K = (1e-9, 1e-7)


@pytest.mark.parametrize("argv, match", [
    (["--case", "nonesuch"], "`--case` = 'nonesuch'"),
    (["--case", "fan_blade_flank_wear", "--P", "10"], "`--P`"),
    ([*HERTZ[:-4], "--Q-max", "300", "--f", "0.5", "--k", "1e-5", "--cycles", "1"], "`--Q-max` = 300"),
    ([*HERTZ, "--k", "1e-5"], "`--cycles` is missing"),
    ([*HERTZ, "--k", "0", "--cycles", "1"], "`--k` = 0"),
    ([*HERTZ, "--k", "1e-5", "--cycles", "0"], "`--cycles` = 0 must lie in"),
    ([*HERTZ, "--k", "1e-5", "--cycles", "5", "--jump", "0"], "`--jump` = 0 must lie in"),
    ([*HERTZ, "--k", "1e-5", "--cycles", "1.5"], "invalid int value"),
    ([*HERTZ, "--k", "1e-5", "--cycles", "1", "--law", "gravity"], "--law"),
    ([*HERTZ[:-2], "--k", "1e-5", "--cycles", "1"], "`--f` is missing"),
])
def test_bad_options_exit_2_with_one_line(capsys, argv, match):
    assert main(["wear", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert match in err and len(err.splitlines()) == 1 and "Traceback" not in err


def test_the_fem_march_needs_a_material(capsys):
    """``--method fem`` marches two similar bodies: ``--A`` alone is refused in one line, E and nu march."""
    assert main(["wear", *SHORT, "--method", "fem"]) == 2
    err = capsys.readouterr().err.strip()
    assert "`--method` = fem" in err and "`--E`" in err and len(err.splitlines()) == 1
    material = ["--E", "210000", "--nu", "0.3"]
    given = [*HERTZ[:6], *material, *HERTZ[8:], "--law", "energy", "--k", "1e-5", "--cycles", "4", "--method", "fem"]
    assert main(["wear", *given, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    limit = wear_limit(solve_normal(Punch(R1=10, R2=10, b=0), 400.0, 0.0, A=4 * (1 - 0.09) / 210e3), 100.0, 0.5)
    W = 2 * solve_normal(Punch(R1=10, R2=10, b=0), 400.0, 0.0, A=4 * (1 - 0.09) / 210e3).a
    assert doc["method"] == "fem" and doc["cycles_reached"] == 4
    assert np.allclose(doc["stick_end"], limit.stick_zone, rtol=0, atol=tolerance("wear", "fem_stick_zone").limit * W)


def test_the_wear_case_is_the_fan_blade_flank_fretted():
    """The catalogue's wear case: the fan-blade flank's punch, material, P, s, f and Q_max, 10^6 cycles."""
    wc = wear_case("fan_blade_flank_wear")
    flank = get_case("fan_blade_flank_bulk")
    c = wc.case
    assert (c.punch, c.material, c.P, c.s, c.f, c.Q) == (flank.punch, flank.material, flank.P, flank.s,
                                                           flank.f, flank.Q)
    assert c.kind == "wear" and c.cycle and c.A == flank.A
    assert wc.law == "archard" and wc.cycles == 10**6 and TITANIUM_K[0] <= wc.k <= TITANIUM_K[1] and wc.source
    assert [w.name for w in wear_cases()] == ["fan_blade_flank_wear"]


@pytest.mark.parametrize("change, match", [
    (lambda w: w["wear"].pop("k"), "has no field 'k'"),
    (lambda w: w["wear"].update(law="gravity"), "`law` = 'gravity'"),
    (lambda w: w.pop("Q_over_fP"), "has no field 'Q_over_fP'"),
    (lambda w: w.update(P=-1.0), "`P` = -1"),
])
def test_a_bad_wear_case_is_named_with_its_file(tmp_path, change, match):
    from threepart.problem.catalogue import CASES_FILE
    from threepart.errors import InputError

    data = json.loads(CASES_FILE.read_text(encoding="utf-8"))
    change(next(c for c in data["cases"] if c["name"] == "fan_blade_flank_wear"))
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(InputError, match=match) as info:
        wear_cases(str(path))
    assert "fan_blade_flank_wear" in str(info.value) and "cases.json" in str(info.value)


@pytest.fixture(scope="module")
def short_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("wear") / "out"
    from contextlib import redirect_stdout
    import io

    buf = io.StringIO()
    with redirect_stdout(buf):
        assert main(["wear", *SHORT, "--json", "--out", str(out)]) == 0
    return json.loads(buf.getvalue()), out


def test_a_short_run_keeps_the_worn_limits_stick_zone(short_run):
    """Hertz: the march's stick zone at Q_max is the closed-form worn limit's (eq. W11), and stays."""
    doc, _ = short_run
    limit = wear_limit(solve_normal(Punch(R1=10, R2=10, b=0), 400.0, 0.0, A=A), 100.0, 0.5)
    W = 2 * solve_normal(Punch(R1=10, R2=10, b=0), 400.0, 0.0, A=A).a
    tol = tolerance("wear", "stick_zone").limit * W
    assert np.allclose(doc["stick_end"], limit.stick_zone, rtol=0, atol=tol)
    assert np.allclose(doc["stick_start"], limit.stick_zone, rtol=0, atol=tol)
    assert np.allclose(doc["limit_stick_zone"], limit.stick_zone, rtol=0, atol=tol)
    assert doc["cycles_reached"] == doc["cycles_requested"] == 12 and doc["stopped"] is None
    assert doc["volume"] > 0 and doc["units"]["energy"].startswith("N*mm/mm")
    # the distance to the limit falls as the slip zones wear (docs/WEAR.md section 1)
    assert np.all(np.diff(doc["records"]["distance"]) < 0)


def test_a_short_run_writes_its_files(short_run):
    doc, out = short_run
    with open(out / "wear.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [int(r["cycle"]) for r in rows] == doc["records"]["cycles"]
    assert [float(r["energy [N*mm/mm]"]) for r in rows] == doc["records"]["energy"]
    with open(out / "depths.csv", newline="", encoding="utf-8") as fh:
        depths = list(csv.reader(fh))
    assert len(depths[0]) == 1 + len(rows)
    x = np.array([float(r[0]) for r in depths[1:]])
    last = np.array([float(r[-1]) for r in depths[1:]])
    # the volume is the depth's integral (trapezoidal on the knots), and nothing is worn in the stick zone
    assert np.trapezoid(last, x) == pytest.approx(doc["volume"], rel=tolerance("wear-limit", "round_off").limit)
    x1, x2 = doc["stick_end"]
    assert np.all(last[(x > x1) & (x < x2)] == 0) and np.all(last >= 0)
    assert (out / "wear.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_the_fan_blade_flank_reaches_its_worn_limit(capsys):
    """The wear case's 10^6 cycles: the energy per cycle falls below 5 % of its start, the pressure within 1 %
    of the closed-form limit on the stick zone it reached, which lies in the limit's bracket (docs/WEAR.md §3)."""
    assert main(["wear", "--case", "fan_blade_flank_wear", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    energy, distance = doc["records"]["energy"], doc["records"]["distance"]
    assert doc["cycles_reached"] == 10**6 and doc["stopped"] is None
    assert energy[-1] <= tolerance("wear", "energy_left").limit * energy[0]
    assert distance[-1] <= tolerance("wear", "limit_L2").limit
    assert doc["stick_to_limit_over_W"] <= tolerance("wear", "stick_zone").limit


def test_the_parser_names_the_librarys_laws_and_marchers():
    """``--law`` and ``--method`` choices (named in the parser, which loads no numpy) are the library's."""
    from threepart.cli import wear as cli_wear
    from threepart.fretting_wear import LAWS, marchers

    assert cli_wear.LAWS == LAWS and sorted(cli_wear.METHODS) == sorted(marchers())

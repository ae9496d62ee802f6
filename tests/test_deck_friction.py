"""``threepart deck`` with friction: the GetFEM script and the CalculiX deck of two similar bodies.

Checked without running either code: the script's parameters (read as a literal) and the deck's
cards (parsed) carry the problem's loads, the friction law and the modulus that gives the problem's
compliance A as two similar bodies, E = 4(1 - nu^2)/A (eq. 4), computed here independently.
"""
from __future__ import annotations

import pytest

from threepart.calculix import parse_deck
from threepart.cli import main
from threepart.getfem.script import params_of

HERTZ = ["--R1", "200", "--R2", "200", "--b", "0", "--P", "20", "--E", "210000", "--nu", "0.3"]
#: rounding of a modulus written with 6 or more digits
DIGITS = 1e-9


def test_the_getfem_script_of_a_partial_slip(tmp_path, capsys):
    out = tmp_path / "job.py"
    assert main(["deck", "--format", "getfem", *HERTZ, "--Q", "4", "--f", "0.5", "--out", str(out)]) == 0
    params = params_of(out.read_text())
    A = 4 * (1 - 0.3**2) / 210000.0
    assert params["E"] == pytest.approx(4 * (1 - 0.3**2) / A, rel=DIGITS)
    assert (params["P"], params["f"], params["nu"]) == (20.0, 0.5, 0.3)
    assert [leg["Q"] for leg in params["legs"]] == [4.0]
    assert "wrote" in capsys.readouterr().out


def test_the_calculix_deck_of_a_fretting_cycle(tmp_path):
    out = tmp_path / "cycle.inp"
    assert main(["deck", *HERTZ, "--Q-max", "4", "--f", "0.5", "--out", str(out)]) == 0
    cards = parse_deck(out.read_text())
    names = [c.name for c in cards]
    friction = [c for c in cards if c.name == "FRICTION"]
    assert friction and float(friction[0].data[0][0]) == 0.5
    assert names.count("STEP") == 4          # the normal load, then Q, -Q, Q
    materials = [float(c.data[0][0]) for c in cards if c.name == "ELASTIC"]
    assert materials and all(E == pytest.approx(210000.0, rel=DIGITS) for E in materials)


@pytest.mark.parametrize("extra, match", [
    (["--format", "getfem"], "`--format getfem` writes friction only"),
    (["--Q", "4"], "needs `--f`"),
    (["--Q", "4", "--Q-max", "4", "--f", "0.5"], "not both"),
    (["--Q", "40", "--f", "0.5"], "full sliding"),
    (["--format", "abaqus", "--Q", "4", "--f", "0.5"], "invalid choice"),
])
def test_a_half_given_friction_deck_is_one_line_and_exit_2(tmp_path, capsys, extra, match):
    assert main(["deck", *HERTZ, *extra, "--out", str(tmp_path / "d.inp")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and match in err[0], err
    assert not (tmp_path / "d.inp").exists()

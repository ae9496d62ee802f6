"""The ``threepart solve`` and ``threepart slip`` commands."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

from threepart.cli import main

GEOM = ["--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--rigid", "--P", "400"]


def test_solve_json_matches_the_hertz_anchor(capsys):
    assert main(["solve", "--R1", "10", "--R2", "10", "--b", "0", "--A", "1e-5", "--P", "400",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    a = math.sqrt(2 * 400 * 1e-5 * 10 / math.pi)
    assert out["a"] == pytest.approx(a, rel=1e-12) and out["c"] == pytest.approx(a, rel=1e-12)
    assert out["peak_left"]["p"] == pytest.approx(2 * 400 / (math.pi * a), rel=1e-9)
    # lift-off of a cylinder: the contact may roll until one edge reaches x = 0
    assert out["lift_off"]["s_max"] == pytest.approx(a, rel=1e-12)


def test_solve_text_lists_the_figures(capsys):
    assert main(["solve", *GEOM, "--s", "0.2"]) == 0
    text = capsys.readouterr().out
    for key in ("a ", "c ", "alpha", "peak_left", "peak_right", "s_min", "s_max"):
        assert key in text


def test_slip_json(capsys):
    assert main(["slip", *GEOM, "--s", "0.1", "--Q", "80", "--f", "0.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert -out["a"] < out["stick_zone"]["left"] < -1 and 1 < out["stick_zone"]["right"] < out["c"]


def test_bad_input_is_a_clear_error_with_exit_status_2(capsys):
    assert main(["solve", *GEOM, "--s", "0.9"]) == 2
    err = capsys.readouterr().err
    assert "`s` = 0.9 exceeds the lift-off lever arm" in err and "Traceback" not in err
    assert main(["slip", *GEOM, "--Q", "300", "--f", "0.5"]) == 2
    assert "full sliding" in capsys.readouterr().err
    assert main(["solve", "--R1", "10", "--R2", "5", "--b", "1", "--P", "400"]) == 2
    assert "needs `--A`" in capsys.readouterr().err


def test_console_script_runs_as_a_module():
    out = subprocess.run([sys.executable, "-m", "threepart.cli", "solve", *GEOM, "--json"],
                         capture_output=True, text=True, check=True)
    assert json.loads(out.stdout)["tilt"] == "free"

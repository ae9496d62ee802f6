"""The ``threepart solve`` and ``threepart slip`` commands."""
from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from threepart.cli import main
from threepart.tolerances import tolerance

#: an identity of the closed form in double precision (the JSON prints 17 digits)
ROUND_OFF = tolerance("closedform", "round_off").limit
#: the peak by a bounded search on Hertz's flat maximum: p0 (1 - (Δx/a)^2 / 2)
PEAK_SEARCH = 1e-9
#: the trapezoid rule on p with square-root edges: the error falls as h^1.5 (order 1.3..1.7), and is
#: below TRAPEZOID_LEVEL on 8001 points
TRAPEZOID_LEVEL, SQRT_EDGE_ORDER = 3e-5, (1.3, 1.7)
#: the friction coefficient of the slip command below (--f 0.5)
SLIP_F = 0.5

GEOM = ["--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--rigid", "--P", "400"]


def test_solve_json_matches_the_hertz_anchor(capsys):
    assert main(["solve", "--R1", "10", "--R2", "10", "--b", "0", "--A", "1e-5", "--P", "400",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    a = math.sqrt(2 * 400 * 1e-5 * 10 / math.pi)
    assert out["a"] == pytest.approx(a, rel=ROUND_OFF) and out["c"] == pytest.approx(a, rel=ROUND_OFF)
    assert out["peak_left"]["p"] == pytest.approx(2 * 400 / (math.pi * a), rel=PEAK_SEARCH)
    # lift-off of a cylinder: the contact may roll until one edge reaches x = 0
    assert out["lift_off"]["s_max"] == pytest.approx(a, rel=ROUND_OFF)


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
    assert main(["solve", *GEOM, "--s", "0.9", "--method", "closedform"]) == 2
    err = capsys.readouterr().err
    assert "`s` = 0.9 exceeds the lift-off lever arm" in err and "Traceback" not in err
    assert main(["slip", *GEOM, "--Q", "300", "--f", "0.5"]) == 2
    assert "full sliding" in capsys.readouterr().err
    assert main(["solve", "--R1", "10", "--R2", "5", "--b", "1", "--P", "400"]) == 2
    assert "needs `--A`" in capsys.readouterr().err


def test_console_script_runs_as_a_module(capsys, monkeypatch):
    """``python -m threepart.cli solve ... --json``, run in this process as the interpreter runs a
    module (its ``__main__`` under that name, the arguments in ``sys.argv``): status 0 and the JSON.
    ``python -m threepart.cli`` in a fresh interpreter: the broken-pipe test below."""
    import runpy

    import threepart.cli

    # run_path, not run_module: pytest's assertion rewriter holds the threepart package (a plugin)
    # and cannot hand runpy a module's code
    monkeypatch.setattr(sys, "argv", ["threepart.cli", "solve", *GEOM, "--json"])
    with pytest.raises(SystemExit) as done:
        runpy.run_path(str(Path(threepart.cli.__file__).with_name("__main__.py")), run_name="__main__")
    assert done.value.code == 0
    assert json.loads(capsys.readouterr().out)["tilt"] == "free"


# ---------------------------------------------------------------------------------------
# a command line that keeps its promise: one-line errors, strict JSON, negative numbers, units
# ---------------------------------------------------------------------------------------
def _refuse(name):
    raise ValueError(f"not strict JSON: {name}")


def _one_line_error(capsys, command="solve"):
    cap = capsys.readouterr()
    assert cap.err.count("\n") == 1, cap.err
    assert cap.err.startswith(f"threepart {command}: error: ") and "Traceback" not in cap.err
    return cap.err


@pytest.mark.parametrize("args,match", [
    (["--P", "-1"], r"`P` = -1\.0 must be"),
    (["--P", "abc"], r"argument --P: invalid float value: 'abc'"),
    (["--P", "400", "--R1", "0"], r"`R1` = 0\.0 must be > 0"),
    (["--P", "400", "--bogus", "1"], r"unrecognized arguments: --bogus 1"),
    (["--P", "400", "--tilt", "sideways"], r"argument --tilt: invalid choice: 'sideways'"),
    (["--P"], r"argument --P: expected one argument"),
    # a number double precision cannot hold is refused, not rounded to 0 or inf
    (["--P", "400", "--b", "1e-400"], r"argument --b: 1e-400 underflows to 0 in double precision "
                                      r"\(the smallest positive number is 4\.9e-324\)"),
    (["--P", "1e400"], r"argument --P: 1e400 overflows to inf in double precision \(the largest "
                       r"number is 1\.8e\+308\)"),
    (["--P", "400", "--x", "0.1,-1e-999"], r"argument --x: invalid list of numbers: '0\.1,-1e-999' "
                                           r"\(-1e-999 underflows to 0"),
])
def test_every_input_error_is_one_line_with_exit_status_2(capsys, args, match):
    base = ["--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--rigid"]
    assert main(["solve", *base, *args]) == 2
    assert re.search(match, _one_line_error(capsys))


def test_a_missing_command_is_a_one_line_usage_error(capsys):
    assert main([]) == 2
    err = capsys.readouterr().err
    assert err == ("threepart: error: the following arguments are required: command "
                   "(see `threepart --help`)\n")


@pytest.mark.parametrize("error", ["NoConvergenceError", "ContactZoneError"])
def test_a_solver_that_fails_gives_one_line_and_exit_status_2(capsys, monkeypatch, error):
    from dataclasses import replace

    from threepart import errors, registry

    def fail(*a, **k):
        raise getattr(errors, error)("the root did not close\nafter 100 steps")

    monkeypatch.setitem(registry._REGISTRY, "closedform", replace(registry.get("closedform"),
                                                                  normal=fail))
    assert main(["solve", *GEOM]) == 2
    assert "error: the root did not close after 100 steps" in _one_line_error(capsys)


def test_an_os_error_gives_one_line_and_exit_status_2(capsys):
    assert main(["verify", "--quick", "--out", "/proc/x"]) == 2
    assert "cannot write `out` = '/proc/x'" in _one_line_error(capsys, "verify")


def test_ctrl_c_prints_one_line_and_exits_130(capsys, monkeypatch):
    from dataclasses import replace

    from threepart import registry

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setitem(registry._REGISTRY, "closedform", replace(registry.get("closedform"),
                                                                  normal=interrupted))
    try:
        status = main(["solve", *GEOM])
    except KeyboardInterrupt:
        pytest.fail("KeyboardInterrupt escaped main()")
    assert status == 130
    assert capsys.readouterr().err == "threepart solve: interrupted\n"


#: a command whose solver's import is interrupted as numpy's is (the Ctrl-C comes out as an
#: ImportError), in a process of its own that signals only itself
C_EXTENSION_CTRL_C = """
import os, signal, sys
from dataclasses import replace
from threepart import registry
from threepart.cli import main

def import_interrupted(*a, **k):
    try:
        os.kill(os.getpid(), signal.SIGINT)
    except KeyboardInterrupt:
        pass
    raise ImportError("Importing the numpy C-extensions failed.")

registry._REGISTRY["closedform"] = replace(registry.get("closedform"), normal=import_interrupted)
status = main(sys.argv[1:])
if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
    sys.exit("main() did not restore the SIGINT handler it replaced")
sys.exit(status)
"""


def test_ctrl_c_that_a_c_extension_turns_into_another_error_is_still_an_interrupt():
    """numpy's import turns a Ctrl-C into an ImportError ("Importing the numpy C-extensions
    failed"), losing the KeyboardInterrupt: still one line, exit status 130, and the handler main()
    replaced is restored. The SIGINT is sent in a child in its own session, to itself: never to
    the test runner."""
    import signal

    # Python's own handler, as in a terminal's foreground job (a background `pytest &` starts
    # with SIGINT ignored, and its children would inherit that)
    proc = subprocess.run([sys.executable, "-c", C_EXTENSION_CTRL_C, "solve", *GEOM],
                          cwd=Path(__file__).resolve().parents[1], capture_output=True, text=True,
                          start_new_session=True,
                          preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr == "threepart solve: interrupted\n"


#: 128 + SIGPIPE: the status a program killed by SIGPIPE reports (POSIX shells, git, coreutils)
SIGPIPE_STATUS = 141


def test_a_reader_that_goes_away_ends_the_output_silently_with_141():
    """``threepart slip ... | head -1``: no "Broken pipe" line, the shell's 128 + SIGPIPE."""
    proc = subprocess.Popen([sys.executable, "-m", "threepart.cli", "slip", "--R1", "10", "--R2",
                             "10", "--b", "1", "--P", "100", "--Q", "20", "--f", "0.5", "--A",
                             "1e-5", "--grid", "20000"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stdout.readline().startswith("method:")
    proc.stdout.close()                       # the reader goes away, as `head -1` does
    err = proc.stderr.read()
    assert proc.wait() == SIGPIPE_STATUS
    assert err == ""


def test_a_broken_pipe_elsewhere_is_still_a_one_line_error(capsys, monkeypatch):
    """A broken pipe that is not standard output's (a socket, a worker) is an error, exit 2."""
    from dataclasses import replace

    from threepart import registry

    def broken(*a, **k):
        raise BrokenPipeError(32, "Broken pipe")

    monkeypatch.setitem(registry._REGISTRY, "closedform", replace(registry.get("closedform"),
                                                                  normal=broken))
    assert main(["solve", *GEOM]) == 2
    assert "error: [Errno 32] Broken pipe" in _one_line_error(capsys)


def test_help_still_works_and_documents_units_and_null(capsys):
    assert main(["solve", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "[N/mm]" in text and "[mm]" in text and "any consistent set" in text
    assert "an infinite R (flat centre) is null" in text
    assert main(["--help"]) == 0
    assert "1/MPa" in capsys.readouterr().out


def test_usage_error_of_the_console_script_is_one_line():
    out = subprocess.run([sys.executable, "-m", "threepart", "solve", "--P", "abc"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and out.stderr.startswith("threepart solve: error: ")


def test_json_is_strict_and_an_infinite_R_is_null(capsys):
    assert main(["solve", *GEOM, "--json"]) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=_refuse)
    assert out["punch"]["R"] is None and out["punch"]["case"] == "A"
    assert out["units"]["a"] == "mm" and out["units"]["P"] == "N/mm" and out["units"]["alpha"] == "rad"
    assert out["units"]["p"] == "MPa" and out["units"]["A"] == "1/MPa"


@pytest.mark.parametrize("option,value", [("--s", "-0.1"), ("--s", "-1e-3"), ("--R", "-200"),
                                          ("--Q", "-80"), ("--s", "-.05")])
def test_a_negative_number_may_follow_its_option(capsys, option, value):
    args = ["slip", "--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--rigid",
            "--P", "2000", "--Q", "80", "--f", "0.5", "--json"]
    assert main([*args, "--s", "0.1", option, value]) == 0
    separate = json.loads(capsys.readouterr().out)
    assert main([*args, "--s", "0.1", f"{option}={value}"]) == 0
    assert separate == json.loads(capsys.readouterr().out)
    key = {"--s": "s", "--Q": "Q"}.get(option)
    got = separate["punch"]["R"] if option == "--R" else separate[key]
    assert got == float(value)


def test_every_number_option_accepts_a_negative_value():
    from threepart.cli import NUMERIC_OPTIONS, build_parser, real_arg

    parser = build_parser()
    subs = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    numeric = {o for p in subs.choices.values() for a in p._actions if a.type is real_arg
               for o in a.option_strings}
    assert numeric == set(NUMERIC_OPTIONS)


UNIT_LABELS = {"mm", "N/mm", "MPa", "1/MPa", "rad", "(dimensionless)"}


@pytest.mark.parametrize("command", ["solve", "slip"])
def test_every_number_in_the_text_output_carries_its_unit(capsys, command):
    extra = ["--Q", "80", "--f", "0.5"] if command == "slip" else []
    assert main([command, *GEOM, "--s", "0.1", *extra]) == 0
    lines = capsys.readouterr().out.splitlines()
    numbers = 0
    for line in lines:
        tokens = line.split()
        if len(tokens) >= 2 and re.fullmatch(r"[-+]?(\d[\d.e+-]*|inf)", tokens[1]):
            numbers += 1
            assert len(tokens) == 3 and tokens[2] in UNIT_LABELS, line
    assert numbers == (26 if command == "slip" else 19)   # slope (and sigma_bulk) included
    if command == "slip":
        assert "f          0.5 (dimensionless)" in lines
    assert "  R          inf mm" in lines


def test_json_units_name_every_number(capsys):
    from threepart.cli import UNITS

    assert main(["slip", *GEOM, "--s", "0.1", "--Q", "80", "--f", "0.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=_refuse)
    units = out.pop("units")

    def keys(d):
        for k, v in d.items():
            if isinstance(v, dict):
                yield from keys(v)
            elif isinstance(v, (int, float)) and not isinstance(v, bool) or v is None:
                yield k

    assert set(keys(out)) == set(units) and all(units[k] == UNITS[k] for k in units)


# ---------------------------------------------------------------------------------------
# --method, and the fields at chosen points
# ---------------------------------------------------------------------------------------
def test_auto_says_which_method_answered(capsys):
    assert main(["solve", *GEOM, "--s", "0.1"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == "method: closedform"
    assert main(["solve", *GEOM, "--s", "0.9"]) == 0     # past lift-off: the SIE answers
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("method: sie (the closed form does not hold here: `s` = 0.9 exceeds")


def _grid_integral(capsys, n: int) -> float:
    assert main(["solve", *GEOM, "--s", "0.1", "--grid", str(n), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    x, p = out["points"]["x"], out["points"]["p"]
    assert x[0] == -out["a"] and x[-1] == out["c"] and len(x) == n
    assert out["units"]["p"] == "MPa" and out["units"]["x"] == "mm"
    return sum(0.5 * (p[i] + p[i + 1]) * (x[i + 1] - x[i]) for i in range(n - 1))


def test_pressure_at_points_integrates_to_the_load(capsys):
    """--grid: the trapezoidal integral of p is P, its error falling as h^1.5 (square-root edges)."""
    e1, e2 = (abs(_grid_integral(capsys, n) - 400.0) / 400.0 for n in (2001, 8001))
    assert e2 < TRAPEZOID_LEVEL and 4**SQRT_EDGE_ORDER[0] < e1 / e2 < 4**SQRT_EDGE_ORDER[1], (e1, e2)


def test_shear_at_points_obeys_coulomb_and_the_csv_is_new(capsys, tmp_path):
    csv = tmp_path / "fields.csv"
    args = ["slip", *GEOM, "--s", "0.1", "--Q", "80", "--f", "0.5", "--x", "-2,-0.5,0,0.5,1.7"]
    assert main([*args, "--csv", str(csv), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = csv.read_text().splitlines()
    assert rows[0] == "x [mm],p [MPa],q [MPa]" and len(rows) == 6
    for row, x, p, q in zip(rows[1:], *(out["points"][k] for k in "xpq")):
        assert [float(v) for v in row.split(",")] == [x, p, q]
        assert abs(q) <= SLIP_F * p * (1 + ROUND_OFF)         # |q| <= f p
    assert out["points"]["p"][0] == 0.0                  # x = -2 lies outside the contact
    # the file is threepart's own and unchanged: a rerun replaces it; once edited, it is never overwritten
    assert main([*args, "--csv", str(csv)]) == 0
    assert csv.read_text().splitlines() == rows
    capsys.readouterr()
    csv.write_text("my own notes\n")
    assert main([*args, "--csv", str(csv)]) == 2
    assert "was changed after threepart wrote it; refusing to overwrite it" in _one_line_error(capsys, "slip")
    assert csv.read_text() == "my own notes\n"


@pytest.mark.parametrize("extra,match", [
    (["--x", "1", "--grid", "3"], "give `--x` or `--grid`, not both"),
    (["--grid", "1"], r"`--grid` = 1 must lie in \[2, 1000000\]"),
    (["--x", "1,a"], r"invalid list of numbers: '1,a'"),
    (["--csv", "f.csv"], "`--csv` needs the points"),
    (["--method", "magic"], "argument --method: invalid choice: 'magic'"),
])
def test_bad_point_options_are_one_line_errors(capsys, extra, match):
    assert main(["solve", *GEOM, *extra]) == 2
    assert re.search(match, _one_line_error(capsys))


def test_a_negative_point_list_may_follow_x(capsys):
    assert main(["solve", *GEOM, "--x", "-0.5,0.2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["points"]["x"] == [-0.5, 0.2]


def test_fem_slip_is_the_two_body_friction_model_and_agrees_with_the_closed_form(capsys):
    from threepart.tolerances import tolerance

    def run(*method: str) -> dict:
        assert main(["slip", *GEOM, "--Q", "80", "--f", "0.5", "--json", *method]) == 0
        return json.loads(capsys.readouterr().out)

    cf, fe = run("--method", "closedform"), run("--method", "fem", "--mesh", "quick")
    assert fe["method"] == "fem"
    for key in ("d", "e"):
        err = abs(fe[key] - cf[key]) / cf["d"]
        assert err < tolerance("fem-quick", key).limit, (key, fe[key], cf[key])


AGEOM = ["--R1", "10", "--R2", "5", "--b", "1", "--A", "8.67e-6", "--P", "400"]


@pytest.mark.parametrize("extra,match", [
    (["--rigid"], r"`--rigid` applies to `--E`/`--nu`"),
    (["--nu", "0.3"], r"`--nu` with `--A` is used only by a method that models a finite body"),
])
def test_a_compliance_with_material_options_is_refused_not_ignored(capsys, extra, match):
    assert main(["solve", *AGEOM, *extra]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and re.search(match, err), err


def test_past_lift_off_the_monotone_half_has_no_interior_peak(capsys):
    """At s = 0.6 > s_max the left edge sits on the flat centre: p rises from -a to the right peak."""
    assert main(["solve", *AGEOM, "--s", "0.6", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["peak_left"] == {"none": "no interior peak: p rises monotonically from the left "
                                        "end into the right half"}
    from threepart import Punch, sie
    r = sie.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, 0.6, A=8.67e-6)
    x = np.linspace(-r.a, r.c, 4001)
    p = r.pressure(x)
    rising = x < out["peak_right"]["x"]   # sampled independently of peaks(): monotone to the peak
    assert np.all(np.diff(p[rising]) > 0)
    assert out["peak_right"]["p"] >= p.max()


def test_fem_states_the_poisson_ratio_it_assumed_and_echoes_s_as_given(capsys):
    assert main(["solve", *AGEOM, "--s", "0.1", "--method", "fem", "--mesh", "quick", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["nu"] == 0.3 and "nu = 0.3 assumed" in out["nu_note"]
    assert repr(out["s"]) == "0.1"
    # the contact's slope is reported: at least the tilt, at least the profile's slope at -a
    assert out["slope"] >= max(abs(out["alpha"]), (out["a"] - 1.0) / 10.0)


@pytest.mark.parametrize("loaded, delay", [("_multiarray_umath", 0.0), ("libgmsh", 1.0)])
def test_ctrl_c_while_loading_or_solving_prints_exactly_one_line(loaded, delay, tmp_path):
    """SIGINT while numpy and scipy still load (numpy's core just mapped), or while the FEM
    meshes and solves (gmsh loaded, a second later): one line, exit status 130.

    The moment is read from the process's memory map, not guessed from the clock, so that a
    loaded machine cannot move the signal into the interpreter's own start-up, before any of
    threepart runs."""
    import signal
    import time

    # a shell's background job (`pytest &`, nohup) starts with SIGINT ignored, and so would the
    # child: give it the default disposition a terminal's foreground process has
    proc = subprocess.Popen([sys.executable, "-m", "threepart", "solve", *AGEOM, "--method", "fem",
                             "--mesh", "fine"], cwd=tmp_path, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    maps = Path(f"/proc/{proc.pid}/maps")
    t0 = time.monotonic()
    while loaded not in maps.read_text():   # fails, never proceeds, if the moment does not come
        assert proc.poll() is None, f"the child ended before {loaded} was loaded: {proc.stderr.read()}"
        assert time.monotonic() - t0 < LINE_GUARD_S, f"{loaded} not loaded in {LINE_GUARD_S} s"
        time.sleep(0.005)
    time.sleep(delay)   # into the FE solve, which takes far longer on the fine mesh (never shorter under load)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=LINE_GUARD_S)
    assert proc.returncode == 130, err
    assert err.strip() == "threepart solve: interrupted", err


def test_the_command_list_names_every_sub_command():
    from threepart.cli import COMMANDS, build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    assert set(sub.choices) == set(COMMANDS)


def test_every_sub_command_module_has_the_interface_and_its_command_is_in_the_help(capsys):
    """Each public module of the package threepart/cli/, as found on disk (pkgutil, not the parser's
    own tuple), has ``add_parser`` and ``run``; ``threepart --help`` lists its command (its name, ``-``
    for ``_``), which runs its ``run``; and every command listed is run by one of those modules."""
    import importlib
    import pkgutil

    import threepart.cli as package
    from threepart.cli import build_parser

    names = [m.name for m in pkgutil.iter_modules(package.__path__) if not m.name.startswith("_")]
    assert "solve" in names and "cycle" in names
    assert main(["--help"]) == 0
    listed = re.search(r"\{([a-z,-]+)\}", capsys.readouterr().out).group(1).split(",")
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    for name in names:
        module = importlib.import_module(f"threepart.cli.{name}")
        assert callable(getattr(module, "add_parser", None)) and callable(getattr(module, "run", None)), name
        command = name.replace("_", "-")
        assert command in listed, f"`threepart --help` does not list {command} (threepart/cli/{name}.py)"
        assert sub.choices[command].get_default("func") is module.run, name
    runs = {sub.choices[c].get_default("func").__module__ for c in listed}
    assert runs == {f"threepart.cli.{name}" for name in names}


def test_a_number_that_double_precision_holds_is_read_as_before(capsys):
    """The float-argument parser against float(): the smallest subnormal, the largest double and
    an infinite R (flat centre) are read as they are; only 0 and inf reached by rounding are refused."""
    from threepart.cli import real_arg

    for text in ("5e-324", "1.7976931348623157e308", "inf", "-inf", "0", "-0.0", "1_000.5", " 2.5 "):
        assert real_arg(text) == float(text) or (math.isnan(float(text)))
    assert main(["solve", *GEOM, "--R", "inf", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["punch"]["R"] is None


# ---------------------------------------------------------------------------------------
# compare: its own options and the pressure refused before anything is written
# ---------------------------------------------------------------------------------------
COMPARE = ["compare", "--R1", "10", "--R2", "5", "--b", "1", "--P", "400", "--E", "210000", "--nu", "0.3"]


def _pressure_csv(path: Path, x_scale: float = 1.0, p_scale: float = 1.0) -> Path:
    """A square-root pressure on [-2, 2] at 21 points, its x and p scaled."""
    x = np.linspace(-2.0, 2.0, 21)
    p = np.sqrt(np.clip(4.0 - x ** 2, 0.0, None)) / 2.0
    path.write_text("x,p\n" + "".join(f"{float(u * x_scale)!r},{float(v * p_scale)!r}\n"
                                        for u, v in zip(x, p)))
    return path


@pytest.mark.parametrize("extra, match", [
    (["--alpha", "nan"], r"`--alpha` = nan must be a finite number"),
    (["--alpha", "inf"], r"`--alpha` = inf must be a finite number"),
    (["--alpha", "1e300"], r"`--alpha` = 1e\+300 rad exceeds the small-slope limit 0\.5"),
    (["--penalty", "-5"], r"`--penalty` = -5\.0 must be > 0"),
    (["--penalty", "1e300"], r"`--penalty` = 1e\+300 is outside \[1e-60, 1e\+60\]"),
])
def test_compare_refuses_its_options_out_of_range_before_writing(capsys, tmp_path, extra, match):
    out = tmp_path / "report"
    argv = [*COMPARE, "--pressure", str(_pressure_csv(tmp_path / "p.csv")), "--out", str(out), *extra]
    assert main(argv) == 2
    assert re.search(match, _one_line_error(capsys, "compare"))
    assert not out.exists()


@pytest.mark.parametrize("x_scale, p_scale, match", [
    (1.0, 1e308, r"the pressure's `p` reaches 1e\+308 in magnitude, past 1e\+60"),
    (1e300, 1.0, r"the pressure's `x` reaches 2e\+300 in magnitude, past 1e\+60"),
])
def test_compare_refuses_a_pressure_whose_load_overflows_before_writing(capsys, tmp_path, x_scale,
                                                                        p_scale, match):
    """Its ∫p dx or ∫x p dx would be inf (the report's figures None): one line, exit 2, no report."""
    out = tmp_path / "report"
    csv = _pressure_csv(tmp_path / "p.csv", x_scale, p_scale)
    assert main([*COMPARE, "--pressure", str(csv), "--out", str(out)]) == 2
    assert re.search(match, _one_line_error(capsys, "compare"))
    assert not out.exists()


# ---------------------------------------------------------------------------------------
# a modulus in GPa, unbounded work
# ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("E, unit", [("210", "GPa"), ("210e9", "Pa")])
def test_a_modulus_in_other_units_is_refused_before_any_solve(capsys, E, unit):
    """--E 210 (steel in GPa) or 210e9 (in Pa) lies outside the moduli of engineering solids in MPa
    (threepart.problem.units.E_RANGE): one line naming --E and the range, exit 2, whatever the load."""
    from threepart.problem.units import E_RANGE

    base = ["solve", "--R1", "10", "--R2", "5", "--b", "1", "--nu", "0.3", "--s", "0.1", "--P", "400"]
    assert main([*base, "--E", E]) == 2
    err = _one_line_error(capsys)
    assert "`--E`" in err and f"[{E_RANGE[0]:g}, {E_RANGE[1]:g}] MPa" in err, (unit, err)
    assert main([*base, "--E", "210000"]) == 0
    capsys.readouterr()


FATIGUE = ["fatigue", "--R1", "10", "--R2", "10", "--b", "0", "--E", "210000", "--nu", "0.3", "--P", "100",
           "--Q-max", "20", "--f", "0.5", "--nx", "3", "--nz", "2", "--ns", "3"]
#: the longest a test waits for a line a thread of the command prints (a hang guard, not a timing:
#: the wait ends as soon as the line is there)
LINE_GUARD_S = 600


def test_fatigue_states_are_bounded_and_the_bound_is_in_the_help(capsys):
    from threepart.cli.fatigue import MAX_FATIGUE_STATES

    assert main([*FATIGUE, "--states", "1000"]) == 2
    assert f"`--states` = 1000 must lie in [2, {MAX_FATIGUE_STATES}]" in _one_line_error(capsys, "fatigue")
    assert main(["fatigue", "--help"]) == 0
    help_text = " ".join(capsys.readouterr().out.split())
    assert f"recorded states per branch of the cycle, 2 to {MAX_FATIGUE_STATES}" in help_text


def test_fatigue_constant_reaches_its_row_and_crossland_is_affine_in_kappa(capsys, tmp_path):
    """``--constant kappa=...`` reaches Crossland's row: its field is affine in kappa (Crossland's
    definition, sqrt(J2,a) + kappa sigma_h,max), kappa moves it, and no option gives its default."""
    from threepart.fatigue.table import KAPPA_CROSSLAND

    def field(*extra):
        out = tmp_path / f"f{len(list(tmp_path.iterdir()))}.csv"
        assert main([*FATIGUE, "--csv", str(out), *extra]) == 0
        text = capsys.readouterr().out
        rows = [line.split(",") for line in out.read_text().splitlines()]
        col = rows[0].index("crossland [MPa]")
        return np.array([float(r[col]) for r in rows[1:]]), text

    c0, text0 = field("--constant", "kappa=0")
    c1, _ = field("--constant", "kappa=1")
    default, text = field()
    assert "constants  k 0.3, kappa 0 " in text0 and "kappa" not in text.split("constants", 1)[1].splitlines()[0]
    sigma_h = c1 - c0
    assert np.abs(sigma_h).max() > 0       # kappa moves the field
    scale = np.abs(c1).max()
    assert np.abs(default - (c0 + KAPPA_CROSSLAND * sigma_h)).max() <= tolerance("closedform", "round_off").limit * scale


@pytest.mark.parametrize("given, match", [
    ("kappa", r"argument --constant: invalid constant: 'kappa' \(write NAME=VALUE"),
    ("k=0.3", r"`--constant k=...`: Findley's constant is `--k`"),
    ("foo=1", r"no fatigue parameter has a constant `foo` \(theirs: kappa"),
    ("kappa=11", r"`kappa` = 11.0 must lie in \[0, 10\]"),
])
def test_a_bad_fatigue_constant_is_one_line_and_exit_2(capsys, given, match):
    assert main([*FATIGUE, "--constant", given]) == 2
    assert re.search(match, _one_line_error(capsys, "fatigue"))


def test_a_fatigue_constant_given_twice_is_refused(capsys):
    assert main([*FATIGUE, "--constant", "kappa=0.1", "--constant", "kappa=0.2"]) == 2
    assert "`--constant kappa` is given twice" in _one_line_error(capsys, "fatigue")


def test_fatigue_auto_falls_back_past_lift_off_and_says_why_on_its_first_line(capsys):
    """threepart.fretting's ``auto`` behind ``threepart fatigue``: past lift-off the SIE answers, and the
    first line quotes the refusal the closed form raises when called directly (one auto fallback)."""
    from threepart import Punch, registry, similar_pair
    from threepart.errors import LiftOffError

    with pytest.raises(LiftOffError) as refusal:
        registry.get("closedform").fretting(Punch(10.0, 5.0, 1.0), 400.0, 0.9, A=similar_pair(210e3, 0.3),
                                            Q_max=60.0, f=0.5, states=2)
    argv = ["fatigue", *GEOM[:6], "--E", "210000", "--nu", "0.3", "--P", "400", "--s", "0.9",
            "--Q-max", "60", "--f", "0.5", "--states", "2", "--nx", "3", "--nz", "2", "--ns", "3"]
    assert main(argv) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first == f"method: sie (the closed form does not hold here: {refusal.value})"


def test_a_long_fatigue_run_says_it_is_still_running(capsys, monkeypatch):
    """The heartbeat every HEARTBEAT_S (15 s; here shortened): the stage and "still running" on stderr.
    The cycle is held until the first such line is written, so no clock decides the outcome."""
    import io
    import threading

    from threepart import progress
    from threepart.cli import fatigue as cli_fatigue

    class Stderr(io.StringIO):
        beat = threading.Event()

        def write(self, text: str) -> int:
            if "still running" in text:
                self.beat.set()
            return super().write(text)

    err = Stderr()
    real = cli_fatigue._fretting

    def held(*args):
        cycle = real(*args)
        assert err.beat.wait(LINE_GUARD_S)
        return cycle

    monkeypatch.setattr(progress, "HEARTBEAT_S", 1e-3)
    monkeypatch.setattr(cli_fatigue, "_fretting", held)
    monkeypatch.setattr(sys, "stderr", err)
    assert main([*FATIGUE, "--states", "3"]) == 0
    assert re.search(r"^threepart fatigue: the fretting cycle \(3 states per branch\) still running "
                     r"\(\d+ s\)$", err.getvalue(), re.M), err.getvalue()


# ---------------------------------------------------------------------------------------
# Ctrl-C before main() watches SIGINT
# ---------------------------------------------------------------------------------------
#: the console script, as pip writes it from pyproject.toml's [project.scripts], in a process that
#: sends itself SIGINT when the module named by argv[1] is first imported (the command line loading)
EARLY_CTRL_C = """
import os, signal, sys, tomllib

loading = sys.argv[1]

class CtrlC:
    def find_spec(self, name, path=None, target=None):
        if name == loading:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None

entry = tomllib.load(open("pyproject.toml", "rb"))["project"]["scripts"]["threepart"]
module, attr = entry.split(":")
sys.meta_path.insert(0, CtrlC())
sys.argv = ["threepart", *sys.argv[2:]]
main = getattr(__import__(module, fromlist=[attr]), attr)
sys.exit(main())
"""


@pytest.mark.parametrize("loading", ["threepart.cli", "argparse", "gettext"])
def test_ctrl_c_while_the_command_line_loads_is_one_line_and_130(loading):
    """SIGINT while the command line, argparse or argparse's own imports load, before main() watches
    SIGINT: one line, exit status 130, never a traceback. The child is in a session of its own and
    signals only itself."""
    import signal

    root = Path(__file__).resolve().parents[1]
    proc = subprocess.run([sys.executable, "-c", EARLY_CTRL_C, loading, "solve", *GEOM], cwd=root,
                          capture_output=True, text=True, start_new_session=True,
                          preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr == "threepart solve: interrupted\n"


def test_each_sub_commands_help_line_comes_from_its_own_module():
    """``threepart --help`` lists every sub-command with the ``help=`` its module gave (issue 40): a new
    sub-command's line is written once, in its module; and a module's line reaches the listing."""
    import argparse

    from threepart.cli import build_parser
    from threepart.cli._main import command_lines

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    listed = {ln.split()[0]: ln.split(None, 1)[1] for ln in command_lines(sub).splitlines()}
    assert listed == {a.dest: a.help for a in sub._choices_actions}
    assert all(f"{name}" in parser.description and help_ in parser.description for name, help_ in listed.items())
    # a module's own line, not a copy: a sub-parser added here is listed with its help
    extra = argparse.ArgumentParser().add_subparsers()
    extra.add_parser("toy", help="a toy sub-command")
    assert command_lines(extra) == "toy  a toy sub-command"

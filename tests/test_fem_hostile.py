"""Hostile input to the FE package: refused before any numerics, in one exception family.

Every public FE entry point checks its input before it meshes or solves
anything; the ``no_numerics`` fixture makes any meshing, locating or
condensing fail the test, so each refusal below is proved to come first.
Foreign failures (NumPy's ``LinAlgError``, meshio's ``ReadError``, gmsh's
bare ``Exception``) surface as the package's own errors, in one line.
The references are the arguments' documented limits, not the code's output.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import gmsh
import numpy as np
import pytest

from threepart import fem, meshes
from threepart.errors import NoConvergenceError
from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch

PUNCH = Punch(R1=10.0, R2=5.0, b=1.0)
REFERENCE_MSH = Path(meshes.__file__).parent / "reference.msh"
E, NU = 210e3, 0.3

#: the four solvers, each with the keywords it needs besides the hostile one
ENTRIES = {
    "solve_normal": (fem.solve_normal, dict(E=E, nu=NU, mesh="quick")),
    "solve_partial_slip": (fem.solve_partial_slip, dict(E=E, nu=NU, mesh="quick", Q=10.0, f=0.5)),
    "fretting_cycle": (fem.fretting_cycle, dict(E=E, nu=NU, mesh="quick", Q_max=10.0, f=0.5)),
    "solve_finite": (fem.solve_finite, dict(E=E, nu=NU, mesh="quick", H=8.0)),
    "locate_contact": (fem.locate_contact, dict(E=E, nu=NU, tilt="free")),
}


@pytest.fixture
def no_numerics(monkeypatch):
    """Any meshing, locating or condensing fails the test: input is checked first."""
    def boom(*args, **kwargs):
        raise AssertionError("numerics ran before the input was checked")

    from threepart.fem import finite, solve, twobody
    for module, names in ((solve, ("locate_ends", "make_substrate", "read_substrate", "condense")),
                          (twobody, ("place_substrate", "make_substrate", "interface", "bulk_field")),
                          (finite, ("locate_ends", "make_substrate", "condense"))):
        for name in names:
            monkeypatch.setattr(module, name, boom)
    monkeypatch.setattr(gmsh, "initialize", boom)


def call(entry: str, P=400.0, s=0.0, **kwargs):
    func, base = ENTRIES[entry]
    return func(PUNCH, P, s, **{**base, **kwargs})


@pytest.mark.parametrize("entry", ENTRIES)
@pytest.mark.parametrize("s", [1e300, -1e300, 6.0, -11.0, float("inf")])
def test_a_lever_arm_off_the_footprint_is_refused(no_numerics, entry, s):
    """The footprint of Punch(10, 5, 1) is (-(b + R1), b + R2) = (-11, 6), open."""
    with pytest.raises(ValueError, match=r"`s` = .*(footprint \(-11, 6\)|finite)"):
        call(entry, s=s)


def test_the_fuzzed_cli_crash_is_a_one_line_refusal():
    """gmsh used to crash the process (SIGSEGV, exit 139) on s = 1e300."""
    out = subprocess.run([sys.executable, "-m", "threepart", "solve", "--R1", "10", "--R2", "5",
                          "--b", "1", "--A", "8.67e-6", "--P", "400", "--s", "1e300",
                          "--method", "fem", "--mesh", "quick"],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "`s`" in lines[0] and "footprint" in lines[0], out.stderr


@pytest.mark.parametrize("entry", ENTRIES)
@pytest.mark.parametrize("kwargs, error, match", [
    (dict(nu=-1.0), ValueError, r"`nu` = -1.0 must lie in \(-1, 0.5\)"),
    (dict(nu=0.5, E=0.0), ValueError, r"`nu` = 0.5"),     # nu is named first, E derives from it
    (dict(nu=True), TypeError, "`nu`"),
    (dict(E=-1.0), ValueError, "`E` = -1.0 must be > 0"),
    (dict(E="210e3"), TypeError, "`E`"),
    (dict(P=1e-300), ValueError, r"`P` = 1e-300 is outside \[1e-60, 1e\+60\]"),
    (dict(P=1e60, E=1e-60), ValueError, r"`P` = 1e\+60 gives A P max\(R1, R2, b\) = .* outside "
                                        r"\[1e-120, 1e\+120\]"),
    (dict(P=-1.0), ValueError, "`P` = -1.0 must be > 0"),
    (dict(P=True), TypeError, "`P`"),
    (dict(tilt="locked"), ValueError, "`tilt` = 'locked'"),
    (dict(max_iter=True), TypeError, "`max_iter`"),
    (dict(max_iter=10**9), ValueError, r"`max_iter` = 1000000000 must lie in \[1, 10000\]"),
])
def test_bad_input_names_the_argument_and_the_limit(no_numerics, entry, kwargs, error, match):
    with pytest.raises(error, match=match):
        call(entry, **kwargs)


@pytest.mark.parametrize("entry", ["solve_normal", "solve_partial_slip", "fretting_cycle",
                                   "solve_finite"])
@pytest.mark.parametrize("mesh, error, match", [
    (42, TypeError, "`mesh` must be a preset name"),
    ("huge", ValueError, "`mesh` = 'huge' is not a preset"),
    (fem.MeshPreset(n=10), None, None),   # a valid preset: reaches the numerics
])
def test_the_mesh_argument_is_checked(no_numerics, entry, mesh, error, match):
    if error is None:
        with pytest.raises(AssertionError, match="numerics ran"):
            call(entry, mesh=mesh)
    else:
        with pytest.raises(error, match=match):
            call(entry, mesh=mesh)


@pytest.mark.parametrize("entry", ["solve_normal", "solve_partial_slip", "fretting_cycle"])
def test_a_missing_mesh_file_is_refused(no_numerics, entry, tmp_path):
    with pytest.raises(ValueError, match="is not a file"):
        call(entry, mesh=str(tmp_path / "absent.msh"))


@pytest.mark.parametrize("entry, kwargs, error, match", [
    ("solve_partial_slip", dict(steps=True), TypeError, "`steps`"),
    ("solve_partial_slip", dict(steps=0), ValueError, r"`steps` = 0 must lie in \[1, 1000\]"),
    ("solve_partial_slip", dict(steps=10**7), ValueError, r"\[1, 1000\]"),
    ("solve_partial_slip", dict(steps=2.0), TypeError, "`steps`"),
    ("fretting_cycle", dict(states=True), TypeError, "`states`"),
    ("fretting_cycle", dict(states=1), ValueError, r"`states` = 1 must lie in \[2, 1000\]"),
    ("fretting_cycle", dict(Q_max=-1.0), ValueError, "`Q_max`"),
    ("solve_partial_slip", dict(Q=float("nan")), ValueError, "`Q`"),
    ("solve_partial_slip", dict(f=True), TypeError, "`f`"),
    ("solve_partial_slip", dict(Q=400.0), ValueError, r"`Q`.*f P"),    # FullSlidingError
    ("solve_finite", dict(H=True), TypeError, "`H`"),
    ("solve_finite", dict(H=1e300), ValueError, r"`H` = 1e\+300"),
    ("solve_finite", dict(H=2e4), ValueError, r"`H` = 20000.0 exceeds 1000 \(b \+ max\(R1, R2\)\) "
                                              r"= 11000"),
    ("solve_finite", dict(H=-1.0), ValueError, "`H` = -1.0 must be > 0"),
    ("solve_finite", dict(theta=2.0), ValueError, r"`theta` = 2.0 must lie in \(0, pi/2\)"),
    ("solve_finite", dict(profile="cone"), ValueError, "`profile` = 'cone'"),
    ("solve_normal", dict(fields="yes"), TypeError, "`fields`"),
    ("solve_normal", dict(progress="loud"), TypeError, "`progress`"),
    ("fretting_cycle", dict(progress=1), TypeError, "`progress`"),
])
def test_counts_and_sizes_have_bounds(no_numerics, entry, kwargs, error, match):
    with pytest.raises(error, match=match):
        call(entry, **kwargs)


def test_solve_finite_refuses_a_rounded_centre(no_numerics):
    with pytest.raises(ValueError, match="flat centre"):
        fem.solve_finite(Punch(10.0, 5.0, 1.0, R=100.0), 400.0, E=E, nu=NU, H=8.0, mesh="quick")


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(n=True), TypeError, "`n`"),
    (dict(n=1e9), ValueError, r"`n` = 1000000000.0 must lie in \[4, 2400\]"),
    (dict(n=100, growth=1e-9), ValueError, r"`growth` = 1e-09 must lie in \[0.0125, 1\]"),
    (dict(n=100, L=1e300), ValueError, r"`L` = 1e\+300 must lie in \[4, 10000\]"),
    (dict(n=100, refine=1e6), ValueError, r"`refine`"),
    (dict(n=100, margin=0.0), ValueError, r"`margin` = 0.0 must lie in \(0, 2\]"),
])
def test_a_preset_has_bounds(kwargs, error, match):
    with pytest.raises(error, match=match):
        fem.MeshPreset(**kwargs)


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(x_lo=-1.0, x_hi=1.0, h=1e-9, L=10.0), ValueError, "elements along the zone"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.1, L=1e300), ValueError, "`L` = 1e\\+300 is"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.1, L=10.0, growth=1e-9), ValueError, "`growth`"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.1, L=10.0, h_fine=1e-9, refine_at=(0.0,)), ValueError,
     "`h_fine`"),
    (dict(x_lo=-1.0, x_hi=1.0, h=True, L=10.0), TypeError, "`h`"),
])
def test_a_substrate_spec_has_bounds(kwargs, error, match):
    with pytest.raises(error, match=match):
        SubstrateSpec(**kwargs)


def test_an_unreadable_mesh_file_is_a_value_error_naming_it(tmp_path):
    """meshio's ReadError is not a ValueError: it must not escape."""
    bad = tmp_path / "bad.msh"
    bad.write_text("$MeshFormat\nthis is not gmsh\n")
    with pytest.raises(ValueError, match="bad.msh") as info:
        fem.solve_normal(PUNCH, 400.0, E=E, nu=NU, mesh=bad)
    assert "\n" not in str(info.value)


def test_a_gmsh_failure_is_no_convergence_without_a_temporary_path(monkeypatch):
    def fail(*args, **kwargs):
        raise Exception("Invalid boundary mesh (overlapping facets) on surface 1 in /tmp/x")

    monkeypatch.setattr(gmsh.model.mesh, "generate", fail)
    spec = SubstrateSpec(x_lo=-0.7, x_hi=0.7, h=0.05, L=40.0, growth=0.3)   # not cached
    with pytest.raises(NoConvergenceError, match="gmsh could not mesh the substrate") as info:
        fem.make_substrate(spec)
    assert "threepart-mesh-" not in str(info.value)
    assert not gmsh.isInitialized()


@pytest.mark.parametrize("foreign", [np.linalg.LinAlgError("Singular matrix"),
                                     ZeroDivisionError("float division by zero"),
                                     OverflowError("math range error")])
def test_a_foreign_numerical_error_becomes_no_convergence(monkeypatch, foreign):
    from threepart.fem import solve

    def fail(*args, **kwargs):
        raise foreign

    monkeypatch.setattr(solve, "condense", fail)
    with pytest.raises(NoConvergenceError, match=type(foreign).__name__) as info:
        fem.solve_normal(Punch(1.0, 1.0, 0.25), 0.05, E=1.0, nu=0.3, mesh=REFERENCE_MSH)
    assert not isinstance(info.value, type(foreign)) and "\n" not in str(info.value)


# -- progress: one line per stage on stderr, quiet unless asked (or a terminal) ---------------
def _normal(**kwargs):
    return fem.solve_normal(Punch(1.0, 1.0, 0.25), 0.05, E=1.0, nu=0.3, mesh=REFERENCE_MSH,
                            **kwargs)


def test_progress_prints_one_line_per_stage(capsys):
    _normal(progress=True)
    err = capsys.readouterr().err.splitlines()
    stages = [line.split("fem: ")[1].split(":")[0] for line in err]
    assert stages == ["mesh", "condense", "contact"], err
    assert all(line.rstrip().endswith(" s)") for line in err)   # each stage says its time


def test_progress_is_quiet_by_default_off_a_terminal_and_when_asked(capsys):
    assert not sys.stderr.isatty()           # pytest captures stderr: not a terminal
    _normal()
    _normal(progress=False)
    assert capsys.readouterr().err == ""


def test_progress_goes_to_a_callable():
    lines: list[str] = []
    _normal(progress=lines.append)
    assert [m.split(":")[0] for m in lines] == ["mesh", "condense", "contact"]


def test_partial_slip_reports_each_load_step(capsys):
    lines: list[str] = []
    fem.solve_partial_slip(Punch(1.0, 1.0, 0.25), 0.05, Q=0.01, f=0.5, E=1.0, nu=0.3,
                           mesh=REFERENCE_MSH, steps=3, progress=lines.append)
    steps = [m for m in lines if m.startswith("step ")]
    assert [m.split(",")[0] for m in steps] == ["step 1/3", "step 2/3", "step 3/3"], lines
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("scale", [1e-20, 1e30])
def test_a_contact_gmsh_cannot_mesh_faithfully_is_refused(no_numerics, scale):
    """The same problem scaled by powers of ten: at 1e-20 gmsh's absolute tolerances
    failed it, at 1e30 it answered 3 % off. Refused, naming ``P`` and the range."""
    punch = Punch(R1=10.0 * scale, R2=5.0 * scale, b=scale)
    with pytest.raises(ValueError, match=r"`P` = .* length scale .* outside \[1e-06, 1e\+18\]"):
        fem.solve_normal(punch, 400.0 * scale, E=E, nu=NU, mesh="quick")


def test_nu_minus_one_through_the_shared_entry_point_names_nu(no_numerics):
    """threepart.solve derives the FE modulus 2 (1 - nu^2) / A = 0 from nu = -1: the
    refusal must name `nu` and its range, not the derived `E`."""
    from threepart import solve

    with pytest.raises(ValueError, match=r"`nu` = -1.0 must lie in \(-1, 0.5\)"):
        solve(PUNCH, 400.0, A=8.67e-6, method="fem", nu=-1.0, mesh="quick")

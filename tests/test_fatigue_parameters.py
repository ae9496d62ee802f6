"""The fatigue parameters' table (threepart.fatigue.table) and Crossland's parameter, its one new row.

References: closed forms of Crossland's parameter for uniaxial, shear and
90-degree out-of-phase histories (the deviatoric path a segment or an ellipse,
whose smallest enclosing ball is known), a brute-force smallest enclosing ball
in 50-digit arithmetic (mpmath: every ball through 2, 3 or 4 of the states,
the smallest that holds them all), the identity ``sqrt(J2,a) = σvM(Δσ)/(2√3)``
of two states against the independent von Mises range, and the report's
schema and the command line's labels read against the table's rows.
"""
from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from threepart import fatigue as fat
from threepart.fatigue import table as fp
from threepart.stress import Stress

NU = 0.3
#: the closed forms and the brute force agree with the vectorised code to round-off
ROUNDING = 1e-12
#: a brute-force ball holds a state when it lies within this fraction of the radius (50 digits)
MP_SLACK = mpmath.mpf("1e-30")
#: the random paths' balls exceed the farthest pair's by more than this fraction (Welzl's branch runs)
BEYOND_CHORD = 1e-6


def _history(sxx, szz, sxz, nu=NU):
    """A synthetic history at one point per column: one Stress record per state."""
    sxx, szz, sxz = (np.atleast_2d(np.asarray(a, float).T).T for a in (sxx, szz, sxz))
    n = sxx.shape[1]
    x, z = np.arange(n, dtype=float), np.ones(n)
    return fat.History.from_stresses([Stress(x=x, z=z, sxx=a, szz=b, sxz=c, nu=nu)
                                      for a, b, c in zip(sxx, szz, sxz)])


def test_the_table_names_every_parameter_once_with_its_unit_and_plane():
    """The five parameters of before and Crossland, each with a unit; the critical-plane ones have θ."""
    rows = fp.parameters()
    assert [p.name for p in rows] == ["von_mises_range", "swt", "findley", "ruiz_fdp", "ruiz_ffdp",
                                      "crossland"]
    assert {p.name for p in rows if p.critical_plane} == {"swt", "findley"}
    assert {p.name for p in rows if p.surface} == {"ruiz_ffdp", "ruiz_fdp"}
    assert all(p.unit and p.label and p.short for p in rows)
    h = _history([0.0, 100.0, -30.0], [0.0, -50.0, 10.0], [0.0, 20.0, 5.0])
    for p in rows:
        if not p.surface:
            got = p.function(fp.Inputs(None, h, h, 2e5))   # type: ignore[arg-type]
            assert got.name == p.name and (got.theta is not None) == p.critical_plane


@pytest.mark.parametrize("mean", [0.0, 0.5])
def test_crossland_of_a_uniaxial_history_is_its_closed_form(mean):
    """σxx = S (mean + amplitude sin t), plane strain: √J2,a = S amp √((1 - ν + ν²)/3), σh,max = (1 + ν) σxx,max/3."""
    S, kappa = 100.0, 0.4
    amp = 1.0 - mean
    t = np.linspace(0.0, 2 * math.pi, 41)
    h = _history(S * (mean + amp * np.sin(t)), 0 * t, 0 * t)
    want = S * amp * math.sqrt((1 - NU + NU * NU) / 3) + kappa * (1 + NU) * S * (mean + amp) / 3
    assert fp.crossland(h, kappa=kappa).hot.value == pytest.approx(want, rel=ROUNDING)


def test_crossland_of_alternating_shear_is_the_shear_amplitude():
    """σxz = T sin t (torsion's plane analogue): √J2,a = T and no hydrostatic stress."""
    T = 70.0
    t = np.linspace(0.0, 2 * math.pi, 37)
    assert fp.crossland(_history(0 * t, 0 * t, T * np.sin(t))).hot.value == pytest.approx(T, rel=ROUNDING)


@pytest.mark.parametrize("A, T", [(100.0, 30.0), (100.0, 80.0)])
def test_the_deviatoric_amplitude_of_an_out_of_phase_path_is_its_ellipse_s_semi_major_axis(A, T):
    """σxx = A cos t, σxz = T sin t: the deviatoric path is an ellipse of semi-axes
    A √((1 - ν + ν²)/3) and T, whose smallest enclosing ball is the larger (the longest chord
    would say the same only because both axis ends are states)."""
    t = np.linspace(0.0, 2 * math.pi, 73)
    got = fp.deviatoric_amplitude(_history(A * np.cos(t), 0 * t, T * np.sin(t)))
    assert got[0] == pytest.approx(max(A * math.sqrt((1 - NU + NU * NU) / 3), T), rel=ROUNDING)


def _deviator(sxx, szz, sxz, nu=NU):
    """The state's point y (|y_i - y_j|² = J2(σ_i - σ_j)), in mpmath, from the full deviator."""
    sxx, szz, sxz = (mpmath.mpf(float(v)) for v in (sxx, szz, sxz))
    syy = nu * (sxx + szz)
    p = (sxx + syy + szz) / 3
    s = [sxx - p, syy - p, szz - p]
    # J2 = ½ s:s = ½ (s_xx² + s_yy² + s_zz²) + s_xz²: the Euclidean norm of (s/√2, s_xz)
    return mpmath.matrix([v / mpmath.sqrt(2) for v in s] + [sxz])


def _brute_ball(points):
    """The smallest radius of a ball through 2, 3 or 4 of ``points`` that holds them all (mpmath)."""
    best = None
    for k in (2, 3, 4):
        for R in itertools.combinations(points, k):
            A = mpmath.matrix([list(r - R[0]) for r in R[1:]])
            G = A * A.T
            try:
                lam = mpmath.lu_solve(G, mpmath.matrix([G[i, i] / 2 for i in range(k - 1)]))
            except ZeroDivisionError:
                continue
            c = R[0] + A.T * lam
            r = mpmath.norm(c - R[0])
            if all(mpmath.norm(q - c) <= r * (1 + MP_SLACK) for q in points) and (best is None or r < best):
                best = r
    return best


def test_the_deviatoric_amplitude_of_a_non_proportional_path_is_the_brute_force_ball():
    """Random 7-state paths at 6 points, where the farthest pair's ball misses a state (Welzl's
    branch): the radius equals the smallest of all balls through 2-4 states that hold every state."""
    rng = np.random.default_rng(7)
    sxx, szz, sxz = rng.normal(0.0, 100.0, (3, 7, 6))
    h = _history(sxx, szz, sxz)
    got = fp.deviatoric_amplitude(h)
    chord = np.array([max(float(mpmath.norm(_deviator(*a) - _deviator(*b)))
                          for a, b in itertools.combinations(zip(sxx[:, p], szz[:, p], sxz[:, p]), 2)) / 2
                      for p in range(6)])
    with mpmath.workdps(50):
        want = [float(_brute_ball([_deviator(sxx[i, p], szz[i, p], sxz[i, p]) for i in range(7)]))
                for p in range(6)]
    assert np.any(np.array(want) > chord * (1 + BEYOND_CHORD)), "no point needs more than the farthest pair"
    np.testing.assert_allclose(got, want, rtol=ROUNDING)


def test_two_states_give_half_the_von_mises_range_over_root_3():
    """A 2-state (or proportional) path: √J2,a = σvM(Δσ)/(2√3), the von Mises range's own evaluation."""
    rng = np.random.default_rng(3)
    sxx, szz, sxz = rng.normal(0.0, 100.0, (3, 2, 9))
    h = _history(sxx, szz, sxz)
    np.testing.assert_allclose(fp.deviatoric_amplitude(h),
                               fat.von_mises_range(h).value / (2 * math.sqrt(3)), rtol=ROUNDING)


def test_kappa_out_of_range_is_refused_by_name():
    h = _history([0.0, 1.0], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match=r"^`kappa` = -0\.1 must lie in \[0, 10\]"):
        fp.crossland(h, kappa=-0.1)


def test_the_default_kappa_is_crossland_s_from_the_stated_fatigue_limit_ratio():
    """κ = 3 t-1/f-1 - √3 (torsion equal to bending in Crossland's criterion at the two limits)."""
    assert fp.KAPPA_CROSSLAND == pytest.approx(3 * fp.T_OVER_F_CROSSLAND - math.sqrt(3), rel=ROUNDING)


def test_the_report_schema_names_the_table_s_reported_parameters():
    from threepart.reports.verify import load_schema
    from threepart.reports.verify.stress_section import FATIGUE_NAMES

    schema = load_schema()
    assert schema["$defs"]["fatigue_parameter"]["enum"] == list(fp.reported())
    assert list(FATIGUE_NAMES) == list(fp.reported())
    assert "crossland" in fp.reported() and "ruiz_fdp" not in fp.reported()


def test_an_unknown_constant_is_refused_by_name():
    with pytest.raises(TypeError, match=r"^`kapa` is not a constant of any fatigue parameter"):
        fp.fatigue(None, 0.0, 0.0, E=1.0, kapa=0.3)   # type: ignore[arg-type]


@pytest.fixture
def toy_parameter(monkeypatch):
    """A new parameter as a newcomer adds one: one function and one row, for one test only."""
    from dataclasses import replace

    monkeypatch.setattr(fp, "_TABLE", dict(fp._TABLE))

    def scaled_range(history, *, scale=2.0):
        """The von Mises range times ``scale``: a toy with a constant of its own."""
        vm = fat.von_mises_range(history)
        return replace(vm, name="toy", value=scale * vm.value, hot=replace(vm.hot, value=scale * vm.hot.value))

    fp.register_parameter(fp.FatigueParameter("toy", "toy (scaled range)", "Toy", "MPa",
                                              lambda i, **c: scaled_range(i.history, **c),
                                              constants=("scale",)))
    return fp.parameter("toy")


def test_a_new_row_reaches_the_core_the_command_line_the_report_and_its_schema(toy_parameter, capsys,
                                                                               tmp_path):
    """One function and one row: fatigue() evaluates it, the command line prints it with its unit
    and writes its CSV column, the report tabulates it and its schema admits it; nothing else edited."""
    from threepart.reports.verify import load_schema
    from threepart.reports.verify.stress_section import fatigue_names

    from threepart import Punch, rigid_punch
    from threepart import closedform as cf
    from threepart.cli import main

    normal = cf.solve_normal(Punch(R1=10.0, R2=10.0, b=0.0), 100.0, 0.0, A=rigid_punch(2.1e5, NU) * 2)
    cycle = cf.fretting_cycle(normal, 20.0, 0.5, states=3)
    x, z = np.linspace(-1.0, 1.0, 5)[None, :], np.linspace(0.0, 0.5, 3)[:, None]
    res = fp.fatigue(cycle, x, z, E=2.1e5, scale=3.0)
    assert res.toy.hot.value == pytest.approx(3.0 * res.von_mises_range.hot.value, rel=ROUNDING)
    assert res.constants["scale"] == 3.0
    assert "toy" in fp.reported() and load_schema()["$defs"]["fatigue_parameter"]["enum"][-1] == "toy"
    assert fatigue_names()["toy"] == "Toy"
    csv = tmp_path / "f.csv"
    assert main(["fatigue", "--R1", "10", "--R2", "10", "--b", "0", "--E", "210000", "--nu", "0.3",
                 "--P", "100", "--Q-max", "20", "--f", "0.5", "--nx", "5", "--nz", "3",
                 "--csv", str(csv)]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.strip().startswith("toy (scaled"))
    assert " MPa  at x = " in line
    assert "toy [MPa]" in csv.read_text().splitlines()[0].split(",")


def test_the_fatigue_commands_help_shows_the_tables_default_constants(capsys):
    """`threepart fatigue --help` prints Findley's k and Crossland's kappa from their one home, the
    table (kappa = 3 t-1/f-1 - sqrt(3) at t-1/f-1 = T_OVER_F_CROSSLAND), not a number typed twice."""
    import math

    from threepart.cli import main
    from threepart.fatigue import K_FINDLEY
    from threepart.fatigue.table import T_OVER_F_CROSSLAND

    assert main(["fatigue", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert f"default {3 * T_OVER_F_CROSSLAND - math.sqrt(3):.3g})" in text and f"(default {K_FINDLEY:g})" in text

"""The friction referee: another code's partial slip judged by the verification run's comparison.

The points are an independent reference sampled at nodes (the closed form of Hertz's partial
slip, whose stick zone is Mindlin's c/a = sqrt(1 - Q/fP)); each pitfall is provoked by the one
fault it names, and each limit fails at 3x and passes at 0.3x of itself (as tests/test_compare.py).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import threepart
from threepart import Punch
from threepart.errors import InputError
from threepart.reports.referee import friction, judge, slip_from_points
from threepart.tolerances import tolerance

A = 4 * (1 - 0.3**2) / 210e3          # two similar steel bodies
P, F, RATIO = 400.0, 0.5, 0.4
#: rounding of the closed form's Mindlin c/a and of a linear crossing: a few ulps of 1
ROUNDING = 1e-12
#: issue 38's target for the stick-zone ends, of W
ENDS = 5e-3
#: the recovered shift of a synthetic stick zone, of W: the crossing between nodes of spacing W/400
SHIFT_TOL = 1e-3


@pytest.fixture(scope="module")
def ref():
    return threepart.solve(Punch(R1=10, R2=10, b=0), P, 0.0, A=A, Q=RATIO * F * P, f=F,
                           method="closedform")


def _nodes(ref, n=481, reach=1.2):
    x = np.linspace(-reach * ref.a, reach * ref.c, n)
    return x, ref.pressure(x), ref.shear(x)


def test_the_reference_is_mindlins(ref):
    assert ref.d / ref.a == pytest.approx(math.sqrt(1 - RATIO), rel=ROUNDING)


def test_sampled_reference_passes_and_its_stick_zone_is_mindlins(ref):
    x, p, q = _nodes(ref)
    res = slip_from_points(x, p, q, ref)
    W = ref.a + ref.c
    assert abs(res.d - math.sqrt(1 - RATIO) * ref.a) < ENDS * W
    assert abs(res.e) < ENDS * W
    doc = judge(res, ref, source="sampled")
    failed = [(c["quantity"], c["error"]) for c in doc["checks"] if not c["passed"]]
    assert doc["passed"], (failed, doc["pitfalls"])
    names = {c["quantity"] for c in doc["checks"]}
    assert {"d", "e", "q_interior_max", "q_integral", "q_bound"} <= names


def test_points_that_all_slip_are_refused_by_name(ref):
    x, p, _ = _nodes(ref)
    with pytest.raises(InputError, match="no two points stick"):
        slip_from_points(x, p, F * p, ref)


def test_a_flipped_shear_is_named(ref):
    x, p, q = _nodes(ref)
    doc = judge(slip_from_points(x, p, -q, ref), ref)
    assert [q["name"] for q in doc["pitfalls"]] == ["shear-sign"]
    assert not doc["passed"]


def test_a_shifted_stick_zone_is_named_coupling(ref):
    """q = f p(x) - f p*(x + delta): the stick zone moves by -delta, its width and ∫q stay."""
    x, p, q = _nodes(ref, n=961)
    W = ref.a + ref.c
    delta = 4 * friction.SHIFT * W

    def shifted(xs):
        return F * ref.pressure(xs) - (F * ref.pressure(xs + delta) - ref.shear(xs + delta))

    res = slip_from_points(x, p, shifted(x), ref)
    assert res.e == pytest.approx(ref.e + delta, abs=SHIFT_TOL * W)
    names = [q["name"] for q in judge(res, ref)["pitfalls"]]
    assert "coupling" in names
    small = slip_from_points(x, p, F * p - (F * ref.pressure(x + 0.3 * friction.SHIFT * W)
                                             - ref.shear(x + 0.3 * friction.SHIFT * W)), ref)
    assert "coupling" not in [q["name"] for q in judge(small, ref)["pitfalls"]]


def test_a_stick_zone_that_does_not_slip_is_named(ref):
    """Points that stick everywhere (|q| = f p / 2 scaled to ∫q = Q): nothing slips."""
    x, p, _ = _nodes(ref)
    q = 0.5 * F * p
    res = slip_from_points(x, p, q * ref.Q / np.trapezoid(q, x), ref)
    assert "no-slip" in [q["name"] for q in judge(res, ref)["pitfalls"]]


@pytest.mark.parametrize("factor, named", [(3.0, True), (0.3, False)])
def test_the_stick_slope_is_named_at_three_times_its_limit(ref, factor, named):
    x, p, q = _nodes(ref)
    W = ref.a + ref.c
    K_t = 1.0 / (factor * friction.SLOPE * A * W)       # creep = factor * SLOPE
    pitfalls = judge(slip_from_points(x, p, q, ref), ref, stick_slope=K_t)["pitfalls"]
    assert ("stick-slope" in [q["name"] for q in pitfalls]) is named


@pytest.mark.parametrize("factor, passes", [(3.0, False), (0.3, True)])
def test_the_shear_limit_fails_at_three_times_and_holds_at_a_third(ref, factor, passes):
    x, p, q = _nodes(ref, n=961)
    limit = tolerance("referee", "q_interior_max").limit
    peak = float(np.max(np.abs(q)))
    W = ref.a + ref.c
    bump = factor * limit * peak * np.exp(-((x - 0.1 * W) / (0.02 * W)) ** 2)   # inside the stick zone
    check = {c["quantity"]: c for c in judge(slip_from_points(x, p, q + bump, ref), ref)["checks"]}
    assert check["q_interior_max"]["passed"] is passes


def test_a_non_finite_shear_is_refused_by_name(ref):
    x, p, q = _nodes(ref)
    q[3] = np.nan
    with pytest.raises(InputError, match="non-finite q"):
        slip_from_points(x, p, q, ref)


# --- threepart compare --Q --f: the same judgement at the command line ------------------------------
HERTZ = ["--R1", "10", "--R2", "10", "--b", "0", "--P", str(P), "--E", "210000", "--nu", "0.3"]   # A of the pair


def _csv(path, x, p, q):
    path.write_text("x,p,q\n" + "\n".join(f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in zip(x, p, q)))
    return path


def test_compare_reads_a_getfem_vtus_shear_and_judges_a_partial_slip_by_the_friction_rows(tmp_path, ref):
    """GetFEM's deck writes contact_pressure and contact_shear: `--Q --f` judges that shear without
    `--shear`, and a file of partial slip is judged by the ``referee-friction`` rows (its contact ends
    as a friction model's nodal tractions give them), a pressure alone by the ``referee`` rows."""
    import json

    import meshio

    from threepart.cli import main

    x, p, q = _nodes(ref)
    points = np.array([(xi, y, 0.0) for y in (0.0, -1.0) for xi in x])
    n = len(x)
    cells = np.array([(i, i + 1, n + i + 1, n + i) for i in range(n - 1)])
    top = np.arange(2 * n) < n
    fields = {"contact_pressure": np.where(top, np.tile(p, 2), 0.0), "contact_shear": np.where(top, np.tile(q, 2), 0.0)}
    vtu = tmp_path / "job.vtu"
    meshio.write(vtu, meshio.Mesh(points, [("quad", cells)], point_data=fields))
    for extra, group in (([], "referee"), (["--Q", repr(ref.Q), "--f", repr(F)], "referee-friction")):
        out = tmp_path / group
        assert main(["compare", "--pressure", str(vtu), *HERTZ, *extra, "--out", str(out)]) == 0
        limits = {c["quantity"]: c["limit"] for c in json.loads((out / "report.json").read_text())["checks"]}
        assert limits["a"] == tolerance(group, "a").limit and limits["p_left"] == tolerance(group, "p_left").limit
        assert ("q_integral" in limits) == bool(extra)


@pytest.mark.parametrize("sign, status, line", [(1.0, 0, "PASSED"), (-1.0, 1, "pitfall shear-sign")])
def test_compare_judges_a_partial_slip_from_a_csv(tmp_path, capsys, ref, sign, status, line):
    from threepart.cli import main

    x, p, q = _nodes(ref)
    csv = _csv(tmp_path / "slip.csv", x, p, sign * q)
    argv = ["compare", "--pressure", str(csv), *HERTZ, "--Q", repr(ref.Q), "--f", repr(F),
            "--out", str(tmp_path / "report")]
    assert main(argv) == status
    assert line in capsys.readouterr().out
    assert (tmp_path / "report" / "report.html").is_file()


@pytest.mark.parametrize("extra, match", [
    (["--Q", "80"], "give both `--Q` and `--f`"),
    (["--stick-slope", "1e6"], "judge a partial slip: give `--Q` and `--f` too"),
    (["--Q", "80", "--f", "0.5", "--stick-slope", "-1"], "`--stick-slope`"),
])
def test_compare_refuses_a_half_given_partial_slip(tmp_path, capsys, ref, extra, match):
    from threepart.cli import main

    x, p, q = _nodes(ref)
    csv = _csv(tmp_path / "slip.csv", x, p, q)
    assert main(["compare", "--pressure", str(csv), *HERTZ, *extra, "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and match in err[0], err


def test_compare_of_a_partial_slip_needs_the_files_shear(tmp_path, capsys, ref):
    from threepart.cli import main

    x, p, _ = _nodes(ref)
    csv = tmp_path / "normal.csv"
    csv.write_text("x,p\n" + "\n".join(f"{a:.17g},{b:.17g}" for a, b in zip(x, p)))
    assert main(["compare", "--pressure", str(csv), *HERTZ, "--Q", repr(ref.Q), "--f", repr(F),
                 "--out", str(tmp_path / "r")]) == 2
    assert "carries no shear q" in capsys.readouterr().err


def test_noise_outside_the_contact_does_not_move_the_stick_ends(ref):
    """A code's multiplier leaves p ~ 1e-4 of the peak outside the contact with |q|/(f p) = 0.98
    (GetFEM at W/h = 32): those nodes are not judged, and the ends stay Mindlin's."""
    from threepart.results.fields import stick_ends

    x, p, q = _nodes(ref, n=241)
    clean = stick_ends(x, p, q, F)
    outside = p == 0
    p_noisy = np.where(outside, 1e-4 * p.max(), p)
    q_noisy = np.where(outside, 0.98 * F * p_noisy, q)
    assert stick_ends(x, p_noisy, q_noisy, F) == pytest.approx(clean, abs=ROUNDING)
    W = ref.a + ref.c
    assert np.abs(np.array(clean) - np.array(ref.stick_zone)).max() < ENDS * W


#: a smeared cusp: the shear within this fraction of W of each stick end lowered by SMEAR of its peak
SMEAR_REACH, SMEAR = 0.02, 0.1


def test_the_referee_judges_the_shear_away_from_the_stick_ends_and_the_solvers_next_to_them(ref):
    """A code's nodes smear the shear's cusp at each stick end (CalculiX: 7.8e-2 of the peak there): the
    referee's q_interior_max leaves EDGE_FRACTION W around the stick ends out, the solvers' keeps them."""
    from threepart.reports.compare import EDGE_FRACTION, compare, slip_figures

    x, p, q = _nodes(ref)
    W = ref.a + ref.c
    near = np.any([np.abs(x - end) < SMEAR_REACH * W for end in ref.stick_zone], axis=0)
    q = np.where(near, q - SMEAR * np.max(np.abs(q)) * np.sign(q), q)
    res = slip_from_points(x, p, q, ref)
    assert SMEAR_REACH < EDGE_FRACTION
    kept = slip_figures(ref, res)["q_interior_max"][2]
    away = slip_figures(ref, res, away_from_stick_ends=True)["q_interior_max"][2]
    assert kept >= SMEAR * (1 - ENDS)
    assert away <= tolerance("referee", "q_interior_max").limit
    (check,) = [c for c in compare(ref, res, "referee", stresses=False)
                if c.quantity == "q_interior_max"]
    assert check.error == away and check.passed

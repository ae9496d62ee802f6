"""The matching pad test (issue 32, docs/EDGES.md section 6): threepart.studies.matching.match and `threepart match`.

References, each independent of the code under test:

* Hertz's formulas for the pad: ``a² = 2 A R P/π``, ``p0 = 2P/(πa)``, ``K_N = p0 √(2/a)``
  and the stuck shear's ``K_T = (Q/π ± sigma_bulk a/4)/√(2a)``: the pad's loads give back the
  flank edge's multipliers;
* the flank's own surface σxx (threepart.stress) and fatigue parameters (threepart.fatigue),
  against the pad's, over the slip zone.
"""
from __future__ import annotations

import math
import re

import pytest

from threepart import Punch, similar_pair, solve
from threepart.results import edges as asymptotics
from threepart.studies.matching import match
from threepart.problem.catalogue import get_case
from threepart.errors import FullSlidingError
from threepart.tolerances import tolerance

F = 0.5            # the coefficient of friction (an input, not a limit)
#: the pad's multipliers against the flank's (issue target 1e-6)
MULTIPLIERS = tolerance("match", "multipliers").limit
#: the surface σxx over the slip zone (issue target 5 %)
SXX = tolerance("match", "sxx_slip").limit
#: the fatigue parameters near the edge
FATIGUE = tolerance("match", "fatigue").limit
#: the command line prints 6 significant digits
PRINTED = 1e-5


def _flank(ratio: float = 0.02, sigma: float = 0.0, name: str = "caseA_moment"):
    c = get_case(name).resolved()
    return solve(c.punch, c.P, c.s, A=c.A, Q=ratio * F * c.P, f=F, sigma_bulk=sigma, method="closedform")


def _hertz_edge(A: float, R: float, P: float, Q: float, sigma: float, side: str) -> tuple[float, float]:
    """``(K_N, K_T)`` of a Hertzian pad at an edge, from Hertz's formulas alone."""
    a = math.sqrt(2 * A * R * P / math.pi)
    p0 = 2 * P / (math.pi * a)
    bulk = sigma * a / 4 if side == "left" else -sigma * a / 4
    return p0 * math.sqrt(2 / a), (Q / math.pi + bulk) / math.sqrt(2 * a)


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("size", [{"R": 10.0}, {"P": 5000.0}, {}])
@pytest.mark.parametrize("sigma", [0.0, 20.0])
def test_pad_reproduces_the_edge(side, size, sigma):
    flank = _flank(sigma=sigma)
    m = match(flank, side, **size, fatigue=False)
    target = flank.edges()[("left", "right").index(side)]
    K_N, K_T = _hertz_edge(m.A, m.R, m.P, m.Q, m.sigma_bulk, side)
    assert K_N == pytest.approx(target.K_N, rel=MULTIPLIERS)
    assert K_T == pytest.approx(target.K_T, rel=MULTIPLIERS)
    assert m.pad.slip_zone == pytest.approx(target.slip_zone, rel=MULTIPLIERS)
    assert m.sigma_bulk == flank.sigma_bulk and m.f == flank.f and m.punch.b == 0.0
    for key, value in size.items():
        assert getattr(m, key) == value


@pytest.mark.parametrize("side", ["left", "right"])
def test_surface_stress_and_fatigue_agree(side):
    """The pad of best σxx (neither R nor P): σxx within 5 % over the slip zone, the fatigue parameters
    within 1 %."""
    m = match(_flank(0.05), side)
    assert m.sxx_error <= SXX, f"{side}: {m.sxx_error:.3e}"
    for name, (flank, pad) in m.fatigue.items():
        assert abs(pad - flank) <= FATIGUE * abs(flank), f"{name}: {flank:.6g} against {pad:.6g}"


def test_surface_stress_agreement_falls_with_the_slip_zone():
    """With R fixed the match is first order: σxx's disagreement shrinks with Q/fP, within 5 % at 0.02."""
    errors = [match(_flank(ratio), "left", R=50.0, fatigue=False).sxx_error
              for ratio in (0.05, 0.02, 0.005)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[1] <= SXX


def test_refusals():
    flank = _flank()
    with pytest.raises(TypeError, match="`flank_result` must be a partial-slip result"):
        match(flank.normal, "left", R=50.0)
    with pytest.raises(ValueError, match="`edge` = 'middle' must be 'left' or 'right'"):
        match(flank, "middle", R=50.0)
    with pytest.raises(ValueError, match="give at most one of `R`"):
        match(flank, "left", R=50.0, P=100.0)
    with pytest.raises(ValueError, match="`R` = -1.0 must be > 0"):
        match(flank, "left", R=-1.0)
    with pytest.raises(FullSlidingError, match="the pad of `R` = 1 would need"):
        match(_flank(0.2), "left", R=1.0)


# --- the command line ---------------------------------------------------------------------------
FLANK = ["--R1", "10", "--R2", "5", "--b", "1", "--E", "210000", "--nu", "0.3", "--P", "400", "--s", "0.1",
         "--Q", "8", "--f", "0.5"]


def test_command_line(capsys):
    from threepart.cli import main
    assert main(["match", *FLANK, "--edge", "left", "--pad-R", "10", "--no-fatigue"]) == 0
    out = capsys.readouterr().out
    flank = solve(Punch(10.0, 5.0, 1.0), 400.0, 0.1, A=similar_pair(210e3, 0.3), Q=8.0, f=F)
    K_N = flank.edges()[0].K_N
    line = next(s for s in out.splitlines() if s.strip().startswith("K_N"))
    flank_K_N, pad_K_N = (float(v) for v in line.split()[1:3])
    assert flank_K_N == pytest.approx(K_N, rel=PRINTED) and pad_K_N == pytest.approx(K_N, rel=PRINTED)
    assert "pad: Punch(R1=R2=10, b=0)" in out


@pytest.mark.parametrize("extra, match", [
    (["--edge", "left", "--pad-R", "10", "--pad-P", "5"], r"give `--pad-R` or `--pad-P`"),
    (["--edge", "left", "--pad-R", "-1"], r"`--pad-R` = -1.0 must be > 0"),
    (["--edge", "left", "--pad-R", "0.5"], r"the pad of `R` = 0.5 would need \|Q\|"),
    (["--edge", "left", "--case", "hertz"], r"give `--case` or the punch, material and loads, not both"),
    (["--edge", "middle"], r"argument --edge: invalid choice"),
])
def test_bad_input_is_one_line_and_exit_status_2(capsys, extra, match):
    from threepart.cli import main
    assert main(["match", *FLANK, *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and re.search(match, err), err


@pytest.mark.parametrize("argv, match", [
    (["--case", "nowhere", "--edge", "left"], r"`--case` = 'nowhere' is not in the catalogue"),
    (["--case", "hertz", "--edge", "left"], r"case 'hertz' has no partial-slip load"),
    (["--R1", "10", "--R2", "5", "--b", "1", "--A", "1e-5", "--P", "400", "--Q", "300", "--f", "0.5",
      "--edge", "left"], r"\|`Q`\| = 300"),
    (["--R1", "10", "--R2", "5", "--b", "1", "--P", "400", "--Q", "8", "--f", "0.5", "--edge", "left"],
     r"the material needs `--A`, or both `--E` and `--nu`"),
])
def test_bad_problem_is_one_line_and_exit_status_2(capsys, argv, match):
    from threepart.cli import main
    assert main(["match", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and re.search(match, err), err


#: an edge is in its asymptotic regime when its exact slip zone is within this factor of the
#: asymptotic 2|K_T|/(f K_N) (docs/EDGES.md): first-order matching holds there; past it (the
#: bulk-loaded Ti-on-Ti flank's right edge: the bulk stress cancels 95 % of K_T and the exact slip zone
#: is 2.8x the asymptotic one) no pad of the two edge multipliers can reproduce the flank's σxx
ASYMPTOTIC_REGIME = 1.5


@pytest.mark.parametrize("name", ["fan_blade_flank_bulk", "slip_Q0.4"])
def test_the_default_pad_is_the_one_of_least_surface_stress_error(name):
    """Neither R nor P: the pad's radius is searched for the least σxx error over the slip zone, so it
    does no worse than the pad as wide as the flank (R = √W/(A K_N), which the search includes), and
    still reproduces the edge's K_N, K_T and slip zone (Hertz's formulas). Where the edge is in its
    asymptotic regime (its exact slip zone within ASYMPTOTIC_REGIME of Mindlin's 2|K_T|/(f K_N)), σxx
    is within sxx_bulk of the flank's; at least one edge of each flank is."""
    c = get_case(name).resolved()
    flank = solve(c.punch, c.P, c.s, A=c.A, Q=c.Q, f=c.f, sigma_bulk=c.sigma_bulk, method="closedform")
    judged = 0
    for k, side in enumerate(("left", "right")):
        target = flank.edges()[k]
        wide = match(flank, side, R=math.sqrt(flank.normal.width) / (flank.normal.A * target.K_N),
                                 fatigue=False)
        best = match(flank, side, fatigue=False)
        assert best.sxx_error <= wide.sxx_error
        ratio = asymptotics.exact_slip(flank, k) / asymptotics.slip_zone(target.K_T, target.K_N, c.f)
        if ratio <= ASYMPTOTIC_REGIME:
            judged += 1
            assert best.sxx_error <= tolerance("match", "sxx_bulk").limit, (side, best.sxx_error)
        K_N, K_T = _hertz_edge(best.A, best.R, best.P, best.Q, best.sigma_bulk, side)
        assert K_N == pytest.approx(target.K_N, rel=MULTIPLIERS)
        assert K_T == pytest.approx(target.K_T, rel=MULTIPLIERS)
    assert judged >= 1


# --- a flank with no slip zone to match (issue 37 section 4: Q = 0 gave sxx_error NaN) -------------
#: a shear load so small that the slip zone is below tolerance("match", "slip_zone_min") of W: Mindlin's
#: slip zone 2|K_T|/(f K_N) of caseA_moment at Q = 1e-12 is about 4e-16 W
TINY_Q = 1e-12


@pytest.mark.parametrize("Q", [0.0, TINY_Q])
@pytest.mark.parametrize("size", [{"R": 10.0}, {}])
def test_a_flank_without_a_slip_zone_is_refused_by_name_never_nan(Q, size):
    """Q = 0 leaves each edge stuck (K_T = 0, Hertz's and Mindlin's slip zone 0): nothing to match.
    The asymptotic slip zone, 2|K_T|/(f K_N), confirms the premise independently of match."""
    c = get_case("caseA_moment").resolved()
    flank = solve(c.punch, 400.0, 0.1, A=similar_pair(210e3, 0.3), Q=Q, f=F, method="closedform")
    for k, side in enumerate(("left", "right")):
        e = flank.edges()[k]
        assert 2 * abs(e.K_T) / (F * e.K_N) <= tolerance("match", "slip_zone_min").limit * flank.normal.width
        with pytest.raises(ValueError, match=f"`flank_result` has no slip zone to match at its {side} edge"):
            match(flank, side, **size, fatigue=False)


def test_the_command_line_refuses_a_flank_without_shear_with_one_line(capsys):
    from threepart.cli import main
    argv = [a if a != "8" else "0" for a in FLANK]          # --Q 0
    assert main(["match", *argv, "--edge", "left", "--pad-R", "10", "--no-fatigue"]) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and "nan" not in cap.err
    assert re.fullmatch(r"threepart match: error: `flank_result` has no slip zone to match at its left "
                        r"edge: .*\n", cap.err), cap.err

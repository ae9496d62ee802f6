"""The SIE on any profile and the fretting-wear march (issue 39; sie/profile.py, sie/wear.py).

Each check has an independent reference: the punch's own SIE (a zero depth),
another punch (a quadratic depth is a smaller radius), quadrature of the
pressure (equilibrium), the closed-form worn limit (unbounded ends, eq. W3),
the closed-form fretting cycle (an unworn profile), the loop's area against
the friction work (two routes to the energy, eq. W15), and the worn limit's
invariants (the stick zone of a symmetric contact does not move).
"""
from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import threepart
from threepart import Punch
from threepart.closedform import fretting_cycle as cf_fretting, solve_normal as cf_normal, wear_limit
from threepart.errors import InputError, InputTypeError, ReaderError
from threepart.fretting_wear import WearResult
from threepart.sie import solve_normal as sie_normal
from threepart.sie.profile import WornProfile, solve_profile
from threepart.sie.wear import profile_fretting_cycle, solve_profile_slip, wear_rate
from threepart.reports.verify.wear_section import rise_above_floor
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3
P, F = 400.0, 0.5
HERTZ = Punch(R1=10, R2=10, b=0)
ISSUE = Punch(R1=10, R2=5, b=1)
#: a march short enough for the default run: Hertz, Q_max = f P/2, 300 nodes, 1024 terms
SHORT: dict[str, Any] = dict(k=1e-5, cycles=60, points=300, n=1024)
#: rounding of a few operations on the same numbers
ROUNDING = tolerance("wear-limit", "round_off").limit


def _flat(punch: Punch) -> WornProfile:
    x = np.linspace(-2.0, 2.0, 11)
    return WornProfile(punch, x, np.zeros_like(x))


def _peak_error(p, ref, x) -> float:
    return float(np.max(np.abs(p(x) - ref(x))) / np.max(ref(x)))


@pytest.fixture(scope="module")
def short_march() -> WearResult:
    return threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, law="energy", **SHORT)


@pytest.mark.parametrize("punch, s", [(HERTZ, 0.0), (ISSUE, 0.1)])
def test_a_zero_depth_is_the_punch(punch, s):
    ref = sie_normal(punch, P, s, A=A)
    res = solve_profile(_flat(punch), P, s, A=A)
    tol = tolerance("wear", "zero_depth").limit
    W = ref.a + ref.c
    assert abs(res.a - ref.a) <= tol * W and abs(res.c - ref.c) <= tol * W
    assert abs(res.alpha - ref.alpha) <= tol * W / punch.R1       # of the slope scale over the contact
    x = np.linspace(-ref.a, ref.c, 2001)[1:-1]
    assert _peak_error(res.pressure, ref.pressure, x) <= tol


@pytest.mark.parametrize("kind", ["pchip", "linear"])
def test_a_quadratic_depth_is_a_smaller_radius(kind):
    """w = x^2/(2R') on a Hertz punch of radius R is Hertz of 1/R + 1/R' (knots every 1e-3 mm)."""
    x = np.linspace(-2.0, 2.0, 4001)
    res = solve_profile(WornProfile(HERTZ, x, x * x / 20.0, kind), P, 0.05, A=A)
    ref = sie_normal(Punch(R1=5, R2=5, b=0), P, 0.05, A=A)
    W = ref.a + ref.c
    assert max(abs(res.a - ref.a), abs(res.c - ref.c)) <= tolerance("wear", "profile_ends").limit * W
    xs = np.linspace(-ref.a, ref.c, 2001)[20:-20]
    assert _peak_error(res.pressure, ref.pressure, xs) <= tolerance("wear", "profile_pressure").limit


def test_a_worn_profile_carries_its_load_and_moment():
    """∫p = P and ∫x p = P s by quadrature of the pressure function, for a scar of depth ~ (|x| - 0.1)^(3/2)."""
    x = np.linspace(-0.4, 0.4, 401)
    w = 2e-4 * np.clip(np.abs(x) - 0.1, 0, None) ** 1.5 / 0.1 ** 1.5
    res = solve_profile(WornProfile(HERTZ, x, w), P, 0.02, A=A)
    m, h = 0.5 * (res.c - res.a), 0.5 * (res.a + res.c)

    theta = (np.arange(8192) + 0.5) * np.pi / 8192       # the midpoint rule in θ: exact for the sine series
    xs = m + h * np.cos(theta)
    weight = res.pressure(xs) * h * np.sin(theta) * np.pi / 8192

    def integral(g) -> float:
        return float(np.sum(g(xs) * weight))

    load, moment = integral(lambda t: 1.0), integral(lambda t: t)
    tol = tolerance("wear", "equilibrium").limit
    assert abs(load - P) <= tol * P
    assert abs(moment - P * 0.02) <= tol * P * (res.a + res.c)
    assert res.a + res.c > 0 and res.info["least"] >= -tolerance("answer", "p_min").limit


@pytest.mark.parametrize("punch, s, rule", [(HERTZ, 0.0, "pinned"), (HERTZ, 0.1, "pinned"),
                                            (ISSUE, 0.1, "held"), (ISSUE, 0.1, "pinned"),
                                            (ISSUE, 0.1, "consistent")])
def test_unbounded_ends_give_the_closed_form_worn_limit(punch, s, rule):
    """Eq. W3 by the SIE on the limit's stick zone: the pressure, the tilt (W6) and the ends' K (W10)."""
    normal = cf_normal(punch, P, s, A=A)
    limit = wear_limit(normal, 0.4 * F * P, F, stick=rule)
    res = solve_profile(_flat(punch), P, s, A=A, ends="unbounded", contact=limit.stick_zone)
    x1, x2 = limit.stick_zone
    xs = np.linspace(x1, x2, 2001)[100:-100]
    tol = tolerance("wear", "unbounded").limit
    assert np.max(np.abs(res.pressure(xs) - limit.pressure(xs))) <= tol * np.max(normal.pressure(xs))
    assert abs(res.alpha - limit.alpha) <= tol * (x2 - x1) / min(punch.R1, punch.R2)
    assert np.allclose(res.info["K"], limit.K, rtol=tol, atol=0)
    with pytest.raises(InputError, match="info\\['K'\\]"):
        res.edges()


def test_unworn_fretting_is_the_closed_form():
    """The fretting cycle on a zero depth: the loop's energy and the friction work (eq. W15's two routes)."""
    Q = 0.5 * F * P
    res = profile_fretting_cycle(solve_profile(_flat(HERTZ), P, 0.0, A=A), Q, F)
    ref = cf_fretting(cf_normal(HERTZ, P, 0.0, A=A), Q, F)
    tol = tolerance("wear", "unworn_energy").limit
    assert abs(res.energy - ref.energy) <= tol * ref.energy
    assert abs(res.info["friction_work"] - ref.energy) <= tol * ref.energy
    slip = solve_profile_slip(res.normal, Q, F)
    assert np.allclose(slip.stick_zone, ref.stick[len(ref.stick) // 3 - 1], rtol=0, atol=tol)


def test_a_symmetric_contact_keeps_its_stick_zone(short_march):
    """Hertz: wear removes material only outside the stick zone, which does not move (docs/WEAR.md §1)."""
    W = short_march.contacts[0, 1] - short_march.contacts[0, 0]
    drift = np.max(np.abs(short_march.stick_zones - short_march.stick_zones[0]))
    assert drift <= tolerance("wear", "stick_zone").limit * W
    assert short_march.volume > 0 and short_march.cycles[-1] == SHORT["cycles"]
    assert np.all(np.diff(short_march.cycles) > 0)
    x1, x2 = short_march.stick_zones[0]
    inner = (short_march.x > x1) & (short_march.x < x2)
    assert np.all(short_march.depths[-1][inner] == 0.0)


def test_worn_volume_per_cycle_is_k_times_the_loop_energy(short_march):
    """Eq. W15 under the energy law: ΔV/ΔN = k W, W the loop's area (ln h/h*) of the worn state."""
    r = short_march
    j = len(r.cycles) - 2
    dV = (r.volumes[j + 1] - r.volumes[j]) / (r.cycles[j + 1] - r.cycles[j])
    normal = solve_profile(WornProfile(HERTZ, r.x, r.depths[j]), P, 0.0, A=A, n=SHORT["n"])
    loop = profile_fretting_cycle(normal, r.Q_max, r.f)
    assert abs(dV - SHORT["k"] * loop.energy) <= tolerance("wear", "identity").limit * SHORT["k"] * loop.energy
    # the loop and the friction work of the march agree on the worn profile too
    assert abs(loop.energy - r.energy[j]) <= tolerance("wear", "energy_routes").limit * loop.energy
    # ... and both say that early wear raises the energy per cycle above the unworn closed form's:
    # the punch approaches, the contact and its slip zones grow (measured +10 % at k N = 6e-4)
    unworn = cf_fretting(cf_normal(HERTZ, P, 0.0, A=A), r.Q_max, r.f).energy
    assert min(loop.energy, r.energy[j]) > unworn and r.contacts[-1, 1] > r.contacts[0, 1]


def test_archard_is_the_energy_law_with_k_over_f():
    """Docs/WEAR.md §5: slip only where |q| = f p, so Archard's k_A is the energy law's k_A/f."""
    Q = 0.5 * F * P
    a = threepart.wear(HERTZ, P, 0.0, Q, F, A=A, law="archard", k=1e-5, cycles=4, jump=2, points=101, n=512)
    e = threepart.wear(HERTZ, P, 0.0, Q, F, A=A, law="energy", k=1e-5 / F, cycles=4, jump=2, points=101, n=512)
    assert np.allclose(a.depths, e.depths, rtol=ROUNDING, atol=0)


def test_cycle_jumping_agrees_with_every_cycle():
    """The step control (depth per jump, Euler's stability bound) against the march one cycle at a time."""
    kw = dict(A=A, k=1e-5, cycles=40, points=151, n=1024)
    auto = threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, **kw)
    each = threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, jump=1, **kw)
    assert auto.info["steps"] < each.info["steps"] == kw["cycles"]
    tol = tolerance("wear", "jump").limit
    assert np.max(np.abs(auto.depths[-1] - each.depths[-1])) <= tol * np.max(each.depths[-1])
    assert abs(auto.energy[-1] - each.energy[-1]) <= tol * each.energy[-1]


def test_the_wear_rate_vanishes_over_the_stick_zone():
    normal = solve_profile(_flat(HERTZ), P, 0.0, A=A, n=512)
    x = np.linspace(-0.3, 0.3, 301)
    rate, work, (lo, hi), travel = wear_rate(normal, 0.5 * F * P, F, x)
    assert np.all(rate[(x > lo) & (x < hi)] == 0) and np.all(rate >= 0) and work > 0
    assert np.all(rate[(x <= -normal.a) | (x >= normal.c)] == 0)


def test_a_measured_profile_from_a_file(tmp_path):
    x = np.linspace(-0.5, 0.5, 51)
    w = 1e-4 * np.clip(np.abs(x) - 0.2, 0, None)
    path = tmp_path / "scar.csv"
    path.write_text("x,h\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(x, HERTZ.profile(x) + w)))
    prof = WornProfile.from_csv(path, HERTZ, kind="linear")
    assert np.allclose(prof.depth(x), w, rtol=0, atol=ROUNDING * np.max(HERTZ.profile(x)))
    bad = tmp_path / "bad.csv"
    bad.write_text("x,h\n0,1\n1,nan\n")
    with pytest.raises(ReaderError, match="bad.csv"):
        WornProfile.from_csv(bad, HERTZ)


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(law="gravity"), InputError, "`law`"),
    (dict(Q_max=F * P), InputError, "`Q_max`"),
    (dict(cycles=-1), InputError, "`cycles`"),
    (dict(cycles=1.5), InputTypeError, "`cycles`"),
    (dict(jump=0), InputError, "`jump`"),
    (dict(method="nonesuch"), InputError, "`method`"),
    (dict(k=0.0), InputError, "`k`"),
    (dict(points=3), InputError, r"`points` = 3 must lie in \[50, 5000\]"),
    (dict(points=2.5), InputTypeError, "`points`"),
    (dict(bogus=1), InputTypeError, r"`bogus` is not an option of method 'sie'.*its options: n, points"),
    (dict(method="fem", E=210e3, nu=0.3, mesh="quick"), InputTypeError, "`mesh` must be a fem MeshPreset"),
])
def test_wear_refuses_bad_input_by_name(kwargs, error, match):
    args = dict(punch=HERTZ, P=P, s=0.0, Q_max=0.5 * F * P, f=F, A=A, k=1e-5, cycles=1)
    args.update(kwargs)
    with pytest.raises(error, match=match):
        threepart.wear(**args)


def test_profile_refusals():
    x = np.linspace(-1, 1, 5)
    with pytest.raises(InputError, match="`kind`"):
        WornProfile(HERTZ, x, 0 * x, kind="bezier")
    with pytest.raises(InputError, match="`x`"):
        WornProfile(HERTZ, x[::-1], 0 * x)
    with pytest.raises(InputError, match="`contact`"):
        solve_profile(_flat(HERTZ), P, 0.0, A=A, ends="unbounded")
    with pytest.raises(InputError, match="`ends`"):
        solve_profile(_flat(HERTZ), P, 0.0, A=A, ends="open")


#: cycles of the slow march at Archard's k = 1e-5 (dose k N = 1.2e-2; the energy peaks at N = 66)
LONG_CYCLES = 1200
#: the energy per cycle peaks within this share of the slow march's cycles (measured 66 of 1200)
PEAK_SHARE = 0.1


@pytest.fixture(scope="module")
def long_march() -> WearResult:
    return threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, k=1e-5, cycles=LONG_CYCLES, points=200, n=1024)


def _distances(r: WearResult) -> np.ndarray:
    """L2 distance of each recorded state's nodal pressures to eq. W11, over the stick zone less 10 % at each end."""
    limit = wear_limit(cf_normal(HERTZ, P, 0.0, A=A), r.Q_max, r.f)
    x1, x2 = limit.stick_zone
    inner = (r.x > x1 + 0.1 * (x2 - x1)) & (r.x < x2 - 0.1 * (x2 - x1))
    ref = limit.pressure(r.x[inner])
    return np.sqrt(np.mean((r.pressures[:, inner] - ref) ** 2, axis=1) / np.mean(ref ** 2))


@pytest.mark.slow
def test_the_march_approaches_the_worn_limit(long_march):
    """Hertz, Q_max = f P/2: the pressure tends to eq. W11 over the stick zone, monotonically to the nodes' floor;
    the stick zone stays."""
    r = long_march
    assert not r.info["stopped"] and r.cycles[-1] == LONG_CYCLES
    dist = _distances(r)
    assert dist[-1] <= tolerance("wear", "limit_L2").limit, dist
    # it falls at every record to the nodes' floor: no rise ends above its last value
    assert rise_above_floor(dist) <= tolerance("wear", "limit_monotone").limit, dist
    W = r.contacts[0, 1] - r.contacts[0, 0]
    assert np.max(np.abs(r.stick_zones - r.stick_zones[0])) <= tolerance("wear", "stick_zone").limit * W


@pytest.mark.slow
def test_the_energy_falls_monotonically_below_5_percent(long_march):
    """Past its early peak (the punch approaches, the slip zones grow) the energy per cycle falls to below 5 %.

    It falls at every record but where a node joins the contact at its outer edge
    (``("wear", "energy_monotone")``); eq. W14 says it tends to 0.
    """
    r = long_march
    peak = int(np.argmax(r.energy))
    assert 0 < r.cycles[peak] < PEAK_SHARE * LONG_CYCLES
    assert np.max(np.diff(r.energy[peak:])) <= tolerance("wear", "energy_monotone").limit * r.energy[peak]
    assert r.energy[-1] <= tolerance("wear", "energy_left").limit * r.energy[0]


def test_a_step_that_cannot_be_solved_ends_the_march_with_its_records(monkeypatch):
    """A step's contact not found (a named error) ends the march early, says why, and keeps the states solved."""
    import threepart.sie.wear as sw
    from threepart.errors import NoConvergenceError

    calls = {"n": 0}
    real = sw.node_state

    def failing(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] > 4:     # the unworn state on uniform nodes that grades the grid, then cycles 0, 1, 2
            raise NoConvergenceError("contact active set did not settle (stand-in)")
        return real(*args, **kwargs)

    monkeypatch.setattr(sw, "node_state", failing)
    r = threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, k=1e-5, cycles=10, jump=1, points=101, n=512)
    assert list(r.cycles) == [0, 1, 2] and r.info["requested"] == 10
    assert "at cycle 3" in r.info["stopped"] and "stand-in" in r.info["stopped"]
    assert r.depths.shape == (3, r.x.size) and r.pressures.shape == (3, r.x.size)
    # the first step's failure is the caller's: nothing was recorded
    calls["n"] = 4
    with pytest.raises(NoConvergenceError, match="stand-in"):
        threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, k=1e-5, cycles=10, jump=1, points=101, n=512)


@pytest.fixture(scope="module")
def fem_pair() -> tuple[WearResult, WearResult]:
    """Hertz, Archard k = 1e-5, 60 cycles one at a time: the SIE's nodes and the FEM's two bodies (E, nu)."""
    E, nu = 210e3, 0.3
    kw = dict(law="archard", k=1e-5, cycles=60, jump=1)
    sie = threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, **kw)
    fem = threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, method="fem", E=E, nu=nu, **kw)
    return sie, fem


def test_the_fem_march_wears_as_the_sie(fem_pair):
    """Issue 39: the FEM's worn depth (its own slip at Q_max, Masing) within 3 % of the SIE's largest depth."""
    sie, fem = fem_pair
    assert list(fem.cycles) == list(sie.cycles)
    top = np.max(sie.depths[-1])
    assert np.max(np.abs(np.interp(fem.x, sie.x, sie.depths[-1]) - fem.depths[-1])) <= \
        tolerance("wear", "fem_depth").limit * top
    W = fem.contacts[0, 1] - fem.contacts[0, 0]
    assert np.max(np.abs(fem.stick_zones - fem.stick_zones[0])) <= tolerance("wear", "fem_stick_zone").limit * W
    # both say the energy per cycle first rises: the punch approaches, the slip zones grow
    assert fem.energy[-1] > fem.energy[0] and sie.energy[-1] > sie.energy[0]
    # the last worn state's fretting cycle: the FEM's stepped cycle on its worn gap against the SIE's nodes
    assert abs(fem.final.energy - sie.final.energy) <= tolerance("fem-quick", "energy").limit * sie.final.energy


def test_the_fem_march_needs_the_pair():
    with pytest.raises(InputError, match="`E` and `nu`"):
        threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=A, k=1e-5, cycles=1, method="fem")
    with pytest.raises(InputError, match="`A`"):
        threepart.wear(HERTZ, P, 0.0, 0.5 * F * P, F, A=2 * A, k=1e-5, cycles=1, method="fem", E=210e3, nu=0.3)


def test_the_final_cycle_of_an_unworn_march_is_the_closed_forms():
    """WearResult.final on the nodes (sie/nodes.py) at N = 0: the closed-form fretting cycle (Masing, Ciavarella–Jäger).

    The energy (the friction work) and the loop's area (delta of the corrective contacts' approaches)
    are two routes to it; the stick zone at Q_max lies within the nodes' spacing; the shear on the loading and
    unloading branches, away from the stick zones' ends.
    """
    Q = 0.5 * F * P
    r = threepart.wear(HERTZ, P, 0.0, Q, F, A=A, law="energy", k=1e-5, cycles=0)
    cycle = r.final
    ref = cf_fretting(cf_normal(HERTZ, P, 0.0, A=A), Q, F)
    tol = tolerance("wear", "nodes_cycle").limit
    assert abs(cycle.energy - ref.energy) <= tol * ref.energy
    q_loop, d_loop = cycle.loop()
    back = cycle.branch != "loading"
    assert abs(abs(np.trapezoid(d_loop[back], q_loop[back])) - ref.energy) <= tol * ref.energy
    k = len(cycle.stick) // 3 - 1
    spacing = np.interp(ref.stick[k], r.x[1:], np.diff(r.x))      # the nodes' spacing at each end
    assert np.all(np.abs(np.asarray(cycle.stick[k]) - ref.stick[k]) <= spacing)
    x = np.linspace(-0.12, 0.12, 13)
    scale = F * float(ref.normal.pressure(np.zeros(1))[0])
    for Qv, branch in ((Q, "loading"), (0.0, "unloading")):
        assert np.max(np.abs(cycle.shear(x, Qv, branch) - ref.shear(x, Qv, branch))) <= tol * scale
    with pytest.raises(InputError, match="edges"):
        cycle.edges()


#: the three-part punch, symmetric: the flank's loads (docs/WEAR.md) on R1 = R2 = 50 mm, b = 1 mm, s = 0
SYMMETRIC = Punch(R1=50, R2=50, b=1.0)


def test_the_three_part_march_reaches_the_closed_form_limit():
    """Issue 39's target: the SIE's long-run pressure on the three-part punch equals the closed-form worn
    limit (eq. W3, on the unworn corrective contact's stick zone: no moment, so no placement to choose,
    docs/WEAR.md section 3) within ``("wear", "limit_p0")`` of the unworn peak, over the stick zone less
    10 % at each end; the stick zone does not move (``("wear", "stick_zone")`` of W)."""
    A_ti, P_f, f = 3.1220869565217394e-05, 1500.0, 0.8
    Q = 0.4 * f * P_f
    r = threepart.wear(SYMMETRIC, P_f, 0.0, Q, f, A=A_ti, law="archard", k=1e-8, cycles=1_500_000)
    assert not r.info["stopped"]
    limit = wear_limit(cf_normal(SYMMETRIC, P_f, 0.0, A=A_ti), Q, f)
    x1, x2 = limit.stick_zone
    W = r.contacts[0, 1] - r.contacts[0, 0]
    assert np.max(np.abs(r.stick_zones - np.array([x1, x2]))) <= tolerance("wear", "stick_zone").limit * W
    inner = (r.x > x1 + 0.1 * (x2 - x1)) & (r.x < x2 - 0.1 * (x2 - x1))
    gap = np.max(np.abs(r.pressures[-1][inner] - limit.pressure(r.x[inner])))
    assert gap <= tolerance("wear", "limit_p0").limit * np.max(r.pressures[0])

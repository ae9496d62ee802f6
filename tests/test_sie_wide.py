"""Wide random draws: the SIE against the closed form on radii from 0.03 b to 1000 b (issue 29).

Each draw is a punch (``R1``, ``R2`` log-uniform over ``[0.03 b, 1000 b]``, a flat,
convex or concave centre), a compliance (a rigid punch on steel, or two steel
bodies), a load from just above the closed form's least load (or, for a flat
centre, the load that spreads a Hertz contact of ``R1`` over the central segment) to
1e4 times it, a lever arm across the lift-off range or a suppressed tilt, and for
partial slip a shear ratio, a friction coefficient and a bulk stress. Where the
closed form answers, the SIE must answer too and agree; where the SIE reports a
stick zone outside the paper's framework (``within_paper``) or refuses a slip
reversal, the closed form must refuse by name; ``NoConvergenceError`` is never an
answer. Before issue 29 the SIE's pressure was 4.8e-4 of the peak off next to
a sharp edge's join, and fretting cycles under a bulk stress raised
``NoConvergenceError`` or took minutes.

The default suite draws a few hundred cases from fixed seeds; the ``slow``
tests (``pytest -m slow``) draw five times as many from other seeds.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import Punch, closedform as cf, rigid_punch, sie, solve
from threepart.errors import StickSeparationError, StickZoneError, SlipReversalError
from threepart.tolerances import tolerance

#: pointwise comparisons stay this fraction of W inside the ends, where the square root makes
#: p ill-conditioned (a rounding of an end moves p by ~sqrt(eps) of the peak)
END_MARGIN = 1e-6
#: the field's limit: pressure of its peak, shear of f times the peak
FIELD = tolerance("sie-target", "field").limit
#: stick-zone ends of the two methods, of W
ZONE = tolerance("sie", "d").limit
#: friction work of a fretting cycle under a bulk stress (measured <= 3.5e-10 over 240 draws)
ENERGY = tolerance("sie-target", "bulk_energy").limit
STEEL = rigid_punch(210e3, 0.3)
#: (draws, seed) of each default test and of its slow counterpart
NORMAL_DRAWS, SLIP_DRAWS, CYCLE_DRAWS = 300, 100, 40
SLOW_FACTOR = 5


def draw(rng: np.random.Generator) -> dict:
    """One random case (see the module docstring)."""
    R1, R2 = 10 ** rng.uniform(math.log10(0.03), 3.0, 2)
    kind = rng.choice(["flat", "flat", "convex", "concave"])
    big = max(R1, R2)
    R = {"flat": math.inf, "convex": 10 ** rng.uniform(1, 2) * big,
         "concave": -10 ** rng.uniform(1.5, 2.5) * big}[kind]
    punch = Punch(R1=R1, R2=R2, b=1.0, R=R)
    A = STEEL * rng.choice([1.0, 2.0])
    P0 = cf.normal.P_min(punch, A)
    P = (P0 if P0 > 0 else math.pi * punch.b ** 2 / (2 * A * punch.R1)) * 10 ** rng.uniform(
        math.log10(1.001), 4.0)
    return dict(punch=punch, A=A, P=P, s_frac=rng.uniform(0.02, 0.98),
                tilt=rng.choice(["free", "free", "suppressed"]),
                ratio=rng.uniform(0.02, 0.95) * rng.choice([-1.0, 1.0]), f=rng.uniform(0.1, 1.0),
                bulk_frac=rng.uniform(-1.5, 1.5))


def normal_pair(case: dict):
    """The closed form's normal solution and the SIE's (``n`` not given), or None if the closed form refuses."""
    punch, A, P = case["punch"], case["A"], case["P"]
    try:
        if case["tilt"] == "free":
            lim = cf.lift_off(punch, P, A)
            s = lim.s_min + (lim.s_max - lim.s_min) * case["s_frac"]
            return cf.solve_normal(punch, P, s, A=A), sie.solve_normal(punch, P, s, A=A)
        return (cf.solve_normal(punch, P, A=A, tilt="suppressed"),
                sie.solve_normal(punch, P, A=A, tilt="suppressed"))
    except ValueError:     # LiftOffError, SeparationError, SlopeLimitError, ArcExtentError, footprint
        return None


def inside(c) -> np.ndarray:
    """Points over the closed form's contact, END_MARGIN W inside its ends, and next to the joins."""
    W = c.a + c.c
    x = np.concatenate([np.linspace(-c.a, c.c, 2001)[1:-1],
                        [j + d for j in (-c.punch.b, c.punch.b) for d in (-1e-7, 1e-7, -1e-4, 1e-4)]])
    return x[(x > -c.a + END_MARGIN * W) & (x < c.c - END_MARGIN * W)]


def check_normal(case: dict) -> str | None:
    """Why the SIE's pressure disagrees with the closed form's (None if it agrees or the closed form refuses)."""
    pair = normal_pair(case)
    if pair is None:
        return None
    c, g = pair
    x = inside(c)
    pc = c.pressure(x)
    err = float(np.max(np.abs(g.pressure(x) - pc)) / np.max(pc))
    return None if err <= FIELD else f"pressure {err:.2e} of the peak"


def check_slip(case: dict, cycle: bool) -> str | None:
    """Why the two methods' partial slip (or fretting cycle) disagree, or why a refusal is not the other's."""
    pair = normal_pair(case)
    if pair is None:
        return None
    c, g = pair
    W = c.a + c.c
    f = case["f"]
    Q = case["ratio"] * f * c.P
    sb = case["bulk_frac"] * 8 * abs(Q) / (math.pi * W)
    try:
        ref = sie.solve_partial_slip(g, Q, f, sigma_bulk=sb)
    except (SlipReversalError, StickSeparationError) as exc:
        try:
            cf.solve_partial_slip(c, Q, f, sigma_bulk=sb)
        except ValueError:
            return None
        return f"the SIE refused ({type(exc).__name__}) but the closed form answered"
    if not ref.within_paper:
        try:
            cf.solve_partial_slip(c, Q, f, sigma_bulk=sb)
        except StickZoneError:
            return None
        return "the SIE's stick zone is beyond the paper but the closed form answered"
    got = cf.solve_partial_slip(c, Q, f, sigma_bulk=sb)
    why = []
    if max(abs(got.d - ref.d), abs(got.e - ref.e)) > ZONE * W:
        why.append(f"stick zone ({got.d}, {got.e}) against the SIE's ({ref.d}, {ref.e})")
    x = inside(c)
    q_err = float(np.max(np.abs(got.shear(x) - ref.shear(x)))) / (f * float(np.max(c.pressure(x))))
    if q_err > FIELD:
        why.append(f"shear {q_err:.2e} of f p0")
    if cycle:     # the cycle's smallest stick zone is the one at Q_max: within the paper, as checked
        C = cf.fretting_cycle(c, abs(Q), f, sigma_bulk=math.copysign(1.0, Q) * sb, states=3)
        G = sie.fretting_cycle(g, abs(Q), f, sigma_bulk=math.copysign(1.0, Q) * sb, states=3)
        if abs(G.energy - C.energy) > ENERGY * abs(C.energy):
            why.append(f"energy {G.energy!r} against {C.energy!r}")
        if float(np.max(np.abs(C.stick - G.stick))) > ZONE * W:
            why.append("the cycle's stick zones")
    return "; ".join(why) or None


def sweep(check, draws: int, seed: int, **kw) -> None:
    """Run ``check`` on ``draws`` cases from ``seed``; fail with every disagreement or unnamed error."""
    rng = np.random.default_rng(seed)
    failures = []
    for i in range(draws):
        case = draw(rng)
        try:
            why = check(case, **kw)
        except Exception as exc:   # NoConvergenceError, or a refusal that is not the other's: a failure
            why = f"{type(exc).__name__}: {exc}"
        if why is not None:
            failures.append(f"draw {i} of seed {seed} ({case}): {why}")
    assert not failures, "\n".join(failures)


def test_normal_wide_draw():
    sweep(check_normal, NORMAL_DRAWS, 29)


def test_partial_slip_with_a_bulk_stress_wide_draw():
    sweep(check_slip, SLIP_DRAWS, 2029, cycle=False)


def test_fretting_with_a_bulk_stress_wide_draw():
    sweep(check_slip, CYCLE_DRAWS, 4029, cycle=True)


@pytest.mark.slow
@pytest.mark.parametrize("check, draws, kw", [
    (check_normal, NORMAL_DRAWS, {}), (check_slip, SLIP_DRAWS, {"cycle": False}),
    (check_slip, CYCLE_DRAWS, {"cycle": True})])
def test_wide_draw_slow(check, draws, kw):
    sweep(check, SLOW_FACTOR * draws, 290, **kw)


def test_stick_zone_on_the_centre_falls_back():
    """Issue 29: where the SIE's stick zone ends on the centre the closed form refuses by name
    (StickZoneError, not NoConvergenceError), and ``auto`` answers with the SIE."""
    punch = Punch(R1=0.3393379998311084, R2=7.711091939076183, b=1)
    args = dict(A=2 * STEEL, Q=-288.05343682943516, f=0.4780455281119461, sigma_bulk=-83.88453609882512)
    with pytest.raises(StickZoneError, match="central segment"):
        solve(punch, 2517.4993105660747, -0.52813724679045, method="closedform", **args)
    r = solve(punch, 2517.4993105660747, -0.52813724679045, method="auto", **args)
    assert r.method == "sie" and not r.within_paper

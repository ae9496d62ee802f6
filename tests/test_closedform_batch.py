"""The batch solve against per-case solves, the forward equations and the nested roots (issue 33).

A wide random draw: radii over four decades, flat, convex and concave centres,
loads from just above their threshold to 10^4 times it, lever arms over the
whole lift-off range (to within 1e-6 of its ends) and both tilt modes. The batch
(numpy) must give the per-case (Python float) answers to round-off and the same
refusals; its answers must satisfy the forward equations (eqs.
equilibrium_condition_1, _2 and consistency_condition, evaluated by
:mod:`closedform.formulas`), and equal the nested bracketed roots that the
two-dimensional Newton step replaced; and it must take at most
:data:`MAX_EVALUATIONS` forward evaluations per case.
"""
from __future__ import annotations

import functools
import itertools
import math
import re

import numpy as np
import pytest

from threepart import closedform as cf
from threepart.closedform import formulas
from threepart.closedform.newton import _solve_phi_nested, ray_state
from threepart.errors import ArcExtentError, LiftOffError, SeparationError, SlopeLimitError
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance

#: issue 33's target for the forward evaluations per case of a batch (7.6 measured on caseA_moment)
MAX_EVALUATIONS = 12
ROUND_OFF = tolerance("closedform", "round_off").limit
#: the random draws: (seed, centre) for each punch
DRAWS = [(seed, centre) for seed in range(4) for centre in ("flat", "convex", "concave")]
#: cases per punch and tilt mode
N_CASES = 150
#: the fraction of the punch's footprint inside which lever arms are drawn
FOOTPRINT = 0.999
#: the batch's stages of refusal, in its order: lift-off, separation, then the arcs and the slope
STAGES = ((LiftOffError,), (SeparationError,), (ArcExtentError, SlopeLimitError))
#: forward evaluations per case of each draw's batch (filled by the per-case test)
EVALUATIONS: list[float] = []


def _punch(rng: np.random.Generator, centre: str) -> Punch:
    """Radii over four decades, ``b`` from 1e-2 to 1 of the smaller radius."""
    R1, R2 = 10 ** rng.uniform(-2, 2, 2)
    b = 10 ** rng.uniform(-2, 0) * min(R1, R2)
    R = {"flat": math.inf, "convex": 10 ** rng.uniform(0.5, 2) * max(R1, R2),
         "concave": -(10 ** rng.uniform(0.5, 2)) * max(R1, R2)}[centre]
    return Punch(R1, R2, b, R)


def _draw(seed: int, centre: str, tilt: str) -> tuple[Punch, float, np.ndarray, np.ndarray]:
    """A punch, ``A`` and ``N_CASES`` loads and lever arms of the draw."""
    rng = np.random.default_rng([seed, ("flat", "convex", "concave").index(centre), len(tilt)])
    punch, A = _punch(rng, centre), 1.0
    # the threshold: P_min of a convex centre, the separation load of a concave one, and for a
    # flat centre the load that presses the contact 1 % of b past the joins
    threshold = cf.P_min(punch, A) or math.pi * punch.b * 0.01 * punch.b / (A * max(punch.R1, punch.R2))
    P = threshold * (1 + 10 ** rng.uniform(-6, 4, N_CASES))
    frac = rng.uniform(0, 1, N_CASES)
    frac[:10] = [1e-6, 1 - 1e-6, 1e-3, 1 - 1e-3, 0.5, 0.25, 0.75, 1e-5, 1 - 1e-5, 0.5]
    s = np.zeros(N_CASES)
    if tilt == "free":
        for i, Pi in enumerate(P):
            lim = cf.lift_off(punch, float(Pi), A, beyond_small_slopes=True)
            s[i] = lim.s_min + frac[i] * (lim.s_max - lim.s_min)
    # past the arcs the lift-off lever arms may leave the punch's footprint: kept on it (refused later)
    s = np.clip(s, -(punch.b + punch.R1) * FOOTPRINT, (punch.b + punch.R2) * FOOTPRINT)
    return punch, A, P, s


def _per_case(punch: Punch, A: float, P: np.ndarray, s: np.ndarray, tilt: str) -> list:
    """Each case solved alone: its solution, or its error's type and message."""
    out = []
    for Pi, si in zip(P, s):
        try:
            out.append(cf.solve_normal(punch, float(Pi), float(si), A=A, tilt=tilt))
        except ValueError as exc:
            out.append((type(exc), str(exc)))
    return out


@functools.lru_cache(maxsize=None)
def _solved(seed: int, centre: str, tilt: str) -> tuple[Punch, float, np.ndarray, np.ndarray, list]:
    """The draw and its per-case answers, solved once a draw for every test of this file (read only)."""
    punch, A, P, s = _draw(seed, centre, tilt)
    return punch, A, P, s, _per_case(punch, A, P, s, tilt)


def _stage(kind: type) -> int:
    return next(i for i, kinds in enumerate(STAGES) if issubclass(kind, kinds))


def _digits(message: str) -> str:
    """``message`` with each number to 4 digits: a flat minimum's place (x = ...) is set to ~1e-8."""
    return re.sub(r"-?\d+\.?\d*(e[-+]?\d+)?", lambda m: f"{float(m.group()):.4g}", message)


@pytest.mark.parametrize("tilt", ["free", "suppressed"])
@pytest.mark.parametrize("seed,centre", DRAWS)
def test_batch_equals_per_case_and_refuses_alike(seed, centre, tilt):
    punch, A, P, s, single = _solved(seed, centre, tilt)
    refused = [i for i, r in enumerate(single) if isinstance(r, tuple)]
    if refused:   # the batch names the first case refused at its earliest stage, with that case's error
        first = min(refused, key=lambda i: (_stage(single[i][0]), i))
        kind, message = single[first]
        with pytest.raises(kind) as info:
            cf.solve_normal_batch(punch, P, s, A=A, tilt=tilt)
        got = str(info.value)
        if kind in STAGES[2]:
            prefix = f"case {first} (`P` = {P[first]:.6g}, `s` = "
            assert got.startswith(prefix)
            got = got.split("): ", 1)[1]
        assert _digits(got) == _digits(message)
    ok = np.array([not isinstance(r, tuple) for r in single])
    if not ok.any():
        return
    batch = cf.solve_normal_batch(punch, P[ok], s[ok], A=A, tilt=tilt)
    sols = [r for r in single if not isinstance(r, tuple)]
    W = batch.a + batch.c
    for name in ("a", "c", "s"):
        got, want = getattr(batch, name), np.array([getattr(r, name) for r in sols])
        assert np.max(np.abs(got - want) / W) <= ROUND_OFF, name
    # the tilt, on the slope scale of the contact
    slope = punch.max_slope(batch.a, batch.c, 0.0)
    alpha = np.array([r.alpha for r in sols])
    assert np.max(np.abs(batch.alpha - alpha) / slope) <= ROUND_OFF
    EVALUATIONS.append(batch.evaluations)


@pytest.mark.parametrize("tilt", ["free", "suppressed"])
@pytest.mark.parametrize("seed,centre", DRAWS[:6])
def test_batch_satisfies_the_forward_equations_and_equals_the_nested_roots(seed, centre, tilt):
    punch, A, P, s, single = _solved(seed, centre, tilt)
    ok = np.array([not isinstance(r, tuple) for r in single])
    P, s = P[ok], s[ok]
    if not P.size:
        return
    batch = cf.solve_normal_batch(punch, P, s, A=A, tilt=tilt)
    W = batch.a + batch.c
    # eq. equilibrium_condition_1 (load) and _2 (moment), and the consistency condition
    assert np.max(np.abs(formulas.load(punch, batch.a, batch.c, A) / P - 1)) <= ROUND_OFF
    Ps = formulas.moment(punch, batch.a, batch.c, A)
    assert np.max(np.abs(Ps / P - batch.s) / W) <= ROUND_OFF
    slope = punch.max_slope(batch.a, batch.c, 0.0)
    assert np.max(np.abs(formulas.tilt(punch, batch.a, batch.c) - batch.alpha) / slope) <= ROUND_OFF
    # the nested bracketed roots that the two-dimensional Newton step replaced
    dAP = A * P - 0.5 * math.pi * punch.kappa0 * punch.b**2
    target, value, sign = ("moment", A * P * s, 1.0) if tilt == "free" else ("tilt", 0.0 * P, -1.0)
    r, phi, below, above = _solve_phi_nested(punch, dAP, target, value, np, sign)
    assert not (below | above).any()
    nested = ray_state(punch, r, phi, np)
    assert np.max(np.abs(nested.a - batch.a) / W) <= ROUND_OFF
    assert np.max(np.abs(nested.c - batch.c) / W) <= ROUND_OFF


def test_evaluation_count_on_the_wide_draw():
    """At most MAX_EVALUATIONS per case over the wide draw (9.1 measured; up to 21 with R1/R2 = 1/2700)."""
    if not EVALUATIONS:
        for (seed, centre), tilt in itertools.product(DRAWS, ("free", "suppressed")):
            punch, A, P, s, single = _solved(seed, centre, tilt)
            ok = np.array([not isinstance(r, tuple) for r in single])
            if ok.any():
                EVALUATIONS.append(cf.solve_normal_batch(punch, P[ok], s[ok], A=A, tilt=tilt).evaluations)
    assert np.mean(EVALUATIONS) <= MAX_EVALUATIONS


def test_evaluation_count_on_the_benchmark_draw():
    """The benchmark's draw (caseA_moment, 2,000 cases): at most MAX_EVALUATIONS per case, also alone."""
    from threepart.problem.catalogue import get_case

    case = get_case("caseA_moment")
    rng = np.random.default_rng(0)
    P, s = rng.uniform(200.0, 2000.0, 2000), rng.uniform(-0.3, 0.3, 2000)
    assert cf.solve_normal_batch(case.punch, P, s, A=case.A).evaluations <= MAX_EVALUATIONS
    assert cf.solve_normal(case.punch, 400.0, 0.1, A=case.A).info["evaluations"] <= MAX_EVALUATIONS


def test_least_centre_pressure_of_a_batch_is_brents():
    """The batch's golden-section refinement of the least centre pressure against scipy's bounded
    Brent search of each case (closedform.normal._centre_pressure_min), concave centre near separation."""
    from threepart.closedform.normal import _CENTRE_GRID, _centre_minima, _centre_pressure_min

    punch, A = Punch(1.0, 1.5, 0.3, -50.0), 1.0
    P = cf.P_min(punch, A, tilt="suppressed") * np.linspace(1.001, 1.5, 40)
    batch = cf.solve_normal_batch(punch, P, 0.0, A=A, tilt="suppressed")
    xg = np.linspace(-punch.b, punch.b, _CENTRE_GRID)
    grid = formulas.pressure(punch, batch.a[:, None], batch.c[:, None], A, xg[None, :])
    got = _centre_minima(punch, batch.a, batch.c, A, grid)
    want = np.array([_centre_pressure_min(punch, float(a), float(c), A)[1] for a, c in zip(batch.a, batch.c)])
    assert np.max(np.abs(got - want) / (P / (batch.a + batch.c))) <= ROUND_OFF

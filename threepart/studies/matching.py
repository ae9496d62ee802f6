"""The matching pad test: the cylinder-on-flat test that reproduces one edge of a flank (docs/EDGES.md §6).

Two edges that share ``K_N``, ``K_T`` and the bulk stress share their local
field, and with it the slip zone (:mod:`threepart.results.edges`). This study
solves a Hertzian pad through :func:`threepart.solve` so that its edge has a
flank's multipliers, and compares the surface σxx over the slip zone and the
fatigue parameters near the edge (:func:`threepart.fatigue.fatigue`). It sits
above the methods: the results' edge multipliers never import it.

Names
-----
Match       -- the pad test of :func:`match`: its punch, loads, result and how well its edge field agrees
match       -- the cylinder-on-flat test that reproduces one edge of a flank
pad_loads   -- ``(R, P, Q)`` of the Hertzian pad whose edge has given K_N and K_T (E9)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import registry
from ..errors import FullSlidingError, InputError, InputTypeError
from ..fatigue.table import fatigue as cycle_fatigue, reported
from ..methods import solve
from ..problem.material import NU, similar_pair_modulus
from ..problem.punch import Punch
from ..problem.checks import positive, show
from ..results.slip import SlipResult
from ..results.edges import SIDES, Edge, edges, exact_slip
from ..tolerances import tolerance

__all__ = ["Match", "match", "pad_loads", "SXX_POINTS", "FATIGUE_GRID", "FATIGUE_STATES", "PAD_RANGE",
           "PAD_SCAN"]

#: surface points over the slip zone at which σxx of flank and pad are compared
SXX_POINTS = 201
#: the fatigue grid near the edge: points along the surface (over twice the slip zone) and in depth
FATIGUE_GRID = (21, 6)
#: recorded states per branch of the fretting cycles whose fatigue parameters are compared (the
#: cycle's extremes ±Q_max are among them; the parameters are ranges and maxima over the states)
FATIGUE_STATES = 5


@dataclass(frozen=True)
class Match:
    """The cylinder-on-flat test that reproduces one edge of a flank (:func:`match`, docs/EDGES.md §6).

    Attributes
    ----------
    side
        The flank's edge matched, ``"left"`` or ``"right"``; the pad's same edge reproduces it.
    punch, R, P, Q, sigma_bulk, f, A
        The pad (``Punch(R, R, 0)``), its loads (``s = 0``), the flank's friction and compliance.
    result
        The pad's own partial-slip result (solved through :func:`threepart.solve`).
    flank, pad
        The :class:`Edge` records of the flank's edge and the pad's same edge.
    r, sxx_flank, sxx_pad
        Distances inside the edge over the slip zone (the smaller of the flank's and the
        pad's exact ones, which agree to first order, E6) and the surface σxx of each there.
    sxx_error
        ``max |Δσxx|`` over those points, of the flank's largest ``|σxx|`` there.
    fatigue
        ``{name: (flank, pad)}``: each fatigue parameter's largest value near the edge, over a
        fretting cycle of amplitude ``Q`` (:func:`threepart.fatigue.fatigue`), for the table's
        parameters the report tabulates (:func:`threepart.fatigue.table.reported`); empty if not asked.
    """

    side: str
    punch: Any
    R: float
    P: float
    Q: float
    sigma_bulk: float
    f: float
    A: float
    result: Any
    flank: Edge
    pad: Edge
    r: Any
    sxx_flank: Any
    sxx_pad: Any
    sxx_error: float
    fatigue: dict[str, tuple[float, float]]


def _match_iv(flank: Any, edge: Any, R: Any, P: Any) -> tuple[int, float | None, float | None]:
    """Checks of :func:`match`'s input, before anything is solved: ``(side index, R, P)``."""
    if not isinstance(flank, SlipResult):
        raise InputTypeError(f"`flank_result` must be a partial-slip result (threepart.solve with Q and f), "
                        f"not {type(flank).__name__}")
    if edge not in SIDES:
        raise InputError(f"`edge` = {show(edge)} must be 'left' or 'right'")
    if R is not None and P is not None:
        raise InputError("give at most one of `R` (the pad's radius) and `P` (its load), not both")
    return (SIDES.index(edge), None if R is None else positive("R", R),
            None if P is None else positive("P", P))


def pad_loads(K_N: float, K_T: float, share: float, sigma_bulk: float, f: float, A: float,
              R: float | None = None, P: float | None = None) -> tuple[float, float, float]:
    """``(R, P, Q)`` of the Hertzian pad whose edge has ``K_N`` and ``K_T`` (E9).

    ``K_N = √(2a)/(A R)`` (E2) fixes ``a`` from ``R`` (``a = (K_N A R)²/2``) or from ``P``
    (``a³ = 8 P²/(π² K_N²)``), and Hertz's ``P = π a²/(2 A R)`` the other; ``K_T =
    Q/(π √(2a)) + share`` (E3, ``share = ±sigma_bulk √(2a)/8`` at the left/right edge, sign
    given by ``share``'s of a unit stress) fixes ``Q``.

    Raises
    ------
    FullSlidingError
        If that ``Q`` is not below ``f P``: no pad of that size reproduces the edge.
    """
    given = f"`R` = {R:.6g}" if R is not None else f"`P` = {P:.6g}"
    if R is not None:
        a = 0.5 * (K_N * A * R) ** 2
        P = math.pi * a * a / (2.0 * A * R)
    else:
        assert P is not None
        a = (8.0 * P * P / (math.pi * K_N) ** 2) ** (1.0 / 3.0)
        R = math.pi * a * a / (2.0 * A * P)
    Q = math.pi * math.sqrt(2.0 * a) * (K_T - share * sigma_bulk * math.sqrt(2.0 * a) / 8.0)
    if abs(Q) >= f * P:
        raise FullSlidingError(f"the pad of {given} would need |Q| = {abs(Q):.6g} >= f P = {f * P:.6g} "
                               "to reproduce the edge's K_T: it would slide; choose a larger pad")
    return R, P, Q


def match(flank_result: Any, edge: str, R: float | None = None, P: float | None = None, *,
          method: str = "closedform", fatigue: bool = True, nu: float | None = None) -> Match:
    """The cylinder-on-flat test that reproduces one edge of a flank (docs/EDGES.md §6).

    The pad is ``Punch(R, R, 0)`` of the flank's compliance ``A`` and friction ``f``, at
    ``s = 0``, under the flank's bulk stress (the edge's regular tension), with ``P`` and
    ``Q`` such that its edge ``edge`` has the flank's ``K_N`` and ``K_T`` (E9), hence its
    slip zone (E5).

    Parameters
    ----------
    flank_result
        The flank's partial-slip result, of any method.
    edge
        ``"left"`` (``-a``) or ``"right"`` (``c``).
    R, P
        At most one: the pad's radius, or its load. Neither: the radius whose pad puts the
        surface σxx over the slip zone closest to the flank's (the largest difference over
        the flank's largest ``|σxx|`` there, minimised over ``R`` from :data:`PAD_RANGE`'s
        factors of the pad as wide as the flank's contact, ``R = √W/(A K_N)``): the
        multipliers fix the edge to first order, the radius its second-order terms.
    method
        The method that solves the pad (through :func:`threepart.solve`).
    fatigue
        Also compare the fatigue parameters near the edge over a fretting cycle of
        amplitude ``Q`` (flank and pad, :func:`threepart.fatigue.fatigue`).
    nu
        Poisson's ratio of the substrate for the stresses (default :data:`threepart.problem.material.NU`);
        ``E = 4 (1 - nu²)/A`` (similar bodies) for the fatigue parameters.

    Raises
    ------
    TypeError, ValueError
        On bad input (before anything is solved).
    FullSlidingError
        If no pad of the given size reproduces the edge without sliding.
    """
    k, R, P = _match_iv(flank_result, edge, R, P)
    nu = NU if nu is None else nu
    target = edges(flank_result)[k]
    assert target.K_T is not None and target.sigma_bulk is not None
    _slip_zone_iv(flank_result, edge, k)
    if R is None and P is None:
        R = _best_radius(flank_result, k, target, method, nu)
    pad, R, P, Q, result, mine, r, s_flank, s_pad, error = _pad(flank_result, k, target, method, nu,
                                                                  R=R, P=P)
    sign = 1.0 if k == 0 else -1.0
    slip = float(r[-1] + r[0])
    found = _fatigue(flank_result, result, target, mine, slip, sign, nu) if fatigue else {}
    return Match(edge, pad, R, P, Q, flank_result.sigma_bulk, flank_result.f, flank_result.normal.A,
                 result, target, mine, r, s_flank, s_pad, error, found)


def _slip_zone_iv(flank: Any, edge: str, k: int) -> None:
    """Refuse a flank whose slip zone at ``edge`` is none (``Q = 0``) or below the rounding of its ends.

    The σxx comparison runs over the slip zone: over none it would be 0/0, and below
    ``tolerance("match", "slip_zone_min")`` of the contact width the rounding of the
    contact and stick-zone ends sets its size (issue 37).
    """
    slip, width = _exact_slip(flank, k), flank.normal.width
    least = tolerance("match", "slip_zone_min").limit
    if slip > least * width:
        return
    raise InputError(f"`flank_result` has no slip zone to match at its {edge} edge: it is "
                     f"{max(slip, 0.0):.3g}, not over {least:g} of the contact width {width:.6g} "
                     f"(Q = {flank.Q:g}, sigma_bulk = {flank.sigma_bulk:g}); give a larger shear load")


#: the pad radii :func:`match` searches when given neither ``R`` nor ``P``: factors of the pad as
#: wide as the flank's contact (the optimum lay at 0.47-0.78 of it on the catalogue's flanks)
PAD_RANGE = (0.05, 20.0)
#: points of the coarse scan over PAD_RANGE (log-spaced) before the bounded refinement
PAD_SCAN = 17


def _pad(flank: Any, k: int, target: Edge, method: str, nu: float, *, R: float | None,
         P: float | None) -> tuple[Any, ...]:
    """The pad of radius ``R`` (or load ``P``) reproducing ``target``, solved, and its surface σxx
    over the slip zone against the flank's: ``(punch, R, P, Q, result, edge, r, sxx_flank, sxx_pad,
    error)``."""
    sign = 1.0 if k == 0 else -1.0
    A, f, sigma = flank.normal.A, flank.f, flank.sigma_bulk
    assert target.K_T is not None          # a flank with a shear (checked by match)
    R, P, Q = pad_loads(target.K_N, target.K_T, sign, sigma, f, A, R=R, P=P)
    pad = Punch(R, R, 0.0)
    result = solve(pad, P, 0.0, A=A, Q=Q, f=f, sigma_bulk=sigma, method=method)
    mine = edges(result)[k]
    slip = min(_exact_slip(flank, k), _exact_slip(result, k))
    if not slip > 0.0:   # the flank's is checked by match: the pad's, of the same K_T/K_N
        raise InputError(f"the pad `R` = {R:.6g} has no slip zone at its {SIDES[k]} edge to compare")
    r = slip * (np.arange(SXX_POINTS) + 0.5) / SXX_POINTS
    zero = np.zeros_like(r)
    s_flank = flank.stress(target.x + sign * r, zero, nu=nu).sxx
    s_pad = result.stress(mine.x + sign * r, zero, nu=nu).sxx
    error = float(np.max(np.abs(s_pad - s_flank)) / np.max(np.abs(s_flank)))
    return pad, R, P, Q, result, mine, r, s_flank, s_pad, error


def _best_radius(flank: Any, k: int, target: Edge, method: str, nu: float) -> float:
    """The pad radius of least σxx error over the slip zone (:data:`PAD_RANGE`, :data:`PAD_SCAN`)."""
    from scipy.optimize import minimize_scalar

    R0 = math.sqrt(flank.normal.width) / (flank.normal.A * target.K_N)

    def error(log_factor: float) -> float:
        try:
            return float(_pad(flank, k, target, method, nu, R=R0 * math.exp(log_factor), P=None)[-1])
        except ValueError:   # a pad that slides, or whose bulk stress reverses the slip: not a candidate
            return math.inf

    grid = np.linspace(math.log(PAD_RANGE[0]), math.log(PAD_RANGE[1]), PAD_SCAN)
    errors = [error(g) for g in grid]
    i = int(np.argmin(errors))
    if not math.isfinite(errors[i]):
        return R0                     # no pad in the range fits: the width rule, refused by pad_loads
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    with np.errstate(invalid="ignore"):   # a candidate that slides is inf: Brent's parabola steps past it
        best = minimize_scalar(error, bounds=(lo, hi), method="bounded", options={"xatol": 1e-3})
    return R0 * math.exp(float(best.x) if best.fun <= errors[i] else float(grid[i]))


def _exact_slip(res: Any, k: int) -> float:
    """:func:`exact_slip` of a partial-slip result, which has one."""
    slip = exact_slip(res, k)
    assert slip is not None, "a partial-slip result has a stick zone"
    return slip


def _fatigue(flank: Any, pad: Any, e_flank: Edge, e_pad: Edge, slip: float, sign: float,
             nu: float) -> dict[str, tuple[float, float]]:
    """Each fatigue parameter's largest value near the edge, over a fretting cycle of amplitude ``Q``, flank and pad."""
    n, m = FATIGUE_GRID
    r = np.linspace(-0.5 * slip, 2.0 * slip, n)[:, None]
    z = np.linspace(0.0, slip, m)[None, :]
    E = similar_pair_modulus(flank.normal.A, nu)
    found: dict[str, list[float]] = {name: [] for name in reported()}
    for res, e in ((flank, e_flank), (pad, e_pad)):
        normal, cycle_of = res.normal, registry.get(res.method).fretting
        if cycle_of is None:
            raise InputError(f"method {res.method!r} has no fretting cycle for the fatigue parameters; "
                             "pass fatigue=False")
        cycle = cycle_of(normal.punch, normal.P, normal.s, A=normal.A, tilt=normal.tilt, nu=None,
                         Q_max=abs(res.Q), states=FATIGUE_STATES, f=res.f,
                         sigma_bulk=res.sigma_bulk * (1.0 if res.Q > 0 else -1.0), normal=normal)
        x = e.x + sign * r
        fat = cycle_fatigue(cycle, x, z, E=E, nu=nu, surface=np.sort(e.x + sign * r.ravel()))
        for name in found:
            found[name].append(fat.parameters[name].hot.value)
    return {name: (v[0], v[1]) for name, v in found.items()}

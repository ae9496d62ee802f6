"""Edge asymptotics: the multipliers of each contact edge, its asymptotic slip zone, the matching pad test.

Near an edge of an incomplete contact, at a distance ``r`` inside it, the
pressure is ``p ≈ K_N √r`` and the shear of the fully stuck contact is
``q ≈ K_T/√r`` (docs/EDGES.md). Two edges that share ``K_N``, ``K_T`` and the
bulk stress share their local field, and with it the slip zone
``2 |K_T|/(f K_N)`` (eq. E5): a dovetail flank's edge can be reproduced by a
Hertzian pad test (:func:`match`).

The core holds no solver: a method gives its ``K_N`` through the registry
(:attr:`threepart.registry.Method.edges`); ``K_T`` follows from the loads and
the method's own contact ``[-a, c]`` (eq. E3), the same for every method.

Names
-----
Edged       -- the ``edges()`` method every normal, slip, fretting and steady-state result inherits
Edge        -- the multipliers of one edge (left ``-a`` or right ``c``), with units (threepart.problem.units)
edges       -- the two :class:`Edge` records of a normal, slip, fretting or steady-state result
K_T_stuck   -- ``(K_T_left, K_T_right)`` of the fully stuck shear under ``Q`` and ``sigma_bulk`` (E3)
K_sigma     -- the bulk stress's share of ``K_T`` at each edge (E3)
slip_zone   -- the asymptotic slip zone ``2 |K_T|/(f K_N)`` (E5), or of a cycle (E7)
exact_slip  -- a result's own slip zone at an edge, to compare the asymptote with
hertz_K_N   -- ``K_N = p0 √(2/a)`` of a Hertzian contact (E2)
Match       -- the pad test of :func:`match`: its punch, loads, result and how well its edge field agrees
match       -- the cylinder-on-flat test that reproduces one edge of a flank
pad_loads   -- ``(R, P, Q)`` of the Hertzian pad whose edge has given K_N and K_T (E9)
SIDES       -- ``("left", "right")``
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import registry
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:
    from .contact import NormalResult

__all__ = ["Edge", "Edged", "edges", "K_T_stuck", "K_sigma", "slip_zone", "exact_slip", "hertz_K_N", "SIDES",
           "Match", "match", "pad_loads", "SXX_POINTS", "FATIGUE_GRID", "FATIGUE_STATES", "FATIGUE_PARAMETERS"]

#: the two edges of a contact, in the order :func:`edges` returns them
SIDES = ("left", "right")


@dataclass(frozen=True)
class Edge:
    """The asymptotic multipliers of one contact edge (docs/EDGES.md); units in :data:`threepart.problem.units.UNITS`.

    Attributes
    ----------
    side, x
        ``"left"`` (at ``x = -a``) or ``"right"`` (at ``x = c``), and that ``x``.
    K_N
        Bounded pressure's multiplier, ``p ≈ K_N √r`` at ``r`` inside the edge
        (MPa/√mm; eq. E1). For a cycle the mean of its two end states'.
    K_T
        Multiplier of the fully stuck shear, ``q ≈ K_T/√r`` (MPa·√mm; eq. E3),
        with the sign of the shear's force; for a cycle, of the change of shear
        from state 0 (or ``-Q_max``) to state 1 (or ``Q_max``). None without a shear.
    K_sigma
        The bulk stress's share of ``K_T`` (E3), None without a shear.
    sigma_bulk
        The bulk stress at the edge (MPa): the regular tension of its local
        field; for a cycle its change. None without a shear.
    slip_zone
        Asymptotic slip zone at the edge (mm; eq. E5, E7), None without a shear.
    fit_error
        Bound on the error of ``K_N`` from the method's fit (FEM), None where
        ``K_N`` is exact to rounding (closed form, SIE).
    kind, method
        The result it came from (``"normal"``, ``"slip"``, ``"fretting"``,
        ``"steady"``) and its method.
    """

    side: str
    x: float
    K_N: float
    K_T: float | None = None
    K_sigma: float | None = None
    sigma_bulk: float | None = None
    slip_zone: float | None = None
    fit_error: float | None = None
    kind: str = "normal"
    method: str = ""


def hertz_K_N(p0: float, a: float) -> float:
    """``K_N = p0 √(2/a)`` of Hertz's pressure ``p0 √(1 - x²/a²)`` (eq. E2)."""
    return p0 * math.sqrt(2.0 / a)


def K_T_stuck(Q: float, sigma_bulk: float, a: float, c: float) -> tuple[float, float]:
    """``(K_T_left, K_T_right)`` of the fully stuck shear on ``[-a, c]`` (eq. E3).

    ``q = [Q/π + (sigma_bulk/4)(m - x)]/√((x + a)(c - x))``, ``m = (c - a)/2``
    (docs/BULK_STRESS.md, B6 over the whole contact), so with ``W = a + c``
    ``K_T = (Q/π ± sigma_bulk W/8)/√W``, ``+`` at the left edge.
    """
    W = a + c
    shear = Q / math.pi
    left, right = K_sigma(sigma_bulk, a, c)
    return shear / math.sqrt(W) + left, shear / math.sqrt(W) + right


def K_sigma(sigma_bulk: float, a: float, c: float) -> tuple[float, float]:
    """The bulk stress's share of ``K_T`` at each edge: ``(+, -) sigma_bulk √W/8`` (eq. E3)."""
    share = sigma_bulk * math.sqrt(a + c) / 8.0
    return share, -share


def slip_zone(K_T: float, K_N: float, f: float, *, cycle: bool = False) -> float:
    """Asymptotic slip zone ``2 |K_T|/(f K_N)`` (eq. E5); of a cycle ``|ΔK_T|/(f K_N)`` (eq. E7).

    For a cycle ``K_T`` is the change of the stuck shear's multiplier over the
    half-cycle and ``K_N`` the mean of the two end states' (the slip zones
    carry ``2 f`` times the mean pressure's change of shear, eq. S3).
    """
    return (1.0 if cycle else 2.0) * abs(K_T) / (f * K_N)


def _normal_multipliers(normal: NormalResult) -> tuple[tuple[float, float | None], ...]:
    """``((K_N, fit_error), (K_N, fit_error))`` of a normal result, by its method's ``edges``."""
    method = registry.get(normal.method)
    if method.edges is None:
        raise InputError(f"method {normal.method!r} does not compute edge multipliers "
                         "(its registry entry has no `edges`)")
    return method.edges(normal)


def _edges_normal(result: NormalResult) -> tuple[Edge, Edge]:
    """The two records of a normal result: ``K_N`` (and the FEM's fit error) only."""
    (K_l, err_l), (K_r, err_r) = _normal_multipliers(result)
    return (Edge("left", -result.a, K_l, fit_error=err_l, method=result.method),
            Edge("right", result.c, K_r, fit_error=err_r, method=result.method))


def _with_shear(normals: tuple[NormalResult, ...], K_T: tuple[float, float],
                K_s: tuple[float, float], sigma: float, f: float, kind: str, method: str,
                cycle: bool) -> tuple[Edge, Edge]:
    """The two records of a result with a shear: ``K_N`` (mean over ``normals``) and the given ``K_T``."""
    mults = [_normal_multipliers(n) for n in normals]
    out = []
    for k, side in enumerate(SIDES):
        K_N = sum(m[k][0] for m in mults) / len(mults)
        errs = [m[k][1] for m in mults]
        err = None if all(e is None for e in errs) else max(e or 0.0 for e in errs)
        x = (-normals[0].a, normals[0].c)[k]
        out.append(Edge(side, x, K_N, K_T[k], K_s[k], sigma, slip_zone(K_T[k], K_N, f, cycle=cycle),
                        err, kind, method))
    return out[0], out[1]


class Edged:
    """What every normal, slip, fretting and steady-state result has: :meth:`edges`."""

    def edges(self) -> tuple[Edge, Edge]:
        """Multipliers of the edges ``-a`` and ``c``: K_N, K_T, slip zone (:func:`edges`)."""
        return edges(self)


def edges(result: Any) -> tuple[Edge, Edge]:
    """The :class:`Edge` records ``(left, right)`` of a result of any method (docs/EDGES.md).

    Parameters
    ----------
    result
        A :class:`~threepart.results.NormalResult`, :class:`~threepart.results.SlipResult`
        (``K_T`` of its ``Q`` and ``sigma_bulk``, E3), :class:`~threepart.results.FrettingResult`
        (``K_T`` of the change from ``-Q_max`` to ``Q_max``, reloading) or
        :class:`~threepart.results.cycles.SteadyStateResult` (of the change from state 0 to 1).

    Raises
    ------
    TypeError
        For any other object.
    ValueError
        If the result's method computes no multipliers (its registry entry has
        no ``edges``), or as that method's ``edges`` raises (the FEM: too few
        nodes near an edge for the fit).
    """
    from .cycles import SteadyStateResult
    from .contact import FrettingResult, NormalResult, SlipResult
    if isinstance(result, NormalResult):
        return _edges_normal(result)
    if isinstance(result, SlipResult):
        n = result.normal
        return _with_shear((n,), K_T_stuck(result.Q, result.sigma_bulk, n.a, n.c),
                           K_sigma(result.sigma_bulk, n.a, n.c), result.sigma_bulk, result.f,
                           "slip", result.method, cycle=False)
    if isinstance(result, FrettingResult):
        n, dQ, ds = result.normal, 2.0 * result.Q_max, 2.0 * result.sigma_bulk
        return _with_shear((n,), K_T_stuck(dQ, ds, n.a, n.c), K_sigma(ds, n.a, n.c), ds, result.f,
                           "fretting", result.method, cycle=True)
    if isinstance(result, SteadyStateResult):
        return _edges_steady(result)
    raise InputTypeError(f"`result` must be a normal, slip, fretting or steady-state result, "
                    f"not {type(result).__name__}")


def _edges_steady(result: Any) -> tuple[Edge, Edge]:
    """Records of a steady state: ``K_T`` of the change of the stuck shear from state 0 to 1 (E7)."""
    n0, n1 = result.normals
    (_, _, Q0, s0), (_, _, Q1, s1) = result.states
    T0, T1 = K_T_stuck(Q0, s0, n0.a, n0.c), K_T_stuck(Q1, s1, n1.a, n1.c)
    S0, S1 = K_sigma(s0, n0.a, n0.c), K_sigma(s1, n1.a, n1.c)
    dT = (T1[0] - T0[0], T1[1] - T0[1])
    dS = (S1[0] - S0[0], S1[1] - S0[1])
    return _with_shear((n0, n1), dT, dS, s1 - s0, result.f, "steady", result.method, cycle=True)


# --- the matching pad test ------------------------------------------------------------------------
#: surface points over the slip zone at which σxx of flank and pad are compared
SXX_POINTS = 201
#: the fatigue grid near the edge: points along the surface (over twice the slip zone) and in depth
FATIGUE_GRID = (21, 6)
#: recorded states per branch of the fretting cycles whose fatigue parameters are compared (the
#: cycle's extremes ±Q_max are among them; the parameters are ranges and maxima over the states)
FATIGUE_STATES = 5
#: the fatigue parameters compared, by the name of their hot spot in :class:`threepart.fatigue.Fatigue`
FATIGUE_PARAMETERS = ("von_mises_range", "swt", "findley", "ruiz_ffdp")


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
        fretting cycle of amplitude ``Q`` (:func:`threepart.fatigue.fatigue`); empty if not asked.
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
    from .contact import SlipResult
    from ..problem.validate import positive, show
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
    from ..errors import FullSlidingError
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
        the flank's largest |σxx| there, minimised over ``R`` from :data:`PAD_RANGE`'s
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
    from ..problem.material import NU
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
    from ..tolerances import tolerance
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
    from ..methods import solve
    from ..problem.punch import Punch
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


def exact_slip(res: Any, k: int) -> float | None:
    """A result's own slip zone at edge ``k`` (0 left, 1 right): from its contact end to its stick
    zone's; None for a result without a stick zone (a normal result, a cycle that shook down)."""
    zone = getattr(res, "stick_zone", None)
    if zone is None or getattr(res, "shakedown", False) or not hasattr(res, "d"):
        return None
    normal = res.normals[0] if hasattr(res, "normals") else getattr(res, "normal", res)
    lo, hi = zone
    return float(lo + normal.a) if k == 0 else float(normal.c - hi)


def _exact_slip(res: Any, k: int) -> float:
    """:func:`exact_slip` of a partial-slip result, which has one."""
    slip = exact_slip(res, k)
    assert slip is not None, "a partial-slip result has a stick zone"
    return slip


def _fatigue(flank: Any, pad: Any, e_flank: Edge, e_pad: Edge, slip: float, sign: float,
             nu: float) -> dict[str, tuple[float, float]]:
    """Each fatigue parameter's largest value near the edge, over a fretting cycle of amplitude ``Q``, flank and pad."""
    from ..fatigue.table import fatigue
    from ..problem.material import similar_pair_modulus
    n, m = FATIGUE_GRID
    r = np.linspace(-0.5 * slip, 2.0 * slip, n)[:, None]
    z = np.linspace(0.0, slip, m)[None, :]
    E = similar_pair_modulus(flank.normal.A, nu)
    found: dict[str, list[float]] = {name: [] for name in FATIGUE_PARAMETERS}
    for res, e in ((flank, e_flank), (pad, e_pad)):
        normal, cycle_of = res.normal, registry.get(res.method).fretting
        if cycle_of is None:
            raise InputError(f"method {res.method!r} has no fretting cycle for the fatigue parameters; "
                             "pass fatigue=False")
        cycle = cycle_of(normal.punch, normal.P, normal.s, A=normal.A, tilt=normal.tilt, nu=None,
                         Q_max=abs(res.Q), states=FATIGUE_STATES, f=res.f,
                         sigma_bulk=res.sigma_bulk * (1.0 if res.Q > 0 else -1.0), normal=normal)
        x = e.x + sign * r
        fat = fatigue(cycle, x, z, E=E, nu=nu, surface=np.sort(e.x + sign * r.ravel()))
        for name in FATIGUE_PARAMETERS:
            found[name].append(fat.parameters[name].hot.value)
    return {name: (v[0], v[1]) for name, v in found.items()}

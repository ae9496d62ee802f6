"""Normal problem under load control: the contact ends found with the discretised pressure.

The integral equation (paper eq. integral_equation), with compressive pressure
``p >= 0`` on ``[-a, c]``,

    -(1/π) PV ∫ p(t)/(t - x) dt = v'(x)/A,        -a < x < c,

is solved bounded at both ends. On the trial contact ``x = m + h s`` a scheme
(:mod:`sie.schemes`) gives the Chebyshev coefficients ``G_0, G_1, G_2`` of the
geometric slope; the unknowns ``(m, h)`` then satisfy two of

* consistency (the extra collocation equation): ``α + G_0 = 0``,
* vertical equilibrium (eq. vertical): ``π h G_1/(2A) = P``,
* rotational equilibrium (eq. rotational): ``m + π h^2 G_2/(4AP) = s``,

namely load and centroid for ``tilt="free"`` (then ``α = -G_0``), and
consistency and load with ``α = 0`` for ``tilt="suppressed"`` (then ``s`` is
returned). A damped Newton iteration with the exact Jacobian solves them.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from threepart.problem.punch import Punch

from threepart.problem.checks import check_tilt, positive
from threepart.problem.validate import check_arcs, check_contact, check_punch, lever_arm, load_scale
from threepart.errors import InputError, NoConvergenceError, SeparationError
from threepart.results import Diagnostics, NormalResult

from .projection import slope_coefficients
from .quadrature import MAX_N, check_n
from .roots import bracket_root, newton
from .schemes import Plain, Projected, make_scheme
from threepart.tolerances import tolerance
from .series import ChebyshevPressure, power_series

__all__ = ["SieNormalResult", "solve_normal", "solve_ends", "lift_off", "DEFAULT_N", "DEFAULT_SCHEME",
           "check_scheme", "check_single_contact", "scan_ends", "two_level_estimate"]

#: the first ``n`` of the two-level search when the user gives none (doubled until the estimate
#: meets the target); the projected pressure is exact for any ``n``, so it stops at the first pair
DEFAULT_N = 64
DEFAULT_SCHEME = "projected"
MAX_PLAIN_N = 4096
#: angles of the two-level estimate: uniform in θ over the contact (the sqrt ends resolved)
ESTIMATE_POINTS = 1025
#: distances from a join, in half-widths, at which the two-level estimate also compares (the
#: kink's (x - b) ln|x - b| is where a truncated series was coarsest)
ESTIMATE_OFFSETS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7)


@dataclass(frozen=True)
class SieNormalResult(NormalResult):
    """Normal solution from :func:`solve_normal`, with its discretisation.

    Its ``diagnostics`` hold ``n`` (Gauss–Chebyshev nodes for ``"plain"``, sine
    terms for ``"projected"``), ``scheme``, the Newton ``iterations`` and
    ``residual``, and the time.

    Attributes
    ----------
    density
        The pressure representation that :meth:`pressure` evaluates.
    """

    density: ChebyshevPressure | None = field(default=None, repr=False, compare=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure at ``x``, interpolated between nodes; 0 outside ``[-a, c]``."""
        assert self.density is not None
        return self.density(x)


def check_scheme(scheme: str, n: int) -> Plain | Projected:
    """Validate ``scheme`` and ``n`` and build the scheme."""
    n = check_n(n)
    if scheme == "plain" and n > MAX_PLAIN_N:
        raise InputError(f"`n` = {n} exceeds {MAX_PLAIN_N}, the largest plain collocation "
                         "system factorised here (use scheme='projected')")
    return make_scheme(scheme, n)


def check_normal(punch: Punch, P: float, s: float, A: float, tilt: str, n: int,
                  scheme: str) -> tuple[float, float, float, Plain | Projected]:
    """Validate before any numerics; return ``P``, ``s``, ``A`` as float64 and the scheme."""
    check_punch(punch)
    P, A = positive("P", P), positive("A", A)
    s = lever_arm(punch, s)
    check_tilt(tilt)
    if tilt == "suppressed" and s != 0:
        raise InputError(f"`s` = {s!r} must be 0 with tilt='suppressed': the centroid is returned")
    load_scale(punch, P, A)
    return P, s, A, check_scheme(scheme, n)


def solve_ends(punch: Punch, A: float, P: float, sch: Plain | Projected, *,
               s: float | None = None, alpha: float | None = None,
               m0: float = 0.0, h0: float | None = None) -> tuple[float, float, np.ndarray, int, float]:
    """Find the ends ``m ± h`` of a bounded pressure of load ``P``.

    Exactly one of ``s`` (centroid given, tilt free) and ``alpha`` (tilt
    given) must be set. Used for the contact and, in :mod:`sie.slip`, for the
    stick zone.

    Returns
    -------
    m, h, G, iterations, residual
        ``G`` holds ``(G_0, G_1, G_2)`` at the solution.

    Raises
    ------
    NoConvergenceError
        If the bracketing or the Newton iteration fails.
    """
    if (s is None) == (alpha is None):
        raise InputError("exactly one of `s` and `alpha` must be given")
    scale_h = h0 if h0 is not None else max(punch.b, math.sqrt(2 * P * A * max(punch.R1, punch.R2) / math.pi))
    k = math.pi / (2 * A * P)

    def load(h: float) -> float:
        return k * h * float(sch.moments(punch, m0, h)[0][1]) - 1.0

    h_start = bracket_root(load, scale_h, what="sie: initial contact width")
    slope_scale = 1.0 / (k * h_start)

    def residual(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m, h = z
        G, J = sch.moments(punch, m, h)
        r0 = k * h * G[1] - 1.0
        j0 = [k * h * J[1, 0], k * (G[1] + h * J[1, 1])]
        if s is not None:
            r1 = (m + 0.5 * k * h * h * G[2] - s) / h_start
            j1 = [(1.0 + 0.5 * k * h * h * J[2, 0]) / h_start,
                  0.5 * k * (2 * h * G[2] + h * h * J[2, 1]) / h_start]
        else:
            r1 = (alpha + G[0]) / slope_scale
            j1 = [J[0, 0] / slope_scale, J[0, 1] / slope_scale]
        return np.array([r0, r1]), np.array([j0, j1])

    z, its, res = newton(residual, np.array([m0, h_start]),
                         what=f"sie.{sch.name}: contact ends for P = {P:g}")
    m, h = float(z[0]), float(z[1])
    return m, h, sch.moments(punch, m, h)[0], its, res


def _gap_slope_outside(punch: Punch, m: float, h: float, alpha: float, xi: np.ndarray,
                       nterms: int = 2048) -> np.ndarray:
    """Slope of the gap at ``x = m + h ξ`` outside the contact (``|ξ| > 1``).

    With the exact slope coefficients ``G_k`` (:mod:`sie.projection`) the
    pressure is ``Σ (G_k/A) sin kθ``, and outside the contact

        (1/π) ∫ √(1-s²) U_{k-1}(s)/(ξ - s) ds = ρ^k,   ρ = ξ - sgn ξ √(ξ² - 1),

    so the gap's slope is ``v'(x) - α - Σ_{k>=1} G_k ρ^k``; it vanishes at the
    ends of a bounded solution.
    """
    G = slope_coefficients(punch, m, h, nterms)[0]
    rho = xi - np.sign(xi) * np.sqrt(xi * xi - 1.0)
    series = rho * power_series(G[1:], rho)    # Σ_{k>=1} G_k ρ^k, Horner
    return punch.slope(m + h * xi, alpha) - series


def check_single_contact(punch: Punch, A: float, P: float, s: float, m: float, h: float,
                          alpha: float) -> None:
    """Refuse a one-contact solution that is not one: tensile pressure, or penetration outside.

    Only a concave centre (``R < 0``) can fail; with ``v'' >= 0`` everywhere
    the bounded solution is non-negative and the gap opens outside it. The
    pressure is sampled with 2048 sine terms and counts as tensile only below
    minus the scheme's own pointwise truncation bound, so that a contact at
    its separation load is not refused for the series' error. The gap is
    integrated outwards from each end over the punch's joins and one more
    half-width, where the profile is convex again.

    Raises
    ------
    SeparationError
        If the pressure is tensile, or the punch penetrates the half-plane
        outside the contact: the true contact has two zones.
    """
    if punch.kappa0 >= 0 or punch.b == 0:
        return
    p, extra = Projected(2048).pressure(punch, A, m, h)
    theta = np.linspace(0, np.pi, 1601)[1:-1]
    val = p(m + h * np.cos(theta))
    i = int(np.argmin(val))
    if val[i] < -extra["pressure_bound"] - 1e-12 * float(np.max(val)):
        raise SeparationError(
            f"`P` = {P:g} with `s` = {s:g}: the one-contact pressure is tensile "
            f"(min {val[i]:.3g} at x = {m + h * np.cos(theta[i]):.4g}) for R = {punch.R:g}; "
            "the contact separates into two zones")
    t = np.linspace(0.0, 1.0, 801)[1:]
    for side in (1.0, -1.0):
        # out to the far join plus one half-width, points clustered at the end (√ behaviour)
        reach = max(0.0, (punch.b - side * m) / h - 1.0) + 1.0
        xi = side * (1.0 + reach * t * t)
        x = np.concatenate([[m + side * h], m + h * xi])
        slope = np.concatenate([[0.0], _gap_slope_outside(punch, m, h, alpha, xi)])
        gap = np.concatenate([[0.0], np.cumsum(0.5 * (slope[1:] + slope[:-1]) * np.diff(x))])
        scale = h * float(np.max(np.abs(slope)))
        j = int(np.argmin(gap))
        if gap[j] < -1e-6 * scale:
            raise SeparationError(
                f"`P` = {P:g} with `s` = {s:g}: the one-contact solution on [{m - h:.6g}, "
                f"{m + h:.6g}] would penetrate the half-plane at x = {x[j]:.4g} (gap "
                f"{gap[j]:.3g}) for R = {punch.R:g}; the contact separates into two zones")


def scan_ends(punch: Punch, A: float, P: float, sch: Plain | Projected, *,
               s: float | None = None, alpha: float | None = None,
               points: int = 161) -> list[tuple[float, float, np.ndarray, int, float]]:
    """Every single contact ``m ± h`` of load ``P`` with centroid ``s`` (or tilt ``α``), by a scan.

    A concave centre can have several single-contact solutions of the
    equations, or none; Newton from one start finds at most one. Here the
    load fixes ``h(m)`` along the contact centre ``m`` (a bracketed root), and
    the centroid (or consistency) residual is scanned over ``m`` and each sign
    change closed by Brent's method. Each root is returned as
    :func:`solve_ends` returns its one (``iterations`` = -1).
    """
    k = math.pi / (2 * A * P)
    scale = max(punch.b, math.sqrt(2 * P * A * max(punch.R1, punch.R2) / math.pi))

    def ends(m: float) -> tuple[float, np.ndarray]:
        h = bracket_root(lambda h: k * h * float(sch.moments(punch, m, h)[0][1]) - 1.0, scale,
                         what="sie: contact width")
        return h, sch.moments(punch, m, h)[0]

    def miss(m: float) -> float:
        try:
            h, G = ends(m)
        except NoConvergenceError:
            return math.nan
        if s is not None:
            return (m + 0.5 * k * h * h * float(G[2]) - s) / scale
        return (float(alpha or 0.0) + float(G[0])) * scale * k    # over the load's slope scale

    centre = 0.0 if s is None else s
    ms = centre + scale * np.linspace(-4.0, 4.0, points)
    vals = np.array([miss(float(m)) for m in ms])
    found = []
    for i in np.flatnonzero(np.isfinite(vals[:-1]) & np.isfinite(vals[1:])
                            & (np.sign(vals[:-1]) != np.sign(vals[1:]))):
        m = float(brentq(miss, ms[i], ms[i + 1], xtol=1e-15 * scale, rtol=1e-15))
        res = abs(miss(m))
        if res < 1e-10:   # a root, not a jump of the residual
            h, G = ends(m)
            found.append((m, h, G, -1, res))
    return found


def _estimate_points(res: SieNormalResult) -> np.ndarray:
    """Where the two-level estimate compares: uniform in θ, and next to the joins inside the contact."""
    m, h = 0.5 * (res.c - res.a), 0.5 * (res.a + res.c)
    theta = np.linspace(0.0, np.pi, ESTIMATE_POINTS)[1:-1]
    near = [j + side * h * d for j in (-res.punch.b, res.punch.b) for side in (-1.0, 1.0)
            for d in ESTIMATE_OFFSETS]
    x = np.concatenate([m + h * np.cos(theta), near])
    return x[(x > -res.a) & (x < res.c)]


def two_level_estimate(fine: SieNormalResult, coarse: SieNormalResult) -> float:
    """``max |p_fine - p_coarse| / max p_fine`` at :func:`_estimate_points` of the fine contact.

    The error estimate of the coarser of two solves (``n`` and ``2n``, or
    ``n/2`` and ``n``), and so a bound for the finer one when the pressure converges.
    """
    x = _estimate_points(fine)
    pf = fine.pressure(x)
    return float(np.max(np.abs(pf - coarse.pressure(x))) / np.max(np.abs(pf)))


def solve_normal(punch: Punch, P: float, s: float = 0.0, *, A: float, tilt: str = "free",
                 n: int | None = None, scheme: str = DEFAULT_SCHEME) -> SieNormalResult:
    """Contact ``[-a, c]``, tilt ``α`` and pressure for load ``P`` at lever arm ``s``.

    Parameters
    ----------
    punch
        Three-part punch geometry (paper eq. 2).
    P
        Compressive load, > 0 (eq. vertical).
    s
        Lever arm of the load, positive to the right, = pressure centroid
        (eq. rotational). Must be 0 for ``tilt="suppressed"``.
    A
        Compliance (eq. 4), > 0.
    tilt
        ``"free"``: ``α`` follows from consistency, ``s`` is imposed.
        ``"suppressed"``: ``α = 0``, ``s`` is returned.
    n
        Nodes (``"plain"``) or sine terms (``"projected"``), >= 2. ``None``
        (default): chosen by the two-level estimate, ``n`` and ``2n`` from
        ``DEFAULT_N`` doubled until the estimate meets the target
        ``tolerance("sie-target", "pressure")`` (1e-6 of the peak).
    scheme
        ``"projected"`` (kink-aware, default) or ``"plain"`` collocation;
        see :mod:`sie.schemes`.

    Returns
    -------
    SieNormalResult
        ``method="sie"``; ``diagnostics`` hold ``n``, ``scheme``, the Newton
        ``iterations`` and ``residual`` and the time; ``info`` holds
        ``error_estimate`` (:func:`two_level_estimate`, of the peak, against
        ``n/2`` when ``n`` is given, else against ``2n``) and, for the
        projected scheme, ``pressure_bound`` (bound on its pointwise rounding).

    Raises
    ------
    TypeError
        A ``punch`` that is not a :class:`Punch`, a number or ``n`` of the wrong type.
    ValueError
        For invalid input: ``P``, ``A`` outside ``LENGTH_RANGE``, ``s`` outside
        the punch's footprint (:func:`threepart.problem.validate.lever_arm`), ``n``
        outside ``[2, MAX_N]``.
    SeparationError
        A concave centre whose single contact would be tensile or penetrate.
    ArcExtentError, SlopeLimitError
        The solved contact runs past an arc or past the small-slope limit
        (:func:`threepart.problem.validate.check_contact`).
    NoConvergenceError
        If the Newton iteration fails, or (``n`` not given) the estimate has not
        met the target at the scheme's largest ``n``.
    """
    P, s, A, sch = check_normal(punch, P, s, A, tilt, DEFAULT_N if n is None else n, scheme)
    t0 = time.perf_counter()
    if n is not None:
        res = _solve_at(punch, P, s, A, tilt, sch)
        est = two_level_estimate(res, _solve_at(punch, P, s, A, tilt, make_scheme(scheme, max(2, n // 2))))
        return _with_estimate(res, est, t0)
    target = tolerance("sie-target", "pressure").limit
    largest = MAX_PLAIN_N if scheme == "plain" else MAX_N
    coarse = _solve_at(punch, P, s, A, tilt, sch)
    while 2 * sch.n <= largest:
        sch = make_scheme(scheme, 2 * sch.n)
        fine = _solve_at(punch, P, s, A, tilt, sch)
        est = two_level_estimate(fine, coarse)
        if est <= target:
            return _with_estimate(fine, est, t0)
        coarse = fine
    raise NoConvergenceError(
        f"sie.{scheme}: the pressure did not reach {target:g} of its peak by n = {sch.n} "
        f"(two-level estimate {est:.2g} against n = {sch.n // 2}); pass `n` to accept a coarser result")


def _with_estimate(res: SieNormalResult, est: float, t0: float) -> SieNormalResult:
    """``res`` with ``info["error_estimate"]`` and the whole search's time."""
    diagnostics = dataclasses.replace(res.diagnostics, timings={"total": time.perf_counter() - t0})
    return dataclasses.replace(res, diagnostics=diagnostics, info={**res.info, "error_estimate": est})


def _solve_at(punch: Punch, P: float, s: float, A: float, tilt: str,
              sch: Plain | Projected) -> SieNormalResult:
    """One solve with the scheme ``sch`` (validated input): the body of :func:`solve_normal`."""
    t0 = time.perf_counter()
    target: dict[str, float] = {"s": s} if tilt == "free" else {"alpha": 0.0}
    try:
        found = [solve_ends(punch, A, P, sch, m0=s, **target)]
    except NoConvergenceError:
        if punch.kappa0 >= 0:
            raise   # a convex or flat centre has one single contact: Newton must find it
        found = []
    refusals: list[SeparationError] = []

    def single(candidates: list[tuple[float, float, np.ndarray, int, float]]) -> tuple | None:
        """The first candidate that is one contact, with its α and s (refusals kept)."""
        for m, h, G, its, res in candidates:
            alpha = -float(G[0]) if tilt == "free" else 0.0
            s_out = float(s) if tilt == "free" else m + math.pi * h * h * float(G[2]) / (4 * A * P)
            try:
                check_single_contact(punch, A, P, s_out, m, h, alpha)
            except SeparationError as exc:
                refusals.append(exc)
                continue
            return m, h, G, its, res, alpha, s_out
        return None

    chosen = single(found)
    if chosen is None and punch.kappa0 < 0:
        # a concave centre: look for every single contact that carries P at s
        chosen = single(scan_ends(punch, A, P, sch, s=target.get("s"), alpha=target.get("alpha")))
    if chosen is None:
        raise refusals[0] if refusals else SeparationError(
            f"`P` = {P:g} with `s` = {s:g}: no single contact of the concave centre R = "
            f"{punch.R:g} carries the load; the contact separates into two zones")
    m, h, G, its, res, alpha, s_out = chosen
    check_contact(punch, h - m, h + m, alpha)
    density, extra = sch.pressure(punch, A, m, h)
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, iterations=its, residual=res,
                              timings={"total": time.perf_counter() - t0})
    return SieNormalResult(punch=punch, A=float(A), a=h - m, c=h + m, alpha=alpha, P=float(P),
                           s=s_out, tilt=tilt, method="sie", diagnostics=diagnostics,
                           info=dict(extra), density=density)


def lift_off(punch: Punch, P: float, A: float) -> tuple[float, float]:
    """Lever arms ``(s_min, s_max)`` at which a contact edge reaches a join ``x = ±b`` (tilt free).

    At ``s_max`` the left edge sits at ``-b`` (``a = b``); at ``s_min`` the right
    edge sits at ``+b`` (``c = b``). The contact width follows from the exact
    projected load equation along that family, so the closed form's
    admissible range (its edges on the outer segments) can be checked
    independently. Beyond it :func:`solve_normal` still solves. A lift-off
    contact past an arc's extent is refused as :func:`solve_normal` refuses
    it (``ArcExtentError`` naming ``P``).
    """
    check_punch(punch)
    P, A = positive("P", P), positive("A", A)
    load_scale(punch, P, A)
    if punch.b == 0:
        raise InputError("`punch`.b = 0: there is no join to lift off from (case C / Hertz)")
    sch = Projected(2)
    k = math.pi / (2 * A * P)
    out = []
    for sign in (-1.0, 1.0):  # sign = +1: left edge at -b, m = h - b
        def load(h: float, sign: float = sign) -> float:
            return k * h * float(sch.moments(punch, sign * (h - punch.b), h)[0][1]) - 1.0
        h = bracket_root(load, 2 * punch.b, what="sie.lift_off: contact width")
        m = sign * (h - punch.b)
        G = sch.moments(punch, m, h)[0]
        out.append(m + 0.5 * k * h * h * float(G[2]))
        try:   # on the arcs, as solve_normal's contacts and the closed form's lift_off
            check_arcs(punch, h - m, h + m)
        except ValueError as exc:
            raise type(exc)(f"`P` = {P:.6g} has no lift-off lever arm {('s_min', 's_max')[sign > 0]} = "
                            f"{out[-1]:.6g}: {exc}") from None
    return out[0], out[1]

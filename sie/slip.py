"""Partial slip by the Ciavarella–Jäger superposition, stick zone from the discretised equations.

With elastically similar bodies the shear problem (paper eq.
integral_equation_tangential) uncouples from the normal one, and the shear is

    q(x) = sign(Q) f [p(x) - p*(x)],

where ``p`` is the normal pressure on ``[-a, c]`` and the corrective ``p*`` is
the bounded solution of the *same* equation (same ``v'``, same tilt ``α``) on
the stick zone ``[-(d+e), d-e]`` (eq. integral_equation_2), with load
``P* = P - |Q|/f`` (eq. horizontal_equilibrium). The two stick-zone ends follow
from the discretised consistency and load equations exactly as the contact ends
do in :mod:`sie.normal` (:func:`sie.normal.solve_ends` with ``α`` given), so
``d = h*`` and ``e = -m*``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from threepart.halfplane.bulk import check_sigma_bulk, corrective_tilt, slip_direction_margin
from threepart.problem.validate import SLIP_RATIO_LIMIT
from threepart.results.slip import check_shear
from threepart.errors import (InputError, NoConvergenceError, SeparationError, SlipReversalError,
                              StickSeparationError)
from threepart.results import Diagnostics, NormalResult, SlipResult

from .normal import (DEFAULT_N, DEFAULT_SCHEME, check_scheme, check_single_contact, scan_ends,
                     solve_ends)
from .schemes import Plain, Projected
from .series import ChebyshevPressure

__all__ = ["SieSlipResult", "solve_partial_slip", "stick_zone", "coulomb_violation",
           "stick_zone_by_continuation", "check_slip_direction", "PATH_STATES"]


@dataclass(frozen=True)
class SieSlipResult(SlipResult):
    """Partial-slip solution from :func:`solve_partial_slip`.

    Its ``diagnostics`` hold the discretisation of the corrective pressure
    ``p*`` (``n``, ``scheme``), the Newton ``iterations`` and ``residual``.

    Attributes
    ----------
    stick
        The corrective pressure ``p*`` on the stick zone (zero outside).
    """

    stick: ChebyshevPressure | None = field(default=None, repr=False, compare=False)

    def corrective(self, x: ArrayLike) -> np.ndarray:
        """Corrective pressure ``p*(x)`` (0 outside the stick zone)."""
        assert self.stick is not None
        return self.stick(x)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear ``q = sign(Q) f (p - p*)``; has the sign of ``Q`` and integrates to ``Q``."""
        return math.copysign(1.0, self.Q) * self.f * (self.normal.pressure(x) - self.corrective(x)) \
            if self.Q != 0 else np.zeros(np.shape(x))


def coulomb_violation(normal: NormalResult, P_star: float, m: float, h: float,
                      alpha: float | None = None) -> str | None:
    """Why the stick zone ``m ± h`` (load ``P_star``) breaks Coulomb's law, or None if it does not.

    ``|q| <= f p`` needs ``0 <= p* <= p`` on the stick zone; the slip in the
    slip zones opposes the shear only if the corrective contact's gap stays
    open outside the stick zone. Only a concave centre can fail: then ``p*``
    and its gap are checked as a normal contact's (:func:`sie.normal.check_single_contact`),
    and ``p - p*`` at 1599 points clustered at the stick zone's ends. ``alpha`` is the
    corrective contact's tilt (``normal.alpha`` by default; shifted under a bulk stress).
    """
    punch, A = normal.punch, normal.A
    if punch.kappa0 >= 0 or punch.b == 0:
        return None
    try:
        check_single_contact(punch, A, P_star, normal.s, m, h,
                             normal.alpha if alpha is None else alpha)
    except SeparationError as exc:
        return f"its corrective contact (load P* = {P_star:.6g}) separates: {exc}"
    p_star, extra = Projected(2048).pressure(punch, A, m, h)
    x = m + h * np.cos(np.linspace(0, np.pi, 1601)[1:-1])
    excess = normal.pressure(x) - p_star(x)
    i = int(np.argmin(excess))
    tol = extra["pressure_bound"] + 1e-9 * normal.P / (normal.a + normal.c)
    if excess[i] < -tol:
        return f"its corrective pressure exceeds p by {-excess[i]:.4g} at x = {x[i]:.6g}"
    return None


#: the least number of load steps of the continuation from the contact (P* = P) to P*
CONTINUATION_STEPS = 16
#: the largest ratio between the loads of two continuation steps (near full sliding
#: P*/P is tiny, and the steps are geometric)
CONTINUATION_RATIO = 2.0


def stick_zone_by_continuation(normal: NormalResult, P_star: float, sch: Plain | Projected,
                               alpha: float | None = None) -> tuple[float, float, int, float]:
    """The stick zone at ``P_star`` by continuation in the load from the contact itself.

    Newton from the scaled contact can fall into a minimum of the residual
    that is not a root (a sharp corner arc next to the stick zone's end makes
    the tilt equation stiff); stepping ``P*`` down from ``P`` in
    geometric steps (at least :data:`CONTINUATION_STEPS`, each at most a factor
    :data:`CONTINUATION_RATIO`), each started from the last, keeps every start
    in its root's basin.
    """
    alpha0 = normal.alpha        # the tilt goes to `alpha` (bulk stress) in proportion to ln P*
    alpha = alpha0 if alpha is None else alpha
    m, h = 0.5 * (normal.c - normal.a), 0.5 * (normal.a + normal.c)
    its = 0
    res = 0.0
    total = math.log(normal.P / P_star)          # the path in ln P*, from 0 to `total`
    step = min(total / CONTINUATION_STEPS, math.log(CONTINUATION_RATIO))
    done = 0.0
    while done < total:
        # a failed step is halved (a stick-zone end crossing a join makes the equations kink)
        t = min(done + step, total)
        load = P_star if t == total else normal.P * math.exp(-t)
        tilt = alpha if t == total else alpha0 + (alpha - alpha0) * t / total
        try:
            m1, h1, _, it, res = solve_ends(normal.punch, normal.A, load, sch, alpha=tilt,
                                            m0=m, h0=h)
        except NoConvergenceError:
            step *= 0.5
            if step < 1e-6 * total:
                raise
            continue
        m, h, done, its = m1, h1, t, its + it
    return m, h, its, res


def stick_zone(normal: NormalResult, Q: float, f: float, sch: Plain | Projected,
               sigma_bulk: float = 0.0) -> tuple[float, float, int, float]:
    """``(m*, h*, iterations, residual)`` of the stick zone ``[m* - h*, m* + h*]`` for ``|Q| < f P``.

    Newton (:func:`sie.normal.solve_ends`, tilt held at ``normal.alpha``, shifted
    under a bulk stress by :func:`threepart.halfplane.bulk.corrective_tilt`) from
    the contact scaled by ``sqrt(P*/P)``. On a concave centre the equations may
    have several roots: a root that breaks Coulomb's law (:func:`coulomb_violation`) is
    set aside and the others are found by a scan (:func:`sie.normal.scan_ends`).

    Raises
    ------
    StickSeparationError
        If no single stick zone inside the contact obeys Coulomb's law.
    NoConvergenceError
        If no root is found at all.
    """
    punch, A = normal.punch, normal.A
    P_star = normal.P - abs(Q) / f
    alpha = float(corrective_tilt(normal.alpha, A, Q if Q else 1.0, f, sigma_bulk))
    m0 = 0.5 * (normal.c - normal.a)
    h0 = 0.5 * (normal.a + normal.c) * math.sqrt(P_star / normal.P)
    try:
        try:
            m, h, _, its, res = solve_ends(punch, A, P_star, sch, alpha=alpha, m0=m0, h0=h0)
        except NoConvergenceError:
            m, h, its, res = stick_zone_by_continuation(normal, P_star, sch, alpha)
        found = [(m, h, its, res)]
    except NoConvergenceError:
        if punch.kappa0 >= 0 or punch.b == 0:
            raise
        # a concave centre: every root of the stick-zone equations, by a scan
        found = [(mm, hh, it, rr) for mm, hh, _, it, rr in scan_ends(punch, A, P_star, sch, alpha=alpha)]
        if not found:
            raise StickSeparationError(
                f"`Q`/(f P) = {abs(Q) / (f * normal.P):.6g}: no single stick zone on the concave centre "
                f"R = {punch.R:g}; the corrective contact at P* = {P_star:g} separates into two zones, "
                "one on each flank, which the Ciavarella–Jäger superposition of one zone cannot model") from None
    ratio = abs(Q) / (f * normal.P)
    whys = []
    for k, (m, h, its, res) in enumerate(found):
        why = coulomb_violation(normal, P_star, m, h, alpha)
        if why is None:
            return m, h, its, res
        whys.append((m, h, why))
        if k == 0:      # a concave centre: every other root of the stick-zone equations
            found += [(mm, hh, it, rr) for mm, hh, _, it, rr in
                      scan_ends(punch, A, P_star, sch, alpha=alpha)
                      if abs(mm - m) > 1e-9 * h or abs(hh - h) > 1e-9 * h]
    if not whys:
        raise NoConvergenceError(f"sie: no stick zone found for `Q`/(f P) = {ratio:.6g}")
    m, h, why = whys[0]
    raise StickSeparationError(
        f"`Q`/(f P) = {ratio:.6g}: the single stick zone [{m - h:.6g}, {m + h:.6g}] of the "
        f"Ciavarella–Jäger superposition on the concave centre R = {punch.R:g} breaks Coulomb's "
        f"law: {why}; no other single stick zone obeys it, so the true stick zone is not one "
        "interval")


#: load fractions of the path ``(lam Q, lam sigma_bulk)`` at which the SIE checks the slip direction
PATH_STATES = 9


def check_slip_direction(normal: NormalResult, Q: float, f: float, sigma_bulk: float,
                         sch: Plain | Projected, top: tuple[float, float]) -> None:
    """Refuse a bulk stress that reverses the slip on the load path (:class:`SlipReversalError`).

    :func:`threepart.halfplane.bulk.slip_direction_margin` at ``lam = 0`` (the contact,
    exact), at :data:`PATH_STATES` - 2 interior fractions (stick zones by
    :func:`stick_zone`) and at ``lam = 1`` (``top = (m*, h*)``) must be ``>= 0``.
    The SIE does not model a reversed slip zone; it refuses by name.
    """
    if sigma_bulk == 0:
        return
    lam = np.linspace(0.0, 1.0, PATH_STATES)
    ends = [(-normal.a, normal.c)]
    for t in lam[1:-1]:
        m, h, _, _ = stick_zone(normal, t * Q, f, sch, t * sigma_bulk)
        ends.append((m - h, m + h))
    ends.append((top[0] - top[1], top[0] + top[1]))
    lo, hi = np.array(ends).T
    gl, gr = slip_direction_margin(Q, sigma_bulk, normal.a, normal.c, lo, hi)
    if min(gl.min(), gr.min()) >= -1e-9 * abs(Q):
        return
    end = "left" if gl.min() < gr.min() else "right"
    k = int(np.argmin(gl if end == "left" else gr))
    raise SlipReversalError(
        f"`sigma_bulk` = {sigma_bulk:.6g} reverses the slip at the {end} end of the contact with "
        f"`Q` = {Q:.6g} rising in proportion (from {lam[k]:.3g} of the load on); the SIE models "
        f"only slip that opposes q: at the start of the load path this needs |sigma_bulk| <= "
        f"8|Q|/(π (a + c)) = {8 * abs(Q) / (math.pi * (normal.a + normal.c)):.6g}")


def solve_partial_slip(normal: NormalResult, Q: float, f: float, *, n: int | None = None,
                       scheme: str | None = None, sigma_bulk: float = 0.0) -> SieSlipResult:
    """Stick zone ``[-(d+e), d-e]`` and shear ``q(x)`` for shear force ``Q`` and friction ``f``.

    Parameters
    ----------
    normal
        A normal solution (any method): its punch, ``A``, ``α``, ``P`` and
        ``pressure`` are used.
    Q
        Shear force the punch exerts on the substrate along +x, ``|Q| < f P``;
        the shear has its sign.
    f
        Coefficient of friction, > 0.
    n, scheme
        Discretisation of ``p*``; by default those of ``normal`` when it is
        an SIE result, else ``n = 1024`` and ``"projected"``.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q`` (tension positive), rising
        with ``Q`` in proportion: its strain ``A sigma_bulk/4`` enters the
        tangential equation, which shifts the corrective tilt
        (:func:`threepart.halfplane.bulk.corrective_tilt`, docs/BULK_STRESS.md).

    Returns
    -------
    SieSlipResult
        ``method="sie"``; ``diagnostics`` hold ``n``, ``scheme``, ``iterations``,
        ``residual`` and the time; ``info`` holds ``P_star`` and the scheme's
        ``pressure_bound``. Its ``within_paper`` says whether the
        stick zone contains the central segment, as the paper's closed form
        requires (end of its partial-slip section); a stick zone that ends on
        the central segment is solved all the same, as is one on a contact
        past lift-off.

    Raises
    ------
    TypeError
        ``normal`` not a NormalResult, a number of the wrong type.
    ValueError
        For invalid input (``FullSlidingError`` for ``|Q| >= f P``, and for
        ``|Q|/(fP)`` past ``threepart.problem.validate.SLIP_RATIO_LIMIT = 1 - 1e-6``).
    StickSeparationError
        On a concave centre, when no single stick zone obeys Coulomb's law
        ``|q| <= f p`` (the true one splits in two).
    SlipReversalError
        ``sigma_bulk`` reverses the slip at one end on the load path
        (:func:`check_slip_direction`).
    NoConvergenceError
        If the Newton iteration fails.
    """
    Q, f = check_shear(normal, Q, f, limit=SLIP_RATIO_LIMIT)
    sigma_bulk = check_sigma_bulk(sigma_bulk, normal, Q)
    n = (normal.diagnostics.n or DEFAULT_N) if n is None else n
    scheme = (normal.diagnostics.scheme or DEFAULT_SCHEME) if scheme is None else scheme
    sch = check_scheme(scheme, n)
    t0 = time.perf_counter()
    P_star = normal.P - abs(Q) / f
    punch, A = normal.punch, normal.A
    m, h, its, res = stick_zone(normal, Q, f, sch, sigma_bulk)
    d, e = h, -m
    lo, hi = m - h, m + h
    if sigma_bulk:
        check_slip_direction(normal, Q, f, sigma_bulk, sch, (m, h))
    if lo < -normal.a * (1 + 1e-12) or hi > normal.c * (1 + 1e-12):
        raise InputError(f"`Q` = {Q:g}: stick zone [{lo:.6g}, {hi:.6g}] leaves the contact "
                         f"[{-normal.a:.6g}, {normal.c:.6g}]; is `normal` consistent with its punch?")
    stick, extra = sch.pressure(punch, A, m, h)
    diagnostics = Diagnostics(n=sch.n, scheme=sch.name, iterations=its, residual=res,
                              timings={"total": time.perf_counter() - t0})
    return SieSlipResult(normal=normal, Q=float(Q), f=float(f), d=d, e=e, method="sie",
                         diagnostics=diagnostics, info={"P_star": P_star, **extra}, stick=stick,
                         sigma_bulk=sigma_bulk)

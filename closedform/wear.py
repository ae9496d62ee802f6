"""The worn limit of partial-slip fretting at constant ``P`` and ``s`` (docs/WEAR.md).

Under a fretting cycle ``Q: ±Q_max`` the permanent stick zone ``[-(d+e), d-e]``
is the Ciavarella–Jäger stick zone at ``Q_max`` (:mod:`closedform.fretting`).
Wear removes material only in the slip zones; in the limit the slip zones carry
no pressure and the punch's original profile over the stick zone ``[x1, x2]``
carries the whole load, with square-root singular pressure at its ends
(docs/WEAR.md, eq. W3)::

    p_L(x) = p'(x) + [C0 + C1 (x - m)] / w(x),      w = sqrt((x - x1)(x2 - x)),

``p'`` the bounded pressure of eq. (pressure_abbreviated) on ``[x1, x2]`` at
its consistent tilt, ``C0`` and ``C1`` the load and moment it leaves (eqs. W4,
W5); a free tilt changes by ``-A C1`` (eq. W6). Where a moment makes the slip
zones unload unequally (``C1 != 0``) the stick zone is placed by one of
:data:`STICK_RULES` (docs/WEAR.md, "The tilt"). The worn depth is the gap the
limit closes (eqs. W8, W9).

wear_limit   -- the limit state: ``pressure(x)``, ``depth(x)``, ``stick_zone``, ``worn_zone``, ``alpha``
WearLimit    -- its result
limit_depth  -- the gap the limit closes outside a stick zone (eq. W8)
STICK_RULES  -- "pinned", "held", "consistent"
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from threepart.errors import NoConvergenceError, StickZoneError
from threepart.problem.checks import finite
from threepart.problem.punch import Punch
from threepart.results import NormalResult

from . import formulas
from .fretting import fretting_iv, stick_gap
from .normal import solve_normal
from .slip import check_coulomb, stick_zone_bound, stick_zone_leaves, stick_zones_on_path

__all__ = ["WearLimit", "wear_limit", "limit_depth", "STICK_RULES"]

#: how the limit's stick zone is placed under a free tilt (docs/WEAR.md, section "The tilt"):
#: ``"pinned"`` the end the tilt would advance stays at the cycle's stick zone (the scar
#: holds it), the other recedes until its corrective pressure is bounded (eq. W12);
#: ``"held"`` both ends at the cycle's stick zone at ``Q_max`` (eq. W5; Coulomb's law
#: fails in a thin layer at one end when ``C1 != 0``); ``"consistent"`` both ends free,
#: ``C1 = 0`` (eq. W7). All three agree where ``C1 = 0`` (symmetric contacts, Hertz, a
#: suppressed tilt).
STICK_RULES = ("pinned", "held", "consistent")
#: the moment's rounding, of ``P h``: a held residual below it is ``C1 = 0`` (a few dozen operations)
_MOMENT_ROUNDING = 64 * np.finfo(float).eps
#: first inward step of the receding end (eq. W12), of the stick zone's half-width; doubled
_RECEDE_STEP = 1e-7
#: the scar's outer end is bracketed by steps of this fraction of the stick zone's width
_SCAR_STEP = 0.25
#: ... and at most this many steps outward before NoConvergenceError
_SCAR_STEPS = 400


def limit_depth(punch: Punch, x1: float, x2: float, C0: float, C1: float, A: float,
                x: ArrayLike) -> np.ndarray:
    """Gap the limit state closes outside ``[x1, x2]``: ``-G_L(x)`` of eq. (W8), 0 inside.

    ``G_L = G*(x) - A C0 arccosh|ξ| - A C1 h sign(ξ) sqrt(ξ^2 - 1)`` with
    ``ξ = (x - m)/h``, ``m, h`` the stick zone's centre and half-width and
    ``G*`` the gap of its corrective contact (:func:`closedform.fretting.stick_gap`).
    Positive where the original profile would penetrate the limit surface:
    there wear removed exactly this depth.
    """
    x = np.asarray(x, dtype=float)
    h, m = 0.5 * (x2 - x1), 0.5 * (x1 + x2)
    xi = (x - m) / h
    r = np.maximum(np.abs(xi), 1.0)
    closed = A * C0 * np.arccosh(r) + A * C1 * h * np.sign(xi) * np.sqrt(r * r - 1.0)
    return np.where(r > 1.0, closed - stick_gap(punch, -x1, x2, x), 0.0)


@dataclass(frozen=True)
class WearLimit:
    """The worn limit of a fretting cycle (:func:`wear_limit`, docs/WEAR.md).

    Attributes
    ----------
    normal
        The normal problem of the unworn punch.
    Q_max, f
        The cycle's shear amplitude and the coefficient of friction.
    stick_zone
        ``(x1, x2)``: the contact of the limit, which never slips; ``p'`` of eq. (W3) is
        eq. (pressure_abbreviated) on it.
    C0, C1
        The singular terms of eq. (W3): ``C0 = (P - P')/π`` (eq. W4; ``Q_max/(π f)`` for
        ``"held"`` and ``"consistent"``), ``C1`` of eq. (W5).
    alpha
        The limit's tilt, ``alpha' - A C1`` (eq. W6).
    P, s
        The load and its lever arm, carried by the stick zone alone.
    worn_zone
        ``(xw1, xw2)``: the outer ends of the wear scar (eq. W9), where the depth returns to 0.
    stick
        The rule of :data:`STICK_RULES` that placed the stick zone.
    """

    normal: NormalResult
    Q_max: float
    f: float
    stick_zone: tuple[float, float]
    C0: float
    C1: float
    alpha: float
    P: float
    s: float
    worn_zone: tuple[float, float]
    stick: str | tuple[float, float] = "pinned"

    @property
    def K(self) -> tuple[float, float]:
        """``lim p w`` at the left and right end of the stick zone: ``C0 ∓ C1 h`` (eq. W10).

        The limit is a fixed point of the wear (the stick zone holds at
        ``Q_max``, ``q/p -> f`` at both ends) when both equal ``Q_max/(π f)``.
        """
        h = 0.5 * (self.stick_zone[1] - self.stick_zone[0])
        return self.C0 - self.C1 * h, self.C0 + self.C1 * h

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure of the limit (eq. W3): 0 outside the stick zone, ``inf`` at its ends."""
        x = np.asarray(x, dtype=float)
        x1, x2 = self.stick_zone
        inside = (x > x1) & (x < x2)
        xi = np.where(inside, x, 0.5 * (x1 + x2))
        w = np.sqrt((xi - x1) * (x2 - xi))
        bounded = formulas.pressure(self.normal.punch, -x1, x2, self.normal.A, xi)
        value = bounded + (self.C0 + self.C1 * (xi - 0.5 * (x1 + x2))) / w
        return np.where(inside, value, np.where((x == x1) | (x == x2), np.inf, 0.0))

    def depth(self, x: ArrayLike) -> np.ndarray:
        """Worn depth (eq. W8): the gap the limit closes over the scar, 0 elsewhere.

        Over ``worn_zone`` less the stick zone the worn profile just touches the
        limit surface with zero pressure; beyond the scar nothing was worn. It is
        the two bodies' wear together, shared in any fixed proportion (docs/WEAR.md, section 4).
        """
        x = np.asarray(x, dtype=float)
        (x1, x2), (xw1, xw2) = self.stick_zone, self.worn_zone
        d = limit_depth(self.normal.punch, x1, x2, self.C0, self.C1, self.normal.A, x)
        return np.where((x > xw1) & (x < xw2), np.maximum(d, 0.0), 0.0)


def _scar_end(depth, start: float, step: float) -> float:
    """The first zero of ``depth`` beyond ``start`` in the direction of ``step`` (eq. W9)."""
    lo = start + 1e-9 * step
    for _ in range(_SCAR_STEPS):
        hi = lo + step
        if float(depth(hi)) <= 0.0:
            return float(brentq(lambda t: float(depth(t)), lo, hi, xtol=4e-15 * abs(step),
                                rtol=4 * np.finfo(float).eps))
        lo = hi
    raise NoConvergenceError(f"wear limit: the scar does not close within {_SCAR_STEPS} steps of "
                             f"{abs(step):.4g} beyond the stick zone; no result is returned")


def _held(normal: NormalResult, Q_max: float, f: float) -> tuple[float, float]:
    """The fretting cycle's stick zone at ``Q_max``, ``(a*, c*)`` (eqs. horizontal_equilibrium, consistency_condition)."""
    a_s, c_s, out = stick_zones_on_path(normal, Q_max, f, 0.0, [1.0])
    if out[0]:
        raise StickZoneError(
            f"`Q_max`/(f P) = {Q_max / (f * normal.P):.6g}: the stick zone at `Q_max` would "
            f"{stick_zone_leaves(normal.punch.b)}, where the closed form does not hold; it holds for "
            f"`Q_max`/(f P) < {stick_zone_bound(normal):.6g}")
    return float(a_s[0]), float(c_s[0])


def _consistent(normal: NormalResult, Q_max: float, f: float, held: tuple[float, float]
                ) -> tuple[float, float]:
    """The fixed point of eq. (W7): the normal contact at ``P*`` and the lever arm ``s*(m)``.

    ``P* s* = P s - (Q_max/f) m`` with ``m`` the contact's own centre: a scalar
    root in ``m`` (Brent), each step a closed-form normal solve.
    """
    P_star, F = normal.P - Q_max / f, Q_max / f

    def contact(m: float) -> tuple[float, float]:
        sol = solve_normal(normal.punch, P_star, (normal.P * normal.s - F * m) / P_star, A=normal.A)
        return sol.a, sol.c

    def residual(m: float) -> float:
        a, c = contact(m)
        return 0.5 * (c - a) - m

    m0, h0 = 0.5 * (held[1] - held[0]), 0.5 * (held[0] + held[1])
    lo, hi = m0 - 0.25 * h0, m0 + 0.25 * h0   # the fixed point moves m by ~1e-4 h (docs/WEAR.md)
    try:
        m = brentq(residual, lo, hi, xtol=1e-15 * h0, rtol=4 * np.finfo(float).eps)
    except ValueError:      # no sign change: the moment moves the contact by more than h/4
        raise StickZoneError(f"`stick` = 'consistent': no fixed point of eq. W7 within h/4 of the "
                             f"cycle's stick zone for s = {normal.s:.6g}") from None
    return contact(m)


def _terms(normal: NormalResult, a: float, c: float) -> tuple[float, float]:
    """``C0, C1`` of eq. (W3) on the contact ``[-a, c]``: the load and moment it leaves to the ``1/w`` terms."""
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    C0 = (normal.P - float(formulas.load(normal.punch, a, c, normal.A))) / math.pi
    if normal.tilt != "free":
        return C0, 0.0
    M = float(formulas.moment(normal.punch, a, c, normal.A))
    return C0, (normal.P * normal.s - M - math.pi * C0 * m) / (0.5 * math.pi * h * h)


def _pinned(normal: NormalResult, Q_max: float, f: float, held: tuple[float, float]
            ) -> tuple[float, float]:
    """Eq. (W12): the end with ``K > Q_max/(π f)`` held, the other receding until ``K = Q_max/(π f)``.

    The receding end ``z`` is a root of the moment's residual (Brent), bracketed
    by inward steps doubled from :data:`_RECEDE_STEP` of the half-width.
    """
    a0, c0 = held
    h0, C0 = 0.5 * (a0 + c0), Q_max / (math.pi * f)
    right = _terms(normal, a0, c0)[1] < 0          # the right end's K = C0 + C1 h falls short

    def contact(z: float) -> tuple[float, float]:
        return (a0, z) if right else (z, c0)

    def residual(z: float) -> float:
        a, c = contact(z)
        h, m = 0.5 * (a + c), 0.5 * (c - a)
        C0p = (normal.P - float(formulas.load(normal.punch, a, c, normal.A))) / math.pi
        C1p = (C0 - C0p) / h if right else (C0p - C0) / h
        M = float(formulas.moment(normal.punch, a, c, normal.A))
        return M + math.pi * C0p * m + 0.5 * math.pi * C1p * h * h - normal.P * normal.s

    z_hi = c0 if right else a0
    r_hi, step = residual(z_hi), _RECEDE_STEP * h0
    if abs(r_hi) <= _MOMENT_ROUNDING * normal.P * h0:     # C1 = 0 but for rounding: nothing recedes
        return held
    while True:
        z_lo = z_hi - step
        if z_lo < normal.punch.b:
            raise StickZoneError(f"the worn limit's stick zone would recede into the central segment "
                                 f"[-b, b] = [{-normal.punch.b:g}, {normal.punch.b:g}] at its "
                                 f"{'right' if right else 'left'} end, where the closed form does not hold")
        if (residual(z_lo) > 0) != (r_hi > 0):
            break
        step *= 2
    z = brentq(residual, z_lo, z_hi, xtol=1e-15 * h0, rtol=4 * np.finfo(float).eps)
    return contact(z)


def _place(normal: NormalResult, Q_max: float, f: float, stick: str | tuple[float, float]
           ) -> tuple[float, float]:
    """``(a, c)`` of the limit's contact ``[-a, c]`` by the rule ``stick`` (:data:`STICK_RULES`), or given."""
    if isinstance(stick, tuple):
        return -stick[0], stick[1]
    held = _held(normal, Q_max, f)
    check_coulomb(normal, held[0], held[1], Q_max / (f * normal.P))
    if stick == "held" or normal.tilt != "free" or _terms(normal, *held)[1] == 0:
        return held
    return _pinned(normal, Q_max, f, held) if stick == "pinned" else _consistent(normal, Q_max, f, held)


def _given(normal: NormalResult, stick: tuple) -> tuple[float, float]:
    """A given stick zone ``(x1, x2)``: finite, ordered, inside the contact, its ends on the outer segments."""
    if len(stick) != 2:
        raise ValueError(f"`stick` = {stick!r} must be a rule or a pair (x1, x2)")
    x1, x2 = (finite("stick", v) for v in stick)
    b = normal.punch.b
    if not (-normal.a <= x1 < -b and b < x2 <= normal.c):
        raise ValueError(f"`stick` = ({x1:.6g}, {x2:.6g}) must lie in the contact [{-normal.a:.6g}, "
                         f"{normal.c:.6g}] with its ends on the outer segments, beyond [-b, b] = [{-b:g}, {b:g}]")
    return x1, x2


def wear_limit(normal: NormalResult, Q_max: float, f: float, *,
               stick: str | tuple[float, float] = "pinned") -> WearLimit:
    """The worn limit of the fretting cycle ``±Q_max`` at the normal result's ``P`` and ``s`` (docs/WEAR.md).

    Parameters
    ----------
    normal
        The normal problem (any method) in the closed form's framework: its
        punch, ``A``, ``a``, ``c``, ``alpha``, ``P``, ``s`` and ``tilt`` are used.
    Q_max
        Shear amplitude of the cycle, ``0 < Q_max < f P``.
    f
        Coefficient of friction, > 0.
    stick
        Where the stick zone of the limit lies when the tilt is free and a
        moment makes the slip zones unload unequally (``C1 != 0``; docs/WEAR.md,
        "The tilt"): ``"pinned"`` (default) the end the tilt would advance stays at
        the cycle's stick zone at ``Q_max``, held by the scar, and the other recedes
        until its corrective pressure is bounded (eq. W12); ``"held"`` both ends stay
        (eq. W5; it breaks Coulomb's law in a thin layer at one end); ``"consistent"``
        both ends move to the fixed point ``C1 = 0`` on the unworn profile (eq. W7).
        The true limit lies between ``"pinned"`` and ``"consistent"``; all three are the
        cycle's stick zone where ``C1 = 0`` (a symmetric contact, Hertz, ``tilt="suppressed"``,
        where ``s`` becomes the support's lever arm). A pair ``(x1, x2)`` is a given stick
        zone: the limit that a marched history reached there (eqs. W3-W6 on it), which
        must lie on the outer segments.

    Returns
    -------
    WearLimit
        ``pressure(x)``, ``depth(x)``, ``stick_zone``, ``worn_zone``, ``alpha``, ``P``, ``s``.

    Raises
    ------
    TypeError
        ``normal`` not a NormalResult.
    ValueError
        ``Q_max`` or ``f`` not finite and > 0; ``stick`` not one of :data:`STICK_RULES`.
    FullSlidingError
        ``Q_max >= f P``.
    LiftOffError
        The normal contact ends on the central segment.
    StickZoneError
        The stick zone at ``Q_max`` would end on the central segment (the
        message gives the bound on ``Q_max/(f P)``), its corrective pressure
        breaks Coulomb's law (``StickSeparationError``, a concave centre), or
        the moment would make the limit's pressure tensile at an end (``K < 0``).
    """
    Q_max, f, _ = fretting_iv(normal, Q_max, f, 2)
    if isinstance(stick, tuple):
        stick = _given(normal, stick)
    elif stick not in STICK_RULES:
        raise ValueError(f"`stick` = {stick!r} must be one of {', '.join(STICK_RULES)} or a pair (x1, x2)")
    punch, A = normal.punch, normal.A
    a_s, c_s = _place(normal, Q_max, f, stick)
    x1, x2 = -a_s, c_s
    h, m = 0.5 * (x2 - x1), 0.5 * (x1 + x2)
    C0, C1 = _terms(normal, a_s, c_s)
    K = (C0 - C1 * h, C0 + C1 * h)
    if min(K) < 0:
        side = "left" if K[0] < 0 else "right"
        raise StickZoneError(
            f"`normal` (s = {normal.s:.6g}): the stick zone [{x1:.6g}, {x2:.6g}] cannot carry the "
            f"moment P s alone; its worn limit's pressure would be tensile at the {side} end")
    free = normal.tilt == "free"
    alpha = float(formulas.tilt(punch, a_s, c_s)) - A * C1 if free else normal.alpha
    M = float(formulas.moment(punch, a_s, c_s, A))
    s = normal.s if free else (M + math.pi * C0 * m) / normal.P

    def depth(t: float) -> float:
        return float(limit_depth(punch, x1, x2, C0, C1, A, t))

    worn = (_scar_end(depth, x1, -_SCAR_STEP * h), _scar_end(depth, x2, _SCAR_STEP * h))
    return WearLimit(normal=normal, Q_max=Q_max, f=f, stick_zone=(x1, x2),
                     C0=C0, C1=C1, alpha=alpha, P=normal.P, s=s, worn_zone=worn, stick=stick)

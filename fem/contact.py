"""Frictionless unilateral contact of a rigid punch on the condensed surface, under load control.

On the candidate nodes ``x_i`` with compliance ``C`` (``u_y = -C f``) the punch's
lower surface is ``y_p = g(x) + alpha x - delta``, with ``g`` the punch shape of
eq. (2). The gap and the complementarity conditions are::

    gap_i = g(x_i) + alpha x_i - delta + (C f)_i >= 0,   f_i >= 0,   f_i gap_i = 0,

with the load and its lever arm prescribed::

    sum f_i = P,    sum x_i f_i = P s        (tilt "free": alpha unknown)
    sum f_i = P,    alpha = 0                (tilt "suppressed": s is an output)

The active-set solve is the core's, :func:`threepart.halfplane.surface.solve_contact`
(the half-plane's wear march shares it); here it is wrapped at the FE package's boundary.

**Contact kinematics** (:data:`KINEMATICS`). ``"small"`` is the half-plane
theory's: the gap is measured vertically between the undeformed surfaces and
the contact force is vertical. ``"first_order"`` keeps the terms of first
order in the slopes that a contact formulation on the deformed surfaces adds
(:func:`first_order_compliance`): both are linear in ``f``, so the same
active-set solve takes a modified compliance.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any, Callable

import numpy as np

from threepart.errors import InputError, InputTypeError, NoConvergenceError
from threepart.halfplane.surface import ContactSolution
from threepart.halfplane.surface import solve_contact as _solve_contact

from ._boundary import boundary

__all__ = ["ContactSolution", "solve_contact", "KINEMATICS", "check_kinematics",
           "first_order_compliance", "solve_kinematic"]

#: the contact kinematics of :func:`fem.solve_normal` and :func:`fem.solve_finite`
KINEMATICS = ("small", "first_order")


def check_kinematics(kinematics: Any) -> str:
    """``kinematics`` if it is one of :data:`KINEMATICS`; ``TypeError``/``ValueError`` naming it."""
    if not isinstance(kinematics, str):
        raise InputTypeError(f"`kinematics` must be a str, one of {KINEMATICS}, "
                        f"not {type(kinematics).__name__}")
    if kinematics not in KINEMATICS:
        raise InputError(f"`kinematics` = {kinematics!r} must be one of {KINEMATICS}")
    return kinematics


def first_order_compliance(C2: np.ndarray, slope: np.ndarray) -> np.ndarray:
    """The compliance of the contact conditions on the deformed surfaces, to first order in the slopes.

    Parameters
    ----------
    C2
        The ``(2n, 2n)`` compliance of the relative surface displacement in the
        global directions, ``u_x`` then ``u_y`` (:func:`fem.elasticity.condense`
        with both components; for two bodies the sum of both, each in its own
        orientation): ``d = u^lower - u^upper = C2 F`` for the nodal force
        ``F`` the upper body exerts on the lower one.
    slope
        The punch's surface slope ``v'(x_i) = g'(x_i) + alpha`` (eq. 2) at the nodes.

    Returns
    -------
    numpy.ndarray
        ``(n, n)``: ``gap = g + alpha x - delta + C f`` for the downward nodal
        forces ``f`` (the vertical resultant is ``P = sum f``).

    Notes
    -----
    The lower surface is ``y = 0``, the punch's ``y = v(x) - delta`` with
    ``v = g + alpha x`` (eq. 2). Two first-order terms join the small-slope
    conditions:

    (i) *the gap between the deformed surfaces*: the lower surface point at
    ``x`` moves to ``x + d_x`` (relative to the punch) and faces the punch's
    face there, so ``gap = v(x + d_x) - delta - d_y = v - delta - d_y + v' d_x``;

    (ii) *the force along the punch's normal*: the punch's face ``y = v(x)``
    has the outward normal ``(v', -1)/sqrt(1 + v'^2)``, so a frictionless
    contact force ``f`` (down) carries a tangential force ``+v' f`` along
    ``+x`` on the lower body: outward, away from the lowest point of the
    profile, on both sides. The nodal force is ``F = (V f, -f)``, ``V = diag(v')``.

    With ``d_x = C_xx V f - C_xy f`` and ``d_y = C_yx V f - C_yy f``::

        gap = v - delta + (C_yy - C_yx V - V C_xy + V C_xx V) f,

    and the last term, of second order in the slope, is dropped. As
    ``C_xy = C_yx^T``, the result is symmetric (the two first-order terms are
    each other's transposes: the load is conservative to this order). ``P`` and
    ``P s`` stay the resultant and moment of the vertical forces; the
    tangential forces ``v' f`` sum to a horizontal reaction on the punch (zero
    for a symmetric contact) and act on the surface, where they have no moment
    arm about it.
    """
    n = len(slope)
    V = np.asarray(slope, dtype=float)
    C_xy, C_yx, C_yy = C2[:n, n:], C2[n:, :n], C2[n:, n:]
    return C_yy - C_yx * V[None, :] - V[:, None] * C_xy


solve_contact = boundary(_solve_contact)


#: fixed-point passes on the tilt's share of the slope in :func:`solve_kinematic` (and on the
#: secant's ``d_x``)
TILT_PASSES = 20
#: the secant's ``d_x`` has settled when a pass moves it by this share of its largest value:
#: the gap then moves by this share of ``d_x / R``. Measured at p0/E* = 0.21 (the map's heaviest
#: slope point): the nodal forces change by 3e-5, 2e-6, 3e-7 of their largest in the first
#: passes, then by a slow tail (x0.68 a pass) far below any FE error
D_X_SETTLED = 1e-5
#: the tilt has settled when a pass moves it by this share of the largest slope: to round-off
#: while only the tilt moves the slope; with the secant, whose d_x moves it too, the tilt
#: follows d_x's slow tail (by 1e-11 a pass at p0/E* = 0.21), and 1e-9 of the slope moves the
#: gap by 1e-9 of the contact's width
ALPHA_SETTLED, ALPHA_SETTLED_SECANT = 1e-12, 1e-9
#: below this share of the zone's width, ``|d_x|`` is too small for a secant: the tangent is used
#: (they differ by ``g'' d_x / 2``; the secant's rounding error grows as ``eps |g| / |d_x|``)
SECANT_MIN_STEP = 1e-6


def solve_kinematic(C: np.ndarray, x: np.ndarray, g0: np.ndarray, slope: np.ndarray, P: float,
                    s: float, *, kinematics: str, free_tilt: bool, max_iter: int,
                    active: np.ndarray | None = None,
                    face_common: Callable[[ContactSolution], np.ndarray] | None = None,
                    profile: Callable[[np.ndarray], np.ndarray] | None = None
                    ) -> ContactSolution:
    """:func:`solve_contact` with the contact kinematics ``kinematics`` (:data:`KINEMATICS`).

    Parameters
    ----------
    C
        ``(n, n)`` vertical compliance for ``"small"``; ``(2n, 2n)`` compliance of
        both components (:func:`first_order_compliance`) for ``"first_order"``.
    slope
        The profile's slope ``g'(x_i)`` at the nodes, without the tilt (eq. 2).
    kinematics, free_tilt, max_iter, active
        As :func:`solve_contact`; ``kinematics`` is checked by the caller.
    face_common
        For an elastic punch: the two faces' common vertical displacement
        ``u_y^lower + u_y^upper`` at the nodes of a solution (zero for two
        similar half-planes; the finite punch's own bending and rotation). The
        solve is then repeated once with the slope of the deformed interface in
        place of ``g' + alpha``: ``u_y^lower = (common + relative) / 2``, and in
        contact the relative displacement closes the gap, so its slope is the
        profile's (the secant, with ``profile``) and the interface's slope is
        ``(g' + alpha + common') / 2``; outside the contact the same expression
        carries it on. Taking the relative part from the profile rather than
        from the FE displacement keeps the pressure's roughness out of the
        slope (a 1 % wiggle of ``p`` moves a surface slope by about
        ``0.01 p/E*``; the two bodies' shares cancel in ``common``). The slope
        enters multiplied by the normal-tangential coupling, so one correction
        is consistent to first order (a fixed point on it does not settle: the
        nodal surface slope at the contact's ends feeds back). ``None``: a rigid
        punch, whose face keeps the slope ``g' + alpha``.
    profile
        The profile's height ``g(x)`` (eq. 2, without the tilt), exact off the
        nodes too. The gap's first-order term ``g(x + d_x) - g(x)`` is then
        taken as the secant slope over ``[x, x + d_x]`` times ``d_x``, with the
        relative tangential displacement ``d_x`` of the pass before, in place of
        the tangent ``g'(x) d_x``: where the profile's curvature jumps (``x = +-b``,
        the centre joining an edge), ``g' d_x`` kinks by ``d_x / R`` and puts a
        spurious pressure spike on the join (10 % at ``p0/E* = 0.12``, larger than
        the peak at 0.15); the secant is as smooth as ``g`` itself and equal to
        the tangent to first order. ``None``: the tangent ``slope``.

    Returns
    -------
    ContactSolution
        With ``slope`` the surface slope its forces act along (zeros for
        ``"small"``: vertical forces).

    Raises
    ------
    NoConvergenceError
        As :func:`solve_contact`, or if the tilt does not settle: a rigid
        punch's slope ``g' + alpha`` holds the unknown tilt, found by fixed-point
        passes (each a linear contact problem) until ``alpha`` changes by under
        :data:`ALPHA_SETTLED` of the largest slope (with ``profile``,
        :data:`ALPHA_SETTLED_SECANT`, and ``d_x`` by under :data:`D_X_SETTLED` of
        its largest), at most :data:`TILT_PASSES`.
    """
    if kinematics == "small":
        sol = solve_contact(C, x, g0, P, s, free_tilt=free_tilt, max_iter=max_iter, active=active)
        return replace(sol, slope=np.zeros(len(x)))
    sol, V = _settle_tilt(C, x, g0, slope, P, s, free_tilt, max_iter, active, profile)
    if face_common is None:
        return replace(sol, slope=V)
    V = 0.5 * (V + np.gradient(face_common(replace(sol, slope=V)), x))
    sol = solve_contact(first_order_compliance(C, V), x, g0, P, s, free_tilt=free_tilt,
                        max_iter=max_iter, active=sol.active)
    return replace(sol, slope=V)


def _settle_tilt(C: np.ndarray, x: np.ndarray, g0: np.ndarray, slope: np.ndarray, P: float, s: float,
                 free_tilt: bool, max_iter: int, active: np.ndarray | None,
                 profile: Callable[[np.ndarray], np.ndarray] | None
                 ) -> tuple[ContactSolution, np.ndarray]:
    """:func:`solve_kinematic`'s fixed-point passes on the tilt (and ``d_x`` with ``profile``):
    the settled solution and the slope ``V`` its forces act along."""
    n = len(x)
    alpha, change, d_x, moved = 0.0, np.inf, None, np.inf
    for _ in range(TILT_PASSES):
        V = (slope if d_x is None or profile is None else _secant(profile, x, d_x, slope)) + alpha
        sol = solve_contact(first_order_compliance(C, V), x, g0, P, s, free_tilt=free_tilt,
                            max_iter=max_iter, active=active)
        active, change = sol.active, sol.alpha - alpha
        # the tilt to round-off when only it moves V; to the secant's share when d_x moves V too
        tol = ALPHA_SETTLED if profile is None else ALPHA_SETTLED_SECANT
        settled = abs(change) <= tol * (float(np.max(np.abs(V))) + abs(sol.alpha))
        if profile is not None:
            d_new = (C @ np.concatenate([V * sol.f, -sol.f]))[:n]
            moved = np.inf if d_x is None else float(np.max(np.abs(d_new - d_x)))
            settled = settled and moved <= D_X_SETTLED * float(np.max(np.abs(d_new)))
            d_x = d_new
        if settled:
            break
        alpha = sol.alpha
    else:
        raise NoConvergenceError(f"the tilt of the first-order contact did not settle in "
                                 f"{TILT_PASSES} passes (last change {change:.3g}"
                                 + (f", of d_x {moved:.3g})" if profile is not None else ")"))
    return sol, V


def _secant(profile: Callable[[np.ndarray], np.ndarray], x: np.ndarray, d_x: np.ndarray,
            slope: np.ndarray) -> np.ndarray:
    """``(g(x + d_x) - g(x)) / d_x``, the tangent ``slope`` where ``|d_x|`` is too small for it."""
    tiny = np.abs(d_x) <= SECANT_MIN_STEP * float(np.ptp(x))
    step = np.where(tiny, 1.0, d_x)
    return np.where(tiny, slope, (profile(x + step) - profile(x)) / step)

"""Frictionless unilateral contact of a rigid punch on the condensed surface, under load control.

On the candidate nodes ``x_i`` with compliance ``C`` (``u_y = -C f``) the punch's
lower surface is ``y_p = g(x) + alpha x - delta``, with ``g`` the punch shape of
eq. (2). The gap and the complementarity conditions are::

    gap_i = g(x_i) + alpha x_i - delta + (C f)_i >= 0,   f_i >= 0,   f_i gap_i = 0,

with the load and its lever arm prescribed::

    sum f_i = P,    sum x_i f_i = P s        (tilt "free": alpha unknown)
    sum f_i = P,    alpha = 0                (tilt "suppressed": s is an output)

A primal-dual active-set iteration (Hintermueller, Ito & Kunisch 2002) solves it,
with the translation ``delta`` and the tilt ``alpha`` as extra unknowns of the
small linear system on the active set.

**Contact kinematics** (:data:`KINEMATICS`). ``"small"`` is the half-plane
theory's: the gap is measured vertically between the undeformed surfaces and
the contact force is vertical. ``"first_order"`` keeps the terms of first
order in the slopes that a contact formulation on the deformed surfaces adds
(:func:`first_order_compliance`): both are linear in ``f``, so the same
active-set solve takes a modified compliance.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, Callable

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from threadpoolctl import threadpool_limits

from threepart.errors import InputError, InputTypeError, NoConvergenceError
from threepart.problem.checks import finite, integer, positive

from ._boundary import boundary
from ._iv import MAX_ITER

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


@dataclass(frozen=True, eq=False)
class ContactSolution:
    """Nodal solution of the discrete contact problem.

    Attributes
    ----------
    f
        Downward nodal contact forces (``>= 0``).
    gap
        Gap between punch and surface at the nodes (``>= 0``).
    active
        Nodes in contact.
    delta, alpha
        Rigid indentation and tilt of the punch.
    iterations
        Active-set iterations used.
    residual
        The largest complementarity violation left: tensile force (relative to
        ``P/n``) or penetration (relative to the profile's range), >= 0.
    slope
        The surface slope ``v'(x_i)`` the forces act along (:func:`solve_kinematic`):
        zeros for vertical forces (``kinematics = "small"``).
    """

    f: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    delta: float
    alpha: float
    iterations: int
    residual: float = 0.0
    slope: np.ndarray | None = None


def _solve_active(C: np.ndarray, x: np.ndarray, g0: np.ndarray, active: np.ndarray,
                  P: float, s: float, free_tilt: bool, symmetric: bool = False
                  ) -> tuple[np.ndarray, float, float]:
    """Forces on the active set with ``gap = 0`` there, plus the equilibrium rows.

    The system ``C_AA f + B lam = -g0_A``, ``D^T f = e`` (``lam = (delta, alpha)``,
    ``B = (-1, x)``, ``D = (1, x)``, ``e = (P, P s)``). A symmetric ``C``
    (``symmetric``; the small-slope compliance) is positive definite: a Cholesky
    factor of ``C_AA`` and the ``k x k`` Schur complement of the bordered rows
    (half the work of an LU of the whole); otherwise, or if that factor fails,
    one LU of the bordered matrix.
    """
    idx = np.flatnonzero(active)
    m = len(idx)
    k = 2 if free_tilt else 1
    A = C[np.ix_(idx, idx)]
    D = np.ones((m, k))
    if free_tilt:
        D[:, 1] = x[idx]
    B = D.copy()
    B[:, 0] = -1.0
    e = np.array([P, P * s][:k])
    f = np.zeros(len(x))
    if symmetric:
        try:
            factor = cho_factor(A, lower=True, overwrite_a=True, check_finite=False)
        except np.linalg.LinAlgError:
            A = C[np.ix_(idx, idx)]
        else:
            Y = cho_solve(factor, np.column_stack([-g0[idx], B]), check_finite=False)
            lam = np.linalg.solve(D.T @ Y[:, 1:], D.T @ Y[:, 0] - e)
            f[idx] = Y[:, 0] - Y[:, 1:] @ lam
            return f, float(lam[0]), float(lam[1]) if free_tilt else 0.0
    M = np.zeros((m + k, m + k))
    M[:m, :m], M[:m, m:], M[m:, :m] = A, B, D.T
    sol = np.linalg.solve(M, np.concatenate([-g0[idx], e]))
    f[idx] = sol[:m]
    return f, float(sol[m]), float(sol[m + 1]) if free_tilt else 0.0


@boundary
def solve_contact(C: np.ndarray, x: np.ndarray, g0: np.ndarray, P: float, s: float = 0.0, *,
                  free_tilt: bool = True, max_iter: int = 100,
                  active: np.ndarray | None = None) -> ContactSolution:
    """Primal-dual active-set solution of the load-controlled contact problem.

    Parameters
    ----------
    C
        Surface compliance on the candidate nodes, ``(n, n)``.
    x
        Node positions, ``(n,)``.
    g0
        Punch shape at the nodes (profile with ``alpha = delta = 0``).
    P, s
        Load and lever arm (``s`` is ignored when ``free_tilt`` is False).
    free_tilt
        Whether the tilt is an unknown (``True``) or suppressed (``alpha = 0``).
    max_iter
        Largest number of active-set iterations.
    active
        Initial active set; default all nodes.

    Returns
    -------
    ContactSolution

    Raises
    ------
    NoConvergenceError
        If the active set does not settle within ``max_iter`` iterations, or the
        settled set leaves a tensile force or a penetration above round-off, or
        the iteration breaks down (an active set that cannot carry the load, a
        singular system) from every start tried: the one given, all nodes, and
        the nodes the punch's shape reaches (:func:`_start`).
    """
    P, s, max_iter, C, x, g0, active = _contact_iv(C, x, g0, P, s, max_iter, active)
    starts = ["given" if active is not None else "all", "geometric"]
    if active is not None:
        starts.insert(1, "all")
    failures = []
    for start in starts:
        act = _start(start, C, x, g0, P, active)
        try:
            return _iterate(C, x, g0, P, s, free_tilt, max_iter, act)
        except _Breakdown as e:
            failures.append(f"from the {start} start: {e}")
    raise NoConvergenceError("contact active set broke down " + "; ".join(failures))


def _contact_iv(C: Any, x: Any, g0: Any, P: Any, s: Any, max_iter: Any, active: Any
                ) -> tuple[float, float, int, np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """The checked input of :func:`solve_contact`: finite arrays of matching shapes, ``P > 0``."""
    P, s = positive("P", P), finite("s", s)
    max_iter = integer("max_iter", max_iter, *MAX_ITER)
    x = np.asarray(x, dtype=float)
    n = len(x) if x.ndim == 1 else -1
    C, g0 = np.asarray(C, dtype=float), np.asarray(g0, dtype=float)
    if n < 1 or C.shape != (n, n) or g0.shape != (n,):
        raise InputError(f"`C`, `x`, `g0` must have shapes (n, n), (n,), (n,); got {C.shape}, "
                         f"{x.shape}, {g0.shape}")
    for name, arr in (("C", C), ("x", x), ("g0", g0)):
        if not np.all(np.isfinite(arr)):
            raise InputError(f"`{name}` holds a non-finite value")
    if active is not None:
        active = np.asarray(active)
        if active.shape != (n,) or active.dtype != bool:
            raise InputError(f"`active` must be a bool array of shape ({n},)")
    return P, s, max_iter, C, x, g0, active


class _Breakdown(Exception):
    """The active-set iteration left the admissible sets (it is not globally convergent)."""


def _start(start: str, C: np.ndarray, x: np.ndarray, g0: np.ndarray, P: float,
           active: np.ndarray | None) -> np.ndarray:
    """An initial active set: the one given, every node, or the nodes the punch's shape reaches.

    ``"geometric"``: the nodes whose initial gap lies within the largest
    surface displacement of the load spread over all nodes, ``max C (P/n)``,
    of its lowest point: a set about the size of the contact.
    """
    if start == "given":
        return np.asarray(active, bool).copy()
    if start == "all":
        return np.ones(len(x), bool)
    d = float(np.max(np.abs(C @ np.full(len(x), P / len(x)))))
    return g0 - g0.min() <= max(d, 0.0)


def _admissible(act: np.ndarray, x: np.ndarray, s: float, free_tilt: bool) -> str | None:
    """Why the active-set system of ``act`` is singular, or None.

    With a free tilt the forces must balance the moment ``P s`` too: one
    active node makes the force and moment rows dependent.
    """
    m = int(act.sum())
    if free_tilt and m < 2:
        return (f"{m} active node at x = {x[act][0]:.6g} cannot balance the moment of the "
                f"load at s = {s:.6g}")
    return None


def _iterate(C: np.ndarray, x: np.ndarray, g0: np.ndarray, P: float, s: float, free_tilt: bool,
             max_iter: int, act: np.ndarray) -> ContactSolution:
    """The primal-dual active-set iteration from ``act``; :class:`_Breakdown` if it leaves the admissible sets."""
    n = len(x)
    cpd = 1.0 / float(np.mean(np.diag(C)))  # force per unit gap: balances the two terms
    symmetric = bool(np.array_equal(C, C.T))
    with threadpool_limits(limits=1, user_api="blas"):
        for it in range(1, max_iter + 1):
            if not act.any():
                act[np.argmin(g0)] = True
            why = _admissible(act, x, s, free_tilt)
            if why is not None:
                raise _Breakdown(f"at iteration {it}: {why}")
            try:
                f, delta, alpha = _solve_active(C, x, g0, act, P, s, free_tilt, symmetric)
            except np.linalg.LinAlgError:
                raise _Breakdown(f"at iteration {it}: a singular active-set system "
                                 f"({int(act.sum())} active nodes)") from None
            gap = g0 + alpha * x - delta + C @ f
            gap[act] = 0.0
            new = f - cpd * gap > 0
            if np.array_equal(new, act):
                break
            act = new
        else:
            raise NoConvergenceError(
                f"contact active set did not settle within `max_iter` = {max_iter} iterations "
                f"({int(np.sum(new != act))} nodes still changing)")
    if not (np.all(np.isfinite(f)) and np.isfinite(delta) and np.isfinite(alpha)):
        raise _Breakdown(f"at iteration {it}: non-finite forces")
    scale_f, scale_g = P / n, float(np.ptp(g0)) + 1e-300
    if f.min() < -1e-9 * scale_f * n or gap.min() < -1e-9 * scale_g:
        raise NoConvergenceError(
            f"active set settled after {it} iterations with min force {f.min():.3g} "
            f"and min gap {gap.min():.3g}: not a contact solution")
    residual = max(0.0, -float(f.min()) / scale_f, -float(gap.min()) / scale_g)
    return ContactSolution(f=f, gap=gap, active=act, delta=delta, alpha=alpha, iterations=it,
                           residual=residual)


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

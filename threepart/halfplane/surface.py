"""Unilateral contact on a discrete surface compliance: the dense complementarity problem.

A surface of candidate nodes ``x_i`` with compliance ``C`` (``u_y = -C f``, ``f``
the nodal forces) is what both the FEM and the half-plane's influence
coefficients give: an elastic body condensed onto its surface
(:func:`fem.elasticity.condense`), or the half-plane's log kernel on nodes
(:func:`influence`). A punch's lower surface is ``y_p = g0(x) + alpha x - delta``.
The gap and the complementarity conditions are::

    gap_i = g0_i + alpha x_i - delta + (C f)_i >= 0,   f_i >= 0,   f_i gap_i = 0,

with the load and its lever arm prescribed::

    sum f_i = P,    sum x_i f_i = P s        (tilt "free": alpha unknown)
    sum f_i = P,    alpha = 0                (tilt "suppressed": s is an output)

A primal-dual active-set iteration (Hintermueller, Ito & Kunisch 2002) solves it,
with the translation ``delta`` and the tilt ``alpha`` as extra unknowns of the
small linear system on the active set. A given tilt is ``alpha x`` added to ``g0``
with ``free_tilt=False``.

ContactSolution -- nodal forces, gap, active set, delta, alpha
solve_contact   -- the active-set solve
solve_active    -- one active set's bordered system (a factor kept per set; the Coulomb stick set's too)
symmetric       -- whether a compliance equals its transpose, found once per array
PerArray        -- a bounded map keyed by an array's identity (what is kept per compliance)
influence       -- the half-plane's compliance of a piecewise-linear pressure on nodes (eq. 0.1 of docs/WEAR.md)
MAX_ITER        -- the range of active-set iterations a caller may ask for
"""
from __future__ import annotations

import math
import threading
import warnings
import weakref
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.linalg import LinAlgWarning, cho_factor, cho_solve, lu_factor, lu_solve

from threepart.threads import one_blas_thread
from threepart.errors import InputError, NoConvergenceError
from threepart.problem.checks import finite, integer, positive

__all__ = ["ContactSolution", "solve_contact", "solve_active", "symmetric", "influence", "PerArray",
           "MAX_ITER"]

#: active-set iterations a caller may ask for, ``[1, 10000]``
MAX_ITER = (1, 10_000)


def influence(x: np.ndarray, A: float) -> tuple[np.ndarray, np.ndarray]:
    """The half-plane's surface compliance of a piecewise-linear pressure on nodes, per unit nodal force.

    The pressure is linear between the nodes ``x`` (strictly increasing):
    ``p(t) = Σ p_j φ_j(t)``, ``φ_j`` the hat of node ``j``. Node ``j`` carries the
    force ``f_j = p_j w_j``, ``w_j = ∫ φ_j`` (half its two elements' lengths). The gap of
    eq. (0.1) of docs/WEAR.md at the nodes is then ``g0_i + alpha x_i - delta + (C f)_i`` with::

        C_ij = -(A/π) ∫ φ_j(t) ln(|x_i - t|/L) dt / w_j,

    ``A = 4(1 - nu^2)/E`` of two similar bodies (eq. 4). On an element ``[x_e, x_e+1]``
    with ``u = t - x_i``, ``ln|u|`` integrates to ``u ln|u| - u`` and ``u ln|u|`` to
    ``u^2 ln|u|/2 - u^2/4``. The length ``L`` (ten times the span) only shifts ``delta``;
    it keeps the kernel's quadratic form positive (the interval's logarithmic capacity, a
    quarter of its length, is then below ``L``). A linear pressure between the nodes
    converges at second order away from a singular end, where a uniform one per cell is
    first order (docs/WEAR.md, section 8).

    Returns
    -------
    C, w
        The compliance ``(n, n)`` and the nodes' shares of the length ``w`` (``Σ w`` is the span).
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2 or not np.all(np.diff(x) > 0):
        raise InputError("`x` must be at least 2 strictly increasing node positions")
    L = 10.0 * float(x[-1] - x[0])
    h = np.diff(x)

    def F0(u: np.ndarray) -> np.ndarray:      # ∫ ln(|u|/L) du
        v = np.abs(u) / L
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(v > 0, u * np.log(np.where(v > 0, v, 1.0)) - u, 0.0)

    def F1(u: np.ndarray) -> np.ndarray:      # ∫ u ln(|u|/L) du
        v = np.abs(u) / L
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(v > 0, 0.5 * u * u * np.log(np.where(v > 0, v, 1.0)) - 0.25 * u * u, 0.0)

    lo, hi = x[None, :-1] - x[:, None], x[None, 1:] - x[:, None]     # each element's u-range from x_i
    i0, i1 = F0(hi) - F0(lo), F1(hi) - F1(lo)
    right = (i1 - lo * i0) / h[None, :]       # ∫ (t - x_e)/h ln: the element's share of its right node
    I = np.zeros((x.size, x.size))
    I[:, :-1] += i0 - right
    I[:, 1:] += right
    w = np.zeros(x.size)
    w[:-1] += 0.5 * h
    w[1:] += 0.5 * h
    return -(A / math.pi) * I / w[None, :], w


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


class PerArray:
    """A bounded, thread-safe map keyed by an array's identity (and a key of its own), least recent dropped.

    The array is held by a weak reference, so that a new array whose ``id`` reuses a freed
    one's is never taken for it; the array must not change in place while it is a key. The
    home of what is kept per compliance: the active sets' factors and their symmetry
    (:func:`_factor`, :func:`symmetric`), the FEM's last contact per condensed body
    (:mod:`fem.solve`).
    """

    def __init__(self, kept: int) -> None:
        self.kept = kept
        self._entries: "OrderedDict[tuple[int, Any], tuple[weakref.ref, Any]]" = OrderedDict()
        self._lock = threading.Lock()

    def get(self, array: np.ndarray, key: Any = None) -> Any:
        """The value kept for ``array`` and ``key``, or None."""
        with self._lock:
            hit = self._entries.get((id(array), key))
            if hit is None or hit[0]() is not array:
                return None
            self._entries.move_to_end((id(array), key))
            return hit[1]

    def clear(self) -> None:
        """Forget every entry."""
        with self._lock:
            self._entries.clear()

    def put(self, array: np.ndarray, key: Any, value: Any) -> Any:
        """Keep ``value`` for ``array`` and ``key``; returns it."""
        with self._lock:
            self._entries[(id(array), key)] = (weakref.ref(array), value)
            self._entries.move_to_end((id(array), key))
            while len(self._entries) > self.kept:
                self._entries.popitem(last=False)
        return value


#: the active-set systems' factors kept (:func:`_factor`): a march's or a cycle's steps return to the
#: same active sets on the same compliance, the normal and the Coulomb stick sets of a two-body
#: step alike (4 let the one evict the other: a map's slip study factorised 469 times, not 74)
FACTORS_KEPT = 8
_FACTORS = PerArray(FACTORS_KEPT)
#: compliances whose symmetry is known (an n^2 comparison per solve otherwise)
_SYMMETRIC = PerArray(64)


def symmetric(C: np.ndarray) -> bool:
    """Whether ``C`` equals its transpose, found once per compliance."""
    known = _SYMMETRIC.get(C)
    return bool(known) if known is not None else _SYMMETRIC.put(C, None, bool(np.array_equal(C, C.T)))


def _factor(C: np.ndarray, x: np.ndarray, active: np.ndarray, free_tilt: bool, sym: bool) -> Any:
    """The factor of the active set's bordered system, reused while ``C`` (the same object) and the set are.

    Symmetric ``C`` (the small-slope compliance, positive definite): a Cholesky factor of
    ``C_AA``, ``Y_B = C_AA^-1 B`` and the ``k x k`` Schur complement ``D^T Y_B`` (half the work
    of an LU of the whole); otherwise, or if that factor fails, one LU of the bordered matrix.
    ``C`` must not change in place between solves (a weak reference tells a new array from a
    freed one whose id was reused).
    """
    key = (free_tilt, active.tobytes())
    hit = _FACTORS.get(C, key)
    if hit is not None:
        return hit
    idx = np.flatnonzero(active)
    m, k = len(idx), 2 if free_tilt else 1
    A = C[np.ix_(idx, idx)]
    D = np.ones((m, k))
    if free_tilt:
        D[:, 1] = x[idx]
    B = D.copy()
    B[:, 0] = -1.0
    factor: Any = None
    if sym:
        try:
            cho = cho_factor(A, lower=True, check_finite=False)
        except np.linalg.LinAlgError:
            pass
        else:
            Y = cho_solve(cho, B, check_finite=False)
            factor = ("cholesky", idx, D, cho, Y, lu_factor(D.T @ Y, check_finite=False))
    if factor is None:
        M = np.zeros((m + k, m + k))
        M[:m, :m], M[:m, m:], M[m:, :m] = A, B, D.T
        with warnings.catch_warnings():     # a singular set is told by its zero pivot, below
            warnings.simplefilter("ignore", LinAlgWarning)
            factor = ("lu", idx, D, lu_factor(M, check_finite=False))
        if not np.all(np.isfinite(factor[3][0])) or np.any(np.diag(factor[3][0]) == 0):
            raise np.linalg.LinAlgError("singular active-set system")
    return _FACTORS.put(C, key, factor)


def solve_active(C: np.ndarray, x: np.ndarray, g0: np.ndarray, active: np.ndarray,
                 P: float, s: float, free_tilt: bool, sym: bool = False
                 ) -> tuple[np.ndarray, float, float]:
    """Forces on the active set with ``gap = 0`` there, plus the equilibrium rows.

    The system ``C_AA f + B lam = -g0_A``, ``D^T f = e`` (``lam = (delta, alpha)``,
    ``B = (-1, x)``, ``D = (1, x)``, ``e = (P, P s)``), by :func:`_factor`'s factor.
    ``sym``: :func:`symmetric` of ``C``.
    """
    factor = _factor(C, x, active, free_tilt, sym)
    idx, D = factor[1], factor[2]
    k = D.shape[1]
    e = np.array([P, P * s][:k])
    f = np.zeros(len(x))
    if factor[0] == "cholesky":
        y = cho_solve(factor[3], -g0[idx], check_finite=False)
        lam = lu_solve(factor[5], D.T @ y - e, check_finite=False)
        f[idx] = y - factor[4] @ lam
    else:
        sol = lu_solve(factor[3], np.concatenate([-g0[idx], e]), check_finite=False)
        f[idx], lam = sol[:-k], sol[-k:]
    return f, float(lam[0]), float(lam[1]) if free_tilt else 0.0


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


class _Breakdown(NoConvergenceError):
    """The active-set iteration left the admissible sets (it is not globally convergent); caught inside."""


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
    sym = symmetric(C)
    with one_blas_thread():
        for it in range(1, max_iter + 1):
            if not act.any():
                act[np.argmin(g0)] = True
            why = _admissible(act, x, s, free_tilt)
            if why is not None:
                raise _Breakdown(f"at iteration {it}: {why}")
            try:
                f, delta, alpha = solve_active(C, x, g0, act, P, s, free_tilt, sym)
            except np.linalg.LinAlgError:
                raise _Breakdown(f"at iteration {it}: a singular active-set system "
                                 f"({int(act.sum())} active nodes)") from None
            gap = g0 + alpha * x - delta + C @ f
            gap[act] = 0.0
            new = f - cpd * gap > 0
            changed = int(np.sum(new != act))
            if not changed:
                break
            act = new
        else:
            raise NoConvergenceError(
                f"contact active set did not settle within `max_iter` = {max_iter} iterations "
                f"({changed} nodes changed at the last)")
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



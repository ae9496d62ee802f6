"""Safeguarded Newton iterations for the inverse problems, scalar and vectorised.

The closed forms are evaluated at the contact half-width ``h = (a+c)/2`` and
centre ``m = (c-a)/2``; the 2-D iterations run in ``u1 = sqrt(a-b)``,
``u2 = sqrt(c-b)``, which keeps both contact edges on the outer segments. The residuals use the closed forms of :mod:`closedform.formulas`
written in the join angles, with their exact Jacobians:

* ``d(AP)/dm = k2/R2 W3 - k1/R1 W1`` and
  ``d(AP)/dh = 2AP/h + h (k1/R1 sin b1 cos b1 + k2/R2 sin b2 cos b2)``;
* ``d alpha/dm = -F0/pi`` and ``d alpha/dh = (k1/R1 sin b1 - k2/R2 sin b2)/pi``;
* for the moment ``T = A P s``: ``dT/dm = AP + m d(AP)/dm + h^2/2 (k1/R1 s1 c1 + k2/R2 s2 c2)``
  and ``dT/dh = m d(AP)/dh + h^2/2 (k2/R2 sin b2 - k1/R1 sin b1)``.

A single case runs on Python floats with :mod:`math` (``solve_hm_scalar``), a
batch on arrays (``solve_hm``); both evaluate the same :class:`State`.
"""
from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from threepart.errors import NoConvergenceError
from .formulas import _chi, _psi
from threepart.punch import Punch

__all__ = ["State", "solve_hm", "solve_hm_scalar", "newton1d", "newton1d_scalar", "SCALAR", "pick"]

MAX_ITER = 60
RTOL = 1e-14      # residuals are relative: load error / load, moment error / (load h)
MAX_HALVINGS = 50


class _Scalar:
    """The few array functions :class:`State` needs, on Python floats."""

    sqrt, arctan2, sin, cos = math.sqrt, math.atan2, math.sin, math.cos

    @staticmethod
    def maximum(x: float, y: float) -> float:
        return x if x > y else y

    @staticmethod
    def minimum(x: float, y: float) -> float:
        return x if x < y else y

    @staticmethod
    def where(cond: bool, x: float, y: float) -> float:
        return x if cond else y


SCALAR: Any = _Scalar


class State:
    """Closed forms (with ``A = 1``) and their derivatives at ``(h, m)``.

    ``xp`` is :mod:`numpy` for arrays or :data:`SCALAR` for Python floats.
    """

    def __init__(self, punch: Punch, h: Any, m: Any, xp: Any = np) -> None:
        b, k0, k1, k2 = punch.b, punch.kappa0, punch.kappa1, punch.kappa2
        a, c = h - m, h + m
        # clipped at 0: on the lift-off lines c - b (or a - b) is 0 up to rounding
        b1 = 2 * xp.arctan2(xp.sqrt(xp.maximum(a - b, 0.0)), xp.sqrt(xp.maximum(c + b, 0.0)))
        b2 = 2 * xp.arctan2(xp.sqrt(xp.maximum(c - b, 0.0)), xp.sqrt(xp.maximum(a + b, 0.0)))
        s1, c1, s2, c2 = xp.sin(b1), xp.cos(b1), xp.sin(b2), xp.cos(b2)
        self.h, self.m = h, m
        self.F0 = k1 * b1 + k2 * b2 + math.pi * k0
        self.AP = 0.25 * h * h * (k1 * _psi(b1, xp) + k2 * _psi(b2, xp) + 2 * math.pi * k0)
        self.T = m * self.AP + h**3 * (k2 * s2**3 - k1 * s1**3) / 6
        self.alpha = h * (k1 * _chi(b1, xp) - k2 * _chi(b2, xp)) / math.pi - m * k0
        sc = k1 * s1 * c1 + k2 * s2 * c2
        self.AP_m = h * (k2 * s2 - k1 * s1)
        self.AP_h = 2 * self.AP / h + h * sc
        self.T_m = self.AP + m * self.AP_m + 0.5 * h * h * sc
        self.T_h = m * self.AP_h + 0.5 * h * h * (k2 * s2 - k1 * s1)
        self.alpha_m = -self.F0 / math.pi
        self.alpha_h = (k1 * s1 - k2 * s2) / math.pi


Residual = Callable[[State, Any], tuple[Any, Any, Any, Any, Any, Any]]


def pick(value: Any, idx: Any) -> Any:
    """``value[idx]`` for per-case arrays; scalars (and ``idx=None``) pass through."""
    return value if idx is None or np.ndim(value) == 0 else value[idx]


def _to_u(h: Any, m: Any, b: float, xp: Any) -> tuple[Any, Any]:
    """Iteration variables ``u1 = sqrt(a - b)``, ``u2 = sqrt(c - b)``."""
    return xp.sqrt(xp.maximum(h - m - b, 0.0)), xp.sqrt(xp.maximum(h + m - b, 0.0))


def _to_hm(u1: Any, u2: Any, b: float) -> tuple[Any, Any]:
    return b + 0.5 * (u1 * u1 + u2 * u2), 0.5 * (u2 * u2 - u1 * u1)


def _newton_step(r: tuple, u1: Any, u2: Any) -> tuple[Any, Any]:
    """Newton step in ``(u1, u2)`` from residuals and their ``(h, m)`` Jacobian.

    ``d/du1 = u1 (d/dh - d/dm)`` and ``d/du2 = u2 (d/dh + d/dm)``.
    """
    r1, r2, f1h, f1m, f2h, f2m = r
    j11, j12 = u1 * (f1h - f1m), u2 * (f1h + f1m)
    j21, j22 = u1 * (f2h - f2m), u2 * (f2h + f2m)
    det = j11 * j22 - j12 * j21
    return -(j22 * r1 - j12 * r2) / det, -(-j21 * r1 + j11 * r2) / det


def solve_hm_scalar(punch: Punch, residual: Residual, h: float, m: float,
                    max_iter: int = MAX_ITER) -> tuple[float, float, bool]:
    """Newton on ``residual(state) -> (r1, r2, dr1/dh, dr1/dm, dr2/dh, dr2/dm)`` for one case.

    The iteration runs in ``u1 = sqrt(a-b)``, ``u2 = sqrt(c-b)``: every iterate
    is admissible (both edges on the outer segments) and the closed forms,
    which behave like ``(c-b)^(3/2)`` near lift-off, are smooth in ``u``.
    Steps are halved until the residual norm decreases. Returns
    ``(h, m, converged)``.
    """
    b = punch.b
    u1, u2 = _to_u(h, m, b, SCALAR)
    r = residual(State(punch, h, m, SCALAR), None)
    norm = math.hypot(r[0], r[1])
    for _ in range(max_iter):
        if norm <= RTOL:
            return h, m, True
        try:
            d1, d2 = _newton_step(r, u1, u2)
        except ZeroDivisionError:
            return h, m, False
        lam = 1.0
        for _ in range(MAX_HALVINGS):
            v1, v2 = u1 + lam * d1, u2 + lam * d2
            hn, mn = _to_hm(v1, v2, b)
            if hn > 0:
                rn = residual(State(punch, hn, mn, SCALAR), None)
                normn = math.hypot(rn[0], rn[1])
                if normn < norm:
                    break
            lam *= 0.5
        else:  # no decrease: converged to rounding, or stuck
            return h, m, norm <= 1e3 * RTOL
        u1, u2, h, m, r, norm = v1, v2, hn, mn, rn, normn
    return h, m, norm <= RTOL


def solve_hm(punch: Punch, residual: Residual, h0: np.ndarray, m0: np.ndarray,
             max_iter: int = MAX_ITER) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vectorised :func:`solve_hm_scalar`; returns ``(h, m, converged)`` arrays.

    Only the cases still iterating (and, in the line search, only those whose
    step is still being halved) are evaluated; ``residual(state, idx)`` takes
    the indices of the cases in ``state``.
    """
    b = punch.b
    h, m = np.array(h0, float, copy=True), np.array(m0, float, copy=True)
    u1, u2 = _to_u(h, m, b, np)
    everything = np.arange(h.size)
    r = [np.array(x, float) for x in residual(State(punch, h, m), everything)]
    norm = np.hypot(r[0], r[1])
    done = norm <= RTOL
    for _ in range(max_iter):
        act = np.flatnonzero(~done)
        if act.size == 0:
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            d1, d2 = _newton_step(tuple(x[act] for x in r), u1[act], u2[act])
        finite = np.isfinite(d1) & np.isfinite(d2)
        done[act[~finite]] = True
        act, d1, d2 = act[finite], d1[finite], d2[finite]
        lam = np.ones(act.size)
        pending = np.arange(act.size)
        for _ in range(MAX_HALVINGS):
            idx = act[pending]
            v1, v2 = u1[idx] + lam[pending] * d1[pending], u2[idx] + lam[pending] * d2[pending]
            hn, mn = _to_hm(v1, v2, b)
            ok = hn > 0
            hn, mn = np.where(ok, hn, h[idx]), np.where(ok, mn, m[idx])
            rn = residual(State(punch, hn, mn), idx)
            normn = np.hypot(rn[0], rn[1])
            acc = ok & (normn < norm[idx])
            sel = idx[acc]
            u1[sel], u2[sel], h[sel], m[sel], norm[sel] = v1[acc], v2[acc], hn[acc], mn[acc], normn[acc]
            for k in range(6):
                r[k][sel] = rn[k][acc]
            pending = pending[~acc]
            if pending.size == 0:
                break
            lam[pending] *= 0.5
        # no decrease possible: converged to rounding, or stuck (reported below)
        done[act[pending]] = True
        done |= norm <= RTOL
    return h, m, norm <= 1e3 * RTOL


def newton1d_scalar(fun: Callable[[float], tuple[float, float]], x: float, lo: float,
                    what: str, xtol: float = 1e-11) -> float:
    """Newton for an increasing ``fun`` with ``fun(lo) < 0``, from ``x``.

    ``fun(x)`` returns ``(f, f')``. Steps below ``lo`` (or not finite) are
    replaced by bisection towards ``lo``; the bracket's upper end is the
    lowest point seen with ``f >= 0``. Stops once the step is below ``xtol``
    relative (the error is then of order ``xtol**2``).
    """
    hi = math.inf
    for _ in range(200):
        f, df = fun(x)
        if f < 0:
            lo = x
        else:
            hi = min(hi, x)
        xn = x - f / df if df > 0 else math.nan
        if lo <= xn <= hi and abs(xn - x) <= xtol * abs(x):
            return xn
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi) if math.isfinite(hi) else 2 * x - lo
        if hi - lo <= 4e-16 * abs(hi) < math.inf:  # bracket collapsed
            return xn
        x = xn
    raise NoConvergenceError(f"{what}: the Newton iteration did not converge in 200 steps")


def newton1d(fun: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]], x: np.ndarray,
             lo: np.ndarray, what: str, xtol: float = 1e-11) -> np.ndarray:
    """Vectorised :func:`newton1d_scalar`; ``fun(x, idx)`` evaluates the cases ``idx``."""
    x, lo = np.array(x, float, copy=True), np.array(lo, float, copy=True)
    hi = np.full_like(x, np.inf)
    idx = np.arange(x.size)
    for _ in range(200):
        xi, loi, hii = x[idx], lo[idx], hi[idx]
        f, df = fun(xi, idx)
        loi = np.where(f < 0, xi, loi)
        hii = np.where(f >= 0, np.minimum(hii, xi), hii)
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = np.where(df > 0, xi - f / df, np.nan)
        inside = (xn > loi) & (xn < hii)
        small = (xn >= loi) & (xn <= hii) & (np.abs(xn - xi) <= xtol * np.abs(xi))
        xn = np.where(inside | small, xn, np.where(np.isfinite(hii), 0.5 * (loi + hii), 2 * xi - loi))
        x[idx], lo[idx], hi[idx] = xn, loi, hii
        collapsed = np.isfinite(hii) & (hii - loi <= 4e-16 * np.abs(hii))
        idx = idx[~(small | collapsed)]
        if idx.size == 0:
            return x
    raise NoConvergenceError(f"{what}: the Newton iteration did not converge in 200 steps")

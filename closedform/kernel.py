"""The closed form's inner loop, compiled: one forward evaluation and the 2-D Newton iteration of one case.

The inverse problems spend their time in two places: the forward closed forms
in the join angles with their ``(h, m)`` derivatives (eqs. consistency_condition,
equilibrium_condition_1 and _2), and the Newton iteration that drives them to
a root. Both are written here once, for one case on plain floats, and compiled
by numba (``cache=True``: compiled once per machine, loaded from
``__pycache__`` after that); a batch is the same code in a compiled loop over
its cases. Nothing here raises: a case that does not converge comes back with
``ok = False`` and goes to the bracketed, nested roots of
:mod:`closedform.newton`, which decide a refusal.

state           -- the closed forms and their derivatives at ``a = b + u1^2``, ``c = b + u2^2`` (a tuple, :data:`FIELDS`)
states          -- the same on arrays (a compiled loop), one row per field
newton_2d       -- the 2-D Newton iteration of one case in ``(r, phi)``
newton_2d_many  -- the same for arrays of cases
psi, chi        -- ``2x - sin 2x`` and ``sin x - x cos x`` without cancellation (floats; ``psi_v``, ``chi_v`` on arrays)
pressure_v      -- the compressive pressure of eq. (pressure_abbreviated) at one point, a numpy ufunc (``formulas.pressure``)
f0_v            -- ``F0`` of eq. (f0), a numpy ufunc (``formulas.F0``)

Run with ``NUMBA_DISABLE_JIT=1`` the same functions run as plain Python (for a
debugger); the answers agree to rounding.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, vectorize

__all__ = ["FIELDS", "state", "states", "newton_2d", "newton_2d_many", "psi", "chi", "psi_v", "chi_v",
           "f0_v", "pressure_v", "MOMENT", "TILT", "STALL"]

#: the fields of :func:`state`, in order (the attributes of :class:`closedform.newton.State`)
FIELDS = ("a", "c", "h", "m", "dAP", "AP", "AP_h", "AP_m", "F0", "T", "T_h", "T_m",
          "alpha", "alpha_h", "alpha_m")
_N_FIELDS = len(FIELDS)
#: the outer equation of :func:`newton_2d`: the moment ``A P s`` (tilt free) or the tilt ``alpha``
MOMENT, TILT = 0, 1
#: a step below this that no longer halves is rounding: the iteration has converged
STALL = 1e-8

_HALF_PI = 0.5 * math.pi
#: compiled once per machine (cached beside the source), IEEE division (inf, NaN: never an exception)
_compiled = njit(cache=True, error_model="numpy", nogil=True)


def _psi(x: float) -> float:
    x2 = x * x
    if x < 1e-2:
        return (4.0 / 3.0) * x2 * x * (1.0 - x2 / 5.0 + 2.0 * x2 * x2 / 105.0)
    return 2.0 * x - math.sin(2.0 * x)


def _chi(x: float) -> float:
    x2 = x * x
    if x < 1e-2:
        return x2 * x / 3.0 * (1.0 - x2 / 10.0 + x2 * x2 / 280.0)
    return math.sin(x) - x * math.cos(x)


#: ``2x - sin 2x``, with its series below ``x = 0.01`` (no cancellation): the load's angle function
psi = _compiled(_psi)
#: ``sin x - x cos x``, with its series below ``x = 0.01``: the tilt's angle function
chi = _compiled(_chi)
#: :func:`psi` and :func:`chi` as numpy ufuncs (``formulas.load`` and ``formulas.tilt``); numba's
#: vectorize gives a DUFunc whose Python-level ``__call__`` costs 5 µs, its ``ufunc`` is plain numpy's
psi_v = vectorize(["float64(float64)"], cache=True)(_psi).ufunc
chi_v = vectorize(["float64(float64)"], cache=True)(_chi).ufunc


@_compiled
def _log_ratio(x: float, a: float, c: float, b: float, sign: float) -> float:
    """``(x + sign b) ln|(a+c)(x + sign b)/N|`` with ``N`` the paper's denominator of F1/F3.

    ``N = (sqrt((c-x)(a - sign b)) + sqrt((x+a)(c + sign b)))^2`` is the printed
    ``2 sqrt(...) + 2(ac ± bx) + (a-c)(b ∓ x)`` written as a perfect square;
    ``(x ± b) ln|x ± b|`` is 0 at the join.
    """
    g = x + sign * b
    root = math.sqrt((c - x) * max(a - sign * b, 0.0)) + math.sqrt((x + a) * max(c + sign * b, 0.0))
    n = root * root
    glog = 0.0 if g == 0.0 else g * math.log(abs(g))
    return glog + g * math.log((a + c) / n)


def _f0(b: float, k0: float, k1: float, k2: float, a: float, c: float) -> float:
    """``F0 = k1/R1 beta1 + k2/R2 beta2 + pi/R`` of one contact (eq. f0).

    The join angles as ``2 atan2(sqrt(a-b), sqrt(c+b))`` (``formulas.beta``), exact also
    with an edge at a join.
    """
    b1 = 2.0 * math.atan2(math.sqrt(max(a - b, 0.0)), math.sqrt(c + b))
    b2 = 2.0 * math.atan2(math.sqrt(max(c - b, 0.0)), math.sqrt(a + b))
    return k1 * b1 + k2 * b2 + math.pi * k0


#: :func:`_f0` as a numpy ufunc, on a float or arrays of contacts (``formulas.F0``, its one home)
f0_v = vectorize(["float64(float64, float64, float64, float64, float64, float64)"], cache=True)(_f0).ufunc


def _pressure(x: float, a: float, c: float, A: float, F0: float, k1: float, k2: float, b: float) -> float:
    """Compressive pressure ``-p(x)`` of eq. (pressure_abbreviated) on ``[-a, c]``, 0 at and beyond the edges.

    ``-p(x) = [w F0 + k1/R1 (x+b) F1(x) + k2/R2 (x-b) F3(x)] / (pi A)`` with
    ``w = sqrt((x+a)(c-x))``, ``F0`` of the contact (:func:`_f0`, eq. f0) and the
    logarithms of :func:`_log_ratio` (``k1, k2`` = ``k1/R1``, ``k2/R2``).
    """
    if not (x > -a and x < c):
        return 0.0
    w = math.sqrt((x + a) * (c - x))
    return (w * F0 + k1 * _log_ratio(x, a, c, b, 1.0) - k2 * _log_ratio(x, a, c, b, -1.0)) / (math.pi * A)


#: :func:`_pressure` as a numpy ufunc: broadcasts ``x``, ``a``, ``c``, ``A``, ``F0`` (``formulas.pressure``)
pressure_v = vectorize(["float64(float64, float64, float64, float64, float64, float64, float64, float64)"],
                       cache=True)(_pressure).ufunc


@_compiled
def state(b: float, k0: float, k1: float, k2: float, u1: float, u2: float) -> tuple:
    """The closed forms (``A = 1``) and their ``(h, m)`` derivatives at ``a = b + u1^2``, ``c = b + u2^2``.

    ``h = (a+c)/2``, ``m = (c-a)/2``; the join angles ``beta1 = 2 atan(u1/sqrt(c+b))``,
    ``beta2 = 2 atan(u2/sqrt(a+b))`` (eq. f0). Returns the :data:`FIELDS`:
    ``A P`` (eq. equilibrium_condition_1) and ``A (P - P_0)`` (free of cancellation),
    ``F0`` (eq. f0), the moment ``T = A P s`` (eq. equilibrium_condition_2), the
    tilt ``alpha`` (eq. consistency_condition), and their ``h``, ``m`` derivatives.
    """
    ab, cb = u1 * u1, u2 * u2                          # a - b, c - b
    rho = 0.5 * (ab + cb)                              # h - b
    h, m = b + rho, 0.5 * (cb - ab)
    b1 = 2.0 * math.atan2(u1, math.sqrt(2.0 * b + cb))
    b2 = 2.0 * math.atan2(u2, math.sqrt(2.0 * b + ab))
    s1, c1, s2, c2 = math.sin(b1), math.cos(b1), math.sin(b2), math.cos(b2)
    edges = 0.25 * h * h * (k1 * psi(b1) + k2 * psi(b2))
    dAP = edges + 0.5 * math.pi * k0 * rho * (2.0 * b + rho)
    AP = edges + 0.5 * math.pi * k0 * h * h
    sc = k1 * s1 * c1 + k2 * s2 * c2
    AP_m = h * (k2 * s2 - k1 * s1)
    AP_h = 2.0 * AP / h + h * sc
    F0 = k1 * b1 + k2 * b2 + math.pi * k0
    T = m * AP + h ** 3 * (k2 * s2 ** 3 - k1 * s1 ** 3) / 6.0
    alpha = h * (k1 * chi(b1) - k2 * chi(b2)) / math.pi - m * k0
    T_m = AP + m * AP_m + 0.5 * h * h * sc
    T_h = m * AP_h + 0.5 * h * h * (k2 * s2 - k1 * s1)
    return (b + ab, b + cb, h, m, dAP, AP, AP_h, AP_m, F0, T, T_h, T_m,
            alpha, (k1 * s1 - k2 * s2) / math.pi, -F0 / math.pi)


@_compiled
def states(b: float, k0: float, k1: float, k2: float, u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
    """:func:`state` at each ``(u1[i], u2[i])``: an array of shape ``(len(FIELDS), n)``."""
    out = np.empty((_N_FIELDS, u1.size))
    for i in range(u1.size):
        st = state(b, k0, k1, k2, u1[i], u2[i])
        for j in range(_N_FIELDS):
            out[j, i] = st[j]
    return out


@_compiled
def _ratio(num: float, den: float) -> float:
    """``num/den`` where ``den > 0``, NaN elsewhere."""
    return num / den if den > 0.0 else math.nan


@_compiled
def newton_2d(b: float, k0: float, k1: float, k2: float, dAP: float, target: int, value: float,
              sign: float, r: float, phi: float, xtol: float, max_iter: int) -> tuple:
    """Newton's method in ``(r, phi)`` on the load and the ``target`` equation of one case.

    The case is ``A (P - P_0) = dAP`` and ``target`` (:data:`MOMENT`: ``A P s``;
    :data:`TILT`: ``alpha``, with ``sign = -1`` as it decreases in ``phi``)
    equal to ``value``, with ``u1 = r cos(phi)``, ``u2 = r sin(phi)``. Each step
    is one :func:`state`, which gives both residuals and the exact Jacobian
    (``h_r = r``, ``m_r = -r cos 2phi``, ``m_phi = r^2 sin 2phi``): the load's Newton correction ``dr`` at fixed ``phi``
    and the target linearised onto the constant-load curve, ``f = g + g_r dr``,
    stepped in ``t = sin^2 phi`` (linear at the lift-off lines) inside a bracket
    on ``phi`` narrowed where the sign of ``f`` is sure. Converged: a full step
    below ``xtol`` (relative in ``r``, absolute in ``phi``), or below
    :data:`STALL` and no longer halving (the rounding floor).

    Returns
    -------
    r, phi, ok, evaluations
        ``ok``: converged with ``0 < phi < pi/2`` (strictly inside the lift-off range,
        where the system has one root).
    """
    lo, hi, last = 0.0, _HALF_PI, math.inf
    for n in range(1, max_iter + 1):
        st = state(b, k0, k1, k2, r * math.sin(_HALF_PI - phi), r * math.sin(phi))
        dAP_, AP_h, AP_m = st[4], st[6], st[7]
        if target == MOMENT:
            g, g_h, g_m = st[9], st[10], st[11]
        else:
            g, g_h, g_m = st[12], st[13], st[14]
        cos2, sin2 = math.cos(2.0 * phi), math.sin(2.0 * phi)
        L_r = r * (AP_h - cos2 * AP_m)
        G_r = sign * r * (g_h - cos2 * g_m)
        dr = -_ratio(dAP_ - dAP, L_r)                      # the load's correction at fixed phi
        r_phi = -_ratio(r * r * sin2 * AP_m, L_r)          # the constant-load curve's slope
        f = sign * (g - value) + G_r * dr                  # the target, on the curve
        df = sign * r * r * sin2 * g_m + G_r * r_phi
        # the sign of f is trusted where its linear correction is small against it
        near = abs(dr) <= 0.1 * r
        if near and abs(G_r * dr) <= 0.5 * abs(f):
            if f < 0.0:
                lo = phi
            else:
                hi = phi
        dt = -_ratio(f * sin2, df)
        sp, cp = math.sin(phi), math.sin(_HALF_PI - phi)
        newton = math.atan2(math.sqrt(max(sp * sp + dt, 0.0)), math.sqrt(max(cp * cp - dt, 0.0)))
        phin = phi
        if near:
            phin = newton if (lo < newton < hi) or abs(newton - phi) <= xtol else 0.5 * (lo + hi)
        drn = dr + r_phi * (phin - phi)
        step = abs(_ratio(drn, r)) + abs(phin - phi)
        if not (math.isfinite(step) and math.isfinite(f)):
            step = math.inf
        small = step <= xtol or (step <= STALL and step >= 0.5 * last)
        rn = r + drn
        r, phi, last = (rn if rn > 0.0 else 0.5 * r), phin, step
        if small:
            return r, phi, 0.0 < phi < _HALF_PI, n
    return r, phi, False, max_iter


@_compiled
def newton_2d_many(b: float, k0: float, k1: float, k2: float, dAP: np.ndarray, target: int,
                   value: np.ndarray, sign: float, r: np.ndarray, phi: float, xtol: float,
                   max_iter: int) -> tuple:
    """:func:`newton_2d` for each case ``i`` (``dAP[i]``, ``value[i]``, from ``r[i]``, ``phi``).

    Returns arrays ``r``, ``phi``, ``ok`` and the total number of evaluations.
    """
    n = dAP.size
    r_out, phi_out, ok = np.empty(n), np.empty(n), np.empty(n, dtype=np.bool_)
    total = 0
    for i in range(n):
        r_out[i], phi_out[i], ok[i], k = newton_2d(b, k0, k1, k2, dAP[i], target, value[i], sign, r[i], phi,
                                                   xtol, max_iter)
        total += k
    return r_out, phi_out, ok, total

"""Independent numerical evaluation of the integrals that define the closed forms.

Nothing here calls :mod:`closedform.formulas`; only the profile slope ``v'(t)``
of eq. (2) is used. Each integral over ``[-a, c]`` is split at the joins
``±b`` (where ``v''`` jumps) and at the collocation point, and the
``1/sqrt((t+a)(c-t))`` end singularities are given to QUADPACK's algebraic
weights (``weight="alg"``). Cauchy principal values are removed by
subtracting ``v'(x)``: for ``-a < x < c``, ``PV int dt/(w(t)(t-x)) = 0``, so

``PV int v'(t)/(w(t)(t-x)) dt = int (v'(t) - v'(x))/((t-x) w(t)) dt``,

whose integrand is bounded (the pressure uses :func:`sie.pressure_by_quadrature`,
which evaluates that integral in ``theta``).
"""
from __future__ import annotations

import math
from typing import Callable

from threepart.problem.punch import Punch
from threepart.sie.reference import pressure_by_quadrature, quiet_quad

EPS = 1e-13



def integrate(fun: Callable[[float], float], a: float, c: float, breaks=(), power: float = -0.5,
              ) -> float:
    """``int_{-a}^{c} fun(t) ((t+a)(c-t))^power dt``, split at ``breaks``."""
    pts = sorted({-a, c, *[t for t in breaks if -a < t < c]})
    total = 0.0
    for lo, hi in zip(pts[:-1], pts[1:]):
        left, right = lo == -a, hi == c
        def g(t: float, lo=lo, hi=hi, left=left, right=right) -> float:
            wl = 1.0 if left else (t + a) ** power
            wr = 1.0 if right else (c - t) ** power
            return fun(t) * wl * wr
        wvar = (power if left else 0.0, power if right else 0.0)
        val, _ = quiet_quad(g, lo, hi, weight="alg", wvar=wvar, epsabs=0.0, epsrel=EPS, limit=400)
        total += val
    return total


def _breaks(punch: Punch) -> tuple[float, ...]:
    return (-punch.b, punch.b) if punch.b > 0 else (0.0,)


def tilt(punch: Punch, a: float, c: float) -> float:
    """``alpha`` solving the consistency condition ``int v'(t)/w(t) dt = 0`` (eq. consistency_cond)."""
    geo = integrate(lambda t: float(punch.slope(t, 0.0)), a, c, _breaks(punch))
    one = integrate(lambda t: 1.0, a, c)
    return -geo / one


def load(punch: Punch, a: float, c: float, A: float) -> float:
    """``P = -int p dx = (1/2A) int (a - c + 2t) v'(t)/w(t) dt`` (appendix, vertical equilibrium).

    Uses the finite Hilbert transform ``int w(x)/(t-x) dx = pi (a - c + 2t)/2``.
    """
    alpha = tilt(punch, a, c)
    return integrate(lambda t: (a - c + 2 * t) * float(punch.slope(t, alpha)), a, c,
                     _breaks(punch)) / (2 * A)


def moment(punch: Punch, a: float, c: float, A: float) -> float:
    """``P s = -int p x dx = (1/8A) int (8t^2 + 4t(a-c) - (a+c)^2) v'(t)/w(t) dt``.

    (appendix, rotational equilibrium; ``int w(x) x/(t-x) dx = pi/8 (8t^2 + 4t(a-c) - (a+c)^2)``.)
    """
    alpha = tilt(punch, a, c)
    return integrate(lambda t: (8 * t * t + 4 * t * (a - c) - (a + c) ** 2)
                     * float(punch.slope(t, alpha)), a, c, _breaks(punch)) / (8 * A)


def pressure(punch: Punch, a: float, c: float, A: float, x: float) -> float:
    """Compressive pressure ``(w(x)/(pi A)) PV int v'(t)/(w(t)(t-x)) dt`` (eq. inverted_IE).

    The principal value is removed by the same subtraction, in ``x = m + h cos(theta)``,
    by :func:`sie.pressure_by_quadrature` (adaptive quadrature, no closed form).
    """
    return float(pressure_by_quadrature(punch, A, a, c, 0.0, x)[0])


def segment_cauchy(lo: float, hi: float, a: float, c: float, x: float) -> float:
    """``int_lo^hi dt/(w(t)(t-x))``, a principal value when ``lo < x < hi`` (appendix F_j/w)."""
    pieces = [lo, hi]
    if lo < x < hi:
        d = 0.25 * min(x - lo, hi - x)
        pieces = [lo, x - d, x + d, hi]
    total = 0.0
    for p, q in zip(pieces[:-1], pieces[1:]):
        left, right = p == -a, q == c
        if p < x < q:  # Cauchy weight 1/(t - x) on an interior piece
            val, _ = quiet_quad(lambda t: 1 / math.sqrt((t + a) * (c - t)), p, q, weight="cauchy",
                          wvar=x, epsabs=0.0, epsrel=EPS, limit=400)
        else:
            def g(t: float, left=left, right=right) -> float:
                wl = 1.0 if left else (t + a) ** -0.5
                wr = 1.0 if right else (c - t) ** -0.5
                return wl * wr / (t - x)
            val, _ = quiet_quad(g, p, q, weight="alg", wvar=(-0.5 if left else 0.0, -0.5 if right else 0.0),
                          epsabs=0.0, epsrel=EPS, limit=400)
        total += val
    return total


def strain_in_stick(q: Callable[[float], float], a: float, c: float, breaks, x: float) -> float:
    """``(1/pi) PV int_{-a}^{c} q(t)/(t-x) dt`` for a bounded ``q`` (eq. integral_equation_tangential)."""
    qx = q(x)
    pts = sorted({-a, c, x, *[t for t in breaks if -a < t < c]})
    total = 0.0
    for lo, hi in zip(pts[:-1], pts[1:]):
        val, _ = quiet_quad(lambda t: (q(t) - qx) / (t - x), lo, hi, epsabs=0.0, epsrel=1e-12, limit=400)
        total += val
    return (total + qx * math.log((c - x) / (x + a))) / math.pi

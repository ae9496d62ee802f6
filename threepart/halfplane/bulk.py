"""A bulk stress in the substrate during partial slip: what every half-plane method shares.

The derivation is in docs/BULK_STRESS.md. For elastically similar bodies the
substrate's uniform strain ``eps = sigma_bulk (1 - nu^2)/E = A sigma_bulk/4``
(``A`` of eq. 4) enters the stick condition of eq.
(integral_equation_tangential), and the Ciavarella–Jäger corrective pressure
``p*`` becomes the normal pressure of the same punch with its tilt shifted by
:func:`corrective_tilt`. The superposition holds while both slip zones slip in
the direction that opposes ``q`` at every stage of the proportional load path;
:func:`slip_direction_margin` measures that exactly.

* :func:`check_sigma_bulk` -- the input check of ``sigma_bulk``;
* :func:`corrective_tilt` -- the tilt ``alpha*`` of the corrective contact;
* :func:`slip_direction_margin` -- the margin of the slip direction at both contact ends;
* :func:`slip_dissipation` -- the friction work of a fretting cycle, ``4 f^2 ∫ p gap*``.
"""
from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np
from numpy.typing import ArrayLike

from ..errors import NoConvergenceError, SlipReversalError
from ..problem.checks import finite
from .legendre import gauss01

__all__ = ["check_sigma_bulk", "corrective_tilt", "slip_direction_margin", "slip_dissipation"]


def check_sigma_bulk(sigma_bulk: object, normal: Any = None, Q: float = 0.0) -> float:
    """``sigma_bulk`` as a finite float (tension positive), else ``ValueError``/``TypeError``.

    With the ``normal`` result and the shear load ``Q`` (``Q_max`` of a cycle) it
    also refuses, before any numerics, a bulk stress that reverses the slip at
    the very start of the load path: there the slip-direction margin
    (docs/BULK_STRESS.md, eq. B8 at ``lam = 0``) is ``|Q|/π - |sigma_bulk| (a + c)/8``
    (:class:`~threepart.errors.SlipReversalError`).
    """
    value = finite("sigma_bulk", sigma_bulk)
    if normal is not None and value:
        bound = 8.0 * abs(Q) / (math.pi * (normal.a + normal.c))
        if abs(value) > bound * (1.0 + 1e-12):
            gl, gr = slip_direction_margin(Q if Q else 1.0, value, normal.a, normal.c, -normal.a, normal.c)
            end = "left" if float(np.min(gl)) < float(np.min(gr)) else "right"
            raise SlipReversalError(
                f"`sigma_bulk` = {value:.6g} reverses the slip at the {end} end of the contact from the "
                f"start of the load path, with `Q` = {Q:.6g} rising in proportion (the "
                f"Ciavarella–Jäger superposition does not hold): it needs |sigma_bulk| <= "
                f"8|Q|/(π (a + c)) = {bound:.6g}")
    return value


def corrective_tilt(alpha: ArrayLike, A: float, Q: float, f: float, sigma_bulk: ArrayLike) -> np.ndarray:
    """Tilt of the corrective contact ``p*``: ``alpha* = alpha - sign(Q) A sigma_bulk/(4 f)``.

    In the stick zone ``(A/π) ∫ q/(x - t) dt = A sigma_bulk/4`` (the bulk
    strain); with ``q = sign(Q) f (p - p*)`` and eq. (integral_equation) for
    ``p`` (slope ``alpha + g'``), ``p*`` solves eq. (integral_equation_2) with
    the slope ``alpha* + g'`` (docs/BULK_STRESS.md, eq. B4). ``A`` is the
    compliance of an elastically similar pair, ``4(1 - nu^2)/E``, whose quarter
    is the substrate's strain per unit bulk stress (eq. B2).
    """
    return np.asarray(alpha, dtype=float) - math.copysign(1.0, Q) * A * np.asarray(sigma_bulk) / (4 * f)


def psi(t: np.ndarray) -> np.ndarray:
    """``arccosh(1 + t)/sqrt(t (t + 2))`` for ``t >= 0`` (1 at ``t = 0``), free of cancellation."""
    t = np.maximum(np.asarray(t, dtype=float), 0.0)
    root = np.sqrt(t * (t + 2.0))
    with np.errstate(invalid="ignore", divide="ignore"):
        exact = np.log1p(t + root) / root
    return np.where(t < 1e-8, 1.0 - t / 3.0, exact)


def slip_direction_margin(Q: float, sigma_bulk: float, a: float, c: float, left: ArrayLike,
                          right: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Margins ``(g_left, g_right)`` (N/mm) of the slip direction in the two slip zones.

    On the load path ``Q`` and ``sigma_bulk`` rise in proportion; with the stick
    zone ``[l, r] = [m - h, m + h]`` the traction increment per unit of the
    load parameter is ``dq = [Q/π + (sigma_bulk/4)(m - t)]/sqrt((t - l)(r - t))``
    (the only solution of the stick condition with ``∫ dq = Q``), and the slip
    increment at ``x > r`` is ``-A ∫_r^x N/W``, ``N`` the numerator and
    ``W = sqrt((t - l)(t - r))`` (docs/BULK_STRESS.md, eq. B7). It opposes
    ``q`` throughout the slip zone ``(r, c]`` exactly when

        g_right = |Q|/π ψ(ξ) - sign(Q) sigma_bulk h/4 >= 0,   ξ = (c - m)/h,

    ``ψ(ξ) = arccosh ξ / sqrt(ξ^2 - 1)``; the left one has ``ξ = (m + a)/h`` and
    ``+``. ``g = 0`` at ``ξ = 1`` is the stick-zone end beginning to move
    outwards. ``left``, ``right`` broadcast (states along the path).
    """
    left, right = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    h = 0.5 * (right - left)
    st = math.copysign(1.0, Q) * sigma_bulk
    g_right = abs(Q) / math.pi * psi((c - right) / h) - st * h / 4
    g_left = abs(Q) / math.pi * psi((left + a) / h) + st * h / 4
    return g_left, g_right


#: Gauss–Legendre nodes per panel of the first and the last friction-work quadrature
FIRST_NODES, MAX_NODES = 32, 4096
#: relative change of the friction work at which its quadrature has settled, where the
#: integrand's rounding allows it
SETTLE_RTOL = 1e-13
#: a settled quadrature may differ between two levels by this multiple of the integrand's own
#: rounding (:func:`_dissipation`'s ``noise``): the gap outside a tiny slip zone is a difference
#: of O(1) terms, measured 1e-9 of itself, so 1e-13 was out of reach (issue 29)
NOISE_FACTOR = 10.0
#: relative perturbation of the abscissae that exposes that rounding (a few ulps)
NOISE_STEP = 8 * np.finfo(float).eps


def slip_dissipation(pressure: Callable[[np.ndarray], np.ndarray], gap: Callable[[np.ndarray], np.ndarray],
                     f: float, a: float, c: float, stick: tuple[float, float],
                     joins: ArrayLike = ()) -> tuple[float, int]:
    """Friction work of one fretting cycle (Masing's rule), ``W = 4 f^2 ∫ p(x) gap*(x) dx``.

    ``gap*`` is the gap of the corrective contact at ``Q_max`` outside the stick
    zone ``stick`` (the slip at ``Q_max`` is ``f gap*``): on loading each point
    slips by ``f gap*`` under ``|q| = f p``, unloading and reloading twice that
    (docs/BULK_STRESS.md, eq. B9). Each slip zone, cut at the ``joins``, is
    integrated by Gauss–Legendre in ``θ`` with ``x = lo + (hi - lo)(1 - cos θ)/2``,
    which makes the square-root ends smooth; the nodes per panel are doubled
    from ``FIRST_NODES`` until ``W`` settles to ``SETTLE_RTOL``, or to
    ``NOISE_FACTOR`` times the integrand's rounding where that is larger
    (returned with ``W``).

    Raises
    ------
    NoConvergenceError
        If it has not settled with ``MAX_NODES`` nodes per panel.
    """
    nodes, previous, change = FIRST_NODES, math.nan, math.nan
    while nodes <= MAX_NODES:
        W, noise = _dissipation(pressure, gap, f, a, c, stick, joins, nodes)
        change = abs(W - previous)
        if change <= max(SETTLE_RTOL * abs(W), NOISE_FACTOR * noise):
            return W, nodes
        previous, nodes = W, 2 * nodes
    raise NoConvergenceError(f"fretting energy: the slip-zone quadrature did not settle with {MAX_NODES} "
                             f"nodes per panel (last change {change / abs(W):.2g} of W, the integrand's "
                             f"rounding {noise / abs(W):.2g}); no result is returned")


def _dissipation(pressure: Callable[[np.ndarray], np.ndarray], gap: Callable[[np.ndarray], np.ndarray],
                 f: float, a: float, c: float, stick: tuple[float, float], joins: ArrayLike,
                 nodes: int) -> tuple[float, float]:
    """``W`` with ``nodes`` per panel, and its rounding: the same sum of ``|Δgap|`` at abscissae moved by a few ulps."""
    theta, w = gauss01(nodes)                  # Gauss–Legendre in θ on [0, π]
    theta, w = np.pi * theta, np.pi * w
    total = noise = 0.0
    for lo, hi in ((-a, stick[0]), (stick[1], c)):
        if hi <= lo:
            continue
        cuts = sorted({lo, hi, *(float(j) for j in np.ravel(joins) if lo < j < hi)})
        for p0, p1 in zip(cuts[:-1], cuts[1:]):
            x = p0 + (p1 - p0) * 0.5 * (1 - np.cos(theta))
            wp = w * 0.5 * (p1 - p0) * np.sin(theta) * pressure(x)
            g = gap(x)
            total += float(np.sum(wp * g))
            noise += float(np.sum(np.abs(wp * (gap(x * (1 + NOISE_STEP)) - g))))
    return 4 * f * f * total, 4 * f * f * noise

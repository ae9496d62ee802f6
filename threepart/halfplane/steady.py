"""The periodic steady state of in-phase loading: what every half-plane method shares.

The derivation is in docs/STEADY_STATE.md (equations S1--S12). Two states
``(P, s, Q, sigma_bulk)`` are the ends of the cycle; the loads move linearly
between them, all four in phase. With elastically similar bodies the change of
the shear from the start ``i`` of a half-cycle to the state ``lam`` on it is

    Δq = sign(ΔQ) f [p_i + p_lam - 2 p*_lam],                         (S4)

``p*_lam`` the bounded normal pressure of the same punch on the stick zone, of
load :func:`corrective_load` and tilt :func:`corrective_tilt_cycle`. The
permanent stick zone is that of ``lam = 1``.

* :func:`check_cycle_states` -- the input check of ``states`` and ``f``;
* :func:`state_values` -- one state's four values, from a tuple or a mapping by :data:`STATE_KEYS`;
* :func:`ramp` -- ``(P, s, Q, sigma_bulk)`` at the fractions ``lam`` of a half-cycle;
* :func:`corrective_load`, :func:`corrective_tilt_cycle` -- ``P*`` and ``alpha*`` (S5, S6);
* :func:`tilt_rate` -- ``d alpha/d lam`` of a normal solution on the path (S8);
* :func:`gap_rate` -- ``d gap*/d lam`` of the corrective contact outside it (S9);
* :func:`cycle_margin` -- the slip-direction margins at the two contact ends (S10);
* :func:`half_cycle_work` -- the friction work of a half-cycle by quadrature (S11);
* :func:`lam_rule` -- its Gauss–Legendre fractions ``lam`` and weights;
* :func:`cycle_states` -- the states of a cycle marched as a load history, from rest;
* :func:`common_contact` -- the intersection of the two end contacts, where a permanent stick zone lies;
* :func:`shakes_down` -- whether the permanent stick zone covers it (eq. S12).
"""
from __future__ import annotations

import math
from typing import Any, Callable, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .bulk import psi
from ..errors import (DisjointContactsError, InputError, InputTypeError, NoConvergenceError,
                      OneSidedSlipError, StickZoneError, full_sliding)
from .legendre import gauss01
from ..problem.checks import finite, positive, show

__all__ = ["STATE_KEYS", "state_values", "shakes_down", "common_contact", "cycle_states", "check_cycle_states", "ramp", "corrective_load", "corrective_tilt_cycle", "tilt_rate",
           "gap_rate", "cycle_margin", "half_cycle_work", "lam_rule", "WORK_RTOL", "WORK_NODES"]

#: relative change of the friction work between two quadratures at which it has settled
WORK_RTOL = 1e-12
#: Gauss–Legendre nodes of the first quadrature (in ``lam`` and per slip-zone panel); doubled
WORK_NODES = 16
#: the most nodes tried before NoConvergenceError
MAX_WORK_NODES = 1024

LoadState = tuple[float, float, float, float]


def check_cycle_states(states: Any, f: Any) -> tuple[tuple[LoadState, LoadState], float]:
    """``states`` as two ``(P, s, Q, sigma_bulk)`` float tuples and ``f`` as a float > 0.

    ``P`` must be > 0 and ``|Q| < f P`` at both ends (``FullSlidingError``
    otherwise, naming the state). Checked before any numerics.
    """
    if isinstance(states, (str, bytes)) or not hasattr(states, "__len__"):
        raise InputTypeError(f"`states` must be a sequence of two (P, s, Q, sigma_bulk) tuples, not "
                        f"{type(states).__name__}")
    if len(states) != 2:
        raise InputError(f"`states` has {len(states)} entries: it must hold the two ends of the "
                         "cycle, each (P, s, Q, sigma_bulk)")
    f = positive("f", f)
    out = []
    for k, st in enumerate(states):
        st = state_values(st, f"`states[{k}]`")
        P = positive(f"states[{k}].P", st[0])
        s, Q, sigma = (finite(f"states[{k}].{n}", v) for n, v in zip(("s", "Q", "sigma_bulk"), st[1:]))
        if abs(Q) >= f * P:
            raise full_sliding(f"states[{k}].Q", Q, f, P, "there is no steady state with a stick zone")
        out.append((P, s, Q, sigma))
    return (out[0], out[1]), f


#: the names of a state's four values, in order (a mapping gives them by these keys)
STATE_KEYS = ("P", "s", "Q", "sigma_bulk")


def state_values(state: Any, label: str, length_error: type[Exception] = InputError) -> tuple[Any, ...]:
    """A state's four values ``(P, s, Q, sigma_bulk)``, unchecked: from a sequence of four, or a
    mapping with exactly the keys :data:`STATE_KEYS`; else ``TypeError``/``ValueError`` (``length_error``
    for a sequence of another length) whose message starts with ``label`` (e.g. ```states[0]```)."""
    if isinstance(state, Mapping):
        keys = set(state)
        if keys != set(STATE_KEYS):
            missing, extra = sorted(set(STATE_KEYS) - keys), sorted(map(str, keys - set(STATE_KEYS)))
            raise InputError(f"{label} = {show(state)} must have exactly the keys {', '.join(STATE_KEYS)}"
                             + (f" (missing {', '.join(missing)})" if missing else "")
                             + (f" (unknown {', '.join(extra)})" if extra else ""))
        return tuple(state[key] for key in STATE_KEYS)
    if isinstance(state, (str, bytes)) or not isinstance(state, (Sequence, np.ndarray)):
        raise InputTypeError(f"{label} = {show(state)} must be a ({', '.join(STATE_KEYS)}) tuple or a "
                             f"mapping with those keys, not {type(state).__name__}")
    if len(state) != len(STATE_KEYS):
        raise length_error(f"{label} = {show(state)} has {len(state)} values: it must be a "
                           f"({', '.join(STATE_KEYS)}) tuple")
    return tuple(state)


def ramp(start: LoadState, end: LoadState, lam: ArrayLike) -> tuple[np.ndarray, ...]:
    """``(P, s, Q, sigma_bulk)`` at the fractions ``lam`` from ``start`` to ``end`` (each linear in ``lam``)."""
    lam = np.asarray(lam, dtype=float)
    return tuple(a + lam * (b - a) for a, b in zip(start, end))


def corrective_load(P_i: float, P: ArrayLike, dQ: ArrayLike, f: float) -> np.ndarray:
    """``P* = [f (P_i + P) - |ΔQ|]/(2 f)`` (eq. S6), horizontal equilibrium of the change (S4)."""
    return (f * (P_i + np.asarray(P, dtype=float)) - np.abs(dQ)) / (2 * f)


def corrective_tilt_cycle(alpha_i: float, alpha: ArrayLike, A: float, sign: float, dsigma: ArrayLike,
                          f: float) -> np.ndarray:
    """``alpha* = (alpha_i + alpha)/2 - sign(ΔQ) A Δsigma_bulk/(8 f)`` (eq. S5).

    The stick condition of the change (docs/BULK_STRESS.md B3 with ``Δsigma_bulk``)
    with eq. (integral_equation) for ``p_i`` and ``p``.
    """
    return 0.5 * (alpha_i + np.asarray(alpha, dtype=float)) - sign * A * np.asarray(dsigma) / (8 * f)


def tilt_rate(A: float, a: ArrayLike, c: ArrayLike, dP: ArrayLike, dM: ArrayLike) -> np.ndarray:
    """``d alpha = 2 A (m dP - dM)/(π h^2)`` of a normal solution on ``[-a, c]`` (eq. S8).

    The change of a bounded pressure whose load changes by ``dP`` and moment
    ``P s`` by ``dM`` is ``[dP/π + (d alpha/A)(m - t)]/w(t)`` (the ends move, the
    pressure vanishes there); its moment ``m dP - π h^2 d alpha/(2A)`` fixes ``d alpha``.
    """
    a, c = np.asarray(a, dtype=float), np.asarray(c, dtype=float)
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    return 2 * A * (m * np.asarray(dP) - np.asarray(dM)) / (math.pi * h * h)


def gap_rate(x: ArrayLike, left: ArrayLike, right: ArrayLike, A: float, dP: ArrayLike,
             dalpha: ArrayLike) -> np.ndarray:
    """``d gap/d lam`` outside ``[left, right]`` of a normal contact whose load and tilt change by ``dP``, ``dalpha``.

    ``(A|dP|... )``: right of the zone ``-(A dP/π) arccosh ξ + dalpha h sqrt(ξ^2 - 1)``,
    ``ξ = (x - m)/h``; left of it ``-(A dP/π) arccosh ξ - dalpha h sqrt(ξ^2 - 1)``,
    ``ξ = (m - x)/h`` (eq. S9); 0 inside. Broadcasts.
    """
    x = np.asarray(x, dtype=float)
    left, right = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    h, m = 0.5 * (right - left), 0.5 * (right + left)
    side = np.sign(x - m)
    xi = np.maximum(np.abs(x - m) / h, 1.0)
    return (-A * np.asarray(dP) / math.pi * np.arccosh(xi)
            + side * np.asarray(dalpha) * h * np.sqrt(xi * xi - 1.0))


def cycle_margin(left: ArrayLike, right: ArrayLike, a: ArrayLike, c: ArrayLike, A: float, f: float,
                 dP_star: float, dalpha_star: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Margins ``(g_left, g_right)`` (N/mm) of the slip direction at the contact ends ``-a``, ``c`` (eq. S10).

    Every point of the slip zones must slip forward (in the sense of ``ΔQ``):
    ``d gap*/d lam >= 0`` there (:func:`gap_rate`). ``ψ`` falls with ``ξ``, so
    the contact end binds:

        g_right = -f dP*/π ψ(ξ_c) + (f/A) dalpha* h,
        g_left  = -f dP*/π ψ(ξ_a) - (f/A) dalpha* h,

    the fretting cycle's docs/BULK_STRESS.md eq. (B8) when ``P`` is constant.
    """
    left, right = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    h, m = 0.5 * (right - left), 0.5 * (right + left)
    lead = -f * dP_star / math.pi
    tail = f / A * np.asarray(dalpha_star) * h
    # ψ(ξ) = arccosh ξ/sqrt(ξ^2 - 1), as threepart.halfplane.bulk's (of ξ - 1)
    return (lead * psi((m + np.asarray(a)) / h - 1.0) - tail, lead * psi((np.asarray(c) - m) / h - 1.0) + tail)


#: ``path(lam)`` -> (pressure(x) broadcasting over lam, a, c, left, right, dP*, dalpha*) on a half-cycle
Path = Callable[[np.ndarray], tuple[Callable[[np.ndarray], np.ndarray], np.ndarray, np.ndarray,
                                     np.ndarray, np.ndarray, float, np.ndarray]]


def lam_rule(n: int, breaks: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Fractions ``lam`` and weights: ``n`` Gauss nodes per panel between the ``breaks``, in ``(1 - cos πt)/2``."""
    t, wt = gauss01(n)
    edges = np.array(sorted({0.0, 1.0, *breaks}))
    lo, span = edges[:-1, None], np.diff(edges)[:, None]
    lam = lo + span * 0.5 * (1 - np.cos(math.pi * t))     # smooth at both ends of each panel
    return lam.ravel(), (span * wt * 0.5 * math.pi * np.sin(math.pi * t)).ravel()


def _work(path: Path, A: float, f: float, b: float, n: int, breaks: tuple[float, ...] = ()) -> float:
    """:func:`half_cycle_work` on ``n`` nodes per panel in ``lam`` and per slip-zone panel."""
    lam, wl = lam_rule(n, breaks)
    pressure, a, c, left, right, dP, dalpha = path(lam)
    theta, wth = gauss01(n)
    theta, wth = theta * math.pi, wth * math.pi
    xs, ws = [], []                     # the six panels side by side, one evaluation of each factor
    for lo, hi in ((-a, left), (right, c)):
        cuts = [lo, np.clip(-b, lo, hi), np.clip(b, lo, hi), hi]
        for p0, p1 in zip(cuts[:-1], cuts[1:]):
            span = np.maximum(p1 - p0, 0.0)[:, None]
            xs.append(p0[:, None] + span * 0.5 * (1 - np.cos(theta)))
            ws.append(wth * 0.5 * span * np.sin(theta))
    x, w = np.hstack(xs), np.hstack(ws)
    rate = gap_rate(x, left[:, None], right[:, None], A, dP, dalpha[:, None])
    return float(2 * f * f * np.sum(wl * np.sum(w * pressure(x) * rate, axis=1)))


def half_cycle_work(path: Path, A: float, f: float, b: float, rtol: float = WORK_RTOL,
                    breaks: tuple[float, ...] = ()) -> tuple[float, int]:
    """Friction work of one half-cycle, ``2 f^2 ∫_0^1 dlam ∫ p_lam(x) d gap*/d lam dx`` (eq. S11).

    A point of a slip zone slips by ``2 f d gap*`` (eq. S7) under ``|q| = f p_lam``.
    ``path(lam)`` gives, at the fractions ``lam``, the pressure (a callable
    broadcasting ``x`` of shape ``(len(lam), k)``), the contact ends ``a, c``,
    the stick-zone ends ``left, right``, ``dP*/dlam`` and ``d alpha*/dlam``.
    Gauss–Legendre in ``lam = (1 - cos πt)/2`` and, over each slip zone cut at the
    joins ``±b``, in ``θ`` with ``x = lo + (hi - lo)(1 - cos θ)/2``; the nodes are
    doubled from :data:`WORK_NODES` until the work settles to ``rtol``. ``breaks`` are
    fractions where a stick-zone or contact end crosses a join (the SIE past the
    closed form): the ``lam`` quadrature is composite, with panel ends there.

    Returns
    -------
    work, nodes

    Raises
    ------
    NoConvergenceError
        If it has not settled with :data:`MAX_WORK_NODES` nodes.
    """
    n, previous = WORK_NODES, math.nan
    while n <= MAX_WORK_NODES:
        W = _work(path, A, f, b, n, breaks)
        if abs(W - previous) <= rtol * abs(W):
            return W, n
        previous, n = W, 2 * n
    raise NoConvergenceError(f"steady-state energy: the quadrature did not settle with {MAX_WORK_NODES} "
                             "nodes; no result is returned")


def shakes_down(left: float, right: float, lo: float, hi: float) -> bool:
    """Whether the permanent stick zone ``[left, right]`` covers the smaller contact ``[lo, hi]`` (eq. S12).

    True: nothing slips in the steady state (shakedown). False: both ends slip.

    Raises
    ------
    OneSidedSlipError
        If the zone reaches one edge of the smaller contact but not the other:
        one end slips and the other has shaken down (or the two slip in
        opposite senses), which the superposition of one sense of slip a
        half-cycle does not model.
    """
    if not (math.isfinite(left) and math.isfinite(right) and left < right):
        raise StickZoneError(f"the permanent stick zone [{left:.6g}, {right:.6g}] is empty or not finite: "
                             "no stick zone is returned")
    tol = 1e-12 * (hi - lo)
    at_lo, at_hi = left <= lo + tol, right >= hi - tol
    if at_lo and at_hi:
        return True
    if right <= lo or left >= hi:
        raise OneSidedSlipError(
            f"the superposition's permanent stick zone would lie wholly outside the smaller contact "
            f"[{lo:.6g}, {hi:.6g}] (at [{left:.6g}, {right:.6g}]): the ends slip in opposite senses, which "
            "the steady-state superposition (one sense of slip a half-cycle) does not model")
    if at_lo or at_hi:
        raise OneSidedSlipError(
            f"the permanent stick zone [{left:.6g}, {right:.6g}] would reach the "
            f"{'left' if at_lo else 'right'} edge of the smaller contact [{lo:.6g}, {hi:.6g}] but not "
            "the other: one end slips and the other has shaken down, or the two slip in opposite "
            "senses, which the steady-state superposition (one sense of slip a half-cycle) does not model")
    return False


def common_contact(contacts: tuple[tuple[float, float], tuple[float, float]]) -> tuple[float, float]:
    """``(lo, hi)``: the points in contact at both ends of a cycle, where a permanent stick zone lies (eq. S12).

    ``contacts`` are the end states' contacts ``(-a_0, c_0)``, ``(-a_1, c_1)``.

    Raises
    ------
    DisjointContactsError
        If they do not overlap: no point stays in contact all cycle, so no point
        sticks all cycle; no stick zone is returned outside a contact.
    """
    (l0, r0), (l1, r1) = contacts
    lo, hi = max(l0, l1), min(r0, r1)
    if not hi > lo:
        raise DisjointContactsError(
            f"the contacts of the cycle's two end states, [{l0:.6g}, {r0:.6g}] and [{l1:.6g}, {r1:.6g}], "
            "do not overlap: no point stays in contact all cycle, so the cycle has no permanent stick zone")
    return lo, hi


def cycle_states(start: LoadState, end: LoadState, steps: int, cycles: int) -> np.ndarray:
    """The states ``(P, s, Q, sigma_bulk)``, ``(K, 4)``, of the cycle between ``start`` and ``end`` marched as a history.

    From rest the four loads rise in proportion to ``start`` (``P`` at the lever arm
    ``s`` of ``start``) in ``steps`` states, then ``cycles`` cycles ``start -> end ->
    start`` of ``steps`` states a half-cycle, the loads linear (eq. S1): each cycle
    ends at ``start``, every ``2 steps`` states.
    """
    lam = np.linspace(0.0, 1.0, steps + 1)[1:]
    first = np.array(ramp((0.0, start[1], 0.0, 0.0), start, lam)).T
    half, back = (np.array(ramp(a, b, lam)).T for a, b in ((start, end), (end, start)))
    return np.vstack([first, *([half, back] * cycles)])

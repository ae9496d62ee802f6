"""The fretting cycle: ``Q`` from 0 to ``Q_max``, to ``-Q_max`` and back, at constant ``P`` and ``s``.

On loading the shear is the Ciavarella–Jäger traction of :mod:`closedform.slip`,
``q_load(x; Q) = sign(Q) f [p(x) - p*_Q(x)]``, where ``p*_Q`` is the normal
pressure of the same punch, with the same tilt ``alpha``, on the stick zone
``[-(d+e), d-e]`` of load ``P - |Q|/f`` (eqs. integral_equation_2,
horizontal_equilibrium). A reversal superposes the same solution, doubled
(Mindlin–Deresiewicz, Masing's rule)::

    unloading, Q_max -> Q:   q = q_load(Q_max) - 2 q_load((Q_max - Q)/2)
    reloading, -Q_max -> Q:  q = -q_load(Q_max) + 2 q_load((Q_max + Q)/2)

and so do the relative slip and the rigid tangential displacement ``delta``;
the zone that has not slipped since the reversal is the stick zone of
``q_load`` at ``(Q_max ∓ Q)/2``. Every stick zone of the cycle is therefore a
loading stick zone of load ``u`` in ``[0, Q_max]``; the smallest is the one at
``Q_max``.

The loading curve ``delta = F(u)``
---------------------------------
Eq. (integral_equation_tangential) and eq. (integral_equation) have the same
kernel and the same compliance ``A`` (eq. 4) for similar materials, so the
relative tangential displacement of the surfaces is the log-potential
``-(A/π) ∫ q(t) ln|x - t| dt`` plus a term linear in ``Q``, just as the normal
one is that of the compressive pressure. In the stick zone it equals
``delta``. Both log-potentials of ``q = f (p - p*)`` are evaluated inside their
own contacts, where each is ``approach - alpha x - g(x)`` of its normal
problem (eq. 2, ``g`` the profile), so ``alpha x`` and ``g`` cancel and

    F(u) = f [D(P) - D(P - u/f)]        (factor exactly f; plus a term linear in u),

with ``D`` the rigid approach of the normal problem at fixed ``alpha``
(:func:`approach`). Averaging the log-potential against the Chebyshev weight
``1/(π w)``, under which ``ln|x - t|`` averages to ``ln(h/2)`` for every ``t`` in
the contact, gives it in closed form:

    D(a, c) = <g>_w + alpha m - (A P/π) ln(h/2),     <g>_w = (1/π) ∫ g/w dx,

``h = (a+c)/2``, ``m = (c-a)/2``, ``w = sqrt((x+a)(c-x))``. Its load derivative at
fixed ``alpha`` is that of the flat-punch pressure ``1/(π w)``:
``dD/dP = -(A/π) ln(h/2)``, so the tangential compliance is
``F'(u) = -(A/π) ln(d(u)/2)``, ``d(u)`` the stick zone's half-width.

Energy per cycle
----------------
The loop area of Masing's rule is ``4 Q_max F(Q_max) - 8 ∫_0^Q_max F(u) du``
(positive: ``F`` is convex), i.e. ``4 ∫_0^Q_max (2u - Q_max) F'(u) du``, in
which any part of ``F`` linear in ``u`` integrates to zero:

    W = (4A/π) ∫_0^Q_max (2u - Q_max) ln(h/d(u)) du,

evaluated by Gauss–Legendre quadrature in ``u`` (the stick zones at the nodes
by the vectorised roots of :mod:`closedform.newton`), refined until it settles.

Slip
----
The derivative of the relative slip is the Cauchy integral of ``q`` (eq.
integral_equation_tangential); in the slip zones it is ``f`` times the gap
slope of the stick zone's normal problem, so the slip on loading is ``f``
times that gap (:func:`stick_gap`, closed form). The slip amplitude of the
cycle is the slip at ``Q_max`` on loading: the state at ``-Q_max`` is its mirror.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from threepart.halfplane.bulk import check_sigma_bulk, corrective_tilt, slip_dissipation
from threepart.errors import LiftOffError, NoConvergenceError, StickZoneError
from threepart.halfplane.legendre import gauss01
from threepart.problem.punch import Punch
from threepart.results import Diagnostics, MasingCycle, NormalResult
from threepart.problem.validate import check_states
from threepart.results.slip import check_shear

from . import formulas

from .slip import (check_coulomb, check_slip_direction, stick_zone_bound, stick_zone_leaves,
                   stick_zones_on_path)

__all__ = ["FrettingSolution", "fretting_cycle", "approach", "stick_gap", "omega",
           "loop_energy", "fretting_iv"]

#: Gauss–Legendre nodes of the first energy quadrature; doubled until it settles
ENERGY_NODES = 16
#: the most nodes tried before NoConvergenceError
MAX_ENERGY_NODES = 2048
#: relative change of the energy between two quadratures at which it has settled
ENERGY_RTOL = 1e-13


def omega(beta: ArrayLike) -> np.ndarray:
    """``ω(β) = ∫_0^β (cos β - cos φ)^2 dφ = β (1 + cos 2β/2) - (3/4) sin 2β``.

    The Chebyshev-weighted mean of an outer segment's quadratic: over the join
    angle ``β`` of eq. (f0) the segment ``(x ∓ b)^2`` averages to ``h^2 ω(β)/π``.
    A series replaces the cancelling closed form for ``β < 0.2``.
    """
    b = np.asarray(beta, dtype=float)
    b2 = b * b
    series = b2 * b2 * b * (2 / 15 - b2 * (8 / 315 - b2 * (2 / 945 - b2 * (16 / 155925
                                                                          - b2 * 4 / 1216215))))
    exact = b * (1 + 0.5 * np.cos(2 * b)) - 0.75 * np.sin(2 * b)
    return np.where(b < 0.2, series, exact)


def approach(punch: Punch, a: ArrayLike, c: ArrayLike, A: float, alpha: ArrayLike) -> np.ndarray:
    """Rigid approach ``D`` of the normal problem on ``[-a, c]`` with tilt ``alpha``.

    ``D = g(x) + alpha x - (A/π) ∫ p(t) ln|x - t| dt`` for any ``x`` in the contact
    (compressive ``p``, ``g`` the profile of eq. 2 without ``Delta`` and tilt):
    ``-Delta`` of eq. (2) up to a term linear in ``P``, which half-plane theory
    leaves undetermined. In closed form (module docstring)::

        D = kappa0 (m^2 + h^2/2)/2 + h^2 [kappa1 ω(beta1) + kappa2 ω(beta2)]/(2π)
            + alpha m - (A P/π) ln(h/2),

    with ``beta1, beta2`` of eq. (f0) and ``P`` of eq. (equilibrium_condition_1).
    ``a``, ``c`` and ``alpha`` broadcast; ``alpha`` must be the tilt that makes
    ``[-a, c]`` consistent (eq. consistency_condition), the corrective tilt
    under a bulk stress.
    """
    a, c, alpha = (np.asarray(v, dtype=float) for v in (a, c, alpha))
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    b1, b2 = formulas.beta(a, c, punch.b)
    AP = A * formulas.load(punch, a, c, A)
    mean_g = (0.5 * punch.kappa0 * (m * m + 0.5 * h * h)
              + h * h * (punch.kappa1 * omega(b1) + punch.kappa2 * omega(b2)) / (2 * math.pi))
    return mean_g + alpha * m - AP / math.pi * np.log(0.5 * h)


def _gap_right(xi: np.ndarray, h: float, F0: float, k_near: float, b_near: float,
               k_far: float, b_far: float) -> np.ndarray:
    """Gap beyond the right end of ``[m - h, m + h]`` at ``x = m + h cosh φ`` (``xi = cosh φ``).

    ``near`` is the segment the end lies on (curvature jump ``kappa2``, angle
    ``beta2``), ``far`` the other one.
    """
    phi = np.arccosh(xi)
    sh, t = np.sinh(phi), np.tanh(0.5 * phi)
    cn, cf = math.cos(b_near), math.cos(b_far)
    v_near = np.arctan2(math.cos(0.5 * b_near) * t, math.sin(0.5 * b_near))
    u_far = np.arctan2(math.sin(0.5 * b_far) * t, math.cos(0.5 * b_far))
    return h * h / math.pi * (
        0.5 * F0 * (sh * xi - phi)
        + k_near * ((xi - cn) ** 2 * v_near - 0.5 * math.sin(b_near) * (sh - cn * phi))
        - k_far * ((xi + cf) ** 2 * u_far - 0.5 * math.sin(b_far) * (sh + cf * phi)))


def stick_gap(punch: Punch, a: float, c: float, x: ArrayLike) -> np.ndarray:
    """Gap outside ``[-a, c]`` of the normal problem on it, whatever its tilt; 0 inside.

    Integrating the gap slope ``v'(x) + (A/π) ∫ p(t)/(t - x) dt`` (eq.
    integral_equation continued outside the contact) from the right end, with
    ``x = m + h cosh φ`` and the join angles of eq. (f0)::

        gap = h^2/π { F0 (sinh φ cosh φ - φ)/2
                      + kappa2 [(cosh φ - cos beta2)^2 V2 - sin beta2 (sinh φ - φ cos beta2)/2]
                      - kappa1 [(cosh φ + cos beta1)^2 U1 - sin beta1 (sinh φ + φ cos beta1)/2] },

    ``U1 = arctan(tan(beta1/2) tanh(φ/2))``, ``V2 = arctan(cot(beta2/2) tanh(φ/2))``
    and ``F0`` of eq. (f0); the left side is its mirror image. Hertz: ``(x sqrt(x^2 - h^2)
    - h^2 arccosh(x/h))/(2R)``. Valid for ``a, c >= b`` (the ends on the outer segments).
    """
    x = np.asarray(x, dtype=float)
    h, m = 0.5 * (a + c), 0.5 * (c - a)
    b1, b2 = (float(v) for v in formulas.beta(a, c, punch.b))
    F0 = float(formulas.F0(punch, a, c))
    xi = (x - m) / h
    right = _gap_right(np.maximum(xi, 1.0), h, F0, punch.kappa2, b2, punch.kappa1, b1)
    left = _gap_right(np.maximum(-xi, 1.0), h, F0, punch.kappa1, b1, punch.kappa2, b2)
    return np.where(xi > 1.0, right, np.where(xi < -1.0, left, 0.0))


def loop_energy(h: float, d: ArrayLike, u: ArrayLike, weights: ArrayLike, A: float,
                Q_max: float) -> float:
    """``W = (4A/π) ∫_0^Q_max (2u - Q_max) ln(h/d(u)) du`` by the quadrature ``(u, weights)``."""
    u, d, weights = (np.asarray(v, dtype=float) for v in (u, d, weights))
    return float(4 * A / math.pi * np.sum(weights * (2 * u - Q_max) * np.log(h / d)))


@dataclass(frozen=True)
class FrettingSolution(MasingCycle):
    """Closed-form fretting cycle from :func:`fretting_cycle`.

    ``shear``, ``slip`` and ``slip_amplitude`` take any ``Q`` on a branch, not only
    the recorded states: the stick zone of ``(Q_max ∓ Q)/2`` (with the bulk
    stress in proportion) is solved anew (:func:`closedform.slip.stick_zones_on_path`,
    microseconds).
    """

    method: str = "closedform"

    def _stick_load(self, u: float) -> tuple[float, float]:
        """Ends of the loading stick zone at ``u > 0`` (``sigma_bulk u/Q_max`` with it)."""
        a_s, c_s, _ = stick_zones_on_path(self.normal, self.Q_max, self.f, self.sigma_bulk,
                                          [u / self.Q_max])
        return -float(a_s[0]), float(c_s[0])

    def _q_load(self, x: np.ndarray, u: float) -> np.ndarray:
        """Shear of the loading state at ``u >= 0``: ``f (p - p*)``."""
        n = self.normal
        if u == 0:
            return np.zeros(x.shape)
        left, right = self._stick_load(u)
        return self.f * (n.pressure(x) - formulas.pressure(n.punch, -left, right, n.A, x))

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        """Slip of the loading state at ``u >= 0``: ``f`` times the stick zone's gap, in the contact."""
        n = self.normal
        if u == 0:
            return np.zeros(x.shape)
        left, right = self._stick_load(u)
        gap = stick_gap(n.punch, -left, right, x)
        return np.where((x > -n.a) & (x < n.c), self.f * gap, 0.0)


def fretting_iv(normal: NormalResult, Q_max: float, f: float, states: int
                 ) -> tuple[float, float, int]:
    Q_max, f = check_shear(normal, Q_max, f, "Q_max", "there is no fretting cycle",
                           argument="normal_solution")
    states = check_states(states)
    if not normal.within_paper:
        raise LiftOffError(f"`normal_solution` has its contact [{-normal.a:.6g}, {normal.c:.6g}] "
                           f"ending on the central segment [-b, b] = [{-normal.punch.b:g}, "
                           f"{normal.punch.b:g}], outside the closed form")
    return Q_max, f, states


def _stick_zones(normal: NormalResult, u: np.ndarray, f: float, Q_max: float,
                 sigma_bulk: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Ends ``(a*, c*)`` of the loading stick zones at the forces ``u`` (vectorised), ``(a, c)`` at 0.

    As :func:`closedform.solve_partial_slip`: load ``P - u/f`` (eq.
    horizontal_equilibrium) at the normal solution's tilt (eq. consistency_condition),
    shifted by the bulk stress ``sigma_bulk u/Q_max`` (:func:`threepart.halfplane.bulk.corrective_tilt`).

    Raises
    ------
    StickZoneError
        A stick zone (the one at ``Q_max`` first) would end inside the central segment.
    """
    punch = normal.punch
    a_s, c_s, out = stick_zones_on_path(normal, Q_max, f, sigma_bulk, u / Q_max)
    if bool(np.any(out)):
        raise StickZoneError(
            f"`Q_max`/(f P) = {Q_max / (f * normal.P):.6g}: the stick zone at `Q_max` would "
            f"{stick_zone_leaves(punch.b)}, where the closed form does not hold; it holds for "
            f"`Q_max`/(f P) < {stick_zone_bound(normal):.6g}"
            + (" without a bulk stress" if sigma_bulk else ""))
    return a_s, c_s


def _energy(normal: NormalResult, Q_max: float, f: float) -> tuple[float, int]:
    """The loop area ``W`` by Gauss–Legendre quadrature, doubled until it settles.

    The force is ``u = Q_max (1 - tau^2)``: the stick zone's half-width has a
    ``(u_c - u)^(3/2)`` branch point where an end would reach a join, at
    ``u_c >= Q_max``; in ``tau`` it becomes ``(u_c - Q_max + Q_max tau^2)^(3/2)``,
    smooth at the closed form's limit ``u_c = Q_max`` itself.
    """
    h = 0.5 * (normal.a + normal.c)
    # rounding of ln(h/d) (~1e-15) bounds the attainable accuracy for small Q_max/(f P)
    floor = 1e-14 * normal.A * Q_max**2
    n, previous = ENERGY_NODES, math.nan
    while n <= MAX_ENERGY_NODES:
        tau, w = gauss01(n)
        u, weights = Q_max * (1 - tau * tau), 2 * Q_max * tau * w
        a_s, c_s = _stick_zones(normal, u, f, Q_max)
        W = loop_energy(h, 0.5 * (a_s + c_s), u, weights, normal.A, Q_max)
        if abs(W - previous) <= ENERGY_RTOL * abs(W) + floor:
            return W, n
        previous, n = W, 2 * n
    raise NoConvergenceError(f"fretting energy: the Gauss–Legendre quadrature did not settle with "
                             f"{MAX_ENERGY_NODES} nodes (`Q_max` = {Q_max:g}); no result is returned")


def fretting_cycle(normal_solution: NormalResult, Q_max: float, f: float, *,
                   states: int = 21, sigma_bulk: float = 0.0) -> FrettingSolution:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` at the normal solution's ``P``, ``s``, ``alpha``.

    Parameters
    ----------
    normal_solution
        The normal problem (any method) in the closed form's framework; its
        punch, ``A``, ``a``, ``c``, ``alpha`` and ``P`` are used.
    Q_max
        Amplitude of the shear force, ``0 < Q_max < f P``.
    f
        Coefficient of friction, > 0.
    states
        Recorded states per branch, evenly spaced in ``Q``, both ends included (>= 2).
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q_max`` (tension positive),
        in phase with ``Q`` (``sigma_bulk Q/Q_max``); Masing's superposition
        carries it, as it is linear in ``Q`` (docs/BULK_STRESS.md).

    Returns
    -------
    FrettingSolution
        ``branch``, ``Q``, ``stick`` (the zone not slipped since the last
        reversal; the whole contact at ``Q = 0`` and at each reversal), ``delta``
        (Masing's rule on ``F(u) = f [D(P) - D(P - u/f)]``, :func:`approach`),
        ``energy`` (:func:`loop_energy`; under a bulk stress, which also works on
        the substrate, the friction work :func:`threepart.halfplane.bulk.slip_dissipation`).
        ``diagnostics`` hold ``steps`` (the recorded states per branch) and the
        time; ``info`` holds ``energy_nodes`` (of the energy quadrature).

    Raises
    ------
    ValueError
        ``Q_max`` or ``f`` not finite and > 0, ``states`` < 2.
    FullSlidingError
        ``Q_max >= f P``.
    StickZoneError
        The stick zone at ``Q_max`` (the smallest of the cycle) would end inside
        the central segment; the message gives the bound on ``Q_max/(f P)``.
        ``StickSeparationError`` (a subclass): a recorded stick zone on a
        concave centre breaks Coulomb's law (:func:`closedform.slip.check_coulomb`).
        ``SlipReversalError`` (a subclass): ``sigma_bulk`` reverses the slip at one
        end on the loading branch (and so on every branch).
    TypeError
        ``normal_solution`` not a NormalResult, ``states`` not an integer.
    LiftOffError
        The normal solution's contact ends on the central segment.
    NoConvergenceError
        The energy quadrature did not settle (not expected).
    """
    normal = normal_solution
    Q_max, f, states = fretting_iv(normal, Q_max, f, states)
    sigma_bulk = check_sigma_bulk(sigma_bulk, normal, Q_max)
    t0 = time.perf_counter()
    punch, A, alpha = normal.punch, normal.A, normal.alpha
    u = np.linspace(0.0, Q_max, states)
    check_slip_direction(normal, Q_max, f, sigma_bulk)
    a_s, c_s = _stick_zones(normal, u, f, Q_max, sigma_bulk)
    for i in range(1, states):      # Coulomb's law in every recorded loading state (concave centre)
        check_coulomb(normal, float(a_s[i]), float(c_s[i]), float(u[i]) / (f * normal.P))
    alpha_star = corrective_tilt(alpha, A, 1.0, f, sigma_bulk * u / Q_max)
    F = f * (approach(punch, normal.a, normal.c, A, alpha) - approach(punch, a_s, c_s, A, alpha_star))
    F[0] = 0.0
    if sigma_bulk == 0:
        energy, nodes = _energy(normal, Q_max, f)
    else:
        energy, nodes = slip_dissipation(normal.pressure, lambda x: stick_gap(punch, a_s[-1], c_s[-1], x),
                                         f, normal.a, normal.c, (-float(a_s[-1]), float(c_s[-1])))
    stick = np.column_stack([-a_s, c_s])
    diagnostics = Diagnostics(steps=states, timings={"total": time.perf_counter() - t0})
    return FrettingSolution.from_loading(normal, Q_max, f, u, stick, F, energy=energy,
                                         method="closedform", diagnostics=diagnostics,
                                         info={"energy_nodes": nodes}, sigma_bulk=sigma_bulk)

"""Fretting-fatigue parameters from the stress history of a fretting or flight cycle, for any method.

Every function here works on a :class:`~threepart.results.FrettingResult` of any
method through the shared interface only: ``cycle.stress(x, z, Q, branch, nu=...)``,
``cycle.shear(x, Q, branch)``, ``cycle.slip_amplitude(x)``, ``cycle.Q`` and
``cycle.branch``. None of them special-cases a method. Definitions, units and
references: ``docs/FATIGUE.md``.

Conventions (README): ``x`` along the surface, ``z >= 0`` the depth into the
substrate, tension positive; ``q(x)`` is the shear the punch exerts on the
substrate along ``+x``; plane strain, ``σyy = ν (σxx + σzz)``. A plane is named by
the angle ``theta`` (rad, in ``[0, π)``) of its normal ``n = (cos θ, sin θ)`` from
``+x`` toward ``+z``; every plane whose normal lies in the x–z plane is searched.
On such a plane the normal stress and the in-plane shear are (with ``φ = 2θ``)::

    σn = (σxx + σzz)/2 + (σxx - σzz)/2 cos φ + σxz sin φ
    τ  = -(σxx - σzz)/2 sin φ + σxz cos φ

and plane-strain Hooke's law gives the normal strain
``εn = (1 + ν)/E [σn - ν (σxx + σzz)]``.

Parameters (each a :class:`Parameter`: the field on the points and its hot spot)
----------
von_mises_range     -- max over pairs of states of the von Mises stress of the stress difference
swt                 -- Smith–Watson–Topper on the critical plane: max_θ σn,max Δεn / 2
findley             -- Findley on the critical plane: max_θ (τa + k σn,max)
ruiz                -- Ruiz's FDP τδ and FFDP σxx τ δ at the surface (Ruiz, Boddington & Chen 1984)

The table of parameters (name, label, unit, function, critical plane or not) that
:func:`threepart.fatigue.fatigue`, the command line and the report loop over, and
Crossland's parameter, are in :mod:`threepart.fatigue.table`; a cycle's stress
history (:class:`~threepart.fatigue.history.History`) in :mod:`threepart.fatigue.history`.

Building blocks
---------------
HotSpot             -- where a parameter peaks, how much, and on which plane
hot_spot            -- the one hot-spot rule: the first point within HOT_SPOT_TIE of the largest value
critical_plane      -- max over plane angles of a function of (σn, τ) histories
findley_k           -- Findley's constant checked: a float in [0, 10]
K_FINDLEY           -- the default Findley constant k = 0.3
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Sequence

import numpy as np

from ..results.cycles import SteadyStateResult
from .history import Cycle, History, check_cycle, as_history
from ..results.slip import BRANCHES
from ..stress.flamant import Stress
from ..problem.checks import finite, positive
from threepart.errors import InputError

__all__ = ["HotSpot", "Parameter", "Ruiz", "von_mises_range", "swt", "findley", "ruiz", "critical_plane",
           "hot_spot", "hot_spot_parameter", "K_FINDLEY", "COARSE_ANGLES", "ZOOM_LEVELS", "HOT_SPOT_TIE", "findley_k"]

#: Findley's constant ``k`` by default: 0.3 is typical of steels and titanium alloys
#: (Socie & Marquis, *Multiaxial Fatigue*, 2000, report 0.2–0.3); give the material's own
K_FINDLEY = 0.3
#: plane angles of the coarse scan over ``φ = 2θ`` in ``[0, 2π)`` (θ in steps of 1°)
COARSE_ANGLES = 180
#: zoom levels after the coarse scan: each scans 11 angles over ± the previous step around
#: the best so far, so the step shrinks 5-fold a level: 2π/180/5**8 = 9e-8 rad in φ
ZOOM_LEVELS = 8
#: local maxima of the coarse scan that are zoomed into, per point (the best is kept)
CANDIDATES = 2
#: peaks within this fraction of the largest value are ties: the hot spot is the first of them
#: in the points' order (a symmetric cycle's two mirror-image peaks differ by rounding only)
HOT_SPOT_TIE = 1e-6
#: points per block of the critical-plane scan (memory: states x block x 8 bytes per array)
_BLOCK = 4096


@dataclass(frozen=True)
class HotSpot:
    """Where a parameter is largest: at ``(x, z)``, ``value``, on the plane ``theta`` (rad) if any."""

    x: float
    z: float
    value: float
    theta: float | None = None


@dataclass(frozen=True)
class Parameter:
    """A fatigue parameter's field on the points and its hot spot.

    Attributes
    ----------
    name
        A row's name in :mod:`threepart.fatigue.table` (``"swt"``, ``"ruiz_fdp"``, ...).
    x, z
        The points (broadcast against each other).
    value
        The parameter at the points, of their shape.
    theta
        The critical plane's angle at each point (rad, ``[0, π)``, the normal from ``+x``
        toward ``+z``); ``None`` for a parameter without a plane.
    hot
        The largest value, where and on which plane: the first point, in the points'
        order, within :data:`HOT_SPOT_TIE` (1e-6) of the largest value, and its value.
    """

    name: str
    x: np.ndarray
    z: np.ndarray
    value: np.ndarray
    theta: np.ndarray | None
    hot: HotSpot


def hot_spot(x: np.ndarray, z: np.ndarray, value: np.ndarray, theta: np.ndarray | None = None) -> HotSpot:
    """Where ``value`` (at the points ``(x, z)``, of its shape) is largest: the one hot-spot rule.

    The first point, in the points' order, within :data:`HOT_SPOT_TIE` of the largest value:
    mirror-image peaks (a symmetric cycle) then give the same hot spot whatever the rounding
    of each method. ``theta``: the plane at each point, if any.
    """
    top = float(np.max(value))
    i = int(np.argmax(value >= top - HOT_SPOT_TIE * abs(top)))
    return HotSpot(float(x.flat[i]), float(z.flat[i]), float(value.flat[i]),
                   None if theta is None else float(theta.flat[i]))


def hot_spot_parameter(name: str, x: np.ndarray, z: np.ndarray, value: np.ndarray,
                       theta: np.ndarray | None = None) -> Parameter:
    """The :class:`Parameter` ``name`` of ``value`` at the points, with its :func:`hot_spot`."""
    return Parameter(name, x, z, value, theta, hot_spot(x, z, value, theta))


def von_mises_range(history: History | Sequence[Stress]) -> Parameter:
    """Von Mises range: the largest von Mises stress of the difference of two states.

    ``max_{i<j} σvM(σ_i - σ_j)`` with ``σvM² = ((Δσxx - Δσyy)² + (Δσyy - Δσzz)² +
    (Δσzz - Δσxx)²)/2 + 3 Δσxz²`` and, in plane strain, ``Δσyy = ν (Δσxx + Δσzz)``.

    Parameters
    ----------
    history
        The states' stresses (:func:`~threepart.fatigue.stress_history`, or a sequence of ``Stress``).
    """
    h = as_history(history)
    nu = h.nu
    best = np.zeros(h.x.shape)
    for i in range(h.states - 1):
        dxx, dzz, dxz = (a[i + 1:] - a[i] for a in (h.sxx, h.szz, h.sxz))
        dyy = nu * (dxx + dzz)
        vm2 = 0.5 * ((dxx - dyy) ** 2 + (dyy - dzz) ** 2 + (dzz - dxx) ** 2) + 3.0 * dxz ** 2
        best = np.maximum(best, np.sqrt(vm2.max(axis=0)))
    return hot_spot_parameter("von_mises_range", h.x, h.z, best)


#: a plane function: (σn, τ, σxx + σzz) histories of shape (m, N) -> the parameter, shape (N,)
PlaneFunction = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]


def _on_planes(ABC: tuple[np.ndarray, np.ndarray, np.ndarray], func: PlaneFunction,
               phi: np.ndarray | float) -> np.ndarray:
    """``func`` on the plane ``φ`` (shape ``(N,)`` or scalar) from ``A = (σxx + σzz)/2``, ``B = (σxx - σzz)/2``, ``C = σxz``."""
    A, B, C = ABC
    cos, sin = np.cos(phi), np.sin(phi)
    return func(A + B * cos + C * sin, C * cos - B * sin, 2.0 * A)


def critical_plane(history: History | Sequence[Stress], func: PlaneFunction,
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The largest value over planes of ``func`` and its plane angle, at each point.

    Parameters
    ----------
    history
        The states' stresses.
    func
        ``func(sn, tau, trace)`` of the normal stress ``σn``, the shear ``τ`` on the
        plane and ``σxx + σzz``, each of shape ``(m, N)`` (states by points), returning
        the parameter of that plane at each point, shape ``(N,)``.

    Returns
    -------
    value, theta
        The maximum over ``θ`` in ``[0, π)`` and the angle ``θ`` (rad) where it is
        reached, of the points' shape.

    Notes
    -----
    A coarse scan of :data:`COARSE_ANGLES` angles ``φ = 2θ`` finds, per point, the
    :data:`CANDIDATES` largest local maxima; each is zoomed into :data:`ZOOM_LEVELS`
    times (11 angles over ± the previous step), to a step of 9e-8 rad in φ. The
    scan is vectorised over the points and states; the loop is over the angles only.
    tests/test_fatigue.py checks it against a brute-force scan of 10⁵ angles.
    """
    h = as_history(history)
    m = h.states
    shape = h.x.shape
    flat = History(h.x.ravel(), h.z.ravel(), h.sxx.reshape(m, -1), h.szz.reshape(m, -1),
                   h.sxz.reshape(m, -1), h.nu, h.Q, h.branch)
    N = flat.x.size
    value, angle = np.empty(N), np.empty(N)
    step0 = 2 * math.pi / COARSE_ANGLES
    coarse = np.arange(COARSE_ANGLES) * step0
    for start in range(0, N, _BLOCK):
        sl = slice(start, start + _BLOCK)
        sxx, szz = flat.sxx[:, sl], flat.szz[:, sl]
        part = (0.5 * (sxx + szz), 0.5 * (sxx - szz), flat.sxz[:, sl])
        F = np.stack([_on_planes(part, func, p) for p in coarse])            # (angles, n)
        peak = (F >= np.roll(F, 1, axis=0)) & (F >= np.roll(F, -1, axis=0))
        ranked = np.argsort(np.where(peak, F, -np.inf), axis=0)[::-1][:CANDIDATES]
        best_v = np.full(F.shape[1], -np.inf)
        best_p = np.zeros(F.shape[1])
        for cand in ranked:
            phi = coarse[cand]
            v = F[cand, np.arange(F.shape[1])]
            step = step0
            for _ in range(ZOOM_LEVELS):
                trial = phi[None, :] + np.linspace(-step, step, 11)[:, None]
                G = np.stack([_on_planes(part, func, t) for t in trial])
                j = np.argmax(G, axis=0)
                gv = G[j, np.arange(G.shape[1])]
                better = gv > v
                phi = np.where(better, trial[j, np.arange(G.shape[1])], phi)
                v = np.where(better, gv, v)
                step /= 5.0
            take = v > best_v
            best_v, best_p = np.where(take, v, best_v), np.where(take, phi, best_p)
        value[sl], angle[sl] = best_v, best_p
    theta = np.mod(0.5 * angle, math.pi)
    return value.reshape(shape), theta.reshape(shape)


def swt(history: History | Sequence[Stress], *, E: float) -> Parameter:
    """Smith–Watson–Topper on the critical plane: ``max_θ σn,max(θ) Δεn(θ) / 2``.

    ``σn,max`` is the largest normal stress on the plane over the states and
    ``Δεn`` the range of its normal strain, ``εn = (1 + ν)/E [σn - ν (σxx + σzz)]``
    (plane-strain Hooke's law, ``ν`` the history's). Units: stress (strain is
    dimensionless). Smith, Watson & Topper, *J. Materials* 5 (1970) 767–778; on the
    critical plane as Szolwinski & Farris, *Wear* 198 (1996) 93–107.

    Parameters
    ----------
    history
        The states' stresses.
    E
        Young's modulus of the substrate, > 0, in the stresses' unit.
    """
    h = as_history(history)
    E = positive("E", E)
    factor = (1.0 + h.nu) / E
    nu = h.nu

    def plane(sn: np.ndarray, tau: np.ndarray, trace: np.ndarray) -> np.ndarray:
        eps = sn - nu * trace
        return sn.max(axis=0) * factor * (eps.max(axis=0) - eps.min(axis=0)) / 2.0

    value, theta = critical_plane(h, plane)
    return hot_spot_parameter("swt", h.x, h.z, value, theta)


def findley_k(k: Any) -> float:
    """Findley's constant as a float in ``[0, 10]``, else ``ValueError`` naming ``k``."""
    v = finite("k", k)
    if not 0.0 <= v <= 10.0:
        raise InputError(f"`k` = {k!r} must lie in [0, 10] (Findley's constant; typically 0.2-0.3)")
    return v


def findley(history: History | Sequence[Stress], *, k: float = K_FINDLEY) -> Parameter:
    """Findley on the critical plane: ``max_θ [τa(θ) + k σn,max(θ)]``.

    ``τa`` is half the range of the shear stress ``τ`` on the plane over the
    states and ``σn,max`` the largest normal stress on it. Findley, *J. Eng.
    Industry* 81 (1959) 301–306.

    Parameters
    ----------
    history
        The states' stresses.
    k
        Findley's material constant, ``0 <= k <= 10``; default :data:`K_FINDLEY` = 0.3.
    """
    h = as_history(history)
    k = findley_k(k)

    def plane(sn: np.ndarray, tau: np.ndarray, trace: np.ndarray) -> np.ndarray:
        return 0.5 * (tau.max(axis=0) - tau.min(axis=0)) + k * sn.max(axis=0)

    value, theta = critical_plane(h, plane)
    return hot_spot_parameter("findley", h.x, h.z, value, theta)


@dataclass(frozen=True)
class Ruiz:
    """Ruiz's parameters along the surface (Ruiz, Boddington & Chen 1984).

    Attributes
    ----------
    x
        Surface points.
    sxx_max
        Tensile part of the surface ``σxx``, largest over the states: ``max(0, max_t σxx)``.
    q
        ``|q(x)|`` at ``Q_max`` (the end of the loading branch).
    delta
        Slip amplitude ``δ(x)`` (:meth:`FrettingResult.slip_amplitude`).
    fdp
        ``τ δ = |q| δ``, the fretting damage parameter (frictional work; units stress·length).
    ffdp
        ``σxx,max⁺ |q| δ``, the fretting-fatigue damage parameter (stress²·length).
    """

    x: np.ndarray
    sxx_max: np.ndarray
    q: np.ndarray
    delta: np.ndarray
    fdp: Parameter
    ffdp: Parameter


def ruiz(cycle: Cycle, history: History) -> Ruiz:
    """Ruiz's fretting parameters at the surface points of ``history``.

    With ``σxx⁺ = max(0, max over the history's states of σxx(x, 0))``,
    ``τ = |q(x)|`` at ``Q_max`` (of a steady cycle: the larger of ``|q|`` at its
    two end states) and ``δ(x)`` the slip amplitude (half the peak-to-peak
    relative slip over the cycle):

    - ``FDP = τ δ`` (Ruiz's first parameter, the frictional work, for wear);
    - ``FFDP = σxx⁺ τ δ`` (the fretting-fatigue damage parameter).

    Ruiz, Boddington & Chen, "An investigation of fatigue and fretting in a
    dovetail joint", *Experimental Mechanics* 24 (1984) 208–217.

    Parameters
    ----------
    cycle
        The cycle the history was taken from.
    history
        Its states' stresses; only the points at ``z = 0`` are used (at least one).
    """
    cycle = check_cycle(cycle)
    s = as_history(history).surface()
    x = s.x
    sxx_max = np.maximum(s.sxx.max(axis=0), 0.0)
    if isinstance(cycle, SteadyStateResult):
        q = np.maximum(*(np.abs(np.asarray(cycle.shear(x, k), float)) for k in (0, 1)))
    else:
        q = np.abs(np.asarray(cycle.shear(x, cycle.Q_max, BRANCHES[0]), float))
    delta = np.asarray(cycle.slip_amplitude(x), float)
    fdp = q * delta
    zero = np.zeros_like(x)
    return Ruiz(x, sxx_max, q, delta, hot_spot_parameter("ruiz_fdp", x, zero, fdp),
                hot_spot_parameter("ruiz_ffdp", x, zero, sxx_max * fdp))

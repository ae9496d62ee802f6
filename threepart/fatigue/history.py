"""The stress history of a cycle's states at points (x, z), the input of every fatigue parameter.

Re-exported by :mod:`threepart.fatigue`, whose parameters take it (definitions:
``docs/FATIGUE.md``). Conventions as there: ``x`` along the surface, ``z >= 0``
the depth, tension positive, plane strain.

History             -- stacked σxx, σzz, σxz of several states at the same points
stress_history      -- the history of a cycle's states at points (x, z); a Masing cycle's from its
                       loading states by superposition (n + 1 stress evaluations instead of 3n)
Cycle               -- what the parameters take: a fretting cycle or a steady state of a cycle
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..results.cycles import SteadyStateResult
from ..problem.material import NU
from ..results.slip import FrettingResult, MasingCycle, masing
from ..stress.flamant import Stress
from ..problem.checks import integer, poisson, reals
from threepart.errors import InputError, InputTypeError

__all__ = ["History", "stress_history", "Cycle", "SAME_U"]


@dataclass(frozen=True)
class History:
    """The stresses of several states of a cycle at the same points, stacked on a first axis.

    Attributes
    ----------
    x, z
        The points, broadcast against each other (shape ``S``).
    sxx, szz, sxz
        ``σxx``, ``σzz``, ``σxz`` of each state, shape ``(m,) + S``.
    nu
        Poisson's ratio of the plane-strain substrate, ``σyy = ν (σxx + σzz)``.
    Q, branch
        The shear force and branch of each state (``NaN`` and ``""`` for a synthetic history).
    """

    x: np.ndarray
    z: np.ndarray
    sxx: np.ndarray
    szz: np.ndarray
    sxz: np.ndarray
    nu: float
    Q: np.ndarray
    branch: np.ndarray

    @classmethod
    def from_stresses(cls, stresses: Sequence[Stress], Q: ArrayLike | None = None,
                      branch: Sequence[str] | None = None) -> History:
        """Stack :class:`~threepart.stress.Stress` records of one set of points, one per state.

        Raises
        ------
        TypeError
            An entry that is not a ``Stress``.
        ValueError
            Fewer than 2 states, points or ``nu`` that differ between states,
            non-finite stresses.
        """
        stresses = list(stresses)
        for i, s in enumerate(stresses):
            if not isinstance(s, Stress):
                raise InputTypeError(f"`stresses[{i}]` must be a threepart.stress.Stress, not "
                                f"{type(s).__name__}")
        if len(stresses) < 2:
            raise InputError(f"`stresses` holds {len(stresses)} state(s): a cycle needs at least 2")
        first = stresses[0]
        for i, s in enumerate(stresses[1:], 1):
            if s.x.shape != first.x.shape or not (np.array_equal(s.x, first.x)
                                                  and np.array_equal(s.z, first.z)):
                raise InputError(f"`stresses[{i}]` is at other points than `stresses[0]`: a history "
                                 "needs every state at the same points")
            if s.nu != first.nu:
                raise InputError(f"`stresses[{i}]` has nu = {s.nu!r}, `stresses[0]` nu = {first.nu!r}: "
                                 "a history needs one material")
        sxx, szz, sxz = (np.stack([getattr(s, k) for s in stresses]) for k in ("sxx", "szz", "sxz"))
        for k, arr in zip(("sxx", "szz", "sxz"), (sxx, szz, sxz)):
            if not np.all(np.isfinite(arr)):
                raise InputError(f"`stresses` hold a non-finite {k}: every stress must be finite")
        m = len(stresses)
        Qs = np.full(m, np.nan) if Q is None else np.asarray(Q, float).reshape(m)
        br = np.full(m, "", dtype=object) if branch is None else np.asarray(branch, dtype=object).reshape(m)
        return cls(first.x, first.z, sxx, szz, sxz, nu=first.nu, Q=Qs, branch=br)

    @property
    def states(self) -> int:
        """The number of states."""
        return self.sxx.shape[0]

    def surface(self) -> History:
        """The history at the points with ``z = 0``, flattened (``ValueError`` if there are none)."""
        at = (self.z == 0).ravel()
        if not at.any():
            raise InputError("the history has no surface point (z = 0): Ruiz's parameter is a "
                             "surface quantity")
        m = self.states
        pick = lambda a: a.reshape(m, -1)[:, at]   # noqa: E731
        return History(self.x.ravel()[at], self.z.ravel()[at], pick(self.sxx), pick(self.szz),
                       pick(self.sxz), self.nu, self.Q, self.branch)


def as_history(history: Any) -> History:
    if isinstance(history, History):
        return history
    if isinstance(history, (list, tuple)):
        return History.from_stresses(history)
    raise InputTypeError(f"`history` must be a threepart.fatigue.History or a sequence of Stress, not "
                    f"{type(history).__name__}")


#: a cycle whose stress history the parameters take: a fretting cycle, or the steady state of a
#: cycle between two states (a flight cycle, docs/STEADY_STATE.md)
Cycle = FrettingResult | SteadyStateResult


def check_cycle(cycle: Any) -> Cycle:
    if not isinstance(cycle, (FrettingResult, SteadyStateResult)):
        raise InputTypeError(f"`cycle` must be a FrettingResult (from a fretting_cycle) or a SteadyStateResult "
                        f"(from a steady_state), not {type(cycle).__name__}")
    return cycle


def _steady_history(cycle: SteadyStateResult, xb: np.ndarray, zb: np.ndarray, states: Any,
                    nu: float) -> History:
    """The steady cycle's stresses at its two end states (docs/FATIGUE.md, "The flight cycle")."""
    if states is not None:
        raise InputError(f"`states` = {states!r} selects recorded states of a fretting cycle; a steady "
                         "state's history is its two end states: leave `states` out")
    stresses = [cycle.stress(xb, zb, k, nu=nu) for k in (0, 1)]
    return History.from_stresses(stresses, Q=[cycle.states[0][2], cycle.states[1][2]],
                                 branch=["state 0", "state 1"])


def _points(x: ArrayLike, z: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """``x``, ``z`` as finite float arrays, ``z >= 0``, broadcast against each other."""
    xa = reals("x", x).reshape(np.shape(x))
    za = reals("z", z).reshape(np.shape(z))
    if not (np.all(np.isfinite(xa)) and np.all(np.isfinite(za))):
        raise InputError("`x` and `z` must hold finite numbers")
    if np.any(za < 0):
        raise InputError(f"`z` = {float(za[za < 0].flat[0])!r} must be >= 0: z is the depth into "
                         "the substrate")
    try:
        xb, zb = np.broadcast_arrays(xa, za)
    except ValueError:
        raise InputError(f"`x` of shape {xa.shape} and `z` of shape {za.shape} do not broadcast "
                         "against each other") from None
    if xb.size == 0:
        raise InputError("`x` and `z` hold no point")
    return xb.copy(), zb.copy()


def _states(cycle: FrettingResult, states: Any) -> np.ndarray:
    """Indices of the recorded states to use: all by default, else ``states`` checked."""
    n = len(cycle.Q)
    if states is None:
        return np.arange(n)
    if isinstance(states, (str, bytes)) or not hasattr(states, "__len__"):
        raise InputTypeError(f"`states` must be a sequence of indices into `cycle.Q`, not "
                        f"{type(states).__name__}")
    idx = np.array([integer(f"states[{i}]", s, -n, n - 1) for i, s in enumerate(states)], dtype=int)
    idx = np.unique(idx % n) if idx.size else idx
    if idx.size < 2:
        raise InputError(f"`states` selects {idx.size} distinct state(s) of the cycle's {n}: a "
                         "stress range needs at least 2")
    return idx


def _distinct(cycle: FrettingResult, idx: np.ndarray) -> np.ndarray:
    """``idx`` less the states that repeat an earlier one (same ``Q``, same shear).

    A branch starts where the previous one ended (``Q_max`` on loading and on
    unloading, ``-Q_max`` on unloading and reloading), so these states appear
    twice; the shear is compared at 65 points of the contact, to 1e-12 of its
    largest value, so that a method whose two records differ keeps both.
    """
    normal = cycle.normal
    xs = np.linspace(-normal.a, normal.c, 65)
    q = {int(i): np.asarray(cycle.shear(xs, float(cycle.Q[i]), str(cycle.branch[i])), float)
         for i in idx}
    scale = max(float(np.max(np.abs(v))) for v in q.values()) or 1.0
    kept: list[int] = []
    for i in map(int, idx):
        if not any(cycle.Q[j] == cycle.Q[i] and np.max(np.abs(q[j] - q[i])) <= 1e-12 * scale
                   for j in kept):
            kept.append(i)
    return np.array(kept, dtype=int)


def stress_history(cycle: Cycle, x: ArrayLike, z: ArrayLike, *, states: Any = None,
                   nu: float = NU) -> History:
    """The stresses of a cycle's states at the points ``(x, z)``, ``z >= 0``.

    Parameters
    ----------
    cycle
        A fretting cycle of any method, or the steady state of a cycle between two
        states (:class:`~threepart.results.SteadyStateResult`): its history is its
        two end states (docs/FATIGUE.md, "The flight cycle").
    x, z
        Points, broadcast against each other; ``z = 0`` is the surface.
    states
        Indices into ``cycle.Q`` (and ``cycle.branch``) of the states to use, at
        least 2 distinct; default all recorded states. States that repeat an
        earlier one (a branch's first state is the previous branch's last) are
        evaluated once.
    nu
        Poisson's ratio of the substrate, in ``(-1, 0.5)`` (:meth:`FrettingResult.stress`).

    Returns
    -------
    History
    """
    cycle = check_cycle(cycle)
    xb, zb = _points(x, z)
    nu = poisson(nu)
    if isinstance(cycle, SteadyStateResult):
        return _steady_history(cycle, xb, zb, states, nu)
    idx = _distinct(cycle, _states(cycle, states))
    if _superposes(cycle):
        return _masing_history(cycle, xb, zb, idx, nu)
    stresses = [cycle.stress(xb, zb, float(cycle.Q[i]), str(cycle.branch[i]), nu=nu) for i in idx]
    return History.from_stresses(stresses, Q=cycle.Q[idx], branch=cycle.branch[idx])


def _superposes(cycle: FrettingResult) -> bool:
    """Whether the cycle's states are Masing superpositions of its loading states (:class:`MasingCycle`)
    whose stresses are the half-plane's of their tractions (:meth:`FrettingResult.stress`, linear in them)."""
    return isinstance(cycle, MasingCycle) and type(cycle).stress is FrettingResult.stress


#: loading states closer than this fraction of ``Q_max`` are one (an unloading state's
#: ``u = (Q_max - Q)/2`` repeats a loading state's ``Q`` up to rounding)
SAME_U = 1e-12


def _masing_history(cycle: FrettingResult, xb: np.ndarray, zb: np.ndarray, idx: np.ndarray,
                    nu: float) -> History:
    """The history of a Masing cycle from its loading states, by superposition (docs/FATIGUE.md).

    A state ``(Q, branch)`` carries the pressure, the shear
    ``c_max q(Q_max) + c_u q(u)`` of :func:`threepart.results.slip.masing` and the
    bulk stress ``sigma_bulk Q/Q_max``; the stresses are linear in the
    tractions, so they are the pressure's stresses (one evaluation) plus the
    same combination of the shear-only stresses of the loading states at
    ``Q_max`` and at each ``u`` (one evaluation each): ``n + 1`` evaluations of
    one traction for ``n`` loading states, instead of one of two tractions per
    state (``3n - 3`` distinct states).
    """
    from ..stress.flamant import stress

    normal, Q_max = cycle.normal, cycle.Q_max
    ends = (-normal.a, normal.c)
    coeffs = [masing(Q_max, float(cycle.Q[i]), str(cycle.branch[i])) for i in idx]
    loads: list[float] = []
    for c_max, c_u, u in coeffs:
        for v in ((Q_max,) if c_max else ()) + ((u,) if c_u and u > 0 else ()):
            if not any(abs(v - w) <= SAME_U * Q_max for w in loads):
                loads.append(v)
    p = stress(xb, zb, pressure=normal.pressure, ends=ends, nu=nu, kinks=cycle.state_kinks(0.0, "loading"))
    q = [stress(xb, zb, pressure=None, shear=functools.partial(cycle.shear, Q=u, branch="loading"),
                ends=ends, nu=nu, kinks=cycle.state_kinks(u, "loading")) for u in loads]

    def shear_part(u: float) -> Stress:
        return q[min(range(len(loads)), key=lambda j: abs(loads[j] - u))]

    out = {k: np.empty((len(idx),) + xb.shape) for k in ("sxx", "szz", "sxz")}
    for n, ((c_max, c_u, u), i) in enumerate(zip(coeffs, idx)):
        for k in out:
            val = getattr(p, k).copy()
            if c_max:
                val += c_max * getattr(shear_part(Q_max), k)
            if c_u and u > 0:
                val += c_u * getattr(shear_part(u), k)
            out[k][n] = val
        out["sxx"][n] += cycle.sigma_bulk * float(cycle.Q[i]) / Q_max
    for k, arr in out.items():
        if not np.all(np.isfinite(arr)):
            raise InputError(f"the history holds a non-finite {k}: every stress must be finite")
    return History(p.x, p.z, out["sxx"], out["szz"], out["sxz"], nu=nu, Q=cycle.Q[idx],
                   branch=cycle.branch[idx])

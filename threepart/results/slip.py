"""The results with a shear: partial slip and the fretting cycle, on the one result shape.

A :class:`SlipResult` holds its normal solution (:class:`~threepart.results.contact.NormalResult`)
and the stick zone; a :class:`FrettingResult` the cycle ``Q = 0 -> Q_max -> -Q_max -> Q_max``
of its branches :data:`BRANCHES`; :class:`MasingCycle` builds one from the loading branch alone
(Masing's rule, :func:`masing`). Sign conventions as :mod:`threepart.results.contact`.

Names
-----
SlipResult      -- partial slip: Q, f, d, e, the stick zone, shear(x), slip(x)
FrettingResult  -- one fretting cycle: its branches' shear and slip, the slip amplitude
MasingCycle     -- a fretting cycle from its loading branch by Masing's rule
masing          -- the loading-branch loads whose sum is a state of the cycle
BRANCHES        -- ``("loading", "unloading", "reloading")``
check_normal    -- the ``normal`` argument of a slip or fretting solve: a NormalResult
check_shear     -- ``Q`` (or ``Q_max``) and ``f`` on a normal result: ``|Q| < f P`` (shear_load)
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Self

import numpy as np
from numpy.typing import ArrayLike

from ..problem.checks import finite
from ..problem.material import NU
from ..problem.validate import shear_load
from .answer import check_coulomb
from .contact import Answer, Diagnostics, NormalResult, interior_kinks, segments_in_contact
from .edges import Edged
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:
    from ..stress.flamant import Stress

__all__ = ["SlipResult", "FrettingResult", "MasingCycle", "masing", "BRANCHES", "check_normal", "check_shear"]

#: the three branches of a fretting cycle: 0 -> Q_max, Q_max -> -Q_max, -Q_max -> Q_max
BRANCHES = ("loading", "unloading", "reloading")


@dataclass(frozen=True)
class SlipResult(Edged, Answer):
    """Partial-slip solution: stick zone ``[-(d+e), d-e]`` inside the contact.

    Attributes
    ----------
    normal
        The normal solution the shear load was applied to.
    Q, f
        Shear force and coefficient of friction, ``|Q| < f P``.
    d, e
        Stick-zone half-width and eccentricity (stick zone centred at ``-e``).
    sigma_bulk
        Bulk stress ``σxx`` in the substrate, tension positive, applied with
        ``Q`` in proportion (after the normal load).
    """

    edge_kind = "slip"   # its edge records (threepart.results.edges.EDGE_KINDS)

    normal: NormalResult
    Q: float
    f: float
    d: float
    e: float
    method: str = ""
    sigma_bulk: float = 0.0
    diagnostics: Diagnostics = field(default_factory=Diagnostics, compare=False)
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    # the normal result's fields, so that a slip result has the shared shape too
    @property
    def a(self) -> float:
        return self.normal.a

    @property
    def c(self) -> float:
        return self.normal.c

    @property
    def alpha(self) -> float:
        return self.normal.alpha

    @property
    def P(self) -> float:
        return self.normal.P

    @property
    def s(self) -> float:
        return self.normal.s

    @property
    def stick_zone(self) -> tuple[float, float]:
        """``(-(d+e), d-e)``."""
        return -(self.d + self.e), self.d - self.e

    @property
    def segments(self) -> tuple[str, ...]:
        """The punch segments in contact (of the normal solution)."""
        return self.normal.segments

    @property
    def stick_segments(self) -> tuple[str, ...]:
        """The punch segments the stick zone covers, as :attr:`NormalResult.segments`."""
        return segments_in_contact(self.normal.punch.b, *self.stick_zone)

    @property
    def within_paper(self) -> bool:
        """Whether the paper's closed form covers this solution.

        The normal contact must be in its framework and the stick zone must
        contain the central segment (``d + e >= b`` and ``d - e >= b``): the
        paper's substitution holds only for stick-zone ends on the outer
        segments (end of its partial-slip section).
        """
        lo, hi = self.stick_zone
        b = self.normal.punch.b
        return self.normal.within_paper and lo <= -b and hi >= b

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure of the normal problem."""
        return self.normal.pressure(x)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear traction ``q(x)``, with the sign of ``Q``; integrates to ``Q``."""
        raise NotImplementedError

    def stress(self, x: ArrayLike, z: ArrayLike, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)``: pressure, shear and ``sigma_bulk`` (see :meth:`NormalResult.stress`)."""
        from ..stress.flamant import stress
        return stress(x, z, pressure=self.pressure, shear=self.shear, ends=(-self.a, self.c),
                      sigma_bulk=self.sigma_bulk, nu=nu,
                      kinks=interior_kinks(self.normal.punch.b, -self.a, self.c, *self.stick_zone))

    def check(self) -> None:
        """Coulomb's law over the contact (:func:`threepart.results.answer.check_coulomb`); its normal was checked when built."""
        check_coulomb(self)


@dataclass(frozen=True)
class FrettingResult(Edged, Answer):
    """One fretting cycle at constant ``P`` and ``s``: ``Q`` from 0 to ``Q_max``, to ``-Q_max`` and back.

    The states are recorded along the load path, branch by branch (:data:`BRANCHES`).

    Attributes
    ----------
    normal
        The normal solution the cycle is applied to.
    Q_max, f
        Amplitude of the shear force (``0 < Q_max < f P``) and coefficient of friction.
    branch
        Branch of each recorded state: ``"loading"``, ``"unloading"`` or ``"reloading"``.
    Q
        Shear force of each state.
    stick
        Ends ``(left, right)`` of the zone that sticks at each state, shape ``(n, 2)``.
        On the loading branch it is the stick zone ``[-(d+e), d-e]``; on unloading
        (reloading) it is the zone that has not slipped since ``Q_max`` (``-Q_max``).
    delta
        Tangential displacement of the punch relative to the substrate at each state,
        in the direction of positive ``Q``. In half-plane theory it is defined only up
        to a term linear in ``Q``; :meth:`loop` removes that term.
    energy
        Energy dissipated per cycle and unit length (the area of the ``Q``–``delta`` loop;
        under a bulk stress, which works on the substrate too, the friction work,
        docs/BULK_STRESS.md eq. B9).
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q_max``, tension positive; it
        varies in phase with ``Q``: ``sigma_bulk Q / Q_max`` at each state.
    """

    edge_kind = "fretting"   # its edge records (threepart.results.edges.EDGE_KINDS)

    normal: NormalResult
    Q_max: float
    f: float
    branch: np.ndarray
    Q: np.ndarray
    stick: np.ndarray
    delta: np.ndarray
    energy: float
    method: str = ""
    sigma_bulk: float = 0.0
    diagnostics: Diagnostics = field(default_factory=Diagnostics, compare=False)
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    def loop(self) -> tuple[np.ndarray, np.ndarray]:
        """The hysteresis loop ``(Q, delta - Q delta(Q_max)/Q_max)``, comparable across methods.

        The subtracted line joins the loop's tips ``(±Q_max, ±delta(Q_max))``,
        so every method's loop starts and ends at zero whatever its elastic
        (linear) part; its area is :attr:`energy`.
        """
        tip = self.delta[(self.branch == "loading") & (self.Q == self.Q_max)]
        return self.Q, self.delta - self.Q * float(tip[-1]) / self.Q_max

    def shear(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        """Shear traction ``q(x)`` at force ``Q`` on ``branch`` (sign of the applied shear)."""
        raise NotImplementedError

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        """Half the peak-to-peak relative slip at ``x`` over the cycle (0 where it never slips)."""
        raise NotImplementedError

    def state_kinks(self, Q: float, branch: str) -> list[float]:
        """Points of the contact where the shear at ``(Q, branch)`` may not be smooth.

        The joins ``x = ±b`` and the ends of every recorded zone that has not
        slipped; :meth:`stress` puts quadrature panel ends there.
        """
        return interior_kinks(self.normal.punch.b, -self.normal.a, self.normal.c, *np.ravel(self.stick))

    def stress(self, x: ArrayLike, z: ArrayLike, Q: float, branch: str, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)`` in the state ``(Q, branch)`` of the cycle.

        The pressure, the shear :meth:`shear` of that state and the bulk stress
        ``sigma_bulk Q / Q_max`` (in phase with ``Q``); see
        :meth:`NormalResult.stress`.
        """
        from ..stress.flamant import stress
        normal = self.normal
        return stress(x, z, pressure=normal.pressure, shear=lambda t: self.shear(t, Q, branch),
                      ends=(-normal.a, normal.c), sigma_bulk=self.sigma_bulk * float(Q) / self.Q_max,
                      nu=nu, kinks=self.state_kinks(Q, branch))


class MasingCycle(FrettingResult):
    """A fretting cycle built from its loading states by Masing's rule (:func:`masing`).

    A subclass gives the shear ``_q_load(x, u)`` and the slip ``_s_load(x, u)``
    of the loading state at ``0 <= u <= Q_max`` (zero at ``u = 0``); the shear,
    slip and slip amplitude anywhere on the cycle follow. Shared by the closed
    form and the SIE, which solve the loading states each in its own way.
    """

    @classmethod
    def from_loading(cls, normal: NormalResult, Q_max: float, f: float, u: np.ndarray,
                     stick: np.ndarray, delta: np.ndarray, **fields: Any) -> Self:
        """The cycle's recorded states from its loading branch alone (Masing's rule).

        ``u`` runs from 0 to ``Q_max`` in equal steps; ``stick`` (``(n, 2)``) and
        ``delta`` are the loading states' stick zones and displacements. Unloading
        to ``Q`` is the loading state of ``u = (Q_max - Q)/2`` superposed
        (``delta(Q_max) - 2 delta(u)``, the same unslipped zone), and reloading
        mirrors it; ``fields`` are the rest of the result's fields.
        """
        n = len(u)
        return cls(normal=normal, Q_max=Q_max, f=f, branch=np.repeat(np.array(BRANCHES), n),
                   Q=np.concatenate([u, np.linspace(Q_max, -Q_max, n), np.linspace(-Q_max, Q_max, n)]),
                   stick=np.concatenate([stick, stick, stick]),
                   delta=np.concatenate([delta, delta[-1] - 2 * delta, -delta[-1] + 2 * delta]),
                   **fields)

    def _q_load(self, x: np.ndarray, u: float) -> np.ndarray:
        raise NotImplementedError

    def _stick_load(self, u: float) -> tuple[float, float]:
        """Ends of the loading stick zone at ``0 < u <= Q_max``."""
        raise NotImplementedError

    def state_kinks(self, Q: float, branch: str) -> list[float]:
        """The joins ``x = ±b`` and the stick-zone ends of the loading states superposed at ``(Q, branch)``.

        Only the states at ``Q_max`` and at ``u`` of :func:`masing` enter the
        shear there, so only their ends are kinks of it.
        """
        c_max, c_u, u = masing(self.Q_max, Q, branch)
        ends = [*(self._stick_load(self.Q_max) if c_max else ()), *(self._stick_load(u) if u > 0 else ())]
        return interior_kinks(self.normal.punch.b, -self.normal.a, self.normal.c, *ends)

    def _s_load(self, x: np.ndarray, u: float) -> np.ndarray:
        raise NotImplementedError

    def shear(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        """Shear ``q(x)`` at force ``Q`` on ``branch``: the superposed loading states' shear."""
        return self._superposed(self._q_load, np.asarray(x, dtype=float), Q, branch)

    def slip(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        """Relative slip at ``x`` since the start of loading, positive in the direction of positive ``Q``."""
        return self._superposed(self._s_load, np.asarray(x, dtype=float), Q, branch)

    def _superposed(self, load: Any, x: np.ndarray, Q: float, branch: str) -> np.ndarray:
        """``c_max X(Q_max) + c_u X(u)`` of :func:`masing`; a state of weight 0 is not solved (on the
        loading branch the state at ``Q_max`` is not: a lazily solved state costs a solve a call)."""
        c_max, c_u, u = masing(self.Q_max, Q, branch)
        out = np.zeros(x.shape)
        for c, at in ((c_max, self.Q_max), (c_u, u)):
            if c != 0:
                out = out + c * load(x, at)
        return out

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        """Half the peak-to-peak relative slip over the cycle: the slip at ``Q_max`` on loading."""
        return self._s_load(np.asarray(x, dtype=float), self.Q_max)


def masing(Q_max: float, Q: float, branch: str) -> tuple[float, float, float]:
    """``(c_max, c_u, u)``: the state at ``Q`` on ``branch`` is ``c_max X(Q_max) + c_u X(u)``.

    ``X`` is the loading shear, slip or ``delta`` (Masing's rule, the
    Mindlin–Deresiewicz superposition): unloading from ``Q_max`` subtracts twice
    the loading state of ``(Q_max - Q)/2``, reloading from ``-Q_max`` adds twice
    that of ``(Q_max + Q)/2``. Shared by every method that superposes loading
    states (the closed form and the SIE).

    Raises
    ------
    ValueError
        For an unknown ``branch`` or a ``Q`` outside the branch's range.
    """
    if branch not in BRANCHES:
        raise InputError(f"`branch` = {branch!r} must be one of {BRANCHES}")
    Q = finite("Q", Q)
    lo = 0.0 if branch == "loading" else -Q_max
    tol = 1e-12 * Q_max
    if not lo - tol <= Q <= Q_max + tol:
        raise InputError(f"`Q` = {Q:g} lies outside [{lo:g}, {Q_max:g}], the range of the "
                         f"{branch} branch for `Q_max` = {Q_max:g}")
    Q = min(max(Q, lo), Q_max)
    if branch == "loading":
        return 0.0, 1.0, Q
    if branch == "unloading":
        return 1.0, -2.0, min(max(0.5 * (Q_max - Q), 0.0), Q_max)
    return -1.0, 2.0, min(max(0.5 * (Q_max + Q), 0.0), Q_max)


def check_normal(normal: Any, argument: str = "normal") -> Any:
    """``normal`` if it is a :class:`~threepart.results.contact.NormalResult`, else ``TypeError`` (the ``normal`` argument of a
    slip or fretting solve).

    ``argument`` is the parameter's name in the caller (``"normal_solution"``
    in the closed form), which the message names.
    """
    if not isinstance(normal, NormalResult):
        raise InputTypeError(f"`{argument}` must be a NormalResult (from a solve_normal), not "
                             f"{type(normal).__name__}")
    return normal


def check_shear(normal: Any, Q: Any, f: Any, name: str = "Q", what: str = "there is no stick zone",
                limit: float = 1.0, argument: str = "normal") -> tuple[float, float]:
    """:func:`~threepart.problem.validate.shear_load` on a normal result (a half-plane slip or fretting
    solve): ``normal`` must be a NormalResult (else ``TypeError``).

    ``argument`` is the normal result's parameter name in the caller, for the message.
    """
    return shear_load(Q, f, check_normal(normal, argument).P, name, what, limit)

"""The one result shape shared by the closed form, the SIE and the FEM solvers.

Every solver returns a :class:`NormalResult` (and, for partial slip, a
:class:`SlipResult`) subclass, so that :mod:`threepart.reports` never
special-cases a method. It holds no solution formula.

Sign conventions (see README): ``P > 0`` is compressive, ``s`` is the lever arm
of the load, positive to the right, and equals the centroid of the pressure;
``pressure(x) >= 0`` is compressive (the paper's ``p`` is negative);
``shear(x)`` has the sign of ``Q`` and integrates to ``Q``.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, ClassVar, Mapping, Self

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from ..problem.material import NU   # the default Poisson's ratio of the stresses (its home, with why)
from .answer import check_coulomb, check_pressure
from .edges import Edged
from ..problem.punch import Punch
from ..problem.checks import coordinates, finite, integer
from threepart.errors import InputError

if TYPE_CHECKING:
    from ..stress.flamant import Stress

__all__ = ["NormalResult", "SlipResult", "FrettingResult", "MasingCycle", "Peak", "Diagnostics", "SEGMENTS",
           "BRANCHES", "masing", "segments_in_contact", "PEAK_N", "PEAK_GRID"]


#: the bounds of ``n``, the grid points per side, of :meth:`NormalResult.peaks`: two points
#: (the side's ends) at least; at most a million (8 MB a side; 10**9 would allocate 7.5 GiB)
PEAK_N = (2, 1_000_000)
#: the least grid per side that :meth:`NormalResult.peaks` searches, whatever ``n``: a peak
#: of a three-part punch lies within a few per cent of the contact from a join (eq. 2), so a
#: coarser grid can bracket the wrong hump; 257 points a side (at most W long) put a dozen
#: inside any hump 5 % of W wide
PEAK_GRID = 257
#: how many of a side's largest grid maxima :meth:`NormalResult.peaks` refines (two humps
#: of one side, e.g. at a join and at the centre, plus one for a noisy FE field)
_PEAK_CANDIDATES = 3

#: the punch's segments, left to right (eq. 2)
SEGMENTS = ("R1", "centre", "R2")
#: the three branches of a fretting cycle: 0 -> Q_max, Q_max -> -Q_max, -Q_max -> Q_max
BRANCHES = ("loading", "unloading", "reloading")


def segments_in_contact(b: float, left: float, right: float) -> tuple[str, ...]:
    """The segments of a punch of half-width ``b`` that the interval ``[left, right]`` covers.

    Parameters
    ----------
    b
        Half-width of the central segment (joins at ``x = ±b``).
    left, right
        Ends of the contact (or stick zone), ``left < right``.

    Returns
    -------
    tuple of str
        Names from :data:`SEGMENTS`, left to right; a segment counts when the
        interval overlaps it over a non-zero length.
    """
    spans = ((-np.inf, -b), (-b, b), (b, np.inf))
    return tuple(name for name, (lo, hi) in zip(SEGMENTS, spans)
                 if min(right, hi) > max(left, lo))


@dataclass(frozen=True)
class Peak:
    """The largest pressure ``p`` of one half of the contact, at position ``x``.

    ``interior`` is False when that largest value is not a local maximum of the
    whole distribution: the pressure rises monotonically through that half into
    the other (past lift-off, the half on the edge that left the outer segment).
    Then ``x`` is where the half ends, and there is no interior peak in it.
    """

    x: float
    p: float
    interior: bool = True


@dataclass(frozen=True)
class Diagnostics:
    """How a result was computed: its discretisation, iterations and timings.

    One typed record for every method; a field that a method does not have is
    ``None`` (the closed form has no ``n``, the SIE no ``h``). A result's
    ``info`` holds only what is particular to one method and is not here.

    Attributes
    ----------
    n, scheme
        SIE: collocation points and Gauss–Chebyshev scheme.
    h, h_end, dofs, L
        FEM: element size along the contact and at its ends, degrees of
        freedom, block size (width and depth).
    iterations
        Iterations of the method's nonlinear solve (Newton, active set),
        summed over its load steps.
    residual
        The final residual of that solve, in the method's own norm.
    steps
        Load steps (FEM partial slip) or recorded states (fretting cycles).
    timings
        Wall seconds per phase; ``"total"`` is the whole solve.
    """

    n: int | None = None
    scheme: str | None = None
    h: float | None = None
    h_end: float | None = None
    dofs: int | None = None
    L: float | None = None
    iterations: int | None = None
    residual: float | None = None
    steps: int | None = None
    timings: Mapping[str, float] = field(default_factory=dict)

    @property
    def time_s(self) -> float | None:
        """Wall seconds of the whole solve (``timings["total"]``), ``None`` if not timed."""
        return self.timings.get("total")


def interior_kinks(b: float, lo: float, hi: float, *more: float) -> list[float]:
    """The joins ``x = ±b`` and the points ``more`` that lie strictly inside ``(lo, hi)``."""
    return sorted({float(k) for k in (-b, b, *more) if lo < k < hi})


def _checked(method: Callable[..., Any], names: tuple[str, ...]) -> Callable[..., Any]:
    """``method`` with its first ``len(names)`` arguments checked by :func:`~threepart.problem.validate.coordinates`."""
    if getattr(method, "_coordinates", False):
        return method

    @functools.wraps(method)
    def call(self: Any, *args: Any, **kwargs: Any) -> Any:
        given = [coordinates(name, v) for name, v in zip(names, args)]
        return method(self, *given, *args[len(names):], **kwargs)
    call._coordinates = True  # type: ignore[attr-defined]
    return call


#: the methods of a result that take coordinates, and the names of those arguments
_COORDINATES = {"pressure": ("x",), "shear": ("x",), "slip": ("x",), "slip_amplitude": ("x",),
                "stress": ("x", "z")}


def _check_coordinates(cls: type) -> None:
    """Wrap every method of ``cls`` (not inherited) that takes coordinates (:data:`_COORDINATES`)."""
    for name, args in _COORDINATES.items():
        if name in cls.__dict__:
            setattr(cls, name, _checked(cls.__dict__[name], args))


class Answer:
    """What every result shares: coordinates checked in every method, and the answer checked once built.

    A subclass's ``pressure``, ``shear``, ``slip``, ``slip_amplitude`` and ``stress``
    are wrapped when the class is made, so their ``x`` (and ``z``) pass
    :func:`threepart.problem.validate.coordinates` in every method. Each result is checked
    when built (:meth:`check`, :mod:`threepart.results.answer`): a tensile pressure or a shear
    past Coulomb's bound is refused by name. A result that wraps someone else's
    numbers to be judged (the pytest plugin's, the referee's) sets
    ``checks_answer = False``: the comparison measures what it gets wrong instead.
    """

    checks_answer: ClassVar[bool] = True

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        _check_coordinates(cls)

    def __post_init__(self) -> None:
        if self.checks_answer:
            self.check()

    def check(self) -> None:
        """Refuse an answer that breaks the contact's laws (each result kind says which); none here."""


@dataclass(frozen=True)
class NormalResult(Edged, Answer):
    """Solution of the normal problem on the contact ``[-a, c]``.

    Attributes
    ----------
    punch, A
        Geometry and compliance (eq. 4) that were solved for.
    a, c
        Contact extent ``[-a, c]``.
    alpha
        Tilt of the punch (eq. 2); 0 when ``tilt == "suppressed"``.
    P, s
        Compressive load and its lever arm (the pressure centroid).
    tilt
        ``"free"`` or ``"suppressed"``.
    method
        ``"closedform"``, ``"sie"`` or ``"fem"``.
    diagnostics
        How it was computed (:class:`Diagnostics`).
    info
        What is particular to one method and not in ``diagnostics``.
    """

    punch: Punch
    A: float
    a: float
    c: float
    alpha: float
    P: float
    s: float
    tilt: str = "free"
    method: str = ""
    diagnostics: Diagnostics = field(default_factory=Diagnostics, compare=False)
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive contact pressure at ``x`` (0 outside ``[-a, c]``)."""
        raise NotImplementedError

    def stress(self, x: ArrayLike, z: ArrayLike, *, nu: float = NU) -> Stress:
        """Stresses in the substrate at ``(x, z)``, ``z >= 0`` the depth (:func:`threepart.stress.stress`).

        From this result's pressure by Flamant's kernels; ``z = 0`` gives the
        surface. ``nu`` is the substrate's Poisson ratio (plane strain), used
        for ``σyy`` and the derived stresses; an FE result uses its own.
        """
        from ..stress.flamant import stress
        return stress(x, z, pressure=self.pressure, ends=(-self.a, self.c), nu=nu,
                      kinks=interior_kinks(self.punch.b, -self.a, self.c))

    @property
    def width(self) -> float:
        """Contact width ``W = a + c``."""
        return self.a + self.c

    @property
    def segments(self) -> tuple[str, ...]:
        """The punch segments in contact, left to right: ``"R1"``, ``"centre"``, ``"R2"``.

        A segment counts when the contact covers part of it of non-zero width;
        ``b = 0`` (case C, Hertz) has no centre.
        """
        return segments_in_contact(self.punch.b, -self.a, self.c)

    @property
    def within_paper(self) -> bool:
        """Whether the contact lies in the paper's framework: both edges on the outer segments.

        The closed form holds for ``a >= b`` and ``c >= b`` (an edge exactly at
        a join is the lift-off limit). Past lift-off (an edge on the central
        segment, or the punch on one corner) only the SIE and the FEM answer.
        """
        return self.a >= self.punch.b and self.c >= self.punch.b

    def peaks(self, n: int = 2001) -> tuple[Peak, Peak]:
        """Largest pressure left and right of ``x = 0``, each refined by a bounded search.

        Each side is sampled on ``n`` points (at least :data:`PEAK_GRID`, and
        the joins ``x = ±b``, where the pressure has a kink); each of its
        largest grid maxima is refined by a bounded Brent search between its
        neighbours, so the peaks do not depend on ``n`` beyond rounding. For a
        single-humped distribution (Hertz, case C) both may be the same point
        or one may sit at ``x = 0``. A contact that does not straddle ``x = 0``
        (the punch on one corner) is split at its middle instead.

        Raises
        ------
        TypeError, ValueError
            ``n`` not an integer (a bool is not one), or outside :data:`PEAK_N`.
        """
        n = integer("n", n, *PEAK_N)
        mid = 0.0 if -self.a < 0.0 < self.c else 0.5 * (self.c - self.a)
        out = []
        step = 1e-6 * self.width   # a peak at the split is a true one only if p falls beyond it
        for side, (lo, hi) in enumerate(((-self.a, mid), (mid, self.c))):
            best = self._side_peak(lo, hi, max(n, PEAK_GRID))
            beyond = best.x + step if side == 0 else best.x - step
            if abs(best.x - mid) <= 2 * step and float(self.pressure(beyond)) > best.p:
                best = Peak(best.x, best.p, interior=False)
            out.append(best)
        return out[0], out[1]

    def _side_peak(self, lo: float, hi: float, n: int) -> Peak:
        """The largest pressure on ``[lo, hi]``: the grid's largest maxima, each refined by Brent."""
        x = np.union1d(np.linspace(lo, hi, n), interior_kinks(self.punch.b, lo, hi))
        p = self.pressure(x)
        pad = np.concatenate([[-np.inf], p, [-np.inf]])
        maxima = np.flatnonzero((pad[1:-1] >= pad[:-2]) & (pad[1:-1] >= pad[2:]))
        best = Peak(float(x[maxima[0]]), float(p[maxima[0]]))
        for i in maxima[np.argsort(p[maxima])[::-1][:_PEAK_CANDIDATES]]:
            left, right = x[max(i - 1, 0)], x[min(i + 1, x.size - 1)]
            found = Peak(float(x[i]), float(p[i]))
            if right > left:
                r = minimize_scalar(lambda t: -float(self.pressure(t)), bounds=(left, right),
                                    method="bounded", options={"xatol": 1e-12 * self.width})
                if -r.fun > found.p:
                    found = Peak(float(r.x), float(-r.fun))
            if found.p > best.p:
                best = found
        return best

    @property
    def slope(self) -> float:
        """The contact's slope: the largest of tilt, profile and surface slopes (rad).

        See :meth:`threepart.Punch.max_slope`. Half-plane theory assumes it
        small; every solver refuses a contact past
        ``threepart.problem.validate.SLOPE_LIMIT``.
        """
        return self.punch.max_slope(self.a, self.c, self.alpha)

    def check(self) -> None:
        """A compressive pressure over the contact (:func:`threepart.results.answer.check_pressure`)."""
        check_pressure(self)


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
        x = np.asarray(x, dtype=float)
        c_max, c_u, u = masing(self.Q_max, Q, branch)
        return c_max * self._q_load(x, self.Q_max) + c_u * self._q_load(x, u)

    def slip(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        """Relative slip at ``x`` since the start of loading, positive in the direction of positive ``Q``."""
        x = np.asarray(x, dtype=float)
        c_max, c_u, u = masing(self.Q_max, Q, branch)
        return c_max * self._s_load(x, self.Q_max) + c_u * self._s_load(x, u)

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

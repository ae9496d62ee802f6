"""The one result shape shared by the closed form, the SIE and the FEM solvers.

Every solver returns a :class:`NormalResult` (and, for partial slip, a
:class:`~threepart.results.slip.SlipResult`) subclass, so that :mod:`threepart.reports` never
special-cases a method. It holds no solution formula.

Sign conventions (see README): ``P > 0`` is compressive, ``s`` is the lever arm
of the load, positive to the right, and equals the centroid of the pressure;
``pressure(x) >= 0`` is compressive (the paper's ``p`` is negative);
``shear(x)`` has the sign of ``Q`` and integrates to ``Q``.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, ClassVar, Mapping

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from ..problem.material import NU   # the default Poisson's ratio of the stresses (its home, with why)
from .answer import check_pressure
from .edges import Edged
from ..problem.punch import Punch
from ..problem.checks import coordinates, integer

if TYPE_CHECKING:
    from ..stress.flamant import Stress

__all__ = ["NormalResult", "Peak", "Diagnostics", "Answer", "SEGMENTS", "segments_in_contact", "interior_kinks",
           "PEAK_N", "PEAK_GRID"]


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
    """``method`` with its first ``len(names)`` arguments checked by :func:`~threepart.problem.checks.coordinates`."""
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
    :func:`threepart.problem.checks.coordinates` in every method. Each result is checked
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

    edge_kind = "normal"   # its edge records (threepart.results.edges.EDGE_KINDS)

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

"""The fatigue parameters as one table: a row per parameter, that the core, the command line, the report and its schema loop over.

Each row is a :class:`FatigueParameter`: its name, its labels, its unit in the
command line's consistent set (mm, N/mm, MPa), the function that evaluates it
from a cycle's stress history, whether it is searched over critical planes, and
whether it is a surface quantity (Ruiz's). :func:`fatigue` evaluates every row;
the command line (``threepart fatigue``, ``threepart cycle``) prints, writes
CSV/VTU and plots every row; the verification report tabulates every row with
``in_report`` and its schema takes the names from :func:`reported`.

Adding a parameter
------------------
Write its function (a history in, a :class:`~threepart.fatigue.Parameter` out)
and register one row, as :func:`crossland` and its row below do; nothing else
changes. A constant of the parameter (Findley's ``k``, Crossland's ``kappa``) is a
keyword of its function, named in the row's ``constants`` with its default
(``defaults``) and its check (``checks``): :func:`fatigue` then takes it too, checks
it before any stress is computed and reports it in :attr:`Fatigue.constants`.

Names
-----
FatigueParameter   -- a row of the table: name, labels, unit, function, critical plane or not
register_parameter -- add (or replace) a row
parameters         -- the rows, in registration order
parameter          -- the row of a name
reported           -- the names the verification report tabulates
Inputs             -- what a row's function reads: the cycle, its histories, E, nu
Fatigue            -- every parameter of one cycle on one set of points
fatigue            -- evaluate every row on a cycle's points
grid               -- the default points of a cycle's fatigue fields under a contact (GRID)
crossland          -- Crossland: sqrt(J2,a) + kappa sigma_h,max
crossland_kappa    -- Crossland's constant checked: a float in [0, 10]
deviatoric_amplitude -- sqrt(J2,a): the radius of the smallest ball holding the deviatoric path
KAPPA_CROSSLAND    -- Crossland's kappa by default
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .functions import (K_FINDLEY, Parameter, Ruiz, hot_spot_parameter, findley, findley_k, ruiz, swt,
                        von_mises_range)
from .history import Cycle, History, as_history, stress_history
from ..problem.material import NU
from ..stress.flamant import Stress
from ..problem.checks import finite, poisson, positive, reals
from threepart.errors import InputError, InputTypeError

__all__ = ["FatigueParameter", "register_parameter", "parameters", "parameter", "reported", "Inputs", "GRID", "grid",
           "Fatigue", "fatigue", "crossland", "crossland_kappa", "deviatoric_amplitude", "KAPPA_CROSSLAND",
           "T_OVER_F_CROSSLAND"]


@dataclass(frozen=True)
class Inputs:
    """What a row's function reads: the cycle, its stress history on the points and on the surface.

    ``ruiz`` is Ruiz's record of the surface history, evaluated once for both of its rows.
    """

    cycle: Cycle
    history: History
    surface: History
    E: float

    @cached_property
    def ruiz(self) -> Ruiz:
        """Ruiz's parameters at the surface points (:func:`threepart.fatigue.ruiz`)."""
        return ruiz(self.cycle, self.surface)


@dataclass(frozen=True)
class FatigueParameter:
    """A row of the table.

    Attributes
    ----------
    name
        The key of its field in :class:`Fatigue`, the CSV, the JSON and the report.
    label
        As the command line prints it (plain ASCII).
    short
        As the report's table heads it.
    unit
        In the command line's consistent set (mm, N/mm, MPa), e.g. ``"MPa^2 mm"``.
    function
        ``function(inputs, **constants)``: the parameter from :class:`Inputs`.
    critical_plane
        True if it is a maximum over planes: its field has the plane angle ``theta``
        (the CSV's ``theta_<name>`` column, in degrees).
    surface
        True for a surface quantity, evaluated on the surface points only (Ruiz's).
    in_report
        True if the verification report tabulates its hot spots.
    constants
        The keywords of ``function`` that :func:`fatigue` passes on (e.g. ``("kappa",)``).
    defaults
        A constant's value when :func:`fatigue` is not given it (else the function's own default).
    checks
        A constant's check, ``check(value) -> float`` raising on a bad one, run by :func:`fatigue`
        before any stress is computed.
    zero
        Where the command line says the hot spot is when the value is 0 (e.g. no slip), or "".
    """

    name: str
    label: str
    short: str
    unit: str
    function: Callable[..., Parameter]
    critical_plane: bool = False
    surface: bool = False
    in_report: bool = True
    constants: tuple[str, ...] = ()
    zero: str = ""
    defaults: Mapping[str, float] = field(default_factory=dict)
    checks: Mapping[str, Callable[[Any], float]] = field(default_factory=dict)


_TABLE: dict[str, FatigueParameter] = {}


def register_parameter(row: FatigueParameter) -> FatigueParameter:
    """Add ``row`` to the table (replacing one of the same name) and return it."""
    if not isinstance(row, FatigueParameter):
        raise InputTypeError(f"`row` must be a threepart.fatigue.table.FatigueParameter, not "
                        f"{type(row).__name__}")
    _TABLE[row.name] = row
    return row


def parameters() -> tuple[FatigueParameter, ...]:
    """The rows, in registration order."""
    return tuple(_TABLE.values())


def parameter(name: str) -> FatigueParameter:
    """The row called ``name`` (``ValueError`` listing the names otherwise)."""
    try:
        return _TABLE[name]
    except (KeyError, TypeError):
        raise InputError(f"`name` = {name!r} must be one of {', '.join(_TABLE)}") from None


def reported() -> tuple[str, ...]:
    """The names of the parameters the verification report tabulates, in table order."""
    return tuple(p.name for p in parameters() if p.in_report)


# --- Crossland ----------------------------------------------------------------------------

#: the ratio of the fully reversed fatigue limits in torsion and bending, t-1/f-1, that sets
#: Crossland's ``kappa`` by default: 0.7, a hard metal's (von Mises' ratio 1/sqrt(3) = 0.577
#: gives kappa = 0, and Crossland's criterion is meant for ratios above it); give the material's own
T_OVER_F_CROSSLAND = 0.7
#: Crossland's ``kappa = 3 t-1/f-1 - sqrt(3)`` by default (= 0.368 for t-1/f-1 = 0.7)
KAPPA_CROSSLAND = 3.0 * T_OVER_F_CROSSLAND - math.sqrt(3.0)
#: a state lies in a ball when its squared distance from the centre exceeds the squared radius by
#: at most this fraction of the largest squared deviatoric norm at the point (round-off)
_BALL_SLACK = 1e-12
#: the fixed order in which Welzl's algorithm visits the states (its expected cost is linear in a
#: random order; the path's own order can make it cubic)
_SEED = 0


def _ball(R: list[np.ndarray]) -> tuple[np.ndarray, float]:
    """The smallest ball with the points ``R`` (at most 4, in 3-D) on its boundary: centre, radius²."""
    p0 = R[0]
    if len(R) == 1:
        return p0, 0.0
    A = np.array([p - p0 for p in R[1:]])
    G = A @ A.T
    lam = np.linalg.lstsq(G, 0.5 * np.diag(G), rcond=None)[0]
    c = p0 + lam @ A
    return c, float((c - p0) @ (c - p0))


def _welzl(P: np.ndarray, slack: float) -> float:
    """Radius of the smallest ball holding the rows of ``P`` (3-D): Welzl's algorithm, iterative."""
    def ball(n: int, R: list[np.ndarray]) -> tuple[np.ndarray, float]:
        if len(R) == 4:
            return _ball(R)
        c, r2 = (_ball(R) if R else (P[0], 0.0))
        start = 0 if R else 1
        for i in range(start, n):
            d = P[i] - c
            if d @ d > r2 + slack:
                c, r2 = ball(i, [*R, P[i]])
        return c, r2
    P = P[np.random.default_rng(_SEED).permutation(len(P))]
    return math.sqrt(ball(len(P), [])[1])


def deviatoric_amplitude(history: History | Sequence[Stress]) -> np.ndarray:
    """``sqrt(J2,a)``: the radius of the smallest ball holding the deviatoric stress path, per point.

    The deviatoric stress of a state is mapped to ``y = ((σxx - σzz)/2, (σxx + σzz -
    2σyy)/(2√3), σxz)``, a map under which ``|y_i - y_j|² = J2(σ_i - σ_j)``, the second
    invariant of the deviatoric part of the difference; ``σyy = ν (σxx + σzz)``. The
    amplitude is the radius of the smallest ball holding every state's ``y`` (the
    minimum circumscribed hypersphere; Papadopoulos et al., *Int. J. Fatigue* 19 (1997)
    219). For a proportional path, or two states, it is half the largest distance,
    ``σvM(Δσ)/(2√3)`` (half the von Mises range over √3). The ball is the farthest
    pair's where it holds every state, else Welzl's (*LNCS* 555, 1991) at that point.
    """
    h = as_history(history)
    m = h.states
    b = h.nu * (h.sxx + h.szz)
    y = np.stack([0.5 * (h.sxx - h.szz), (h.sxx + h.szz - 2.0 * b) / (2.0 * math.sqrt(3.0)), h.sxz],
                 axis=-1).reshape(m, -1, 3)                          # (states, points, 3)
    N = y.shape[1]
    best, ia, ib = np.full(N, -1.0), np.zeros(N, int), np.zeros(N, int)
    for i in range(m - 1):
        d2 = np.sum((y[i + 1:] - y[i]) ** 2, axis=-1)               # (m - i - 1, N)
        j = np.argmax(d2, axis=0)
        far = d2[j, np.arange(N)]
        take = far > best
        best, ia, ib = np.where(take, far, best), np.where(take, i, ia), np.where(take, i + 1 + j, ib)
    pts = np.arange(N)
    centre = 0.5 * (y[ia, pts] + y[ib, pts])
    radius2 = 0.25 * best
    slack = _BALL_SLACK * np.max(np.sum(y ** 2, axis=-1), axis=0)
    outside = np.max(np.sum((y - centre) ** 2, axis=-1), axis=0) > radius2 + slack
    radius = np.sqrt(radius2)
    for p in np.flatnonzero(outside):
        radius[p] = _welzl(y[:, p], float(slack[p]))
    return radius.reshape(h.x.shape)


def crossland_kappa(kappa: Any) -> float:
    """Crossland's constant as a float in ``[0, 10]``, else ``ValueError`` naming ``kappa``."""
    v = finite("kappa", kappa)
    if not 0.0 <= v <= 10.0:
        raise InputError(f"`kappa` = {kappa!r} must lie in [0, 10] (Crossland's constant, "
                         "3 t-1/f-1 - sqrt(3))")
    return v


def crossland(history: History | Sequence[Stress], *, kappa: float = KAPPA_CROSSLAND) -> Parameter:
    """Crossland: ``sqrt(J2,a) + κ σh,max``.

    ``sqrt(J2,a)`` is the amplitude of the second invariant of the deviatoric stress
    over the states, the radius of the smallest ball holding the deviatoric path
    (:func:`deviatoric_amplitude`; half the von Mises range over √3 for a proportional
    path), and ``σh,max = max (σxx + σyy + σzz)/3`` over the states, ``σyy = ν (σxx +
    σzz)``. Crossland, *Proc. Int. Conf. on Fatigue of Metals*, IMechE (1956) 138–149.
    Units: stress.

    Parameters
    ----------
    history
        The states' stresses.
    kappa
        Crossland's constant, ``0 <= κ <= 10``; from the fully reversed fatigue limits
        in torsion ``t-1`` and bending ``f-1``, ``κ = 3 t-1/f-1 - √3``. Default
        :data:`KAPPA_CROSSLAND` = 0.368, from ``t-1/f-1`` = 0.7.
    """
    h = as_history(history)
    kappa = crossland_kappa(kappa)
    sh = ((1.0 + h.nu) * (h.sxx + h.szz) / 3.0).max(axis=0)
    return hot_spot_parameter("crossland", h.x, h.z, deviatoric_amplitude(h) + kappa * sh)


# --- the table ----------------------------------------------------------------------------

register_parameter(FatigueParameter("von_mises_range", "von Mises range", "von Mises range", "MPa",
                                    lambda i: von_mises_range(i.history)))
register_parameter(FatigueParameter("swt", "SWT (critical plane)", "SWT", "MPa",
                                    lambda i: swt(i.history, E=i.E), critical_plane=True))
register_parameter(FatigueParameter("findley", "Findley (critical plane)", "Findley", "MPa",
                                    lambda i, **c: findley(i.history, **c), critical_plane=True,
                                    constants=("k",), defaults={"k": K_FINDLEY}, checks={"k": findley_k}))
register_parameter(FatigueParameter("ruiz_fdp", "Ruiz FDP q delta", "Ruiz FDP", "MPa mm",
                                    lambda i: i.ruiz.fdp, surface=True, in_report=False,
                                    zero="no surface point slips"))
register_parameter(FatigueParameter("ruiz_ffdp", "Ruiz FFDP s_xx q delta", "Ruiz FFDP", "MPa^2 mm",
                                    lambda i: i.ruiz.ffdp, surface=True,
                                    zero="no surface point in tension where the contact slips"))
register_parameter(FatigueParameter("crossland", "Crossland", "Crossland", "MPa",
                                    lambda i, **c: crossland(i.history, **c), constants=("kappa",),
                                    defaults={"kappa": KAPPA_CROSSLAND}, checks={"kappa": crossland_kappa}))


# --- every parameter of a cycle -------------------------------------------------------------

@dataclass(frozen=True)
class Fatigue:
    """Every parameter of the table, of one cycle on one set of points.

    Attributes
    ----------
    parameters
        ``name -> Parameter``, in table order; each is also an attribute
        (``fat.swt``, ``fat.crossland``).
    ruiz
        Ruiz's record along the surface (its factors ``sxx_max``, ``q``, ``delta``).
    E, nu
        Young's modulus and Poisson's ratio used.
    states
        The number of states in the stress history.
    constants
        Every constant passed to a row's function, given or its row's default (Findley's
        ``k``, Crossland's ``kappa``, ...).
    """

    parameters: Mapping[str, Parameter]
    ruiz: Ruiz
    E: float
    nu: float
    states: int
    constants: Mapping[str, float] = field(default_factory=dict)

    def __getattr__(self, name: str) -> Parameter:
        if name.startswith("__") or name == "parameters":
            raise AttributeError(name)
        try:
            return self.parameters[name]
        except KeyError:
            raise AttributeError(f"'Fatigue' object has no attribute {name!r}") from None


def fatigue(cycle: Cycle, x: ArrayLike, z: ArrayLike, *, E: float, nu: float = NU,
            states: Any = None, surface: ArrayLike | None = None, **constants: float) -> Fatigue:
    """Every parameter of the table (:func:`parameters`) of ``cycle`` at ``(x, z)``.

    Parameters
    ----------
    cycle
        A fretting cycle of any method, or the steady state of a cycle between two
        states (a flight cycle; its history is its two end states).
    x, z
        Points, broadcast against each other, ``z >= 0``.
    E, nu
        Young's modulus (> 0) and Poisson's ratio of the substrate (plane strain).
    states
        Indices of the states to use (default all; :func:`~threepart.fatigue.stress_history`).
    surface
        Surface points ``x`` for the surface parameters (Ruiz's). Default: the points of
        ``(x, z)`` at ``z = 0`` or, if there are none, the distinct ``x`` on the surface.
        Ruiz's tension lives in a narrow band at the slip zones' outer ends, so a grid's
        row is often too coarse for its hot spot: give a fine line here.
    **constants
        The parameters' constants, by the names in their rows' ``constants``: ``k=`` for
        Findley (default :data:`~threepart.fatigue.K_FINDLEY`), ``kappa=`` for Crossland
        (default :data:`KAPPA_CROSSLAND`); each is checked by its row before any stress is
        computed, and defaulted by it.

    Raises
    ------
    TypeError
        A keyword that no row names.
    """
    known = {c for p in parameters() for c in p.constants}
    unknown = sorted(set(constants) - known)
    if unknown:
        raise InputTypeError(f"`{unknown[0]}` is not a constant of any fatigue parameter (theirs: "
                        f"{', '.join(sorted(known))})")
    E = positive("E", E)
    nu = poisson(nu)
    given: dict[str, float] = {}
    for p in parameters():
        for c in p.constants:
            if c in constants:
                given[c] = p.checks[c](constants[c]) if c in p.checks else constants[c]
            elif c in p.defaults:
                given[c] = p.defaults[c]
    xs = None if surface is None else reals("surface", surface)
    h = stress_history(cycle, x, z, states=states, nu=nu)
    if xs is None and np.any(h.z == 0):
        top = h
    else:
        xs = np.unique(h.x) if xs is None else xs
        top = stress_history(cycle, xs, np.zeros_like(xs), states=states, nu=nu)
    inputs = Inputs(cycle, h, top, E)
    values = {p.name: p.function(inputs, **{c: given[c] for c in p.constants if c in given})
              for p in parameters()}
    return Fatigue(values, inputs.ruiz, E=E, nu=nu, states=h.states, constants=given)


#: the default grid of a cycle's fatigue fields (``threepart fatigue``, ``threepart cycle``): points
#: along x over ``[-a - W/4, c + W/4]`` and in depth over ``[0, depth W]`` (``W = a + c``), and
#: Ruiz's surface points over the contact
GRID: dict[str, Any] = {"nx": 41, "nz": 21, "ns": 201, "depth": 1.0}


def grid(lo: float, hi: float, *, nx: int = GRID["nx"], nz: int = GRID["nz"], ns: int = GRID["ns"],
         depth: float = GRID["depth"]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points of a cycle's fatigue fields under the contact ``[lo, hi]``: ``(x, z, surface)``.

    ``x`` (shape ``(1, nx)``) over ``[lo - W/4, hi + W/4]`` and ``z`` (shape ``(nz, 1)``) over
    ``[0, depth W]``, ``W = hi - lo``, so that the fields have shape ``(nz, nx)`` with row 0 the
    surface; ``surface`` the grid's surface points and ``ns`` more at the midpoints of equal
    parts of the contact (never on a contact end), for Ruiz's parameters (:func:`fatigue`).
    """
    W = hi - lo
    x = np.linspace(lo - 0.25 * W, hi + 0.25 * W, nx)[None, :]
    z = np.linspace(0.0, depth * W, nz)[:, None]
    line = lo + W * (np.arange(ns) + 0.5) / ns
    return x, z, np.union1d(np.ravel(x), line)

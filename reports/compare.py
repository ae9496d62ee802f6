"""Method-agnostic comparison of two results of the shared shape.

:func:`compare` takes a reference (the closed form) and another solution of
the same case (SIE or FEM) and returns one :class:`Check` per quantity of
:mod:`threepart.tolerances`, each already judged against the tolerance table.
It only uses the shared result attributes (``a``, ``c``, ``alpha``, ``P``,
``s``, ``pressure``, ``peaks`` and, for partial slip, ``d``, ``e``, ``shear``),
so it never needs to know which solver made a result.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from threepart.halfplane.legendre import gauss01
from threepart.output import json_safe
from threepart.tolerances import (FRETTING_QUANTITIES, NORMAL_QUANTITIES, SLIP_QUANTITIES, STEADY_QUANTITIES,
                                  STRESS_QUANTITIES, tolerance)
from threepart.errors import InputError

__all__ = ["Check", "FieldErrors", "compare", "field_errors", "sample_points", "is_slip", "normal_of",
           "normal_figures", "slip_figures", "fretting_figures", "is_fretting", "SHEAR_STATES",
           "is_steady", "steady_figures", "SteadyRange",
           "EDGE_FRACTION", "AWAY_FROM_STICK_ENDS", "shear_field_errors"]

#: fraction of the contact width excluded at each end for the "interior" errors
EDGE_FRACTION = 0.05
_NGRID = 4001


@dataclass(frozen=True)
class Check:
    """One compared quantity: values, normalised error, its tolerance and the verdict."""

    comparison: str
    quantity: str
    reference: float
    obtained: float
    error: float
    limit: float
    reason: str

    @property
    def passed(self) -> bool:
        """``error <= limit``; a NaN error never passes."""
        return bool(self.error <= self.limit)

    def as_dict(self) -> dict[str, Any]:
        return json_safe({"comparison": self.comparison, "quantity": self.quantity,
                          "reference": self.reference, "obtained": self.obtained,
                          "error": self.error, "limit": self.limit,
                          "passed": self.passed, "reason": self.reason})


@dataclass(frozen=True)
class FieldErrors:
    """A traction field of two results on one grid, for the error curves.

    ``x`` spans the union of both contacts; ``ref`` and ``other`` are the fields,
    ``scale`` the normalising maximum of the reference, ``interior`` a mask of
    the points more than ``EDGE_FRACTION * W`` inside the reference contact.
    """

    x: np.ndarray
    ref: np.ndarray
    other: np.ndarray
    scale: float
    interior: np.ndarray

    @property
    def error(self) -> np.ndarray:
        """Pointwise error ``(other - ref) / scale``."""
        return (self.other - self.ref) / self.scale

    def interior_peak(self, field: np.ndarray) -> float:
        """Largest ``|field|`` over the interior points (0 if there are none)."""
        return float(np.max(np.abs(field[self.interior]), initial=0.0))

    @property
    def interior_max(self) -> float:
        return float(np.max(np.abs(self.error[self.interior]))) if self.interior.any() else math.nan

    @property
    def l2(self) -> float:
        """``||other - ref||_2 / ||ref||_2`` by the trapezoidal rule."""
        num = np.trapezoid((self.other - self.ref) ** 2, self.x)
        den = np.trapezoid(self.ref**2, self.x)
        return float(np.sqrt(num / den))


def is_slip(result: Any) -> bool:
    """True for a partial-slip result (it has a stick zone and a shear field)."""
    return hasattr(result, "d") and hasattr(result, "shear")


def is_fretting(result: Any) -> bool:
    """True for a fretting cycle (it has an energy per cycle and a loop)."""
    return hasattr(result, "energy") and hasattr(result, "loop")


def is_steady(result: Any) -> bool:
    """True for the steady state of a cycle between two states (it has both ends' normals and a shakedown)."""
    return hasattr(result, "normals") and hasattr(result, "shakedown") and hasattr(result, "slip_amplitude")


def normal_of(result: Any) -> Any:
    """The normal result inside a slip result or a fretting cycle, the wider of a steady cycle's two
    end states, or the result itself."""
    if is_steady(result):
        return max(result.normals, key=lambda n: float(n.a + n.c))
    return result.normal if (is_slip(result) or is_fretting(result)) and hasattr(result, "normal") \
        else result


def sample_points(other: Any, lo: float, hi: float, n: int = _NGRID) -> np.ndarray:
    """Where a result's field is compared: its own nodes if it exposes them, else a uniform grid.

    A nodal method (the FEM) knows its pressure only at its nodes (``x_nodes``);
    between them its linear interpolant misses the ``(x - b) ln|x - b|`` kinks at
    ``x = ±b`` by ~1e-3 of the peak even when the nodal values are 3e-4 accurate,
    which would measure the interpolation, not the solution. A result with a
    global interpolant (closed form, SIE) is sampled at ``n`` uniform points.
    """
    nodes = getattr(other, "x_nodes", None)
    if nodes is not None:
        nodes = np.asarray(nodes, dtype=float)
        nodes = np.unique(nodes[(nodes > lo) & (nodes < hi)])
        if nodes.size >= 16:
            return np.concatenate([[lo], nodes, [hi]])
    return np.linspace(lo, hi, n)


def field_errors(ref: Any, other: Any, field: str = "pressure", n: int = _NGRID) -> FieldErrors:
    """Evaluate ``field`` (``"pressure"`` or ``"shear"``) of both results at common points.

    The points span the union of both contacts; see :func:`sample_points`.
    """
    lo = min(-ref.a, -other.a)
    hi = max(ref.c, other.c)
    x = sample_points(normal_of(other), lo, hi, n)
    fr = np.asarray(getattr(ref, field)(x), dtype=float)
    fo = np.asarray(getattr(other, field)(x), dtype=float)
    scale = float(np.max(np.abs(fr)))
    if not scale > 0:
        scale = 1.0
    margin = EDGE_FRACTION * (ref.a + ref.c)
    interior = (x > -ref.a + margin) & (x < ref.c - margin)
    return FieldErrors(x=x, ref=fr, other=fo, scale=scale, interior=interior)


def _slope_scale(ref: Any) -> float:
    """``v'(c) - v'(-a)`` of the untilted punch: the slope scale over the contact."""
    ds = float(ref.punch.slope(ref.c) - ref.punch.slope(-ref.a))
    return ds if ds > 0 else (ref.a + ref.c) / max(ref.punch.R1, ref.punch.R2)


def normal_figures(ref: Any, other: Any) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, normalised error)`` for the normal problem."""
    W = ref.a + ref.c
    out: dict[str, tuple[float, float, float]] = {}
    out["a"] = (ref.a, other.a, abs(other.a - ref.a) / W)
    out["c"] = (ref.c, other.c, abs(other.c - ref.c) / W)
    alpha_scale = max(abs(ref.alpha), _slope_scale(ref))
    out["alpha"] = (ref.alpha, other.alpha, abs(other.alpha - ref.alpha) / alpha_scale)
    out["P"] = (ref.P, other.P, abs(other.P - ref.P) / abs(ref.P))
    out["s"] = (ref.s, other.s, abs(other.s - ref.s) / W)
    (rl, rr), (ol, orr) = ref.peaks(), other.peaks()
    pmax = max(rl.p, rr.p)
    out["p_left"] = (rl.p, ol.p, abs(ol.p - rl.p) / pmax)
    out["x_left"] = (rl.x, ol.x, abs(ol.x - rl.x) / W)
    out["p_right"] = (rr.p, orr.p, abs(orr.p - rr.p) / pmax)
    out["x_right"] = (rr.x, orr.x, abs(orr.x - rr.x) / W)
    fe = field_errors(ref, other, "pressure")
    # both values are the field's largest magnitude over the same interior points
    out["p_interior_max"] = (fe.interior_peak(fe.ref), fe.interior_peak(fe.other), fe.interior_max)
    out["p_L2"] = (float(np.sqrt(np.trapezoid(fe.ref**2, fe.x))),
                   float(np.sqrt(np.trapezoid(fe.other**2, fe.x))), fe.l2)
    return out


#: comparisons whose shear is judged away from the stick zone's ends too: another code's nodal shear
#: smears the square-root cusp at a stick end over an element (CalculiX at W/h = 100: 7.8e-2 of the
#: peak there, 4e-3 away from it), which the stick ends' own checks (d, e) judge instead
AWAY_FROM_STICK_ENDS = ("referee", "referee-friction")


def shear_field_errors(ref: Any, other: Any, *, away_from_stick_ends: bool = False) -> FieldErrors:
    """:func:`field_errors` of the shear; with ``away_from_stick_ends`` its interior also leaves out
    ``EDGE_FRACTION W`` around each end of the reference's stick zone."""
    fe = field_errors(ref, other, "shear")
    if not away_from_stick_ends:
        return fe
    margin = EDGE_FRACTION * (ref.a + ref.c)
    away = np.all([np.abs(fe.x - end) > margin for end in ref.stick_zone], axis=0)
    return FieldErrors(x=fe.x, ref=fe.ref, other=fe.other, scale=fe.scale, interior=fe.interior & away)


def slip_figures(ref: Any, other: Any, *, away_from_stick_ends: bool = False) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, normalised error)`` for the stick zone and shear
    (``q_interior_max`` away from the stick zone's ends too with ``away_from_stick_ends``)."""
    out: dict[str, tuple[float, float, float]] = {}
    out["d"] = (ref.d, other.d, abs(other.d - ref.d) / abs(ref.d))
    out["e"] = (ref.e, other.e, abs(other.e - ref.e) / abs(ref.d))
    fe = shear_field_errors(ref, other, away_from_stick_ends=away_from_stick_ends)
    out["q_interior_max"] = (fe.interior_peak(fe.ref), fe.interior_peak(fe.other), fe.interior_max)
    out["q_L2"] = (float(np.sqrt(np.trapezoid(fe.ref**2, fe.x))),
                   float(np.sqrt(np.trapezoid(fe.other**2, fe.x))), fe.l2)
    integral = _shear_integral(other)
    out["q_integral"] = (other.Q, integral, abs(integral - other.Q) / abs(other.Q))
    excess = _friction_excess(other)
    out["q_bound"] = (0.0, excess, excess)
    return out


#: points of the stress comparison: surface points over the contact and its surroundings
#: (a fraction ``STRESS_REACH`` of W beyond each end), and a grid at depth >= ``STRESS_DEPTH`` a
STRESS_REACH = 0.25
STRESS_DEPTH = 0.2
_STRESS_SURFACE = 401
_STRESS_GRID = (41, 9)


def surface_line(ref: Any, n: int = 801) -> np.ndarray:
    """Surface points over the contact of ``ref`` and ``STRESS_REACH W`` beyond each end.

    The contact ends themselves are left out: the surface ``σxx`` has a
    square-root kink there.
    """
    nr = normal_of(ref)
    W = nr.a + nr.c
    x = np.linspace(-nr.a - STRESS_REACH * W, nr.c + STRESS_REACH * W, n)
    return x[np.min(np.abs(x[:, None] - np.array([-nr.a, nr.c])), axis=1) > 1e-3 * W]


def stress_points(ref: Any) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """``((x, z), (x, z))``: the surface line and the grid at depth where stresses are compared.

    The surface line spans the contact and ``STRESS_REACH W`` beyond each end,
    where the trailing edge's tension peaks; the grid spans the contact in
    ``x`` and ``STRESS_DEPTH a <= z <= W`` in depth (``a`` the contact's
    half-width ``W/2``), where an FE stress recovery converges at its own
    rate. Both avoid the contact ends at the surface, where σxx has a
    ``sqrt``-kink.
    """
    n = normal_of(ref)
    W = n.a + n.c
    xs = surface_line(ref, _STRESS_SURFACE)
    nx, nz = _STRESS_GRID
    xg, zg = np.meshgrid(np.linspace(-n.a, n.c, nx), np.linspace(STRESS_DEPTH * 0.5 * W, W, nz))
    return (xs, np.zeros_like(xs)), (xg.ravel(), zg.ravel())


def stress_figures(ref: Any, other: Any) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, normalised error)`` for the stress field in the substrate.

    ``sxx_surface`` is the largest difference of the surface ``σxx`` over
    :func:`stress_points`' surface line, ``stress_depth`` that of ``σxx``,
    ``σzz`` and ``σxz`` over its grid at depth, both in units of the
    reference's peak pressure; ``sxx_peak`` is the difference of the largest
    surface ``σxx`` (the tension at the trailing edge) in units of the
    reference's largest ``|σxx|`` on that line. Each result evaluates its own
    ``stress(x, z)`` (the FEM from its displacement field) with its own
    Poisson ratio, which the compared components do not depend on.
    """
    (xs, zs), (xg, zg) = stress_points(ref)
    p_max = max(pk.p for pk in normal_of(ref).peaks())
    sr, so = ref.stress(xs, zs), other.stress(xs, zs)
    out: dict[str, tuple[float, float, float]] = {}
    i = int(np.argmax(np.abs(so.sxx - sr.sxx)))
    out["sxx_surface"] = (float(sr.sxx[i]), float(so.sxx[i]), float(np.abs(so.sxx - sr.sxx)[i]) / p_max)
    top_r, top_o = float(sr.sxx.max()), float(so.sxx.max())
    out["sxx_peak"] = (top_r, top_o, abs(top_o - top_r) / float(np.abs(sr.sxx).max()))
    gr, go = ref.stress(xg, zg), other.stress(xg, zg)
    worst = (0.0, 0.0, -1.0)
    for comp in ("sxx", "szz", "sxz"):
        r, o = getattr(gr, comp), getattr(go, comp)
        j = int(np.argmax(np.abs(o - r)))
        worst = max(worst, (float(r[j]), float(o[j]), float(abs(o[j] - r[j])) / p_max), key=lambda t: t[2])
    out["stress_depth"] = worst
    return out


def _shear_integral(res: Any) -> float:
    """``∫ q dx`` of a slip result: exact on a nodal result's interpolant, else by quadrature.

    The quadrature splits the contact at its ends, the stick-zone ends and the
    joins, where ``q`` has square-root or logarithmic kinks, and maps each piece
    by ``x = u + (v - u)(1 - cos θ)/2``, which removes the square roots at its ends,
    before Gauss–Legendre in ``θ`` (:data:`_QUAD_NODES` points a piece).
    """
    n = normal_of(res)
    nodes = getattr(n, "x_nodes", None)
    if nodes is not None:
        x = sample_points(n, -n.a, n.c)
        return float(np.trapezoid(res.shear(x), x))
    lo, hi = -n.a, n.c
    b = n.punch.b
    breaks = sorted({lo, hi, *(x for x in (*res.stick_zone, -b, b) if lo < x < hi)})
    t, w = gauss01(_QUAD_NODES)         # on [0, 1]: θ = π t, dθ = π dt
    theta = np.pi * t
    total = 0.0
    for u, v in zip(breaks, breaks[1:]):
        x = u + 0.5 * (v - u) * (1 - np.cos(theta))
        total += 0.5 * np.pi * (v - u) * float(np.sum(w * np.sin(theta) * res.shear(x)))
    return total


#: Gauss–Legendre points per piece of :func:`_shear_integral`
_QUAD_NODES = 400


def _friction_excess(res: Any) -> float:
    """``max(|q| - f p, 0) / (f p_max)`` over the contact: Coulomb's bound, 0 when it holds."""
    n = normal_of(res)
    x = sample_points(n, -n.a, n.c)
    p = n.pressure(x)
    excess = np.abs(res.shear(x)) - res.f * p
    return float(max(excess.max(), 0.0) / (res.f * p.max()))


def compare(ref: Any, other: Any, comparison: str, *, stresses: bool = True) -> list[Check]:
    """Compare ``other`` with the reference ``ref`` and judge each figure.

    Parameters
    ----------
    ref
        The reference result (the closed form), normal, partial slip or a fretting cycle.
    other
        The result to check. When both are partial-slip results the stick
        zone and the shear field are compared too, when both are fretting
        cycles the cycle's figures (:func:`fretting_figures`), when both are
        steady states of a cycle between two states those of the steady
        state alone (:func:`steady_figures`); otherwise only the normal
        problem is compared.
    comparison
        Row group of :data:`threepart.tolerances.TOLERANCES`: ``"sie"``,
        ``"fem-quick"``, ``"fem-default"`` or ``"fem-fine"``; ``"referee"`` (another code's
        points) judges the shear away from the stick zone's ends too (:data:`AWAY_FROM_STICK_ENDS`).
    stresses
        Whether a partial slip's stresses in the substrate are compared too
        (:data:`~threepart.tolerances.STRESS_QUANTITIES`).

    Returns
    -------
    list of Check
        One per quantity, in the order of :data:`threepart.tolerances.QUANTITIES`.
    """
    if is_steady(ref) and is_steady(other):
        return _judge(steady_figures(ref, other), STEADY_QUANTITIES, comparison)
    figures = normal_figures(normal_of(ref), normal_of(other))
    quantities: tuple[str, ...] = NORMAL_QUANTITIES
    if is_slip(ref) and is_slip(other):
        figures.update(slip_figures(ref, other, away_from_stick_ends=comparison in AWAY_FROM_STICK_ENDS))
        quantities = NORMAL_QUANTITIES + SLIP_QUANTITIES
        if stresses:
            figures.update(stress_figures(ref, other))
            quantities += STRESS_QUANTITIES
    elif is_fretting(ref) and is_fretting(other):
        figures.update(fretting_figures(ref, other))
        quantities = NORMAL_QUANTITIES + FRETTING_QUANTITIES
    return _judge(figures, quantities, comparison)


def _judge(figures: dict[str, tuple[float, float, float]], quantities: tuple[str, ...],
           comparison: str) -> list[Check]:
    """One :class:`Check` per quantity: its figures judged against the tolerance table."""
    checks = []
    for q in quantities:
        r, o, err = figures[q]
        tol = tolerance(comparison, q)
        err = float(err) if math.isfinite(err) else math.inf
        checks.append(Check(comparison, q, float(r), float(o), err, tol.limit, tol.reason))
    return checks


#: the fretting states whose shear is compared: (Q / Q_max, branch)
SHEAR_STATES = ((1.0, "loading"), (0.0, "unloading"), (-1.0, "unloading"))


@dataclass(frozen=True)
class _State:
    """One state of a fretting cycle, seen as a partial-slip result (for :func:`field_errors`)."""

    cycle: Any
    Q: float
    branch: str

    @property
    def normal(self) -> Any:
        return self.cycle.normal

    @property
    def a(self) -> float:
        return float(self.cycle.normal.a)

    @property
    def c(self) -> float:
        return float(self.cycle.normal.c)

    @property
    def d(self) -> float:
        return math.nan

    def shear(self, x: Any) -> np.ndarray:
        return self.cycle.shear(x, self.Q, self.branch)


def fretting_figures(ref: Any, other: Any) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, normalised error)`` for two fretting cycles.

    Both must record the same states (branch and ``Q``). ``stick`` is the
    largest difference of the stick-zone ends over the states, in units of the
    reference's ``d`` at ``Q_max``; ``loop`` that of :meth:`FrettingResult.loop`
    in units of its largest value; ``q_states`` the largest interior shear
    difference at :data:`SHEAR_STATES`, in units of the largest shear there.
    """
    if len(ref.Q) != len(other.Q) or not np.allclose(ref.Q, other.Q, rtol=0, atol=1e-12 * ref.Q_max) \
            or not np.array_equal(ref.branch, other.branch):
        raise InputError("the two fretting cycles do not record the same states (branch and Q)")
    out: dict[str, tuple[float, float, float]] = {}
    out["energy"] = (ref.energy, other.energy, abs(other.energy - ref.energy) / abs(ref.energy))
    at_max = int(np.flatnonzero(ref.branch == "loading")[-1])
    d_max = 0.5 * float(ref.stick[at_max, 1] - ref.stick[at_max, 0])
    dev = np.abs(np.asarray(other.stick) - np.asarray(ref.stick))
    out["stick"] = (d_max, 0.5 * float(other.stick[at_max, 1] - other.stick[at_max, 0]),
                    float(dev.max()) / d_max)
    (_, hr), (_, ho) = ref.loop(), other.loop()
    scale = float(np.max(np.abs(hr)))
    out["loop"] = (scale, float(np.max(np.abs(ho))), float(np.max(np.abs(ho - hr))) / scale)
    worst = (0.0, 0.0, 0.0)
    for frac, branch in SHEAR_STATES:
        fe = field_errors(_State(ref, frac * ref.Q_max, branch),
                          _State(other, frac * other.Q_max, branch), "shear")
        figure = (fe.interior_peak(fe.ref), fe.interior_peak(fe.other), fe.interior_max)
        worst = max(worst, figure, key=lambda f: f[2])
    out["q_states"] = worst
    return out



@dataclass(frozen=True)
class SteadyRange:
    """The shear range ``q_1 - q_0`` of a steady cycle, over its larger contact (eqs. S3, S4).

    It is what the steady state fixes everywhere: ``±f (p_0 + p_1)`` in the slip
    zones and ``f (p_0 + p_1) - 2 f p*`` in the permanent stick zone, where the
    shear at either end alone carries a part locked in by the load history
    (eq. S13; a marched method finds the history's, the superposition a choice).
    Seen as a partial-slip result for :func:`field_errors`.
    """

    steady: Any

    @property
    def normal(self) -> Any:
        return max(self.steady.normals, key=lambda n: float(n.a + n.c))

    @property
    def a(self) -> float:
        return float(self.normal.a)

    @property
    def c(self) -> float:
        return float(self.normal.c)

    def shear(self, x: Any) -> np.ndarray:
        return np.asarray(self.steady.shear(x, 1), float) - np.asarray(self.steady.shear(x, 0), float)


def steady_figures(ref: Any, other: Any) -> dict[str, tuple[float, float, float]]:
    """``quantity -> (reference, obtained, normalised error)`` for two steady states of one cycle.

    ``stick_ends``: the larger difference of the permanent stick zone's ends
    ``(-(d + e), d - e)`` in units of the width ``W`` of the smaller contact
    (the intersection of the two ends' contacts); ``cycle_energy``: ``|ΔW|/W``
    of the energy per cycle (eq. S11); ``q_range``: the largest interior difference of the shear
    range ``q_1 - q_0`` (eq. S4, :class:`SteadyRange`) in units of its largest value; ``slip_amplitude``: the largest difference of the slip amplitude
    (eq. S7) over the smaller contact in units of its largest value. In
    shakedown (eq. S12) the shear and the slip are zero or history: only the
    stick zone and the energy are compared.
    """
    lo = max(-float(n.a) for n in ref.normals)
    hi = min(float(n.c) for n in ref.normals)
    W = hi - lo
    (rl, rr), (ol, orr) = ref.stick_zone, other.stick_zone
    out: dict[str, tuple[float, float, float]] = {}
    out["stick_ends"] = (float(ref.d), float(other.d), max(abs(ol - rl), abs(orr - rr)) / W)
    dE = abs(other.energy - ref.energy)
    out["cycle_energy"] = (ref.energy, other.energy, dE / ref.energy if ref.energy > 0 else dE)
    if ref.shakedown or other.shakedown:
        out["q_range"] = out["slip_amplitude"] = (0.0, 0.0, 0.0 if ref.shakedown == other.shakedown
                                                     else math.inf)
        return out
    fe = field_errors(SteadyRange(ref), SteadyRange(other), "shear")
    out["q_range"] = (fe.interior_peak(fe.ref), fe.interior_peak(fe.other), fe.interior_max)
    x = sample_points(other.normals[0], lo, hi)
    dr, do = (np.asarray(r.slip_amplitude(x), float) for r in (ref, other))
    # the largest amplitudes where they lie (the one routine of the command line and the report)
    peak_ref, peak_other = ref.largest_slip_amplitude()[0], other.largest_slip_amplitude()[0]
    scale = peak_ref or 1.0
    out["slip_amplitude"] = (peak_ref, peak_other, float(np.max(np.abs(do - dr))) / scale)
    return out

"""The load axis of the validity map: what the small-slope contact kinematics cost at a point.

Half-plane theory (eqs. 1-4) measures the gap vertically between the undeformed
surfaces and takes the contact force as vertical. The finite-body FEM solves a
map point twice, with ``kinematics="small"`` (that assumption) and with
``kinematics="first_order"`` (the contact conditions on the deformed surfaces,
to first order in the slopes: :func:`fem.contact.first_order_compliance`); the
signed relative difference is what the assumption costs there. It grows with
the load, measured by ``load_level = p0 A / 2 = p0 / E*`` (``A`` of eq. 4 for
two similar bodies is ``2 / E*``, ``E* = E / (2 (1 - nu^2))``; ``p0`` the
closed form's larger peak). This level is chosen over ``4 P A / b`` because it
is defined for every ``b`` (``4 P A / b`` diverges as ``b -> 0``, Hertz) and it
is the strain scale of the contact, which sets the slopes (Hertz:
``p0 A / 2 = a / (2 R)``, half the edge slope).

Two elastically similar half-planes have no normal-tangential coupling
(Dundurs' ``beta = 0``), and both first-order terms act through it: the paper's
model (``H = None``) costs nothing at first order. The cost here comes from the
punch's finite height, which couples the two bodies through its shape. The
finite-deformation cost that CalculiX measures is larger and has another cause
(``docs/SMALL_SLOPE.md``).

:func:`evaluate_slope` evaluates one :class:`~reports.map.validity.MapPoint`
(keys :data:`SLOPE_RESULT_KEYS`); :func:`slope_crossing` finds, along one curve
of the map (fixed ``R2/R1``, ``b/R1``, ``H/b``), the load level at which the
cost of the peak crosses a level (1 %).
"""
from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from threepart import fem
from threepart.results.fields import peak
from threepart.problem.material import similar_pair
from threepart.tolerances import MAP_LIMIT

from .validity import E, GRID, MESHES, NU, THETA, MapPoint, closed_form, point_load, point_punch, \
    feasible

__all__ = ["evaluate_slope", "slope_crossing", "load_level", "SLOPE_RESULT_KEYS", "SLOPE_LEVEL",
           "SLOPE_BRACKET"]

#: what :func:`evaluate_slope` returns for a point (all floats)
SLOPE_RESULT_KEYS = ("load_level", "slope_peak_rel_error", "slope_a_rel_error", "slope_time_s")
#: the small-slope cost of the peak the map marks: the map's 1 % (threepart.tolerances.MAP_LIMIT)
SLOPE_LEVEL = MAP_LIMIT
#: the overhangs ``(a - b)/R1`` that bracket :func:`slope_crossing`: the full map grid's ends
#: (the upper end is lowered to the largest grid overhang the curve's punch can hold)
SLOPE_BRACKET = (min(GRID["full"]["a_minus_b_over_R1"]), max(GRID["full"]["a_minus_b_over_R1"]))
#: the relative precision of the crossing's overhang (Brent's ``rtol``): a few FEM pairs
CROSSING_RTOL = 0.02


def load_level(point: MapPoint) -> float:
    """``p0 / E* = p0 A / 2`` of the closed form at ``point`` (``p0`` its larger peak, eq. 4's ``A``)."""
    punch, P, A = point_punch(point), point_load(point), similar_pair(E, NU)
    cf = closed_form(punch, P, 0.0, A=A)
    return 0.5 * A * _peak(cf)


def _peak(result: Any) -> float:
    """The larger pressure peak of a result: of its FE nodes (:func:`threepart.results.fields.peak`), else
    of its pressure function (:meth:`~threepart.results.NormalResult.peaks`)."""
    if hasattr(result, "p_nodes") and len(result.p_nodes):
        return peak(result.x_nodes, result.p_nodes)[1]
    return max(pk.p for pk in result.peaks())


def evaluate_slope(point: MapPoint, quick: bool = False) -> dict[str, float]:
    """The small-slope kinematics' cost at ``point`` (keys :data:`SLOPE_RESULT_KEYS`).

    The finite body of the map (:func:`fem.solve_finite`, the point's ``H``,
    the map mode's fine mesh :data:`reports.map.validity.MESHES`) with both
    kinematics at the point's load; ``slope_peak_rel_error`` and
    ``slope_a_rel_error`` are SIGNED, small minus first-order over
    first-order, of the larger peak and of the left half-width ``a``.
    """
    t0 = time.perf_counter()
    punch, P = point_punch(point), point_load(point)
    mesh = MESHES["quick" if quick else "full"][0]
    runs = {k: fem.solve_finite(punch, P, 0.0, E=E, nu=NU, H=point.H_over_b * punch.b,
                                theta=THETA, mesh=mesh, kinematics=k, progress=False)
            for k in ("small", "first_order")}
    small, first = runs["small"], runs["first_order"]
    return {"load_level": load_level(point),
            "slope_peak_rel_error": _peak(small) / _peak(first) - 1,
            "slope_a_rel_error": small.a / first.a - 1,
            "slope_time_s": time.perf_counter() - t0}


def slope_crossing(R2_over_R1: float, b_over_R1: float, H_over_b: float, quick: bool = False,
                   level: float = SLOPE_LEVEL,
                   bracket: tuple[float, float] | None = None) -> dict[str, Any]:
    """The load level at which the small-slope cost of the peak crosses ``level`` on one map curve.

    Brent's method on ``log(cost / level)`` against ``log((a - b)/R1)`` over
    ``bracket`` (nearly linear: the cost grows as a power of the overhang, so
    it converges in a few steps; relative precision :data:`CROSSING_RTOL` of
    the overhang), each step one :func:`evaluate_slope` (two FEM solves). ``bracket = None``: :data:`SLOPE_BRACKET`, its upper end
    lowered to the largest overhang of the full grid that the curve's punch
    holds (:func:`reports.map.validity.feasible`).

    Returns
    -------
    dict
        ``load_level`` and ``a_minus_b_over_R1`` at the crossing (``None``
        when the cost stays on one side of ``level`` over the bracket: both
        ends' costs are then in ``ends``), ``evaluations`` and ``time_s``.
    """
    t0 = time.perf_counter()
    curve = MapPoint(R2_over_R1, b_over_R1, SLOPE_BRACKET[0], H_over_b)
    if bracket is None:
        held = [ab for ab in GRID["full"]["a_minus_b_over_R1"]
                if feasible(replace(curve, a_minus_b_over_R1=ab))]
        bracket = (SLOPE_BRACKET[0], max(held))
    seen: list[tuple[float, float]] = []

    def excess(log_overhang: float) -> float:
        """``log(cost / level)``: near linear in ``log(overhang)`` (the cost is ~ k overhang^m)."""
        overhang = float(np.exp(log_overhang))
        cost = abs(evaluate_slope(replace(curve, a_minus_b_over_R1=overhang), quick)
                   ["slope_peak_rel_error"])
        seen.append((overhang, cost))
        return float(np.log(max(cost, 1e-300) / level))

    lo, hi = (excess(float(np.log(x))) for x in bracket)
    out: dict[str, Any] = {"load_level": None, "a_minus_b_over_R1": None,
                           "ends": [(x, c) for x, c in seen]}
    if lo * hi < 0:
        root = float(np.exp(brentq(excess, *np.log(bracket), xtol=CROSSING_RTOL)))
        out["a_minus_b_over_R1"] = root
        out["load_level"] = load_level(replace(curve, a_minus_b_over_R1=root))
    out.update(evaluations=len(seen), time_s=time.perf_counter() - t0)
    return out

"""Where the half-plane formulas stop: one point of the validity map, and the map's grid.

A point is a punch of real shape (central segment ``2b``, exact edge arcs of
radius ``R1`` and ``R2``, straight flanks, height ``H``) pressed into a finite
block by ``P`` at the lever arm ``s`` with the tilt free, solved by the
finite-body FEM (:mod:`fem.finite`) and by the closed form at the same
``(P, s)``. The lever arm is a fraction ``s_over_lift`` of the closed form's
lift-off lever arm ``s_max(P)`` (eq. s_lift-off, :func:`closedform.lift_off`:
the load towards the ``R2`` edge, at which the left edge reaches its join).
The load is chosen so that the closed form's larger overhang,
``max(a - b, c - b)``, is ``(a_minus_b_over_R1) R1`` (at ``s = 0`` and
``R2 <= R1`` that is ``a - b``). The map sweeps :class:`MapPoint` over
:func:`map_points`; :func:`evaluate` returns the closed form's SIGNED errors
against the finite body, ``(closed form - finite body) / finite body`` (the
peaks over the finite body's larger peak), with the FEM's own
discretisation-error estimate, a magnitude, beside them. A positive peak
error means that the closed form over-predicts the peak pressure: it is
conservative for the contact stress there.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass
from typing import Any

from scipy.optimize import brentq

from threepart import closedform, fem
from threepart.convergence import run_study
from threepart.errors import MeshResolutionError
from threepart.fem.finite import zone_margin
from threepart.fem.mesh import PRESETS
from threepart.problem.material import NU as NU_DEFAULT, similar_pair
from threepart.meshes import SubstrateSpec
from threepart.meshes.punch import PunchSpec
from threepart.results.fields import edge_multipliers
from threepart.problem.punch import Punch

from ..compare import normal_figures

__all__ = ["MapPoint", "map_points", "evaluate", "control", "feasible", "convergence", "RESULT_KEYS",
           "EDGE_KEYS", "edge_errors",
           "GRID", "STUDY_POINTS", "SLIP_SUBSET", "SLOPE_SUBSET", "subset", "slope_curves"]

#: what :func:`evaluate` returns for a point (all floats); every ``*_error`` but
#: ``fem_error_estimate`` is signed, closed form minus finite body
RESULT_KEYS = ("peak_rel_error", "p_left_rel_error", "p_right_rel_error", "a_rel_error",
               "c_rel_error", "alpha_error", "fem_error_estimate", "P", "s", "time_s")
#: issue 32: each edge's K_N (docs/EDGES.md), closed form minus finite body over the finite
#: body's (its fit over the fine mesh's nodes, :func:`threepart.results.fields.edge_multipliers`); None
#: where the fit finds too few nodes. Not part of ``fem_error_estimate``
EDGE_KEYS = ("K_N_left_rel_error", "K_N_right_rel_error")


@dataclass(frozen=True)
class MapPoint:
    """One point of the validity map (all ratios dimensionless; ``R1 = 10`` sets the scale).

    ``a_minus_b_over_R1`` is the closed form's larger overhang ``max(a - b, c - b) / R1``;
    ``s_over_lift`` the lever arm as a fraction of the lift-off lever arm ``s_max(P)``.
    """

    R2_over_R1: float
    b_over_R1: float
    a_minus_b_over_R1: float
    H_over_b: float
    s_over_lift: float = 0.0

    def key(self) -> str:
        """A stable identifier (for resuming an interrupted sweep)."""
        return (f"R2R1={self.R2_over_R1:.6g}_bR1={self.b_over_R1:.6g}_"
                f"abR1={self.a_minus_b_over_R1:.6g}_Hb={self.H_over_b:.6g}_"
                f"sL={self.s_over_lift:.6g}")

    def as_dict(self) -> dict[str, float]:
        return asdict(self)


#: the scale of every point (the ratios fix the rest), the material and the flank angle
R1, E, NU, THETA = 10.0, 1.0, NU_DEFAULT, math.pi / 3
#: the grid of each map mode (:func:`map_points` drops the points the punch cannot hold)
GRID = {
    "quick": dict(R2_over_R1=(1.0, 0.5), H_over_b=(4.0,), s_over_lift=(0.0, 0.5),
                  b_over_R1=(0.1, 0.3, 1.0), a_minus_b_over_R1=(0.01, 0.03, 0.1, 0.2, 0.3)),
    "full": dict(R2_over_R1=(1.0, 0.5), H_over_b=(1.0, 4.0, 16.0), s_over_lift=(0.0, 0.5),
                 b_over_R1=(0.1, 0.3, 1.0, 3.0), a_minus_b_over_R1=(0.01, 0.03, 0.1, 0.2, 0.35, 0.5)),
}
#: the points of the grid that also get the partial-slip study (:mod:`reports.map.validity_slip`,
#: issue 23: the stick zone at Q/fP = 0.4): the central load on the middle height, both R2/R1,
#: every b/R1 and overhang (26 quick points, 33 full; about 3x a normal point each)
SLIP_SUBSET: dict[str, tuple[float, ...]] = {"s_over_lift": (0.0,), "H_over_b": (4.0,)}
#: the points (and the curves over b/R1) of the small-slope load axis
#: (:mod:`reports.map.validity_slope`): its cost is a property of the load and the shape, so one
#: shape family is enough: R2/R1 = 1, H/b = 4, central load
SLOPE_SUBSET: dict[str, tuple[float, ...]] = {"s_over_lift": (0.0,), "H_over_b": (4.0,),
                                              "R2_over_R1": (1.0,)}
#: the FE meshes of a point in each map mode, fine and coarse (their difference is the FEM's
#: error estimate)
MESHES = {"quick": ("quick", 0.5), "full": ("default", 0.5)}


def map_mode(quick: bool) -> str:
    """The map mode, the key of :data:`GRID` and :data:`MESHES`."""
    return "quick" if quick else "full"


def point_punch(point: MapPoint) -> Punch:
    return Punch(R1=R1, R2=point.R2_over_R1 * R1, b=point.b_over_R1 * R1)


def closed_form(punch: Punch, P: float, s: float, *, A: float) -> Any:
    """The paper's formulas at any load: the map measures their error past the small slopes too."""
    return closedform.solve_normal(punch, P, s, A=A, beyond_small_slopes=True)


def _lever_arm(point: MapPoint, punch: Punch, P: float, A: float) -> float:
    """``s = (s_over_lift) s_max(P)``: a fraction of the closed form's lift-off lever arm at ``P``."""
    if point.s_over_lift == 0:
        return 0.0
    return point.s_over_lift * closedform.lift_off(punch, P, A, beyond_small_slopes=True).s_max


def point_load(point: MapPoint) -> float:
    """The load at which the closed form's larger overhang is ``max(a, c) - b = (a_minus_b_over_R1) R1``.

    The lever arm follows the load (:func:`_lever_arm`), so the pair ``(P, s)``
    is solved together: ``s = (s_over_lift) s_max(P)`` inside the root function.
    """
    punch, A = point_punch(point), similar_pair(E, NU)
    target = point.a_minus_b_over_R1 * R1

    def overhang(P: float) -> float:
        cf = closed_form(punch, P, _lever_arm(point, punch, P, A), A=A)
        return max(cf.a, cf.c) - punch.b - target

    hi = 1e-3
    while overhang(hi) < 0:
        hi *= 4
    return float(brentq(overhang, hi / 4 if hi > 1e-3 else 1e-12, hi, xtol=1e-14, rtol=1e-13))


def point_case(point: MapPoint) -> tuple[Punch, float, float]:
    """The punch, the load ``P`` and the lever arm ``s`` of ``point``."""
    punch, P = point_punch(point), point_load(point)
    return punch, P, _lever_arm(point, punch, P, similar_pair(E, NU))


def feasible(point: MapPoint) -> bool:
    """Whether the punch's lower face and height hold the contact with a margin (before any FE)."""
    punch, P, s = point_case(point)
    ref = closed_form(punch, P, s, A=similar_pair(E, NU))
    H = point.H_over_b * punch.b
    # the solver's locate margin with 50 % to spare for the finite body's larger contact
    margin = 1.5 * zone_margin(punch.b, -ref.a, ref.c, 0.15) * ref.width
    try:
        zone = SubstrateSpec(x_lo=-ref.a - margin, x_hi=ref.c + margin, h=ref.width / 10, L=1e3 * R1)
        PunchSpec(zone=zone, b=punch.b, R1=punch.R1, R2=punch.R2, H=H, theta=THETA)
    except ValueError:
        return False
    return True


def map_points(quick: bool = False) -> list[MapPoint]:
    """The grid of the map (:data:`GRID`) less the points whose punch cannot hold the contact."""
    g = GRID[map_mode(quick)]
    return [pt for pt in (MapPoint(r, b, ab, hb, sl) for r in g["R2_over_R1"]
                          for hb in g["H_over_b"] for sl in g["s_over_lift"]
                          for b in g["b_over_R1"] for ab in g["a_minus_b_over_R1"])
            if feasible(pt)]


def subset(points: list[MapPoint], where: dict[str, tuple[float, ...]]) -> list[MapPoint]:
    """The points whose coordinates take the values of ``where`` (e.g. :data:`SLIP_SUBSET`)."""
    return [p for p in points if all(getattr(p, a) in v for a, v in where.items())]


def slope_curves(points: list[MapPoint]) -> list[tuple[float, float, float]]:
    """The curves ``(R2/R1, b/R1, H/b)`` of :data:`SLOPE_SUBSET` among ``points``, for
    :func:`reports.map.validity_slope.slope_crossing`."""
    return sorted({(p.R2_over_R1, p.b_over_R1, p.H_over_b) for p in subset(points, SLOPE_SUBSET)})


def _signed(figure: tuple[float, float, float]) -> float:
    """A ``(reference, obtained, normalised error)`` figure's error with the sign of obtained - reference."""
    ref, got, err = figure
    return math.copysign(err, got - ref) if got != ref else 0.0


def _errors(fe: Any, cf: Any) -> dict[str, float]:
    """The closed form's signed errors against the FEM (the reference), as :func:`compare` measures them.

    Closed form minus finite body: the peaks over the finite body's larger
    peak and the tilt over its slope scale (:func:`reports.compare.normal_figures`),
    ``a`` and ``c`` each over the finite body's own. ``peak_rel_error`` is the
    one of the two peak errors with the larger magnitude, with its sign.
    """
    fig = normal_figures(fe, cf)
    left, right = _signed(fig["p_left"]), _signed(fig["p_right"])
    return {"p_left_rel_error": left, "p_right_rel_error": right,
            "peak_rel_error": left if abs(left) >= abs(right) else right,
            "a_rel_error": (cf.a - fe.a) / fe.a, "c_rel_error": (cf.c - fe.c) / fe.c,
            "alpha_error": _signed(fig["alpha"])}


def evaluate(point: MapPoint, quick: bool = False) -> dict[str, Any]:
    """The closed form's signed errors against the finite-body FEM at ``point`` (keys :data:`RESULT_KEYS`).

    The FEM runs on two meshes of one self-similar family (:data:`MESHES`);
    ``fem_error_estimate`` is the largest change of the compared figures from
    the coarse to the fine one, an upper estimate of the fine mesh's error
    (a magnitude).
    """
    t0 = time.perf_counter()
    punch, P, s = point_case(point)
    cf = closed_form(punch, P, s, A=similar_pair(E, NU))
    name, coarse = MESHES[map_mode(quick)]
    runs = [fem.solve_finite(punch, P, s, E=E, nu=NU, H=point.H_over_b * punch.b, theta=THETA,
                             mesh=m) for m in (PRESETS[name].scaled(coarse), name)]
    fine, rough = _errors(runs[1], cf), _errors(runs[0], cf)
    estimate = max(abs(fine[k] - rough[k]) for k in fine)
    return {**fine, "fem_error_estimate": estimate, "P": P, "s": s, **edge_errors(runs[1], cf),
            "time_s": time.perf_counter() - t0}


def edge_errors(fe: Any, cf: Any) -> dict[str, float | None]:
    """:data:`EDGE_KEYS`: the closed form's K_N at each edge against the finite body's nodal fit.

    The edge can be right while the peak is not, or the reverse (issue 32).
    """
    try:
        fitted = edge_multipliers(fe.x_nodes, fe.p_nodes, fe.a, fe.c, fe.punch.b)
    except MeshResolutionError:
        return {k: None for k in EDGE_KEYS}
    return {k: (e.K_N - K) / K for k, (K, _), e in zip(EDGE_KEYS, fitted, cf.edges())}


def control(quick: bool = False) -> dict[str, Any]:
    """The map's zero line: the paper's model (eq. 2 profile, large bodies) against the closed form.

    The finite-body code with ``H = None`` (:func:`fem.solve_finite`) at one
    point of the grid; ``control_rel_error`` is the closed form's larger
    peak-pressure error (a magnitude), which must be <= 1e-3.
    """
    t0 = time.perf_counter()
    point = MapPoint(1.0, 0.3, 0.1, 4.0)
    punch, P = point_punch(point), point_load(point)
    cf = closed_form(punch, P, 0.0, A=similar_pair(E, NU))
    fe = fem.solve_finite(punch, P, 0.0, E=E, nu=NU, H=None, mesh=MESHES[map_mode(quick)][0])
    err = _errors(fe, cf)
    studies = [convergence(pt, STUDY_N[:-1] if quick else STUDY_N) for pt in STUDY_POINTS]
    return {"control_rel_error": abs(err["peak_rel_error"]), **err, "point": point.as_dict(), "P": P,
            "convergence": studies, "time_s": time.perf_counter() - t0}


#: the two map points of the finite body's own convergence study, and its meshes (W/h)
STUDY_POINTS = (MapPoint(1.0, 0.1, 0.1, 4.0), MapPoint(1.0, 1.0, 0.03, 4.0))
STUDY_N = (38, 75, 150, 300)


def convergence(point: MapPoint, ns: tuple[int, ...] = STUDY_N) -> dict[str, Any]:
    """The finite-body FEM's own convergence at ``point``: both peaks and ``a`` over ``ns``.

    ``ns`` are elements across the contact of the default mesh's self-similar
    family (:meth:`fem.MeshPreset.scaled`); the order and the fine-grid GCI
    come from the three finest levels (Celik et al. 2008, reference-free), and
    only where the values converge monotonically (the one driver,
    :func:`threepart.convergence.run_study`).
    """
    punch, P = point_punch(point), point_load(point)

    def level(n: int) -> tuple[float, dict[str, float], dict[str, Any]]:
        res = fem.solve_finite(punch, P, 0.0, E=E, nu=NU, H=point.H_over_b * punch.b, theta=THETA,
                               mesh=PRESETS["default"].scaled(n / PRESETS["default"].n))
        left, right = res.peaks()
        return res.diagnostics.h or math.nan, {"p_left": left.p, "p_right": right.p, "a": res.a}, {}

    st = run_study(level, list(ns), param="h")
    nan = math.nan
    return {"point": point.as_dict(), "n": list(ns), "h": st.sizes, "values": st.values,
            "order": {q: st.orders.get(q, nan) for q in st.values},
            "gci": {q: st.gci.get(q, nan) for q in st.values}}

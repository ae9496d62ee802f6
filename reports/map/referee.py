"""Two points of the validity map refereed by CalculiX: the finite body's FEM against an outside code.

The validity map (:mod:`reports.map.validity`) judges the closed form against
threepart's own finite-body FEM (:func:`fem.solve_finite`). Here an
independent model of the same physical problem -- CalculiX's CPE8 elements,
its node-to-surface penalty contact, its own gmsh mesh
(:func:`threepart.calculix.build_finite_model`) -- referees that FEM at two of
the map's points (issue 23): the punch of real shape (flat centre ``2b``,
exact arcs of radius ``R1 = R2 = 10``, flanks at ``theta = pi/3``, height
``H``) welded at its top to a rigid plate that carries ``P`` at ``s = 0``,
free to tilt, on a block ``200 W`` wide and deep clamped at its base; both
bodies ``E = 1``, ``nu = 0.3``, plane strain.

Large slopes: CalculiX's linear step pairs the faces on their deformed
positions. The two bodies are elastically similar (Dundurs ``beta = 0``), so
the faces' horizontal displacements are equal and the pairing sees the same
points as the linear FEM's node-by-node gap: the comparison needs no scaled
load (and a scaled load would not do: the arcs are exact circles, not the
parabolas under which the contact is self-similar in the load).

Names
-----
REFEREE_POINTS -- the two map points (issue 23): ``(a - b)/R1 = 0.03`` and ``0.1``, ``b/R1 = 0.1``, ``H/b = 4``
REFEREE_N      -- CalculiX's elements across the contact width ``W`` (``h = W/n``) on the whole model
REFEREE_LEVELS -- the symmetric (half) model's study in ``h``: ``W/h`` of its levels, the finest last
PEAK_WINDOW    -- the half-width of the fit that reads a peak, in ``W``
referee        -- CalculiX at one point, with its signed differences from the FEM and the closed form
read_run       -- CalculiX's ``p_left``, ``p_right``, ``a``, ``c`` from one run of the finite deck
fitted_peak    -- a peak of nodal pressures: the maximum of a local quartic fit
finite_deck    -- the CalculiX model and deck of one point (its half when the point is symmetric)
partial_slip_point -- opt-in: the partial-slip column at a point (an outside code's stick zone, judged)

Symmetric points (``R1 = R2``, ``s = 0``, both referee points) are modelled as
their half ``x >= 0`` (``build_finite_model(..., half=True)``: ``u_x = 0`` on
``x = 0``, the plate level): one peak, no mesh noise between two sides, and a
finer mesh at the same cost.
"""
from __future__ import annotations

import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from threepart.results.fields import peak
from threepart import calculix
from threepart.calculix import read as ccx_read
from threepart.problem.material import similar_pair

from .validity import MESHES, NU, THETA, E, MapPoint, closed_form, point_load, point_case, point_punch

__all__ = ["REFEREE_POINTS", "REFEREE_N", "REFEREE_LEVELS", "REFEREE_PENALTY", "REFEREE_INCREMENT",
           "PEAK_WINDOW", "referee", "read_run", "finite_deck", "fitted_peak", "symmetric", "partial_slip_point"]

#: the issue's two points: the closed form's peak about 1 % too high at 0.03, 0.3-0.6 % too low at 0.1
REFEREE_POINTS = (MapPoint(1.0, 0.1, 0.03, 4.0), MapPoint(1.0, 0.1, 0.1, 4.0))
#: CalculiX's elements across the contact width: W/h = 100 (at 200 ccx stops with "nonpositive
#: jacobian" in a block element, see docs/CALCULIX.md)
REFEREE_N = 100.0
#: the half model's levels (W/h): 100, 200, 300; the whole model stopped with "nonpositive
#: jacobian" at 200, the half model does not (docs/CALCULIX.md)
REFEREE_LEVELS = (100.0, 200.0, 300.0)
#: the fit that reads a peak spans +-0.03 W about it: the nodal pressures scatter by about 1 %
#: node to node (the master face's nodes, 1.37 h apart, against the slave's), so their largest
#: value is biased high; the same fit on the closed form's pressure at the nodes of the three
#: levels reads its peak to 1.3e-4 (at +-0.06 W to 6.5e-3: the window reaches the curvature's
#: jump at x = b)
PEAK_WINDOW = 0.03
#: the penalty in E/h: 20 (at 200 E/h and W/h = 100 ccx needed 13 increments, at 50 E/h it left
#: some penetrating slave nodes unpaired; 20 E/h converges in 4 increments of 1/4)
REFEREE_PENALTY = 20.0
#: the step's first and smallest increments: 1/4 (one increment does not converge on these
#: similar bodies), cut down to 1e-5 at most (at (a - b)/R1 = 0.1 the 1/64 of the small-slope
#: deck was not enough)
REFEREE_INCREMENT = (0.25, 1e-5)


def symmetric(point: MapPoint) -> bool:
    """Whether ``point`` is symmetric (``R2 = R1``; the map's load acts at ``s = 0``)."""
    return point.R2_over_R1 == 1.0


def fitted_peak(x: np.ndarray, p: np.ndarray, half_width: float) -> tuple[float, float]:
    """The peak ``(x, p)`` of the nodal pressures ``p`` at ``x`` (sorted): the maximum of the
    least-squares quartic over the nodes within ``half_width`` of it (:func:`threepart.results.fields.peak`
    with a window: centred on the largest five-node moving average, then on the first fit's maximum).
    """
    return peak(x, p, half_width=half_width, degree=4)


def finite_deck(point: MapPoint, *, n: float = REFEREE_N, penalty_factor: float = REFEREE_PENALTY,
                half: bool | None = None) -> tuple[calculix.Model, str, Any]:
    """The CalculiX model and deck of ``point``, and the closed form that sized its mesh.

    The fine zone is laid over the closed form's contact ``[-a, c]`` with the
    deck's margin (the finite body's contact differs from it by about 1 %).
    ``half``: model the half ``x >= 0`` (``None``: when the point is :func:`symmetric`).
    """
    half = symmetric(point) if half is None else half
    punch, P = point_punch(point), point_load(point)
    cf = closed_form(punch, P, 0.0, A=similar_pair(E, NU))
    settings = calculix.DeckSettings(n=n, penalty_factor=penalty_factor, pair=True)
    model = calculix.build_finite_model(punch, cf.a, cf.c, H=point.H_over_b * punch.b, theta=THETA,
                                        settings=settings, half=half)
    deck = calculix.write_deck(model, P=P, s=0.0, E=E, nu=NU, settings=settings, clamped=True,
                               increment=REFEREE_INCREMENT,
                               title=f"validity map point {point.key()}: finite punch, clamped block")
    return model, deck, cf


def read_run(model: calculix.Model, stem: Path) -> dict[str, float]:
    """CalculiX's ``p_left``, ``p_right`` (each side's :func:`fitted_peak`, at ``x_left``,
    ``x_right``), ``a``, ``c`` (from the gap) and the load the base and the contact forces carry,
    from one run of :func:`finite_deck`. A half model's figures are the whole body's: its one
    peak and end on both sides, twice its loads."""
    sp = ccx_read.surface_pressure(model, stem)
    # the peaks among the nodes the read-out fits (the loaded ones, DEALTERNATE_NODES in from
    # each end, where it keeps f / share, which alternates)
    on = np.flatnonzero(sp.f > 0)
    fitted = np.zeros(sp.x.size, bool)
    fitted[on[0] + ccx_read.DEALTERNATE_NODES:on[-1] + 1 - ccx_read.DEALTERNATE_NODES] = True
    W = model.a + model.c
    if "block_sym" in model.nsets:                 # the half x >= 0 of a symmetric point
        fitted[on[0]:on[0] + ccx_read.DEALTERNATE_NODES] = True     # x = 0 is no end
        x, p = fitted_peak(sp.x[fitted], sp.p[fitted], PEAK_WINDOW * W)
        return {"p_left": p, "p_right": p, "x_left": -x, "x_right": x, "a": sp.c, "c": sp.c,
                "P_base": 2 * sp.P, "P_forces": 2 * float(sp.f.sum())}
    left = sp.x < 0
    xl, pl = fitted_peak(sp.x[left & fitted], sp.p[left & fitted], PEAK_WINDOW * W)
    xr, pr = fitted_peak(sp.x[~left & fitted], sp.p[~left & fitted], PEAK_WINDOW * W)
    return {"p_left": pl, "p_right": pr, "x_left": xl, "x_right": xr, "a": sp.a, "c": sp.c,
            "P_base": sp.P, "P_forces": float(sp.f.sum())}


def _signed(mine: dict[str, float], other: dict[str, float]) -> dict[str, float]:
    """``(other - mine) / mine`` for the peaks and the ends."""
    return {q: (other[q] - mine[q]) / mine[q] for q in ("p_left", "p_right", "a", "c")}


def _run(point: MapPoint, n: float, penalty_factor: float, half: bool, workdir: Path | None,
         ) -> tuple[calculix.Model, dict[str, float], Any]:
    """One CalculiX run at ``point``: its model, its read-out (with ``n``, ``h``, nodes, ``K``,
    the CPU time of ccx) and the closed form."""
    import resource

    model, deck, cf = finite_deck(point, n=n, penalty_factor=penalty_factor, half=half)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory(prefix="threepart-ccx-map-") as tmp:
        where = Path(workdir) / f"n{n:g}_K{penalty_factor:g}" if workdir else Path(tmp)
        where.mkdir(parents=True, exist_ok=True)
        stem = calculix.run_ccx(deck, where, "finite")
        out = read_run(model, stem)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    W = cf.a + cf.c
    out.update(n=n, h=model.h0, nodes=model.n_nodes,
               K=calculix.DeckSettings(n=n, penalty_factor=penalty_factor).K(E, W),
               cpu_calculix_s=(after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime))
    return model, out, cf


def referee(point: MapPoint, *, n: float = REFEREE_N, penalty_factor: float = REFEREE_PENALTY,
            levels: tuple[float, ...] = REFEREE_LEVELS, workdir: Path | None = None) -> dict[str, Any]:
    """CalculiX at ``point``, against the finite-body FEM and the closed form.

    A :func:`symmetric` point is run as its half model at each of ``levels``
    (``W/h``, the finest last, which is CalculiX's answer), and once more at
    the coarsest with the penalty doubled; any other point as the whole
    model at ``W/h = n``.

    Returns
    -------
    dict
        ``calculix``: its ``p_left``, ``p_right``, ``a``, ``c`` (and the peaks'
        ``x``, the loads); ``fem`` and ``closed_form``: the same figures;
        ``fem_minus_calculix`` and ``closed_form_minus_calculix``: signed
        differences over CalculiX's (``(other - calculix) / calculix``);
        ``closed_form_minus_fem``: the map's own figure; the mesh (``n``,
        ``h``, nodes), the penalty ``K`` and the times; ``half``; for a
        symmetric point ``study``: each level's read-out, the penalty's, and
        ``peak_change`` (the peak's change between the two finest levels over
        the finest's) and ``penalty_change`` (doubling ``K`` at the second
        finest level).

    Raises
    ------
    calculix.CcxMissing
        Without ``ccx`` on the PATH (before any numerics).
    """
    if not calculix.ccx_available():
        raise calculix.CcxMissing("`ccx` (CalculiX) is not on the PATH: apt-get install calculix-ccx")
    from threepart import fem

    half = symmetric(point)
    t0 = time.perf_counter()
    study: dict[str, Any] = {}
    if half:
        runs = [_run(point, lv, penalty_factor, True, workdir) for lv in levels]
        model, ccx, cf = runs[-1]
        # K in E/h: its relative effect does not change with h, so the coarsest level shows it
        stiff = _run(point, levels[0], 2 * penalty_factor, True, workdir)[1]
        coarser, coarsest = runs[-2][1], runs[0][1]
        study = {"levels": [r[1] for r in runs], "penalty": stiff,
                 "peak_change": (ccx["p_right"] - coarser["p_right"]) / ccx["p_right"],
                 "penalty_change": (stiff["p_right"] - coarsest["p_right"]) / coarsest["p_right"]}
    else:
        model, ccx, cf = _run(point, n, penalty_factor, False, workdir)
    t_ccx = time.perf_counter() - t0
    punch, P = point_punch(point), point_load(point)
    fe = fem.solve_finite(punch, P, 0.0, E=E, nu=NU, H=point.H_over_b * punch.b, theta=THETA,
                          mesh=MESHES["full"][0])
    t_fem = time.perf_counter() - t0 - t_ccx
    figs = {name: {"p_left": r.peaks()[0].p, "p_right": r.peaks()[1].p, "a": r.a, "c": r.c}
            for name, r in (("fem", fe), ("closed_form", cf))}
    W = cf.a + cf.c
    return {"point": point.as_dict(), "P": P, "half": half, "calculix": ccx, **figs,
            "fem_minus_calculix": _signed(ccx, figs["fem"]),
            "closed_form_minus_calculix": _signed(ccx, figs["closed_form"]),
            "closed_form_minus_fem": _signed(figs["fem"], figs["closed_form"]),
            "n": ccx["n"], "h": model.h0, "W": W, "nodes": model.n_nodes, "K": ccx["K"],
            "study": study, "time_calculix_s": t_ccx, "time_fem_s": t_fem,
            "cpu_calculix_s": sum(r["cpu_calculix_s"] for r in [*study.get("levels", [ccx]),
                                                                 *([study["penalty"]] if study else [])])}


def partial_slip_point(point: MapPoint, *, code: str = "calculix", n: float | None = None,
                       workdir: Path | None = None, say: Any = print) -> dict[str, Any]:
    """The partial-slip column of a referee point: an outside code's stick zone against the
    closed form (the SIE where it refuses), judged as the verification run's friction columns.

    Opt-in (``python -m threepart.reports.map.referee --friction``; not run by ``threepart
    map``, whose cost is unchanged): the map's points carry no shear, and CalculiX's friction
    run costs minutes. The point's punch (``R1``, ``R2``, ``b``: the profile of eq. 2 that its
    arcs follow) and load, with the radii times :data:`~reports.referee.studies.SLOPE_SCALE`
    and ``P`` over it as in the columns (the same contact, slopes / 20), of two similar steel
    bodies at the load of the same ``P A`` as the map's (the same contact), at ``Q = 0.4 f P`` (:mod:`reports.referee.friction_problems`), at
    ``W/h = n`` (default: the code's finest level).

    Returns
    -------
    dict
        ``point``, ``code``, ``n``, ``h``, ``errors`` (``stick_width``, ``stick_shift`` of W,
        ``q_interior_max``, ``q_integral``), ``rows`` (the verdict of
        :func:`reports.referee.verdict.column_verdict`), ``passed``; a code that is not
        installed gives ``status`` "not installed" and its ``note``, no numbers.
    """
    from dataclasses import replace

    from ..referee.friction_problems import FrictionProblem, pair_problem
    from ..referee.friction_studies import referee as friction_referee
    from ..referee.friction_studies import run_level
    from ..referee.studies import SLOPE_SCALE
    from ..referee.verdict import column_verdict

    ref = friction_referee(code)
    if not ref.available():
        return {"point": point.as_dict(), "code": code, "status": "not installed", "note": ref.missing}
    from threepart.problem.material import E_STEEL

    punch, P, s = point_case(point)
    punch = replace(punch, R1=SLOPE_SCALE * punch.R1, R2=SLOPE_SCALE * punch.R2, R=SLOPE_SCALE * punch.R)
    P *= similar_pair(E, NU) / similar_pair(E_STEEL, NU) / SLOPE_SCALE   # steel, the same P A: the same contact
    pr = pair_problem(punch, P, s, tilt="free", E=E_STEEL, nu=NU, method="auto",
                      title=f"validity map point {point.key()} (steel, the same P A), radii x {SLOPE_SCALE:g}, "
                            f"P / {SLOPE_SCALE:g}")
    level = float(n if n is not None else ref.levels[-1])
    problem = FrictionProblem(f"map {point.key()}", lambda: pr, "slip", "full")
    with tempfile.TemporaryDirectory(prefix="threepart-map-friction-") as tmp:
        where = Path(workdir) if workdir else Path(tmp)
        where.mkdir(parents=True, exist_ok=True)
        h, values, _, errors = run_level(ref, problem, pr, level, where, say)
    slip = pr["slip"]
    study = {"sizes": [h], "labels": [str(level)], "errors": {q: [e] for q, e in errors.items()},
             "orders": {}, "values": {q: [v] for q, v in values.items()},
             "reference": {"d": slip.d, "e": slip.e, "q_integral": slip.Q}}
    rows = column_verdict(study, ref.documented)
    return {"point": point.as_dict(), "code": code, "status": "run", "n": level, "h": h,
            "reference_method": slip.method, "errors": errors, "rows": rows,
            "passed": all(r["passed"] for r in rows)}


def _main() -> None:  # pragma: no cover - a measurement, run by hand
    import json
    import sys

    args = [a for a in sys.argv[1:] if a != "--friction"]
    points = [REFEREE_POINTS[int(k)] for k in args] or list(REFEREE_POINTS)
    run = partial_slip_point if "--friction" in sys.argv[1:] else referee
    for pt in points:
        print(json.dumps(run(pt), indent=1, default=float), flush=True)


if __name__ == "__main__":  # pragma: no cover
    _main()

"""Partial slip on the validity map's points (issue 23): the closed form's stick zone against the finite body.

At a point of the map (:class:`reports.map.validity.MapPoint`: the punch of real
shape on a finite block, ``P`` at ``s = 0`` with the tilt free, the load that
gives the point's overhang) the punch is then sheared by ``Q = Q_OVER_FP f P``
with the coefficient of friction :data:`F`, by the finite-body friction model
(:func:`fem.solve_finite_slip`: the two-body model on the real punch shape,
coupling kept) and by the closed form (:func:`closedform.solve_partial_slip`
on the closed form's own normal solution at the same ``P``).
:func:`evaluate_slip` returns the closed form's signed errors in the stick
zone's half-width ``d`` and offset ``e``, beside the FEM's own
discretisation-error estimate, as :func:`reports.map.validity.evaluate` does for
the normal problem.
"""
from __future__ import annotations

import math
import time
from typing import Any

from threepart import closedform, fem
from threepart.fem.mesh import PRESETS
from threepart.problem.material import similar_pair

from ..compare import slip_figures
from .validity import E, MESHES, NU, THETA, MapPoint, closed_form, point_load, map_mode, point_punch

__all__ = ["Q_OVER_FP", "F", "SLIP_RESULT_KEYS", "evaluate_slip"]

#: issue 23: the stick zone is compared at this fraction of full sliding
Q_OVER_FP = 0.4
#: coefficient of friction: the catalogue's usual value (its slip and fretting cases of
#: caseA_moment use f = 0.5). At s = 0 with no bulk stress the closed form's stick zone depends on Q/(fP) only, so
#: f matters only through the coupling of the finite body's normal and tangential problems
F = 0.5
#: what :func:`evaluate_slip` returns for a point (all floats)
SLIP_RESULT_KEYS = ("d_rel_error", "e_rel_error", "slip_fem_error_estimate", "d", "e",
                    "slip_time_s")


def _signed(fe: Any, cf: Any) -> dict[str, float]:
    """Closed form minus finite body, in units of the finite body's ``|d|`` (as :func:`slip_figures`)."""
    fig = slip_figures(fe, cf)
    return {"d_rel_error": math.copysign(fig["d"][2], cf.d - fe.d),
            "e_rel_error": math.copysign(fig["e"][2], cf.e - fe.e)}


def evaluate_slip(point: MapPoint, quick: bool = False) -> dict[str, Any]:
    """The closed form's stick-zone errors against the finite body at ``point`` (keys :data:`SLIP_RESULT_KEYS`).

    ``d_rel_error = (d_cf - d_fe) / |d_fe|`` and ``e_rel_error = (e_cf - e_fe) / |d_fe|``:
    signed, closed form minus finite body, normalised as
    :func:`reports.compare.slip_figures` normalises them. The FEM runs on the
    two meshes of :data:`reports.map.validity.MESHES` (one self-similar family);
    ``slip_fem_error_estimate`` is the larger change of the two errors from the
    coarse to the fine one. ``d`` and ``e`` are the finite body's (fine mesh).

    Raises
    ------
    StickZoneError
        If the closed form's stick zone at ``Q_OVER_FP`` ends inside the flat
        centre, where its formulas do not hold.
    """
    t0 = time.perf_counter()
    punch, P = point_punch(point), point_load(point)
    Q = Q_OVER_FP * F * P
    cf = closedform.solve_partial_slip(closed_form(punch, P, 0.0, A=similar_pair(E, NU)), Q, F)
    name, coarse = MESHES[map_mode(quick)]
    runs = [fem.solve_finite_slip(punch, P, 0.0, Q=Q, f=F, E=E, nu=NU, H=point.H_over_b * punch.b,
                                  theta=THETA, mesh=m) for m in (PRESETS[name].scaled(coarse), name)]
    rough, fine = (_signed(r, cf) for r in runs)
    estimate = max(abs(fine[k] - rough[k]) for k in fine)
    return {**fine, "slip_fem_error_estimate": estimate, "d": runs[1].d, "e": runs[1].e,
            "slip_time_s": time.perf_counter() - t0}

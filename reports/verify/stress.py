"""Stress and fatigue in the verification run: the substrate under each partial-slip case, by every method.

The comparison (:func:`reports.compare.stress_figures`) judges each method's
stress field against the reference's; this module gives the report what a
designer reads off that field: where the surface tension and the von Mises
stress peak, and how much, by each method, and the fields drawn in
:func:`reports.verify.plots.stress_surface` and :func:`reports.verify.plots.von_mises`.
Every method's stresses come from its own ``stress(x, z)`` (one result shape;
nothing here knows a method). Nothing here solves a contact.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

from threepart.fatigue import HotSpot, hot_spot
from threepart.stress import Stress
from threepart.problem.material import NU, similar_pair_modulus

from ..compare import STRESS_REACH, is_steady, normal_of, surface_line

__all__ = ["FIELD_GRID", "FATIGUE_GRID", "field_grid", "surface_line", "StressFields", "stress_fields",
           "hot_spots", "case_hot_spots",
           "fatigue_states", "fatigue_hot_spots", "joined_fatigue", "stress_nu"]

#: points ``(nx, nz)`` of the field under a contact: x over the contact and ``STRESS_REACH W``
#: beyond each end, z from the surface to the depth ``W``
FIELD_GRID = (97, 49)


def stress_nu(case_material: tuple[float, float] | None) -> float:
    """Poisson's ratio for the stresses of a case: its material's, else :data:`threepart.problem.material.NU`."""
    return float(case_material[1]) if case_material is not None else NU


def field_grid(ref: Any, shape: tuple[int, int] = FIELD_GRID) -> tuple[np.ndarray, np.ndarray]:
    """``(x, z)`` of shape ``(nz, nx)``: the section under the contact of ``ref``, depth 0 to ``W``.

    The surface row avoids the contact ends (see :func:`surface_line`) by
    starting the depth at ``1e-3 W``.
    """
    nr = normal_of(ref)
    W = nr.a + nr.c
    nx, nz = shape
    xs = np.linspace(-nr.a - STRESS_REACH * W, nr.c + STRESS_REACH * W, nx)
    zs = np.linspace(1e-3 * W, W, nz)
    return np.meshgrid(xs, zs)


@dataclass(frozen=True)
class StressFields:
    """One result's stresses where a partial-slip case's hot spots are searched and its stress plots drawn.

    ``surface`` at the points ``xs`` of :func:`surface_line` (``z = 0``), ``field`` at ``(x, z)``
    of :func:`field_grid`, both of the reference's contact: computed once (:func:`stress_fields`),
    read by :func:`hot_spots`, :func:`reports.verify.plots.stress_surface` and
    :func:`reports.verify.plots.von_mises`.
    """

    xs: np.ndarray
    surface: Stress
    x: np.ndarray
    z: np.ndarray
    field: Stress


def stress_fields(result: Any, nu: float, ref: Any | None = None) -> StressFields:
    """The stresses of ``result`` on the surface line and the field grid of ``ref`` (default: its own)."""
    ref = result if ref is None else ref
    xs = surface_line(ref)
    x, z = field_grid(ref)
    return StressFields(xs, result.stress(xs, np.zeros_like(xs), nu=nu), x, z, result.stress(x, z, nu=nu))


def hot_spots(result: Any, nu: float, ref: Any | None = None,
              fields: StressFields | None = None) -> dict[str, HotSpot]:
    """The largest surface tension ``σxx``, von Mises stress and Tresca shear of ``result``.

    ``σxx`` is searched along :func:`surface_line` (where fretting cracks
    start: the trailing edge), the other two over :func:`field_grid`
    (Hamilton's subsurface maximum, or the surface in partial slip). ``ref``
    sets the points (the reference's contact), so that every method of a case
    is searched on the same points. ``fields``: the stresses there, if computed
    already (:func:`stress_fields`).
    """
    fields = stress_fields(result, nu, ref) if fields is None else fields
    xs, st = fields.xs, fields.field
    out = {"sxx": hot_spot(xs, np.zeros_like(xs), fields.surface.sxx)}
    for name, values in (("von_mises", st.von_mises), ("max_shear", st.max_shear)):
        out[name] = hot_spot(fields.x, fields.z, values)
    return out


def case_hot_spots(results: Mapping[str, Any], nu: float, reference: str,
                   fields: Mapping[str, StressFields] | None = None) -> dict[str, dict[str, Any]]:
    """``method -> quantity -> hot spot`` (as dicts) for the slip results of one case.

    ``fields``: each method's :class:`StressFields`, if computed already.
    """
    ref = results[reference]
    fields = fields or {}
    return {m: {q: {"quantity": q, "x": h.x, "z": h.z, "value": h.value}
                for q, h in hot_spots(res, nu, ref, fields.get(m)).items()} for m, res in results.items()}


#: points ``(nx, nz)`` of the fatigue fields of a fretting case, and every how many recorded
#: states its stress history takes (the cycle's reversals and tips are kept)
FATIGUE_GRID = (25, 13)
FATIGUE_STRIDE = 5


def fatigue_states(cycle: Any) -> np.ndarray:
    """Indices of the states a report's fatigue history uses: every :data:`FATIGUE_STRIDE`-th and each branch's ends."""
    n = len(cycle.Q)
    ends = [i for i in range(n) if i == 0 or i == n - 1 or cycle.branch[i] != cycle.branch[i - 1]
            or cycle.branch[i] != cycle.branch[min(i + 1, n - 1)]]
    return np.unique(np.concatenate([np.arange(0, n, FATIGUE_STRIDE), ends]))


def fatigue_hot_spots(results: Mapping[str, Any], material: tuple[float, float] | None,
                      reference: str, methods: Sequence[str] | None = None) -> dict[str, Any]:
    """``method -> parameter -> hot spot`` of the fretting cycles, or the steady flight cycles, of one
    case (:mod:`threepart.fatigue`).

    Every method is evaluated on the reference's points and the same states; ``methods``
    (default: every one of ``results``) chooses which, so that a case's methods can be
    evaluated apart and their ``hot_spots`` joined.
    The substrate's Young's modulus for the SWT strains is the case's
    ``material`` ``(E, nu)``; a case given by its compliance alone is read as a
    similar pair, ``E = 4(1 - ν²)/A`` (eq. 4) with :data:`threepart.problem.material.NU`.
    """
    from threepart.fatigue import K_FINDLEY
    from threepart.fatigue.table import fatigue, reported

    ref = results[reference]
    nu = stress_nu(material)
    E = float(material[0]) if material is not None else similar_pair_modulus(normal_of(ref).A, nu)
    x, z = field_grid(ref, FATIGUE_GRID)
    nr = normal_of(ref)
    line = np.linspace(-nr.a, nr.c, 202)[1:-1]
    idx = None if is_steady(ref) else fatigue_states(ref)   # a steady cycle: its two end states
    out: dict[str, Any] = {"E": E, "nu": nu, "k": K_FINDLEY, "states": 2 if idx is None else int(len(idx)),
                           "hot_spots": {}}
    for m in results if methods is None else methods:
        fat = fatigue(results[m], x, z, E=E, nu=nu, states=idx, surface=line)
        out["hot_spots"][m] = {n: {"x": p.hot.x, "z": p.hot.z, "value": p.hot.value}
                               for n in reported() for p in (fat.parameters[n],)}
    return out


def joined_fatigue(records: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """One case's fatigue record from its methods' (:func:`fatigue_hot_spots` of one method each)."""
    return {**records[0], "hot_spots": {m: h for r in records for m, h in r["hot_spots"].items()}}

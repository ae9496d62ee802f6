"""Convergence studies: SIE in the number of nodes n, FEM in the mesh size h (normal and partial slip).

Both are measured against the closed form, so they live in :mod:`reports`.
Each study returns a :class:`Study` of plain numbers: the errors per level, the
observed orders fitted as ``np.polyfit(np.log(h), np.log(err), 1)``, and, for
the FEM, Roache's grid-convergence index (GCI) of the three finest levels; the
tools are those of :mod:`threepart.convergence`.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from threepart.catalogue import Case
from threepart.output import json_safe
from threepart.convergence import (ROUND_OFF, converges_monotonically, fitted_order, gci,
                                   is_monotone, richardson, three_level_order)

from .catalogue import Mode, solve_normal
from .compare import normal_figures, slip_figures
from . import solvers

__all__ = ["Study", "sie_study", "fem_study", "fem_slip_study", "fem_step_study",
           "STUDY_QUANTITIES", "SLIP_STUDY_QUANTITIES", "STEP_STATES"]

#: figures followed through a study (errors normalised as in threepart.tolerances)
STUDY_QUANTITIES = ("a", "c", "alpha", "p_left", "p_right", "p_interior_max")
#: figures followed through a partial-slip study
SLIP_STUDY_QUANTITIES = ("a", "c", "alpha", "d", "e", "q_interior_max")
#: states per branch of the fretting load-step study (the step halves from one to the next)
STEP_STATES = (6, 11, 21, 41)
#: quantities that are themselves a field error (their "value" is the error, no Richardson step)
_FIELD_ERRORS = ("p_interior_max", "q_interior_max")


@dataclass
class Study:
    """Errors of one method against the closed form over a sequence of discretisations.

    ``param`` is ``"n"`` (SIE) or ``"h"`` (FEM); ``values`` the parameter per
    level; ``errors[q]`` the normalised error of quantity ``q`` per level;
    ``raw[q]`` the quantity itself per level; ``orders[q]`` the fitted
    observed order (error ~ n^-p or h^p, so p > 0 means convergence);
    ``gci[q]`` the fine-grid GCI (FEM only); ``extrapolated[q]`` the
    Richardson estimate of ``q`` from the two finest levels.
    """

    method: str
    case: str
    param: str
    values: list[float]
    labels: list[str]
    errors: dict[str, list[float]]
    raw: dict[str, list[float]]
    reference: dict[str, float]
    times: list[float]
    orders: dict[str, float] = field(default_factory=dict)
    gci: dict[str, float] = field(default_factory=dict)
    extrapolated: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    scheme: str = ""

    @property
    def quantities(self) -> tuple[str, ...]:
        """The quantities followed, in order."""
        return tuple(self.errors)

    def as_dict(self) -> dict[str, Any]:
        return json_safe({"method": self.method, "scheme": self.scheme, "case": self.case, "param": self.param,
                      "values": self.values, "labels": self.labels, "errors": self.errors,
                      "raw": self.raw, "reference": self.reference, "times": self.times,
                      "orders": self.orders, "gci": self.gci, "extrapolated": self.extrapolated,
                      "notes": self.notes})


def _figures(ref: Any, res: Any, quantities: Sequence[str]) -> tuple[dict[str, float], dict[str, float]]:
    """Obtained values and normalised errors of ``quantities`` (as :func:`compare`)."""
    figures = normal_figures(getattr(ref, "normal", ref), getattr(res, "normal", res))
    if "d" in quantities:
        figures.update(slip_figures(ref, res))
    raw = {q: figures[q][1] for q in quantities}
    err = {q: figures[q][2] for q in quantities}
    for q in _FIELD_ERRORS:
        if q in raw:
            raw[q] = err[q]
    return raw, err


def _three_level(raw: Sequence[float], hs: np.ndarray) -> tuple[float, float] | None:
    """Order and fine-grid GCI from the three finest levels (None with fewer than three)."""
    if len(hs) < 3:
        return None
    (f3, f2, f1), (h3, h2, h1) = raw[-3:], hs[-3:]
    p = three_level_order(f3, f2, f1, h2 / h1, h3 / h2)
    return p, gci(f2, f1, h2 / h1, p)


def _run(method: str, case: Case, labels: Sequence[str], solver: Callable[[Case, str], Any],
         param_of: Callable[[Any, str], float], param: str,
         progress: Callable[[str], None] | None, param_label: str = "level",
         quantities: Sequence[str] = STUDY_QUANTITIES) -> Study:
    case = case.resolved()
    ref = solve_normal(case, "closedform", Mode("study", None, "quick", (), ()))
    if "d" in quantities:
        ref = solvers.slip("closedform", case, ref)
    reference = _figures(ref, ref, quantities)[0]
    st = Study(method, case.name, param, [], [], {q: [] for q in quantities},
               {q: [] for q in quantities}, reference, [])
    for lab in labels:
        t0 = time.perf_counter()
        try:
            res = solver(case, lab)
        except Exception as exc:  # noqa: BLE001 - a failed level is a note, not a crash
            st.notes.append(f"level {lab}: {type(exc).__name__}: {exc}")
            continue
        dt = time.perf_counter() - t0
        raw, err = _figures(ref, res, quantities)
        st.values.append(param_of(res, lab))
        st.labels.append(str(lab))
        st.times.append(dt)
        for q in quantities:
            st.errors[q].append(err[q])
            st.raw[q].append(raw[q])
        if progress:
            where = f"{param_label} {lab}" if param_label.endswith("=") else param_label
            progress(f"{method} {param} = {st.values[-1]:.4g} ({where}): {dt:.2f} s")
    v = np.asarray(st.values, dtype=float)
    hs = 1.0 / v if param == "n" else v
    for q in quantities:
        three = _three_level(st.raw[q], hs) if q not in _FIELD_ERRORS else None
        if not is_monotone(st.errors[q]):
            # an order fitted through errors that rise again would claim a rate that is not there
            st.orders[q] = math.nan
            if three is not None and converges_monotonically(st.raw[q][-3:]):
                # the values still converge from one side: the reference-free order and GCI hold
                st.orders[q], st.gci[q] = three
                st.notes.append(f"{q}: the values converge monotonically (order {three[0]:.2f} "
                                "from the three finest levels), but the error against the closed "
                                "form is not monotone: it falls below the finest level's change")
            elif any(e > ROUND_OFF for e in st.errors[q]):
                st.notes.append(f"{q}: the errors are not monotone in the refinement; no order is given")
            continue
        st.orders[q] = fitted_order(hs, st.errors[q])[0]
        if q in _FIELD_ERRORS:
            continue
        p = st.orders[q]
        if len(hs) >= 2 and math.isfinite(p) and p > 0 and hs[-2] > hs[-1]:
            st.extrapolated[q] = float(richardson(hs, st.raw[q], p))
        if three is not None:
            st.gci[q] = three[1]
    return st


def sie_study(case: Case, ns: Sequence[int], scheme: str | None = None,
              progress: Callable[[str], None] | None = None) -> Study:
    """SIE errors against the closed form for each ``n`` in ``ns``.

    ``scheme`` is passed to ``sie.solve_normal`` (``"plain"`` collocation or
    the kink-aware ``"projected"``; None: the solver's default).
    """
    options = {} if scheme is None else {"scheme": scheme}

    def solver(c: Case, lab: str) -> Any:
        return solvers.normal("sie", c, n=int(lab), **options)

    st = _run("sie", case, [str(n) for n in ns], solver,
              lambda res, lab: float(getattr(res, "n", None) or res.info.get("n", int(lab))),
              "n", progress, "scheme " + (scheme or "default"))
    st.scheme = scheme or "default"
    return st


def fem_study(case: Case, ns: Sequence[int],
              progress: Callable[[str], None] | None = None) -> Study:
    """FEM errors against the closed form for ``n`` elements across the contact (coarse to fine).

    The meshes are members of the default preset's self-similar family
    (:meth:`fem.MeshPreset.scaled`): every element size, the grading included,
    scales with ``1/n`` at fixed block size and end refinement.
    """
    def solver(c: Case, lab: str) -> Any:
        return solve_normal(c, "fem", Mode("study", None, _family(int(lab)), (), ()))

    return _run("fem", case, [str(n) for n in ns], solver, _h_of, "h", progress, "W/h =")


def fem_slip_study(case: Case, ns: Sequence[int],
                   progress: Callable[[str], None] | None = None) -> Study:
    """Two-body friction FEM errors (contact, stick zone, shear) against the closed form, by ``n``.

    ``case`` is a partial-slip case; the meshes are those of :func:`fem_study`.
    """
    def solver(c: Case, lab: str) -> Any:
        return solvers.slip("fem", c, None, mesh=_family(int(lab)))

    return _run("fem", case, [str(n) for n in ns], solver, _h_of, "h", progress, "W/h =",
                SLIP_STUDY_QUANTITIES)


def _family(n: int) -> Any:
    """The member of the default mesh's self-similar family with ``n`` elements across W."""
    from threepart.fem.mesh import PRESETS

    return PRESETS["default"].scaled(n / PRESETS["default"].n)


def _h_of(res: Any, lab: str) -> float:
    """Element size along the contact of an FE result (normal or partial slip)."""
    normal = getattr(res, "normal", res)
    return float(getattr(normal, "h", None) or normal.info["h"])


def fem_step_study(case: Case, reference: Any, mesh: Any = "quick",
                   states: Sequence[int] = STEP_STATES,
                   progress: Callable[[str], None] | None = None) -> Study:
    """The FE energy per fretting cycle as the load step ``ΔQ = 2 Q_max / (states - 1)`` shrinks.

    ``case`` is a fretting case and ``reference`` the closed form's cycle. The
    errors against it level off at the mesh's own error, so the order is
    also given reference-free, from the three finest steps (Celik et al.
    2008), where the energies converge from one side.
    """
    case = case.resolved()
    Q = case.shear_load[0]
    st = Study("fem", case.name, "dQ", [], [], {"energy": []}, {"energy": []},
               {"energy": float(reference.energy)}, [])
    for k in states:
        t0 = time.perf_counter()
        res = solvers.fretting("fem", case, None, k, mesh=mesh)
        st.times.append(time.perf_counter() - t0)
        st.values.append(2 * Q / (k - 1))
        st.labels.append(str(k))
        st.raw["energy"].append(res.energy)
        st.errors["energy"].append(abs(res.energy / reference.energy - 1))
        if progress:
            progress(f"fem {k} states per branch: energy {res.energy:.8g} ({st.times[-1]:.2f} s)")
    E, dQ = st.raw["energy"], np.asarray(st.values)
    three = _three_level(E, dQ)
    if three is not None and converges_monotonically(E[-3:]):
        st.orders["energy"], st.gci["energy"] = three
        st.extrapolated["energy"] = float(richardson(dQ, E, three[0]))
        fit = fitted_order(dQ, st.errors["energy"])[0]
        st.notes.append(f"energy: order {three[0]:.2f} from the three finest steps (reference-free); "
                        f"against the closed form the error includes the mesh's and fits order "
                        f"{fit:.2f}")
    else:
        st.orders["energy"] = math.nan
        st.notes.append("energy: the energies do not converge monotonically in the load step; "
                        "no order is given")
    return st

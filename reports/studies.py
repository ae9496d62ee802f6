"""Convergence studies: SIE in the number of nodes n, FEM in the mesh size h.

Both are measured against the closed form, so they live in :mod:`reports`.
Each study returns a :class:`Study` of plain numbers: the errors per level, the
observed orders fitted as ``np.polyfit(np.log(h), np.log(err), 1)``, and, for
the FEM, Roache's grid-convergence index (GCI) of the three finest levels.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from threepart.sie.convergence import richardson

from .catalogue import Case, Mode, solve_normal
from .compare import normal_figures
from .solvers import SOLVERS

__all__ = ["Study", "observed_order", "gci", "sie_study", "fem_study", "STUDY_QUANTITIES"]

#: figures followed through a study (errors normalised as in reports.tolerances)
STUDY_QUANTITIES = ("a", "c", "alpha", "p_left", "p_right", "p_interior_max")
#: normalised errors below this are round-off and carry no order
ROUND_OFF = 1e-13


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

    def as_dict(self) -> dict[str, Any]:
        def clean(v: Any) -> Any:
            if isinstance(v, dict):
                return {k: clean(x) for k, x in v.items()}
            if isinstance(v, (list, tuple)):
                return [clean(x) for x in v]
            if isinstance(v, float) and not math.isfinite(v):
                return None
            return v

        return clean({"method": self.method, "scheme": self.scheme, "case": self.case, "param": self.param,
                      "values": self.values, "labels": self.labels, "errors": self.errors,
                      "raw": self.raw, "reference": self.reference, "times": self.times,
                      "orders": self.orders, "gci": self.gci, "extrapolated": self.extrapolated,
                      "notes": self.notes})


def observed_order(param: Sequence[float], err: Sequence[float], inverse: bool = False) -> float:
    """Slope of ``log err`` against ``log param`` (negated when ``inverse``, for n).

    Levels with a non-finite error or one at the round-off floor
    (:data:`ROUND_OFF`, normalised) are dropped; NaN if fewer than two remain.
    """
    x = np.asarray(param, dtype=float)
    y = np.asarray(err, dtype=float)
    ok = np.isfinite(y) & (y > ROUND_OFF) & np.isfinite(x) & (x > 0)
    if ok.sum() < 2:
        return math.nan
    slope = float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])
    return -slope if inverse else slope


def gci(f: Sequence[float], h: Sequence[float], Fs: float = 1.25) -> tuple[float, float, float]:
    """Roache's grid-convergence index of the finest of three levels.

    The observed order and the GCI are :func:`fem.studies.observed_order` and
    :func:`fem.studies.gci` (Celik et al. 2008); the extrapolation is
    :func:`sie.convergence.richardson`.

    Parameters
    ----------
    f, h
        Values and mesh sizes of three levels, coarse to fine.
    Fs
        Safety factor (1.25 for three grids).

    Returns
    -------
    (p, gci_fine, f_extrapolated)
        Observed order from the three values, the relative GCI of the finest
        value, and the Richardson extrapolation. NaN when the three values do
        not converge monotonically.
    """
    from threepart.fem.studies import gci as fine_gci
    from threepart.fem.studies import observed_order as three_level_order

    f3, f2, f1 = (float(v) for v in f[-3:])
    h3, h2, h1 = (float(v) for v in h[-3:])
    p = three_level_order(f1, f2, f3, h2 / h1, h3 / h2)
    if not math.isfinite(p):
        return math.nan, math.nan, math.nan
    f_ext = float(richardson([1 / h2, 1 / h1], [f2, f1], p))
    return p, fine_gci(f1, f2, h2 / h1, p, Fs), f_ext


def _figures(ref: Any, res: Any) -> tuple[dict[str, float], dict[str, float]]:
    """Obtained values and normalised errors of :data:`STUDY_QUANTITIES` (as :func:`compare`)."""
    figures = normal_figures(ref, res)
    raw = {q: figures[q][1] for q in STUDY_QUANTITIES}
    err = {q: figures[q][2] for q in STUDY_QUANTITIES}
    raw["p_interior_max"] = err["p_interior_max"]
    return raw, err


def _run(method: str, case: Case, labels: Sequence[str], solver: Callable[[Case, str], Any],
         param_of: Callable[[Any, str], float], param: str,
         progress: Callable[[str], None] | None, param_label: str = "level") -> Study:
    case = case.resolved()
    ref = solve_normal(case, "closedform", Mode("study", None, "quick", (), ()))
    rl, rr = ref.peaks()
    reference = {"a": ref.a, "c": ref.c, "alpha": ref.alpha, "p_left": rl.p, "p_right": rr.p,
                 "p_interior_max": 0.0}
    st = Study(method, case.name, param, [], [], {q: [] for q in STUDY_QUANTITIES},
               {q: [] for q in STUDY_QUANTITIES}, reference, [])
    for lab in labels:
        t0 = time.perf_counter()
        try:
            res = solver(case, lab)
        except Exception as exc:  # noqa: BLE001 - a failed level is a note, not a crash
            st.notes.append(f"level {lab}: {type(exc).__name__}: {exc}")
            continue
        dt = time.perf_counter() - t0
        raw, err = _figures(ref, res)
        st.values.append(param_of(res, lab))
        st.labels.append(str(lab))
        st.times.append(dt)
        for q in STUDY_QUANTITIES:
            st.errors[q].append(err[q])
            st.raw[q].append(raw[q])
        if progress:
            where = f"{param_label} {lab}" if param_label.endswith("=") else param_label
            progress(f"{method} {param} = {st.values[-1]:.4g} ({where}): {dt:.2f} s")
    inverse = param == "n"
    v = np.asarray(st.values, dtype=float)
    hs = 1.0 / v if inverse else v
    for q in STUDY_QUANTITIES:
        st.orders[q] = observed_order(st.values, st.errors[q], inverse=inverse)
        if q == "p_interior_max":
            continue
        p = st.orders[q]
        if len(hs) >= 2 and math.isfinite(p) and p > 0 and hs[-2] > hs[-1]:
            st.extrapolated[q] = float(richardson(1 / hs[-2:], st.raw[q][-2:], p))
        if len(hs) >= 3:
            st.gci[q] = gci(st.raw[q], list(hs))[1]
    return st


def sie_study(case: Case, ns: Sequence[int], scheme: str | None = None,
              progress: Callable[[str], None] | None = None) -> Study:
    """SIE errors against the closed form for each ``n`` in ``ns``.

    ``scheme`` is passed to ``sie.solve_normal`` (``"plain"`` collocation or
    the kink-aware ``"projected"``; None: the solver's default).
    """
    options = {} if scheme is None else {"scheme": scheme}

    def solver(c: Case, lab: str) -> Any:
        return SOLVERS["sie"].normal(c, n=int(lab), **options)

    st = _run("sie", case, [str(n) for n in ns], solver,
              lambda res, lab: float(getattr(res, "n", None) or res.info.get("n", int(lab))),
              "n", progress, "scheme " + (scheme or "default"))
    st.scheme = scheme or "default"
    return st


#: grading and domain of the FEM study meshes (only the element count across W changes)
FEM_STUDY_GROWTH, FEM_STUDY_L = 0.1, 200.0


def fem_study(case: Case, ns: Sequence[int],
              progress: Callable[[str], None] | None = None) -> Study:
    """FEM errors against the closed form for ``n`` elements across the contact (coarse to fine).

    The meshes share grading and domain size (:data:`FEM_STUDY_GROWTH`,
    :data:`FEM_STUDY_L` contact widths), so only ``h = W/n`` changes.
    """
    from threepart.fem.mesh import MeshPreset

    def solver(c: Case, lab: str) -> Any:
        mesh = MeshPreset(n=int(lab), growth=FEM_STUDY_GROWTH, L=FEM_STUDY_L)
        return solve_normal(c, "fem", Mode("study", None, mesh, (), ()))

    def h_of(res: Any, lab: str) -> float:
        h = getattr(res, "h", None)
        if h is None:
            h = res.info.get("h")
        return float(h)

    return _run("fem", case, [str(n) for n in ns], solver, h_of, "h", progress, "W/h =")

"""Mesh-convergence and domain-size studies of the FE model, returned as plain records.

The convergence study refines ``h = W/n`` at fixed grading and block size and
reports, for ``a``, ``c``, ``alpha`` and both peak pressures, the observed order
and the grid-convergence index (Roache's GCI with safety factor 1.25, in the
form of Celik et al. 2008 for non-constant refinement ratios) of the three finest
levels. Errors against a reference solution, when one is given, are fitted with
``np.polyfit(log h, log err, 1)``. The tools are :mod:`threepart.convergence`'s.
No closed form is called here.
"""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Any, Callable, Sequence

from threepart.convergence import fitted_order, gci, three_level_order
from threepart.punch import Punch

from ._boundary import boundary
from .mesh import MeshPreset
from .solve import FemResult, solve_normal

__all__ = ["StudyLevel", "StudyRecord", "convergence_study", "domain_study", "QUANTITIES"]

#: quantities followed by the studies
QUANTITIES = ("a", "c", "alpha", "p_left", "p_right")


@dataclass(frozen=True)
class StudyLevel:
    """One solve of a study: its mesh and the followed quantities."""

    n: float
    L: float
    h: float
    dofs: int
    seconds: float
    values: dict[str, float]


@dataclass(frozen=True)
class StudyRecord:
    """Levels of a study (coarse to fine) and, for a convergence study, orders and GCI.

    Attributes
    ----------
    kind
        ``"convergence"`` or ``"domain"``.
    levels
        The solves, in the order run.
    order, gci
        Observed order and fine-grid GCI (relative) of each quantity, from the
        three finest levels (convergence study only; ``nan`` when undefined).
    fitted_order, errors
        With a reference: errors per level and the slope of ``log err`` on ``log h``.
    """

    kind: str
    levels: list[StudyLevel]
    order: dict[str, float] = field(default_factory=dict)
    gci: dict[str, float] = field(default_factory=dict)
    fitted_order: dict[str, float] = field(default_factory=dict)
    errors: dict[str, list[float]] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        """Plain nested dict (JSON-ready)."""
        return asdict(self)


def _values(res: FemResult) -> dict[str, float]:
    left, right = res.peaks()
    return {"a": res.a, "c": res.c, "alpha": res.alpha, "p_left": left.p, "p_right": right.p}


def _solve(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
           pre: MeshPreset) -> StudyLevel:
    t0 = time.perf_counter()
    res = solve_normal(punch, P, s, E=E, nu=nu, tilt=tilt, mesh=pre)
    return StudyLevel(n=pre.n, L=pre.L, h=res.h, dofs=res.dofs,
                      seconds=time.perf_counter() - t0, values=_values(res))


@boundary
def convergence_study(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                      tilt: str = "free", ns: Sequence[float] = (30, 60, 120, 240),
                      growth: float = 0.1, L: float = 200.0,
                      reference: Callable[[], dict[str, float]] | dict[str, float] | None = None
                      ) -> StudyRecord:
    """Solve on ``len(ns) >= 4`` meshes with ``n`` elements across W, coarse to fine.

    Parameters
    ----------
    punch, P, s, E, nu, tilt
        As for :func:`fem.solve_normal`.
    ns
        Elements across the contact width, increasing, at least four.
    growth, L
        Grading and block size (in contact widths), shared by all levels.
    reference
        Optional exact values of :data:`QUANTITIES` (or a callable giving them),
        e.g. from another solver; then ``errors`` and ``fitted_order`` are filled.

    Returns
    -------
    StudyRecord
    """
    ns = [float(n) for n in ns]
    if len(ns) < 4 or any(b <= a for a, b in zip(ns, ns[1:])):
        raise ValueError(f"`ns` = {ns!r} must hold at least 4 increasing element counts")
    levels = [_solve(punch, P, s, E, nu, tilt, MeshPreset(n=n, growth=growth, L=L)) for n in ns]
    order, index = {}, {}
    l3, l2, l1 = levels[-3:]
    for q in QUANTITIES:
        p = three_level_order(l3.values[q], l2.values[q], l1.values[q], l2.h / l1.h, l3.h / l2.h)
        order[q] = p
        index[q] = gci(l2.values[q], l1.values[q], l2.h / l1.h, p)
    errors, fitted = {}, {}
    if reference is not None:
        ref = reference() if callable(reference) else reference
        W = ref["a"] + ref["c"]
        for q in QUANTITIES:  # a, c in units of W; alpha and peaks relative (alpha = 0: absolute)
            scale = W if q in ("a", "c") else (abs(ref[q]) or 1.0)
            errors[q] = [abs(lv.values[q] - ref[q]) / scale for lv in levels]
            fitted[q] = fitted_order([lv.h for lv in levels], errors[q])[0]
    return StudyRecord("convergence", levels, order, index, fitted, errors)


@boundary
def domain_study(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                 tilt: str = "free", Ls: Sequence[float] = (12.5, 25, 50, 100, 200, 400),
                 n: float = 120, growth: float = 0.1) -> StudyRecord:
    """Solve with block sizes ``L`` (in contact widths) at fixed ``n`` and grading.

    ``errors`` holds each quantity's change from the largest block, relative for
    ``alpha`` and the peaks, in units of the contact width for ``a`` and ``c``.
    """
    Ls = [float(v) for v in Ls]
    if len(Ls) < 2 or any(b <= a for a, b in zip(Ls, Ls[1:])):
        raise ValueError(f"`Ls` = {Ls!r} must hold at least 2 increasing block sizes")
    levels = [_solve(punch, P, s, E, nu, tilt, MeshPreset(n=n, growth=growth, L=v)) for v in Ls]
    last = levels[-1].values
    W = last["a"] + last["c"]
    errors = {}
    for q in QUANTITIES:
        scale = W if q in ("a", "c") else (abs(last[q]) or 1.0)
        errors[q] = [abs(lv.values[q] - last[q]) / scale for lv in levels]
    return StudyRecord("domain", levels, errors=errors)

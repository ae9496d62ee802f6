"""The convergence tools every study uses: fitted order, three-level order, GCI and Richardson.

All take the discretisation as a size ``h`` that falls as the discretisation is
refined (a mesh size, or ``1/n`` for ``n`` nodes), so an order ``p > 0`` always
means convergence, ``error ~ C h^p``.

fitted_order        -- p and C from ``np.polyfit(log h, log err, 1)``, round-off levels dropped
three_level_order   -- p from three solutions, no reference needed (Celik et al. 2008)
gci                 -- Roache's relative fine-grid convergence index (Celik et al. 2008)
richardson          -- Richardson-extrapolated value from the two finest levels

Study               -- the one result shape of every convergence study (SIE, FEM, report, map)
run_study           -- the one driver: evaluate each level, then :func:`analyse` it
analyse             -- orders, GCI and Richardson estimates of a study's levels, by one rule

Celik, Ghia, Roache, Freitas, Coleman & Raad, "Procedure for estimation and
reporting of uncertainty due to discretization in CFD applications",
J. Fluids Eng. 130 (2008) 078001.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike
from threepart.errors import InputError

__all__ = ["ROUND_OFF", "is_monotone", "converges_monotonically", "fitted_order", "three_level_order",
           "gci", "richardson", "Study", "run_study", "analyse"]

#: normalised errors at or below this are round-off and carry no order
ROUND_OFF = 1e-13


def is_monotone(err: ArrayLike, floor: float = ROUND_OFF) -> bool:
    """Whether the errors, ordered coarse to fine, fall at every step (those above ``floor``).

    An observed order means something only for such a sequence: a fit
    through errors that rise and fall again would print a rate the
    discretisation does not have.

    Parameters
    ----------
    err
        Normalised errors, coarse to fine.
    floor
        Errors at or below it (round-off) end the sequence.

    Returns
    -------
    bool
        True when at least two errors lie above ``floor`` and each is smaller
        than the one before.
    """
    y = np.asarray(err, dtype=float)
    y = y[np.isfinite(y)]
    above = y[: int(np.argmax(y <= floor))] if np.any(y <= floor) else y
    return len(above) >= 2 and bool(np.all(np.diff(above) < 0))


def converges_monotonically(values: ArrayLike) -> bool:
    """Whether values, ordered coarse to fine, change by steps of one sign that shrink.

    This is the reference-free test of the GCI method (Celik et al. 2008,
    ``0 < R < 1`` for the ratio of successive changes): the sequence
    approaches its limit from one side, so the three-level order and the
    GCI mean something even where the error against a reference, itself
    smaller than the last change, is not monotone.
    """
    d = np.diff(np.asarray(values, dtype=float))
    return (len(d) >= 2 and bool(np.all(np.isfinite(d))) and bool(np.all(d != 0))
            and bool(np.all(np.sign(d) == np.sign(d[0])))
            and bool(np.all(np.abs(d[1:]) < np.abs(d[:-1]))))


def fitted_order(h: ArrayLike, err: ArrayLike, floor: float = ROUND_OFF) -> tuple[float, float]:
    """Fit ``err = C h^p`` by ``np.polyfit(np.log(h), np.log(err), 1)``; return ``(p, C)``.

    Parameters
    ----------
    h
        Discretisation sizes (positive).
    err
        Normalised errors at those sizes.
    floor
        Errors at or below it (round-off), and non-finite ones, are left out.

    Returns
    -------
    (p, C)
        ``p > 0`` for convergence; both NaN when fewer than two levels remain.
    """
    x = np.asarray(h, dtype=float)
    y = np.asarray(err, dtype=float)
    keep = np.isfinite(y) & (y > floor) & np.isfinite(x) & (x > 0)
    if keep.sum() < 2:
        return math.nan, math.nan
    slope, icpt = np.polyfit(np.log(x[keep]), np.log(y[keep]), 1)
    return float(slope), float(np.exp(icpt))


def three_level_order(f_coarse: float, f_medium: float, f_fine: float, r21: float, r32: float) -> float:
    """Observed order from three solutions, coarse to fine (Celik et al. 2008, eqs. 3-4).

    ``r21 = h_medium/h_fine`` and ``r32 = h_coarse/h_medium`` (both > 1). The
    fixed-point iteration handles unequal ratios. NaN when two levels agree
    exactly or the sequence is not monotone (oscillatory convergence).
    """
    e21, e32 = f_medium - f_fine, f_coarse - f_medium
    if e21 == 0 or e32 == 0 or e32 / e21 <= 0:
        return math.nan
    ln_ratio = math.log(abs(e32 / e21))
    p = abs(ln_ratio) / math.log(r21)
    for _ in range(100):
        q = math.log((r21**p - 1.0) / (r32**p - 1.0))
        p_new = abs(ln_ratio + q) / math.log(r21)
        if abs(p_new - p) < 1e-10:
            return p_new
        p = p_new
    return p


def gci(f_medium: float, f_fine: float, r21: float, p: float, Fs: float = 1.25) -> float:
    """Relative fine-grid convergence index ``Fs |(f_medium - f_fine)/f_fine| / (r21^p - 1)``.

    ``Fs = 1.25`` is the safety factor for three grids (Celik et al. 2008,
    eq. 7). NaN when ``p`` is not a positive number or ``f_fine`` is 0.
    """
    if not math.isfinite(p) or p <= 0 or f_fine == 0:
        return math.nan
    return Fs * abs((f_medium - f_fine) / f_fine) / (r21**p - 1.0)


def richardson(h: ArrayLike, values: ArrayLike, p: float) -> np.ndarray:
    """Richardson extrapolation to ``h = 0`` from the last two levels, at order ``p``.

    ``f_fine + (f_fine - f_coarse)/(r^p - 1)`` with ``r = h_coarse/h_fine``;
    ``values`` may hold arrays (one row per level).
    """
    hh = np.asarray(h, dtype=float)
    v = np.asarray(values, dtype=float)
    r = hh[-2] / hh[-1]
    return np.asarray(v[-1] + (v[-1] - v[-2]) / (r**p - 1.0))


@dataclass
class Study:
    """One convergence study: its levels, coarse to fine, and what they show.

    Attributes
    ----------
    param
        What ``sizes`` holds: ``"n"`` (a node count; ``h = 1/n``), or a size
        that falls as the study refines (``"h"``, a load step ``"dQ"``).
    labels, sizes
        Each level's label and its discretisation parameter.
    values
        Each quantity per level (scalars, or arrays of a field).
    reference, scales
        The reference value of each quantity and the scale its errors are
        divided by; empty for a reference-free study.
    errors
        ``max |value - reference| / scale`` of each quantity per level.
    orders, constants
        The observed order ``p`` (``error ~ C h^p``) and ``C``; NaN where the
        sequence gives none (see :func:`analyse`).
    gci, extrapolated
        The fine-grid GCI (relative) and the Richardson estimate, where defined.
    times, info, notes
        Seconds and metadata (dofs, block size, ...) per level; what the
        analysis found worth saying (a failed level, a non-monotone sequence).
    method, case, scheme
        What was studied, where the caller says (the verification run does).
    """

    param: str
    labels: list[str] = field(default_factory=list)
    sizes: list[float] = field(default_factory=list)
    values: dict[str, list[Any]] = field(default_factory=dict)
    reference: dict[str, Any] = field(default_factory=dict)
    scales: dict[str, float] = field(default_factory=dict)
    errors: dict[str, list[float]] = field(default_factory=dict)
    orders: dict[str, float] = field(default_factory=dict)
    constants: dict[str, float] = field(default_factory=dict)
    gci: dict[str, float] = field(default_factory=dict)
    extrapolated: dict[str, Any] = field(default_factory=dict)
    times: list[float] = field(default_factory=list)
    info: list[dict[str, Any]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    method: str = ""
    case: str = ""
    scheme: str = ""

    def as_dict(self) -> dict[str, Any]:
        """A JSON-safe dict of the study (non-finite numbers as None; no per-level ``info``)."""
        from .output import json_safe

        return json_safe({k: getattr(self, k) for k in (
            "method", "scheme", "case", "param", "labels", "sizes", "values", "reference",
            "errors", "orders", "constants", "gci", "extrapolated", "times", "notes")})

    @property
    def h(self) -> np.ndarray:
        """The sizes that fall as the study refines: ``h``, or ``1/n``."""
        v = np.asarray(self.sizes, dtype=float)
        return 1.0 / v if self.param == "n" else v

    @property
    def quantities(self) -> tuple[str, ...]:
        """The quantities followed, in order."""
        return tuple(self.values)


def _error(value: Any, reference: Any, scale: float) -> float:
    return float(np.max(np.abs(np.asarray(value, dtype=float) - np.asarray(reference, dtype=float)))
                 / scale)


def analyse(study: Study, error_only: Sequence[str] = (), require_monotone: bool = True) -> Study:
    """Fill ``study``'s orders, GCI and Richardson estimates, by one rule for every study.

    With a reference, the order is fitted to the errors (:func:`fitted_order`)
    only where they fall at every level (:func:`is_monotone`); otherwise, if
    the three finest values still converge from one side
    (:func:`converges_monotonically`), the reference-free three-level order
    and GCI are given and a note says why; else no order. Without a
    reference, the three-level order and GCI are given where the values
    converge monotonically. ``error_only`` names quantities whose values are
    themselves errors (a field's largest deviation): they get a fitted order
    and nothing else. ``require_monotone=False`` fits the order through errors
    that wobble (a sequence of both parities of ``n``, chosen to average an
    even-odd wobble), as long as more than one lies above round-off.
    """
    h = study.h
    for q, vals in study.values.items():
        scalar = all(np.ndim(v) == 0 for v in vals)
        three = None
        if scalar and q not in error_only and len(vals) >= 3:
            (f3, f2, f1), (h3, h2, h1) = vals[-3:], h[-3:]
            p = three_level_order(f3, f2, f1, h2 / h1, h3 / h2)
            three = (p, gci(f2, f1, h2 / h1, p))
        one_sided = three is not None and converges_monotonically(vals[-3:])
        errs = study.errors.get(q)
        if errs is None:              # reference-free: only a one-sided approach has an order
            study.orders[q] = study.constants[q] = math.nan
            if one_sided:
                study.orders[q], study.gci[q] = three   # type: ignore[misc]
                study.extrapolated[q] = float(richardson(h, vals, study.orders[q]))
            continue
        if require_monotone and not is_monotone(errs):
            study.orders[q] = study.constants[q] = math.nan
            if one_sided:
                study.orders[q], study.gci[q] = three   # type: ignore[misc]
                study.notes.append(f"{q}: the values converge monotonically (order "
                                   f"{study.orders[q]:.2f} from the three finest levels), but the "
                                   "error against the reference is not monotone: it falls below "
                                   "the finest level's change")
            elif any(e > ROUND_OFF for e in errs):
                study.notes.append(f"{q}: the errors are not monotone in the refinement; no order "
                                   "is given")
            continue
        p, C = fitted_order(h, errs)
        study.orders[q], study.constants[q] = p, C
        if q in error_only:
            continue
        if len(h) >= 2 and math.isfinite(p) and p > 0 and h[-2] > h[-1]:
            study.extrapolated[q] = richardson(h, np.asarray(vals, dtype=float), p)
            if np.ndim(study.extrapolated[q]) == 0:
                study.extrapolated[q] = float(study.extrapolated[q])
        if three is not None:
            study.gci[q] = three[1]
    return study


def run_study(evaluate: Callable[[Any], tuple[Any, ...]],
              levels: Sequence[Any], *, param: str = "h",
              reference: Mapping[str, Any] | None = None,
              scales: Mapping[str, float] | None = None, error_only: Sequence[str] = (),
              skip: tuple[type[BaseException], ...] = (), require_monotone: bool = True,
              progress: Callable[[float, Any, float], None] | None = None,
              method: str = "", case: str = "", scheme: str = "") -> Study:
    """The one convergence-study driver: evaluate each level, coarse to fine, then :func:`analyse`.

    Parameters
    ----------
    evaluate
        Maps a level (an ``n``, a mesh, a label) to ``(size, values, info)``:
        the level's discretisation parameter (``n`` or ``h``, as ``param``
        says), the quantities followed (scalars or arrays), and metadata; or
        to ``(size, values, info, errors)`` when the caller normalises the
        errors itself (as the verification run does, by its tolerance table's
        units).
    levels
        The levels, coarse to fine.
    param
        ``"n"`` (sizes are node counts) or the name of a size that falls (``"h"``).
    reference, scales
        Reference values and error scales (default 1) of the quantities; errors
        are ``max |value - reference| / scale``. Without a reference the study
        is reference-free.
    error_only, require_monotone
        See :func:`analyse`.
    skip
        Exception types that make a level a note instead of an error.
    progress
        Called after each level with its size, the level and its seconds.
    method, case, scheme
        What was studied, recorded as they are.

    Returns
    -------
    Study
    """
    if not isinstance(param, str) or not param:
        raise InputError(f"`param` = {param!r} must name the discretisation parameter")
    if len(levels) < 2:
        raise InputError(f"`levels` = {list(levels)!r} must hold at least two levels")
    study = Study(param, reference=dict(reference or {}), method=method, case=case, scheme=scheme)
    for level in levels:
        t0 = time.perf_counter()
        try:
            size, values, info, *own = evaluate(level)
        except skip as exc:
            study.notes.append(f"level {level}: {type(exc).__name__}: {exc}")
            continue
        dt = time.perf_counter() - t0
        study.labels.append(str(level))
        study.sizes.append(float(size))
        study.times.append(dt)
        study.info.append(dict(info))
        for q, v in values.items():
            study.values.setdefault(q, []).append(v)
        for q, e in (own[0] if own else {}).items():
            study.errors.setdefault(q, []).append(float(e))
        if progress:
            progress(float(size), level, dt)
    if reference is not None and not study.errors:
        for q in study.values:
            scale = float((scales or {}).get(q, 1.0))
            study.scales[q] = scale
            study.errors[q] = [_error(v, reference[q], scale) for v in study.values[q]]
    return analyse(study, error_only, require_monotone)

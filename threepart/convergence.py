"""The convergence tools every study uses: fitted order, three-level order, GCI and Richardson.

All take the discretisation as a size ``h`` that falls as the discretisation is
refined (a mesh size, or ``1/n`` for ``n`` nodes), so an order ``p > 0`` always
means convergence, ``error ~ C h^p``.

fitted_order        -- p and C from ``np.polyfit(log h, log err, 1)``, round-off levels dropped
three_level_order   -- p from three solutions, no reference needed (Celik et al. 2008)
gci                 -- Roache's relative fine-grid convergence index (Celik et al. 2008)
richardson          -- Richardson-extrapolated value from the two finest levels

Celik, Ghia, Roache, Freitas, Coleman & Raad, "Procedure for estimation and
reporting of uncertainty due to discretization in CFD applications",
J. Fluids Eng. 130 (2008) 078001.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["ROUND_OFF", "is_monotone", "converges_monotonically", "fitted_order", "three_level_order", "gci", "richardson"]

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

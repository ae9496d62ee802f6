"""Convergence studies: errors over a list of ``n``, the fitted order and a Richardson estimate."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["ConvergenceStudy", "convergence_study", "observed_order", "richardson"]


@dataclass(frozen=True)
class ConvergenceStudy:
    """Result of :func:`convergence_study`.

    Attributes
    ----------
    n
        The discretisation sizes.
    values
        The quantity at each ``n`` (scalars or arrays, stacked).
    errors
        ``max |value - reference| / scale`` at each ``n``.
    order
        Fitted order ``p`` of ``error ~ C n^-p``.
    constant
        Fitted ``C``.
    extrapolated
        Richardson estimate from the two largest ``n`` with order ``order``.
    """

    n: np.ndarray
    values: np.ndarray
    errors: np.ndarray
    order: float
    constant: float
    extrapolated: np.ndarray


def observed_order(n: ArrayLike, err: ArrayLike) -> tuple[float, float]:
    """Fit ``err = C n^-p`` by ``np.polyfit(log n, log err, 1)``; return ``(p, C)``.

    Zero errors (exact results) are left out; with fewer than two left the
    order is ``inf`` and ``C`` is 0.
    """
    n = np.asarray(n, dtype=float)
    err = np.asarray(err, dtype=float)
    keep = err > 0
    if keep.sum() < 2:
        return float("inf"), 0.0
    slope, icpt = np.polyfit(np.log(n[keep]), np.log(err[keep]), 1)
    return float(-slope), float(np.exp(icpt))


def richardson(n: ArrayLike, values: ArrayLike, order: float) -> np.ndarray:
    """Richardson extrapolation ``(n2^p v2 - n1^p v1)/(n2^p - n1^p)`` from the last two entries."""
    n = np.asarray(n, dtype=float)
    v = np.asarray(values, dtype=float)
    w1, w2 = n[-2] ** order, n[-1] ** order
    return (w2 * v[-1] - w1 * v[-2]) / (w2 - w1)


def convergence_study(quantity: Callable[[int], ArrayLike], ns: Sequence[int],
                      reference: ArrayLike, *, scale: float = 1.0) -> ConvergenceStudy:
    """Evaluate ``quantity(n)`` for each ``n`` and fit the order of its error.

    Parameters
    ----------
    quantity
        Maps ``n`` to a number or an array (e.g. pressure at fixed points).
    ns
        Increasing discretisation sizes, at least two.
    reference
        Exact or converged value(s) to measure against.
    scale
        Errors are divided by it (e.g. the peak pressure, or the load).
    """
    if len(ns) < 2:
        raise ValueError(f"`ns` = {list(ns)!r} must hold at least two sizes")
    ref = np.asarray(reference, dtype=float)
    vals = np.array([np.asarray(quantity(int(n)), dtype=float) for n in ns])
    errs = np.array([np.max(np.abs(v - ref)) / scale for v in vals])
    order, const = observed_order(ns, errs)
    extra = richardson(ns, vals, order if np.isfinite(order) else 1.0)
    return ConvergenceStudy(n=np.asarray(ns), values=vals, errors=errs, order=order,
                            constant=const, extrapolated=extra)

"""Convergence studies in ``n``: errors over a list of ``n``, the fitted order and a Richardson estimate.

The tools themselves (fitted order, Richardson step) are those of
:mod:`threepart.convergence`, with ``h = 1/n``.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from threepart.convergence import fitted_order, richardson

__all__ = ["ConvergenceStudy", "convergence_study"]


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
        Fitted order ``p`` of ``error ~ C n^-p`` (NaN when fewer than two
        errors lie above the round-off floor).
    constant
        Fitted ``C``.
    extrapolated
        Richardson estimate from the two largest ``n`` with order ``order``
        (with order 1 when no order could be fitted).
    """

    n: np.ndarray
    values: np.ndarray
    errors: np.ndarray
    order: float
    constant: float
    extrapolated: np.ndarray


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
    h = 1.0 / np.asarray(ns, dtype=float)
    order, const = fitted_order(h, errs)
    extra = richardson(h, vals, order if np.isfinite(order) else 1.0)
    return ConvergenceStudy(n=np.asarray(ns), values=vals, errors=errs, order=order,
                            constant=const, extrapolated=extra)

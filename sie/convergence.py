"""Convergence studies in ``n``: errors over a list of ``n``, the fitted order and a Richardson estimate.

A thin use of the one driver, :func:`threepart.convergence.run_study`, with
``h = 1/n``; its result is the one study shape, :class:`threepart.convergence.Study`,
whose single quantity is named ``"value"``.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

from numpy.typing import ArrayLike

from threepart.convergence import Study, run_study
from threepart.errors import InputError

__all__ = ["convergence_study"]


def convergence_study(quantity: Callable[[int], ArrayLike], ns: Sequence[int],
                      reference: ArrayLike, *, scale: float = 1.0) -> Study:
    """Evaluate ``quantity(n)`` for each ``n`` and fit the order of its error.

    Parameters
    ----------
    quantity
        Maps ``n`` to a number or an array (e.g. pressure at fixed points).
    ns
        Increasing discretisation sizes, at least two; both parities may be
        mixed to average an even-odd wobble (the order is fitted through it).
    reference
        Exact or converged value(s) to measure against.
    scale
        Errors are divided by it (e.g. the peak pressure, or the load).

    Returns
    -------
    Study
        ``orders["value"]``, ``constants["value"]``, ``errors["value"]`` (per
        ``n``), ``extrapolated["value"]`` (Richardson, from the two largest ``n``).
    """
    if len(ns) < 2:
        raise InputError(f"`ns` = {list(ns)!r} must hold at least two sizes")
    return run_study(lambda n: (int(n), {"value": quantity(int(n))}, {}), list(ns), param="n",
                     reference={"value": reference}, scales={"value": scale},
                     require_monotone=False)

"""Gauss–Legendre rules on ``[0, 1]``: the one home of the rule every quadrature of a loop or a zone uses.

gauss01  -- the ``n``-point rule's nodes in ``[0, 1]`` and weights (cached)
graded01 -- ``n``-point rules on panels of ``[0, 1]`` graded geometrically toward ``u = 0`` (the stresses')
"""
from __future__ import annotations

import functools

import numpy as np
import scipy.special

__all__ = ["gauss01", "graded01"]


@functools.lru_cache(maxsize=32)
def gauss01(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes in ``[0, 1]`` and weights of the ``n``-point Gauss–Legendre rule (exact to degree ``2n - 1``).

    scipy's roots are O(n); numpy's ``leggauss`` solves an n x n eigenproblem (100 s at n = 4096).
    The arrays are read-only, as they are shared by every caller.
    """
    t, w = scipy.special.roots_legendre(n)
    nodes, weights = 0.5 * (t + 1), 0.5 * w
    nodes.flags.writeable = weights.flags.writeable = False
    return nodes, weights


def graded01(n: int, ratio: float, levels: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ``u`` and weights on ``[0, 1]``: ``n``-point Gauss–Legendre panels ``[0, ratio**levels]``,
    ``[ratio**levels, ratio**(levels - 1)]``, ..., ``[ratio, 1]``, graded geometrically toward ``u = 0``.

    The rule of the stresses' remainder near each break point (:data:`threepart.stress.RULE`).
    """
    g, w = gauss01(n)
    edges = np.concatenate([[0.0], ratio ** np.arange(levels, -1, -1.0)])
    lo, hi = edges[:-1, None], edges[1:, None]
    return (lo + (hi - lo) * g).ravel(), ((hi - lo) * w).ravel()

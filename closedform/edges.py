"""The pressure's edge multipliers in closed form: the limits of eq. (pressure_abbreviated) at ``-a`` and ``c``.

At a distance ``r`` inside an edge the bounded pressure is ``p ≈ K_N √r``. With
``W = a + c`` and the join angles ``beta1``, ``beta2`` of eq. (f0)
(:func:`closedform.formulas.beta`), docs/EDGES.md (E1) derives

    K_N(-a) = √W [F0 + kappa1 sin(beta1) - kappa2 sin(beta2)] / (π A),
    K_N(c)  = √W [F0 + kappa2 sin(beta2) - kappa1 sin(beta1)] / (π A),

``F0`` of eq. (f0). For Hertz (``b = 0``, ``R1 = R2``) both are ``p0 √(2/a)``.

K_N       -- ``(K_N(-a), K_N(c))`` of a contact ``[-a, c]``, vectorised
edges     -- the registry's ``edges`` call: ``((K_N, None), (K_N, None))`` of a closed-form normal result
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from threepart.problem.punch import Punch
from threepart.results import NormalResult

from .formulas import F0, beta

__all__ = ["K_N", "edges"]


def K_N(punch: Punch, a: ArrayLike, c: ArrayLike, A: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """``(K_N(-a), K_N(c))``: the limits of ``p/√r`` of eq. (pressure_abbreviated) at the edges (E1).

    Parameters
    ----------
    punch
        The three-part punch (eq. 2).
    a, c
        The contact ``[-a, c]`` (both ends on the outer arcs, ``a, c >= b``).
    A
        Compliance (eq. 4).
    """
    a, c = np.asarray(a, float), np.asarray(c, float)
    b1, b2 = beta(a, c, punch.b)
    scale = np.sqrt(a + c) / (np.pi * np.asarray(A, float))
    base = F0(punch, a, c)
    odd = punch.kappa1 * np.sin(b1) - punch.kappa2 * np.sin(b2)
    return scale * (base + odd), scale * (base - odd)


def edges(normal: NormalResult) -> tuple[tuple[float, float | None], tuple[float, float | None]]:
    """``((K_N(-a), None), (K_N(c), None))`` of a closed-form normal result: exact, no fit error."""
    left, right = K_N(normal.punch, normal.a, normal.c, normal.A)
    return (float(left), None), (float(right), None)

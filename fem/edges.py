"""The pressure's edge multipliers of the FEM: a least-squares fit over its nodes near each edge.

Near an edge, ``p² = K_N² (r - r0) + O(r²)`` with ``r`` the distance inside the
FE contact's own end and ``r0`` that end's error, so ``K_N²`` is the slope at
its root of a polynomial fitted to ``p²`` (the end's error drops out, as in
:mod:`fem.ends`). The fit skips the edge node (its lumped pressure carries the
square-root edge inside one element) and stops short of the nearer join
``x = ±b`` (the pressure's ``(x ∓ b) ln|x ∓ b|``): at most :data:`JOIN_SHARE`
of the way to it. It is made on :data:`WINDOWS` nodes by polynomials of the
degrees :data:`DEGREES`; ``K_N`` is their median and its ``fit_error`` their
largest distance from it (docs/EDGES.md, E8).

K_N      -- ``((K_N, fit_error), (K_N, fit_error))`` at ``-a`` and ``c`` of nodal pressures
edges    -- the registry's ``edges`` call on an FE normal result
"""
from __future__ import annotations

import numpy as np

from threepart.errors import MeshResolutionError
from threepart.results import NormalResult

__all__ = ["K_N", "edges", "WINDOWS", "DEGREES", "JOIN_SHARE", "MIN_NODES"]

#: nodes after the edge node of each fit (the smaller windows resolve a short arc, the larger
#: average the nodal noise; their spread is the fit's error)
WINDOWS = (12, 18, 24, 32)
#: degrees of the polynomial in r fitted to p² (the second: K_N² r + the r² term; the third adds r³)
DEGREES = (2, 3)
#: share of the distance from the edge to the nearer join that a fit may span
JOIN_SHARE = 0.5
#: least nodes a fit needs (a third-degree fit and two to spare)
MIN_NODES = 6


def _one_edge(r: np.ndarray, p: np.ndarray, reach: float) -> tuple[float, float]:
    """``(K_N, fit_error)`` from nodal ``p`` at distances ``r`` inside one edge, fits within ``reach``."""
    keep = (r > 0) & (p > 0)
    order = np.argsort(r[keep])
    rs, ps = r[keep][order][1:], p[keep][order][1:]        # the edge node skipped
    rs, ps = rs[rs <= reach], ps[rs <= reach]
    if rs.size < MIN_NODES:
        raise MeshResolutionError(f"the FE mesh has {rs.size} nodes between the contact end and "
                                  f"{JOIN_SHARE:g} of the way to the join, fewer than the {MIN_NODES} "
                                  "the edge multiplier's fit needs: refine the mesh at the ends")
    Ks = []
    for n in WINDOWS:
        for deg in DEGREES:
            m = min(n, rs.size)
            coef = np.polyfit(rs[:m], ps[:m] ** 2, deg)
            root = -coef[-1] / coef[-2]
            slope = np.polyval(np.polyder(coef), root)
            if slope > 0:
                Ks.append(float(np.sqrt(slope)))
    K = float(np.median(Ks))
    return K, float(max(abs(k - K) for k in Ks))


def K_N(x: np.ndarray, p: np.ndarray, a: float, c: float, b: float
        ) -> tuple[tuple[float, float], tuple[float, float]]:
    """``((K_N, fit_error), (K_N, fit_error))`` at ``-a`` and ``c`` from nodal pressures ``p`` at ``x``.

    Raises
    ------
    MeshResolutionError
        If fewer than :data:`MIN_NODES` nodes lie between an edge and
        :data:`JOIN_SHARE` of the way to the nearer join.
    """
    W = a + c
    joins_left = [j for j in (-b, b) if -a < j < c]
    reach_l = JOIN_SHARE * (min(joins_left) + a) if joins_left else W
    reach_r = JOIN_SHARE * (c - max(joins_left)) if joins_left else W
    return _one_edge(x + a, p, reach_l), _one_edge(c - x, p, reach_r)


def edges(normal: NormalResult) -> tuple[tuple[float, float | None], tuple[float, float | None]]:
    """The fit of :func:`K_N` over an FE normal result's ``x_nodes``, ``p_nodes``."""
    x, p = getattr(normal, "x_nodes", None), getattr(normal, "p_nodes", None)
    if x is None or p is None or len(x) == 0:
        raise ValueError("`normal` has no FE nodal pressures to fit the edge multipliers to")
    left, right = K_N(np.asarray(x, float), np.asarray(p, float), normal.a, normal.c, normal.punch.b)
    return left, right

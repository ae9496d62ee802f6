"""Nodal pressures: the edge multipliers of a pressure known at nodes (an FE model's, another code's).

Near an edge, ``p² = K_N² (r - r0) + O(r²)`` with ``r`` the distance inside the
contact's own end and ``r0`` that end's error, so ``K_N²`` is the slope at
its root of a polynomial fitted to ``p²`` (the end's error drops out). The fit
skips the edge node (a lumped pressure carries the square-root edge inside one
element) and stops short of the nearer join ``x = ±b`` (the pressure's
``(x ∓ b) ln|x ∓ b|``): at most :data:`JOIN_SHARE` of the way to it. It is made
on :data:`WINDOWS` nodes by polynomials of the degrees :data:`DEGREES`; ``K_N``
is their median and its ``fit_error`` their largest distance from it
(docs/EDGES.md, E8). The FEM (:mod:`fem.edges`) and the referee of another
code's pressure (:mod:`reports.referee`) both use it.

edge_multipliers -- ``((K_N, fit_error), (K_N, fit_error))`` at ``-a`` and ``c`` of nodal pressures
"""
from __future__ import annotations

import numpy as np

from .errors import MeshResolutionError

__all__ = ["edge_multipliers", "WINDOWS", "DEGREES", "JOIN_SHARE", "MIN_NODES"]

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
    windows = sorted({min(n, rs.size) for n in WINDOWS})   # distinct: a short run of nodes is one
    fits = [(m, deg) for m in windows for deg in DEGREES]
    Ks = []
    for m, deg in fits:
        coef = np.polyfit(rs[:m], ps[:m] ** 2, deg)
        root = -coef[-1] / coef[-2]
        slope = np.polyval(np.polyder(coef), root)
        if slope > 0:
            Ks.append(float(np.sqrt(slope)))
    if len(Ks) < 2 or 2 * len(Ks) < len(fits):
        raise MeshResolutionError(f"only {len(Ks)} of the {len(fits)} fits of p² near the contact "
                                  "end rise into the contact: the nodal pressure does not resolve "
                                  "the square-root edge there")
    K = float(np.median(Ks))
    return K, float(max(abs(k - K) for k in Ks))


def edge_multipliers(x: np.ndarray, p: np.ndarray, a: float, c: float, b: float
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

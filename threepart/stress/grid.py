"""The stresses on a grid of points: one quadrature rule, one set of kernels per depth (issue 33).

Where the points of :func:`threepart.stress.stress` form a grid (the same ``x`` on
every row, one depth ``z`` per row), a row at depth ``z`` shares one rule in ``t``:
near each break point (the contact ends and kinks) a piece of length ``z/2``
mapped by ``t = B ± h u²`` (the tractions' square-root ends become smooth) and
graded as :data:`threepart.stress.RULE`'s shared intervals, and between them
Gauss–Legendre panels no longer than ``2z``, on which the kernels' poles at
``x ± i z`` lie far enough for :data:`GRID_NODES` nodes (their error decays like
``2.41^{-2n}``, 5e-16 at 20 nodes; measured against the pointwise rule, 1.1e-11
of the peak pressure on caseA_moment's 200 x 100 grid, the pointwise rule's own level). The four kernels of every point of the row are
then four matrix–vector products with the tractions' weighted values, built from
``1/r²``: no subtraction of the point's own value is needed at that depth.
Rows shallower than :data:`GRID_DEPTH` of the contact's width (the surface among
them) keep the pointwise rule, whose grading follows each point.

is_grid         -- ``(x_row, z_col)`` if broadcast points form a grid, else None
grid_integrals  -- the four kernels' integrals of each traction on one row
GRID_DEPTH      -- the least depth, as a fraction of the contact's width, of a row on this path
"""
from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from ..halfplane.legendre import gauss01, graded01

__all__ = ["is_grid", "grid_integrals", "GRID_DEPTH", "GRID_NODES", "GRID_PANEL"]

#: rows at depth ``z >= GRID_DEPTH W`` (``W`` the contact's width) take the grid path
GRID_DEPTH = 1.0 / 200
#: Gauss–Legendre nodes of each panel between the break points' end pieces
GRID_NODES = 20
#: the longest panel between the end pieces, in units of the depth ``z``
GRID_PANEL = 2.0
#: x-points per block of a row: a block's kernel matrices hold about 2e6 entries each
_ENTRIES = 2_000_000


def is_grid(xb: np.ndarray, zb: np.ndarray) -> tuple[np.ndarray, np.ndarray, list[slice]] | None:
    """``(x of a row, z of each row, each row's slice of the flattened points)`` if 2-d points form a grid.

    Rows of one depth may lie along either axis (``x`` of shape ``(1, nx)`` with
    ``z`` of ``(nz, 1)``, or the transpose); else None.
    """
    if xb.ndim != 2 or xb.shape[0] < 2 or xb.shape[1] < 2:
        return None
    n0, n1 = xb.shape
    if np.all(xb == xb[:1]) and np.all(zb == zb[:, :1]):
        return xb[0], zb[:, 0], [slice(j * n1, (j + 1) * n1) for j in range(n0)]
    if np.all(xb == xb[:, :1]) and np.all(zb == zb[:1]):
        return xb[:, 0], zb[0], [slice(j, None, n1) for j in range(n1)]
    return None


def _row_rule(z: float, F: np.ndarray, rule: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights in ``t`` of the row at depth ``z`` over the intervals between break points ``F``."""

    U, Wu = graded01(rule["n"], rule["ratio"], rule["min_levels"])
    g, w = gauss01(GRID_NODES)
    nodes, weights = [], []
    for A, B in zip(F[:-1], F[1:]):
        e = min(0.5 * z, 0.25 * (B - A))
        for E, h in ((A, e), (B, -e)):                   # t = E + h u^2, graded toward E
            nodes.append(E + h * U * U)
            weights.append(2.0 * e * U * Wu)
        m = max(1, math.ceil((B - A - 2 * e) / (GRID_PANEL * z)))
        edges = np.linspace(A + e, B - e, m + 1)
        lo, hi = edges[:-1, None], edges[1:, None]
        nodes.append((lo + (hi - lo) * g).ravel())
        weights.append(((hi - lo) * w).ravel())
    return np.concatenate(nodes), np.concatenate(weights)


def grid_integrals(x: np.ndarray, z: float, funcs: dict[str, Callable[[np.ndarray], np.ndarray]],
                   F: np.ndarray, rule: dict[str, Any],
                   evaluate: Callable[[str, Any, np.ndarray], np.ndarray]) -> dict[str, tuple[np.ndarray, ...]]:
    """``∫ w(t) K(x - t, z) dt`` for the four kernels of :func:`threepart.stress.flamant._kernels`, one row.

    With ``C = 1/r²``, ``A = C²``, ``s = x - t``: ``z s²/r⁴ = z (C - z² A)``,
    ``z³/r⁴ = z³ A``, ``z² s/r⁴ = z² s A`` and ``s³/r⁴ = s C - z² s A``, so that
    each row costs four matrix–vector products of ``C``, ``A``, ``sA`` and ``sC``.
    """
    t, wt = _row_rule(z, F, rule)
    values = {name: evaluate(name, func, t) * wt for name, func in funcs.items()}
    V = np.column_stack(list(values.values()))
    out = {name: tuple(np.empty(x.size) for _ in range(4)) for name in funcs}
    block = max(1, _ENTRIES // t.size)
    z2 = z * z
    for start in range(0, x.size, block):
        xb = x[start:start + block]
        s = xb[:, None] - t[None, :]
        C = 1.0 / (s * s + z2)
        A = C * C
        iC, iA = C @ V, A @ V
        sA, sC = (s * A) @ V, (s * C) @ V
        for j, name in enumerate(values):
            part = slice(start, start + xb.size)
            out[name][0][part] = z * (iC[:, j] - z2 * iA[:, j])
            out[name][1][part] = z * z2 * iA[:, j]
            out[name][2][part] = z2 * sA[:, j]
            out[name][3][part] = sC[:, j] - z2 * sA[:, j]
    return out

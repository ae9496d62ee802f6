"""The pressure's edge multipliers of the FEM: the nodal fit of :mod:`threepart.results.fields` (docs/EDGES.md, E8).

edges    -- the registry's ``edges`` call on an FE normal result
"""
from __future__ import annotations

import numpy as np

from threepart.results.fields import edge_multipliers
from threepart.results import NormalResult
from threepart.errors import InputError

__all__ = ["edges"]


def edges(normal: NormalResult) -> tuple[tuple[float, float | None], tuple[float, float | None]]:
    """The fit of :func:`threepart.results.fields.edge_multipliers` over an FE normal result's ``x_nodes``, ``p_nodes``."""
    x, p = getattr(normal, "x_nodes", None), getattr(normal, "p_nodes", None)
    if x is None or p is None or len(x) == 0:
        raise InputError("`normal` has no FE nodal pressures to fit the edge multipliers to")
    left, right = edge_multipliers(np.asarray(x, float), np.asarray(p, float), normal.a, normal.c, normal.punch.b)
    return left, right

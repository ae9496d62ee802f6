"""Coulomb friction on the interface: one load step's stick/slip states by a primal-dual active set.

In a load step the interface nodes in contact either stick (the relative
tangential displacement ``w_i`` of the punch keeps its value of the previous
step) or slip (``t_i = ±f fn_i`` with the sign of the slip increment). The
states are found by a primal-dual active-set iteration on the complementarity
function ``t_i = proj_[-f fn_i, f fn_i](t_i + c Δw_i)`` (Hüeber, Stadler &
Wohlmuth 2008), :func:`threepart.halfplane.coulomb.coulomb_state`, which the SIE's load
history shares. Notation as in :mod:`fem.friction`: ``fn`` the normal nodal
forces, ``t`` the shear nodal forces the punch drags the substrate with,
``f`` (here ``mu``) the coefficient of friction.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from threepart.halfplane.coulomb import coulomb_state

from .interface import Interface

__all__ = ["Step", "tangential", "reversal"]


@dataclass(frozen=True, eq=False)
class Step:
    """The interface after one load step.

    Attributes
    ----------
    Q, branch
        Shear force and branch (:data:`threepart.results.BRANCHES`).
    fn, t
        Normal and shear nodal forces (``fn``: ``f`` is the coefficient of friction).
    w
        Relative tangential displacement of the punch at the nodes.
    xi
        Tangential displacement of the loading plate.
    stick
        Nodes that did not slip in this step.
    direction
        Sign of the step's load increment (+1 or -1).
    iterations
        Active-set iterations of the tangential problem.
    residual
        Largest ``|t_i| - f fn_i`` left (<= 0: Coulomb's bound holds), relative to ``max f fn_i``.
    """

    Q: float
    branch: str
    fn: np.ndarray = field(repr=False)
    t: np.ndarray = field(repr=False)
    w: np.ndarray = field(repr=False)
    xi: float
    stick: np.ndarray = field(repr=False)
    direction: int
    iterations: int
    residual: float = 0.0


def tangential(itf: Interface, fn: np.ndarray, w_prev: np.ndarray, w_fixed: np.ndarray, Q: float,
               mu: float, stick0: np.ndarray, max_iter: int
               ) -> tuple[np.ndarray, float, np.ndarray, int, float]:
    """Shear forces, plate displacement and stick set of one load step (normal forces ``fn`` given).

    ``w = xi + w_fixed - C_tt t`` is the relative tangential displacement,
    with ``w_fixed`` its part that does not depend on the shear (the normal
    forces' coupling ``C_tn fn`` and the bulk strain of the substrate). Stick
    nodes keep ``w_prev``; slip nodes carry ``t_i = ±mu fn_i``; ``sum t = Q``.
    The active set is :func:`threepart.halfplane.coulomb.coulomb_state`'s, on ``C_tt``
    with the bounds ``mu fn``.

    Returns
    -------
    t, xi, stick, iterations, residual
        See :class:`Step`.

    Raises
    ------
    FullSlidingError
        If every node in contact slides.
    NoConvergenceError
        If the states do not settle within ``max_iter`` iterations or a shear
        exceeds Coulomb's bound after they settle.
    """
    return coulomb_state(itf.C_tt, mu * fn, w_prev, w_fixed, Q, stick0, max_iter)


def reversal(st: Step, branch: str, direction: int) -> Step:
    """The state ``st`` recorded again as the first of ``branch`` (a reversal point)."""
    return Step(Q=st.Q, branch=branch, fn=st.fn, t=st.t, w=st.w, xi=st.xi, stick=st.stick,
                direction=direction, iterations=0, residual=st.residual)

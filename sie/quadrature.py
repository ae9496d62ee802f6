"""Gauss–Chebyshev rules for solutions bounded at both ends (Erdogan, Gupta & Cook 1973).

On the normalised contact ``s ∈ [-1, 1]`` the compressive pressure is written
``p(s) = sqrt(1 - s^2) psi(s)`` with ``psi`` smooth. The rule

    ∫ sqrt(1 - σ^2) f(σ) dσ  ≈  Σ_i W_i f(σ_i),      σ_i = cos(iπ/(n+1)),
                                                    W_i = π/(n+1) sin^2(iπ/(n+1)),

is Gauss quadrature for the Chebyshev weight of the second kind (exact for
polynomials of degree ``2n - 1``). Evaluated at the ``n + 1`` zeros of
``T_{n+1}``,

    s_k = cos((2k - 1)π / (2(n+1))),   k = 1, ..., n + 1,

the same sum also gives the Cauchy principal value
``(1/π) PV ∫ sqrt(1-σ^2) psi(σ)/(σ - s_k) dσ`` exactly when ``psi`` is a
polynomial of degree ``n - 1`` (the finite Hilbert transform maps
``sqrt(1-σ^2) U_{k-1}`` to ``-T_k``). That gives ``n + 1`` collocation
equations for ``n`` unknowns; the extra one is the consistency condition.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.linalg

from threepart.problem.checks import integer

__all__ = ["GaussChebyshevRule", "gauss_chebyshev", "cauchy_matrix", "PlainFunctionals",
           "plain_functionals"]


@dataclass(frozen=True)
class GaussChebyshevRule:
    """Nodes, weights and collocation points of the bounded–bounded rule.

    Attributes
    ----------
    nodes
        ``σ_i = cos(iπ/(n+1))``, ``i = 1..n`` (zeros of ``U_n``), descending.
    weights
        ``W_i = π/(n+1) sin^2(iπ/(n+1))``; they sum to ``π/2``.
    collocation
        ``s_k = cos((2k-1)π/(2(n+1)))``, ``k = 1..n+1`` (zeros of ``T_{n+1}``).
    """

    n: int
    nodes: np.ndarray
    weights: np.ndarray
    collocation: np.ndarray

    @property
    def angles(self) -> np.ndarray:
        """``θ_i = iπ/(n+1)`` with ``σ_i = cos θ_i``."""
        return np.arange(1, self.n + 1) * np.pi / (self.n + 1)


#: the largest ``n`` (nodes or sine terms) a solve accepts: the projected scheme's cost and
#: memory grow with ``n`` (2**16 terms: ~0.01 s and a few MB per normal solve), the plain
#: scheme is capped lower (``sie.normal.MAX_PLAIN_N``); ``n = 10**9`` would not return
MAX_N = 2**16


def check_n(n: int) -> int:
    """``n`` as an ``int`` in ``[2, MAX_N]`` (:func:`threepart.problem.checks.integer`).

    A bool or a non-integer is a ``TypeError``; at least 2 terms carry the
    load and the centroid (``T_1``, ``T_2``).
    """
    return integer("n", n, 2, MAX_N)


def gauss_chebyshev(n: int) -> GaussChebyshevRule:
    """Gauss–Chebyshev rule of the second kind with its collocation points.

    Parameters
    ----------
    n
        Number of quadrature nodes, >= 2.

    Returns
    -------
    GaussChebyshevRule

    References
    ----------
    F. Erdogan, G. D. Gupta & T. S. Cook (1973), "Numerical solution of
    singular integral equations", in *Methods of Analysis and Solutions of
    Crack Problems*, eqs. for the case bounded at both ends.
    """
    n = check_n(n)
    theta = np.arange(1, n + 1) * np.pi / (n + 1)
    k = np.arange(1, n + 2)
    return GaussChebyshevRule(
        n=n,
        nodes=np.cos(theta),
        weights=np.pi / (n + 1) * np.sin(theta) ** 2,
        collocation=np.cos((2 * k - 1) * np.pi / (2 * (n + 1))),
    )


def cauchy_matrix(rule: GaussChebyshevRule) -> np.ndarray:
    """Discrete operator ``K`` of ``-(1/π) PV ∫ sqrt(1-σ^2) psi(σ)/(σ - s) dσ``.

    ``K[k, i] = -(1/π) W_i / (σ_i - s_k)``, shape ``(n + 1, n)``, so that
    ``K @ psi(nodes)`` gives the left-hand side of the normalised integral
    equation at the collocation points (the sign makes compressive pressure
    positive, as in :mod:`closedform.results`).
    """
    return -rule.weights[None, :] / (np.pi * (rule.nodes[None, :] - rule.collocation[:, None]))


@dataclass(frozen=True)
class PlainFunctionals:
    """Linear functionals of the plain collocation system, for one ``n``.

    With ``B = [K, -1]`` (the constant column carries the tilt) and the
    right-hand side ``g'(x_k)`` of the geometric slope at the collocation
    points, ``B [u; α] = g'(x_k)`` has the unique solution ``u = A psi``.
    The rows here map ``g'(x_k)`` straight to the three numbers the
    equilibrium and consistency equations need, scaled so that they are the
    discrete counterparts of the Chebyshev coefficients ``G_0, G_1, G_2`` of
    :func:`sie.projection.slope_coefficients`:

    ``G_0 = -α``, ``G_1 = (2/π) Σ W_i u_i``, ``G_2 = (4/π) Σ W_i σ_i u_i``.
    """

    rule: GaussChebyshevRule
    rows: np.ndarray  # (3, n + 1)
    lu: tuple[np.ndarray, np.ndarray]

    def solve(self, rhs: np.ndarray) -> tuple[np.ndarray, float]:
        """``u`` at the nodes and the consistent tilt ``α`` for slope values ``rhs``."""
        sol = scipy.linalg.lu_solve(self.lu, rhs)
        return sol[:-1], float(sol[-1])


@lru_cache(maxsize=16)
def plain_functionals(n: int) -> PlainFunctionals:
    """Factorise the plain collocation system once per ``n`` (cached)."""
    rule = gauss_chebyshev(n)
    B = np.hstack([cauchy_matrix(rule), -np.ones((n + 1, 1))])
    lu = scipy.linalg.lu_factor(B)
    sel = np.zeros((n + 1, 3))
    sel[-1, 0] = -1.0
    sel[:-1, 1] = 2.0 / np.pi * rule.weights
    sel[:-1, 2] = 4.0 / np.pi * rule.weights * rule.nodes
    rows = scipy.linalg.lu_solve(lu, sel, trans=1).T
    rows.setflags(write=False)
    return PlainFunctionals(rule=rule, rows=rows, lu=lu)

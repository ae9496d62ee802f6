"""The one tolerance table of the verification run.

Every figure that :mod:`reports.compare` computes is checked against exactly one
entry of :data:`TOLERANCES`, keyed by ``(comparison, quantity)``. The
comparison is ``"sie"`` (closed form against the Gauss–Chebyshev SIE solver),
``"fem-quick"``, ``"fem-default"`` or ``"fem-fine"`` (closed form against the
finite-element model on that mesh preset; ``threepart verify --quick`` uses the
quick mesh, the default run the default mesh and --full the fine one). Each entry carries a one-line reason.

How each quantity is normalised (all errors are dimensionless, >= 0):

==================  ===========================================================
quantity            error
==================  ===========================================================
a, c                ``|Δa| / W`` with ``W = a + c`` of the closed form
alpha               ``|Δα| / max(|α|, Δv')``, ``Δv' = v'(c) - v'(-a)`` at α = 0,
                    the slope scale of the punch over the contact
P                   ``|ΔP| / P``
s                   ``|Δs| / W``
p_left, p_right     ``|Δp_peak| / p_max`` (both peaks, left and right of x = 0)
x_left, x_right     ``|Δx_peak| / W``
p_interior_max      ``max |Δp| / p_max`` over the contact less 5 % of W at each end,
                    at the FEM's nodes for the FEM, else at 4001 uniform points
p_L2                ``||Δp||_2 / ||p||_2`` over the whole contact
d, e                ``|Δd| / d``, ``|Δe| / d`` (stick zone, partial slip only)
q_interior_max      ``max |Δq| / max|q|`` over the contact less 5 % of W at each end
q_L2                ``||Δq||_2 / ||q||_2`` over the whole contact
==================  ===========================================================
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Tolerance", "TOLERANCES", "COMPARISONS", "QUANTITIES", "tolerance", "fem_comparison"]


@dataclass(frozen=True)
class Tolerance:
    """Upper limit of one normalised error, with the reason for its value."""

    limit: float
    reason: str


#: quantities compared for every normal result, in report order
NORMAL_QUANTITIES = ("a", "c", "alpha", "P", "s", "p_left", "x_left", "p_right", "x_right",
                     "p_interior_max", "p_L2")
#: quantities compared in addition for a partial-slip result (SIE only: the FEM is frictionless)
SLIP_QUANTITIES = ("d", "e", "q_interior_max", "q_L2")
QUANTITIES = NORMAL_QUANTITIES + SLIP_QUANTITIES
COMPARISONS = ("sie", "fem-quick", "fem-default", "fem-fine")

_T = Tolerance
#: the tolerance table: ``(comparison, quantity) -> Tolerance``
TOLERANCES: dict[tuple[str, str], Tolerance] = {
    # --- closed form vs SIE (Gauss–Chebyshev; issue 3 targets) -------------------------
    ("sie", "a"): _T(1e-10, "SIE target: a, c to 1e-10 (measured ~1e-15 W with the projected scheme)"),
    ("sie", "c"): _T(1e-10, "as a: both ends come from the same Newton solve"),
    ("sie", "alpha"): _T(1e-10, "SIE target 1e-10 rel.; α comes from the same Newton solve as a, c"),
    ("sie", "P"): _T(1e-12, "load control: P is imposed, only quadrature round-off remains"),
    ("sie", "s"): _T(1e-10, "SIE target: s is imposed (free tilt) or the quadrature centroid (suppressed)"),
    ("sie", "p_left"): _T(1e-6, "SIE field target: max |Δp| ≤ 1e-6 of the peak over the contact"),
    ("sie", "p_right"): _T(1e-6, "as p_left"),
    ("sie", "x_left"): _T(1e-4, "peak position: flat maximum, Δx ~ sqrt(Δp/p'') so ~1e-3·sqrt of p error"),
    ("sie", "x_right"): _T(1e-4, "as x_left"),
    ("sie", "p_interior_max"): _T(1e-6, "SIE field target 1e-6 of the peak (kink-aware variant)"),
    ("sie", "p_L2"): _T(1e-6, "L2 is dominated by the same interior error as the max"),
    ("sie", "d"): _T(1e-8, "SIE stick-zone target: d and e to 1e-8 relative"),
    ("sie", "e"): _T(1e-8, "as d, relative to d since e = 0 for symmetric contacts"),
    ("sie", "q_interior_max"): _T(1e-6, "shear is f·p minus a corrective pressure: same field target as p"),
    ("sie", "q_L2"): _T(1e-6, "as q_interior_max"),
    # --- closed form vs FEM, default mesh (issue 4 targets) ----------------------------
    ("fem-default", "a"): _T(1e-4, "FEM target a, c within 1e-4 W (default preset h = W/600)"),
    ("fem-default", "c"): _T(1e-4, "as a"),
    ("fem-default", "alpha"): _T(1e-4, "FEM target 1e-4 rel.; α is the most far-field sensitive figure"),
    ("fem-default", "P"): _T(1e-6, "load control: P is imposed through the rigid-punch equilibrium"),
    ("fem-default", "s"): _T(1e-4, "s is imposed (free) or the FEM pressure centroid (suppressed), ~a, c error"),
    ("fem-default", "p_left"): _T(1e-3, "FEM target: each peak pressure within 1e-3"),
    ("fem-default", "p_right"): _T(1e-3, "as p_left"),
    ("fem-default", "x_left"): _T(5e-3, "peaks are flat and sampled at nodes: about one element (h = W/600)"),
    ("fem-default", "x_right"): _T(5e-3, "as x_left"),
    ("fem-default", "p_interior_max"): _T(1e-3, "FEM target: interior pressure within 1e-3 of the peak"),
    ("fem-default", "p_L2"): _T(1e-2, "includes the sqrt edges, ~1 % at the single edge node"),
    # --- closed form vs FEM, fine mesh (the default verification run; issue 4 targets) ---
    ("fem-fine", "a"): _T(1e-4, "FEM target a, c within 1e-4 W; measured <= 8.3e-5 W on the fine preset"),
    ("fem-fine", "c"): _T(1e-4, "as a"),
    ("fem-fine", "alpha"): _T(1e-4, "FEM target 1e-4 rel.; α is the most far-field sensitive figure"),
    ("fem-fine", "P"): _T(1e-6, "load control: P is imposed through the rigid-punch equilibrium"),
    ("fem-fine", "s"): _T(1e-4, "s is imposed (free) or the FEM pressure centroid (suppressed), ~a, c error"),
    ("fem-fine", "p_left"): _T(1e-3, "FEM target: each peak pressure within 1e-3"),
    ("fem-fine", "p_right"): _T(1e-3, "as p_left"),
    ("fem-fine", "x_left"): _T(5e-3, "peaks are flat and sampled at nodes: a few elements (h = W/900)"),
    ("fem-fine", "x_right"): _T(5e-3, "as x_left"),
    ("fem-fine", "p_interior_max"): _T(1e-3, "FEM target: interior pressure (at the nodes) within 1e-3 of the peak"),
    ("fem-fine", "p_L2"): _T(1e-2, "includes the sqrt edges, ~1 % at the single edge node"),
    # --- closed form vs FEM, quick (CI) mesh -------------------------------------------
    ("fem-quick", "a"): _T(5e-3, "quick mesh h = W/60: end located to ~0.2 h (3e-3 W measured near lift-off)"),
    ("fem-quick", "c"): _T(5e-3, "as a"),
    ("fem-quick", "alpha"): _T(2e-3, "small domain and coarse grading on the quick mesh: far-field error in α"),
    ("fem-quick", "P"): _T(1e-6, "load control: P is imposed"),
    ("fem-quick", "s"): _T(1e-3, "imposed (free) or centroid of a coarse pressure (suppressed)"),
    ("fem-quick", "p_left"): _T(1e-2, "coarse mesh resolves the peaks to about 1 %"),
    ("fem-quick", "p_right"): _T(1e-2, "as p_left"),
    ("fem-quick", "x_left"): _T(2e-2, "peak position to about one quick-mesh element"),
    ("fem-quick", "x_right"): _T(2e-2, "as x_left"),
    ("fem-quick", "p_interior_max"): _T(1e-2, "coarse mesh: interior pressure within 1 % of the peak"),
    ("fem-quick", "p_L2"): _T(3e-2, "includes the poorly resolved sqrt edges"),
}


def tolerance(comparison: str, quantity: str) -> Tolerance:
    """The table entry for ``(comparison, quantity)``; ``KeyError`` names both if missing."""
    try:
        return TOLERANCES[comparison, quantity]
    except KeyError:
        raise KeyError(f"no tolerance for comparison {comparison!r}, quantity {quantity!r}") from None


def fem_comparison(mesh: object) -> str:
    """Name of the FEM comparison for a mesh preset: ``"fem-quick"``, ``"fem-default"`` or ``"fem-fine"``.

    Any other mesh argument is judged as the default preset.
    """
    return f"fem-{mesh}" if mesh in ("quick", "default", "fine") else "fem-default"

"""Material compliance ``A`` of eq. (4), plane strain, and the material defaults.

compliance   -- A of two bodies (eq. 4)
similar_pair -- A of two bodies of one material, 4 (1 - nu^2)/E
rigid_punch  -- A of a rigid punch on an elastic half-plane, 2 (1 - nu^2)/E
NU           -- Poisson's ratio by default, 0.3
E_STEEL      -- Young's modulus of steel, 210 GPa, in MPa
"""
from __future__ import annotations

from .checks import finite, positive
from threepart.errors import InputError

__all__ = ["compliance", "rigid_punch", "similar_pair", "similar_pair_modulus", "NU", "E_STEEL"]

#: Poisson's ratio by default: what ``stress()`` assumes for a half-plane result (closed form,
#: SIE), which knows only the compliance ``A``, and what the FE models take when only ``A`` is given
NU = 0.3
#: Young's modulus of steel (MPa), as in the paper's examples: the studies' and figures' material
E_STEEL = 210_000.0


def _body(E: float, nu: float, name: str) -> float:
    """``(kappa + 1)/(4 mu) = 2 (1 - nu^2)/E`` with ``kappa = 3 - 4 nu`` (plane strain)."""
    E = positive(f"E{name}", E)
    nu = finite(f"nu{name}", nu)
    if not -1.0 < nu <= 0.5:
        raise InputError(f"`nu{name}` = {nu!r} must lie in (-1, 0.5]")
    kappa, mu = 3 - 4 * nu, E / (2 * (1 + nu))
    return (kappa + 1) / (4 * mu)


def compliance(E1: float, nu1: float, E2: float | None = None, nu2: float | None = None) -> float:
    """Compliance ``A = (kappa1+1)/(4 mu1) + (kappa2+1)/(4 mu2)`` (eq. 4).

    With only ``E1, nu1`` the two bodies are the same material
    (``A = 4 (1 - nu^2)/E``).
    """
    if (E2 is None) != (nu2 is None):
        raise InputError("give both `E2` and `nu2`, or neither (same material)")
    if E2 is None or nu2 is None:
        E2, nu2 = E1, nu1
    return _body(E1, nu1, "1") + _body(E2, nu2, "2")


def similar_pair(E: float, nu: float) -> float:
    """Two bodies of the same material: ``A = 4 (1 - nu^2)/E``."""
    return 2 * _body(E, nu, "")


def similar_pair_modulus(A: float, nu: float) -> float:
    """The modulus ``E = 4 (1 - nu^2)/A`` of two similar bodies of compliance ``A`` (inverse of
    :func:`similar_pair`)."""
    return 4.0 * (1.0 - nu * nu) / A


def rigid_punch(E: float, nu: float) -> float:
    """Rigid punch on an elastic half-plane: ``A = 2 (1 - nu^2)/E``."""
    return _body(E, nu, "")

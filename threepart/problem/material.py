"""Material compliance ``A`` of eq. (4), plane strain, the one material convention, and the defaults.

The convention (issue 37): a material ``(E, nu)``, wherever it is taken (the
catalogue, the command line's ``--E --nu``, :func:`material_compliance`), is the
material of BOTH bodies, two similar elastic bodies, ``A = 4 (1 - nu^2)/E``
(:func:`similar_pair`; Dundurs' ``beta = 0``, so the paper's solution is exact
with friction too). A rigid punch on an elastic half-plane, ``A = 2 (1 - nu^2)/E``
(:func:`rigid_punch`), is taken only where it is named (``bodies="rigid punch"``,
a case's ``"bodies"``, the command line's ``--rigid``). ``E`` is in MPa there,
inside :data:`E_RANGE` (:func:`modulus`); in other units, or nondimensionally,
give the compliance ``A`` itself. The formulas below are unit-agnostic.

compliance          -- A of two bodies (eq. 4)
similar_pair        -- A of two bodies of one material, 4 (1 - nu^2)/E
rigid_punch         -- A of a rigid punch on an elastic half-plane, 2 (1 - nu^2)/E
material_compliance -- A of a material (E in MPa, checked) and its bodies: the one convention
BODIES              -- the bodies a material may mean: "similar pair" (default), "rigid punch"
modulus, E_RANGE    -- a Young's modulus in MPa inside the moduli of engineering solids
similar_pair_modulus -- E of two similar bodies of compliance A, 4 (1 - nu^2)/A
rigid_punch_modulus -- E of the block under a rigid punch of compliance A, 2 (1 - nu^2)/A: the FE
                       and CalculiX normal models' block (E/2 for two similar bodies of E)
block_modulus       -- the same block from a material (E, bodies): E/2 (similar pair) or E (rigid punch)
NU           -- Poisson's ratio by default, 0.3
E_STEEL      -- Young's modulus of steel, 210 GPa, in MPa
"""
from __future__ import annotations

from .checks import finite, positive
from .units import E_RANGE   # re-exported: the moduli a material in MPa may give (its home, with why)
from threepart.errors import InputError

__all__ = ["compliance", "rigid_punch", "similar_pair", "similar_pair_modulus", "rigid_punch_modulus",
           "material_compliance", "block_modulus", "modulus", "BODIES", "E_RANGE", "NU", "E_STEEL"]

#: Poisson's ratio by default: what ``stress()`` assumes for a half-plane result (closed form,
#: SIE), which knows only the compliance ``A``, and what the FE models take when only ``A`` is given
NU = 0.3
#: Young's modulus of steel (MPa), as in the paper's examples: the studies' and figures' material
E_STEEL = 210_000.0
#: the bodies a material ``(E, nu)`` may mean: two similar bodies (the convention), or a rigid
#: punch on an elastic half-plane of that material (named where meant)
BODIES = ("similar pair", "rigid punch")


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


def rigid_punch_modulus(A: float, nu: float) -> float:
    """The modulus ``E = 2 (1 - nu^2)/A`` of the elastic block on which a rigid punch has compliance
    ``A`` (inverse of :func:`rigid_punch`).

    The one mapping of the FE and CalculiX normal models (a rigid or stiff punch on a block) onto a
    problem's ``A``: for two similar bodies of modulus ``E`` it gives ``E/2`` with the same ``nu``,
    exact in half-plane theory (Dundurs' ``beta = 0`` for similar bodies, and the frictionless rigid
    punch has no shear; the substrate's stresses depend on the tractions only).
    """
    E = 2.0 * (1.0 - nu * nu) / positive("A", A)
    return positive("E", E)


def block_modulus(E: float, bodies: str = "similar pair") -> float:
    """The modulus of the FE or CalculiX normal model's block under its rigid punch for a material
    ``(E, nu)`` and its ``bodies``: ``E/2`` for two similar bodies of ``E``, ``E`` for a rigid punch on
    a half-plane of ``E`` (the same ``nu``). Exactly :func:`rigid_punch_modulus` of
    :func:`material_compliance`, without its rounding: ``rigid_punch(E/2, nu) == similar_pair(E, nu)``.
    """
    if bodies not in BODIES:
        raise InputError(f"`bodies` = {bodies!r} must be one of {BODIES}")
    return 0.5 * E if bodies == "similar pair" else E


def modulus(E: float, name: str = "E") -> float:
    """``E`` (MPa) as a float inside :data:`E_RANGE`, else ``InputError`` naming ``name``, the range and
    the likely unit slip (Pa or GPa given for MPa)."""
    E = positive(name, E)
    lo, hi = E_RANGE
    if not lo <= E <= hi:
        unit = "Pa or kPa" if E > hi else "GPa"
        raise InputError(f"`{name}` = {E:g} MPa lies outside [{lo:g}, {hi:g}] MPa, the moduli of "
                         f"engineering solids: is it in {unit} (steel: 210000 MPa)? For other units "
                         "or a nondimensional problem give the compliance `A` itself")
    return E


def material_compliance(E: float, nu: float, bodies: str = "similar pair") -> float:
    """The compliance ``A`` (eq. 4) of a material ``(E, nu)``: the one material convention.

    Parameters
    ----------
    E
        Young's modulus in MPa, inside :data:`E_RANGE` (:func:`modulus`).
    nu
        Poisson's ratio.
    bodies
        ``"similar pair"`` (default): ``(E, nu)`` is the material of both bodies,
        ``A = 4 (1 - nu^2)/E``; ``"rigid punch"``: a rigid punch on a half-plane of
        that material, ``A = 2 (1 - nu^2)/E``.
    """
    if bodies not in BODIES:
        raise InputError(f"`bodies` = {bodies!r} must be one of {BODIES}")
    E = modulus(E)
    return similar_pair(E, nu) if bodies == "similar pair" else rigid_punch(E, nu)

"""The unit of each quantity the command line and the report print, by its key.

The library is unit-agnostic; these are the labels of one consistent set (mm, N/mm, MPa).
"""
from __future__ import annotations

__all__ = ["UNITS", "E_RANGE"]

#: the unit printed with each quantity, by its key in the output ("1": dimensionless)
UNITS: dict[str, str] = {
    "R1": "mm", "R2": "mm", "b": "mm", "R": "mm",     # punch geometry
    "A": "1/MPa", "E": "MPa",                         # compliance, eq. (4); modulus
    "P": "N/mm", "Q": "N/mm",                         # loads per unit length
    "s": "mm", "s_min": "mm", "s_max": "mm",          # lever arms
    "a": "mm", "c": "mm", "x": "mm",                  # contact edges, peak positions
    "d": "mm", "e": "mm", "left": "mm", "right": "mm",  # stick zone
    "alpha": "rad",                                   # tilt, eq. (2)
    "p": "MPa", "q": "MPa",                           # pressure, shear traction
    "sigma_bulk": "MPa",                              # bulk stress in the substrate, tension > 0
    "f": "1", "nu": "1",                              # friction coefficient, Poisson's ratio
    "slope": "rad",                                   # Punch.max_slope: tilt, profile, surface
    "K_N": "MPa/√mm", "fit_error": "MPa/√mm",         # edge asymptotics: p ≈ K_N √r (docs/EDGES.md)
    "K_T": "MPa·√mm", "K_sigma": "MPa·√mm",           # stuck shear q ≈ K_T/√r, the bulk stress's share
    "slip_zone": "mm",                                # asymptotic slip zone at an edge
}

#: Young's moduli of engineering solids (MPa), the range a material ``(E, nu)`` may give
#: (:func:`threepart.problem.material.modulus`, every command's ``--E``, the catalogue): a value outside is
#: a unit slip. Low, 1 GPa: above every structural metal's and ceramic's modulus written in GPa
#: (Mg 45 ... steel 210 ... WC 700 GPa), so that ``E = 210`` (steel in GPa) is refused, yet below
#: the engineering polymers (PP 1.5, epoxy 3, nylon 2-4, PEEK 3.6 GPa); softer solids (PE, PTFE,
#: elastomers) give the compliance ``A`` itself. High, 1.5 TPa: above diamond (1.05-1.2 TPa), the
#: stiffest solid, so that steel in Pa (2.1e11) or kPa (2.1e8) is refused.
E_RANGE = (1.0e3, 1.5e6)

"""Input checks of the FE entry points, built from :mod:`threepart.problem.validate`.

Each public FE call validates all of its input here, before any numerics or
meshing, in the style of SciPy's ``_*_iv`` helpers: a wrong type is a
``TypeError``, a value out of range a ``ValueError`` whose message names the
argument and the limit. What is FE-specific lives here (the material, the
physical load scale, the mesh argument and the bounds on counts and sizes);
the rest is :mod:`threepart.problem.validate`'s.

Bounds
------
MAX_ITER        -- active-set iterations, ``[1, 10000]``
STEPS           -- load steps of a partial-slip solve
MAX_FE_STATES   -- states per fretting branch (each a contact solve)
H_FACTOR        -- a finite punch's height ``H`` is at most this many footprints ``b + max(R1, R2)``
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from threepart.problem.material import rigid_punch, similar_pair
from threepart.problem.punch import Punch
from threepart.problem.checks import check_tilt, finite, integer, poisson, positive
from threepart.problem.validate import check_punch, lever_arm, load_scale
from threepart.errors import InputError, InputTypeError
from threepart.halfplane.surface import MAX_ITER

__all__ = ["FE_LENGTH_RANGE", "MAX_ITER", "STEPS", "MAX_FE_STATES", "H_FACTOR", "material", "load",
           "mesh_arg", "normal_iv", "height_iv"]

#: active-set iterations (each is one dense solve on the active set)
#: equal load steps of ``Q`` in :func:`fem.solve_partial_slip` (each costs one contact solve)
STEPS = (1, 1000)
#: the most states per branch of :func:`fem.fretting_cycle` (each costs a contact solve)
MAX_FE_STATES = 1000
#: The contact's length scale ``b + sqrt(A P max(R1, R2))`` that gmsh meshes faithfully:
#: gmsh's absolute tolerances move the answer (by 6e-4 in ``c`` at 1e-10, measured with the
#: same problem scaled by powers of ten) or fail it (1e-20), and past 1e20 it answers wrongly
#: (3 % off at 1e30). The FE answer is scale-free in between (1e-6 relative at 1e-8).
FE_LENGTH_RANGE = (1e-6, 1e18)
#: ``H`` at most ``H_FACTOR (b + max(R1, R2))``: taller punches mesh ever larger bodies
#: for no change in the contact, and gmsh loses its coordinates past double precision
H_FACTOR = 1000.0


def material(E: Any, nu: Any) -> tuple[float, float]:
    """``(E, nu)`` as floats; ``nu`` is checked first (``E`` is often derived from it)."""
    nu = poisson(nu)
    return positive("E", E), nu


def load(punch: Punch, P: Any, A: float) -> float:
    """``P`` as a float, > 0, with the contact scale ``A P max(R1, R2, b)`` representable.

    The same check as the closed form's (``closedform/normal.py``): the
    contact's length scale ``sqrt(2 A P R)`` and its powers must stay finite
    and nonzero in double precision. The mesh then needs the length scale
    ``b + sqrt(A P max(R1, R2))`` inside :data:`FE_LENGTH_RANGE`.
    """
    P = positive("P", P)
    load_scale(punch, P, A)
    ell = punch.b + math.sqrt(A * P * max(punch.R1, punch.R2, punch.b))
    lo, hi = FE_LENGTH_RANGE
    if not lo <= ell <= hi:
        raise InputError(f"`P` = {P!r} gives the contact's length scale b + sqrt(A P max(R1, R2)) "
                         f"= {ell:.3g}, outside [{lo:g}, {hi:g}], where gmsh meshes it faithfully; "
                         "give the lengths in other units")
    return P


def mesh_arg(mesh: Any, kinds: tuple[type, ...], allow_path: bool = True) -> Any:
    """The ``mesh`` argument, checked: a preset name, a ``.msh`` path or one of ``kinds``.

    A preset name becomes its :class:`~fem.mesh.MeshPreset`; a path must be an
    existing file. Anything else is a ``TypeError`` (wrong kind) or a
    ``ValueError`` (an unknown name, a missing file).
    """
    from .mesh import PRESETS, preset

    if isinstance(mesh, str) and not (allow_path and mesh.endswith(".msh")):
        return preset(mesh)
    if allow_path and isinstance(mesh, (str, Path)):
        if not Path(mesh).is_file():
            raise InputError(f"`mesh` = {str(mesh)!r} is not a file")
        return Path(mesh)
    if isinstance(mesh, kinds):
        return mesh
    names = ", ".join(k.__name__ for k in kinds)
    raise InputTypeError(f"`mesh` must be a preset name {sorted(PRESETS)}"
                    + (", a .msh path" if allow_path else "") + f" or a {names}, "
                    f"not {type(mesh).__name__}")


def normal_iv(punch: Any, P: Any, s: Any, E: Any, nu: Any, tilt: Any, max_iter: Any,
              pair: bool) -> tuple[float, float, float, float, str, int]:
    """The checked ``(P, s, E, nu, tilt, max_iter)`` of a normal FE problem.

    ``pair``: two similar bodies (``A = 4 (1 - nu^2) / E``), else a rigid punch
    (``A = 2 (1 - nu^2) / E``).
    """
    check_punch(punch)
    E, nu = material(E, nu)
    A = (similar_pair if pair else rigid_punch)(E, nu)
    P = load(punch, P, A)
    s = lever_arm(punch, s)
    tilt = check_tilt(tilt)
    max_iter = integer("max_iter", max_iter, *MAX_ITER)
    return P, s, E, nu, tilt, max_iter


def height_iv(punch: Punch, H: Any, theta: Any, profile: Any) -> tuple[float | None, float, str]:
    """``(H, theta, profile)`` of :func:`fem.solve_finite`, checked."""
    from threepart.meshes.punch import PROFILES

    if H is not None:
        H = positive("H", H)
        top = H_FACTOR * (punch.b + max(punch.R1, punch.R2))
        if H > top:   # bounded: a finite mesh in a finite time
            raise InputError(f"`H` = {H!r} exceeds {H_FACTOR:g} (b + max(R1, R2)) = {top:g}: a "
                             "taller punch changes nothing in the contact but grows the mesh")
    theta = finite("theta", theta)
    if not 0 < theta < math.pi / 2:
        raise InputError(f"`theta` = {theta!r} must lie in (0, pi/2)")
    if not isinstance(profile, str) or profile not in PROFILES:
        raise InputError(f"`profile` = {profile!r} must be one of {PROFILES}")
    return H, theta, profile

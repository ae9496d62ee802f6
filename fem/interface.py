"""The two bodies of the friction model seen from their matched interface nodes.

The punch body is the substrate's mirror image about the interface ``y = 0``
(:func:`mirror`); both are condensed onto their interface nodes, both
displacement components (:func:`fem.elasticity.condense`), and their
flexibilities are summed into the blocks of :class:`Interface`. The bulk
stress enters through :func:`bulk_field`: the substrate's displacement under a
unit tension on its end faces.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as sla
from skfem import FacetBasis, LinearForm, asm
from skfem import condense as dirichlet
from skfem.models.elasticity import lame_parameters
from skfem import MeshTri
from threepart.threads import one_blas_thread

from ._boundary import boundary
from .elasticity import SurfaceCompliance, condense, stiffness
from .mesh import Substrate
from threepart.errors import InputError, InputTypeError

__all__ = ["Interface", "interface", "mirror", "check_matched", "bulk_field"]


def mirror(sub: Substrate) -> Substrate:
    """The mirror image of ``sub`` about ``y = 0``, with the same named boundary groups.

    The triangles' orientation is restored (two vertices swapped); the groups
    are carried over by their vertex pairs, so the image's ``"contact"`` nodes
    are the original's, node for node.
    """
    if not isinstance(sub, Substrate):
        raise InputTypeError(f"`sub` must be a fem.Substrate, not {type(sub).__name__}")
    m = sub.mesh
    image = MeshTri(np.ascontiguousarray(m.p * np.array([[1.0], [-1.0]])),
                    np.ascontiguousarray(m.t[[0, 2, 1]]))
    nv = m.p.shape[1]

    def keys(mesh: MeshTri) -> np.ndarray:
        pairs = np.sort(mesh.facets, axis=0).astype(np.int64)
        return pairs[0] * nv + pairs[1]

    new_keys = keys(image)
    order = np.argsort(new_keys)
    old_keys = keys(m)
    groups = {name: np.sort(order[np.searchsorted(new_keys, old_keys[facets], sorter=order)])
              for name, facets in sub.boundaries.items()}
    return Substrate(mesh=image, boundaries=groups, path=sub.path + " (mirrored)")


def check_matched(x_lower: np.ndarray, x_upper: np.ndarray, what: str) -> None:
    """Refuse two bodies whose interface nodes do not pair node by node.

    The one check of :func:`interface` and :func:`fem.solve_finite`: the same
    count and the same positions to ``1e-9`` of the zone's length.

    Raises
    ------
    ValueError
        Naming ``what`` (the two bodies) and the first mismatch.
    """
    if len(x_lower) != len(x_upper):
        raise InputError(f"{what}: interface nodes do not match ({len(x_lower)} against "
                         f"{len(x_upper)} nodes)")
    gap = np.abs(np.asarray(x_lower) - np.asarray(x_upper))
    if gap.max(initial=0.0) > 1e-9 * np.ptp(x_lower):
        raise InputError(f"{what}: interface nodes do not match (by {gap.max():.3g} at "
                         f"x = {x_lower[int(np.argmax(gap))]:.6g})")


@dataclass(frozen=True, eq=False)
class Interface:
    """The two bodies seen from their matched interface nodes.

    Attributes
    ----------
    x, weights
        Node positions (increasing) and lumped weights ``w_i = ∫ phi_i ds``.
    C_nn, C_nt, C_tn, C_tt
        Blocks of the interface flexibility (:mod:`fem.friction`).
    h, dofs
        Largest element size on the interface and DOFs of both bodies.
    timings
        Seconds spent assembling and factorising both bodies.
    backend
        The sparse factorisation that condensed them (:func:`fem.choose_backend`).
    substrate
        The substrate's own condensation, whose factor recovers its displacement field.
    """

    x: np.ndarray
    weights: np.ndarray
    C_nn: np.ndarray
    C_nt: np.ndarray
    C_tn: np.ndarray
    C_tt: np.ndarray
    h: float
    dofs: int
    timings: dict[str, float]
    backend: str = "scipy"
    substrate: SurfaceCompliance | None = None


@boundary
def interface(lower: Substrate, upper: Substrate | None, E: float, nu: float) -> Interface:
    """Condense both bodies onto their interface and combine their flexibilities.

    ``lower`` is the substrate (below ``y = 0``), ``upper`` the punch body above
    it; ``None`` stands for ``lower``'s mirror image (:func:`mirror`), whose
    flexibility is ``lower``'s reflected, ``G' = R G R`` with ``R = diag(1, -1)``
    on the ``(u_x, u_y)`` blocks: the same blocks, the coupling ones negated.
    That halves the cost and is what condensing the mirrored mesh gives, to
    round-off (tests/test_fem_friction.py checks it).

    Raises
    ------
    ValueError
        If the two bodies' interface nodes do not match (:func:`check_matched`).
    """
    if upper is not None and not isinstance(upper, Substrate):
        raise InputTypeError(f"`upper` must be a fem.Substrate or None, not {type(upper).__name__}")
    S = condense(lower, E, nu, ("u^1", "u^2"))
    B = S if upper is None else condense(upper, E, nu, ("u^1", "u^2"))
    check_matched(S.x, B.x, "the substrate and the punch body (use `mirror`)")
    n = len(S.x)

    def blocks(sc: SurfaceCompliance, sign: float) -> tuple[np.ndarray, ...]:
        C = sc.C
        return C[:n, :n], sign * C[:n, n:], sign * C[n:, :n], C[n:, n:]

    Sxx, Sxy, Syx, Syy = blocks(S, 1.0)
    Bxx, Bxy, Byx, Byy = blocks(B, -1.0 if upper is None else 1.0)
    # a body read from the cache has a "cache" timing and no condensation's; one condensed now the reverse
    keys = [*S.timings, *(k for k in B.timings if k not in S.timings)] if upper is not None else list(S.timings)
    timings = {k: S.timings.get(k, 0.0) + (0.0 if upper is None else B.timings.get(k, 0.0)) for k in keys}
    return Interface(x=S.x, weights=S.weights, C_nn=Byy + Syy, C_nt=Byx + Syx, C_tn=Bxy + Sxy,
                     C_tt=Bxx + Sxx, h=S.h, dofs=S.dofs + B.dofs, timings=timings,
                     backend=S.backend, substrate=S)


def bulk_field(sub: Substrate, sc: SurfaceCompliance, E: float, nu: float) -> np.ndarray:
    """The substrate's P2 displacement under a unit tension ``σxx = 1`` on its end faces.

    The traction ``σ n = (n_x, 0)`` acts on the ``"left"`` and ``"right"``
    groups (``x = ∓L/2``); the top and the base are free of shear. The problem
    has no rigid-body-free support of its own, so the base is held as the
    model holds the block, but on rollers: ``u_y = 0`` on ``"base"`` and
    ``u_x = 0`` at the base node nearest ``x = 0``; clamping it would resist
    the stretch. The exact solution is then the uniform plane-strain state,
    ``u_x = (1 - nu^2)/E x``, ``u_y = -nu (1 + nu)/E (y + L)``, which the P2
    field holds exactly: the FE solve reproduces it to round-off
    (tests/test_fem_bulk.py checks it).

    Returns
    -------
    numpy.ndarray
        The displacement DOFs on ``sc``'s basis (the numbering of its field).

    Raises
    ------
    ValueError
        If the mesh has no ``"left"`` and ``"right"`` groups to load.
    """
    missing = [g for g in ("left", "right", "base") if g not in sub.boundaries]
    if missing:
        raise InputError(f"`mesh` has no {missing} boundary groups: a bulk stress `sigma_bulk` "
                         "acts on the substrate's end faces")
    basis = sc.basis
    lam, mu = lame_parameters(E, nu)
    K = stiffness(basis, lam, mu)
    ends = np.concatenate([sub.boundaries["left"], sub.boundaries["right"]])
    fb = FacetBasis(basis.mesh, basis.elem, facets=ends)
    F = asm(LinearForm(lambda v, w: v[0] * w.n[0]), fb)
    base = basis.get_dofs(facets=sub.boundaries["base"])
    uy = base.all(["u^2"])
    ux = base.all(["u^1"])
    pin = ux[np.argmin(np.abs(basis.doflocs[0, ux]))]
    D = np.concatenate([uy, [pin]])
    u = np.zeros(basis.N)
    A, b, _, I = dirichlet(K, F, D=D)
    with one_blas_thread():
        u[I] = sla.spsolve(A.tocsc(), b)
    return u

"""Stresses at arbitrary points of the substrate, recovered from its FE displacement field.

The P2 displacement gives a stress that is linear in each triangle and jumps
between them; its plain cell mean is first order and worst at the surface.
Here each component is projected in L2 onto the continuous P2 space of the
same mesh (a global mass-matrix solve, quadrature exact for the products),
which converges at the surface too, and is evaluated at the points by
locating them in the mesh (scikit-fem's ``probes``).

Coordinates: the mesh has ``y = 0`` at the surface and the substrate below
it; threepart's ``z = -y`` is the depth. So ``σzz = σyy(mesh)`` and
``σxz = -σxy(mesh)`` (at the surface ``σxz = -q``, ``σzz = -p``, as in
:mod:`threepart.stress`). Tension is positive.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import scipy.sparse.linalg as sla
from numpy.typing import ArrayLike
from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, LinearForm, asm
from threepart.halfplane.surface import PerArray
from threepart.threads import one_blas_thread

from threepart.stress import Stress
from threepart.problem.checks import finite

from .export import plane_strain_stress
from threepart.errors import InputError

__all__ = ["StressField", "lazy_field", "model_nu"]


def model_nu(nu: Any, own: float) -> float:
    """``nu`` of a ``stress()`` call on an FE result: ``None`` or the model's own ``own``.

    Raises
    ------
    ValueError
        For any other value: the FE field was solved with ``own``.
    """
    if nu is None:
        return own
    v = finite("nu", nu)
    if v != own:
        raise InputError(f"`nu` = {v!r} differs from the FE model's Poisson ratio {own!r}: "
                         "its stress field was solved with it (pass None)")
    return own


@dataclass(frozen=True, eq=False)
class StressField:
    """The substrate's displacement field and its recovered stress.

    Attributes
    ----------
    basis
        The vector P2 basis of the displacement.
    u
        Its DOFs (contact forces, plus the bulk stress where there is one).
    E, nu
        The substrate's material (plane strain).
    """

    basis: Basis
    u: np.ndarray
    E: float
    nu: float
    _nodal: dict[str, np.ndarray] = field(default_factory=dict, repr=False)

    def nodal(self) -> dict[str, np.ndarray]:
        """``sxx``, ``syy``, ``sxy`` (mesh axes) as continuous P2 DOFs, by L2 projection (cached)."""
        if self._nodal:
            return self._nodal
        vb, sb, mass = _projection(self.basis.mesh)
        sxx, syy, sxy, _ = plane_strain_stress(vb.interpolate(self.u).grad, self.E, self.nu)
        comps = {"sxx": sxx, "syy": syy, "sxy": sxy}
        rhs = np.stack([asm(LinearForm(lambda v, w: w["s"] * v), sb, s=s) for s in comps.values()],
                       axis=1)
        with one_blas_thread():
            nodal = mass.solve(rhs)
        self._nodal.update({k: nodal[:, i] for i, k in enumerate(comps)})
        self._nodal["_basis"] = sb   # type: ignore[assignment]
        return self._nodal

    def at(self, x: ArrayLike, z: ArrayLike) -> Stress:
        """The recovered stress at ``(x, z)``, ``z >= 0`` the depth, inside the block.

        Raises
        ------
        ValueError
            For points outside the substrate block (``z < 0``, past its ends or its base).
        """
        xa, za = np.asarray(x, dtype=float), np.asarray(z, dtype=float)
        try:
            xb, zb = np.broadcast_arrays(xa, za)
        except ValueError:
            raise InputError(f"`x` of shape {xa.shape} and `z` of shape {za.shape} do not "
                             "broadcast against each other") from None
        if not (np.all(np.isfinite(xb)) and np.all(np.isfinite(zb))):
            raise InputError("`x` and `z` must be finite")
        p = self.basis.mesh.p
        lo, hi, depth = float(p[0].min()), float(p[0].max()), float(-p[1].min())
        if np.any(zb < 0) or np.any(zb > depth):
            raise InputError(f"`z` must lie in [0, {depth:.6g}], the depth of the FE block "
                             "(z is the depth into the substrate)")
        if np.any(xb < lo) or np.any(xb > hi):
            raise InputError(f"`x` must lie in [{lo:.6g}, {hi:.6g}], the width of the FE block")
        nodal = self.nodal()
        sb = nodal["_basis"]
        pts = np.vstack([xb.ravel(), -zb.ravel()])
        # a point exactly on the surface may fall just outside by round-off: nudge it inside
        pts[1] = np.minimum(pts[1], -1e-14 * (hi - lo))
        probe = sb.probes(pts).tocsr()   # type: ignore[attr-defined]
        shape = xb.shape
        return Stress(x=xb.copy(), z=zb.copy(), sxx=(probe @ nodal["sxx"]).reshape(shape),
                      szz=(probe @ nodal["syy"]).reshape(shape),
                      sxz=-(probe @ nodal["sxy"]).reshape(shape), nu=self.nu)


#: the meshes whose projection (:func:`_projection`) is kept: a cycle's states, a load history's
#: steps and the substrate of a run's cases share a few meshes
PROJECTIONS_KEPT = 4
_PROJECTIONS = PerArray(PROJECTIONS_KEPT)


def _projection(mesh: Any) -> tuple[Basis, Basis, Any]:
    """The vector and scalar P2 bases of ``mesh`` and the factor of its scalar P2 mass matrix.

    Every state of a cycle or a history on one mesh projects onto the same space:
    the mass matrix is factorised once per mesh (kept by the identity of its
    nodes, :class:`threepart.halfplane.surface.PerArray`), not once per stress call.
    """
    kept = _PROJECTIONS.get(mesh.p)
    if kept is not None and kept[0] is mesh.t:
        return kept[1:]
    vb = Basis(mesh, ElementVector(ElementTriP2()), intorder=4)   # exact for P2 x P2
    sb = vb.with_element(ElementTriP2())
    M = asm(BilinearForm(lambda u, v, w: u * v), sb).tocsc()
    with one_blas_thread():
        mass = sla.splu(M)
    _PROJECTIONS.put(mesh.p, None, (mesh.t, vb, sb, mass))
    return vb, sb, mass


class _LazyField(StressField):
    """A :class:`StressField` whose ``basis`` and ``u`` are made on first use (:func:`lazy_field`)."""

    def __init__(self, make: Callable[[], tuple[Basis, np.ndarray]], E: float, nu: float) -> None:
        object.__setattr__(self, "_make", make)
        object.__setattr__(self, "E", E)
        object.__setattr__(self, "nu", nu)
        object.__setattr__(self, "_nodal", {})

    def __getattr__(self, name: str) -> Any:
        if name not in ("basis", "u"):
            raise AttributeError(name)
        basis, u = self.__dict__["_make"]()
        object.__setattr__(self, "basis", basis)
        object.__setattr__(self, "u", u)
        object.__setattr__(self, "_make", None)   # let the factorisation's handle go
        return self.__dict__[name]

    def __reduce__(self) -> tuple[Any, ...]:
        return (StressField, (self.basis, self.u, self.E, self.nu))


def lazy_field(make: Callable[[], tuple[Basis, np.ndarray]], E: float, nu: float) -> StressField:
    """A :class:`StressField` whose displacement ``make()`` (``(basis, u)``) runs when first needed.

    A solve on a condensation read from the cache (:func:`fem.elasticity.condense`)
    then factorises the stiffness only if a stress or a displacement is asked for.
    """
    return _LazyField(make, E, nu)

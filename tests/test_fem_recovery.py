"""The FE stress recovery (fem/recovery.py): the mass matrix factorised once per mesh (issue 41).

References that owe nothing to the recovery: a uniform strain lies in the P2 space, so its
stress is plane-strain Hooke's law, a constant, at every point; and a field recovered with
the mesh's projection made afresh (the path before issue 41, one factorisation per field).
"""
from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, ElementVector

from threepart import fem
from threepart.fem import recovery
from threepart.fem.mesh import PRESETS
from threepart.fem.recovery import StressField

E, NU = 2.0, 0.25
#: a uniform strain lies in the P2 space: its stress is exact to the rounding of the sparse solve
UNIFORM = 1e-10


@pytest.fixture(scope="module")
def mesh():
    return fem.make_substrate(PRESETS["trial"].spec(-1.0, 1.0)).mesh


def uniform(basis: Basis, ex: float, ey: float) -> np.ndarray:
    """DOFs of ``u = (ex x, ey y)``."""
    u = np.zeros(basis.N)
    for i, e in ((0, ex), (1, ey)):
        dofs = np.concatenate([basis.nodal_dofs[i], basis.facet_dofs[i]])
        u[dofs] = e * basis.doflocs[i, dofs]
    return u


def hooke(ex: float, ey: float) -> tuple[float, float]:
    """Plane strain: ``(σxx, σyy)`` of the strains ``(ex, ey)``."""
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    return lam * (ex + ey) + 2 * mu * ex, lam * (ex + ey) + 2 * mu * ey


def test_fields_on_one_mesh_share_one_mass_factor_and_keep_their_own_stress(mesh, monkeypatch):
    """Two states on one mesh: one factorisation, and each state's stress is its own Hooke's law
    (a factor or a projection kept for the mesh and handed to the wrong state would fail)."""
    calls = []
    splu = recovery.sla.splu
    monkeypatch.setattr(recovery.sla, "splu", lambda M: calls.append(1) or splu(M))
    recovery._PROJECTIONS.clear()
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    x, z = np.linspace(-0.5, 0.5, 7), np.linspace(0.1, 1.0, 7)
    for ex, ey in ((1e-3, -2e-3), (-4e-3, 5e-4)):
        s = StressField(basis=basis, u=uniform(basis, ex, ey), E=E, nu=NU).at(x, z)
        sxx, syy = hooke(ex, ey)
        scale = abs(sxx) + abs(syy)
        assert np.abs(s.sxx - sxx).max() < UNIFORM * scale
        assert np.abs(s.szz - syy).max() < UNIFORM * scale
        assert np.abs(s.sxz).max() < UNIFORM * scale
    assert len(calls) == 1


def test_a_kept_projection_gives_the_fresh_projections_stress(mesh):
    """The stress of a non-uniform field is the one recovered with the projection made afresh."""
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    rng = np.random.default_rng(41)
    u = rng.standard_normal(basis.N) * 1e-3
    x, z = np.linspace(-0.8, 0.8, 9), np.linspace(0.05, 2.0, 9)
    kept = StressField(basis=basis, u=u, E=E, nu=NU).at(x, z)     # the projection kept (or made)
    kept_again = StressField(basis=basis, u=u, E=E, nu=NU).at(x, z)
    recovery._PROJECTIONS.clear()
    fresh = StressField(basis=basis, u=u, E=E, nu=NU).at(x, z)
    for k in ("sxx", "szz", "sxz"):
        assert np.array_equal(getattr(kept, k), getattr(fresh, k))
        assert np.array_equal(getattr(kept_again, k), getattr(fresh, k))

"""FE condensation: each installed backend against dense solves of the stiffness; the mesh cache.

The reference is built here by another route: the stiffness assembled with
scikit-fem's default quadrature and Lamé constants written out, the candidate
and clamped DOFs found by their coordinates, and the compliance ``C = E^T K^-1 E``
from a dense Cholesky solve with a unit load on every candidate DOF. Each backend
that :func:`fem.elasticity.backends` finds installed is checked against it, so
the file runs whole (no skips) with or without CHOLMOD.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import cho_factor, cho_solve
from skfem import Basis, ElementTriP2, ElementVector, asm
from skfem.models.elasticity import linear_elasticity

from threepart import fem
from threepart.fem import elasticity
from threepart.meshes import SubstrateSpec

#: a small graded block: about 4,300 DOFs, 37 candidate nodes
SPEC = SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.1, L=4.0, growth=0.6, breakpoints=(-0.25, 0.25),
                     refine_at=(-0.25, 0.4), h_fine=0.025)
E, NU = 2.0e5, 0.3
#: the issue's bound for "identical where only the solver changes": only rounding differs
#: (measured <= 4.4e-13 for C, either backend, both component settings)
SAME = 1e-10
BOTH = ("u^1", "u^2")


@pytest.fixture(scope="module")
def substrate():
    return fem.make_substrate(SPEC)


@pytest.fixture(scope="module")
def reference(substrate):
    """Candidate positions, the dense-solve compliance (all u_x then all u_y), and the solver."""
    basis = Basis(substrate.mesh, ElementVector(ElementTriP2()))     # default (higher) quadrature
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))  # plane strain
    K = asm(linear_elasticity(lam, mu), basis).toarray()
    # the P2 vector DOFs: rows are the components u^1, u^2; vertices, then edge midpoints
    comp = np.hstack([basis.nodal_dofs, basis.facet_dofs])
    x, y = basis.doflocs[:, comp[1]]
    tol = 1e-9 * SPEC.L
    on_zone = (np.abs(y) < tol) & (x > SPEC.x_lo - tol) & (x < SPEC.x_hi + tol)
    order = np.argsort(x[on_zone])
    cand = np.concatenate([comp[0][on_zone][order], comp[1][on_zone][order]])
    clamped = comp[:, np.abs(y + SPEC.L) < tol].ravel()
    free = np.setdiff1d(np.arange(basis.N), clamped)
    chol = cho_factor(K[np.ix_(free, free)])
    units = (free[:, None] == cand[None, :]).astype(float)        # a unit load on each candidate
    C = units.T @ cho_solve(chol, units)
    return x[on_zone][order], C, (basis, free, chol)


def block(C: np.ndarray, components: tuple[str, ...]) -> np.ndarray:
    """The part of the two-component compliance that condensing ``components`` gives."""
    n = C.shape[0] // 2
    return C if components == BOTH else C[n:, n:]


@pytest.mark.parametrize("components", [("u^2",), BOTH])
@pytest.mark.parametrize("backend", elasticity.backends())
def test_compliance_matches_dense_solves(substrate, reference, backend, components):
    x_ref, C_ref, _ = reference
    sc = fem.condense(substrate, E, NU, components, backend=backend)
    assert sc.backend == backend
    np.testing.assert_array_equal(sc.x, x_ref)
    C_ref = block(C_ref, components)
    assert sc.C.shape == C_ref.shape == (len(x_ref) * len(components),) * 2
    err = np.abs(sc.C - C_ref).max() / np.abs(C_ref).max()
    assert err < SAME, f"{backend} {components}: max |C - C_dense| / max |C| = {err:.1e}"
    assert np.array_equal(sc.C, sc.C.T)
    assert np.linalg.eigvalsh(sc.C).min() > 0                     # a compliance: positive definite


@pytest.mark.parametrize("components", [("u^2",), BOTH])
@pytest.mark.parametrize("backend", elasticity.backends())
def test_displacement_field_matches_dense_solve(substrate, reference, backend, components):
    """The recovered P2 field is K^-1 F, and at the candidates it is -C f (vertical) or C F."""
    _, C_ref, (basis, free, chol) = reference
    sc = fem.condense(substrate, E, NU, components, backend=backend)
    f = np.random.default_rng(1).uniform(0.5, 1.5, sc.C.shape[0])
    got_basis, u = sc.displacement(f)
    np.testing.assert_array_equal(got_basis.doflocs, basis.doflocs)
    comp = np.hstack([basis.nodal_dofs, basis.facet_dofs])
    F = np.zeros(basis.N)
    x, y = basis.doflocs[:, comp[1]]
    tol = 1e-9 * SPEC.L
    on = np.flatnonzero((np.abs(y) < tol) & (x > SPEC.x_lo - tol) & (x < SPEC.x_hi + tol))
    on = on[np.argsort(x[on])]
    if components == BOTH:
        F[comp[0][on]], F[comp[1][on]] = f[: len(on)], f[len(on):]
    else:
        F[comp[1][on]] = -f                                         # downward forces
    u_ref = np.zeros(basis.N)
    u_ref[free] = cho_solve(chol, F[free])
    scale = np.abs(u_ref).max()
    assert np.abs(u - u_ref).max() < SAME * scale
    surface = u_ref[np.concatenate([comp[0][on], comp[1][on]] if components == BOTH else [comp[1][on]])]
    expected = block(C_ref, components) @ f
    np.testing.assert_allclose(surface, expected if components == BOTH else -expected,
                               rtol=0, atol=SAME * scale)


@pytest.mark.parametrize("intorder", [2, None])
def test_the_vectorised_stiffness_is_scikit_fems_bit_for_bit(substrate, intorder):
    """:func:`fem.elasticity.stiffness` (the condensation's assembly, issue 41) against scikit-fem's
    own ``asm(linear_elasticity)``: the same sparsity and the same entries, bit for bit, on the
    condensation's rule (3 points) and on scikit-fem's default one (6 points)."""
    basis = Basis(substrate.mesh, ElementVector(ElementTriP2()),
                  **({} if intorder is None else {"intorder": intorder}))
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    ref = asm(linear_elasticity(lam, mu), basis)
    got = elasticity.stiffness(basis, lam, mu)
    assert got.shape == ref.shape
    np.testing.assert_array_equal(got.indptr, ref.indptr)
    np.testing.assert_array_equal(got.indices, ref.indices)
    np.testing.assert_array_equal(got.data, ref.data)


def test_backends_agree_through_a_whole_solve():
    """Each installed backend's quick-mesh solve: SciPy's mesh, and its a, c, alpha to 1e-10.

    The contact estimate that places the mesh is snapped to a grid (fem.mesh.snap), so the
    rounding between backends must not change the mesh. Without CHOLMOD this is SciPy twice.
    """
    from threepart.problem.catalogue import get_case

    case = get_case("caseA_moment").resolved()
    out = {}
    for name in elasticity.backends():
        fem.solve.locate_ends.cache_clear()
        with pytest.MonkeyPatch.context() as mp:
            mp.setenv(elasticity.BACKEND_VARIABLE, name)
            out[name] = fem.solve_normal(case.punch, case.P, case.s_load, E=case.E, nu=case.nu,
                                         tilt=case.tilt, mesh="quick")
    ref = out["scipy"]
    W = ref.a + ref.c
    for name, fe in out.items():
        assert np.array_equal(fe.x_nodes, ref.x_nodes), name
        assert max(abs(fe.a - ref.a), abs(fe.c - ref.c)) < SAME * W, name
        assert abs(fe.alpha - ref.alpha) < SAME * abs(ref.alpha), name


def test_backend_choice_and_its_messages(monkeypatch):
    monkeypatch.delenv(elasticity.BACKEND_VARIABLE, raising=False)
    installed = elasticity.backends()
    assert installed[-1] == "scipy" and set(installed) <= set(elasticity.BACKENDS)
    assert elasticity.choose_backend() == installed[0]             # the fastest installed
    assert elasticity.choose_backend("scipy") == "scipy"
    monkeypatch.setenv(elasticity.BACKEND_VARIABLE, "scipy")
    assert elasticity.choose_backend() == "scipy"
    with pytest.raises(ValueError, match=r"`backend` = 'umfpack' is not a backend; use one of"):
        elasticity.choose_backend("umfpack")
    monkeypatch.setenv(elasticity.BACKEND_VARIABLE, "pardiso")
    with pytest.raises(ValueError, match=r"\$THREEPART_FEM_BACKEND = 'pardiso' is not a backend"):
        elasticity.choose_backend()


def test_without_cholmod_scipy_condenses(monkeypatch, substrate, reference):
    """Without scikit-sparse only SciPy is offered; asking for CHOLMOD says how to install it."""
    monkeypatch.delenv(elasticity.BACKEND_VARIABLE, raising=False)
    monkeypatch.setattr(elasticity, "_cholmod", lambda: None)
    assert elasticity.backends() == ("scipy",)
    with pytest.raises(ValueError, match=r"`backend` = 'cholmod' is not installed: pip install"):
        fem.condense(substrate, E, NU, backend="cholmod")
    sc = fem.condense(substrate, E, NU)
    assert sc.backend == "scipy"
    assert np.abs(sc.C - block(reference[1], ("u^2",))).max() < SAME * np.abs(sc.C).max()


def test_components_are_checked_first(substrate):
    with pytest.raises(ValueError, match=r"`components` = \('u\^1',\) must be"):
        fem.condense(substrate, E, NU, ("u^1",))


# --- the mesh cache (fem.make_substrate) ----------------------------------------------------

def test_a_spec_is_meshed_once_and_each_caller_gets_its_own_copy(monkeypatch, tmp_path):
    from threepart.fem import mesh as fem_mesh
    from threepart.meshes import build_substrate

    spec = SubstrateSpec(x_lo=-0.5, x_hi=0.5, h=0.125, L=6.0, growth=0.7)
    fresh = fem.read_substrate(build_substrate(spec, tmp_path / "fresh.msh"))   # no cache
    built = []
    monkeypatch.setattr(fem_mesh, "build_substrate",
                        lambda s, path: built.append(s) or build_substrate(s, path))
    fem_mesh._meshed.cache_clear()
    first = fem.make_substrate(spec)
    first.mesh.doflocs[1] -= 1.0                                    # a caller changes its copy
    first.boundaries["contact"] = first.boundaries["contact"][:1]
    second = fem.make_substrate(spec)
    assert built == [spec]                                          # gmsh ran once
    assert second is not first and second.mesh is not first.mesh
    np.testing.assert_array_equal(second.mesh.p, fresh.mesh.p)      # as meshed, unchanged
    np.testing.assert_array_equal(second.mesh.t, fresh.mesh.t)
    assert second.boundaries.keys() == fresh.boundaries.keys()
    for name, facets in fresh.boundaries.items():
        np.testing.assert_array_equal(second.boundaries[name], facets)
    other = fem.make_substrate(SubstrateSpec(x_lo=-0.5, x_hi=0.5, h=0.25, L=6.0, growth=0.7))
    assert len(built) == 2 and other.mesh.p.shape[1] < second.mesh.p.shape[1]

"""A cold FE solve meshes only what it solves on (issue 41).

The reference owes nothing to the solve: every mesh a two-body solve makes must be one it condenses.
"""
from __future__ import annotations

from threepart import cache, fem
from threepart.fem import mesh as fem_mesh, solve as fem_solve
from threepart.problem.catalogue import load_cases


def test_a_two_body_solve_makes_no_mesh_it_does_not_condense(monkeypatch, tmp_path):
    """With a refined preset and a shear, the body is meshed with the stick zone's ends as nodes;
    the preset's plain mesh around the contact (made and dropped before issue 41) is not made."""
    import importlib

    fem_interface = importlib.import_module("threepart.fem.interface")   # fem.interface is its function
    made, condensed = [], set()
    build = fem_mesh.build_substrate

    def spy_build(spec, path):
        made.append(spec)
        return build(spec, path)

    def spy_condense(condense):
        def call(sub, *args, **kwargs):
            condensed.add((sub.mesh.p.shape, sub.mesh.t.shape, float(sub.mesh.p.sum())))
            return condense(sub, *args, **kwargs)
        return call

    monkeypatch.setenv(cache.CACHE_VARIABLE, str(tmp_path))     # cold: every mesh made here
    monkeypatch.setattr(fem_mesh, "build_substrate", spy_build)
    for module in (fem_solve, fem_interface):
        monkeypatch.setattr(module, "condense", spy_condense(module.condense))
    fem_mesh._meshed.cache_clear()
    fem_solve.locate_ends.cache_clear()
    case = next(c for c in load_cases("fem") if c.name == "hertz").resolved()
    slip = fem.solve_partial_slip(case.punch, case.P, 0.0, Q=0.3 * case.P, f=0.5,
                                  E=2 * case.block_E, nu=case.nu, mesh="quick", steps=1,
                                  progress=False)
    assert 0 < slip.d < slip.normal.a
    assert len(made) == len(set(made)) == len(condensed), (made, condensed)

"""One condensation per mesh and material (issue 41): the key, damaged entries, an unwritable cache.

Every test keeps threepart's cache in its own ``tmp_path`` (``THREEPART_CACHE``)
and starts with an empty memory of condensations. The reference of every
answer is a cold condensation (``cached=False``: assembled and factorised
afresh, kept nowhere), and through it the dense solves of
``tests/test_fem_linalg.py``.
"""
from __future__ import annotations

import math
import os
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest

from threepart import cache, fem
from threepart.cli import main
from threepart.fem import elasticity
from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance

#: the small graded block of tests/test_fem_linalg.py: about 4,300 DOFs, 37 candidate nodes
SPEC = SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.1, L=4.0, growth=0.6, breakpoints=(-0.25, 0.25),
                     refine_at=(-0.25, 0.4), h_fine=0.025)
E, NU = 2.0e5, 0.3
#: what a cached answer may differ from a cold one by: rounding alone
SAME = tolerance("fem-cache", "same").limit


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    """threepart's cache in this test's own directory, and no condensation in memory."""
    d = tmp_path / "cache"
    monkeypatch.setenv(cache.CACHE_VARIABLE, str(d))
    elasticity.forget()
    yield d
    elasticity.forget()


@pytest.fixture(scope="module")
def substrate():
    return fem.make_substrate(SPEC)


@pytest.fixture(scope="module")
def cold(substrate):
    """The condensation made afresh, kept nowhere: the reference."""
    return fem.condense(substrate, E, NU, cached=False)


@pytest.fixture
def factorisations(monkeypatch):
    """The number of factorisations of the stiffness made so far (every backend counted)."""
    calls: list[str] = []
    for name, f in list(elasticity._FACTORISE.items()):
        def counted(K, last, f=f, name=name):
            calls.append(name)
            return f(K, last)
        monkeypatch.setitem(elasticity._FACTORISE, name, counted)
    return calls


def entry_of(directory: Path) -> Path:
    files = sorted(directory.glob("threepart-compliance-*.npz"))
    assert len(files) == 1, files
    return files[0]


def assert_same(sc, ref) -> None:
    np.testing.assert_array_equal(sc.x, ref.x)
    np.testing.assert_array_equal(sc.weights, ref.weights)
    err = np.abs(sc.C - ref.C).max() / np.abs(ref.C).max()
    assert err <= SAME, f"max |C - C_cold| / max |C| = {err:.1e}"
    assert sc.dofs == ref.dofs and sc.h == ref.h


def test_the_key_changes_with_everything_that_changes_the_compliance(substrate):
    backend = elasticity.choose_backend()
    base = elasticity.compliance_key(substrate, E, NU, ("u^2",), backend)
    again = elasticity.compliance_key(fem.make_substrate(SPEC), E, NU, ("u^2",), backend)
    assert again == base                                  # an equal mesh (another copy): the same key
    other = fem.make_substrate(SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.1, L=4.0, growth=0.6,
                                             breakpoints=(-0.25, 0.25)))
    moved = fem.make_substrate(SPEC)
    moved.mesh.p[0, int(np.argmax(moved.mesh.p[1] < -1.0))] += 1e-12   # one interior node, 1e-12
    keys = {base,
            elasticity.compliance_key(substrate, 1.01 * E, NU, ("u^2",), backend),
            elasticity.compliance_key(substrate, E, 0.25, ("u^2",), backend),
            elasticity.compliance_key(other, E, NU, ("u^2",), backend),
            elasticity.compliance_key(moved, E, NU, ("u^2",), backend),
            elasticity.compliance_key(substrate, E, NU, ("u^1", "u^2"), backend),
            elasticity.compliance_key(substrate, E, NU, ("u^2",), "other-backend")}
    assert len(keys) == 7


def test_a_mesh_condenses_once_and_a_later_run_reads_it(substrate, cold, own_cache, factorisations):
    first = fem.condense(substrate, E, NU)
    assert factorisations == [first.backend]
    assert_same(first, cold)
    assert entry_of(own_cache).stat().st_size > cold.C.nbytes
    assert fem.condense(fem.make_substrate(SPEC), E, NU) is not None and len(factorisations) == 1
    elasticity.forget()                                   # a later run: memory empty, the disk kept
    read = fem.condense(substrate, E, NU)
    assert len(factorisations) == 1 and "cache" in read.timings
    assert_same(read, cold)
    assert not read.C.flags.writeable                     # shared: no caller may change it
    # its displacement field factorises once, when asked for, and equals the cold one's
    f = np.linspace(1.0, 2.0, len(cold.x))
    (_, u_read), (_, u_cold) = read.displacement(f), cold.displacement(f)
    assert len(factorisations) == 2
    assert np.abs(u_read - u_cold).max() <= SAME * np.abs(u_cold).max()
    read.displacement(f)
    assert len(factorisations) == 2


def _flip(path: Path) -> None:
    raw = bytearray(path.read_bytes())
    i = len(raw) // 2                                      # inside C's data
    raw[i:i + 8] = bytes(b ^ 0xFF for b in raw[i:i + 8])
    path.write_bytes(bytes(raw))


def _truncate(path: Path) -> None:
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 3])


def _nan_in_place(path: Path) -> None:
    """A NaN written over one of C's numbers, the file otherwise intact (its zip CRC renewed)."""
    with zipfile.ZipFile(path) as z:
        members = {n: z.read(n) for n in z.namelist()}
    raw = bytearray(members["C.npy"])
    raw[-8:] = np.array([np.nan]).tobytes()
    members["C.npy"] = bytes(raw)
    with zipfile.ZipFile(path, "w") as z:
        for n, b in members.items():
            z.writestr(n, b)


def _nan_signed(path: Path) -> None:
    """An entry whose checksums hold but whose C holds a NaN (written through the cache itself)."""
    k = path.name.split("-")[2].removesuffix(".npz")
    with np.load(path) as z:
        x, w, C = z["x"], z["weights"], z["C"].copy()
    C[3, 3] = np.nan
    assert cache.store("compliance", k, {"x": x, "weights": w, "C": C})


def _wrong_shape(path: Path) -> None:
    """A sound entry of the wrong shape: one candidate node too few."""
    k = path.name.split("-")[2].removesuffix(".npz")
    with np.load(path) as z:
        x, w, C = z["x"], z["weights"], z["C"]
    assert cache.store("compliance", k, {"x": x[:-1], "weights": w[:-1], "C": C[:-1, :-1]})


def _not_an_entry(path: Path) -> None:
    path.write_text("not an npz\n")


@pytest.mark.parametrize("damage", [_truncate, _flip, _nan_in_place, _nan_signed, _wrong_shape,
                                    _not_an_entry])
def test_a_damaged_entry_is_removed_and_rebuilt_never_used(substrate, cold, own_cache, factorisations,
                                                           damage):
    fem.condense(substrate, E, NU)
    path = entry_of(own_cache)
    damage(path)
    elasticity.forget()
    rebuilt = fem.condense(substrate, E, NU)
    assert len(factorisations) == 2 and "cache" not in rebuilt.timings   # condensed again, not read
    assert_same(rebuilt, cold)
    assert entry_of(own_cache) == path                    # and written back, whole
    elasticity.forget()
    read = fem.condense(substrate, E, NU)
    assert len(factorisations) == 2 and "cache" in read.timings
    assert_same(read, cold)
    damage(path)                                          # the look-up alone removes it
    assert cache.load("compliance", path.name.split("-")[2].removesuffix(".npz"),
                      lambda a: a["C"].shape == cold.C.shape) is None
    assert not path.exists()


def test_a_damaged_entry_found_by_a_solve_is_rebuilt(substrate, cold, own_cache, factorisations):
    fem.condense(substrate, E, NU)
    _flip(entry_of(own_cache))
    elasticity.forget()
    assert_same(fem.condense(substrate, E, NU), cold)
    assert len(factorisations) == 2


def test_an_unwritable_cache_still_solves_in_memory(substrate, cold, tmp_path, monkeypatch,
                                                    factorisations):
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv(cache.CACHE_VARIABLE, str(blocker / "cache"))   # its parent is a file
    before = sorted(os.listdir(tmp_path))
    assert_same(fem.condense(substrate, E, NU), cold)
    assert_same(fem.condense(substrate, E, NU), cold)    # the run's memory
    assert len(factorisations) == 1
    assert sorted(os.listdir(tmp_path)) == before and blocker.read_text() == ""
    assert main(["cache"]) == 0 and main(["cache", "--clear"]) == 0


def test_writes_leave_no_temporary_file(substrate, own_cache):
    fem.condense(substrate, E, NU)
    fem.condense(substrate, E, NU, ("u^1", "u^2"))
    names = sorted(os.listdir(own_cache))
    assert len([n for n in names if n.startswith("threepart-compliance-")]) == 2, names
    assert all(n.startswith("threepart-") and n.endswith(".npz") for n in names), names


def test_cache_clear_removes_only_threepart_s_entries(substrate, own_cache, capsys):
    fem.condense(substrate, E, NU)
    ours = entry_of(own_cache)
    stranger = own_cache / "notes.txt"
    stranger.write_text("mine\n")
    lookalike = own_cache / ("threepart-compliance-" + "0" * 64 + ".npz")   # our name, not our file
    lookalike.write_bytes(b"PK\x03\x04 someone else's zip")
    dead_tmp = own_cache / f".{ours.stem}.999999999.0123abcd.tmp"          # no such process
    dead_tmp.write_bytes(b"half")
    entries = len(list(own_cache.glob("threepart-*-*.npz"))) - 1      # the mesh's too, if made here
    assert main(["cache"]) == 0
    out = capsys.readouterr().out
    assert str(own_cache) in out and ours.name in out and f"{entries} entries" in out
    assert "left alone: notes.txt" in out and f"left alone: {lookalike.name}" in out
    assert main(["cache", "--clear"]) == 0
    assert f"removed {entries + 1}" in capsys.readouterr().out
    assert not ours.exists() and not dead_tmp.exists()
    assert stranger.read_text() == "mine\n" and lookalike.exists()
    assert sorted(os.listdir(own_cache)) == sorted([stranger.name, lookalike.name])


def test_a_solve_on_the_cached_mesh_gives_the_cold_answer(factorisations):
    """The whole rigid-punch solve read from the cache against one condensed afresh: the same
    contact, pressure and stress (the stress field factorised when first asked for)."""
    punch = Punch(R1=10.0, R2=5.0, b=1.0)
    spec = SubstrateSpec(x_lo=-2.0, x_hi=2.0, h=0.05, L=40.0, growth=0.3, breakpoints=(-1.0, 1.0))
    sub = fem.make_substrate(spec)
    kw = dict(E=2.0e5, nu=NU, tilt="free", mesh=sub, progress=False)
    fresh = fem.solve_normal(punch, 3000.0, 0.1, **kw)
    elasticity.forget()
    again = fem.solve_normal(punch, 3000.0, 0.1, **kw)
    assert len(factorisations) == 1
    W = fresh.a + fresh.c
    for q in ("a", "c"):
        assert abs(getattr(again, q) - getattr(fresh, q)) <= SAME * W
    assert abs(again.alpha - fresh.alpha) <= SAME * abs(fresh.alpha)
    peak = np.abs(fresh.p_nodes).max()
    assert np.abs(again.p_nodes - fresh.p_nodes).max() <= SAME * peak
    x, z = np.linspace(-0.5 * fresh.a, 0.5 * fresh.c, 5), np.full(5, 0.3 * W)
    s_fresh, s_again = fresh.stress(x, z), again.stress(x, z)
    assert len(factorisations) == 2
    for comp in ("sxx", "szz", "sxz"):
        assert np.abs(getattr(s_again, comp) - getattr(s_fresh, comp)).max() <= SAME * peak


def test_a_history_warm_starts_each_contact_from_the_last_and_gets_the_cold_answers(monkeypatch):
    """Each state's normal contact started from the previous state's active set (issue 41) settles
    on the active set and forces of a cold start (every node active, then the punch's shape), in
    fewer iterations over the history."""
    from threepart.fem import contact, history

    punch = Punch(R1=10.0, R2=5.0, b=1.0)
    E1, P = 1.0, 0.05
    states = [(P * (1 + 0.3 * math.sin(t)), 0.1 * math.cos(t), 0.0, 0.0)
              for t in np.linspace(0.0, 2 * np.pi, 13)[:-1]]
    spec = SubstrateSpec(x_lo=-2.2, x_hi=2.2, h=0.05, L=40.0, growth=0.3, breakpoints=(-1.0, 1.0))
    iterations: dict[str, list[int]] = {"warm": [], "cold": []}

    def run(start: str):
        def counted(*args, **kw):
            if start == "cold":
                kw["active"] = None
            sol = contact.solve_contact(*args, **kw)
            iterations[start].append(sol.iterations)
            return sol
        monkeypatch.setattr(history, "solve_contact", counted)
        return fem.load_history(punch, states, 0.5, E=E1, nu=NU, mesh=spec, progress=False)

    warm, cold = run("warm"), run("cold")
    assert len(iterations["warm"]) == len(iterations["cold"]) == len(states)
    assert sum(iterations["warm"]) < sum(iterations["cold"]), iterations
    for w, c in zip(warm.normals, cold.normals):
        W = c.a + c.c
        assert abs(w.a - c.a) <= SAME * W and abs(w.c - c.c) <= SAME * W
        assert np.abs(w.p_nodes - c.p_nodes).max() <= SAME * np.abs(c.p_nodes).max()


def test_a_mesh_is_kept_on_disk_and_read_back_whole(own_cache, monkeypatch):
    """gmsh's mesh of a spec, read from threepart's cache by a later run: the same nodes, elements,
    facets and groups; a damaged entry is removed and gmsh runs again."""
    from threepart.fem import mesh as fem_mesh

    spec = SubstrateSpec(x_lo=-0.7, x_hi=0.5, h=0.1, L=4.0, growth=0.6, breakpoints=(-0.25, 0.25))
    runs: list[SubstrateSpec] = []
    build = fem_mesh.build_substrate
    monkeypatch.setattr(fem_mesh, "build_substrate", lambda s, p: runs.append(s) or build(s, p))
    fem_mesh._meshed.cache_clear()
    made = fem.make_substrate(spec)
    fem_mesh._meshed.cache_clear()                       # a later run: only the disk remembers
    read = fem.make_substrate(spec)
    assert runs == [spec]
    for a, b in ((read.mesh.p, made.mesh.p), (read.mesh.t, made.mesh.t),
                 (read.mesh.facets, made.mesh.facets)):
        np.testing.assert_array_equal(a, b)
    assert read.boundaries.keys() == made.boundaries.keys()
    for name in made.boundaries:
        np.testing.assert_array_equal(read.boundaries[name], made.boundaries[name])
    entry = next(own_cache.glob("threepart-mesh-*.npz"))
    _truncate(entry)
    fem_mesh._meshed.cache_clear()
    again = fem.make_substrate(spec)
    assert runs == [spec, spec] and entry.exists()       # meshed again and written back
    np.testing.assert_array_equal(again.mesh.p, made.mesh.p)
    fem_mesh._meshed.cache_clear()


def test_the_run_keeps_few_factorisations_and_makes_a_dropped_one_again(substrate, factorisations):
    """Past :data:`~fem.elasticity.FACTORS_KEPT` condensations the oldest lets its factor go; its
    displacement field then factorises again and equals a cold condensation's."""
    moduli = [E * (1 + 0.1 * j) for j in range(elasticity.FACTORS_KEPT + 1)]
    first, *_ = [fem.condense(substrate, e, NU) for e in moduli]
    assert len(factorisations) == len(moduli)
    assert first._solver._parts is None                 # let go
    f = np.linspace(1.0, 2.0, len(first.x))
    _, u = first.displacement(f)
    assert len(factorisations) == len(moduli) + 1
    _, u_cold = fem.condense(substrate, moduli[0], NU, cached=False).displacement(f)
    assert np.abs(u - u_cold).max() <= SAME * np.abs(u_cold).max()


def test_the_test_run_never_writes_the_users_cache():
    """tests/conftest.py points THREEPART_CACHE at the run's temporary cache before the workers start."""
    from threepart.cache import cache_dir

    home = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "threepart"
    assert cache_dir() != home and Path(tempfile.gettempdir()) in cache_dir().parents


# --- the punch body's mesh and a finite body's lazy stress field (issue 41, the quick map) -------

def test_a_punch_body_is_meshed_once_and_read_back_whole(own_cache, monkeypatch, tmp_path):
    """gmsh's punch of a spec (:func:`fem.mesh.make_punch`): meshed once for the run, each caller a
    copy, and a later run reads it from threepart's cache: the nodes, elements and groups of a
    punch meshed afresh and read through meshio."""
    from threepart.fem import mesh as fem_mesh
    from threepart.meshes import PunchSpec, build_punch

    spec = PunchSpec(zone=fem.PRESETS["quick"].scaled(0.5).spec(-1.4, 1.3, (-1.0, 1.0)), b=1.0,
                     R1=10.0, R2=5.0, H=4.0)
    fresh = fem.read_substrate(build_punch(spec, tmp_path / "fresh.msh"))   # no cache at all
    built: list[PunchSpec] = []
    monkeypatch.setattr(fem_mesh, "build_punch", lambda s, p: built.append(s) or build_punch(s, p))
    fem_mesh._meshed.cache_clear()
    first = fem_mesh.make_punch(spec)
    first.mesh.p[1] += 1.0                                             # a caller changes its copy
    again = fem_mesh.make_punch(spec)
    fem_mesh._meshed.cache_clear()                                     # a later run: the disk only
    read = fem_mesh.make_punch(spec)
    assert built == [spec]
    for got in (again, read):
        np.testing.assert_array_equal(got.mesh.p, fresh.mesh.p)
        np.testing.assert_array_equal(got.mesh.t, fresh.mesh.t)
        assert got.boundaries.keys() == fresh.boundaries.keys()
        for name, facets in fresh.boundaries.items():
            np.testing.assert_array_equal(got.boundaries[name], facets)
    fem_mesh._meshed.cache_clear()


def test_a_finite_body_read_from_the_cache_factorises_only_for_its_stresses(own_cache, factorisations):
    """:func:`fem.solve_finite` on condensations read from the cache: the same pressure, no
    factorisation until a stress is asked for, and then the stresses of the run that condensed
    (its factor still in memory): the same to round-off."""
    from threepart.fem.finite import _located

    punch = Punch(R1=10.0, R2=10.0, b=1.0)
    mesh = fem.PRESETS["quick"].scaled(0.5)
    x, z = np.linspace(-1.2, 1.2, 7), np.full(7, 0.3)

    def solve():
        return fem.solve_finite(punch, 0.05, 0.0, E=1.0, nu=NU, H=4.0, mesh=mesh)

    cold = solve()
    made = len(factorisations)
    ref = cold.stress(x, z)
    assert len(factorisations) == made                   # the factor made by the condensation
    elasticity.forget()
    _located.cache_clear()
    warm = solve()
    assert len(factorisations) == made                   # every body read from the cache
    np.testing.assert_array_equal(warm.p_nodes, cold.p_nodes)
    assert (warm.a, warm.c, warm.alpha) == (cold.a, cold.c, cold.alpha)
    got = warm.stress(x, z)
    assert len(factorisations) == made + 1               # the block, once, for its stresses
    scale = np.abs(ref.szz).max()
    for name in ("sxx", "szz", "sxz"):
        assert np.abs(getattr(got, name) - getattr(ref, name)).max() <= SAME * scale, name

"""Time the FE model on the quick and default meshes, side by side with the closed form.

Run ``python benchmarks/bench_fem.py [quick default ...] [--peer | --backends | --pressure]``. For each
case of the catalogue's ``"fem"`` suite (Hertz; case A symmetric and with unequal radii and a
moment; case B; case C; a general finite R; suppressed tilt; near lift-off) it
prints the FE errors against ``closedform.solve_normal`` at the case's compliance
``A`` of the case (a rigid-punch block of ``case.block_E``): ``a`` and ``c`` in units of the contact width W,
``alpha`` relative, both peak pressures and the interior pressure (5 % of W
excluded at each edge) relative to the largest peak, with DOFs and times. Then,
side by side in the same run (every FE solve cold: no cached contact estimate or
mesh, with its time per stage), the FFT-BEM peer tamaas (:mod:`peer_tamaas`, a
benchmark extra) on the tilt-free cases, with the ratio of each FEM preset's time
to tamaas' time to 4e-5 (``--peer``: that table only): cold (nothing remembered,
an empty cache directory), read from threepart's cache by a later run, and at
another load on the cached mesh (issue 41). ``--pressure``: only where the nodal pressure's
error lies and how it falls with the mesh (:func:`pressure`). Last, when CHOLMOD is
installed (the ``fast`` extra), the two condensation backends side by side on the
same meshes: the condensation and the whole cold solve with each, their ratios,
and how far the two answers lie apart (``--backends``: that table only).
"""
from __future__ import annotations

import contextlib
import os
import tempfile
import time
from dataclasses import replace
from typing import Iterator

import numpy as np

from threepart import cache, closedform, fem
from threepart.problem.catalogue import load_cases
from threepart.fem import elasticity


def errors(fe, ref) -> dict[str, float]:
    """FE errors against the closed-form result ``ref``."""
    W = ref.a + ref.c
    pk_ref, pk_fe = ref.peaks(), fe.peaks()
    pmax = max(p.p for p in pk_ref)
    x = np.linspace(-ref.a + 0.05 * W, ref.c - 0.05 * W, 4001)
    alpha_scale = abs(ref.alpha) if abs(ref.alpha) > 0 else 1.0
    return {
        "a/W": (fe.a - ref.a) / W,
        "c/W": (fe.c - ref.c) / W,
        "alpha": (fe.alpha - ref.alpha) / alpha_scale,
        "s/W": (fe.s - ref.s) / W,
        "p_left": (pk_fe[0].p - pk_ref[0].p) / pmax,
        "p_right": (pk_fe[1].p - pk_ref[1].p) / pmax,
        "p_int": float(np.max(np.abs(fe.pressure(x) - ref.pressure(x)))) / pmax,
    }


#: the stages of one FE solve, as in ``FemResult.diagnostics.timings``
STAGES = ("locate", "mesh", "assemble", "factorise", "contact")


@contextlib.contextmanager
def environ(name: str, value: str) -> Iterator[None]:
    """The environment variable ``name`` set to ``value`` inside the block."""
    old = os.environ.get(name)
    os.environ[name] = value
    try:
        yield
    finally:
        if old is None:
            del os.environ[name]
        else:
            os.environ[name] = old


def forget_run() -> None:
    """Forget what this run remembers: contact estimates, meshes, condensations (the disk cache stays)."""
    fem.solve.locate_ends.cache_clear()
    fem.mesh._meshed.cache_clear()
    elasticity.forget()


def timed_solve(case, mesh, P: float | None = None):
    """One FE solve of ``case`` (at load ``P``, default the case's); its wall time."""
    t0 = time.perf_counter()
    fe = fem.solve_normal(case.punch, case.P if P is None else P, case.s_load, E=case.block_E,
                          nu=case.nu, tilt=case.tilt, mesh=mesh)
    return fe, time.perf_counter() - t0


def cold_solve(case, mesh: str):
    """One FE solve of ``case`` with nothing remembered: no contact estimate, mesh or condensation in
    memory, an empty cache directory of threepart's (:mod:`threepart.cache`); its wall time."""
    forget_run()
    with tempfile.TemporaryDirectory(prefix="threepart-bench-") as d, environ(cache.CACHE_VARIABLE, d):
        return timed_solve(case, mesh)


def cached_solves(case, mesh: str, load: float = 1.05):
    """The cache's two gains on ``case``, side by side with :func:`cold_solve` in one run.

    Returns ``(disk, other)``, each ``(result, seconds)``: ``disk`` a later run's
    solve (the run's memory forgotten, threepart's cache directory filled by an
    earlier solve: meshes and condensations are read, not made), ``other`` a
    solve of ``load`` times the case's load on the mesh just solved on
    (:class:`~fem.mesh.Substrate` given; its condensation in memory).
    """
    forget_run()
    with tempfile.TemporaryDirectory(prefix="threepart-bench-") as d, environ(cache.CACHE_VARIABLE, d):
        first, _ = timed_solve(case, mesh)
        forget_run()
        disk = timed_solve(case, mesh)
        pre = fem.mesh.preset(mesh)
        pre = replace(pre, refine=pre.refine * first.info["refined"])
        guess = fem.locate_contact(case.punch, case.P, case.s_load, E=case.block_E, nu=case.nu,
                                   tilt=case.tilt)
        sub = fem.make_substrate(pre.spec(*guess, (-case.punch.b, case.punch.b)))
        timed_solve(case, sub)
        other = timed_solve(case, sub, load * case.P)
    return disk, other


def main(meshes: list[str]) -> None:
    print(f"condensation backend: {elasticity.choose_backend()} (installed: "
          f"{', '.join(elasticity.backends())})")
    print(f"{'case':14s} {'mesh':8s} {'dofs':>7s} {'t_fem':>6s} {'t_cf':>7s} "
          + " ".join(f"{k:>9s}" for k in ("a/W", "c/W", "alpha", "s/W", "p_left", "p_right", "p_int"))
          + "   seconds: " + " ".join(STAGES))
    for case in load_cases("fem"):
        case = case.resolved()
        s = case.s_load
        t0 = time.perf_counter()
        ref = closedform.solve_normal(case.punch, case.P, s, A=case.A, tilt=case.tilt)
        t_cf = time.perf_counter() - t0
        for mesh in meshes:
            fe, t_fe = cold_solve(case, mesh)
            err = errors(fe, ref)
            print(f"{case.name:14s} {mesh:8s} {fe.diagnostics.dofs:7d} {t_fe:6.2f} {t_cf:7.4f} "
                  + " ".join(f"{v:+9.1e}" for v in err.values())
                  + "   " + " ".join(f"{fe.diagnostics.timings.get(k, 0.0):.2f}" for k in STAGES),
                  flush=True)


#: the tilt-free cases the FFT-BEM peer can solve (it has no rigid-body tilt unknown)
PEER_CASES = ("caseA_sym", "suppressed")
#: tamaas grid densities (cells per contact width), on a period of 64 W
PEER_CELLS = (512, 1024, 2048)
#: the other load of a solve on a cached mesh, a multiple of the case's
OTHER_LOAD = 1.05


def peer(meshes: list[str]) -> None:
    """FEM presets and tamaas on the same tilt-free cases, timed side by side in this run.

    Errors are against the closed form: a, c in units of W, pressure at each
    method's own nodes more than 5 % of W inside the ends, of the peak. Each
    FEM preset is solved cold (:func:`cold_solve`), by a later run that reads
    threepart's cache (``disk``), and at another load on the cached mesh
    (``other load``, :func:`cached_solves`), judged against its own closed form.
    """
    from peer_tamaas import available, solve_peer

    if not available():
        print("tamaas is not installed: pip install -e '.[bench]' to time the FFT-BEM peer")
        return
    print(f"\n{'case':12s} {'method':24s} {'time s':>7s} {'a/W':>9s} {'c/W':>9s} {'p':>9s}")
    for name in PEER_CASES:
        case = next(c for c in load_cases("fem") if c.name == name).resolved()

        def row(method: str, dt: float, a: float, c: float, x: np.ndarray,
                p: np.ndarray, ref) -> tuple[float, float]:
            W = ref.a + ref.c
            peak = max(q.p for q in ref.peaks())
            inner = (x > -ref.a + 0.05 * W) & (x < ref.c - 0.05 * W)
            perr = float(np.max(np.abs(p[inner] - ref.pressure(x[inner])))) / peak
            ends = max(abs(a - ref.a) / W, abs(c - ref.c) / W)
            print(f"{name:12s} {method:24s} {dt:7.2f} {abs(a - ref.a) / W:9.1e} "
                  f"{abs(c - ref.c) / W:9.1e} {perr:9.1e}", flush=True)
            return ends, max(ends, perr)

        ref = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        ref_other = closedform.solve_normal(case.punch, OTHER_LOAD * case.P, case.s_load, A=case.A,
                                            tilt=case.tilt)
        W = ref.a + ref.c
        times: dict[str, tuple[float, tuple[float, float]]] = {}
        for mesh in meshes:
            fe, dt = cold_solve(case, mesh)
            times[f"fem {mesh}"] = (dt, row(f"fem {mesh}", dt, fe.a, fe.c, fe.x_nodes, fe.p_nodes, ref))
            (fd, td), (fo, to) = cached_solves(case, mesh, OTHER_LOAD)
            times[f"fem {mesh} disk"] = (td, row(f"fem {mesh} disk", td, fd.a, fd.c, fd.x_nodes,
                                                 fd.p_nodes, ref))
            times[f"fem {mesh} other load"] = (to, row(f"fem {mesh} other load", to, fo.a, fo.c,
                                                       fo.x_nodes, fo.p_nodes, ref_other))
        for cells in PEER_CELLS:
            r = solve_peer(case.punch, case.P, E=case.block_E, nu=case.nu, width=W, cells=cells)
            times[f"tamaas {cells}/W"] = (r.time_s, row(f"tamaas {cells}/W", r.time_s, r.a, r.c, r.x,
                                                        r.p, ref))
        # tamaas' time to 4e-5: its coarsest grid that gets there, else its finest (said so);
        # judged on a and c alone, then on a, c and the pressure
        for which, label in ((0, "a, c"), (1, "a, c, p")):
            peers = [(key, t, e[which]) for key, (t, e) in times.items() if key.startswith("tamaas")]
            key_p, t_p, e_p = next(((k, t, e) for k, t, e in peers if e <= 4e-5), peers[-1])
            for key, (t, e) in times.items():
                if key.startswith("fem"):
                    print(f"{'':12s} [{label}] {key}: time / {key_p} ({e_p:.1e}) = {t / t_p:.2f}, "
                          f"its worst error {e[which]:.1e}")


#: the default preset with the surface refined twice and the volume grading kept
SURFACE_X2 = replace(fem.mesh.PRESETS["default"], n=2 * fem.mesh.PRESETS["default"].n)


def pressure() -> None:
    """Where the FE pressure's error lies, and what a finer mesh buys, on the peer's cases.

    For the self-similar family (quick, default, fine) and the default with only
    the surface refined (:data:`SURFACE_X2`), each solved cold: the time, the
    candidate nodes, the largest nodal-pressure error (of the peak) at the
    interior nodes 5-20 % of W from an end and beyond 20 % (the joins
    included), at the elements' vertices and at their midside nodes
    separately, and the peaks' error. The P2 nodal pressure ``f_i / w_i``
    alternates between vertex and midside nodes; its error falls as ``h^2``
    with the whole mesh, not with the surface alone.
    """
    print(f"\n{'case':12s} {'mesh':12s} {'time s':>7s} {'nodes':>6s} {'5-20% vtx':>10s} "
          f"{'5-20% mid':>10s} {'>20% vtx':>9s} {'>20% mid':>9s} {'peaks':>8s}")
    for name in PEER_CASES:
        case = next(c for c in load_cases("fem") if c.name == name).resolved()
        ref = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        W = ref.a + ref.c
        for label, mesh in (("quick", "quick"), ("default", "default"), ("fine", "fine"),
                            ("surface x2", SURFACE_X2)):
            fe, dt = cold_solve(case, mesh)
            err = errors(fe, ref)
            x = fe.x_nodes
            e = np.abs(fe.p_nodes - ref.pressure(x)) / max(q.p for q in ref.peaks())
            r = np.minimum(x + ref.a, ref.c - x) / W
            vertex = np.arange(len(x)) % 2 == 0   # the P2 surface chain starts at a vertex
            cols = [float(np.max(e[sel], initial=0.0))
                    for band in ((r >= 0.05) & (r < 0.2), r >= 0.2) for sel in (band & vertex, band & ~vertex)]
            print(f"{name:12s} {label:12s} {dt:7.2f} {len(x):6d} " + " ".join(f"{v:10.1e}" for v in cols[:2])
                  + " " + " ".join(f"{v:9.1e}" for v in cols[2:])
                  + f" {max(abs(err['p_left']), abs(err['p_right'])):8.1e}", flush=True)


@contextlib.contextmanager
def backend(name: str) -> Iterator[None]:
    """Make ``name`` the backend of every condensation inside the block (``$THREEPART_FEM_BACKEND``)."""
    old = os.environ.get(elasticity.BACKEND_VARIABLE)
    os.environ[elasticity.BACKEND_VARIABLE] = name
    try:
        yield
    finally:
        if old is None:
            del os.environ[elasticity.BACKEND_VARIABLE]
        else:
            os.environ[elasticity.BACKEND_VARIABLE] = old


def backends(meshes: list[str], repeat: int = 2) -> None:
    """SciPy (SuperLU) and CHOLMOD condensation side by side, on the same meshes, in this run.

    For each case and preset: the condensation (``factorise`` stage) of the
    located mesh with each backend, and the whole cold solve with each (best of
    ``repeat``, interleaved), the ratios SciPy / CHOLMOD, and the largest
    differences between the two: ``max |ΔC| / max |C|``, ``|Δa|/W``, ``|Δc|/W``
    and ``Δα`` scaled as in :func:`errors` (relative to the closed-form ``α``,
    absolute where that is 0). "same" says whether both whole solves and the
    condensations ran on one mesh (identical surface nodes). Last, the
    two-component condensation of the frictional model, on the first case's mesh
    of the last preset.
    """
    if "cholmod" not in elasticity.backends():
        print("\nCHOLMOD is not installed: pip install -e '.[fast]' (after apt-get install "
              "libsuitesparse-dev) to time it against SciPy")
        return
    names = ("scipy", "cholmod")
    print(f"\n{'case':14s} {'mesh':8s} {'dofs':>7s} {'n':>5s} "
          + " ".join(f"{'cond ' + b:>12s}" for b in names) + f" {'ratio':>6s} "
          + " ".join(f"{'solve ' + b:>13s}" for b in names) + f" {'ratio':>6s} {'same':>4s} "
          + " ".join(f"{k:>9s}" for k in ("|dC|/|C|", "|da|/W", "|dc|/W", "|dalpha|")))
    total = {b: {"cond": 0.0, "solve": 0.0} for b in names}
    first = None
    for k, case in enumerate(load_cases("fem")):
        case = case.resolved()
        ref = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        alpha_scale = abs(ref.alpha) if ref.alpha != 0 else 1.0
        for mesh in meshes:
            solves: dict[str, list] = {b: [] for b in names}
            for _ in range(repeat):
                for b in names:
                    with backend(b):
                        solves[b].append(cold_solve(case, mesh))
            (fs, ts), (fc, tc) = (min(solves[b], key=lambda r: r[1]) for b in names)
            # the solves' mesh, made again (from the cache): its preset, refined as they were
            pre = fem.mesh.preset(mesh)
            pre = replace(pre, refine=pre.refine * fs.info["refined"])
            guess = fem.locate_contact(case.punch, case.P, case.s_load, E=case.block_E, nu=case.nu,
                                       tilt=case.tilt)
            sub = fem.make_substrate(pre.spec(*guess, (-case.punch.b, case.punch.b)))
            first = (case, sub) if k == 0 else first
            cond = {b: min((elasticity.condense(sub, case.block_E, case.nu, backend=b, cached=False)
                            for _ in range(repeat)), key=lambda sc: sc.timings["factorise"])
                    for b in names}
            C_s, C_c = cond["scipy"].C, cond["cholmod"].C
            W = fs.a + fs.c
            da = abs(fs.alpha - fc.alpha) / alpha_scale
            same = all(np.array_equal(fs.x_nodes, x) for x in (fc.x_nodes, cond["scipy"].x))
            t_cond = {b: cond[b].timings["factorise"] for b in names}
            for b, t in zip(names, (ts, tc)):
                total[b]["cond"] += t_cond[b]
                total[b]["solve"] += t
            print(f"{case.name:14s} {mesh:8s} {fs.diagnostics.dofs:7d} {len(fs.x_nodes):5d} "
                  + " ".join(f"{t_cond[b]:12.3f}" for b in names)
                  + f" {t_cond['scipy'] / t_cond['cholmod']:6.2f} {ts:13.3f} {tc:13.3f} "
                  f"{ts / tc:6.2f} {'yes' if same else 'no':>4s} "
                  f"{np.max(np.abs(C_s - C_c)) / np.max(np.abs(C_s)):9.1e} "
                  f"{abs(fs.a - fc.a) / W:9.1e} {abs(fs.c - fc.c) / W:9.1e} {da:9.1e}", flush=True)
    print(f"{'all':14s} {'':8s} {'':7s} {'':5s} "
          + " ".join(f"{total[b]['cond']:12.3f}" for b in names)
          + f" {total['scipy']['cond'] / total['cholmod']['cond']:6.2f} "
          + " ".join(f"{total[b]['solve']:13.3f}" for b in names)
          + f" {total['scipy']['solve'] / total['cholmod']['solve']:6.2f}")
    if first is not None:
        case, sub = first
        two = {b: min((elasticity.condense(sub, case.block_E, case.nu, ("u^1", "u^2"), backend=b,
                                            cached=False)
                       for _ in range(repeat)), key=lambda sc: sc.timings["factorise"])
               for b in names}
        t2 = {b: two[b].timings["factorise"] for b in names}
        dC = np.max(np.abs(two["scipy"].C - two["cholmod"].C)) / np.max(np.abs(two["scipy"].C))
        print(f"two components ({case.name}, {sub.mesh.p.shape[1]} vertices, "
              f"{two['scipy'].C.shape[0]} condensed DOFs): scipy {t2['scipy']:.3f} s, cholmod "
              f"{t2['cholmod']:.3f} s, ratio {t2['scipy'] / t2['cholmod']:.2f}, "
              f"max |dC|/|C| {dC:.1e}")


if __name__ == "__main__":
    import argparse

    from threepart.fem.mesh import PRESETS

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("meshes", nargs="*", metavar="MESH",
                        help=f"mesh presets (default: quick default), of {', '.join(sorted(PRESETS))}")
    tables = {"peer": peer, "backends": backends, "pressure": lambda _: pressure()}
    for flag in tables:
        parser.add_argument(f"--{flag}", action="store_true", help=f"only the {flag} table")
    args = parser.parse_args()
    unknown = [m for m in args.meshes if m not in PRESETS]
    if unknown:
        parser.error(f"`MESH` = {unknown[0]!r} is not a mesh preset (the presets: {', '.join(sorted(PRESETS))})")
    chosen = args.meshes or ["quick", "default"]
    only = [flag for flag in tables if getattr(args, flag)]
    if not only:   # everything but the pressure study
        main(chosen)
        only = ["peer", "backends"]
    for flag in only:
        tables[flag](chosen)

"""Time the FE model on the quick and default meshes, side by side with the closed form.

Run ``python benchmarks/bench_fem.py [quick default ...] [--peer]``. For each case of the
catalogue's ``"fem"`` suite (Hertz; case A symmetric and with unequal radii and a
moment; case B; case C; a general finite R; suppressed tilt; near lift-off) it
prints the FE errors against ``closedform.solve_normal`` at the case's compliance
``A = rigid_punch(E, nu)``: ``a`` and ``c`` in units of the contact width W,
``alpha`` relative, both peak pressures and the interior pressure (5 % of W
excluded at each edge) relative to the largest peak, with DOFs and times. Then,
side by side in the same run (every FE solve cold: no cached contact estimate,
with its time per stage), the FFT-BEM peer tamaas (:mod:`peer_tamaas`, a
benchmark extra) on the tilt-free cases, with the ratio of each FEM preset's time
to tamaas' time to 4e-5 (``--peer``: that table only).
"""
from __future__ import annotations

import sys
import time

import numpy as np

from threepart import closedform, fem
from threepart.catalogue import load_cases


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


#: the stages of one FE solve, as in ``FemResult.timings``
STAGES = ("locate", "mesh", "assemble", "factorise", "contact")


def cold_solve(case, mesh: str):
    """One FE solve of ``case`` without the run's cached contact estimate, and its wall time."""
    fem.solve._locate.cache_clear()
    t0 = time.perf_counter()
    fe = fem.solve_normal(case.punch, case.P, case.s_load, E=case.E, nu=case.nu, tilt=case.tilt,
                          mesh=mesh)
    return fe, time.perf_counter() - t0


def main(meshes: list[str]) -> None:
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
            print(f"{case.name:14s} {mesh:8s} {fe.dofs:7d} {t_fe:6.2f} {t_cf:7.4f} "
                  + " ".join(f"{v:+9.1e}" for v in err.values())
                  + "   " + " ".join(f"{fe.timings[k]:.2f}" for k in STAGES), flush=True)


#: the tilt-free cases the FFT-BEM peer can solve (it has no rigid-body tilt unknown)
PEER_CASES = ("caseA_sym", "suppressed")
#: tamaas grid densities (cells per contact width), on a period of 64 W
PEER_CELLS = (512, 1024, 2048)


def peer(meshes: list[str]) -> None:
    """FEM presets and tamaas on the same tilt-free cases, timed side by side in this run.

    Errors are against the closed form: a, c in units of W, pressure at each
    method's own nodes more than 5 % of W inside the ends, of the peak.
    """
    from peer_tamaas import available, solve_peer

    if not available():
        print("tamaas is not installed: pip install -e '.[bench]' to time the FFT-BEM peer")
        return
    print(f"\n{'case':12s} {'method':16s} {'time s':>7s} {'a/W':>9s} {'c/W':>9s} {'p':>9s}")
    for name in PEER_CASES:
        case = next(c for c in load_cases("fem") if c.name == name).resolved()
        ref = closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        W = ref.a + ref.c
        peak = max(q.p for q in ref.peaks())

        def row(method: str, dt: float, a: float, c: float, x: np.ndarray,
                p: np.ndarray) -> tuple[float, float]:
            inner = (x > -ref.a + 0.05 * W) & (x < ref.c - 0.05 * W)
            perr = float(np.max(np.abs(p[inner] - ref.pressure(x[inner])))) / peak
            ends = max(abs(a - ref.a) / W, abs(c - ref.c) / W)
            print(f"{name:12s} {method:16s} {dt:7.2f} {abs(a - ref.a) / W:9.1e} "
                  f"{abs(c - ref.c) / W:9.1e} {perr:9.1e}", flush=True)
            return ends, max(ends, perr)

        times: dict[str, tuple[float, tuple[float, float]]] = {}
        for mesh in meshes:
            fe, dt = cold_solve(case, mesh)
            times[f"fem {mesh}"] = (dt, row(f"fem {mesh}", dt, fe.a, fe.c, fe.x_nodes, fe.p_nodes))
        for cells in PEER_CELLS:
            r = solve_peer(case.punch, case.P, E=case.E, nu=case.nu, width=W, cells=cells)
            times[f"tamaas {cells}/W"] = (r.time_s, row(f"tamaas {cells}/W", r.time_s, r.a, r.c, r.x, r.p))
        # tamaas' time to 4e-5: its coarsest grid that gets there, else its finest (said so);
        # judged on a and c alone, then on a, c and the pressure
        for which, label in ((0, "a, c"), (1, "a, c, p")):
            peers = [(key, t, e[which]) for key, (t, e) in times.items() if key.startswith("tamaas")]
            key_p, t_p, e_p = next(((k, t, e) for k, t, e in peers if e <= 4e-5), peers[-1])
            for key, (t, e) in times.items():
                if key.startswith("fem"):
                    print(f"{'':12s} [{label}] {key}: time / {key_p} ({e_p:.1e}) = {t / t_p:.2f}, "
                          f"its worst error {e[which]:.1e}")


if __name__ == "__main__":
    chosen = [a for a in sys.argv[1:] if a != "--peer"] or ["quick", "default"]
    if "--peer" not in sys.argv[1:]:
        main(chosen)
    peer(chosen)

"""Time the FE model on the quick and default meshes, side by side with the closed form.

Run ``python benchmarks/bench_fem.py [quick default ...]``. For each case of the
catalogue's ``"fem"`` suite (Hertz; case A symmetric and with unequal radii and a
moment; case B; case C; a general finite R; suppressed tilt; near lift-off) it
prints the FE errors against ``closedform.solve_normal`` at the case's compliance
``A = rigid_punch(E, nu)``: ``a`` and ``c`` in units of the contact width W,
``alpha`` relative, both peak pressures and the interior pressure (5 % of W
excluded at each edge) relative to the largest peak, with DOFs and times.
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


def main(meshes: list[str]) -> None:
    print(f"{'case':14s} {'mesh':8s} {'dofs':>7s} {'t_fem':>6s} {'t_cf':>7s} "
          + " ".join(f"{k:>9s}" for k in ("a/W", "c/W", "alpha", "s/W", "p_left", "p_right", "p_int")))
    for case in load_cases("fem"):
        case = case.resolved()
        s = case.s_load
        t0 = time.perf_counter()
        ref = closedform.solve_normal(case.punch, case.P, s, A=case.A, tilt=case.tilt)
        t_cf = time.perf_counter() - t0
        for mesh in meshes:
            t0 = time.perf_counter()
            fe = fem.solve_normal(case.punch, case.P, s, E=case.E, nu=case.nu, tilt=case.tilt, mesh=mesh)
            t_fe = time.perf_counter() - t0
            err = errors(fe, ref)
            print(f"{case.name:14s} {mesh:8s} {fe.dofs:7d} {t_fe:6.2f} {t_cf:7.4f} "
                  + " ".join(f"{v:+9.1e}" for v in err.values()), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or ["quick", "default"])

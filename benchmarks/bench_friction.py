"""Time the two-body Coulomb-friction FE model, with its breakdown per stage, against the closed form.

Run ``python benchmarks/bench_friction.py [quick default fine ...]``. For each
partial-slip case of the catalogue (caseA_moment at Q/fP = 0.2, 0.4, 0.7, and
0.9, where the stick zone ends on the flat centre and the SIE is the reference)
it solves ``fem.solve_partial_slip`` cold (no cached contact estimate) and
prints the errors in a, c (units of W), d, e (units of d) and the interior
shear (units of max|q|), with the wall time of each stage: locating the contact
and the stick zone, meshing, assembly, factorisation (condensation of both
components), the normal solve and the friction iterations. Issue 11's budget is
60 s per solve on the default mesh.

Then one fretting cycle (Q/fP = 0.4, 21 states per branch) per mesh, with the
energy dissipated per cycle, its balance check (friction work against the area
of the Q–xi loop) and the time.

Last, partial slip under a bulk stress (issue 21): Hertz (``Punch(R, R, 0)``) at
Q/fP = 0.4 with ``sigma_bulk`` = 0, 0.5 f p0 and 1.5 f p0 (past the reversal
threshold 4 (1 - sqrt(1 - Q/fP)) f p0 = 0.90 f p0), side by side: d and e
against Cattaneo and Nowell & Hills (``e = -sign(Q) a sigma_bulk / (4 f p0)``),
in units of W, the wall time and its ratio to the solve without the bulk
stress. Issue 21's budget is 60 s per solve with a bulk stress. ``bench_friction.py
bulk default`` runs only this part.
"""
from __future__ import annotations

import math
import time

import numpy as np

from threepart import fem
from threepart.problem.catalogue import get_case
from threepart.fem.method import pair_modulus
from threepart.problem.material import similar_pair
from threepart.problem.punch import Punch
from threepart.reports.compare import compare
from threepart.reports import solvers

CASES = ("slip_Q0.2", "slip_Q0.4", "slip_Q0.7", "beyond_stick_centre")
#: the stages of one partial-slip solve, as in its ``timings``
STAGES = ("locate", "mesh", "assemble", "factorise", "bulk", "normal", "friction")
SHOWN = ("a", "c", "d", "e", "q_interior_max")


def reference(case):
    """The closed form's partial-slip solution, or the SIE's where the closed form refuses."""
    method = "sie" if case.closedform_refuses else "closedform"
    return method, solvers.slip(method, case, solvers.normal(method, case))


def cold(case, mesh: str):
    """One partial-slip solve of ``case`` without the run's cached contact estimate, and its time."""
    fem.solve.locate_ends.cache_clear()
    t0 = time.perf_counter()
    res = solvers.slip("fem", case, None, mesh=mesh)
    return res, time.perf_counter() - t0


def main(meshes: list[str]) -> None:
    print(f"{'case':<20} {'mesh':<8} {'ref':<10} " + " ".join(f"{q:>14}" for q in SHOWN)
          + f" {'total s':>8}  " + " ".join(f"{s:>9}" for s in STAGES))
    for name in CASES:
        case = get_case(name).resolved()
        method, ref = reference(case)
        for mesh in meshes:
            res, dt = cold(case, mesh)
            errs = {c.quantity: c.error for c in compare(ref, res, "sie")}
            t = res.diagnostics.timings
            print(f"{name:<20} {mesh:<8} {method:<10} " + " ".join(f"{errs[q]:14.2e}" for q in SHOWN)
                  + f" {dt:8.2f}  " + " ".join(f"{t.get(s, 0.0):9.2f}" for s in STAGES))
    case = get_case("slip_Q0.4").resolved()
    Q, f = case.shear_load
    print("\nfretting cycle, caseA_moment at Q_max/fP = 0.4, 21 states per branch")
    for mesh in meshes:
        fem.solve.locate_ends.cache_clear()
        t0 = time.perf_counter()
        cyc = fem.fretting_cycle(case.punch, case.P, case.s_load, Q_max=Q, f=f,
                                 E=pair_modulus(case.A, case.nu), nu=case.nu, mesh=mesh)
        dt = time.perf_counter() - t0
        balance = cyc.info["loop_energy"] / cyc.energy - 1
        print(f"  {mesh:<8} energy {cyc.energy:.6e} N mm/mm per cycle, balance {balance:.1e}, "
              f"{dt:.2f} s (friction iterations {cyc.diagnostics.timings['friction']:.2f} s)")
    bulk(meshes)


def bulk(meshes: list[str], E: float = 210e3, nu: float = 0.3, R: float = 50.0, P: float = 1000.0,
         f: float = 0.5, ratio: float = 0.4) -> None:
    """Hertz partial slip with and without a bulk stress: d, e against Nowell & Hills, and the time."""
    A = similar_pair(E, nu)
    a = math.sqrt(2 * P * A * R / math.pi)
    p0 = 2 * P / (math.pi * a)
    Q, W = ratio * f * P, 2 * a
    d_ref = a * math.sqrt(1 - ratio)
    print(f"\nHertz partial slip under a bulk stress, Q/fP = {ratio}, a = {a:.6g} mm, "
          f"p0 = {p0:.6g} MPa (reversal past sigma_bulk/f p0 = {4 * (1 - math.sqrt(1 - ratio)):.3f})")
    for mesh in meshes:
        base = math.nan
        for k in (0.0, 0.5, 1.5):
            sb = k * f * p0
            fem.solve.locate_ends.cache_clear()
            t0 = time.perf_counter()
            res = fem.solve_partial_slip(Punch(R, R, 0.0), P, 0.0, Q=Q, f=f, E=E, nu=nu,
                                         mesh=mesh, sigma_bulk=sb, progress=False)
            dt = time.perf_counter() - t0
            base = dt if k == 0.0 else base
            e_ref = -a * sb / (4 * f * p0)
            lo, hi = res.stick_zone
            st = res.history[-1]
            back = (np.sign(st.t) == -np.sign(Q)) & ~st.stick & (st.fn > 0)
            nh = (f"(N&H {e_ref:.6g}, err {abs(res.e - e_ref) / W:.1e} W)" if not back.any() else
                  f"(reversed slip on [{res.x_nodes[back].min() / a:+.4f}, "
                  f"{res.x_nodes[back].max() / a:+.4f}] a; N&H no longer holds)")
            print(f"  {mesh:<8} sigma_bulk = {k:.1f} f p0 = {sb:8.3f} MPa: d {res.d:.6g} "
                  f"(err {abs(res.d - d_ref) / W:.1e} W), e {res.e:.6g} {nh}, stick "
                  f"[{lo / a:+.4f}, {hi / a:+.4f}] a, {dt:6.2f} s ({dt / base:.2f}x the solve without)")


if __name__ == "__main__":
    import argparse

    from threepart.fem.mesh import PRESETS

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("meshes", nargs="*", metavar="MESH",
                        help=f"mesh presets (default: quick default), of {', '.join(sorted(PRESETS))}; "
                             "a first word 'bulk' runs only the bulk-stress part")
    args = parser.parse_args().meshes
    only_bulk = args[:1] == ["bulk"]     # only the bulk-stress part: bench_friction.py bulk default
    meshes = args[1:] if only_bulk else args
    unknown = [m for m in meshes if m not in PRESETS]
    if unknown:
        parser.error(f"`MESH` = {unknown[0]!r} is not a mesh preset (the presets: {', '.join(sorted(PRESETS))})")
    (bulk if only_bulk else main)(meshes or ["quick", "default"])

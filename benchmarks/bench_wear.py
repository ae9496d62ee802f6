"""Benchmark: 10^6 cycles of the catalogue's fan-blade flank worn by the SIE and by the FEM (issue 39).

Run ``python benchmarks/bench_wear.py`` from the repository root (``--profile`` adds
where the time goes). It marches :data:`CASE` (``threepart wear --case
fan_blade_flank_wear``) with each method in turn, in one run, and prints the wall and
CPU times against issue 39's targets (:data:`TARGETS_S`, alone on the machine), the
steps, the cycles reached, the energy per cycle and the FEM's worn depth against the
SIE's (of the SIE's largest depth).
"""
from __future__ import annotations

import cProfile
import os
import pstats
import time

import numpy as np

from threepart.fretting_wear import wear_case

#: the catalogue's wear case
CASE = "fan_blade_flank_wear"
#: issue 39's targets, seconds alone on the machine
TARGETS_S = {"sie": 60.0, "fem": 600.0}
#: functions listed under --profile
TOP = 12


def march(method: str, profile: bool) -> object:
    wc = wear_case(CASE)
    options = {} if method == "sie" else dict(zip(("E", "nu"), wc.case.material))
    prof = cProfile.Profile() if profile else None
    load = os.getloadavg()[0]
    w0, c0 = time.perf_counter(), time.process_time()
    if prof is not None:
        prof.enable()
    r = wc.run(method=method, **options)
    if prof is not None:
        prof.disable()
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"{method}: {CASE}, {wc.law} law, k = {wc.k:g} mm^2/N, {wc.cycles:,} cycles requested")
    print(f"  wall {wall:.1f} s, CPU {cpu:.1f} s (target {TARGETS_S[method]:g} s alone; load average "
          f"{load:.2f} before, {os.getloadavg()[0]:.2f} after, {os.cpu_count()} CPUs)")
    print(f"  {int(r.cycles[-1]):,} cycles reached in {r.info['steps']} steps ({len(r.x)} "
          f"{'nodes' if method == 'sie' else 'interface nodes'})")
    if r.info["stopped"]:
        print(f"  stopped: {r.info['stopped']}")
    print(f"  energy per cycle {r.energy[0]:.6g} -> {r.energy[-1]:.6g} N*mm/mm ({r.energy[-1] / r.energy[0]:.4f} "
          f"of the start, peak {max(r.energy) / r.energy[0]:.3f})")
    if prof is not None:
        pstats.Stats(prof).sort_stats("cumulative").print_stats(TOP)
    return r


def main(profile: bool) -> None:
    sie = march("sie", profile)
    fem = march("fem", profile)
    top = float(np.max(sie.depths[-1]))
    diff = np.max(np.abs(np.interp(fem.x, sie.x, sie.depths[-1]) - fem.depths[-1])) / top
    print(f"FEM worn depth against the SIE's after {int(fem.cycles[-1]):,} cycles: {diff:.3g} of the SIE's "
          f"largest depth {top:.4g} mm (issue 39's target 3e-2)")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--profile", action="store_true", help="where the time goes (cProfile of each march)")
    main(parser.parse_args().profile)

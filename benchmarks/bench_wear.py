"""Benchmark: 10^6 cycles of the catalogue's fan-blade flank worn by the SIE (issue 39: under a minute).

Run ``python benchmarks/bench_wear.py`` from the repository root (``--profile`` adds
where the time goes). It marches :data:`CASE` (``threepart wear --case
fan_blade_flank_wear``) and prints the wall and CPU times, the steps, the cycles
reached (the march stops early, and says why, when the worn profile's bounded
contact turns tensile past its floor: sie/wear.py), the energy per cycle and the
split of the time between the march's parts: each step's normal contact on the
worn profile, the stick zone at Q_max and the wear rate, and the fretting cycle
on the last worn profile.
"""
from __future__ import annotations

import cProfile
import os
import pstats
import sys
import time

from threepart.errors import ThreepartError
from threepart.fretting_wear import wear_case

#: the catalogue's wear case
CASE = "fan_blade_flank_wear"
#: issue 39's target, seconds alone on the machine
TARGET_S = 60.0
#: the march's parts, by the function that does each (module file, function name)
PARTS = {"normal contact of each step (sie.profile.solve_profile)": ("profile.py", "solve_profile"),
         "stick zone at Q_max and wear rate (sie.wear.wear_rate)": ("wear.py", "wear_rate"),
         "fretting cycle on the last profile (sie.wear.profile_fretting_cycle)": ("wear.py",
                                                                                    "profile_fretting_cycle"),
         "  of which the worn profile's gap series (sie.profile.profile_gap)": ("profile.py", "profile_gap"),
         "  of which the worn depth's Chebyshev coefficients (WornProfile.coefficients)": ("profile.py",
                                                                                         "coefficients")}


def main(profile: bool) -> None:
    wc = wear_case(CASE)
    load = os.getloadavg()[0]
    prof = cProfile.Profile() if profile else None
    w0, c0 = time.perf_counter(), time.process_time()
    if prof is not None:
        prof.enable()
    r = wc.run()
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    print(f"{CASE}: {wc.law} law, k = {wc.k:g} mm^2/N, {wc.cycles:,} cycles requested")
    print(f"  wall {wall:.1f} s, CPU {cpu:.1f} s (target {TARGET_S:g} s alone; load average {load:.2f} before, "
          f"{os.getloadavg()[0]:.2f} after, {os.cpu_count()} CPUs)")
    print(f"  {int(r.cycles[-1]):,} cycles reached in {r.info['steps']} steps "
          f"({len(r.x)} knots, n = {r.info['n']})")
    if r.info["stopped"]:
        print(f"  stopped: {r.info['stopped']}")
    w1 = time.perf_counter()
    try:
        _ = r.final
        final = "solved"
    except (ThreepartError, ValueError) as exc:
        final = f"not solved: {type(exc).__name__}: {' '.join(str(exc).split())[:160]}"
    print(f"  the fretting cycle on the last worn profile (WearResult.final, on demand): "
          f"{time.perf_counter() - w1:.1f} s, {final}")
    if prof is not None:
        prof.disable()
    print(f"  energy per cycle {r.energy[0]:.6g} -> {r.energy[-1]:.6g} N*mm/mm ({r.energy[-1] / r.energy[0]:.3f} "
          f"of the start, peak {max(r.energy) / r.energy[0]:.3f})")
    if prof is None:
        return
    stats = pstats.Stats(prof)
    total = sum(v[3] for k, v in stats.stats.items()                         # type: ignore[attr-defined]
                if k[2] in ("march", "final"))
    print(f"  where the time goes (cumulative, of the march and the final cycle's {total:.1f} s under the "
          "profiler):")
    for label, (fname, func) in PARTS.items():
        t = sum(v[3] for k, v in stats.stats.items()                         # type: ignore[attr-defined]
                if k[0].endswith(os.sep + fname) and k[2] == func)
        print(f"    {label:<80} {t:7.2f} s  {t / total:6.1%}")


if __name__ == "__main__":
    main("--profile" in sys.argv[1:])

"""Speed of the steady state of an in-phase cycle by each method, side by side (issue 31).

    python benchmarks/bench_steady.py [--mesh default] [--repeat 20] [--json out.json]

The cycle is the README's: case A (``R1 = 10``, ``R2 = 5``, ``b = 1``), ``f = 0.5``,
``E = 210 GPa``, ``nu = 0.3``, the ends ``(400, 0.1, -80, -20)`` and
``(450, 0.15, 80, 20)``: ``P``, ``s``, ``Q`` and ``sigma_bulk`` all change. Timed:

- ``closed form``: :func:`threepart.closedform.steady_state`, best of ``--repeat`` (a case);
- ``SIE steady state``: :func:`threepart.sie.steady_state` at its default ``n``, once;
- ``SIE history, 200 states``: :func:`threepart.sie.load_history` (n = 400) through the
  first loading (20 states) and 4.5 cycles of the same ends (40 states a cycle), once;
- ``FEM steady state``: :func:`threepart.fem.steady_state` on ``--mesh``, meshing included, once.

It prints each time beside its target (closed form < 5 ms a case, SIE history < 10 s,
FEM default mesh < 180 s) and the FEM's stick-zone ends (of W) and energy against the
closed form's. Measured 2026-11-26 on the 2-core machine shared with five other jobs
(load average 13.6): see the README's steady-state paragraph.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from threepart import closedform as cf
from threepart import fem, sie
from threepart.fem.method import pair_modulus
from threepart.problem.punch import Punch
from threepart.halfplane.steady import ramp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_sie import best_time  # noqa: E402  (the benchmarks' one timer)

PUNCH = Punch(R1=10.0, R2=5.0, b=1.0)
F, E, NU = 0.5, 210e3, 0.3
A = 4 * (1 - NU**2) / E          # two similar bodies of E, nu (eq. 4)
ENDS = [(400.0, 0.1, -80.0, -20.0), (450.0, 0.15, 80.0, 20.0)]
#: targets, seconds
TARGETS = {"closed form": 5e-3, "SIE history, 200 states": 10.0, "FEM steady state": 180.0}


def history_200() -> list[tuple[float, ...]]:
    """20 states of first loading (all four together), then 180 of the cycle, 20 a half-cycle."""
    st0, st1 = ENDS
    lam = np.arange(1, 21) / 20
    first = list(zip(*ramp((0.0, st0[1], 0.0, 0.0), st0, lam)))
    up = list(zip(*ramp(st0, st1, lam)))
    down = list(zip(*ramp(st1, st0, lam)))
    return [*first, *((up + down) * 5)[:180]]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--mesh", default="default")
    parser.add_argument("--repeat", type=int, default=20)
    parser.add_argument("--json")
    args = parser.parse_args()

    rows: dict[str, float] = {}
    rows["closed form"], ref = best_time(lambda: cf.steady_state(PUNCH, ENDS, F, A=A), args.repeat)
    rows["SIE steady state"], _ = best_time(lambda: sie.steady_state(PUNCH, ENDS, F, A=A), 1)
    states = history_200()
    rows["SIE history, 200 states"], _ = best_time(lambda: sie.load_history(PUNCH, states, F, A=A), 1)
    t = time.perf_counter()
    got = fem.steady_state(PUNCH, ENDS, F, E=pair_modulus(A, NU), nu=NU, mesh=args.mesh, progress=False)
    rows["FEM steady state"] = time.perf_counter() - t

    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} on {os.cpu_count()} cores")
    print(f"{'':28s} {'time':>10s} {'target':>10s}")
    for name, secs in rows.items():
        target = TARGETS.get(name)
        mark = "" if target is None else ("ok" if secs < target else "OVER")
        print(f"{name:28s} {secs:10.4g} {'-' if target is None else f'{target:.4g}':>10s} {mark}")
    W = ref.normals[0].a + ref.normals[0].c
    zone = float(np.abs(np.array(got.stick_zone) - np.array(ref.stick_zone)).max() / W)
    energy = got.energy / ref.energy - 1
    print(f"FEM ({args.mesh}, h = {got.diagnostics.h:.3g} mm, {got.diagnostics.dofs} DOFs, "
          f"{got.info['cycles']} cycles): stick-zone ends {zone:.2e} W, energy {energy:+.2e} "
          "against the closed form")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"times_s": rows, "load": load, "fem_zone_W": zone, "fem_energy": energy}, fh, indent=1)


if __name__ == "__main__":
    main()

"""Speed and accuracy of the half-plane stress field on a 200 x 100 grid.

    python benchmarks/bench_stress.py [--repeat 3] [--json out.json]

The grid: x over [-1.5 a, 1.5 c], z over (0, 2W] (W = a + c), 200 x 100 points.

- Hertz, sliding with q = f p (f = 0.3): time, and the largest error against McEwen's
  closed form (Johnson eqs. 7.17-7.18) over the grid, and against the Hertz axis formula
  (Johnson eq. 4.47) at x = 0 on the grid's depths.
- caseA_moment of the catalogue, closed-form pressure, frictionless and in partial slip at
  Q = 0.4 f P (f = 0.5; kinks at the joins and the stick-zone ends): time, and the largest
  difference on every 7th grid point from a rule with twice the nodes per panel and finer
  grading (there is no closed form to compare with).

All errors are fractions of p0 = max p.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

import threepart.stress.flamant as st
from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.stress import stress

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # the tests' references
from tests.stress_reference import mcewen as _mcewen  # noqa: E402
from bench_sie import best_time as best_of  # noqa: E402  (the benchmarks' one timer)

F = 0.3


def mcewen(x, z, a=1.0, p0=1.0, q0=F):
    """McEwen's stresses of a Hertz line contact sliding with q = f p (tests/stress_reference.py)."""
    return _mcewen(x, z, a=a, p0=p0, q0=q0)


def grid(a: float, c: float) -> tuple[np.ndarray, np.ndarray]:
    W = a + c
    return np.linspace(-1.5 * a, 1.5 * c, 200)[:, None], np.linspace(0.0, 2 * W, 101)[1:][None, :]


def worst(S, ref) -> float:
    return max(float(np.max(np.abs(u - v))) for u, v in zip((S.sxx, S.szz, S.sxz), ref))


def fine_difference(S, x, z, kw) -> float:
    """Largest difference on every 7th grid point from a rule of twice the nodes, finer grading."""
    xs, zs = np.broadcast_arrays(x, z)
    sel = (slice(None, None, 7), slice(None, None, 7))
    saved = dict(st.RULE)
    try:
        st.RULE.update(n=24, ratio=0.5, levels=30, min_levels=30)
        fine = stress(xs[sel], zs[sel], **kw)
    finally:
        st.RULE.update(saved)
    return worst(fine, (S.sxx[sel], S.szz[sel], S.sxz[sel]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json")
    args = parser.parse_args()
    out: dict[str, dict[str, float]] = {}

    p = lambda t: np.sqrt(np.clip(1.0 - np.asarray(t) ** 2, 0.0, None))   # noqa: E731
    q = lambda t: F * p(t)                                                 # noqa: E731
    x, z = grid(1.0, 1.0)
    t, S = best_of(lambda: stress(x, z, pressure=p, shear=q, ends=(-1.0, 1.0)), args.repeat)
    axis = stress(0.0, z.ravel(), pressure=p, ends=(-1.0, 1.0))
    zz = z.ravel()
    root = np.sqrt(1 + zz * zz)
    axis_err = worst(axis, (-((1 + 2 * zz * zz) / root - 2 * zz), -1 / root, 0 * zz))
    out["hertz_mcewen"] = {"seconds": t, "max_error_mcewen": worst(S, mcewen(x, z)),
                           "max_error_hertz_axis": axis_err}

    case = get_case("caseA_moment")
    n = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
    slip = cf.solve_partial_slip(n, 0.4 * 0.5 * case.P, 0.5)
    p0 = float(np.max(n.pressure(np.linspace(-n.a, n.c, 20001))))
    x, z = grid(n.a, n.c)
    b = case.punch.b
    for name, kw in [("caseA_moment", dict(pressure=n.pressure, ends=(-n.a, n.c), kinks=(-b, b))),
                     ("caseA_moment_slip", dict(pressure=n.pressure, shear=slip.shear, ends=(-n.a, n.c),
                                                kinks=(-b, b, *slip.stick_zone)))]:
        t, S = best_of(lambda: stress(x, z, **kw), args.repeat)
        out[name] = {"seconds": t, "max_difference_fine_rule": fine_difference(S, x, z, kw) / p0}

    for name, row in out.items():
        print(f"{name:20s} " + "  ".join(f"{k} {v:.3g}" for k, v in row.items()))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"rule": st.RULE, **out}, fh, indent=1)


if __name__ == "__main__":
    main()

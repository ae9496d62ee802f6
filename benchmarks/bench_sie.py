"""Benchmark: SIE against the closed form, side by side, in one run.

Run ``python benchmarks/bench_sie.py`` from the repository root. For each case of
the catalogue's ``"sie"`` suite it times closedform and the SIE ("projected",
default n) and prints the differences in a, c, alpha, s, the pressure, and the
stick zone, normalised as in :mod:`threepart.tolerances`, against that table's
``"sie"`` limits; then the plain scheme's errors and times against n, with
fitted orders.
"""
from __future__ import annotations

import time

import numpy as np

from threepart import closedform as cf
from threepart import sie
from threepart.problem.catalogue import load_cases, slip_loads
from threepart.convergence import fitted_order
from threepart.reports.compare import compare
from threepart.sie.schemes import Plain, Projected
from threepart.tolerances import tolerance

CASES = {c.name: c.resolved() for c in load_cases("sie")}
SLIP_LOADS = slip_loads("sie")


def best_time(fun, repeat: int = 5) -> tuple[float, object]:
    """Smallest wall time of ``repeat`` calls, and the last result."""
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t)
    return best, out


NORMAL_COLUMNS = ("a", "c", "alpha", "s", "p_interior_max", "p_L2")
SLIP_COLUMNS = ("d", "e", "q_interior_max", "q_L2")


def errors(ref, res, columns) -> dict[str, float]:
    """Normalised errors of ``res`` against ``ref``, as the verification run measures them."""
    return {c.quantity: c.error for c in compare(ref, res, "sie") if c.quantity in columns}


def limits(columns) -> str:
    return ", ".join(f"{q} {tolerance('sie', q).limit:g}" for q in columns)


def normal_table() -> None:
    print("## Normal problem: SIE (projected, n = %d) vs closedform" % sie.normal.DEFAULT_N)
    print(f"{'case':22s} " + " ".join(f"{q:>9.9s}" for q in NORMAL_COLUMNS)
          + f" {'t_cf ms':>8s} {'t_sie ms':>8s} {'t_p ms':>7s}")
    for name, k in CASES.items():
        t_cf, c = best_time(lambda: cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt))
        t_s, r = best_time(lambda: sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt))
        t_p, _ = best_time(lambda: r.pressure(np.linspace(-c.a, c.c, 2001)))
        err = errors(c, r, NORMAL_COLUMNS)
        print(f"{name:22s} " + " ".join(f"{err[q]:9.1e}" for q in NORMAL_COLUMNS)
              + f" {t_cf * 1e3:8.2f} {t_s * 1e3:8.2f} {t_p * 1e3:7.2f}")
    print(f"limits: {limits(NORMAL_COLUMNS)}; <= 50 ms, <= 0.5 s\n")


def slip_table() -> None:
    print("## Partial slip: SIE vs closedform (d, e relative to d; q relative to max |q|)")
    for name, k in CASES.items():
        c = cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
        r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
        for q, f in SLIP_LOADS:
            Q = q * f * k.P
            try:
                t_cf, cs = best_time(lambda: cf.solve_partial_slip(c, Q, f))
            except ValueError as exc:
                cs, t_cf = type(exc).__name__, 0.0
            try:
                t_s, ss = best_time(lambda: sie.solve_partial_slip(r, Q, f))
            except ValueError as exc:
                ss, t_s = type(exc).__name__, 0.0
            if isinstance(cs, str) or isinstance(ss, str):
                print(f"{name:22s} Q/fP={q:5.2f}: closedform {cs if isinstance(cs, str) else 'ok'}, "
                      f"sie {ss if isinstance(ss, str) else 'ok'}")
                continue
            err = errors(cs, ss, SLIP_COLUMNS)
            print(f"{name:22s} Q/fP={q:5.2f}: " + "  ".join(f"{q_} {err[q_]:8.1e}" for q_ in SLIP_COLUMNS)
                  + f"  t_cf {t_cf * 1e3:6.2f} ms  t_sie {t_s * 1e3:6.2f} ms")
    print(f"limits: {limits(SLIP_COLUMNS)}\n")


def plain_study(name: str = "nd_A") -> None:
    k = CASES[name]
    c = cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    m, h = 0.5 * (c.c - c.a), 0.5 * (c.a + c.c)
    x = np.linspace(-c.a, c.c, 2001)[1:-1]
    pc = c.pressure(x)
    P_exact = np.pi * h * Projected(2).moments(k.punch, m, h)[0][1] / (2 * k.A)
    print(f"## Case {name}: errors and times against n (closedform reference)")
    print(f"{'n':>6s} {'plain load':>11s} {'plain a':>9s} {'plain p':>9s} {'t_plain ms':>10s}"
          f" {'proj a':>9s} {'proj p':>9s} {'t_proj ms':>9s}")
    ns = [16, 32, 64, 128, 256, 512, 1024, 1600]
    rows = []
    for n in ns:
        Plain(n).moments(k.punch, m, h)  # factorise once, outside the timing
        t_pl, rp = best_time(lambda: sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt, n=n,
                                                      scheme="plain"), 3)
        t_pr, rj = best_time(lambda: sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt, n=n), 3)
        P_n = np.pi * h * Plain(n).moments(k.punch, m, h)[0][1] / (2 * k.A)
        row = (abs(P_n / P_exact - 1), abs(rp.a / c.a - 1), np.abs(rp.pressure(x) - pc).max() / pc.max(),
               abs(rj.a / c.a - 1), np.abs(rj.pressure(x) - pc).max() / pc.max())
        rows.append(row)
        print(f"{n:6d} {row[0]:11.2e} {row[1]:9.2e} {row[2]:9.2e} {t_pl * 1e3:10.2f}"
              f" {row[3]:9.1e} {row[4]:9.2e} {t_pr * 1e3:9.2f}")
    e = np.array(rows)
    for j, label in [(0, "plain load"), (1, "plain a"), (2, "plain pressure"), (4, "projected pressure")]:
        p, C = fitted_order(1.0 / np.asarray(ns, dtype=float), e[:, j])
        print(f"fitted order, {label}: {p:.2f} (C = {C:.2g})")
    print()


if __name__ == "__main__":
    normal_table()
    slip_table()
    plain_study("nd_A")
    plain_study("nd_general")

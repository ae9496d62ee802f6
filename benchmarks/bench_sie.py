"""Benchmark: SIE against the closed form, side by side, in one run (issue 3 targets).

Run ``python benchmarks/bench_sie.py`` from the repository root. For each case of
:data:`sie.cases.CASES` it times closedform and the SIE ("projected", default n)
and prints the differences in a, c, alpha, s, the pressure, and the stick zone,
against the targets of :data:`sie.tolerances.TOLERANCES`; then the plain
scheme's errors and times against n, with fitted orders.
"""
from __future__ import annotations

import time

import numpy as np

from threepart import closedform as cf
from threepart import sie
from threepart.sie.cases import CASES, SLIP_LOADS
from threepart.sie.schemes import Plain, Projected
from threepart.sie.tolerances import TOLERANCES as TOL


def best_time(fun, repeat: int = 5) -> tuple[float, object]:
    """Smallest wall time of ``repeat`` calls, and the last result."""
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t)
    return best, out


def normal_table() -> None:
    print("## Normal problem: SIE (projected, n = %d) vs closedform" % sie.normal.DEFAULT_N)
    print(f"{'case':20s} {'d(a,c)/W':>9s} {'rel a,c':>9s} {'alpha':>9s} {'s':>9s} {'p/peak':>9s}"
          f" {'t_cf ms':>8s} {'t_sie ms':>8s} {'t_p ms':>7s}")
    for name, k in CASES.items():
        t_cf, c = best_time(lambda: cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt))
        t_s, r = best_time(lambda: sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt))
        W = c.a + c.c
        x = np.linspace(-c.a, c.c, 2001)
        t_p, ps = best_time(lambda: r.pressure(x))
        pc = c.pressure(x)
        slope = W / min(k.punch.R1, k.punch.R2)
        print(f"{name:20s} {max(abs(r.a - c.a), abs(r.c - c.c)) / W:9.1e} "
              f"{max(abs(r.a / c.a - 1), abs(r.c / c.c - 1)):9.1e} "
              f"{abs(r.alpha - c.alpha) / max(abs(c.alpha), slope):9.1e} "
              f"{abs(r.s - c.s) / max(abs(c.s), W):9.1e} {np.abs(ps - pc).max() / pc.max():9.1e} "
              f"{t_cf * 1e3:8.2f} {t_s * 1e3:8.2f} {t_p * 1e3:7.2f}")
    print(f"targets: a,c {TOL['ends_rel'].value:g} rel and {TOL['ends_width'].value:g} W; alpha, s "
          f"{TOL['alpha'].value:g}; pressure {TOL['pressure_peak'].value:g} of peak; <= 50 ms, <= 0.5 s\n")


def slip_table() -> None:
    print("## Partial slip: SIE vs closedform (d, e relative to d; q relative to max |q|)")
    for name, k in CASES.items():
        c = cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
        r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
        x = np.linspace(-c.a, c.c, 2001)
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
                print(f"{name:20s} Q/fP={q:5.2f}: closedform {cs if isinstance(cs, str) else 'ok'}, "
                      f"sie {ss if isinstance(ss, str) else 'ok'}")
                continue
            qc = cs.shear(x)
            print(f"{name:20s} Q/fP={q:5.2f}: d {abs(ss.d - cs.d) / cs.d:8.1e}  e {abs(ss.e - cs.e) / cs.d:8.1e}"
                  f"  q {np.abs(ss.shear(x) - qc).max() / np.abs(qc).max():8.1e}"
                  f"  t_cf {t_cf * 1e3:6.2f} ms  t_sie {t_s * 1e3:6.2f} ms")
    print(f"target: d, e {TOL['stick_rel'].value:g}\n")


def plain_study(name: str = "A") -> None:
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
        p, C = sie.observed_order(ns, e[:, j])
        print(f"fitted order, {label}: {p:.2f} (C = {C:.2g})")
    print()


if __name__ == "__main__":
    normal_table()
    slip_table()
    plain_study("A")
    plain_study("general")

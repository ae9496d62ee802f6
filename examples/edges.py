"""The edges of a contact: the asymptotic multipliers K_N, K_T and the slip zone they predict.

Run it from anywhere (it writes no file)::

    python examples/edges.py

Near an edge every contact looks alike (docs/EDGES.md): at a distance ``r``
inside it the pressure is ``p ≈ K_N √r`` (eq. E1), a fully stuck shear would be
``q ≈ K_T / √r`` (E3), and a small shear slips over ``2 |K_T| / (f K_N)``
(Mindlin's asymptotic slip zone, E5). Every result's ``edges()`` gives them.
For a cylinder they are ``K_N = p0 sqrt(2/a)`` and ``K_T = Q / (pi sqrt(2a))``,
and the slip zone tends to Cattaneo's ``a (1 - sqrt(1 - Q/(f P)))`` as ``Q -> 0``.
"""
from __future__ import annotations

import math

from threepart import Punch, SlipResult, similar_pair, solve

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, f = 400.0, 0.5

# -- a cylinder: Hertz and Cattaneo-Mindlin -------------------------------------------------------
cylinder = Punch(R1=10.0, R2=10.0, b=0.0)
for Q in (100.0, 10.0, 1.0):
    r = solve(cylinder, P=P, s=0.0, A=A, Q=Q, f=f)
    assert isinstance(r, SlipResult)       # Q and f given: a partial slip
    left, right = r.edges()
    exact = r.a - r.stick_zone[1]                          # Cattaneo's slip zone at the right edge
    print(f"cylinder, Q = {Q:6.1f}: K_N = {right.K_N:.9e}, K_T = {right.K_T:.9e}, "
          f"slip zone {right.slip_zone:.6e} mm (Cattaneo's exact {exact:.6e} mm)")

# -- case A by the closed form and the SIE --------------------------------------------------------
punch = Punch(R1=10.0, R2=5.0, b=1.0)
for method in ("closedform", "sie"):
    r = solve(punch, P=P, s=0.1, A=A, Q=10.0, f=f, method=method)
    for edge in r.edges():
        print(f"{method:>10} {edge.side:>5} edge x = {edge.x:+.9f} mm: K_N = {edge.K_N:.9e}, "
              f"K_T = {edge.K_T:.9e}, slip zone {edge.slip_zone:.6e} mm")

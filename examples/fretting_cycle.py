"""A fretting cycle: Q from 0 to Q_max, to -Q_max and back at constant P, and the energy it dissipates.

Run it from anywhere (it writes no file)::

    python examples/fretting_cycle.py

By Masing's rule each reversal of the shear is a partial slip of twice the
amplitude, so the cycle follows from the partial-slip solution. The energy
dissipated per cycle and unit length is the area of the hysteresis loop of the
shear force against the punch's tangential displacement. For a cylinder it is
Mindlin's ``W = (2A/pi) (fP)^2 [(1 - q) ln(1 - q) + q - q^2/2]``,
``q = Q_max/(f P)``, close to ``A Q_max^3 / (3 pi f P)`` for small amplitudes.
"""
from __future__ import annotations

import math

import numpy as np

from threepart import Punch, fretting, similar_pair

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, f = 400.0, 0.5                          # normal load [N/mm], coefficient of friction
Q_max = 0.4 * f * P                        # shear amplitude [N/mm]

# -- the limit: a cylinder, Mindlin's energy ----------------------------------------------------
cyl = fretting(Punch(R1=10.0, R2=10.0, b=0.0), P=P, s=0.0, A=A, Q_max=Q_max, f=f)
q = Q_max / (f * P)
mindlin = 2 * A / math.pi * (f * P) ** 2 * ((1 - q) * math.log1p(-q) + q - q * q / 2)
print(f"cylinder: energy per cycle = {cyl.energy:.9e} N mm/mm ({cyl.method})")
print(f"Mindlin: W = {mindlin:.9e} N mm/mm")

# -- case A, tilted, by the closed form and by the SIE --------------------------------------------
punch = Punch(R1=10.0, R2=5.0, b=1.0)
for method in ("closedform", "sie"):
    cycle = fretting(punch, P=P, s=0.1, A=A, Q_max=Q_max, f=f, method=method, states=401)
    # the loop (Q, delta less its elastic line) and its area by the trapezoid rule, branch by branch
    Q, delta = cycle.loop()
    area = sum(np.trapezoid(delta[cycle.branch == b], Q[cycle.branch == b])
               for b in ("unloading", "reloading"))
    lo, hi = cycle.stick[cycle.branch == "loading"][-1]
    print(f"{method:>10}: energy per cycle = {cycle.energy:.9e} N mm/mm, loop area = {abs(area):.9e}, "
          f"stick zone at Q_max [{lo:.6f}, {hi:.6f}] mm")

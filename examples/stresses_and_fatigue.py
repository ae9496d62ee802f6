"""Stresses under the contact, and the fretting-fatigue hot spots of a cycle.

Run it from anywhere (it writes no file)::

    python examples/stresses_and_fatigue.py

Any result gives the stresses in the substrate at points ``(x, z)``, ``z`` the
depth, tension positive (docs/STRESS.md). Under Hertz's pressure they are
McEwen's: on the axis ``σzz = -p0 a / sqrt(a^2 + z^2)``, and the largest shear
``(σ1 - σ3)/2 = 0.30 p0`` lies at ``z = 0.78 a``. Then the fatigue parameters of
a fretting cycle on a grid (docs/FATIGUE.md): each has a hot spot, where it is
largest; in fretting it sits on the surface at an edge of the contact.
"""
from __future__ import annotations

import numpy as np

from threepart import Punch, fretting, similar_pair, solve
from threepart.fatigue import fatigue

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, f = 400.0, 0.5

# -- McEwen's stresses under a cylinder -----------------------------------------------------------
hertz = solve(Punch(R1=10.0, R2=10.0, b=0.0), P=P, s=0.0, A=A)
a, p0 = hertz.a, float(hertz.pressure([0.0])[0])
z = np.linspace(0.0, 3.0 * a, 3001)
axis = hertz.stress(np.zeros_like(z), z)
mcewen = -p0 * a / np.sqrt(a * a + z * z)
print(f"cylinder: a = {a:.6f} mm, p0 = {p0:.4f} MPa")
print(f"largest |szz - McEwen| on the axis = {np.max(np.abs(axis.szz - mcewen)) / p0:.2e} p0")
k = int(np.argmax(axis.max_shear))
print(f"largest shear on the axis = {axis.max_shear[k] / p0:.5f} p0 at z = {z[k] / a:.4f} a")

# -- the hot spots of a fretting cycle of case A --------------------------------------------------
punch = Punch(R1=10.0, R2=5.0, b=1.0)
cycle = fretting(punch, P=P, s=0.1, A=A, Q_max=0.4 * f * P, f=f)
x = np.linspace(-1.3, 1.3, 105)[:, None]                 # 0.025 mm apart
depth = np.linspace(0.0, 0.2, 9)[None, :]
result = fatigue(cycle, x, depth, E=210e3, nu=0.3)
print(f"case A cycle: contact [{-cycle.normal.a:.6f}, {cycle.normal.c:.6f}] mm, grid step 0.025 mm")
for name, parameter in result.parameters.items():
    hot = parameter.hot
    print(f"{name:>16}: hot spot x = {hot.x:+.4f} mm, z = {hot.z:.4f} mm, value = {hot.value:.4g}")

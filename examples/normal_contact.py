"""Normal contact: one punch solved by the paper's closed form, the SIE and the FEM, side by side.

Run it from anywhere (it writes no file)::

    python examples/normal_contact.py

First the limit every solver must meet: with equal edge radii and no flat
(``R1 = R2 = R``, ``b = 0``) the punch is a cylinder, and Hertz's contact has the
half-width ``a = sqrt(2 A R P / pi)`` and the peak pressure ``p0 = 2 P / (pi a)``.
Then case A of the paper (edge radii 10 and 5 mm, a flat centre over
``[-1, 1]`` mm, the load off-centre at ``s = 0.1`` mm) by the three methods:
the contact ``[-a, c]``, the tilt ``alpha`` and the two pressure peaks. The
closed form and the SIE agree to round-off; the FEM (the quick mesh, about 15 s)
to its mesh's resolution, about 1e-5 of the contact width.
"""
from __future__ import annotations

import math

from threepart import NormalResult, Punch, similar_pair, solve

# two steel bodies (E = 210 GPa, nu = 0.3): the compliance A of eq. (4), in 1/MPa
A = similar_pair(E=210e3, nu=0.3)
P = 400.0                               # normal load per unit length [N/mm]

# -- the limit: a cylinder of radius 10 mm is Hertz's contact --------------------------------------
R = 10.0
hertz = solve(Punch(R1=R, R2=R, b=0.0), P=P, s=0.0, A=A, method="closedform")
print(f"Hertz: a = {hertz.a:.9f} mm, p0 = {hertz.pressure([0.0])[0]:.6f} MPa")
print(f"Hertz by formula: a = {math.sqrt(2 * A * R * P / math.pi):.9f} mm, "
      f"p0 = {2 * P / (math.pi * math.sqrt(2 * A * R * P / math.pi)):.6f} MPa")

# -- case A by the three methods ------------------------------------------------------------------
punch = Punch(R1=10.0, R2=5.0, b=1.0)
results = {
    "closedform": solve(punch, P=P, s=0.1, A=A, method="closedform"),
    "sie": solve(punch, P=P, s=0.1, A=A, method="sie"),
    # the FEM: the same compliance on a gmsh mesh of a block ("quick", "default" or "fine")
    "fem": solve(punch, P=P, s=0.1, A=A, method="fem", mesh="quick", progress=False),
}
print(f"case A: R1 = {punch.R1}, R2 = {punch.R2}, b = {punch.b} mm, P = {P} N/mm, s = 0.1 mm")
for name, r in results.items():
    assert isinstance(r, NormalResult)        # no Q and f given: a normal result (not a slip)
    left, right = r.peaks()
    print(f"{name:>10}: a = {r.a:.12f} c = {r.c:.12f} alpha = {r.alpha:.12e} "
          f"peaks = {left.p:.4f}, {right.p:.4f} MPa")

ref = results["closedform"]
width = ref.a + ref.c
for name in ("sie", "fem"):
    r = results[name]
    print(f"{name} against the closed form: |da|/W = {abs(r.a - ref.a) / width:.2e}, "
          f"|dc|/W = {abs(r.c - ref.c) / width:.2e}")

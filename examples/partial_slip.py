"""Partial slip: a shear load Q below f P, the stick zone and the shear traction (Ciavarella–Jäger).

Run it from anywhere (it writes no file)::

    python examples/partial_slip.py

Under a shear force ``Q < f P`` applied after the normal load, the contact
sticks on a central zone ``[-(d+e), d-e]`` and slips towards its ends. By
Ciavarella and Jäger, the shear is ``f p(x)`` less ``f`` times a corrective
pressure on the stick zone: the pressure of the same punch under the load
``P - Q/f``. For a cylinder (``R1 = R2``, ``b = 0``) this is Cattaneo and
Mindlin's stick zone of half-width ``d = a sqrt(1 - Q/(f P))``. The shear is
integrated here by adaptive quadrature to show ``∫q dx = Q`` and checked
against Coulomb's bound ``|q| <= f p``.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad

from threepart import Punch, SlipResult, similar_pair, solve

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, Q, f = 400.0, 100.0, 0.5                # normal and shear load [N/mm], coefficient of friction

# -- the limit: a cylinder, Cattaneo–Mindlin ----------------------------------------------------
cyl = solve(Punch(R1=10.0, R2=10.0, b=0.0), P=P, s=0.0, A=A, Q=Q, f=f)
assert isinstance(cyl, SlipResult)         # Q and f given: a partial slip
print(f"cylinder: a = {cyl.a:.9f} mm, stick zone [{cyl.stick_zone[0]:.9f}, {cyl.stick_zone[1]:.9f}] mm")
print(f"Cattaneo-Mindlin: d = a sqrt(1 - Q/(f P)) = {cyl.a * math.sqrt(1 - Q / (f * P)):.9f} mm")

# -- case A, tilted: the stick zone shifts with the pressure ------------------------------------
punch = Punch(R1=10.0, R2=5.0, b=1.0)
slips = {}
for method in ("closedform", "sie"):
    r = solve(punch, P=P, s=0.1, A=A, Q=Q, f=f, method=method)
    assert isinstance(r, SlipResult)
    slips[method] = r
    lo, hi = r.stick_zone
    print(f"{method:>10}: contact [{-r.a:.9f}, {r.c:.9f}] mm, stick zone [{lo:.12f}, {hi:.12f}] mm "
          f"(d = {r.d:.12f}, e = {r.e:.12f})")

# the shear of the closed form: its integral is Q, and it never exceeds f p
slip = slips["closedform"]
breaks = sorted({-slip.a, *slip.stick_zone, -punch.b, punch.b, slip.c})
integral = sum(quad(lambda x: float(slip.shear([x])[0]), x0, x1, epsabs=0.0, epsrel=1e-12, limit=200)[0]
               for x0, x1 in zip(breaks[:-1], breaks[1:]))
x = np.linspace(-slip.a, slip.c, 4001)
excess = np.max(np.abs(slip.shear(x)) - f * slip.pressure(x))
print(f"integral of q(x) = {integral:.9f} N/mm (Q = {Q})")
print(f"largest |q| - f p = {excess:.3e} MPa (f p_max = {f * np.max(slip.pressure(x)):.3f} MPa)")

"""The laboratory pad that reproduces one edge of a flank: ``match`` (docs/EDGES.md §6).

Run it from anywhere (it writes no file)::

    python examples/match_a_pad.py

Near its edges every contact looks alike (``examples/edges.py``): the pressure rises as
``K_N √r`` and the shear a full stick would carry falls as ``K_T/√r``. A cylinder on a flat
with the same multipliers at one edge has the same slip zone there to first order (E6), and
so the same fretting damage: that is the fretting test a designer runs for a blade's flank.
``match`` finds the cylinder's radius ``R`` (the one whose surface stress over the slip zone is
closest to the flank's), its load ``P`` and shear ``Q`` (E9). At the command line:
``threepart match --case fan_blade_flank --Q 200 --f 0.5 --edge right``.
"""
from __future__ import annotations

from threepart import Punch, similar_pair, solve
from threepart.studies.matching import match

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, s, Q, f = 400.0, 0.1, 100.0, 0.5        # the flank's load [N/mm], lever arm [mm], shear [N/mm], friction

flank = solve(Punch(R1=10.0, R2=5.0, b=1.0), P=P, s=s, A=A, Q=Q, f=f)   # a tilted three-part flank
print(f"flank: contact [{-flank.a:.6f}, {flank.c:.6f}] mm, stick zone "
      f"[{flank.stick_zone[0]:.6f}, {flank.stick_zone[1]:.6f}] mm")
for edge in ("left", "right"):
    m = match(flank, edge, fatigue=False)
    print(f"{edge} edge: flank K_N = {m.flank.K_N:.9e}, K_T = {m.flank.K_T:.9e}; "
          f"pad R = {m.R:.9e} mm, P = {m.P:.9e} N/mm, Q = {m.Q:.9e} N/mm; "
          f"pad K_N = {m.pad.K_N:.9e}, K_T = {m.pad.K_T:.9e}; "
          f"surface stress over the slip zone within {m.sxx_error:.3g} of the flank's largest")

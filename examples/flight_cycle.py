"""A flight cycle: the periodic steady state of an in-phase cycle between two load states.

Run it from anywhere (it writes no file)::

    python examples/flight_cycle.py

A state is ``(P, s, Q, sigma_bulk)``; between the two ends of the cycle the four
move linearly and in phase (docs/STEADY_STATE.md). After the first cycles the
contact settles into a periodic state: a permanent stick zone ``[-(d+e), d-e]``,
the energy dissipated per cycle and whether it has shaken down (no slip left).

The check first: at constant ``P`` and ``s`` a cycle between ``Q = Q_max`` and
``Q = -Q_max`` is the fretting cycle, so both give the same energy per cycle, and the permanent stick zone is the
fretting cycle's stick zone at ``Q_max``.
Then a flight: the normal load rises from 300 to 400 N/mm while the shear rises
from 0 to 80 N/mm.
"""
from __future__ import annotations

from threepart import Punch, fretting, similar_pair, steady_state

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, s, f = 400.0, 0.1, 0.5                  # normal load [N/mm], its lever arm [mm], friction
Q_max = 0.4 * f * P
punch = Punch(R1=10.0, R2=5.0, b=1.0)

# -- the check: +-Q_max at constant P is the fretting cycle -------------------------------------
cycle = fretting(punch, P=P, s=s, A=A, Q_max=Q_max, f=f)
steady = steady_state(punch, ((P, s, Q_max, 0.0), (P, s, -Q_max, 0.0)), f, A=A)
lo, hi = cycle.stick[cycle.branch == "loading"][-1]      # the stick zone at Q_max
print(f"fretting cycle: energy per cycle = {cycle.energy:.12e} N mm/mm, "
      f"stick zone at Q_max [{lo:.9f}, {hi:.9f}] mm")
print(f"steady state between +-Q_max: energy per cycle = {steady.energy:.12e} N mm/mm, "
      f"permanent stick zone [{-(steady.d + steady.e):.9f}, {steady.d - steady.e:.9f}] mm ({steady.method})")

# -- a flight: P and Q rise together ---------------------------------------------------------------
flight = steady_state(punch, ((300.0, s, 0.0, 0.0), (P, s, 80.0, 0.0)), f, A=A)
print(f"flight 300 -> 400 N/mm, Q 0 -> 80 N/mm: d = {flight.d:.9f} mm, e = {flight.e:.9f} mm, "
      f"energy per cycle = {flight.energy:.6e} N mm/mm, shaken down: {flight.shakedown}")

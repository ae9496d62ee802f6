"""A load history marched with the memory of slip (the SIE), against the fretting cycle it repeats.

Run it from anywhere (it writes no file)::

    python examples/load_history.py

``threepart.sie.load_history`` marches any sequence of states ``(P, s, Q,
sigma_bulk)`` (or a CSV file of them), remembering where the contact has
slipped: its stick intervals, shear, slip and the energy of each completed
cycle. Here the shear swings between ``+Q_max`` and ``-Q_max`` at constant ``P``,
so each cycle after the first loading is Masing's fretting cycle, whose energy
the closed form gives exactly; the marched energy meets it to the resolution of
the march's element grid (``n`` elements; the slip zones must span several).
"""
from __future__ import annotations

from threepart import Punch, fretting, similar_pair
from threepart.sie import load_history

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, s, f = 400.0, 0.1, 0.5
Q_max = 0.4 * f * P
punch = Punch(R1=10.0, R2=5.0, b=1.0)

states = [(P, s, Q_max, 0.0), (P, s, -Q_max, 0.0), (P, s, Q_max, 0.0), (P, s, -Q_max, 0.0), (P, s, Q_max, 0.0)]
history = load_history(punch, states, f, A=A, n=800, progress=False)
exact = fretting(punch, P=P, s=s, A=A, Q_max=Q_max, f=f).energy
print(f"fretting cycle (closed form): energy per cycle = {exact:.9e} N mm/mm")
for k, energy in enumerate(history.energy, start=1):
    print(f"marched cycle {k}: energy = {energy:.9e} N mm/mm, {energy / exact - 1:+.2e} of the closed form's")
print(f"elements across the widest slip zones (left, right): {history.info['slip_elements']}")

"""Where the half-plane formulas stop: two points of the validity map, the closed form against a finite body.

Run it from anywhere (it writes no file)::

    python examples/validity_map.py

The paper's formulas assume small slopes and bodies large beside the contact. The validity map
(``threepart map``, docs/MAP.md) measures the closed form's error against a finite-element model of
a real punch: a flat of half-width ``b`` with exact edge arcs ``R1``, ``R2`` and straight flanks at
60 degrees, of height ``H``, on a finite block (``fem.solve_finite``). A point of the map is a set of
ratios; the load follows from the overhang ``max(a, c) - b`` the contact reaches, in units of ``R1``.
Here one shape (``R2 = R1``, ``b = 0.3 R1``, ``H = 4 b``) at two loads: a small overhang, where the
contact's extent follows the formulas to about 5e-4, and a large one, where the contact runs onto
the arcs' steep part and its extent is a few per cent off, far past the FE model's own error (each
point runs the FE model on two meshes; their difference is that estimate). The peak pressure also
carries what the finite punch and block do beside the slopes, at either load.
"""
from __future__ import annotations

from threepart.reports.map.validity import MapPoint, evaluate

for overhang in (0.01, 0.3):
    point = MapPoint(R2_over_R1=1.0, b_over_R1=0.3, a_minus_b_over_R1=overhang, H_over_b=4.0)
    r = evaluate(point, quick=True)                        # the map's quick meshes
    print(f"overhang (a - b)/R1 = {overhang}: P = {r['P']:.6g} (E = 1, R1 = 10); the closed form's "
          f"error in a {r['a_rel_error']:+.3e}, in the peak pressure {r['peak_rel_error']:+.3e}; "
          f"the FE model's own error estimate {r['fem_error_estimate']:.3e}")

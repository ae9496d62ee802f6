"""Validate another contact code with threepart's pytest plugin: tamaas, the FFT boundary-element solver.

Run it from the repository root (it is not part of threepart's own test run)::

    pip install -e ".[bench]"          # tamaas and threepart (whose plugin pytest loads itself)
    pytest examples/test_tamaas_plugin.py -s

The plugin gives every test two fixtures: ``threepart_case``, one catalogue
case per test run (here chosen by the ``threepart_cases`` marker), and
``threepart_check``, which judges anything with ``a``, ``c`` and
``pressure(x)`` against the case's reference solution and prints the margins
(they are also listed at the end of the run, under "threepart margins").

tamaas is driven as in ``benchmarks/peer_tamaas.py``: a rigid punch pressed
vertically onto a periodic elastic line (no tilt unknown), so only tilt-free
cases are asked for: symmetric ones, and the case whose tilt is suppressed.
"""
from __future__ import annotations

import math
import sys
import types
from pathlib import Path

import pytest

# without the bench extra: one skip that names it, not a ModuleNotFoundError per case
pytest.importorskip("tamaas", reason='tamaas is the bench extra: pip install -e ".[bench]"')
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # benchmarks/ of this repository
from benchmarks.peer_tamaas import solve_peer  # noqa: E402  (needs tamaas: the bench extra)

#: tamaas's grid: cells per contact width W, and the period in units of W
CELLS, PERIOD = 1024, 64.0
#: this example's own limits where tamaas is not held to the table's FE limits (fem-default):
#: its ends are fitted to the last loaded cells (measured <= 8e-5 W at 1024 cells per W), its
#: cell pressures next to the logarithmic kinks at x = ±b err by up to 4e-4 of the peak, and
#: its field is piecewise linear next to the square-root ends (L2 up to 1.5e-3)
TOLERANCES = {"a": 2e-4, "c": 2e-4, "p_interior_max": 1e-3, "p_L2": 3e-3}


@pytest.mark.threepart_cases("caseA_sym", "hertz", "suppressed", "nd_flat_symmetric")
def test_tamaas_against_threepart(threepart_case, threepart_check):
    case = threepart_case
    # a nondimensional case gives A, not a material: any E, nu with the rigid punch's 2(1 - nu^2)/E = A
    E, nu = case.material if case.material is not None else (2 * (1 - 0.3**2) / case.A, 0.3)
    # the grid's scale: the central segment plus a Hertz width of the larger edge radius
    width = 2 * case.punch.b + 2 * (2 * case.P * case.A * max(case.punch.R1, case.punch.R2) / math.pi) ** 0.5
    peer = solve_peer(case.punch, case.P, E=E, nu=nu, width=width, cells=CELLS, period=PERIOD)
    result = types.SimpleNamespace(a=peer.a, c=peer.c, alpha=0.0, pressure=peer.pressure, x_nodes=peer.x)
    threepart_check(result, case, tolerances=TOLERANCES)

"""Another load on a given mesh starts from the last contact solved on it (fem/solve.py, issue 41).

Reference: the same solve started cold (the memory of last contacts cleared): the active
set's answer does not depend on its start, so the two agree to rounding; the warm start
shows in the iteration count only.
"""
from __future__ import annotations

import numpy as np
import pytest

from threepart import Punch, fem
import threepart.fem.solve as fem_solve
from threepart.meshes import SubstrateSpec

E, NU = 210e3, 0.3
PUNCH = Punch(R1=10.0, R2=10.0, b=0.0)
SPEC = SubstrateSpec(x_lo=-0.4, x_hi=0.4, h=0.01, L=8.0, growth=0.4)
#: the warm and cold answers: the same active set, so the same linear solves, to rounding
ROUNDING = 1e-12


@pytest.fixture(scope="module")
def substrate():
    return fem.make_substrate(SPEC)


def _solve(sub, P):
    return fem.solve_normal(PUNCH, P, 0.0, E=E, nu=NU, mesh=sub)


def test_another_load_starts_from_the_last_contact(substrate):
    _solve(substrate, 300.0)
    warm = _solve(substrate, 330.0)
    fem_solve._LAST_ACTIVE.clear()
    cold = _solve(substrate, 330.0)
    assert warm.diagnostics.iterations < cold.diagnostics.iterations
    assert warm.a == pytest.approx(cold.a, rel=ROUNDING) and warm.c == pytest.approx(cold.c, rel=ROUNDING)
    assert np.allclose(warm.p_nodes, cold.p_nodes, rtol=0, atol=ROUNDING * np.max(cold.p_nodes))
    again = _solve(substrate, 330.0)           # the same load again: its own contact, one iteration
    assert again.diagnostics.iterations == 1

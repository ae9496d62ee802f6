"""The FEM's two bodies on any profile: the punch plus a worn depth (issue 39; fem/friction.py ``depth=``).

References: a quadratic depth ``x^2/(2R')`` on a Hertz punch of radius ``R`` is Hertz of the
summed curvature, whose partial slip is Cattaneo's (``d = a sqrt(1 - Q/fP)``, centred); the
SIE on the same worn profile (sie.profile).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import Punch, closedform, fem
from threepart.errors import InputError, InputTypeError
from threepart.tolerances import tolerance

E, NU, P, F = 1.0, 0.3, 0.05, 0.5
A = 4 * (1 - NU**2) / E
HERTZ = Punch(R1=10.0, R2=10.0, b=0.0)


def _quadratic(x: np.ndarray) -> np.ndarray:
    return x * x / 20.0                          # 1/R' = 1/10: with 1/R = 1/10, R = 5


@pytest.mark.parametrize("ratio", [0.3, 0.8])
def test_a_quadratic_depth_is_cattaneo_of_the_summed_curvature(ratio):
    fe = fem.solve_partial_slip(HERTZ, P, 0.0, Q=ratio * F * P, f=F, E=E, nu=NU, mesh="quick", depth=_quadratic)
    ref = closedform.solve_normal(Punch(R1=5.0, R2=5.0, b=0.0), P, 0.0, A=A)
    d = ref.a * math.sqrt(1 - ratio)
    assert abs(fe.normal.a - ref.a) / (2 * ref.a) < tolerance("fem-quick", "a").limit
    assert abs(fe.d - d) / d < tolerance("fem-quick", "d").limit
    assert abs(fe.e) / d < tolerance("fem-quick", "e").limit


def test_a_worn_fretting_cycle_closes_and_its_energy_is_the_closed_forms():
    """The cycle on the worn profile: its energy against Hertz of the summed curvature (Mindlin)."""
    Q_max = 0.5 * F * P
    fe = fem.fretting_cycle(HERTZ, P, 0.0, Q_max=Q_max, f=F, E=E, nu=NU, mesh="quick", states=11,
                            depth=_quadratic)
    ref = closedform.fretting_cycle(closedform.solve_normal(Punch(R1=5.0, R2=5.0, b=0.0), P, 0.0, A=A), Q_max, F)
    assert abs(fe.energy - ref.energy) / ref.energy < tolerance("fem-quick", "energy").limit


def test_a_bad_depth_is_refused_by_name():
    with pytest.raises(InputTypeError, match="`depth`"):
        fem.solve_partial_slip(HERTZ, P, 0.0, Q=0.1 * F * P, f=F, E=E, nu=NU, mesh="quick", depth=3.0)
    with pytest.raises(InputError, match="`depth`"):
        fem.solve_partial_slip(HERTZ, P, 0.0, Q=0.1 * F * P, f=F, E=E, nu=NU, mesh="quick",
                               depth=lambda x: -np.ones_like(x))

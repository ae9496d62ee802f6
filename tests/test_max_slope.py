"""``Punch.max_slope`` on floats (written out for one solve's check) against its array form.

Reference: the array form (numpy, broadcast), the one the batches use, and the slope of
eq. (2) sampled densely over the contact (the extremes of a piecewise-linear slope lie at
the contact's ends and the joins).
"""
from __future__ import annotations

import numpy as np
import pytest

from threepart import Punch

#: the sampled slope against the exact extremes: the same expressions, a few operations apart
ROUNDING = 1e-12


@pytest.mark.parametrize("seed", range(4))
def test_the_float_path_is_the_array_path(seed):
    rng = np.random.default_rng(seed)
    punch = Punch(R1=float(rng.uniform(1, 100)), R2=float(rng.uniform(1, 100)), b=float(rng.uniform(0, 2)),
                  R=float(rng.choice([np.inf, rng.uniform(-200, 200)])))
    a, c, alpha = (rng.uniform(-3, 3, 500) for _ in range(3))
    arrays = punch.max_slope(a, c, alpha)
    floats = np.array([punch.max_slope(float(x), float(y), float(z)) for x, y, z in zip(a, c, alpha)])
    assert np.array_equal(arrays, floats)
    # and both are the largest sampled slope over a contact that straddles the joins
    x = np.linspace(-1.5 * punch.b - 0.5, 1.5 * punch.b + 0.5, 20001)
    v, g = punch.slope(x, 1e-3), punch.slope(x)
    sampled = max(1e-3, float(np.max(np.abs(v))), float(np.max(np.abs(g))))
    exact = punch.max_slope(float(-x[0]), float(x[-1]), 1e-3)
    assert exact == pytest.approx(sampled, rel=ROUNDING)

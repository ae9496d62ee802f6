"""Punch profile (eq. 2) and compliance (eq. 4)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import closedform as cf
from threepart.closedform import Punch
from threepart.tolerances import tolerance

#: exact figures (continuity across a join, moduli) and identities in double precision
EXACT = tolerance("closedform", "exact").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
#: central differences with step 1e-6 of the profile: truncation 1e-12, rounding 1e-10
CENTRAL_DIFFERENCE = 1e-8
#: central differences of the slope, relative to the curvature
SECOND_DIFFERENCE = 1e-6


@pytest.mark.parametrize("punch", [Punch(1.0, 2.0, 0.3), Punch(1.0, 2.0, 0.3, R=5.0),
                                   Punch(1.0, 2.0, 0.3, R=-4.0), Punch(1.0, 2.0, 0.0)])
def test_profile_is_continuous_with_continuous_slope(punch):
    for xb in (-punch.b, punch.b):
        lo, hi = np.nextafter(xb, -np.inf), np.nextafter(xb, np.inf)
        assert punch.profile(lo) == pytest.approx(punch.profile(hi), abs=EXACT)
        assert punch.slope(lo) == pytest.approx(punch.slope(hi), abs=ROUND_OFF)


@pytest.mark.parametrize("punch", [Punch(1.0, 2.0, 0.3, R=5.0), Punch(3.0, 0.5, 0.2)])
def test_slope_is_the_derivative_of_the_profile(punch):
    x = np.linspace(-1.0, 1.0, 41)
    x = x[np.min(np.abs(x[:, None] - np.array([-punch.b, punch.b])[None, :]), axis=1) > 1e-3]
    h = 1e-6
    fd = (punch.profile(x + h, 0.01) - punch.profile(x - h, 0.01)) / (2 * h)
    assert np.allclose(fd, punch.slope(x, 0.01), rtol=0, atol=CENTRAL_DIFFERENCE)
    fd2 = (punch.slope(x + h) - punch.slope(x - h)) / (2 * h)
    assert np.allclose(fd2, punch.curvature(x), rtol=SECOND_DIFFERENCE)


def test_outer_segments_are_circles_of_radius_R1_R2_in_the_parabolic_sense():
    punch = Punch(2.0, 3.0, 0.5, R=10.0)
    # curvature 1/R1 left, 1/R2 right, 1/R centre
    assert punch.curvature(-1.0) == pytest.approx(0.5) and punch.curvature(1.0) == pytest.approx(1 / 3)
    assert punch.curvature(0.0) == pytest.approx(0.1)
    assert punch.segment([-1.0, 0.0, 1.0]).tolist() == [1, 0, 2]


def test_cases_and_mirror():
    assert Punch(1.0, 2.0, 0.3).case == "A"
    assert Punch(1.0, 2.0, 0.3, R=-4.0).case == "B"
    assert Punch(1.0, 2.0, 0.0).case == "C"
    assert Punch(1.0, 1.0, 0.0).case == "Hertz"
    assert Punch(1.0, 2.0, 0.3, R=4.0).case == "general"
    p = Punch(1.0, 2.0, 0.3, R=4.0)
    x = np.linspace(-1, 1, 11)
    assert np.allclose(p.mirrored().profile(x), p.profile(-x))


def test_compliance_plane_strain():
    E, nu = 210e3, 0.3
    mu, kappa = E / (2 * (1 + nu)), 3 - 4 * nu
    assert cf.compliance(E, nu, 70e3, 0.33) == pytest.approx(
        (kappa + 1) / (4 * mu) + (4 - 4 * 0.33) / (4 * 70e3 / (2 * 1.33)), rel=EXACT)
    assert cf.similar_pair(E, nu) == pytest.approx(4 * (1 - nu**2) / E, rel=EXACT)
    assert cf.rigid_punch(E, nu) == pytest.approx(2 * (1 - nu**2) / E, rel=EXACT)
    assert math.isclose(cf.compliance(E, nu), 2 * cf.rigid_punch(E, nu))

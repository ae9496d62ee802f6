"""Partial slip: Hertz exact, equilibrium and Coulomb, and the closed form's stick zone."""
from __future__ import annotations

import functools
import math

import numpy as np
from scipy.integrate import quad
import pytest

from threepart import sie
from threepart.problem.catalogue import load_cases, slip_loads
from threepart.problem.punch import Punch
from threepart.reports.compare import compare
from threepart.tolerances import tolerance

from .fakes import Stored

#: the shear's sign is checked where |q| exceeds rounding (at the contact ends q -> 0)
SHEAR_ZERO = 1e-12

CASES = {c.name: c.resolved() for c in load_cases("sie")}


def tol(comparison: str, quantity: str) -> float:
    return tolerance(comparison, quantity).limit


@pytest.fixture(scope="module")
def normal_A():
    k = CASES["nd_A"]
    return sie.solve_normal(k.punch, k.P, k.s, A=k.A)


@pytest.mark.parametrize("scheme", ["plain", "projected"])
def test_hertz_stick_zone_is_exact(scheme):
    """Hertz: d = a sqrt(1 - |Q|/fP), stick zone centred on the contact centre."""
    R, P, f, Q = 2.0, 3.0, 0.5, -1.1
    # A = 0.01: a contact of half-width 0.28 R/2, inside the arcs and the small-slope limit
    normal = sie.solve_normal(Punch(R, R, 0.0), P, 0.02, A=0.01, n=8, scheme=scheme)
    r = sie.solve_partial_slip(normal, Q, f)
    h = 0.5 * (normal.a + normal.c)
    exact = tol("sie-exact", "hertz")
    assert r.d == pytest.approx(h * math.sqrt(1 - abs(Q) / (f * P)), rel=exact, abs=0)
    assert r.e == pytest.approx(-0.02, rel=exact, abs=0)
    assert r.diagnostics.n == 8 and r.diagnostics.scheme == scheme


@pytest.mark.parametrize("Q", [0.03, -0.045])
def test_shear_integrates_to_Q_and_obeys_coulomb(normal_A, Q):
    f = 0.6
    r = sie.solve_partial_slip(normal_A, Q, f)
    x = np.linspace(-normal_A.a, normal_A.c, 20001)
    q, p = r.shear(x), normal_A.pressure(x)
    lo, hi = r.stick_zone      # quadrature split at the kinks of q: joins and stick-zone ends
    pts = sorted(t for t in (lo, hi, -normal_A.punch.b, normal_A.punch.b) if -normal_A.a < t < normal_A.c)
    total = quad(lambda t: float(r.shear(t)), -normal_A.a, normal_A.c, points=pts, limit=200,
                 epsabs=0, epsrel=1e-12)[0]
    assert total == pytest.approx(Q, rel=tol("sie-identity", "shear_load"), abs=0)
    assert np.all(np.sign(q[np.abs(q) > SHEAR_ZERO]) == np.sign(Q))
    assert np.all(np.abs(q) <= f * p + tol("sie-identity", "coulomb") * p.max())  # |q| <= f p everywhere
    lo, hi = r.stick_zone
    slip = (x < lo) | (x > hi)
    np.testing.assert_allclose(np.abs(q[slip]), f * p[slip], rtol=0,
                               atol=tol("sie-exact", "slip_zone_shear") * p.max())
    assert normal_A.a > r.d + r.e and r.d - r.e < normal_A.c


def test_zero_shear_sticks_everywhere(normal_A):
    r = sie.solve_partial_slip(normal_A, 0.0, 0.5)
    assert r.stick_zone == pytest.approx((-normal_A.a, normal_A.c), rel=tol("sie-exact", "zero_shear"), abs=0)
    assert np.all(r.shear(np.linspace(-1, 1, 7)) == 0)


def test_stick_zone_of_plain_scheme_converges(normal_A):
    k = CASES["nd_A"]
    ref = sie.solve_partial_slip(normal_A, 0.03, 0.6)
    normal = sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=512, scheme="plain")
    r = sie.solve_partial_slip(normal, 0.03, 0.6)
    plain = tol("sie-plain", "stick_zone")
    assert r.d == pytest.approx(ref.d, rel=plain, abs=0) and r.e == pytest.approx(ref.e, abs=plain * ref.d)


@pytest.mark.parametrize("Q, f, match", [
    (0.07, 0.7, r"\|`Q`\| = 0.07 >= f P = 0.07 \(`f` = 0.7, `P` = 0.1\): the contact slides"),
    (0.1, 0.0, "`f` = 0.0 must be > 0"),
    (math.nan, 0.5, "`Q`"),
])
def test_bad_input_is_refused(normal_A, Q, f, match):
    with pytest.raises(ValueError, match=match):
        sie.solve_partial_slip(normal_A, Q, f)


def test_normal_must_be_a_result():
    with pytest.raises(TypeError, match="`normal` must be a NormalResult"):
        sie.solve_partial_slip("nope", 0.1, 0.5)


# -- agreement with the closed form -----------------------------------------------------
def check_slip_agreement(s_r, c_r) -> list:
    """Judge the SIE slip result with the verification run's comparator and ``("sie", q)`` tolerances."""
    checks = compare(c_r, s_r, "sie")
    bad = {c.quantity: f"{c.error:.1e} > {c.limit:g}" for c in checks if not c.passed}
    assert not bad, f"SIE stick zone disagrees with closedform: {bad}"
    return checks


@functools.cache
def _normals(name: str) -> tuple:
    """The closed form's and the SIE's normal solutions of a case, solved once for all its loads."""
    from threepart import closedform as cf
    k = CASES[name]
    return (cf.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt),
            sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt))


@pytest.mark.parametrize("name", [k for k in CASES if k != "nd_near_lift_off"])
@pytest.mark.parametrize("load", slip_loads("sie"))
def test_agreement_with_closed_form(name, load):
    from threepart import closedform as cf
    k = CASES[name]
    q, f = load
    c_n, s_n = _normals(name)
    reference = Stored(cf.solve_partial_slip(c_n, q * f * k.P, f))     # its stresses: once for both
    check_slip_agreement(sie.solve_partial_slip(s_n, q * f * k.P, f), reference)
    # the SIE stick zone from the closed-form normal solution agrees too
    check_slip_agreement(sie.solve_partial_slip(c_n, q * f * k.P, f), reference)


def test_perturbed_stick_zone_fails_the_agreement_check():
    from threepart import closedform as cf
    k = CASES["nd_A"]
    c_n = cf.solve_normal(k.punch, k.P, k.s, A=k.A)
    wrong_n = sie.solve_normal(k.punch, k.P, k.s, A=k.A * (1 + 1e-7))
    with pytest.raises(AssertionError, match="disagrees.*'d'"):
        check_slip_agreement(sie.solve_partial_slip(wrong_n, 0.02, 0.7), cf.solve_partial_slip(c_n, 0.02, 0.7))

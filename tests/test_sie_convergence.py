"""Observed orders of the plain and projected schemes, and the convergence-study API."""
from __future__ import annotations

import numpy as np
import pytest

from threepart import sie
from threepart.sie.cases import CASES
from threepart.sie.schemes import Plain, Projected
from threepart.sie.tolerances import TOLERANCES as TOL

NS = np.unique(np.geomspace(24, 768, 14).astype(int))  # both parities, to average the wobble


def test_observed_order_and_richardson_on_synthetic_data():
    n = np.array([10, 20, 40, 80])
    v = 3.0 + 2.0 * n**-2.0
    study = sie.convergence_study(lambda k: 3.0 + 2.0 * k**-2.0, n, reference=3.0)
    assert study.order == pytest.approx(2.0, abs=1e-12)
    assert study.constant == pytest.approx(2.0, rel=1e-10)
    assert sie.richardson(n, v, 2.0) == pytest.approx(3.0, abs=1e-14)
    assert study.extrapolated == pytest.approx(3.0, abs=1e-12)
    assert sie.observed_order([1, 2], [0.0, 0.0])[0] == np.inf
    with pytest.raises(ValueError, match="`ns`"):
        sie.convergence_study(lambda k: 1.0, [4], reference=1.0)


def contact(name: str):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    return k, r, 0.5 * (r.c - r.a), 0.5 * (r.a + r.c)


@pytest.mark.parametrize("name", ["A", "general"])
def test_plain_load_converges_as_n_minus_2(name):
    """Relative error of the discrete load on the exact contact (kinks limit it to ~n^-2)."""
    k, r, m, h = contact(name)
    exact = Projected(2).moments(k.punch, m, h)[0][1]
    study = sie.convergence_study(lambda n: Plain(n).moments(k.punch, m, h)[0][1], NS,
                                  reference=exact, scale=abs(exact))
    assert study.order >= TOL["plain_load_order"].value, f"observed load order {study.order:.2f}"
    level = study.errors[NS >= 450].max()
    assert level <= TOL["plain_load_level"].value, f"load error {level:.2e}, order {study.order:.2f}"


def test_plain_contact_ends_converge_as_n_minus_2():
    k, r, _, _ = contact("A")
    study = sie.convergence_study(
        lambda n: sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=n, scheme="plain").a, NS[::2],
        reference=r.a, scale=r.a)
    assert study.order >= TOL["plain_ends_order"].value, f"observed order of a: {study.order:.2f}"
    assert study.errors[-1] < 1e-6, f"error in a {study.errors[-1]:.2e} (order {study.order:.2f})"


@pytest.mark.parametrize("name", ["A", "B"])
def test_plain_pressure_converges_as_n_minus_1(name):
    k, r, m, h = contact(name)
    x = np.linspace(-r.a, r.c, 801)[1:-1]
    ref = Projected(8192).pressure(k.punch, k.A, m, h)[0](x)
    study = sie.convergence_study(lambda n: Plain(n).pressure(k.punch, k.A, m, h)[0](x), NS,
                                  reference=ref, scale=ref.max())
    assert study.order >= TOL["plain_pressure_order"].value, f"observed pressure order {study.order:.2f}"
    level = study.errors[NS >= 450].max()
    assert level <= TOL["plain_pressure_level"].value, f"pressure error {level:.2e}, order {study.order:.2f}"


def test_projected_pressure_converges_as_n_minus_2():
    k, r, m, h = contact("A")
    x = np.concatenate([np.linspace(-r.a, r.c, 801)[1:-1], [-0.4 - 1e-6, 0.4 + 1e-9]])
    ref = Projected(8192).pressure(k.punch, k.A, m, h)[0](x)
    ns = [32, 64, 128, 256, 512, 1024]
    study = sie.convergence_study(lambda n: Projected(n).pressure(k.punch, k.A, m, h)[0](x), ns,
                                  reference=ref, scale=ref.max())
    assert study.order >= TOL["projected_pressure_order"].value, f"observed order {study.order:.2f}"
    assert study.errors[-1] <= TOL["projected_pressure_level"].value, \
        f"error {study.errors[-1]:.2e} at n=1024 (order {study.order:.2f})"


def test_projected_ends_do_not_depend_on_n():
    k = CASES["A"]
    ref = sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=4096)
    for n in (2, 17, 300):
        r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=n)
        assert (r.a, r.c, r.alpha) == pytest.approx((ref.a, ref.c, ref.alpha), rel=1e-14, abs=1e-17)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["A", "B", "C", "general", "suppressed", "near_lift_off"])
def test_plain_study_up_to_1600(name):
    """Issue 3's measured figures: load ~2e-6 at n = 512, pressure ~1.4e-4 of the peak at n = 1600."""
    k, r, m, h = contact(name)
    ns = np.unique(np.geomspace(50, 1600, 16).astype(int))
    exact = Projected(2).moments(k.punch, m, h)[0][1]
    load = sie.convergence_study(lambda n: Plain(n).moments(k.punch, m, h)[0][1], ns,
                                 reference=exact, scale=abs(exact))
    x = np.linspace(-r.a, r.c, 1601)[1:-1]
    ref = Projected(16384).pressure(k.punch, k.A, m, h)[0](x)
    pres = sie.convergence_study(lambda n: Plain(n).pressure(k.punch, k.A, m, h)[0](x), ns,
                                 reference=ref, scale=ref.max())
    assert 1.4 <= load.order <= 3.0, f"load order {load.order:.2f}"
    assert 0.9 <= pres.order <= 1.4, f"pressure order {pres.order:.2f}"
    assert pres.errors[-1] < 1e-3, f"pressure error {pres.errors[-1]:.2e} at n=1600"

"""Observed orders of the plain and projected schemes, and the convergence-study API."""
from __future__ import annotations

import numpy as np
import pytest

from threepart import sie
from threepart.catalogue import load_cases
from threepart.sie.schemes import Plain, Projected
from threepart.tolerances import tolerance

CASES = {c.name: c.resolved() for c in load_cases("sie")}
NS = np.unique(np.geomspace(24, 768, 14).astype(int))  # both parities, to average the wobble


def tol(comparison: str, quantity: str) -> float:
    return tolerance(comparison, quantity).limit


def test_convergence_study_on_synthetic_data():
    """3 + 2 n^-2: order 2, constant 2, and the Richardson estimate is the limit 3."""
    exact = tol("convergence", "exact")
    study = sie.convergence_study(lambda k: 3.0 + 2.0 * k**-2.0, [10, 20, 40, 80], reference=3.0)
    assert study.orders['value'] == pytest.approx(2.0, abs=exact)
    assert study.constants["value"] == pytest.approx(2.0, rel=exact)
    assert study.extrapolated["value"] == pytest.approx(3.0, abs=exact)
    exact_at_once = sie.convergence_study(lambda k: 1.0, [4, 8], reference=1.0)
    assert np.isnan(exact_at_once.orders['value']), "round-off errors carry no order"
    with pytest.raises(ValueError, match="`ns`"):
        sie.convergence_study(lambda k: 1.0, [4], reference=1.0)


def contact(name: str):
    k = CASES[name]
    r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, tilt=k.tilt)
    return k, r, 0.5 * (r.c - r.a), 0.5 * (r.a + r.c)


@pytest.mark.parametrize("name", ["nd_A", "nd_general"])
def test_plain_load_converges_as_n_minus_2(name):
    """Relative error of the discrete load on the exact contact (kinks limit it to ~n^-2)."""
    k, r, m, h = contact(name)
    exact = Projected(2).moments(k.punch, m, h)[0][1]
    study = sie.convergence_study(lambda n: Plain(n).moments(k.punch, m, h)[0][1], NS,
                                  reference=exact, scale=abs(exact))
    assert study.orders['value'] >= tol("sie-plain", "load_order"), f"observed load order {study.orders['value']:.2f}"
    level = np.asarray(study.errors['value'])[NS >= 450].max()
    assert level <= tol("sie-plain", "load_level"), f"load error {level:.2e}, order {study.orders['value']:.2f}"


def test_plain_contact_ends_converge_as_n_minus_2():
    k, r, _, _ = contact("nd_A")
    study = sie.convergence_study(
        lambda n: sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=n, scheme="plain").a, NS,   # all 14 n: the kink aliasing wobbles
        reference=r.a, scale=r.a)
    assert study.orders['value'] >= tol("sie-plain", "a_order"), f"observed order of a: {study.orders['value']:.2f}"
    assert np.asarray(study.errors['value'])[-1] < tol("sie-plain", "a_level"), f"error in a {np.asarray(study.errors['value'])[-1]:.2e} (order {study.orders['value']:.2f})"


@pytest.mark.parametrize("name", ["nd_A", "nd_B"])
def test_plain_pressure_converges_as_n_minus_1(name):
    k, r, m, h = contact(name)
    x = np.linspace(-r.a, r.c, 801)[1:-1]
    ref = Projected(8192).pressure(k.punch, k.A, m, h)[0](x)
    study = sie.convergence_study(lambda n: Plain(n).pressure(k.punch, k.A, m, h)[0](x), NS,
                                  reference=ref, scale=ref.max())
    assert study.orders['value'] >= tol("sie-plain", "pressure_order"), f"observed pressure order {study.orders['value']:.2f}"
    level = np.asarray(study.errors['value'])[NS >= 450].max()
    assert level <= tol("sie-plain", "pressure_level"), f"pressure error {level:.2e}, order {study.orders['value']:.2f}"


def test_projected_pressure_converges_as_n_minus_2():
    k, r, m, h = contact("nd_A")
    x = np.concatenate([np.linspace(-r.a, r.c, 801)[1:-1], [-0.4 - 1e-6, 0.4 + 1e-9]])
    ref = Projected(8192).pressure(k.punch, k.A, m, h)[0](x)
    ns = [32, 64, 128, 256, 512, 1024]
    study = sie.convergence_study(lambda n: Projected(n).pressure(k.punch, k.A, m, h)[0](x), ns,
                                  reference=ref, scale=ref.max())
    assert study.orders['value'] >= tol("sie-projected", "pressure_order"), f"observed order {study.orders['value']:.2f}"
    assert np.asarray(study.errors['value'])[-1] <= tol("sie-projected", "pressure_level"), \
        f"error {np.asarray(study.errors['value'])[-1]:.2e} at n=1024 (order {study.orders['value']:.2f})"


def test_projected_ends_do_not_depend_on_n():
    k = CASES["nd_A"]
    ref = sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=4096)
    exact = tol("sie-exact", "projected_ends")
    for n in (2, 17, 300):
        r = sie.solve_normal(k.punch, k.P, k.s, A=k.A, n=n)
        assert (r.a, r.c, r.alpha) == pytest.approx((ref.a, ref.c, ref.alpha), rel=exact, abs=0)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["nd_A", "nd_B", "nd_C", "nd_general", "nd_suppressed", "nd_near_lift_off"])
def test_plain_study_up_to_1600(name):
    """The plain scheme up to n = 1600: load ~2e-6 at n = 512, pressure ~1.4e-4 of the peak at n = 1600."""
    k, r, m, h = contact(name)
    ns = np.unique(np.geomspace(50, 1600, 16).astype(int))
    exact = Projected(2).moments(k.punch, m, h)[0][1]
    load = sie.convergence_study(lambda n: Plain(n).moments(k.punch, m, h)[0][1], ns,
                                 reference=exact, scale=abs(exact))
    x = np.linspace(-r.a, r.c, 1601)[1:-1]
    ref = Projected(16384).pressure(k.punch, k.A, m, h)[0](x)
    pres = sie.convergence_study(lambda n: Plain(n).pressure(k.punch, k.A, m, h)[0](x), ns,
                                 reference=ref, scale=ref.max())
    assert tol("sie-plain", "load_order") <= load.orders['value'] <= tol("sie-plain", "load_order_max"), \
        f"load order {load.orders['value']:.2f}"
    assert tol("sie-plain", "pressure_order") <= pres.orders['value'] <= tol("sie-plain", "pressure_order_max"), \
        f"pressure order {pres.orders['value']:.2f}"
    assert np.asarray(pres.errors['value'])[-1] < tol("sie-plain", "pressure_level_1600"), \
        f"pressure error {np.asarray(pres.errors['value'])[-1]:.2e} at n=1600"

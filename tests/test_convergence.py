"""The convergence tools on manufactured sequences whose order and limit are known exactly."""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart.convergence import fitted_order, gci, richardson, three_level_order
from threepart.tolerances import tolerance

EXACT = tolerance("convergence", "exact").limit
ITERATED = tolerance("convergence", "iterated").limit


@pytest.mark.parametrize("p, C", [(2.0, 0.3), (1.0, 5.0), (0.5, 1e-3)])
def test_fitted_order_of_an_exact_power_law(p, C):
    h = np.array([0.4, 0.2, 0.1, 0.05, 0.02])
    order, const = fitted_order(h, C * h**p)
    assert order == pytest.approx(p, abs=EXACT)
    assert const == pytest.approx(C, rel=EXACT)


def test_fitted_order_drops_round_off_and_non_finite_levels():
    h = np.array([0.4, 0.2, 0.1, 0.05])
    err = 2.0 * h**2
    err[-1] = 1e-16                                   # at the round-off floor
    order, _ = fitted_order(np.append(h, 0.01), np.append(err, np.nan))
    assert order == pytest.approx(2.0, abs=EXACT)
    assert all(math.isnan(v) for v in fitted_order([8, 16, 32], [1e-16, 2e-16, 1e-16]))
    # a diverging sequence has a negative order
    assert fitted_order(h, h**-1.0)[0] == pytest.approx(-1.0, abs=EXACT)


@pytest.mark.parametrize("h", [(0.4, 0.2, 0.1), (0.3, 0.2, 0.07)])
def test_three_level_order_of_an_exact_second_order_sequence(h):
    """Equal and unequal refinement ratios; no reference value is needed."""
    h3, h2, h1 = h
    f = [1.0 + 0.3 * x**2 for x in h]
    assert three_level_order(*f, h2 / h1, h3 / h2) == pytest.approx(2.0, rel=ITERATED)


def test_three_level_order_is_nan_when_not_monotone():
    assert math.isnan(three_level_order(1.0, 1.1, 1.05, 2.0, 2.0))   # oscillates
    assert math.isnan(three_level_order(1.0, 1.0, 1.2, 2.0, 2.0))    # two levels agree
    assert three_level_order(1.2, 1.1, 1.05, 2.0, 2.0) == pytest.approx(1.0, rel=ITERATED)


def test_gci_of_an_exact_second_order_sequence_bounds_the_true_error():
    """f = 1 + 0.3 h^2: the fine-grid error is 0.3 h1^2 and GCI = 1.25 times it (relative)."""
    h2, h1 = 0.2, 0.1
    f2, f1 = 1.0 + 0.3 * h2**2, 1.0 + 0.3 * h1**2
    g = gci(f2, f1, h2 / h1, 2.0)
    assert g == pytest.approx(1.25 * 0.3 * h1**2 / f1, rel=EXACT)
    assert g > abs(f1 - 1.0) / f1
    assert math.isnan(gci(f2, f1, 2.0, math.nan)) and math.isnan(gci(f2, f1, 2.0, -1.0))


def test_richardson_recovers_the_limit():
    h = np.array([0.4, 0.2, 0.1])
    assert richardson(h, 3.0 + 2.0 * h**2, 2.0) == pytest.approx(3.0, abs=EXACT)
    # arrays of values, one row per level; and with n instead of h (h = 1/n)
    n = np.array([10.0, 20.0, 40.0, 80.0])
    v = np.outer(n**-1.0, [1.0, -2.0]) + [5.0, 7.0]
    np.testing.assert_allclose(richardson(1 / n, v, 1.0), [5.0, 7.0], atol=EXACT)


@pytest.mark.parametrize("values, expected", [
    (1.0 + np.array([0.4, 0.2, 0.1]) ** 2, True),              # from one side, shrinking steps
    (1.0 - 3.0 * np.array([0.4, 0.2, 0.1, 0.05]) ** 3, True),
    ([1.78256, 1.78613, 1.786435, 1.786445], True),           # FEM c: the error vs a reference crosses 0
    ([1.0, 1.1, 1.05, 1.07], False),                          # oscillating
    ([1.0, 1.1, 1.3], False),                                 # steps that grow
    ([1.0, 1.0, 1.0], False),                                 # no change: no order
    ([1.0, 1.1], False),                                      # one step: no ratio
])
def test_monotone_convergence_is_told_from_the_values_alone(values, expected):
    from threepart.convergence import converges_monotonically

    assert converges_monotonically(values) is expected



# ---------------------------------------------------------------------------------------
# the one study driver, on manufactured sequences
# ---------------------------------------------------------------------------------------
def test_the_driver_fits_order_constant_and_limit_of_known_sequences():
    from threepart.convergence import run_study

    st = run_study(lambda n: (n, {"v": 3.0 + 2.0 * n**-2.0, "field": np.array([1.0, 2.0]) + n**-1.0},
                              {"dofs": 2 * n}),
                   [10, 20, 40, 80], param="n", reference={"v": 3.0, "field": np.array([1.0, 2.0])},
                   scales={"v": 3.0})
    assert st.orders["v"] == pytest.approx(2.0, abs=EXACT)
    assert st.constants["v"] == pytest.approx(2.0 / 3.0, rel=EXACT)     # error / scale
    assert st.extrapolated["v"] == pytest.approx(3.0, abs=EXACT)
    assert st.orders["field"] == pytest.approx(1.0, abs=EXACT)
    np.testing.assert_allclose(st.extrapolated["field"], [1.0, 2.0], atol=EXACT)
    assert st.info[-1] == {"dofs": 160} and st.h[-1] == pytest.approx(1 / 80)
    # the fine-grid GCI of a second-order sequence: Fs |f2 - f1| / f1 / (r^2 - 1), r = 2
    assert st.gci["v"] == pytest.approx(1.25 * (2 / 40**2 - 2 / 80**2) / (3 + 2 / 80**2) / 3,
                                        rel=ITERATED)


def test_the_driver_gives_no_order_for_a_non_monotone_error_and_says_so():
    from threepart.convergence import run_study

    wobble = {0.4: 1e-2, 0.2: 3e-3, 0.1: 5e-3, 0.05: 1e-3}   # the error rises at h = 0.1
    st = run_study(lambda h: (h, {"v": 1.0 + wobble[h]}, {}), list(wobble), reference={"v": 1.0})
    assert math.isnan(st.orders["v"]) and "not monotone" in st.notes[0]
    # reference-free: the same values do not converge from one side either
    free = run_study(lambda h: (h, {"v": 1.0 + wobble[h]}, {}), list(wobble))
    assert math.isnan(free.orders["v"]) and "v" not in free.gci


def test_the_driver_notes_a_failed_level_and_refuses_a_single_level():
    from threepart.convergence import run_study
    from threepart.errors import NoConvergenceError

    def evaluate(n):
        if n == 20:
            raise NoConvergenceError("did not settle")
        return n, {"v": 1.0 + n**-2.0}, {}

    st = run_study(evaluate, [10, 20, 40, 80], param="n", reference={"v": 1.0},
                   skip=(NoConvergenceError,))
    assert st.labels == ["10", "40", "80"] and "level 20: NoConvergenceError" in st.notes[0]
    assert st.orders["v"] == pytest.approx(2.0, abs=EXACT)
    with pytest.raises(ValueError, match="`levels`"):
        run_study(evaluate, [10])

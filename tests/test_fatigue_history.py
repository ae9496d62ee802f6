"""A Masing cycle's stress history superposed from its loading states (issue 33).

The reference is the history state by state: ``cycle.stress(x, z, Q, branch)`` of
each recorded state, the pressure and that state's shear integrated together
(the path every other method takes). The two differ only in the quadrature's
panels (the superposition integrates the pressure and each loading state's
shear apart), well inside the quadrature's own accuracy.
"""
from __future__ import annotations

import numpy as np
import pytest

import threepart.fatigue as fat
import threepart.fatigue.history as fh
from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.stress import stress

#: the quadrature of threepart.stress is accurate to 1e-8 of p0 (docs/STRESS.md); the two
#: histories differ by 5e-13 of p0 (measured), so a tenth of that accuracy still shows a wrong term
QUADRATURE = 1e-9
#: the hot spots' values: the superposition reorders a few additions (1e-15 measured)
HOT_SPOT = 1e-12


def _cycle(sigma_bulk: float, states: int = 5):
    case = get_case("caseA_moment")
    normal = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
    cycle = cf.fretting_cycle(normal, 0.2 * case.P, 0.5, states=states, sigma_bulk=sigma_bulk)
    W = normal.a + normal.c
    x = np.linspace(-normal.a - 0.25 * W, normal.c + 0.25 * W, 17)[None, :]
    z = np.linspace(0.0, W, 7)[:, None]
    p0 = float(np.max(normal.pressure(np.linspace(-normal.a, normal.c, 2001))))
    return cycle, x, z, p0


def _state_by_state(cycle, x, z, states=None):
    xb, zb = np.broadcast_arrays(x, z)
    idx = fh._distinct(cycle, fh._states(cycle, states))
    return fat.History.from_stresses([cycle.stress(xb, zb, float(cycle.Q[i]), str(cycle.branch[i]))
                                      for i in idx], Q=cycle.Q[idx], branch=cycle.branch[idx])


@pytest.mark.parametrize("sigma_bulk", [0.0, 40.0])
@pytest.mark.parametrize("states", [None, [0, 3, 6, 11, 14]])
def test_superposed_history_equals_the_states_one_by_one(sigma_bulk, states):
    cycle, x, z, p0 = _cycle(sigma_bulk)
    assert fh._superposes(cycle)
    got, want = fat.stress_history(cycle, x, z, states=states), _state_by_state(cycle, x, z, states)
    assert got.states == want.states
    np.testing.assert_array_equal(got.Q, want.Q)
    np.testing.assert_array_equal(got.branch, want.branch)
    for k in ("sxx", "szz", "sxz"):
        assert np.max(np.abs(getattr(got, k) - getattr(want, k))) <= QUADRATURE * p0, k
    for name, param in [("von_mises_range", fat.von_mises_range),
                        ("swt", lambda h: fat.swt(h, E=2.1e5)), ("findley", fat.findley)]:
        a, b = param(got).hot, param(want).hot
        assert (a.x, a.z) == (b.x, b.z), name
        assert abs(a.value - b.value) <= HOT_SPOT * abs(b.value), name


def test_superposition_makes_one_evaluation_per_loading_state(monkeypatch):
    """5 states per branch: the pressure and 4 loading shears, instead of 12 states of two tractions."""
    cycle, x, z, _ = _cycle(0.0)
    calls: list[int] = []
    real = stress

    def counting(*args, **kwargs):
        calls.append((kwargs["pressure"] is not None) + (kwargs.get("shear") is not None))
        return real(*args, **kwargs)

    monkeypatch.setattr("threepart.stress.flamant.stress", counting)
    fat.stress_history(cycle, x, z)
    assert sorted(calls) == [1] * 5


def test_stress_of_the_shear_alone_is_the_difference_of_the_totals():
    """``pressure=None``: the shear's stresses, which the pressure's complete (Flamant is linear)."""
    cycle, x, z, p0 = _cycle(0.0)
    n = cycle.normal
    ends, kinks = (-n.a, n.c), cycle.state_kinks(cycle.Q_max, "loading")
    q = lambda t: cycle.shear(t, cycle.Q_max, "loading")   # noqa: E731
    both = stress(x, z, pressure=n.pressure, shear=q, ends=ends, kinks=kinks)
    alone = stress(x, z, pressure=n.pressure, ends=ends, kinks=kinks)
    shear = stress(x, z, pressure=None, shear=q, ends=ends, kinks=kinks)
    for k in ("sxx", "szz", "sxz"):
        assert np.max(np.abs(getattr(alone, k) + getattr(shear, k) - getattr(both, k))) <= QUADRATURE * p0
    with pytest.raises(TypeError, match="`pressure` must be a callable"):
        stress(x, z, pressure=None, ends=ends)

"""The SIE load history (issue 31): histories of any shape, marched with the memory of slip.

References that owe nothing to the marching: the closed form's partial slip
(a monotonic P-then-Q path, also under a bulk stress) and fretting cycle
(Masing's superposition: stick zones and energy), Cattaneo–Mindlin's Hertz
shear, shakedown under a shear in phase with the load (no slip after the
first cycle, zero energy), the same steady state from two first-loading
paths, the equilibrium and Coulomb's bound of every state, and the grid
convergence of the energy (:func:`threepart.convergence.fitted_order`).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import closedform as cf
from threepart import sie
from threepart.problem.catalogue import load_cases
from threepart.convergence import fitted_order
from threepart.halfplane.load_history import History, check_history, read_history
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance

CASES = {c.name: c.resolved() for c in load_cases("sie")}
#: the coefficient of friction of every history here
F = 0.5
#: Hertz: R = 2, A = 0.01, P = 3 (a = 0.195, inside the arcs and the small-slope limit)
HERTZ, A_H, P_H = Punch(2.0, 2.0, 0.0), 0.01, 3.0
#: states per in-phase cycle
PERIOD = 12


def tol(quantity: str) -> float:
    return tolerance("sie-history", quantity).limit


def ramp(P, s, Q, sb=0.0, steps=10):
    """``P`` at ``s`` first, then ``Q`` (and ``sb``) in proportion: the closed form's load path."""
    return [(P, s, 0.0, 0.0)] + [(P, s, Q * j / steps, sb * j / steps) for j in range(1, steps + 1)]


def fretting(P, s, Q_max, states=21):
    """``0 -> Q_max -> -Q_max -> Q_max`` at the states of closedform.fretting_cycle (each once)."""
    Qs = np.concatenate([np.linspace(0, Q_max, states), np.linspace(Q_max, -Q_max, states)[1:],
                         np.linspace(-Q_max, Q_max, states)[1:]])
    return [(P, s, float(Q), 0.0) for Q in Qs]


def in_phase(first, P0, Q0, dP, dQ, cycles):
    th = np.linspace(0, 2 * np.pi * cycles, PERIOD * cycles + 1)[1:]
    return list(first) + [(P0 + dP * math.sin(t), 0.0, Q0 + dQ * math.sin(t), 0.0) for t in th]


@pytest.mark.parametrize("sigma_bulk", [0.0, 0.03])
def test_monotonic_path_ends_at_the_closed_form_stick_zone(sigma_bulk):
    """(a) P then Q (and a bulk stress in proportion): the stick zone [-(d+e), d-e] of the closed form."""
    k = CASES["nd_A"]
    Q = 0.6 * F * k.P
    ref = cf.solve_partial_slip(cf.solve_normal(k.punch, k.P, k.s, A=k.A), Q, F, sigma_bulk=sigma_bulk)
    r = sie.load_history(k.punch, ramp(k.P, k.s, Q, sigma_bulk), F, A=k.A)
    h = r.info["h"]
    (left, right), = r.stick[-1]
    assert abs(left + ref.d + ref.e) <= tol("stick_end") * h, (left, -(ref.d + ref.e), h)
    assert abs(right - ref.d + ref.e) <= tol("stick_end") * h, (right, ref.d - ref.e, h)
    assert r.energy.size == 0 and r.cycles == ()


def test_equilibrium_and_coulomb_in_every_state():
    """∑ q h = Q and |q| <= f p̄ (the element's mean pressure) in each state of a fretting history."""
    k = CASES["nd_A"]
    Q_max = 0.6 * F * k.P
    r = sie.load_history(k.punch, fretting(k.P, k.s, Q_max, 6), F, A=k.A, n=200)
    h = np.diff(r.edges)
    p_bar = sie.history.element_loads(r.normals[0], r.edges) / h
    for q, Q in zip(r.q_nodes, r.Q):
        assert abs(np.sum(q * h) - Q) <= tol("equilibrium") * Q_max
        assert np.all(np.abs(q) <= F * p_bar * (1 + tol("equilibrium")))


@pytest.mark.parametrize("n", [7, 100, 400])
def test_element_loads_sum_to_P(n):
    """The elements' ∫p dx (the Coulomb bounds' pressure) sum to P, with joins inside elements."""
    k = CASES["nd_A"]
    normal = sie.solve_normal(k.punch, k.P, k.s, A=k.A)
    edges = np.linspace(-normal.a - 0.1, normal.c + 0.05, n + 1)
    total = sie.history.element_loads(normal, edges).sum()
    assert abs(total / k.P - 1) <= tol("element_loads")


def _drop_reversal_repeats(fc):
    """The closed form records each reversal twice (end of a branch, start of the next): keep the first."""
    keep = np.r_[True, np.diff(fc.Q) != 0]
    return fc.stick[keep]


@pytest.fixture(scope="module")
def cycle_nd_A():
    k = CASES["nd_A"]
    Q_max = 0.6 * F * k.P
    fc = cf.fretting_cycle(cf.solve_normal(k.punch, k.P, k.s, A=k.A), Q_max, F)
    return k, Q_max, fc


@pytest.mark.parametrize("sigma_bulk", [0.0, 0.03])
def test_fretting_cycle_against_masing(cycle_nd_A, sigma_bulk):
    """(b) constant P: the stick zone of every state and the energy per cycle of closedform.fretting_cycle
    (under a bulk stress in phase with Q, the friction work of eq. B9)."""
    k, Q_max, fc = cycle_nd_A
    if sigma_bulk:
        fc = cf.fretting_cycle(cf.solve_normal(k.punch, k.P, k.s, A=k.A), Q_max, F, sigma_bulk=sigma_bulk)
    states = [(P, s, Q, sigma_bulk * Q / Q_max) for P, s, Q, _ in fretting(k.P, k.s, Q_max)]
    r = sie.load_history(k.punch, states, F, A=k.A, n=400)
    assert r.cycles == ((20, 60),)          # the turning point Q_max, reached on the way up
    assert abs(r.energy[0] / fc.energy - 1) <= tol("energy"), (r.energy, fc.energy)
    ref = _drop_reversal_repeats(fc)
    h = r.info["h"]
    got = np.array([r.stick_zone(j) for j in range(len(r))])
    assert got.shape == ref.shape
    err = np.abs(got - ref).max() / h
    assert err <= tol("stick_end"), f"stick-zone ends off by {err:.3g} elements"


def test_energy_converges_in_the_grid(cycle_nd_A):
    """The energy per cycle against the closed form over n = 100, 200, 400: the fitted order and its level."""
    k, Q_max, fc = cycle_nd_A
    ns = [100, 200, 400]
    err = [abs(sie.load_history(k.punch, fretting(k.P, k.s, Q_max, 6), F, A=k.A, n=n).energy[0]
               / fc.energy - 1) for n in ns]
    p, _ = fitted_order(1.0 / np.array(ns), err)
    assert p >= tol("energy_order"), f"observed order {p:.3g}, errors {err}"
    assert err[-1] <= tol("energy"), f"error {err[-1]:.3g} at n = 400 (observed order {p:.3g})"


def test_cattaneo_mindlin_hertz():
    """(c) Hertz, P then Q: d = a sqrt(1 - Q/fP), q = f p0 [sqrt(1 - x^2/a^2) - (d/a) sqrt(1 - x^2/d^2)]."""
    Q = 0.6 * F * P_H
    r = sie.load_history(HERTZ, ramp(P_H, 0.0, Q), F, A=A_H)
    a = r.normals[-1].a
    p0 = 2 * P_H / (math.pi * a)
    d = a * math.sqrt(1 - Q / (F * P_H))
    left, right = r.stick_zone(-1)
    h = r.info["h"]
    assert max(abs(left + d), abs(right - d)) <= tol("stick_end") * h
    # the exact shear's mean over each element, by 64-point Gauss–Legendre
    s, w = np.polynomial.legendre.leggauss(64)
    e0, e1 = r.edges[:-1, None], r.edges[1:, None]
    x = 0.5 * (e0 + e1) + 0.5 * (e1 - e0) * s[None, :]
    q = F * p0 * (np.sqrt(np.clip(1 - (x / a) ** 2, 0, None)) - d / a * np.sqrt(np.clip(1 - (x / d) ** 2, 0, None)))
    mean = 0.5 * np.sum(w * q, axis=1)
    L1 = np.sum(np.abs(r.q_nodes[-1] - mean)) * h / Q
    assert L1 <= tol("shear_L1"), f"∫|Δq|/Q = {L1:.3g}"


def test_shakedown_in_phase_hertz():
    """(d) Hertz, Q in phase with P and |ΔQ| < f ΔP: no slip after the first cycle, zero energy."""
    first = [(P_H * j / 4, 0.0, 0.0, 0.0) for j in range(1, 5)] + \
            [(P_H, 0.0, 0.3 * F * P_H * j / 4, 0.0) for j in range(1, 5)]
    dP = 0.2 * P_H
    r = sie.load_history(HERTZ, in_phase(first, P_H, 0.3 * F * P_H, dP, 0.5 * F * dP, 4), F, A=A_H,
                         period=PERIOD)
    assert len(r.energy) == 4 and r.energy[0] > 0     # the first cycle slips
    assert np.all(r.energy[1:] <= tol("shakedown") * r.energy[0]), r.energy
    after = len(first) - 1 + PERIOD
    drift = np.abs(r.slip_nodes[-1] - r.slip_nodes[after]).max()
    assert drift <= tol("shakedown") * np.abs(r.slip_nodes).max()


def test_steady_state_does_not_depend_on_the_first_loading():
    """(e) The same in-phase cycle after P then Q, and after P and Q together: the same steady state."""
    Q0, dQ, dP = 0.3 * F * P_H, 0.25 * F * P_H, 0.2 * P_H
    p_first = [(P_H * j / 4, 0.0, 0.0, 0.0) for j in range(1, 5)] + [(P_H, 0.0, Q0 * j / 4, 0.0) for j in range(1, 5)]
    together = [(P_H * j / 8, 0.0, Q0 * j / 8, 0.0) for j in range(1, 9)]
    r1, r2 = (sie.load_history(HERTZ, in_phase(path, P_H, Q0, dP, dQ, 3), F, A=A_H, period=PERIOD)
              for path in (p_first, together))
    assert r1.energy[0] != pytest.approx(r2.energy[0], rel=tol("steady"))   # the first cycles differ
    assert r1.energy[-1] == pytest.approx(r2.energy[-1], rel=tol("steady"))
    last = range(len(r1) - PERIOD, len(r1))
    assert all(r1.stick[j] == r2.stick[j] for j in last)
    # the permanent stick zone: the elements that stuck in every state of the last cycle
    x = r1.x_nodes
    permanent = np.all([[any(lo <= xi <= hi for lo, hi in r1.stick[j]) for xi in x] for j in last], axis=0)
    p_max = max(float(np.max(n.pressure(x))) for n in r1.normals)
    for j in last:
        diff = np.abs(r1.q_nodes[j] - r2.q_nodes[j])[~permanent]
        assert diff.max() <= tol("steady") * F * p_max


def test_cycles_close_at_the_last_state():
    """A zero crossing passed up and down closes one cycle, not two; ``period`` counts back from the end."""
    up_down = in_phase([(1.0, 0.0, 0.0, 0.0)], 1.0, 0.0, 0.0, 0.1, 2)
    hist = check_history(up_down)
    assert hist.cycles() == ((0, PERIOD), (PERIOD, 2 * PERIOD))
    assert hist.cycles(5) == tuple((i, i + 5) for i in range(4, 2 * PERIOD - 4, 5))


def test_a_csv_history_is_the_sequence(tmp_path):
    states = fretting(0.1, 0.1, 0.03, 4)
    path = tmp_path / "h.csv"
    path.write_text("Q,P,sigma_bulk,s,comment\n" + "".join(f"{Q!r},{P!r},{b!r},{s!r},x\n" for P, s, Q, b in states))
    got = read_history(path)
    assert isinstance(got, History) and len(got) == len(states)
    assert np.array_equal(np.column_stack([got.P, got.s, got.Q, got.sigma_bulk]), np.array(states))


@pytest.mark.parametrize("text, match", [
    ("P,s,Q,sigma_bulk\n1,0,0,0\nnan,0,0.1,0\n", r"h\.csv', row 3, column `P`: 'nan' must be a finite number"),
    ("P,s,Q,sigma_bulk\n1,0,0,0\n-1,0,0.1,0\n", r"row 3, column `P`: '-1' must be > 0"),
    ("P,s,Q,sigma_bulk\n0,0,0,0\n", r"row 2, column `P`: '0' must be > 0"),
    ("P,s,Q,sigma_bulk\n1,0,abc,0\n", r"row 2, column `Q`: 'abc' is not a number"),
    ("P,s,Q\n1,0,0\n", r"has no column `sigma_bulk`"),
    ("P,s,Q,sigma_bulk\n", r"has no states below its header"),
])
def test_csv_errors_name_the_file_the_row_and_the_column(tmp_path, text, match):
    path = tmp_path / "h.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=match):
        sie.load_history(HERTZ, path, F, A=A_H)


def test_input_errors():
    with pytest.raises(ValueError, match="cannot be read"):
        read_history("/nonexistent/h.csv")
    with pytest.raises(ValueError, match=r"`history\[1\].s` = nan must be a finite number"):
        sie.load_history(HERTZ, [(P_H, 0.0, 0.0, 0.0), (P_H, math.nan, 0.0, 0.0)], F, A=A_H)
    with pytest.raises(ValueError, match=r"`history` state 1: \|`Q`\| = 2 >= f P = 1.5"):
        sie.load_history(HERTZ, [(P_H, 0.0, 0.0, 0.0), (P_H, 0.0, 2.0, 0.0)], F, A=A_H)
    with pytest.raises(ValueError, match="`history` has no states"):
        sie.load_history(HERTZ, [], F, A=A_H)
    with pytest.raises(TypeError, match=r"`history` state 0 = .* has 2 values: it must be a \(P, s, Q, sigma_bulk\) tuple"):
        sie.load_history(HERTZ, [(P_H, 0.0)], F, A=A_H)
    with pytest.raises(TypeError, match="`history` must be a sequence"):
        sie.load_history(HERTZ, 3.0, F, A=A_H)
    with pytest.raises(ValueError, match=r"`period` = 0 must lie in \[1, 1\]"):
        sie.load_history(HERTZ, [(P_H, 0.0, 0.0, 0.0)] * 2, F, A=A_H, period=0)
    with pytest.raises(ValueError, match=r"`k` = 5 must be a state index"):
        sie.load_history(HERTZ, [(P_H, 0.0, 0.0, 0.0)], F, A=A_H, n=16).shear(0.0, 5)


@pytest.mark.parametrize("dP", [0.0, 40.0])
def test_the_loop_s_area_is_the_friction_work_of_the_cycle(dP):
    """∮ Q dδ over a steady cycle is the energy dissipated: an identity independent of the march's work sum.

    The normal load's work is conservative in the uncoupled problem, so a P cycling in phase
    adds nothing to the loop's area; the shoelace area of (δ_k, Q_k) and the march's
    Σ |Δslip| f p (trapezoidal in the states) then agree to the states' resolution.
    """
    punch, A_ = Punch(R1=10.0, R2=5.0, b=1.0), 4 * (1 - 0.3**2) / 420e3
    ramp = [(400.0 * j / 4, 0.1, 0.0, 0.0) for j in range(1, 5)]
    cycle = [(400.0 + dP * math.sin(t), 0.1, 80.0 * math.sin(t), 0.0)
             for t in [2 * math.pi * k / 40 for k in range(1, 121)]]
    h = sie.load_history(punch, ramp + cycle, 0.5, A=A_, period=40)
    d, Q = h.loop()
    assert d[0] == pytest.approx(d[-1], abs=tolerance("sie-history", "steady").limit * np.ptp(d))
    area = 0.5 * abs(float(np.sum(d[:-1] * Q[1:] - d[1:] * Q[:-1])))
    assert abs(area / h.energy[-1] - 1) <= tolerance("sie-history", "loop_area").limit

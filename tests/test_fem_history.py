"""The FEM load history (issue 31) against the SIE's, on the quick mesh.

One in-phase cycle of ``P`` and ``Q`` (the contact grows and shrinks, the
stick zone moves) after ``P`` first: the FE model, meshed once for the union
of the contacts, and the SIE's log-kernel march are independent
discretisations of the same half-plane problem; their stick zones must agree
within a few of the FE elements and their friction work per cycle within a
few per cent.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import fem, sie
from threepart.errors import ContactZoneError
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance

#: a small nondimensional problem (E = 1: loads of order 1e-2), as tests/test_fem_friction.py's
PUNCH = Punch(R1=10.0, R2=5.0, b=1.0)
E, NU, P, S, F = 1.0, 0.3, 0.05, 0.1, 0.5
#: states per in-phase cycle
PERIOD = 12


def tol(quantity: str) -> float:
    return tolerance("fem-history", quantity).limit


def in_phase(cycles: int) -> list[tuple[float, float, float, float]]:
    """``P`` in four steps, then ``P (1 + 0.2 sin θ)`` and ``Q = 0.5 f P sin θ``: ``|ΔQ| > f ΔP``, it slips."""
    first = [(P * (j + 1) / 4, S, 0.0, 0.0) for j in range(4)]
    th = np.linspace(0, 2 * np.pi * cycles, PERIOD * cycles + 1)[1:]
    return first + [(P * (1 + 0.2 * math.sin(t)), S, 0.5 * F * P * math.sin(t), 0.0) for t in th]


@pytest.fixture(scope="module")
def pair():
    history = in_phase(1)
    fe = fem.load_history(PUNCH, history, F, E=E, nu=NU, mesh="quick", period=PERIOD, progress=False)
    si = sie.load_history(PUNCH, history, F, A=4 * (1 - NU**2) / E, period=PERIOD)
    return fe, si


def test_one_in_phase_cycle_against_the_sie(pair):
    fe, si = pair
    assert fe.cycles == si.cycles == ((3, 3 + PERIOD),)
    assert abs(fe.energy[0] / si.energy[0] - 1) <= tol("energy"), (fe.energy, si.energy)
    h = fe.diagnostics.h
    for k in range(len(fe)):
        got, ref = np.array(fe.stick_zone(k)), np.array(si.stick_zone(k))
        assert np.abs(got - ref).max() <= tol("stick_end") * h, (k, got, ref, h)


def test_equilibrium_and_coulomb(pair):
    """``∑ t = Q`` and ``|t_i| <= f fn_i`` at every state (the nodal forces of the result's shear)."""
    fe, _ = pair
    w = fe.info["weights"]
    for k, Q in enumerate(fe.Q):
        t = fe.q_nodes[k] * w
        fn = fe.normals[k].p_nodes * w
        assert abs(t.sum() - Q) <= tolerance("sie-history", "equilibrium").limit * F * P
        assert np.all(np.abs(t) <= F * fn * (1 + tolerance("sie-history", "equilibrium").limit))


@pytest.mark.slow
def test_steady_cycles_on_the_default_mesh():
    """Three in-phase cycles on the default mesh (9 s measured): the energy of each against the SIE
    at n = 1600, and the steady state (the third cycle repeats the second)."""
    history = in_phase(3)
    fe = fem.load_history(PUNCH, history, F, E=E, nu=NU, mesh="default", period=PERIOD, progress=False)
    si = sie.load_history(PUNCH, history, F, A=4 * (1 - NU**2) / E, period=PERIOD, n=1600)
    assert len(fe.energy) == len(si.energy) == 3
    err = np.abs(fe.energy / si.energy - 1)
    assert np.all(err <= tolerance("fem-history", "energy_default").limit), err
    assert fe.energy[2] == pytest.approx(fe.energy[1], rel=tolerance("sie-history", "steady").limit)


def test_a_contact_beyond_the_mesh_is_refused():
    """A mesh whose contact zone is narrower than a state's contact: ContactZoneError naming the state's load."""
    spec = fem.PRESETS["quick"].spec(-0.8, 0.8, (-1.0, 1.0))
    with pytest.raises(ContactZoneError, match=r"the contact of `P` = 0.01 at `s` = 0.1 reaches the end"):
        fem.load_history(PUNCH, [(0.01, S, 0.0, 0.0), (P, S, 0.0, 0.0)], F, E=E, nu=NU, mesh=spec,
                         progress=False)


def test_input_errors_name_the_state():
    with pytest.raises(ValueError, match=r"`history` state 1: \|`Q`\| = 0.03 >= f P = 0.025"):
        fem.load_history(PUNCH, [(P, S, 0.0, 0.0), (P, S, 0.03, 0.0)], F, E=E, nu=NU, mesh="quick")
    with pytest.raises(ValueError, match=r"`history` state 0: `s` = 20.0 lies outside the punch's footprint"):
        fem.load_history(PUNCH, [(P, 20.0, 0.0, 0.0)], F, E=E, nu=NU, mesh="quick")

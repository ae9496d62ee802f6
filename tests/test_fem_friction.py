"""Two-body Coulomb-friction FE model: partial slip and the fretting cycle on the quick mesh.

References: the closed form (the catalogue's partial-slip cases, judged by the
verification run's comparator on the ``"fem-quick"`` rows), the SIE where the
stick zone ends on the central segment (the closed form refuses), Cattaneo's
``d = a sqrt(1 - Q/fP)`` for Hertz, the reflection symmetry of a mirrored body,
and the exact properties of Coulomb friction under a monotone or cyclic load.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import closedform, fem, sie
from threepart.problem.catalogue import get_case
from threepart.errors import FullSlidingError
from threepart.problem.punch import Punch
from threepart.results import FrettingResult
from threepart.reports.compare import compare
from threepart.reports import solvers
from threepart.tolerances import tolerance

#: A = 4 (1 - nu^2) / E of the two-body model against the case's: rounding of the conversion
CONVERSION = 1e-12
#: |t_i| <= f fn_i to the rounding of the active set's projection (relative, and absolute in Q)
COULOMB, COULOMB_FLOOR = 1e-12, 1e-15
#: G' = R G R of the condensed compliances, and the zero coupling blocks: rounding of the sparse
#: solves, relative to the largest compliance
CONDENSED = 1e-10
#: one load step against five under a monotone Q (Mindlin): the active set's iteration stop
STEPS = 1e-9
#: Q -> -Q, the loop's closure and the stick zone's zero slip: the same linear solves, rounding only
REVERSAL = 1e-12
#: the cycle's energy by the friction work and by ∮Q dξ over the same states
LOOP_ENERGY = 1e-9
#: reloading to Q_max restores the loading state at Q_max (Masing): the active set's iteration stop
MASING = 1e-9
#: the energy's observed order in the load step: trapezoidal, theory 2
STEP_ORDER = (1.5, 2.5)

SLIP_CASES = ("slip_Q0.2", "slip_Q0.4", "slip_Q0.7")
#: a small nondimensional problem for the properties (E = 1: loads of order 1e-2)
PUNCH = Punch(R1=10.0, R2=5.0, b=1.0)
E, NU, P, S, F = 1.0, 0.3, 0.05, 0.1, 0.5


def tol(quantity: str, comparison: str = "fem-quick") -> float:
    return tolerance(comparison, quantity).limit


def fem_slip(case_name: str):
    case = get_case(case_name).resolved()
    return case, solvers.slip("fem", case, None, mesh="quick")


@pytest.fixture(scope="module", params=SLIP_CASES)
def slip_pair(request):
    case, fe = fem_slip(request.param)
    ref = closedform.solve_partial_slip(
        closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A), *case.shear_load)
    return case, ref, fe


def test_agrees_with_the_closed_form(slip_pair):
    case, ref, fe = slip_pair
    assert fe.method == "fem" and math.isclose(fe.normal.A, case.A, rel_tol=CONVERSION)
    failed = {c.quantity: f"{c.error:.2e} > {c.limit:g}" for c in compare(ref, fe, "fem-quick")
              if not c.passed}
    assert not failed, f"{case.name}: two-body FEM disagrees with closedform: {failed}"


def test_shear_integrates_to_Q_and_never_exceeds_friction(slip_pair):
    """The interpolated shear field integrates to Q (sum t_i = Q itself is imposed by the solve)."""
    case, _, fe = slip_pair
    Q, f = case.shear_load
    last = fe.history[-1]
    assert np.all(np.abs(last.t) <= f * last.fn * (1 + COULOMB) + COULOMB_FLOOR * abs(Q))
    x = np.linspace(-fe.a, fe.c, 20001)
    assert abs(np.trapezoid(fe.shear(x), x) / Q - 1) < tol("load_integral")
    assert np.all(fe.shear(x) * Q >= 0)                              # the shear has the sign of Q


def test_stick_zone_on_the_central_segment_agrees_with_the_sie():
    """Past the closed form (it raises StickZoneError): the SIE is the reference."""
    case, fe = fem_slip("beyond_stick_centre")
    normal = sie.solve_normal(case.punch, case.P, case.s_load, A=case.A)
    ref = sie.solve_partial_slip(normal, *case.shear_load)
    assert not ref.within_paper and ref.stick_zone[0] > -case.punch.b
    failed = {c.quantity: f"{c.error:.2e} > {c.limit:g}" for c in compare(ref, fe, "fem-quick")
              if not c.passed}
    assert not failed, f"FEM disagrees with the SIE past the paper: {failed}"


@pytest.mark.parametrize("ratio", [0.3, 0.8])
def test_hertz_limit_is_cattaneo(ratio):
    """b = 0, equal radii: the stick zone is centred, d = a sqrt(1 - Q/fP) (Cattaneo 1938)."""
    punch = Punch(R1=10.0, R2=10.0, b=0.0)
    fe = fem.solve_partial_slip(punch, P, 0.0, Q=ratio * F * P, f=F, E=E, nu=NU, mesh="quick")
    ref = closedform.solve_normal(punch, P, 0.0, A=4 * (1 - NU**2) / E)
    d = ref.a * math.sqrt(1 - ratio)
    assert abs(fe.d - d) / d < tol("d")
    assert abs(fe.e) / d < tol("e")


def test_mirrored_body_by_reflection_equals_condensing_its_mesh():
    """G' = R G R for the mirror image (R = diag(1, -1)): and the bodies uncouple (Dundurs beta = 0)."""
    spec = fem.PRESETS["trial"].spec(-1.5, 1.5, (-1.0, 1.0))
    lower = fem.make_substrate(spec)
    meshed = fem.interface(lower, fem.mirror(lower), E, NU)
    reflected = fem.interface(lower, None, E, NU)
    scale = np.abs(meshed.C_nn).max()
    for name in ("C_nn", "C_tt", "C_nt", "C_tn"):
        diff = np.abs(getattr(meshed, name) - getattr(reflected, name)).max()
        assert diff < CONDENSED * scale, (name, diff / scale)
    assert np.abs(meshed.C_nt).max() < CONDENSED * scale     # the normal and shear problems uncouple
    assert np.abs(meshed.C_tn).max() < CONDENSED * scale


def test_monotone_loading_does_not_depend_on_the_steps_and_Q_reverses_the_shear():
    """Under a monotone Q the stick zone only shrinks: one step gives the state of many (Mindlin)."""
    Q = 0.3 * F * P
    one = fem.solve_partial_slip(PUNCH, P, S, Q=Q, f=F, E=E, nu=NU, mesh="quick", steps=1)
    five = fem.solve_partial_slip(PUNCH, P, S, Q=Q, f=F, E=E, nu=NU, mesh="quick", steps=5)
    back = fem.solve_partial_slip(PUNCH, P, S, Q=-Q, f=F, E=E, nu=NU, mesh="quick", steps=1)
    qmax = np.abs(one.q_nodes).max()
    assert len(five.history) == 5
    assert abs(one.d - five.d) < STEPS * one.d and abs(one.e - five.e) < STEPS * one.d
    assert np.abs(one.q_nodes - five.q_nodes).max() < STEPS * qmax
    assert np.abs(one.q_nodes + back.q_nodes).max() < REVERSAL * qmax
    assert (back.d, back.e) == pytest.approx((one.d, one.e), rel=REVERSAL)


@pytest.fixture(scope="module")
def cycle():
    return fem.fretting_cycle(PUNCH, P, S, Q_max=0.4 * F * P, f=F, E=E, nu=NU, mesh="quick",
                              states=11)


def test_fretting_energy_is_the_loop_area_and_the_cycle_closes(cycle):
    """Energy balance: the friction work on the slip equals the work of Q on the plate (∮ Q dxi)."""
    assert cycle.energy > 0
    assert abs(cycle.info["loop_energy"] / cycle.energy - 1) < LOOP_ENERGY
    x = np.linspace(-cycle.normal.a, cycle.normal.c, 2001)
    q_load = cycle.shear(x, cycle.Q_max, "loading")
    q_back = cycle.shear(x, cycle.Q_max, "reloading")
    # Masing: reloading to Q_max restores the loading state at Q_max
    assert np.abs(q_back - q_load).max() < MASING * np.abs(q_load).max()
    W = cycle.normal.width
    assert np.abs(cycle.stick[cycle.branch == "loading"][-1] - cycle.stick[-1]).max() < MASING * W
    Q, h = cycle.loop()
    assert abs(h[-1]) < REVERSAL * abs(cycle.delta).max()


def test_fretting_state_stress_is_flamants_over_its_own_tractions(cycle):
    """The FE field at depth >= 0.2a against Flamant's kernels over the same state's nodal
    tractions (the base FrettingResult.stress, an independent evaluation of the same
    solution); issue 21's target 1e-2 p0. At -Q_max the shear is reversed: the FE σxz
    follows it."""
    n = cycle.normal
    x = np.linspace(-1.5 * n.a, 1.5 * n.c, 21)[:, None]
    z = np.array([0.2, 0.6])[None, :] * n.width / 2
    p0 = max(pk.p for pk in n.peaks())
    for Q, branch in ((cycle.Q_max, "loading"), (-cycle.Q_max, "unloading")):
        fe = cycle.stress(x, z, Q, branch)
        ref = FrettingResult.stress(cycle, x, z, Q, branch, nu=NU)
        for k in ("sxx", "szz", "sxz"):
            err = np.abs(getattr(fe, k) - getattr(ref, k)).max() / p0
            assert err < tolerance("fem-quick", "stress_depth").limit, f"{branch} {k}: {err:.2e} p0"
    with pytest.raises(ValueError, match="`nu`"):
        cycle.stress(x, z, cycle.Q_max, "loading", nu=0.2)


def test_fretting_slip_amplitude_vanishes_in_the_stick_zone(cycle):
    lo, hi = cycle.stick[cycle.branch == "loading"][-1]
    x = np.linspace(-cycle.normal.a, cycle.normal.c, 4001)[1:-1]
    amp = cycle.slip_amplitude(x)
    h = 2 * cycle.normal.diagnostics.h_end
    assert np.abs(amp[(x > lo + h) & (x < hi - h)]).max() < REVERSAL * amp.max()
    assert amp[x < lo - h].min() > 0 and amp[x > hi + h].min() > 0


def test_fretting_energy_converges_in_the_load_steps(cycle):
    """The energy's trapezoidal error falls as the step squared (observed order near 2)."""
    # the middle one is the module's cycle (the same call, states=11), solved once
    energies = [fem.fretting_cycle(PUNCH, P, S, Q_max=0.4 * F * P, f=F, E=E, nu=NU, mesh="quick",
                                   states=k).energy if k != 11 else cycle.energy for k in (6, 11, 21)]
    ratio = (energies[1] - energies[0]) / (energies[2] - energies[1])
    assert STEP_ORDER[0] < math.log2(ratio) < STEP_ORDER[1], energies


@pytest.mark.parametrize("kwargs, match", [
    (dict(Q=0.025, f=0.5), r"`Q`.*f P"),
    (dict(Q=0.01, f=0.0), r"`f`"),
    (dict(Q=math.nan, f=0.5), r"`Q`"),
    (dict(Q=0.01, f=0.5, steps=0), r"`steps`"),
])
def test_bad_input_is_refused_before_any_meshing(kwargs, match):
    with pytest.raises(ValueError, match=match):
        fem.solve_partial_slip(PUNCH, P, S, E=E, nu=NU, mesh="quick", **kwargs)


def test_full_sliding_is_the_named_error():
    with pytest.raises(FullSlidingError, match="Q_max"):
        fem.fretting_cycle(PUNCH, P, S, Q_max=F * P, f=F, E=E, nu=NU, mesh="quick")
    with pytest.raises(ValueError, match="states"):
        fem.fretting_cycle(PUNCH, P, S, Q_max=0.01, f=F, E=E, nu=NU, mesh="quick", states=1)


def test_fretting_cycle_agrees_with_the_closed_form():
    """Energy, stick zones, loop and shear of the catalogue's cycle against the closed form's."""
    case = get_case("fretting_Q0.4").resolved()
    ref = solvers.fretting("closedform", case, solvers.normal("closedform", case), 21)
    fe = solvers.fretting("fem", case, None, 21, mesh="quick")
    failed = {c.quantity: f"{c.error:.2e} > {c.limit:g}" for c in compare(ref, fe, "fem-quick")
              if not c.passed}
    assert not failed, f"FEM fretting cycle disagrees with the closed form: {failed}"
    assert abs(fe.energy / ref.energy - 1) < tol("energy")        # issue 11: within 2 %


def test_suppressed_tilt_agrees_with_the_closed_form():
    """The loading plate held level (alpha = 0): the closed form's suppressed-tilt stick zone."""
    A = 4 * (1 - NU**2) / E
    ref = closedform.solve_partial_slip(closedform.solve_normal(PUNCH, P, A=A, tilt="suppressed"),
                                        0.4 * F * P, F)
    fe = fem.solve_partial_slip(PUNCH, P, Q=0.4 * F * P, f=F, E=E, nu=NU, tilt="suppressed",
                                mesh="quick")
    assert fe.alpha == 0.0 and fe.normal.tilt == "suppressed"
    failed = {c.quantity: f"{c.error:.2e} > {c.limit:g}" for c in compare(ref, fe, "fem-quick")
              if not c.passed}
    assert not failed, f"suppressed tilt: {failed}"


def test_a_two_body_contact_past_the_slope_limit_is_refused_before_any_shear():
    """Two similar cylinders (b = 0) at the load Hertz gives a = 0.6 R (A = 4 (1 - nu^2) / E,
    a^2 = 2 A P R / pi): the surface slope a/R passes SLOPE_LIMIT = 0.5, so the
    normal contact is refused before Q is applied."""
    from pathlib import Path

    from threepart import meshes
    from threepart.errors import SlopeLimitError

    A = 4 * (1 - NU**2) / E
    R, a = 1.0, 0.6
    P_ = math.pi * a**2 / (2 * A * R)
    with pytest.raises(SlopeLimitError, match="small-slope limit"):
        fem.solve_partial_slip(Punch(R, R, 0.0), P_, Q=0.1 * P_, f=0.5, E=E, nu=NU,
                               mesh=Path(meshes.__file__).parent / "reference.msh", steps=2)

"""Partial slip of the punch of real shape on a finite block (issue 23): fem.solve_finite_slip.

References: the closed form and the existing two-body solver (fem.solve_partial_slip)
for the paper's model through the new path (H = None), the same solver on the same
mesh to round-off, the closed form in the half-plane limit (a tall punch under a
light load), Coulomb's law node by node, and the mirror symmetry of the problem
(Q -> -Q on a symmetric punch at s = 0).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from threepart import closedform, fem
from threepart.fem.friction import shear_path
from threepart.fem._progress import Progress
from threepart.fem.twobody import TwoBodyModel
from threepart.errors import FullSlidingError
from threepart.problem.material import similar_pair
from threepart.problem.punch import Punch
from threepart.reports.map import validity
from threepart.reports.map import validity_slip
from threepart.tolerances import tolerance

E, NU, F = 1.0, 0.3, 0.5
A = similar_pair(E, NU)
#: a symmetric punch (R1 = R2) on the map's scale R1 = 10
SYMMETRIC = Punch(R1=10.0, R2=10.0, b=1.0)
#: the load of the finite-body tests: overhang a - b = 0.66 = 0.066 R1, the map's small-overhang regime
P_SYM = 0.034
#: a tall punch under a light load: overhang a - b = 0.1 = 0.01 R1 (test_finite's half-plane case)
P_LIGHT = 0.0017
#: the explicitly meshed mirror body against its reflection: the condensed compliances agree to
#: rounding of the sparse solves (1e-10 of the largest, tests/test_fem_friction.py), and d, e and
#: the nodal forces follow to that level through the active sets
SAME_MESH = 1e-9
#: the meshes of +Q and -Q are mirror images only up to gmsh's triangulation away from the
#: located ends: on the W/75 mesh measured 2.6e-5 d in d and 6.4e-5 d in e + (-e), where the
#: finite punch's coupling gives e = -5.6e-4 d
MESH_ASYMMETRY = 2e-4
#: |t_i| <= f fn_i to the rounding of the active set's projection (relative, and absolute in Q)
COULOMB, COULOMB_FLOOR = 1e-12, 1e-15
#: the tall punch (H = 40 b) under the light load: the closed form's d within this of the
#: finite body's, the level at which its normal problem is a half-plane (tests/test_finite.py's
#: HALF_PLANE for the peak pressure)
HALF_PLANE = 1e-3


def tol(quantity: str, comparison: str = "fem-quick") -> float:
    return tolerance(comparison, quantity).limit


def closed_form(punch: Punch, P: float, Q: float):
    return closedform.solve_partial_slip(closedform.solve_normal(punch, P, 0.0, A=A), Q, F)


def test_the_mirror_path_is_the_existing_solver_on_the_same_mesh():
    """TwoBodyModel with the mirror body meshed and the eq. 2 gap given explicitly equals
    fem.solve_partial_slip (the reflected compliance, the default gap) on the same mesh."""
    punch, P, Q = Punch(R1=10.0, R2=5.0, b=1.0), 0.05, 0.4 * F * 0.05
    spec = fem.PRESETS["trial"].spec(-1.5, 1.5, (-1.0, 1.0))
    existing = fem.solve_partial_slip(punch, P, 0.1, Q=Q, f=F, E=E, nu=NU, mesh=spec, steps=2)
    lower = fem.make_substrate(spec)
    model = TwoBodyModel(punch, P, 0.1, E, NU, "free", lower, existing.diagnostics.L, None, 100, F,
                          upper=fem.mirror(lower), gap=punch.profile)
    new = shear_path(model, Q, F, 2, Progress(False), 0.0)
    assert abs(new.d - existing.d) < SAME_MESH * existing.d
    assert abs(new.e - existing.e) < SAME_MESH * existing.d
    scale = np.abs(existing.q_nodes).max()
    assert np.abs(new.q_nodes - existing.q_nodes).max() < SAME_MESH * scale
    assert np.abs(new.normal.p_nodes - existing.normal.p_nodes).max() < SAME_MESH * scale / F


def test_the_papers_model_through_the_finite_path_is_the_closed_form():
    """H = None: the mirror body and the eq. 2 profile, located as the finite body is."""
    Q = 0.4 * F * P_SYM
    ref = closed_form(SYMMETRIC, P_SYM, Q)
    fe = fem.solve_finite_slip(SYMMETRIC, P_SYM, Q=Q, f=F, E=E, nu=NU, H=None, mesh="quick",
                               steps=1)
    assert fe.method == "fem" and fe.info["H"] is None and fe.info["profile"] == "eq. 2"
    assert abs(fe.d - ref.d) / ref.d < tol("d"), (fe.d, ref.d)
    assert abs(fe.e - ref.e) / ref.d < tol("e"), (fe.e, ref.e)
    diag = fe.diagnostics
    assert diag.steps == 1 and diag.dofs > 0 and diag.h_end < diag.h and diag.L > 0


@pytest.mark.slow
def test_the_papers_model_through_the_finite_path_is_the_two_body_solver():
    """H = None against fem.solve_partial_slip on its own quick mesh (located the half-plane way)."""
    Q = 0.4 * F * P_SYM
    fe = fem.solve_finite_slip(SYMMETRIC, P_SYM, Q=Q, f=F, E=E, nu=NU, H=None, mesh="quick",
                               steps=1)
    two_body = fem.solve_partial_slip(SYMMETRIC, P_SYM, Q=Q, f=F, E=E, nu=NU, mesh="quick", steps=1)
    assert abs(fe.d - two_body.d) / two_body.d < tol("d"), (fe.d, two_body.d)
    assert abs(fe.e - two_body.e) / two_body.d < tol("e"), (fe.e, two_body.e)


@pytest.fixture(scope="module")
def flipped():
    """The symmetric punch at s = 0 on the finite block (H = 4 b), sheared by +Q and by -Q
    in two steps, on the quick mesh with every size doubled (W/75: the default run's budget)."""
    Q = 0.4 * F * P_SYM
    return [fem.solve_finite_slip(SYMMETRIC, P_SYM, Q=sign * Q, f=F, E=E, nu=NU, H=4.0,
                                  mesh=fem.PRESETS["quick"].scaled(0.5), steps=2)
            for sign in (1, -1)]


def test_flipping_Q_mirrors_the_stick_zone(flipped):
    """x -> -x maps the problem with Q onto the one with -Q: d -> d, e -> -e (to mesh asymmetry).

    The finite punch's coupling offsets the stick zone (e != 0 at s = 0, unlike the
    closed form), by more than the meshes' asymmetry: so e must change sign.
    """
    plus, minus = flipped
    assert abs(plus.d - minus.d) < MESH_ASYMMETRY * plus.d
    assert abs(plus.e + minus.e) < MESH_ASYMMETRY * plus.d
    assert abs(plus.e) > 2 * MESH_ASYMMETRY * plus.d, plus.e / plus.d
    assert np.all(plus.q_nodes >= 0) and np.all(minus.q_nodes <= 0)   # the shear has Q's sign


def test_coulomb_holds_at_every_node(flipped):
    """|t_i| <= f fn_i everywhere; where a node slips in the last step, |t_i| = f fn_i and the
    punch's slip increment has the sign of t_i (the substrate's friction -t_i opposes it)."""
    for fe in flipped:
        prev, last = fe.history[-2:]
        t, fn = last.t, last.fn
        bound = F * fn * (1 + COULOMB) + COULOMB_FLOOR * abs(fe.Q)
        assert np.all(np.abs(t) <= bound)
        assert np.all(t[fn <= 0] == 0)                   # no shear where the bodies part
        dw = last.w - prev.w
        slips = (fn > 0) & ~last.stick
        assert slips.any() and last.stick.any()
        assert np.allclose(np.abs(t[slips]), F * fn[slips], rtol=COULOMB, atol=COULOMB_FLOOR * abs(fe.Q))
        assert np.all(t[slips] * dw[slips] > 0)
        stuck = np.abs(dw[last.stick]).max()
        assert stuck < COULOMB * np.abs(dw).max(), stuck   # stick nodes do not move


@pytest.mark.slow
def test_a_tall_punch_under_a_light_load_tends_to_the_closed_form():
    """Contact small against R1 and H: the finite body's stick zone tends to the half-plane's.

    The closed form's d errs less on the tall punch (H = 40 b) than on the short one
    (H = 4 b), and by less than HALF_PLANE; the symmetric punch keeps e = 0 to the mesh's level.
    Measured (quick mesh): 9.8e-4 at H = 4 b, 4.9e-4 at H = 40 b (5.7e-4 on the default mesh:
    not the mesh's; the contact W = 2.2 is small against H but not quite against the punch's
    face, which ends at the flanks b + R sin(theta) = 9.7 from the centre).
    """
    Q = 0.4 * F * P_LIGHT
    ref = closed_form(SYMMETRIC, P_LIGHT, Q)
    err = {}
    for H in (4.0, 40.0):
        fe = fem.solve_finite_slip(SYMMETRIC, P_LIGHT, Q=Q, f=F, E=E, nu=NU, H=H, mesh="quick",
                                   steps=1)
        err[H] = abs(ref.d - fe.d) / fe.d
        assert abs(ref.e - fe.e) / fe.d < tol("e"), (H, fe.e)
    assert err[40.0] < HALF_PLANE and err[40.0] < err[4.0], err


@pytest.mark.parametrize("kwargs, match", [
    (dict(Q=0.02, f=0.5), r"`Q`.*f P"),
    (dict(Q=0.001, f=0.0), r"`f`"),
    (dict(Q=math.nan, f=0.5), r"`Q`"),
    (dict(Q=0.001, f=0.5, steps=0), r"`steps`"),
    (dict(Q=0.001, f=0.5, H=-1.0), r"`H`"),
    (dict(Q=0.001, f=0.5, theta=2.0), r"`theta`"),
    (dict(Q=0.001, f=0.5, profile="ellipse"), r"`profile`"),
])
def test_bad_input_is_refused_before_any_meshing(kwargs, match):
    args = {"E": E, "nu": NU, "H": 4.0, "mesh": "quick", **kwargs}
    with pytest.raises(ValueError, match=match):
        fem.solve_finite_slip(SYMMETRIC, P_SYM, **args)


def test_full_sliding_and_a_wrong_mesh_are_refused_by_name():
    with pytest.raises(FullSlidingError, match="`Q`"):
        fem.solve_finite_slip(SYMMETRIC, P_SYM, Q=F * P_SYM, f=F, E=E, nu=NU, H=4.0)
    with pytest.raises(TypeError, match="`mesh`"):
        fem.solve_finite_slip(SYMMETRIC, P_SYM, Q=0.001, f=F, E=E, nu=NU, H=4.0, mesh=3)
    with pytest.raises(ValueError, match="`punch`"):
        fem.solve_finite_slip(Punch(R1=10.0, R2=10.0, b=1.0, R=100.0), P_SYM, Q=0.001, f=F, E=E,
                              nu=NU, H=4.0)


@pytest.mark.slow
def test_a_map_point_reports_signed_errors_of_the_closed_form():
    """evaluate_slip against the closed form's d, e computed here and the finite body's own."""
    point = validity.MapPoint(1.0, 0.1, 0.03, 4.0)
    out = validity_slip.evaluate_slip(point, quick=True)
    assert set(out) == set(validity_slip.SLIP_RESULT_KEYS)
    P = validity.point_load(point)
    ref = closedform.solve_partial_slip(
        closedform.solve_normal(validity.point_punch(point), P, 0.0, A=A),
        validity_slip.Q_OVER_FP * validity_slip.F * P, validity_slip.F)
    assert out["d_rel_error"] == pytest.approx((ref.d - out["d"]) / abs(out["d"]), rel=COULOMB)
    assert out["e_rel_error"] == pytest.approx((ref.e - out["e"]) / abs(out["d"]), rel=COULOMB)
    assert 0 <= out["slip_fem_error_estimate"] < abs(out["d_rel_error"])

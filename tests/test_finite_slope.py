"""The finite-slope FEM option (``kinematics="first_order"``, issue 23 item 4).

References: the kinematics written out by hand (the compliance's algebra),
Dundurs' ``beta = 0`` for two similar bodies (no first-order term), the limit
of small slopes (the change must vanish linearly), and an independent
finite-deformation model, CalculiX, whose numbers are stored in
``tests/data/small_slope_calculix.json`` (made by
``benchmarks/small_slope_calculix.py``; see the file's ``about``).
"""
from __future__ import annotations

import functools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from threepart import fem
from threepart.fem.contact import first_order_compliance
from threepart.fem.elasticity import condense
from threepart.fem.interface import mirror
from threepart.fem.mesh import PRESETS, make_substrate
from threepart.fem.solve import deformed_ends
from threepart.problem.material import rigid_punch
from threepart.problem.punch import Punch

DATA = Path(__file__).parent / "data" / "small_slope_calculix.json"
E, NU = 210000.0, 0.3
HERTZ = Punch(10.0, 10.0, 0.0)
#: the compliance's algebra against the kinematics written out: rounding of sums of ~n terms
ROUND_OFF = 1e-12
#: the mirrored block's coupling cancels the block's to the rounding of the factorisation
#: (relative to the vertical compliance)
MIRROR_ROUND_OFF = 1e-9
#: the fitted order of first_order - small over slopes 0.01-0.04 (quick mesh): 1 exactly at
#: first order; the O(slope^2) remainder (the dropped V C_xx V term, about 0.3 slope^2 of the
#: peak) moves the fitted order by about 0.01 over this range, the mesh by less
ORDER_TOL = 0.05
#: the premise of the beta = 0 test: one body alone (beta = 0.29 for nu = 0.3 against a rigid
#: body) has a first-order term above this share of its vertical compliance (measured 2.6e-3 at
#: the trial mesh's edge slope 0.1), far above the pair's rounding
COUPLED = 1e-4
#: the closed form's peak on 4001 points (evaluate_slope) against 20001: the grid's step
#: at a smooth maximum, (W/4000)^2 p''/2 over p0
LEVEL_GRID = 1e-4
#: the issue's target for the size of the change against the independent model: a third
THIRD = 1.0 / 3.0


@functools.lru_cache(maxsize=None)
def _change(punch: Punch, P: float, mesh: str = "quick") -> dict[str, float]:
    """first_order over small, minus 1: the peak, ``a`` (block's surface), and the contact end on
    the punch (``a + u_x``) of each kinematics against the closed form's."""
    runs = {k: fem.solve_normal(punch, P, 0.0, E=E, nu=NU, mesh=mesh, kinematics=k, progress=False)
            for k in ("small", "first_order")}
    s, f = runs["small"], runs["first_order"]
    return {"peak": float(f.p_nodes.max() / s.p_nodes.max() - 1), "a": f.a / s.a - 1,
            "a_punch_first_order": deformed_ends(f)[0], "a_punch_small": deformed_ends(s)[0]}


def test_the_kinematics_argument_is_checked_before_any_numerics():
    for solve, extra in ((fem.solve_normal, {}), (fem.solve_finite, {"H": None})):
        with pytest.raises(ValueError, match=r"`kinematics` = 'large' must be one of \('small', 'first_order'\)"):
            solve(Punch(10.0, 10.0, 1.0), 100.0, E=E, nu=NU, kinematics="large", **extra)
        with pytest.raises(TypeError, match="`kinematics` must be a str"):
            solve(Punch(10.0, 10.0, 1.0), 100.0, E=E, nu=NU, kinematics=1, **extra)


def test_the_compliance_is_the_gap_between_the_deformed_surfaces_to_first_order():
    """gap = v(x + d_x) - delta - d_y with d = C2 F and F = (v' f, -f), expanded by hand."""
    rng = np.random.default_rng(3)
    n = 7
    M = rng.normal(size=(2 * n, 2 * n))
    C2 = M @ M.T                                      # a symmetric positive compliance
    V, f = rng.normal(scale=0.1, size=n), rng.random(n)
    d = C2 @ np.concatenate([V * f, -f])
    gap_change = -d[n:] + V * d[:n]                   # (i) and (ii), whole
    second = V * (C2[:n, :n] @ (V * f))               # V C_xx V f, of second order in the slope
    K = first_order_compliance(C2, V)
    assert np.allclose(K @ f, gap_change - second, rtol=0, atol=ROUND_OFF * np.abs(gap_change).max())
    assert np.allclose(K, K.T, rtol=0, atol=ROUND_OFF * np.abs(K).max())   # C_xy = C_yx^T


def test_two_similar_bodies_have_no_first_order_term():
    """Dundurs' beta = 0: the block and its mirror image cancel each other's coupling."""
    block = make_substrate(PRESETS["trial"].spec(-1.0, 1.0, (0.0, 0.0)))
    S = condense(block, E, NU, ("u^1", "u^2"))
    B = condense(mirror(block), E, NU, ("u^1", "u^2"))
    n = len(S.x)
    C2 = S.C + B.C
    V = HERTZ.slope(S.x)
    scale = np.abs(C2[n:, n:]).max()
    alone = first_order_compliance(S.C, V) - S.C[n:, n:]
    assert np.abs(alone).max() > COUPLED * scale   # one body alone does couple
    assert np.allclose(first_order_compliance(C2, V), C2[n:, n:], rtol=0,
                       atol=MIRROR_ROUND_OFF * scale)


def test_the_change_vanishes_linearly_with_the_slope():
    """first_order - small -> 0 like the slope a/R (Hertz, rigid punch): fitted order 1."""
    slopes = np.array([0.01, 0.02, 0.04])
    A = rigid_punch(E, NU)
    changes = [_change(HERTZ, math.pi * (s * 10.0) ** 2 / (2 * A * 10.0)) for s in slopes]
    for key in ("peak", "a"):
        d = np.array([c[key] for c in changes])
        order = np.polyfit(np.log(slopes), np.log(np.abs(d)), 1)[0]
        assert abs(order - 1) <= ORDER_TOL, f"{key}: fitted order {order:.3f}, changes {d}"
    # the direction the finite-deformation model shows: a wider contact, a lower peak
    assert all(c["a"] > 0 and c["peak"] < 0 for c in changes)


@pytest.fixture(scope="module")
def calculix() -> dict:
    return json.loads(DATA.read_text())


def test_against_calculix_the_direction_holds_and_the_size_falls_short(calculix):
    """The option against CalculiX's NLGEOM run (stored): same direction, smaller size.

    The option moves ``a`` and the peak the way the finite-deformation model
    does, but by 0.3 to 0.6 of it (docs/SMALL_SLOPE.md): the first-order contact
    kinematics is not the whole finite-deformation effect. The test holds the
    direction, that the option does not overshoot, and the issue's size target
    (within a third) where it is met: the half-width at the paper's load.
    """
    for row in calculix["rows"]:
        ch = _change(Punch(**row["punch"]), row["P"])
        for theirs in ("nlgeom_vs_linear", "nlgeom_vs_closed_form"):
            for key in ("peak", "a"):
                ref = row[theirs][key]
                assert np.sign(ch[key]) == np.sign(ref), (row["name"], theirs, key, ch[key], ref)
                assert abs(ch[key]) < abs(ref), (row["name"], theirs, key, ch[key], ref)
        if row["name"] == "caseA_sym":
            ref = row["nlgeom_vs_closed_form"]["a"]
            assert abs(ch["a"] - ref) <= THIRD * abs(ref), (ch["a"], ref)


def test_the_contact_end_on_the_punch_matches_calculix_linear_run(calculix):
    """CalculiX's geometrically linear step pairs the surfaces on the deformed positions, as
    the option does: its contact end on the punch against the closed form's ``a`` is the
    option's ``a + u_x(a)`` to within a third, where the small kinematics' is not."""
    for row in calculix["rows"]:
        ch = _change(Punch(**row["punch"]), row["P"])
        ref = row["linear_vs_closed_form"]["a"]
        a_cf = row["closed_form"]["a"]
        ours, small = ch["a_punch_first_order"] / a_cf - 1, ch["a_punch_small"] / a_cf - 1
        assert abs(ours - ref) <= THIRD * abs(ref), (row["name"], ours, ref)
        assert abs(small - ref) > THIRD * abs(ref), (row["name"], small, ref)


@pytest.mark.slow
def test_the_map_point_costs_have_the_rigid_punchs_sign_and_the_load_level_is_p0_over_E_star():
    """evaluate_slope on one map point: the small kinematics narrow the contact and raise the
    peak, as against the rigid punch and CalculiX; ``load_level`` is the closed form's
    ``p0 A / 2`` (``A = 4 (1 - nu^2)/E``, eq. 4), computed here from its pressure."""
    from threepart.problem.material import similar_pair
    from threepart.reports.map import validity
    from threepart.reports.map.validity_slope import SLOPE_RESULT_KEYS, evaluate_slope

    point = validity.MapPoint(1.0, 0.1, 0.1, 4.0)
    out = evaluate_slope(point, quick=True)
    assert tuple(out) == SLOPE_RESULT_KEYS
    assert out["slope_a_rel_error"] < 0 < out["slope_peak_rel_error"]
    A = similar_pair(validity.E, validity.NU)
    cf = validity.closed_form(validity.point_punch(point), validity.point_load(point), 0.0, A=A)
    p0 = float(np.max(cf.pressure(np.linspace(-cf.a, cf.c, 20001))))
    assert out["load_level"] == pytest.approx(0.5 * A * p0, rel=LEVEL_GRID)



def test_the_change_lies_between_two_finite_strain_laws(calculix):
    """At strains p0/E ~ slope the finite-deformation answer depends on the material law:
    CalculiX's NLGEOM with St Venant-Kirchhoff (softens in compression) and with a neo-Hookean
    law (stiffens) bracket the option's change of ``a`` and of the peak (Hertz, slope 0.1),
    which is the contact kinematics alone."""
    svk = next(r for r in calculix["rows"] if r["name"] == "hertz" and r["slope"] == 0.1)
    for nh in calculix["neo_hooke"]:
        ch = _change(Punch(**nh["punch"]), nh["P"])
        for key in ("peak", "a"):
            lo, hi = sorted((svk["nlgeom_vs_linear"][key], nh["nlgeom_vs_linear"][key]))
            assert lo < ch[key] < hi, (key, ch[key], lo, hi)


#: the join's neighbourhood, in contact widths either side of x = b, where the first-order
#: pressure must follow the small-slope one smoothly
JOIN_BAND = 0.02
#: how much p_first_order / p_small may vary over that band: the secant moves the join by about
#: d_x / 2 and the pressure has a log-singular slope there, so the ratio drifts by 1.75 % over
#: the band (both meshes); the tangent's spurious spike made it 12 % (quick) and 25 % (default)
JOIN_DRIFT = 0.03
#: how far one node's ratio may stand off its neighbours' mean: 0.24 % (quick) and 0.14 %
#: (default) with the secant, 5.5 % and 11 % with the tangent
JOIN_ROUGH = 0.01


@pytest.mark.parametrize("mesh", ["quick", "default"])
def test_the_finite_punch_has_no_spike_where_its_centre_joins_its_edges(mesh):
    """At x = +-b the profile's curvature jumps. The gap's first-order term taken as the tangent
    ``g' d_x`` kinks there by ``d_x / R`` and put a spurious spike on the join; the secant and
    the interface's slope taken from the profile (fem.contact.solve_kinematic) keep the
    first-order pressure as smooth there as the small-slope one, its reference (b/R1 = 0.3,
    (a - b)/R1 = 0.3, H/b = 4: p0/E* = 0.12)."""
    from threepart.reports.map import validity

    point = validity.MapPoint(1.0, 0.3, 0.3, 4.0)
    punch, P = validity.point_punch(point), validity.point_load(point)
    runs = {k: fem.solve_finite(punch, P, 0.0, E=validity.E, nu=validity.NU, H=4.0 * punch.b,
                                theta=validity.THETA, mesh=mesh, kinematics=k, progress=False)
            for k in ("small", "first_order")}
    small, first = runs["small"], runs["first_order"]
    W = small.a + small.c
    for b in (-punch.b, punch.b):
        near = np.abs(first.x_nodes - b) <= JOIN_BAND * W
        ratio = first.p_nodes[near] / small.pressure(first.x_nodes[near])
        assert np.ptp(ratio) <= JOIN_DRIFT, (mesh, b, np.ptp(ratio))
        rough = np.max(np.abs(ratio[1:-1] - 0.5 * (ratio[:-2] + ratio[2:])))
        assert rough <= JOIN_ROUGH, (mesh, b, rough)

"""Edge asymptotics (issue 32, docs/EDGES.md): K_N of every method, K_T, the asymptotic slip zone.

References, each independent of the code under test:

* Hertz's closed form: ``p0 = 2P/(πa)``, ``a² = 2 A R P/π`` (eq. contact_law_Hertz), so
  ``K_N = p0 √(2/a)``, and the stuck shear ``Q/(π √(a² - x²))``, ``K_T = Q/(π √(2a))``;
* the pressure of eq. (inverted_IE) evaluated by adaptive quadrature at ``r = 1e-8 W``
  inside each edge of three-part punches, ``p/√r`` extrapolated to ``r = 0``;
* Mindlin's (Cattaneo's) slip zone ``a (1 - √(1 - Q/fP))`` and Nowell–Hills' stick zone
  under a bulk stress, ``c' = a √(1 - Q/fP)``, offset ``a sigma/(4 f p0)``, in their
  small-slip limits;
* the exact slip zones of the closed form and the SIE (Ciavarella–Jäger), as ``Q/fP -> 0``;
* the closed form against the SIE and the FEM.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad

import threepart
from threepart import Punch, registry, rigid_punch, solve, steady_state
from threepart.results import edges as asymptotics
from threepart.problem.catalogue import get_case, load_cases
from threepart.tolerances import tolerance
from threepart.problem.units import UNITS

A = rigid_punch(210e3, 0.3)
F = 0.5            # the coefficient of friction (an input, not a limit)
HERTZ = Punch(10.0, 10.0, 0.0)
#: K_N of the exact methods against each other and Hertz
EXACT = tolerance("edges", "K_N_exact").limit
#: closed-form K_N against the quadrature of eq. inverted_IE
QUADRATURE = tolerance("edges", "K_N_quadrature").limit
#: algebraic identities in floating point
IDENTITY = tolerance("edges", "identity").limit
#: the FEM's K_N on the quick mesh
FEM_QUICK = tolerance("edges", "fem_quick").limit
#: the FEM's K_N on the default mesh (issue target)
FEM_DEFAULT = tolerance("edges", "fem_default").limit
#: the 1 % target at slip zones under 1 % of W
FIRST_ORDER = tolerance("edges", "slip_first_order").limit
#: relative error per slip/W, three-part punches
CONSTANT = tolerance("edges", "slip_constant").limit
#: the fitted order of the slip zone's relative error in slip/W
ORDER = (tolerance("edges", "slip_order").limit, tolerance("edges", "slip_order_max").limit)

#: the catalogue's normal cases inside the closed form's framework
NORMAL_CASES = [c.name for c in load_cases() if c.kind == "normal" and not c.beyond]
#: the cases of the FEM suite
FEM_CASES = [c.name for c in load_cases() if "fem" in c.suites]
#: three-part punches of the catalogue (and Hertz and case C) for the slip-zone studies
SLIP_CASES = ("caseA_moment", "general", "fan_blade_flank", "caseC", "hertz")
#: Q/fP of the small-slip sweep
RATIOS = (0.05, 0.02, 0.01, 0.005, 0.002)


def _normal(name: str, method: str = "closedform", **options):
    c = get_case(name).resolved()
    return c, solve(c.punch, c.P, c.s, A=c.A, tilt=c.tilt, method=method, **options)


def _hertz_K_N(P: float, R: float) -> float:
    """Hertz's K_N from Hertz's own formulas: ``a² = 2ARP/π``, ``p0 = 2P/(πa)``."""
    a = math.sqrt(2 * A * R * P / math.pi)
    return 2 * P / (math.pi * a) * math.sqrt(2 / a)


def _inverted_ie(punch: Punch, a: float, c: float, compliance: float, side: str, r: float) -> float:
    """``p/√r`` at ``r`` inside an edge, by quadrature of eq. inverted_IE.

    ``p(x) = w(x)/(πA) ∫ [v'(t) - v'(x)]/(w(t)(t - x)) dt`` (the paper's inversion; the
    subtracted term integrates to 0), with the profile's slope typed in from eq. (2).
    """
    b, k0 = punch.b, (0.0 if math.isinf(punch.R) else 1.0 / punch.R)
    k1, k2 = 1.0 / punch.R1 - k0, 1.0 / punch.R2 - k0

    def slope(t: float) -> float:
        return k0 * t - k1 * max(-b - t, 0.0) + k2 * max(t - b, 0.0)

    x = -a + r if side == "left" else c - r

    def F(t: float) -> float:
        return (slope(t) - slope(x)) / (t - x) if t != x else k0

    joins = [j for j in (-b, b) if -a < j < c] or [0.5 * (c - a)]
    lo, hi = joins[0], joins[-1]
    kw = dict(epsabs=0.0, epsrel=1e-12, limit=200)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        total = quad(lambda t: F(t) / math.sqrt(c - t), -a, lo, weight="alg", wvar=(-0.5, 0), **kw)[0]
        total += quad(lambda t: F(t) / math.sqrt(t + a), hi, c, weight="alg", wvar=(0, -0.5), **kw)[0]
        if hi > lo:
            total += quad(lambda t: F(t) / math.sqrt((t + a) * (c - t)), lo, hi, **kw)[0]
    return math.sqrt(r * (a + c - r)) * total / (math.pi * compliance * math.sqrt(r))


# --- K_N ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["closedform", "sie"])
@pytest.mark.parametrize("P", [50.0, 400.0, 3000.0])
def test_hertz_limit(method, P):
    res = solve(HERTZ, P, 0.0, A=A, method=method)
    for edge in res.edges():
        assert edge.K_N == pytest.approx(_hertz_K_N(P, 10.0), rel=EXACT)
        assert edge.fit_error is None and edge.K_T is None and edge.slip_zone is None


@pytest.mark.parametrize("name", NORMAL_CASES)
def test_closed_form_equals_sie(name):
    _, cf = _normal(name)
    _, si = _normal(name, "sie")
    for e_cf, e_si in zip(cf.edges(), si.edges()):
        assert e_si.K_N == pytest.approx(e_cf.K_N, rel=EXACT), e_cf.side


@pytest.mark.parametrize("name", ["caseA_moment", "general", "caseB", "caseC", "fan_blade_flank",
                                  "suppressed"])
def test_closed_form_is_the_limit_of_the_inversion(name):
    """K_N against p/√r of eq. inverted_IE by quadrature, extrapolated to r -> 0 (Richardson in r)."""
    c, res = _normal(name)
    r = 1e-8 * res.width
    for edge in res.edges():
        once = _inverted_ie(c.punch, res.a, res.c, c.A, edge.side, r)
        twice = _inverted_ie(c.punch, res.a, res.c, c.A, edge.side, 2 * r)
        assert edge.K_N == pytest.approx(2 * once - twice, rel=QUADRATURE), edge.side


def test_closed_form_tends_to_its_pressure():
    """p/√r of the closed form's own pressure tends to K_N, the gap falling as r (first order)."""
    _, res = _normal("caseA_moment")
    for edge, sign in zip(res.edges(), (1.0, -1.0)):
        r = res.width * np.array([1e-3, 1e-4])
        gap = np.abs(res.pressure(edge.x + sign * r) / np.sqrt(r) / edge.K_N - 1)
        order = math.log(gap[0] / gap[1]) / math.log(10.0)
        assert ORDER[0] <= order <= ORDER[1], f"{edge.side}: p/√r approaches K_N at order {order:.3f}"


def _assert_fem_K_N(name: str, mesh: str, limit: float) -> None:
    """The FEM's fitted K_N on ``mesh`` within ``limit`` of the closed form's, and inside its own fit error."""
    _, cf = _normal(name)
    _, fe = _normal(name, "fem", mesh=mesh)
    for e_cf, e_fe in zip(cf.edges(), fe.edges()):
        err = abs(e_fe.K_N - e_cf.K_N)
        assert err <= limit * e_cf.K_N, f"{name} {e_cf.side}: {err / e_cf.K_N:.2e}"
        assert err <= e_fe.fit_error, f"{name} {e_cf.side}: fit error {e_fe.fit_error:.3g} < {err:.3g}"


@pytest.mark.parametrize("name", ["hertz", "caseA_moment", "near_lift_off"])
def test_fem_quick_mesh(name):
    _assert_fem_K_N(name, "quick", FEM_QUICK)


@pytest.mark.slow
@pytest.mark.parametrize("name", FEM_CASES)
def test_fem_default_mesh(name):
    _assert_fem_K_N(name, "default", FEM_DEFAULT)


# --- K_T and the slip zone -----------------------------------------------------------------------
def test_hertz_K_T_and_mindlin_first_order():
    """K_T = Q/(π √(2a)) and the slip zone a Q/(2 f P), Mindlin's first-order term, at each edge."""
    P, Q = 400.0, 8.0
    res = solve(HERTZ, P, 0.0, A=A, Q=Q, f=F, method="closedform")
    a = math.sqrt(2 * A * 10.0 * P / math.pi)
    for edge in res.edges():
        assert edge.K_T == pytest.approx(Q / (math.pi * math.sqrt(2 * a)), rel=IDENTITY)
        assert edge.slip_zone == pytest.approx(a * Q / (2 * F * P), rel=IDENTITY)
        assert edge.K_sigma == 0.0 and edge.sigma_bulk == 0.0


@pytest.mark.parametrize("ratio", RATIOS)
def test_hertz_error_is_slip_over_width(ratio):
    """Against Mindlin's a(1 - √(1 - Q/fP)) the relative error is slip/W exactly, below 1 % under 1 % of W."""
    P = 400.0
    res = solve(HERTZ, P, 0.0, A=A, Q=ratio * F * P, f=F, method="sie")
    a = res.a
    mindlin = a * (1 - math.sqrt(1 - ratio))
    for edge in res.edges():
        err = abs(edge.slip_zone / mindlin - 1)
        assert err == pytest.approx(mindlin / (2 * a), rel=IDENTITY)
        assert err < FIRST_ORDER or mindlin / (2 * a) >= FIRST_ORDER


@pytest.mark.parametrize("sigma", [-30.0, 40.0])
def test_nowell_hills_first_order(sigma):
    """Under a bulk stress each edge's slip zone is the first order of Nowell–Hills' a - c' ± x0."""
    P, Q = 400.0, 8.0
    res = solve(HERTZ, P, 0.0, A=A, Q=Q, f=F, sigma_bulk=sigma, method="closedform")
    a = math.sqrt(2 * A * 10.0 * P / math.pi)
    p0 = 2 * P / (math.pi * a)
    x0 = a * sigma / (4 * F * p0)          # Nowell & Hills' offset (docs/BULK_STRESS.md, B5)
    first = a * Q / (2 * F * P)           # first order of a - c' = a (1 - √(1 - Q/fP))
    left, right = res.edges()
    assert left.slip_zone == pytest.approx(first + x0, rel=IDENTITY)
    assert right.slip_zone == pytest.approx(first - x0, rel=IDENTITY)
    assert left.K_sigma == pytest.approx(sigma * math.sqrt(2 * a) / 8, rel=IDENTITY)


def _exact_slip(res) -> tuple[float, float]:
    lo, hi = res.stick_zone
    return lo + res.a, res.c - hi


def _slip_errors(edges, exacts, width: float, where: str, errs: list, sizes: list) -> None:
    """Append each edge's relative slip-zone error and its exact slip zone over ``width``; each within
    CONSTANT times that size."""
    for edge, exact in zip(edges, exacts):
        errs.append(abs(edge.slip_zone / exact - 1))
        sizes.append(exact / width)
        assert errs[-1] <= CONSTANT * sizes[-1], f"{edge.side} at {where}"


def _assert_first_order(errs: list, sizes: list, label: str) -> None:
    """The log-log slope of the error against the slip zone, per edge (left, right alternate), in ORDER."""
    for k in (0, 1):
        order = np.polyfit(np.log(sizes[k::2]), np.log(errs[k::2]), 1)[0]
        assert ORDER[0] <= order <= ORDER[1], f"{label}: fitted order {order:.3f}"


@pytest.mark.parametrize("name", SLIP_CASES)
@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_slip_zone_is_first_order(name, method):
    """The relative error falls as slip/W (log-log slope 1), at most CONSTANT slip/W."""
    c = get_case(name).resolved()
    errs, sizes = [], []
    for ratio in RATIOS:
        res = solve(c.punch, c.P, c.s, A=c.A, Q=ratio * F * c.P, f=F, method=method)
        _slip_errors(res.edges(), _exact_slip(res), res.normal.width, f"Q/fP = {ratio}", errs, sizes)
    _assert_first_order(errs, sizes, f"{name} {method}")


def test_fretting_cycle_slip_zone_is_the_loading_one():
    """A fretting cycle's change of shear over 2 f (E7) gives the slip zone of its loading at Q_max."""
    c = get_case("caseA_moment").resolved()
    Q_max = 0.01 * F * c.P
    slip = solve(c.punch, c.P, c.s, A=c.A, Q=Q_max, f=F, sigma_bulk=5.0, method="closedform")
    cyc = registry.get("closedform").fretting(c.punch, c.P, c.s, A=c.A, Q_max=Q_max, f=F, sigma_bulk=5.0)
    for e_cyc, e_slip in zip(cyc.edges(), slip.edges()):
        assert e_cyc.K_T == pytest.approx(2 * e_slip.K_T, rel=IDENTITY)
        assert e_cyc.slip_zone == pytest.approx(e_slip.slip_zone, rel=IDENTITY)
        assert e_cyc.kind == "fretting"


@pytest.mark.parametrize("method", ["closedform", "sie"])
def test_steady_state_slip_zone_is_first_order(method):
    """At P, s constant the steady state's permanent slip zones converge at first order (E7)."""
    c = get_case("caseA_moment").resolved()
    errs, sizes = [], []
    for ratio in RATIOS:
        dQ = ratio * F * c.P
        sigma = 2.0 * dQ / c.P * 1e3       # in proportion to ΔQ: 20 MPa at ΔQ/fP = 0.02
        states = [(c.P, c.s, 0.3 * dQ - dQ, -sigma), (c.P, c.s, 0.3 * dQ + dQ, sigma)]
        cyc = steady_state(c.punch, states, F, A=c.A, method=method)
        n = cyc.normals[0]
        lo, hi = cyc.stick_zone
        _slip_errors(cyc.edges(), (lo + n.a, n.c - hi), n.width, f"ΔQ/fP = {2 * ratio}", errs, sizes)
    _assert_first_order(errs, sizes, method)


def test_fem_slip_edges():
    """The FEM's slip result: its own contact's K_T (E3), and its fitted K_N's error bar."""
    c = get_case("caseA_moment").resolved()
    kw = dict(A=c.A, Q=0.05 * F * c.P, f=F, sigma_bulk=10.0)
    ref = solve(c.punch, c.P, c.s, method="closedform", **kw).edges()
    fe = solve(c.punch, c.P, c.s, method="fem", mesh="quick", **kw).edges()
    for e_ref, e_fe in zip(ref, fe):
        assert abs(e_fe.K_N - e_ref.K_N) <= e_fe.fit_error
        assert e_fe.K_T == pytest.approx(e_ref.K_T, rel=FEM_QUICK)


# --- the interface ------------------------------------------------------------------------------
def test_units_and_export():
    for key in ("K_N", "K_T", "K_sigma", "slip_zone", "fit_error"):
        assert key in UNITS
    assert threepart.results.edges is asymptotics


def test_refuses_a_method_without_edges():
    toy = registry.Method("toy-no-edges", normal=registry.get("closedform").normal)
    registry.register(toy)
    try:
        res = solve(HERTZ, 400.0, 0.0, A=A, method="closedform")
        import dataclasses
        other = dataclasses.replace(res, method="toy-no-edges")
        with pytest.raises(ValueError, match="method 'toy-no-edges' does not compute edge multipliers"):
            other.edges()
    finally:
        registry._REGISTRY.pop("toy-no-edges")


def test_refuses_other_objects():
    with pytest.raises(TypeError, match="`result` must be a normal, slip, fretting or steady-state result"):
        asymptotics.edges(3.0)


# --- the report's section ------------------------------------------------------------------------
def test_report_rows_and_section():
    """The multipliers table: the SIE's K_N error against the closed form's, the FEM's covered by its fit error."""
    from threepart.reports.verify.edges import edge_rows, edges_section
    from threepart.reports.verify.runs import CaseRun
    from threepart.reports.verify.sections import Status

    c = get_case("slip_Q0.2").resolved()
    kw = dict(A=c.A, Q=c.Q, f=c.f)
    run = CaseRun(c, results={m: solve(c.punch, c.P, c.s, method=m, **kw, **opt) for m, opt in
                              (("closedform", {}), ("sie", {}), ("fem", {"mesh": "quick"}))})
    rows = edge_rows([run])
    assert [(r["method"], r["side"]) for r in rows] == [(m, s) for m in ("closedform", "sie", "fem")
                                                        for s in ("left", "right")]
    for r in rows:
        exact = _exact_slip(run.results[r["method"]])[("left", "right").index(r["side"])]
        assert r["exact_slip"] == pytest.approx(exact, rel=IDENTITY)
        if r["method"] == "sie":
            assert r["K_N_error"] <= EXACT
        if r["method"] == "fem":
            assert r["K_N_error"] <= min(r["fit_error"], FEM_QUICK)
    doc = {"edges": rows, "cases": [{"name": c.name, "E": c.E}]}
    section = edges_section(doc)
    assert section is not None and section.status is Status.PASS
    assert len(section.tables[0].rows) == len(rows)
    assert edges_section({"edges": [], "cases": []}) is None


def test_the_report_s_asymptote_study_is_first_order_and_hertz_s_constant_is_one(tmp_path):
    """The report's study of the asymptotic slip zone (closed form, Q/fP -> 0): on every edge the
    error falls as (slip/W)^1 (fitted order within the edges table's slip_order bounds), Hertz's
    error per slip/W is 1 (Mindlin's first-order term, an identity), the three-part punches' within
    slip_constant; the plot is drawn and the section shows it."""
    from threepart.reports.verify.edges import asymptote_study, draw_asymptote, edges_section

    study = asymptote_study()
    lo, hi = tolerance("edges", "slip_order").limit, tolerance("edges", "slip_order_max").limit
    for c in study["curves"]:
        assert lo <= c["order"] <= hi, c
        assert c["constant"] <= tolerance("edges", "slip_constant").limit, c
    hertz = [c for c in study["curves"] if c["case"] == "hertz"]
    assert len(hertz) == 2
    for c in hertz:
        assert c["constant"] == pytest.approx(1.0, rel=tolerance("edges", "slip_first_order").limit)
    draw_asymptote(study, tmp_path / "a.png")
    assert (tmp_path / "a.png").stat().st_size > 0
    section = edges_section({"edges": [{"case": "hertz", "method": "closedform", "side": "left",
                                        "K_N": 1.0, "K_N_error": 0.0, "fit_error": None, "K_T": 0.0,
                                        "slip_zone": None, "exact_slip": None}],
                             "cases": [{"name": "hertz"}], "edge_asymptote": {**study, "plot": "a.png"}})
    assert len(section.figures) == 1 and section.figures[0].path == "a.png"
    assert "in proportion to the slip zone" in section.figures[0].caption

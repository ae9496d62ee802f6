"""The one tolerance table of threepart, keyed ``(comparison, quantity)``, each entry with its reason.

The verification run, the tests and the benchmarks read their limits here and
nowhere else. The reasons give the measured figure where it is known.

Comparisons of the verification run
-----------------------------------
Every figure that :mod:`threepart.reports.compare` computes is checked against
exactly one entry. The comparison is ``"sie"`` (closed form against the
Gauss–Chebyshev SIE solver), ``"fem-quick"``, ``"fem-default"`` or
``"fem-fine"`` (closed form against the finite-element model on that mesh
preset; ``threepart verify --quick`` uses the quick mesh, the default run the
default mesh and --full the fine one). ``tests/test_sie_*.py`` and
``tests/test_fem.py`` judge their agreement with the closed form by the same
entries.

How each quantity is normalised (all errors are dimensionless, >= 0):

==================  ===========================================================
quantity            error
==================  ===========================================================
a, c                ``|Δa| / W`` with ``W = a + c`` of the closed form
alpha               ``|Δα| / max(|α|, Δv')``, ``Δv' = v'(c) - v'(-a)`` at α = 0,
                    the slope scale of the punch over the contact
P                   ``|ΔP| / P``
s                   ``|Δs| / W``
p_left, p_right     ``|Δp_peak| / p_max`` (both peaks, left and right of x = 0)
x_left, x_right     ``|Δx_peak| / W``
p_interior_max      ``max |Δp| / p_max`` over the contact less 5 % of W at each end,
                    at the FEM's nodes for the FEM, else at 4001 uniform points
p_L2                ``||Δp||_2 / ||p||_2`` over the whole contact
d, e                ``|Δd| / d``, ``|Δe| / d`` (stick zone, partial slip only)
q_interior_max      ``max |Δq| / max|q|`` over the contact less 5 % of W at each end
q_L2                ``||Δq||_2 / ||q||_2`` over the whole contact
q_integral          ``|∫q dx - Q| / |Q|`` of the result itself (horizontal equilibrium)
q_bound             ``max(|q| - f p, 0) / (f p_max)`` of the result itself (Coulomb's bound)
sxx_surface         ``max |Δσxx| / p_max`` on the surface, over the contact and W/4 beyond each end
sxx_peak            ``|Δ max σxx| / max|σxx|`` on that line: the trailing edge's tension
stress_depth        ``max |Δσ| / p_max`` of σxx, σzz, σxz at depth ``0.1 W <= z <= W`` under the contact
energy              ``|ΔE| / E``, energy dissipated per fretting cycle
stick               largest ``|Δ|`` of the stick-zone ends over a cycle's states, ``/ d`` at Q_max
loop                largest ``|Δ|`` of the hysteresis loop, ``/`` its largest value
q_states            ``q_interior_max`` at Q_max, at Q = 0 after reversal and at -Q_max
stick_ends          flight cycle: largest ``|Δ|`` of the permanent stick zone's ends ``/ W`` of the
                    smaller contact (the intersection of the two end states' contacts)
cycle_energy        flight cycle: ``|ΔE| / E`` of the energy per cycle (eq. S11)
q_range             flight cycle: ``q_interior_max`` of the shear range ``q_1 - q_0`` (eq. S4)
slip_amplitude      flight cycle: ``max |Δδ| / max δ`` over the smaller contact (eq. S7)
stick_end           flight cycle, ``<method>-history``: the marched last cycle's permanent stick
                    zone ends against the steady state's, in the march's elements ``h``
==================  ===========================================================

Other comparisons (tests and benchmarks)
----------------------------------------
A quantity ending in ``_order`` is the lowest admissible fitted order and one
ending in ``_order_max`` the highest; every other limit is an upper bound on a
normalised error (``_level``: at the finest discretisation of a study).

``sie-plain``
    Convergence in ``n`` of the plain SIE scheme (the projected one is exact for any ``n``).
``sie-target``
    What the SIE itself claims: the accuracy its two-level estimate must reach
    when it picks ``n`` (issue 29), and the robustness draws that hold it to that claim.
``sie-reference``
    The SIE pressure against the adaptive-quadrature inversion integral, as a
    fraction of the peak.
``sie-exact``, ``sie-identity``, ``sie-quadrature``
    Limits where the SIE is exact (only rounding remains), integral identities
    checked by quadrature, and the Gauss–Chebyshev building blocks.
``fem-quick`` (beyond the table above), ``fem-reference``, ``fem-export``, ``fem-hertz-study``
    FE load control and identities on the quick mesh, the committed coarse
    reference mesh, the exported fields, and the slow h-refinement study against Hertz.
``closedform``
    The closed form's identities, limits and its agreement with the quadrature reference.
``referee``
    A pressure from another code (``threepart compare --pressure``) and the
    CalculiX column of the verification run, against the closed form (or the
    SIE past lift-off): the issue-22 targets.
``getfem``
    GetFEM's partial slip and fretting cycle of two similar bodies (:mod:`threepart.getfem`)
    against Mindlin and the closed form: the issue-38 targets.
``calculix-friction``
    CalculiX's partial slip and fretting cycle of two similar bodies
    (:mod:`threepart.calculix.friction`) against Mindlin and the closed form: the issue-38
    targets, and what CalculiX reaches where it misses them (``q_integral``, ``stick_shift``).
``referee-pitfall``
    When the referee names a known pitfall of another code's pressure
    (:mod:`threepart.reports.referee.pitfalls`): tension, load, the ends'
    resolution (``end_nodes``: the fewest nodes, a lower bound), node-to-node
    oscillation, the penalty's overclosure.
``catalogue``
    Numbers stored in ``threepart/problem/cases.json`` against what they stand for.
``flight``
    The fatigue parameters of a steady (flight) cycle against the fretting cycle's
    Masing states at constant load (``tests/test_flight_cycle.py``).
``refs``
    The precision each quantity of the reference dataset claims (``threepart
    export-refs``, ``docs/REFERENCE_DATA.md``), checked by ``tests/test_refs.py``.
``steady``
    The periodic steady state of in-phase loading (``tests/test_steady_state.py``,
    docs/STEADY_STATE.md): reductions, Hertz, closed form vs SIE, brute quadrature.
``fem-steady``
    The FEM's periodic steady state (``tests/test_fem_steady.py``): marched
    against the closed form, shakedown, path independence, the march's stop.
``auto-march``
    The steady state's ``auto`` past the superposition (issue 37, ``tests/test_cycles_auto.py``):
    the SIE's load history marched until two cycles agree, and that against the closed form.
``convergence``
    The convergence tools (:mod:`threepart.convergence`) on manufactured sequences.
``answer``
    The one check of every method's answer (:mod:`threepart.results.answer`): the
    least pressure (of the peak) and Coulomb's bound (of ``f p_max``).
"""
from __future__ import annotations

from dataclasses import dataclass

from .outside import OUTSIDE

__all__ = ["Tolerance", "TOLERANCES", "COMPARISONS", "QUANTITIES", "NORMAL_QUANTITIES",
           "SLIP_QUANTITIES", "STRESS_QUANTITIES", "FRETTING_QUANTITIES", "STEADY_QUANTITIES", "tolerance", "fem_comparison", "VALUE_UNITS", "ERROR_UNITS", "ROW_UNITS", "error_unit",
           "NORMALISATION", "MAP_LIMIT", "MAP_LEVELS", "Baseline", "BASELINES"]


@dataclass(frozen=True)
class Tolerance:
    """Limit of one normalised error (or bound on an observed order), with the reason for its value."""

    limit: float
    reason: str


#: quantities compared for every normal result, in report order
NORMAL_QUANTITIES = ("a", "c", "alpha", "P", "s", "p_left", "x_left", "p_right", "x_right",
                     "p_interior_max", "p_L2")
#: quantities compared in addition for a partial-slip result (SIE and the two-body FEM)
SLIP_QUANTITIES = ("d", "e", "q_interior_max", "q_L2", "q_integral", "q_bound")
#: quantities compared in addition for a partial-slip result: the stress field in the substrate
STRESS_QUANTITIES = ("sxx_surface", "sxx_peak", "stress_depth")
QUANTITIES = NORMAL_QUANTITIES + SLIP_QUANTITIES + STRESS_QUANTITIES
#: quantities compared for a fretting cycle (the cycle's own section of the report)
FRETTING_QUANTITIES = ("energy", "stick", "loop", "q_states")
#: quantities compared for the steady state of a flight cycle (the flight cycle's section of the report)
STEADY_QUANTITIES = ("stick_ends", "cycle_energy", "q_range", "slip_amplitude")
#: comparisons of the verification run (closed form against a solver)
COMPARISONS = ("sie", "fem-quick", "fem-default", "fem-fine")

#: the unit of each compared figure's value (the catalogue's units: mm, N/mm, MPa)
VALUE_UNITS: dict[str, str] = {
    "a": "mm", "c": "mm", "s": "mm", "x_left": "mm", "x_right": "mm", "d": "mm", "e": "mm",
    "alpha": "rad", "P": "N/mm",
    "p_left": "MPa", "p_right": "MPa", "p_interior_max": "MPa", "q_interior_max": "MPa",
    "p_L2": "MPa·mm^½", "q_L2": "MPa·mm^½", "closedform": "1 = refused",
    "energy": "N·mm/mm", "stick": "mm", "loop": "mm", "q_states": "MPa",
    "stick_ends": "mm", "cycle_energy": "N·mm/mm", "q_range": "MPa", "slip_amplitude": "mm",
    "stick_end": "mm", "stick_width": "mm", "stick_shift": "mm",   # the friction referee columns: d, e
    "q_integral": "N/mm", "q_bound": "1",
    "sxx_surface": "MPa", "sxx_peak": "MPa", "stress_depth": "MPa",
    # robustness study (reports.verify.robustness): the least pressure of an answer, and counts of draws
    "p_min": "1", "wrong_refusals": "draws", "no_convergence": "draws",
}
#: what each error is a fraction of (its unit), by quantity; see :data:`NORMALISATION`
ERROR_UNITS: dict[str, str] = {
    "a": "W", "c": "W", "s": "W", "x_left": "W", "x_right": "W",
    "alpha": "slope", "P": "P",
    "p_left": "peak", "p_right": "peak", "p_interior_max": "peak", "p_L2": "L2",
    "d": "d", "e": "d", "q_interior_max": "max|q|", "q_L2": "L2", "closedform": "0/1",
    "energy": "energy", "stick": "d", "loop": "loop", "q_states": "max|q|",
    "stick_ends": "W", "cycle_energy": "energy", "q_range": "max|q|", "slip_amplitude": "max δ",
    "stick_end": "h", "stick_width": "W", "stick_shift": "W",   # the last two: the friction referee columns
    "q_integral": "Q", "q_bound": "f p_max",
    "sxx_surface": "peak", "sxx_peak": "max|σxx|", "stress_depth": "peak",
    # robustness study (reports.verify.robustness)
    "p_min": "peak", "wrong_refusals": "count", "no_convergence": "count",
}
#: a row whose unit is not its quantity's (:data:`ERROR_UNITS`): the outside codes' own rows
ROW_UNITS: dict[tuple[str, str], str] = {
    ("getfem", "stick_end"): "W", ("calculix-friction", "stick_end"): "W",
    ("calculix-friction", "bulk_stick_end"): "W", ("calculix-friction", "cycle_q_integral"): "Q",
    ("calculix-friction", "flight_energy"): "energy",
}


def error_unit(comparison: str, quantity: str) -> str:
    """What the error of row ``(comparison, quantity)`` is a fraction of (``""``: a plain number)."""
    return ROW_UNITS.get((comparison, quantity), ERROR_UNITS.get(quantity, ""))


#: the normalisations of :data:`ERROR_UNITS`, in words (stated once at the top of the report)
NORMALISATION: dict[str, str] = {
    "W": "contact width W = a + c of the reference solution (mm): a, c, s and the peak positions",
    "slope": "slope range of the punch over the contact, v'(c) - v'(-a) without tilt (or |α| if "
             "larger): the tilt α",
    "P": "the load P itself",
    "peak": "the larger of the reference's two peak pressures: both peaks and the largest pointwise "
            "pressure difference more than 5 % of W inside the contact ends",
    "L2": "the reference field's L2 norm over the contact: p_L2 and q_L2",
    "d": "the stick-zone half-width d of the reference: d and e",
    "max|q|": "the largest shear traction of the reference: the largest pointwise shear difference "
              "more than 5 % of W inside the contact ends",
    "0/1": "a refusal: 0 when the closed form raised the named error, 1 otherwise",
    "energy": "the reference's energy dissipated per fretting cycle",
    "Q": "the shear force Q itself: ∫q dx of the result against Q",
    "f p_max": "f times the result's largest pressure: how far |q| exceeds f p anywhere",
    "max|σxx|": "the reference's largest |σxx| on the surface line (the contact and a quarter of W "
                "beyond each end): the largest surface σxx, the tension at the trailing edge",
    "h": "the marched history's element (SIE) or node spacing (FEM): the permanent stick zone's ends "
         "of its last cycle (a flight cycle)",
    "max δ": "the largest slip amplitude δ of the reference over the smaller contact (a flight cycle)",
    "loop": "the largest |delta| of the reference's hysteresis loop (delta less the line "
            "through the loop's tips)",
    # robustness study (reports.verify.robustness)
    "count": "a number of random draws that broke a rule of the robustness study (none may)",
}

_T = Tolerance
#: the tolerance table: ``(comparison, quantity) -> Tolerance``
TOLERANCES: dict[tuple[str, str], Tolerance] = {
    # --- closed form vs SIE (Gauss–Chebyshev, projected scheme, default n) ----------------------
    ("sie", "a"): _T(1e-10, "projected a, c carry no discretisation error, Newton stops at 1e-14; measured <= 1.6e-15 W"),
    ("sie", "c"): _T(1e-10, "as a: both ends come from the same Newton solve"),
    ("sie", "alpha"): _T(1e-10, "α comes from the same Newton solve as a, c; measured <= 3e-16"),
    ("sie", "P"): _T(1e-12, "load control: P is imposed, only quadrature round-off remains (measured 0)"),
    ("sie", "s"): _T(1e-10, "s is imposed (free tilt) or the quadrature centroid (suppressed); measured <= 1e-16 W"),
    ("sie", "p_left"): _T(1e-6, "peak pressure, bounded by the field error; measured <= 5e-8"),
    ("sie", "p_right"): _T(1e-6, "as p_left"),
    ("sie", "x_left"): _T(1e-4, "flat maximum: Δx ~ sqrt(Δp/p''), about 1e-3 sqrt of the p error; measured <= 1.6e-7 W"),
    ("sie", "x_right"): _T(1e-4, "as x_left"),
    ("sie", "p_interior_max"): _T(1e-6, "projected pressure converges as n^-2 past the log kinks; measured <= 3.2e-7"),
    ("sie", "p_L2"): _T(1e-6, "L2 is dominated by the same interior error as the max; measured <= 1.7e-8"),
    ("sie", "d"): _T(1e-8, "d and e come from the exact normal ends through one Newton solve; measured <= 2e-15"),
    ("sie", "e"): _T(1e-8, "as d, relative to d since e = 0 for symmetric contacts"),
    ("sie", "q_interior_max"): _T(1e-6, "shear is f·p minus a corrective pressure: same field limit as p; measured <= 2.9e-7"),
    ("sie", "q_L2"): _T(1e-6, "as q_interior_max; measured <= 4e-8"),
    ("sie", "q_integral"): _T(1e-8, "adaptive quadrature of the SIE shear against Q (horizontal equilibrium; the closed form gives 3e-14 by the same quadrature); measured <= 8.6e-10"),
    ("sie", "q_bound"): _T(1e-6, "p* of the Chebyshev series may dip below 0 by its pointwise error only; measured 0"),
    ("sie", "sxx_surface"): _T(1e-6, "issue target for the stresses, 1e-6 p0 at every depth; the Hilbert transform of the SIE's shear against the closed form's, by the same quadrature: measured <= 2.3e-7"),
    ("sie", "sxx_peak"): _T(1e-6, "as sxx_surface; measured <= 2.7e-10"),
    ("sie", "stress_depth"): _T(1e-6, "issue target 1e-6 p0; Flamant quadrature of the two methods' tractions: measured <= 1e-9"),
    ("sie", "energy"): _T(1e-8, "issue 11 target: the same superposition on the SIE's stick zones, the energy from their sizes; measured 4e-16"),
    ("sie", "stick"): _T(1e-8, "every stick zone of the cycle is a loading stick zone (Masing), as d, e; measured 5e-15"),
    ("sie", "loop"): _T(1e-8, "the loop is the loading curve by Masing's rule; measured 3e-14"),
    ("sie", "q_states"): _T(1e-6, "shear at Q_max, at Q = 0 after reversal and at -Q_max: as q_interior_max; measured 1.2e-7"),
    # --- flight cycle: the steady state of an in-phase cycle, closed form vs SIE (fan_blade_flight_cycle) --
    ("sie", "stick_ends"): _T(1e-8, "permanent stick zone's ends of the smaller contact's width: the same (S5)-(S6) roots on the SIE's normal solutions (measured 3.4e-16)"),
    ("sie", "cycle_energy"): _T(1e-7, "energy per cycle (S11): both quadratures settle to 1e-8 of W, the SIE's pressure series leaving ~1e-9 (measured 7.9e-11)"),
    ("sie", "q_range"): _T(1e-6, "shear range q_1 - q_0 (S4), more than 5 % of W inside the larger contact: as q_states (measured 2.0e-14)"),
    ("sie", "slip_amplitude"): _T(1e-8, "slip amplitude (S7) over the smaller contact, of its largest value: the corrective gap on both stick zones (measured 3.4e-12)"),
    ("flight", "fatigue"): _T(1e-9, "fatigue parameters of a steady cycle at P, s constant against the fretting cycle's Masing states -Q_max, Q_max (eq. S14): the same stresses to rounding, the critical plane's zoom alike (measured 0: identical floats)"),
    # --- past the paper's framework: the closed form must refuse ---------------------------------
    ("refusal", "closedform"): _T(0.5, "past its framework the closed form must refuse with the named error (error 0), never answer or raise another (error 1)"),
    # --- closed form vs FEM, default mesh --------------------------------------------------------
    ("fem-default", "a"): _T(1e-5, "default preset: W/300, 8x finer at the ends and joins, a node at each located end: measured <= 5.4e-6 W (the punch on one corner)"),
    ("fem-default", "c"): _T(1e-5, "as a; measured <= 4.8e-6 W"),
    ("fem-default", "alpha"): _T(1e-4, "α is the most far-field sensitive figure (finite block L = 200 W); measured <= 2.5e-5"),
    ("fem-default", "P"): _T(1e-12, "load control imposes sum f_i = P in the linear solve (measured 1.3e-15)"),
    ("fem-default", "s"): _T(1e-5, "s is imposed (free) or the FEM pressure centroid (suppressed, ~a, c error); measured <= 1.1e-6 W"),
    ("fem-default", "p_left"): _T(1e-4, "peaks next to the joins, where the mesh is 8x finer; measured <= 2.9e-5"),
    ("fem-default", "p_right"): _T(1e-4, "as p_left"),
    ("fem-default", "x_left"): _T(5e-3, "peaks are flat and sampled at nodes: measured <= 1.1e-3 W"),
    ("fem-default", "x_right"): _T(5e-3, "as x_left"),
    ("fem-default", "p_interior_max"): _T(3e-4, "lumped nodal pressure f_i / w_i (vertex and midpoint nodes err by opposite signs); measured <= 9e-5"),
    ("fem-default", "p_L2"): _T(1e-3, "includes the sqrt edges; measured <= 1.3e-4"),
    ("fem-default", "d"): _T(2e-4, "two similar bodies with Coulomb friction, stick-zone ends located on the locate mesh and resolved like the contact ends (nodes, 8x finer): issue target 1e-3 W = 2.5e-3 d; measured <= 4.7e-5 d"),
    ("fem-default", "e"): _T(2e-4, "as d; measured <= 3.7e-5 d"),
    ("fem-default", "q_interior_max"): _T(1e-2, "nodal shear t_i / w_i next to the sqrt kinks of q at the stick-zone ends (issue target 1e-2); measured <= 3.6e-3"),
    ("fem-default", "q_L2"): _T(5e-3, "includes the sqrt edges; measured <= 1.0e-3"),
    ("fem-default", "q_integral"): _T(2e-3, "issue 11 target; ∫ of the nodal shear's interpolant misses the sqrt ends (sum t_i = Q is exact): measured <= 1.9e-4 on the quick mesh"),
    ("fem-default", "q_bound"): _T(1e-12, "abs(t_i) <= f f_i node by node, and both fields interpolate the same nodes; measured 0"),
    ("fem-default", "sxx_surface"): _T(5e-2, "surface σxx of the FE field through stress recovery; the issue sets no target inside the contact, only the peak (2 %)"),
    ("fem-default", "sxx_peak"): _T(2e-2, "issue target: the peak surface σxx within 2 %"),
    ("fem-default", "stress_depth"): _T(1e-2, "issue target: stresses at depth >= 0.2a within 1e-2 of p0"),
    ("fem-default", "energy"): _T(2e-2, "issue 11 target; the incremental FE path with 21 states per branch is trapezoidal in the load step (second order, see the step study): measured 2.5e-3"),
    ("fem-default", "stick"): _T(2e-3, "stick zones of every state, in units of d at Q_max (issue target 1e-3 W = 2.3e-3 d here); only the zone at Q_max has refined ends: measured 1.3e-3"),
    ("fem-default", "loop"): _T(2e-2, "hysteresis of the plate displacement against the closed form's; measured 2.3e-4"),
    ("fem-default", "q_states"): _T(1e-2, "as q_interior_max, at Q_max, at Q = 0 after reversal and at -Q_max; measured 4.5e-3"),
    # --- closed form vs FEM, quick mesh (every size of the default mesh doubled) -----------------
    ("fem-quick", "a"): _T(1e-4, "quick preset: the default mesh with every size doubled (W/150, 8x finer at the ends and joins), refined automatically until each end lies 3 elements from a join: measured <= 1.8e-5 W"),
    ("fem-quick", "c"): _T(1e-4, "as a; measured <= 2.2e-5 W"),
    ("fem-quick", "alpha"): _T(1e-3, "finite block L = 200 W: far-field error; measured <= 2.5e-5"),
    ("fem-quick", "P"): _T(1e-12, "load control imposes sum f_i = P in the linear solve; measured <= 9e-16"),
    ("fem-quick", "s"): _T(1e-4, "imposed (free, ~1e-16) or centroid of the coarse nodal forces (suppressed, 2.2e-6)"),
    ("fem-quick", "p_left"): _T(5e-4, "peaks next to the joins on the quick mesh; measured <= 9.8e-5"),
    ("fem-quick", "p_right"): _T(5e-4, "as p_left"),
    ("fem-quick", "x_left"): _T(1e-2, "flat peaks sampled at nodes; measured <= 2.7e-3 W"),
    ("fem-quick", "x_right"): _T(1e-2, "as x_left"),
    ("fem-quick", "p_interior_max"): _T(1e-3, "lumped nodal pressure next to the log kinks at ±b; measured <= 3.3e-4"),
    ("fem-quick", "p_L2"): _T(2e-3, "includes the sqrt edges; measured <= 2.5e-4"),
    ("fem-quick", "d"): _T(5e-4, "two-body friction model on the quick mesh; measured <= 1.3e-4 d"),
    ("fem-quick", "e"): _T(5e-4, "as d; measured <= 1.0e-4 d"),
    ("fem-quick", "q_interior_max"): _T(2e-2, "nodal shear next to the stick-zone ends on the quick mesh; measured <= 1.0e-2"),
    ("fem-quick", "q_L2"): _T(1e-2, "includes the sqrt edges; measured <= 3.1e-3"),
    ("fem-quick", "q_integral"): _T(2e-3, "as on the default mesh"),
    ("fem-quick", "q_bound"): _T(1e-12, "as on the default mesh"),
    ("fem-quick", "sxx_surface"): _T(5e-2, "as on the default mesh; measured <= 1.1e-2 (next to a stick-zone end, where q has a square-root kink)"),
    ("fem-quick", "sxx_peak"): _T(2e-2, "the issue's 2 %, on the surface line 1e-3 W clear of the ends (at the end itself σxx has a square-root cusp and the recovered peak converges as sqrt(h_end): Hertz 2.9 % low on quick); measured <= 2.2e-3"),
    ("fem-quick", "stress_depth"): _T(1e-2, "the issue's 1e-2 p0; L2-recovered P2 stress at depth >= 0.1 W; measured <= 3.8e-3"),
    ("fem-quick", "energy"): _T(2e-2, "as on the default mesh; measured 2.8e-3"),
    ("fem-quick", "stick"): _T(1e-2, "stick zones of every state on the quick mesh (bulk h = W/150 away from the zone at Q_max), units of d at Q_max; measured 3.8e-3"),
    ("fem-quick", "loop"): _T(3e-2, "hysteresis of the plate displacement on the quick mesh; measured 9.9e-4"),
    ("fem-quick", "q_states"): _T(3e-2, "as q_interior_max on the quick mesh, at three states; measured 1.2e-2"),
    ("fem-quick", "load_integral"): _T(2e-3, "∫p dx of the linear interpolant misses the sqrt edges; measured <= 1.3e-3 (moment 2e-4 W)"),
    ("fem-quick", "mirror"): _T(1e-3, "mirrored punch and load give a <-> c, α -> -α up to mesh asymmetry; measured <= 1.1e-4"),
    # --- the finite-body validity map (issue 12) --------------------------------------------------
    ("map", "control"): _T(1e-3, "issue 12 target: the paper's model (eq. 2 profile, large bodies) in the finite-body code against the closed form, peak pressure; measured 1.9e-4 (quick)"),
    # --- FEM on the committed reference mesh and the slow Hertz study ----------------------------
    ("fem-reference", "a"): _T(2e-2, "reference.msh has 24 elements on the 1.2-wide zone (h = 0.05); measured 4.5e-3 W"),
    ("fem-reference", "contact_law"): _T(1e-12, "brentq (xtol 2e-12) inverts the flat rounded punch's contact law to its target a"),
    ("fem-export", "round_trip"): _T(1e-12, "meshio writes and reads float64: fields come back to rounding (measured 0)"),
    ("fem-cache", "same"): _T(1e-12, "a condensation read from threepart's cache against one made afresh: the same numbers (C stored bit for bit; a rebuilt field differs by the factorisation's rounding), measured 0 for C and <= 1e-14 for u"),
    ("fem-export", "surface"): _T(1e-9, "inside the contact u_y = profile - approach is imposed node by node (measured 2.8e-15 of it)"),
    ("fem-hertz-study", "edge_order"): _T(0.7, "the edge fit converges about as h (measured 0.98 over W/h = 20..160)"),
    ("fem-hertz-study", "edge_level"): _T(1.5e-4, "edge error at W/h = 160, units of W (measured 8.3e-5)"),
    ("fem-hertz-study", "peak_order"): _T(1.5, "smooth peak converges as h^2 (measured 2.4 over W/h = 20..160)"),
    ("fem-hertz-study", "peak_level"): _T(5e-5, "peak error at W/h = 160 relative to p0 (measured 3.2e-6)"),
    # --- SIE: its own accuracy claim (issue 29; helper sie) ----------------------------------------
    ("sie-target", "pressure"): _T(1e-6, "the SIE's claim: its two-level estimate (n against 2n, of the peak, uniform in θ and next to the joins) must meet this before it answers unasked for n; the projected scheme sums each kink in closed form and meets it at the first pair (measured <= 1e-12)"),
    ("sie-target", "field"): _T(1e-6, "issue 29: pressure, shear (of f p0) and stresses (of p0) of the SIE against the closed form on random punches with radii 0.03 b to 1000 b, away from the ends' sqrt conditioning (measured <= 2e-7 after the exact kink sums; 4.8e-4 before)"),
    ("sie-target", "bulk_energy"): _T(1e-7, "fretting friction work under a bulk stress, SIE against the closed form, slip zones down to 1.3e-5 W: within a millionth of a zone's width of the stick-zone end the two gaps differ by 3e-2 of themselves (the truncated series against the closed form's cancelling terms), measured <= 1.8e-8 (issue-29 cases, wide draws <= 3.5e-10); 1.7e-8 before the SIE's gap was summed without cancellation"),
    ("sie-target", "gap"): _T(1e-7, "the SIE's gap outside a stick zone against the closed form's, from a tenth of a slip zone of 2.4e-5 W to the contact end: measured <= 2.8e-8 (6.4e-7 while it was a difference of O(1) terms)"),
    # --- SIE convergence in n --------------------------------------------------------------------
    ("sie-plain", "load_order"): _T(1.4, "plain load error, n = 24..768: theory 2, kink wobble gives 1.5-2.2 (measured 1.54, 2.23)"),
    ("sie-plain", "load_order_max"): _T(3.0, "n = 50..1600: an order far above 2 would mean the reference is wrong"),
    ("sie-plain", "load_level"): _T(4e-6, "plain relative load error for n >= 450 (measured <= 1.5e-6)"),
    ("sie-plain", "a_order"): _T(1.8, "plain error in a, theory 2 (measured 2.0-2.3)"),
    ("sie-plain", "a_level"): _T(1e-6, "plain relative error in a at n = 588 (measured 2.6e-7)"),
    ("sie-plain", "pressure_order"): _T(0.9, "plain max|dp|/peak: theory 1 at the log kinks (measured 1.05-1.10)"),
    ("sie-plain", "pressure_order_max"): _T(1.4, "n = 50..1600: the log kinks cap the plain pressure at first order"),
    ("sie-plain", "pressure_level"): _T(2.5e-3, "plain max|dp|/peak for n >= 450 (measured <= 1.1e-3)"),
    ("sie-plain", "pressure_level_1600"): _T(1e-3, "plain max|dp|/peak at n = 1600 (about 1.4e-4 expected at first order)"),
    ("sie-plain", "stick_zone"): _T(1e-5, "plain stick zone at n = 512 against the projected one (measured 1.6e-6 of d)"),
    ("sie-reference", "p"): _T(1e-6, "projected pressure vs the adaptive-quadrature inversion integral (measured <= 3.7e-7)"),
    ("sie-reference", "bound_slack"): _T(1e-12, "rounding of the quadrature reference on top of the solver's own error bound"),
    # --- SIE: exact limits and identities --------------------------------------------------------
    ("sie-exact", "hertz"): _T(1e-13, "Hertz slope is linear: both schemes give a, α, p and the stick zone exactly for any n"),
    ("sie-exact", "flat_rounded"): _T(1e-13, "projected scheme reproduces the flat rounded punch's contact law exactly"),
    ("sie-exact", "symmetry"): _T(1e-14, "symmetric punch, central load: a = c and α = 0 up to rounding"),
    ("sie-exact", "mirror"): _T(1e-12, "mirrored punch and load solved separately at n = 64: Newton stops at 1e-14"),
    ("sie-exact", "projected_ends"): _T(1e-14, "projected a, c, α do not depend on n: exact projection of the slope"),
    ("sie-exact", "zero_shear"): _T(1e-13, "Q = 0 sticks everywhere: the stick zone is the contact, up to rounding"),
    ("sie-exact", "slip_zone_shear"): _T(1e-14, "|q| = f p in the slip zones by construction, as a fraction of the peak pressure"),
    ("sie-exact", "beyond"): _T(1e-10, "past lift-off and stick zones on the centre, vs the shifted punch's forward formulas or Hertz: both exact (measured <= 6e-16 W); the reference's own root stops near 1e-13"),
    ("sie-exact", "beyond_pressure"): _T(1e-10, "punch on one corner: the slope over the contact is linear, so the projected pressure is Hertz's exactly (of the peak)"),
    ("sie-exact", "lift_off"): _T(1e-12, "SIE lift-off lever arms vs closedform.lift_off, both exact roots (measured <= 2.4e-15)"),
    ("sie-identity", "load"): _T(1e-8, "∫p dx = P and ∫x p dx = P s by adaptive quadrature with sqrt ends (measured <= 5.4e-10)"),
    ("sie-identity", "shear_load"): _T(1e-6, "∫q dx = Q by the trapezoid rule on 20001 points with sqrt ends (measured 9e-7)"),
    ("sie-identity", "coulomb"): _T(1e-9, "|q| <= f p everywhere, as a fraction of the peak pressure (measured 0)"),
    ("sie-identity", "near_lift_off_gap"): _T(2e-2, "at 0.999 s_max the left end sits just outside the join (measured a/b - 1 = 5.1e-3)"),
    # --- SIE: Gauss–Chebyshev building blocks ----------------------------------------------------
    ("sie-quadrature", "weights"): _T(1e-14, "the weights sum to π/2: only rounding of the sum"),
    ("sie-quadrature", "nodes"): _T(1e-10, "nodes are zeros of U_n: arccos loses digits near ±1 for n = 200"),
    ("sie-quadrature", "exactness"): _T(1e-14, "the rule is exact for degree 2n - 1: only rounding"),
    ("sie-quadrature", "beyond_degree"): _T(1e-6, "degree 2n is not integrated exactly: relative error well above this"),
    ("sie-quadrature", "cauchy"): _T(1e-13, "the discrete Cauchy operator maps U_{k-1} to T_k exactly for k <= n"),
    ("sie-quadrature", "principal_value"): _T(1e-12, "smooth density, n = 24: spectral agreement with scipy's Cauchy-weight quad"),
    ("sie-quadrature", "functionals"): _T(1e-13, "plain G_0..G_2 are exact Chebyshev coefficients for slopes of degree <= n"),
    ("sie-quadrature", "ramp"): _T(1e-15, "closed-form ramp coefficients vs quad split at the kink (epsabs 1e-15)"),
    ("sie-quadrature", "ramp_continuity"): _T(1e-6, "ramp coefficients at β = -1 + 1e-13 move by O(sqrt(1 + β))"),
    ("sie-quadrature", "slope"): _T(1e-14, "segment-wise projection of v' vs quad split at both kinks"),
    ("sie-quadrature", "slope_gradient"): _T(1e-8, "central differences with step 1e-6: truncation 1e-12, rounding 1e-10"),
    ("sie-quadrature", "log_kink"): _T(1e-10, "direct sum truncated at k = 4e5: its tail is O(1/(k^2 phi))"),
    ("sie-quadrature", "sine_series"): _T(1e-12, "40-term sine series vs a direct matrix product: rounding"),
    ("sie-quadrature", "sine_series_long"): _T(1e-12, "2048-term compiled Clenshaw sum vs the geometric series' closed form r sin θ/(1 - 2r cos θ + r^2), of its peak: the recurrence's rounding grows with n near θ = 0, π (measured 3.6e-14)"),
    ("sie-quadrature", "power_series"): _T(1e-13, "2048-term compiled Horner sum vs the geometric sum's closed form, relative: rounding (measured 1.2e-15)"),
    ("sie-quadrature", "kinked_sums"): _T(1e-14, "the compiled kink and remainder sums vs numpy's log_kink and ramp_remainder term by term, of the peak: the same operations (measured 0)"),
    ("sie-quadrature", "gap_sums"): _T(1e-14, "the stick gap's Σ G_k J_k of 16384 geometric G_k vs mpmath quadrature (30 digits) of its integrand, relative: rounding (measured <= 2.2e-16)"),
    # --- the closed form: identities, limits and the quadrature reference --------------------------
    ("closedform", "quadrature"): _T(1e-10, "closed-form P, P s, α, p and the special cases against adaptive quadrature of the paper's integrals (tests/quad_reference.py, epsrel 1e-13): the issue's acceptance bound"),
    ("closedform", "round_off"): _T(1e-12, "an identity, limit or symmetry of the cancellation-free closed form in double precision: rounding of a few dozen operations"),
    ("closedform", "exact"): _T(1e-14, "a figure exact by construction (a = c, e = 0, a conversion of moduli): rounding of a few operations"),
    # --- steady state: the periodic steady state of in-phase loading (docs/STEADY_STATE.md) --------
    ("steady", "round_off"): _T(1e-12, "P, s constant against cf.fretting_cycle (stick-zone ends of W, energy relative, shear and slip amplitude of their peaks), and the cycle's symmetries: the same roots and quadratures, measured <= 1.4e-14"),
    ("steady", "hertz_zone"): _T(1e-8, "Hertz's stick zone from c'^2 = 2ARP*/π and the offset of eq. S15, both methods, of W (the issue's target; measured <= 5.4e-17)"),
    ("steady", "hertz_energy"): _T(1e-10, "the closed form's energy against eq. S16 by quad (epsrel 1e-13): measured <= 2.2e-15"),
    ("steady", "zone"): _T(1e-8, "closed form vs SIE (n = 1024): stick-zone ends of W (measured <= 2.1e-16), slip amplitude of its peak (8.7e-12); the SIE's steady state vs its fretting cycle past the closed form; the shear in the slip zones and the stress against the closed form's own fretting state"),
    ("steady", "energy"): _T(1e-6, "energy per cycle: closed form vs SIE (measured <= 2.7e-10: the SIE's quadrature settles to 1e-8), vs the brute quadrature of the slip differenced with step 1e-6 (measured <= 1.0e-9), vs the SIE's fretting cycle past the closed form (3.3e-9); ∫q = Q by 400-node panels"),
    ("steady", "march_energy"): _T(1e-2, "the history marched on 400 panels (5e-4 mm to 7e-4 mm over the slip zones, 40 steps a half-cycle, three cycles): its last cycle's friction work, measured 0.12 %, 0.18 % and 0.37 % (the panels' error: 80 steps give the same)"),
    ("steady", "march_panels"): _T(1.0, "the ends of the marched history's never-slipping panels (slip below 1e-9 of the most), in panel widths there: measured <= 0.34"),
    ("steady", "march_shakedown"): _T(1e-9, "the marched history's friction work in a shaken-down cycle, of the work of the same ΔQ at constant P: rounding of its dense solves (displacement changes ~1e-16 mm), measured 4e-12 (200 panels, 20 steps a half-cycle, two cycles)"),
    ("steady", "rate"): _T(1e-7, "eqs. S8, S9 against central differences with step 1e-4 of the load path: truncation ~1e-8"),
    # --- numbers stored in the case catalogue ----------------------------------------------------
    ("catalogue", "stored_lift_off"): _T(1e-12, "a stored lift-off lever arm (the closed form's, an exact root) against sie.lift_off, another exact root (as sie-exact lift_off)"),
    ("catalogue", "paper_load"): _T(1e-4, "P = 28846 N/mm is the paper's 4PA/b = 1 rounded to five digits"),
    # --- the reference dataset (`threepart export-refs`): the precision each quantity claims -----
    ("refs", "a"): _T(1e-12, "closed form: an exact root; past lift-off the SIE's projected ends, exact for any n (vs the SIE, and vs the shifted punch's forward formulas: measured <= 6e-16 W)"),
    ("refs", "c"): _T(1e-12, "as a"),
    ("refs", "alpha"): _T(1e-12, "from the same root as a, c (of the slope scale); measured <= 3e-16"),
    ("refs", "s"): _T(1e-12, "imposed (free tilt) or the closed form's s* (suppressed), of W"),
    ("refs", "p"): _T(1e-12, "closed form, or past lift-off the inversion integral at the SIE's ends by adaptive quadrature (sie.reference), of the peak: vs each other and vs tests/quad_reference.py measured <= 2e-15"),
    ("refs", "p_integral"): _T(1e-12, "∫p dx = P and ∫x p dx = P s of the exported pressure by adaptive quadrature (of P, of W): measured <= 2.4e-15"),
    ("refs", "p_peak"): _T(1e-12, "a peak of the pressure above, located to 1e-12 W where p' = 0 (of the peak)"),
    ("refs", "x_peak"): _T(1e-6, "a flat maximum: its position is known to about sqrt(1e-12) W although p is exact"),
    ("refs", "d"): _T(1e-12, "closed form's root; past the framework the SIE's stick-zone ends, exact for any n (of d): vs the SIE measured <= 1.5e-16"),
    ("refs", "e"): _T(1e-12, "as d (of d)"),
    ("refs", "q"): _T(1e-12, "q = f (p - p*), p* the pressure of the stick zone by the same formula (Ciavarella-Jaeger), of max|q|: closed form vs the inversion integral measured 1.2e-15"),
    ("refs", "energy"): _T(1e-12, "closed-form energy per cycle vs the SIE's superposition of its own stick zones: measured 4.2e-16"),
    ("refs", "loop"): _T(1e-12, "the fretting cycle's hysteresis loop (of its largest value) and stick-zone ends (of d): closed form vs the SIE's Masing superposition measured <= 3e-14"),
    ("refs", "stress"): _T(1e-7, "Flamant quadrature of threepart.stress (1e-8 of p0, docs/STRESS.md) on the closed form, or past lift-off on the SIE at n = 1024 (pressure error 5e-8 of the peak); of the peak pressure"),
    # --- load history (issue 31): sie.load_history and fem.load_history ----------------------------
    ("sie-history", "stick_end"): _T(1.5, "stick-zone ends against the closed form, in elements h: the discrete set ends on an element edge, the true end lies in the element whose state flips (measured <= 0.57 h)"),
    ("sie-history", "energy"): _T(1.5e-3, "energy per fretting cycle at n = 400 against closedform.fretting_cycle (measured 6.2e-4)"),
    ("sie-history", "energy_order"): _T(0.8, "the energy's fitted order in h over n = 100..400 (measured 1.2)"),
    ("sie-history", "shear_L1"): _T(1e-3, "∫|Δq| / Q against Cattaneo–Mindlin's shear at n = 400 (measured 2.3e-4)"),
    ("sie-history", "element_loads"): _T(3e-7, "the elements' loads ∫p dx sum to P: 8-point Gauss–Legendre in θ on pieces split at the joins, whose (x ∓ b) ln|x ∓ b| terms limit it (measured 8.9e-8 at 7 elements, 1.1e-9 at 400; rounding for Hertz)"),
    ("sie-history", "equilibrium"): _T(1e-12, "∑ q h = Q and |q| <= f p̄ of each state: the active set's linear solve, rounding"),
    ("sie-history", "shakedown"): _T(1e-9, "friction work of the cycles after the first, of the first's, and slip after the first cycle, of its largest: rounding (measured 4e-13, 1e-12)"),
    ("sie-history", "loop_area"): _T(1e-2, "area of the Q-delta loop of a cycle against its friction work (∮ Q dδ: the normal work is conservative in the uncoupled problem, so a cycling P adds none), both trapezoidal in the states, 40 a cycle: measured 4.0e-3 (P constant) and 5.0e-3 (P cycling in phase)"),
    ("sie-history", "steady"): _T(1e-9, "two first-loading paths, the last cycle: energy, and the shear outside the permanent stick zone of f p_max: the same discrete states, rounding (measured 1e-15)"),
    ("sie-history", "cycle_12"): _T(1e-2, "issue 37 target: the Hertz cycle (R = 10, P 300 -> 500, Q -50 -> 150, f = 0.6) at 12 states a half-cycle, n = 400, the last cycle's energy against the closed form's (S11): measured 4.3e-3 (3.0e-2 before the passing elements' work and the sub-steps)"),
    ("sie-history", "cycle_energy"): _T(1e-2, "flight cycle (fan_blade_flight_cycle): friction work of the third marched cycle, n = 1024, 10 steps a half-cycle, against the closed form's steady state (S11): measured 5.4e-3 with the Ti-on-Ti compliance (slip zones 8 and 7 elements wide; 4 sub-steps a step give 4.0e-3, n = 2048 gives 3.7e-3, n = 512 4.6e-2: the grid's error dominates)"),
    ("fem-history", "stick_end"): _T(3.0, "FEM on the quick mesh against the SIE at n = 400 over one in-phase cycle, stick-zone ends in the FEM's elements h (measured 0.3 h)"),
    ("fem-history", "energy_default"): _T(5e-3, "FEM on the default mesh against the SIE at n = 1600, energy of each of three in-phase cycles (measured 0.04 % on the first)"),
    ("fem-history", "energy"): _T(7e-2, "FEM on the quick mesh against the SIE at n = 400, energy per in-phase cycle of 12 states: measured 5.6 % short. The SIE's history now integrates each step's friction work with its contact ends' passage and sub-steps (issue 37 §3): 1.2820e-5 at 12 states, 1.2898e-5 at 48 (0.6 %); the FEM's history still takes the work at the step's ends, 1.2097e-5 at 12 (0.7 % from the SIE's old figure): the FEM's step error, not its mesh"),
    # --- the steady state's auto past the superposition (issue 37): the SIE's history marched -------
    ("auto-march", "settle"): _T(1e-6, "the march stops when two successive cycles' friction work agree to this: the active-set march repeats a settled cycle's states, so its work repeats to rounding (the issue's one-sided cycle: 1.8e-4 between cycles 2 and 3, 2.2e-8 between 3 and 4, 2.4e-12 between 4 and 5)"),
    ("auto-march", "energy"): _T(2e-2, "the marched cycle (400 elements, 24 states a half-cycle) against the closed form's energy (S11) on random admissible cycles whose slip zones span >= 10 elements: measured <= 1.3e-2 (3.4e-2 at 3-4 elements, which info['march'] reports)"),
    ("auto-march", "stick_end"): _T(1.5, "the marched cycle's permanent stick-zone ends against the closed form's, in elements h: an element stuck all cycle ends on an element edge (measured <= 0.55 h)"),
    ("auto-march", "shakedown"): _T(1e-9, "a marched cycle has shaken down when its friction work is at most this of the largest cycle's (the first's): rounding, as (\"sie-history\", \"shakedown\")"),
    # --- fem steady state (issue 31): fem.steady_state, the cycle marched until it repeats ----------
    ("fem-steady", "settle"): _T(1e-4, "the march stops when two successive cycles' friction work agree to this: a settled cycle repeats the last to rounding (measured 4e-14); the first after a proportional first loading differs by 15 %"),
    ("fem-steady", "shakedown"): _T(1e-9, "friction work of a shaken-down cycle, of its elastic work (max(|ΔQ|, f ΔP) times the largest nodal range of w); its slip amplitude, of W: rounding (measured 2e-16 of the work, slip amplitude 0)"),
    ("fem-steady", "stick_end"): _T(1.0, "permanent stick-zone ends on the quick mesh against the closed form, in the FEM's elements h (no refinement at the stick ends; an end lies half-way between nodes): measured <= 0.23 h (1.7e-3 W)"),
    ("fem-steady", "energy"): _T(3e-2, "energy per cycle on the quick mesh against the closed form, 40 steps a half-cycle (the trapezoid in the step left -0.5 % at 20): measured <= 3.8e-4"),
    ("fem-steady", "amplitude"): _T(5e-2, "slip amplitude over the smaller contact on the quick mesh against eq. S7, of its peak: measured 4.8e-3"),
    ("fem-steady", "path"): _T(1e-9, "steady states reached from different first loadings (all loads together, P then Q, Q overshooting): d, e of W and energy relative: the same discrete cycle, rounding (measured d, e 0, energy 7.8e-14)"),
    ("fem-steady", "zone_default"): _T(2e-3, "issue 31 target: stick-zone ends on the default mesh within 2e-3 W of the closed form's: measured <= 8.8e-4 W"),
    ("fem-steady", "energy_default"): _T(1e-2, "issue 31 target: energy per cycle on the default mesh within 1 %: measured <= 0.40 % (40 steps a half-cycle)"),
    # --- the flight cycle's steady state (STEADY_QUANTITIES) by the FEM, in the verification run ---
    ("fem-quick", "stick_ends"): _T(2e-3, "fan_blade_flight_cycle on the quick mesh: stick-zone ends of W (the issue's 2e-3 W on the default mesh); measured 4.5e-4 (Ti on Ti, issue 37; 2.4e-4 as a rigid punch)"),
    ("fem-quick", "cycle_energy"): _T(3e-2, "as on the default mesh, quick mesh: measured 1.2e-2 (slip zones of a few elements)"),
    ("fem-quick", "q_range"): _T(3e-3, "shear range q_1 - q_0 at the quick mesh's nodes, interior: measured 6.4e-4"),
    ("fem-quick", "slip_amplitude"): _T(0.12, "slip amplitude of the flight cycle (Ti on Ti, issue 37: slip zones 0.029 and 0.009 mm wide at the lower end state, 0.032 and 0.026 mm at the upper): nodal slip, linear between nodes, against eq. S7; measured 6.0e-2 of the largest (the issue sets no target; as a rigid punch, slip zones of 0.021 and 0.0055 mm, it was 0.42 under a limit of 0.6)"),
    ("fem-default", "stick_ends"): _T(2e-3, "issue 31 target: permanent stick-zone ends within 2e-3 W on the default mesh; measured 2.8e-4 on fan_blade_flight_cycle"),
    ("fem-default", "cycle_energy"): _T(1e-2, "issue 31 target: energy per cycle within 1 % on the default mesh, 40 steps a half-cycle; measured 2.8e-3 on fan_blade_flight_cycle"),
    ("fem-default", "q_range"): _T(1e-3, "shear range q_1 - q_0 at the default mesh's nodes, interior: measured 1.7e-4"),
    ("fem-default", "slip_amplitude"): _T(3e-2, "as on the quick mesh, with half its elements: measured 5.2e-3 of the largest on the Ti-on-Ti flight cycle, 1.3e-2 on the fine mesh (the nodal slip's peak between nodes: not monotone in h; quick 6.0e-2); issue 37 §9: 0.24 under a limit of 0.35 when the case was a rigid punch, its slip zones 1.4 to 4.7 times narrower; no target in the issue"),
    # --- the one check of every answer (threepart.results.answer), of every method -----------------------
    ("answer", "p_min"): _T(1e-6, "the least pressure over the contact, of the peak: the closed form's is exact (rounding, 1e-15) and the SIE's (n = 1024) errs by <= 5e-8 of the peak (the table's 'refs' 'stress'); the SIE's answer to issue 29's case below its separation load dipped by -2.4e-5 of the peak (sharp R1 = 0.037 b), so 1e-6 refuses it and no rounding; measured on 300 random cases at n = 1024: no dip at all (min p >= 0)"),
    ("answer", "q_bound"): _T(1e-6, "|q| - f p, of f p_max: 0 in the slip zones by construction (q = f p), and in the stick zone as the corrective p*'s pointwise error, <= 5e-8 of the peak for the SIE at n = 1024 (as 'sie' 'q_bound'); the FEM holds |t_i| <= f f_i node by node (1e-12)"),
    # --- the convergence tools on manufactured sequences -----------------------------------------
    ("convergence", "exact"): _T(1e-12, "err = C h^p exactly: the fit and the extrapolation are exact up to rounding"),
    ("convergence", "iterated"): _T(1e-8, "the three-level fixed point stops when p moves by < 1e-10"),
}
# --- edge asymptotics (issue 32, threepart.results.edges, docs/EDGES.md): tests/test_edges.py, tests/test_match.py
TOLERANCES.update({
    ("edges", "K_N_exact"): _T(1e-8, "issue 32 target: K_N of the closed form (E1), the SIE's density (E4) and Hertz's p0 sqrt(2/a) agree to 1e-8; measured <= 3.1e-15 (rounding)"),
    ("edges", "K_N_quadrature"): _T(1e-8, "closed-form K_N (E1) against p/sqrt(r) of eq. inverted_IE by adaptive quadrature at r = 1e-8 W and 2e-8 W, Richardson-extrapolated (the r term is 1.5e-8 of K_N there); measured <= 9.6e-13"),
    ("edges", "identity"): _T(1e-12, "an algebraic identity of the asymptotes (E3, E5: Hertz's K_T, Mindlin's and Nowell-Hills' first-order slip zones, Hertz's relative error = slip/W) evaluated in floating point"),
    ("edges", "fem_default"): _T(1e-2, "issue 32 target: the FEM's fitted K_N within 1 % on its default mesh; measured <= 2.4e-3 on the catalogue's fem suite"),
    ("edges", "fem_quick"): _T(8e-3, "the FEM's fitted K_N on the quick mesh, the default run's test: measured <= 3.9e-3 (near_lift_off's left edge), twice that"),
    ("edges", "slip_first_order"): _T(1e-2, "issue 32 target: the asymptotic slip zone within 1 % of the exact one where the slip zone is under 1 % of W (Hertz: the error is slip/W exactly)"),
    ("edges", "slip_constant"): _T(3.0, "relative error of the asymptotic slip zone per slip/W on the catalogue's three-part punches, Q/fP <= 0.05: measured <= 1.95 in partial slip and 2.27 in a steady state under a bulk stress in proportion to ΔQ (caseA_moment's right edge, its arc c - b 0.22 W: the second-order terms of p and q set the constant); Hertz's is exactly 1, so the 1 % target at slip < 1 % W holds for Hertz, and for these punches only below about 0.4 % W"),
    ("edges", "slip_order"): _T(0.95, "the asymptotic slip zone is first order: its relative error falls as (slip/W)^1; fitted 1.00"),
    ("edges", "slip_order_max"): _T(1.05, "as slip_order, from above: fitted 1.00"),
    ("match", "multipliers"): _T(1e-6, "issue 32 target: the matched pad's K_N, K_T and slip zone equal the flank's edge to 1e-6 (closed form); measured <= 1e-14"),
    ("match", "sxx_slip"): _T(5e-2, "issue 32 target: the pad's surface sigma_xx within 5 % of the flank's over the slip zone, of the flank's largest |sigma_xx| there; measured 1.8e-2 to 4.3e-2 on caseA_moment's edges at Q/fP <= 0.05 (a pad of the flank's width, or R = 50 mm at Q/fP = 0.02); it falls with the slip zone, a first-order match (docs/EDGES.md section 6)"),
    ("match", "sxx_bulk"): _T(6e-2, "the default pad (the radius of least surface sigma_xx error over the slip zone) on the catalogue's flanks: measured 2.3e-2 on fan_blade_flank_bulk's left edge (Ti on Ti), <= 1.8e-2 on slip_Q0.4's; judged where the edge is in its asymptotic regime (exact slip zone within 1.5x Mindlin's 2|K_T|/(f K_N)): the bulk-loaded right edge (2.8x, the bulk stress cancels 95 % of K_T) reaches 0.21 at best"),
    ("match", "slip_zone_min"): _T(1e-9, "the smallest slip zone, as a fraction of the contact width W, over which match() compares the surface sigma_xx (issue 37): below it the rounding of the contact and stick-zone ends (1e-16 W) sets the slip zone; measured on caseA_moment's left edge at P = 400, s = 0.1: sxx_error 1.8e-7 at 1.7e-9 W (1.4e-7 by its first order in the slip zone, from 1.7e-7 W), 2.4e-6 at 1.7e-10 W where first order gives 1.4e-8, 8.8e-5 at 1.7e-11 W, 0.61 at 4e-16 W, NaN at Q = 0"),
    ("match", "fatigue"): _T(1e-2, "the fatigue parameters' largest values near the edge (von Mises range, SWT, Findley, Ruiz's FFDP), pad against flank: measured <= 3e-3 on caseA_moment's edges at Q/fP <= 0.05 with a pad of the flank's width, <= 7.9e-3 (Ruiz's FFDP; the others <= 2.8e-3) with the default pad of least sigma_xx error, whose sigma_xx is within 2e-3"),
})

# --- the closed-form worn limit of fretting (issue 39, closedform/wear.py, docs/WEAR.md): tests/test_wear_limit.py
TOLERANCES.update({
    ("wear-limit", "quadrature"): _T(2e-9, "∫p = P and ∫x p = P s of the singular limit pressure by 2^16-node Gauss–Chebyshev (first kind): the joins' (x∓b)ln|x∓b| limit the rule; measured <= 3.9e-10 (three-part, all rules), 1e-12 (Hertz)"),
    ("wear-limit", "round_off"): _T(1e-12, "Hertz against eq. W11; C1 = 0 where the stick zone cannot move (symmetric, Hertz with a moment); the ends' K = Q_max/(π f) of eqs. W7, W12 and Coulomb's margin of the fixed points, of Q_max/π (measured >= -0: 1.4e-7 least): rounding of the closed forms and the roots"),
    ("wear-limit", "hertz"): _T(1e-11, "Hertz against the unbounded-ends Gauss–Chebyshev collocation (exact for a quadratic p w): measured <= 1.6e-13 of the peak, tilt 7e-16"),
    ("wear-limit", "collocation"): _T(3e-5, "three-part punch against the collocation with n = 1600, 5 % of the width from the ends, of the peak (tilt of the slope range): the joins' kinks, measured <= 6.2e-6 (tilt 8.8e-8; held, pinned 8.9e-7, consistent 9.2e-7)"),
    ("wear-limit", "gap"): _T(1e-8, "the worn profile plus the half-plane displacement (QUADPACK weighted rules, epsrel 1e-10) a rigid-body motion over the scar, of the largest depth: measured <= 3.4e-10 (three-part, pinned), 1.1e-13 (Hertz)"),
})

# --- the SIE on a worn profile and the fretting-wear march (issue 39, sie/profile.py, sie/wear.py): tests/test_wear.py
TOLERANCES.update({
    ("wear", "zero_depth"): _T(1e-12, "a zero worn depth adds nothing to the punch's exact coefficients: ends (of W), tilt and pressure (of the peak) as the punch's own SIE; measured 0 and 1.7e-16"),
    ("wear", "profile_ends"): _T(1e-5, "a quadratic depth x^2/20 at 4001 knots against Hertz of the summed curvature, of W: the knots' interpolation; measured 8.4e-7 W (pchip), 5.2e-6 W (linear: the secants lie above the parabola by h^2/8 R')"),
    ("wear", "profile_pressure"): _T(5e-3, "as profile_ends, the pressure of the peak away from the ends: pchip's slope is first order at the minimum x = 0 (5.3e-4), linear's secants kink at every knot (3.0e-3)"),
    ("wear", "equilibrium"): _T(1e-10, "∫p = P and ∫x p = P s of a worn profile's pressure function by the 8192-point midpoint rule in θ (exact for its 2048 sine terms): the load and centroid equations hold for the series to rounding: measured 0 and 2.3e-17"),
    ("wear", "unbounded"): _T(1e-10, "unbounded ends on the limit's stick zone against closedform.wear_limit (eq. W3): pressure of the unworn peak 5 % from the ends, tilt of the slope scale, the ends' K; measured <= 1.6e-14"),
    ("wear", "unworn_energy"): _T(1e-9, "a zero depth's fretting cycle against the closed form: the loop's energy (ln h/h*, 48-node Gauss–Legendre) and the friction work ∫4f²pG* dx (96 nodes per slip zone) measured 4e-16, 3.6e-15; the stick zone at Q_max (mm) 1e-16"),
    ("wear", "stick_zone"): _T(1e-3, "issue 39 target: a symmetric contact's stick zone unchanged by wear, of W: the nodes gather at its ends (sie.wear._grid) and its active set does not change; measured 0 W after 60 cycles at k = 1e-5 (Hertz, 300 nodes) and over 1.5e6 cycles of the symmetric three-part punch"),
    ("wear", "identity"): _T(5e-3, "eq. W15: the worn area per cycle (the knots' increments k 4 f² p G*, trapezoidal) against k times the loop's area (ln h/h*) of the same worn state, Hertz after 60 cycles at k = 1e-5: measured 1.7e-3 on 301 knots; 6.4e-2 on 151, whose 13 knots per slip zone miss the rate's sqrt(r) at the contact ends"),
    ("wear", "energy_routes"): _T(2e-3, "the loop's area (ln h/h*, the stick zones alone) against the march's friction work ∫4f²pG* dx (the slip, by the worn profile's gap series) on a marched worn profile: measured 2.3e-4 on 301 knots (2.0e-3 on 151), the loop's own two-level estimate 3.3e-5"),
    ("wear", "jump"): _T(1e-2, "the automatic cycle jumps (sie.wear: depth per jump <= 1e-2 A P/π, Euler's stability bound per knot) against one cycle per step, Hertz, 40 cycles at k = 1e-5: measured 3.5e-3 of the largest depth, 1.1e-3 of the energy (20 steps against 40); explicit Euler's first-order error in the jump"),
    ("wear", "limit_L2"): _T(1e-2, "issue 39 target: the marched pressure within 1 % of the worn limit (eq. W11), L2 over the stick zone less 10 % of it at each end"),
    ("wear", "energy_left"): _T(5e-2, "issue 39 target: the energy per cycle below 5 % of its start after k N well past the elastic approach"),
    ("wear", "fem_depth"): _T(3e-2, "issue 39 target: the FEM's worn depth against the SIE's after the same cycles and jumps, of the SIE's largest depth (the FEM's nodes, the SIE's interpolated): measured 8.3e-3 (Hertz, 60 cycles one at a time, Archard k = 1e-5); 4.0e-2 at jumps of 3, past the FEM nodes' stability bound; the fan-blade flank 1.9e-2 at 1e5 cycles and 0.67 at 1e6, where the FE interface erodes the limit's marginal stick-zone end (docs/WEAR.md section 8)"),
    ("wear", "fem_stick_zone"): _T(5e-3, "issue 39 target: the FEM's stick zone on a symmetric contact unchanged by wear, of W: measured 4.1e-3 W (Hertz, 60 and 100 cycles at k = 1e-5; the ends read from p*^2 at a uniform W/100 mesh)"),
    ("wear", "nodes_cycle"): _T(5e-3, "the fretting cycle on the march's 400 nodes of an unworn Hertz contact (WearResult.final at N = 0) against the closed form: the friction work 1.2e-4, the loop's area (21 states, trapezoidal) 2.3e-3 of the energy; the shear on loading and unloading 1.5e-5 of f p0 inside 0.12 mm"),
    ("wear", "limit_monotone"): _T(1e-12, "issue 39 target, to the nodes' floor: the L2 distance to the limit (of the limit's norm) falls at every record except where it ends at or below its last value, the discrete long-run state's (reports.verify.wear_section.rise_above_floor): rounding. Measured 0: the flank (400 nodes) falls to 4.358e-5 at 9.9e5 cycles, then returns to 4.380e-5; Hertz (200 nodes) falls to 8.1e-6 at cycle 572, then returns to its floor 2.2e-4"),
    ("wear", "limit_p0"): _T(1e-4, "issue 39 target: the marched long-run pressure against the closed-form limit on the stick zone it reached, largest over the stick zone less 10 % at each end, of the unworn peak: measured 3.7e-5 (the symmetric three-part punch, 400 nodes, 1.5e6 cycles); on the flank, whose receding end drifts under the moment, 6.5e-5 at 400 nodes and 1.2e-3, 2.0e-4, 2.3e-4 at 300, 500, 600 (docs/WEAR.md section 8)"),
    ("wear", "energy_monotone"): _T(1e-3, "the energy per cycle past its early peak may rise, of the peak, where a node joins the contact at its outer edge (the contact grows by a node): measured 7.4e-4 (the flank, 400 nodes); on Hertz (200 nodes) it falls at every record past its peak"),
})

# --- the core's contact on a discrete surface (threepart/halfplane/surface.py): tests/test_surface.py
TOLERANCES.update({
    ("surface", "kernel"): _T(1e-10, "the nodes' influence coefficients (u ln|u| - u, u^2 ln|u|/2 - u^2/4) against QUADPACK of the log kernel times a hat: rounding of the closed form's differences"),
    ("surface", "hertz"): _T(1e-5, "Hertz on 800 uniform nodes over 2.6 a, the pressure linear between them: the pressure of its peak within 0.8 a of the centre, and the tilt of a/R: collocation at the nodes, measured 4.4e-6 (s = 0 and 0.03 mm; the contact's ends lie between nodes), tilt 7e-16"),
})

# closed form vs FEM, fine mesh: every size of the default mesh halved, so the default's limits hold
TOLERANCES.update({("fem-fine", q): _T(t.limit, f"as on the default mesh, which is coarser: {t.reason}")
                   for (comparison, q), t in list(TOLERANCES.items()) if comparison == "fem-default"})

# --- robustness study (reports.verify.robustness, `threepart verify --full`): the issue-29 property rules
# on a wide seeded draw, each limit the table's entry that the default suite's tests assert ---------
_COUNT = "a count of offending draws: none may (one breaks it)"
TOLERANCES.update({("robustness", q): _T(TOLERANCES[key].limit, f"{why}: {TOLERANCES[key].reason}")
                   for q, key, why in (
    ("a", ("sie", "a"), "contact ends of the normal draw, as the SIE's entry"),
    ("p_interior_max", ("sie-target", "field"), "pressure of the normal draw, as the wide-draw tests"),
    ("d", ("sie", "d"), "stick-zone ends of the slip draw, as the SIE's entry"),
    ("q_interior_max", ("sie-target", "field"), "shear of the slip draw, as the wide-draw tests"),
    ("energy", ("sie-target", "bulk_energy"), "friction work of the fretting draw under a bulk stress"),
    ("stick", ("sie", "stick"), "stick-zone ends over the fretting draw's cycles, as the SIE's entry"),
    ("p_min", ("answer", "p_min"), "p >= 0 of every answer, as the answer check"),
    ("q_bound", ("answer", "q_bound"), "|q| <= f p of every slip answer, as the answer check"))})
TOLERANCES.update({
    ("robustness", "wrong_refusals"): _T(0.5, f"{_COUNT}: where one method answers the other must too, "
                                              "and refuse by the named error the SIE's within_paper implies"),
    ("robustness", "no_convergence"): _T(0.5, f"{_COUNT}: NoConvergenceError or an unnamed error is never "
                                              "an answer on admissible input (issue 29)"),
})


# --- the outside codes: another code's points judged (the referee), GetFEM and CalculiX with friction
# (threepart/tolerances/outside.py, one row each as here) ------------------------------------------------
TOLERANCES.update({key: Tolerance(limit, reason) for key, (limit, reason) in OUTSIDE.items()})

# --- limits outside the (comparison, quantity) table, each with its reason --------------------------
#: the validity map's designer limit (issue 23): the closed form within 1 % of the finite body's peak
#: pressure, either way; the small-slope study marks where its cost of the peak reaches it too
MAP_LIMIT = 0.01
#: the validity map's boundaries (issue 23): where the closed form's signed peak error crosses
#: -5 %, -1 %, +1 % and +5 % of the finite body's peak
MAP_LEVELS = (-0.05, -MAP_LIMIT, MAP_LIMIT, 0.05)


@dataclass(frozen=True)
class Baseline:
    """The tolerance of a kind of regression-baseline quantity: ``math.isclose``'s two, and why."""

    rtol: float
    atol: float
    reason: str

    def limits(self) -> dict[str, float]:
        """``{"rtol": ..., "atol": ...}`` as ``tests/regression.py`` takes them."""
        return {"rtol": self.rtol, "atol": self.atol}


#: the regression baselines' tolerances (tests/test_baselines.py), by kind of quantity
BASELINES = {
    "closedform": Baseline(1e-9, 1e-12, "closed-form figures: deterministic Newton solves to ~1e-14; "
                                        "allow for BLAS/libm differences"),
    "closedform_x": Baseline(1e-6, 1e-9, "peak positions: a flat maximum is located to ~sqrt(machine "
                                         "eps) by the bounded search"),
    "sie_error": Baseline(0.0, 1e-7, "SIE errors against the closed form are round-off-level numbers: "
                                     "guard their size, not digits"),
    "history_error": Baseline(1e-6, 1e-9, "the marched history's errors against the steady state (a "
                                          "flight cycle): an active-set march of 60 steps, deterministic, "
                                          "whose stick-zone ends in elements and energy move with rounding "
                                          "only"),
    "fem": Baseline(1e-4, 1e-9, "quick-mesh FEM figures: deterministic given gmsh's mesh; gmsh versions "
                                "may move nodes slightly"),
    "fem_error": Baseline(0.0, 1e-4, "FEM errors against the closed form: a change of 1e-4 (normalised) "
                                     "is a real change"),
}


def tolerance(comparison: str, quantity: str) -> Tolerance:
    """The table entry for ``(comparison, quantity)``; ``KeyError`` names both if missing."""
    try:
        return TOLERANCES[comparison, quantity]
    except KeyError:
        raise KeyError(f"no tolerance for comparison {comparison!r}, quantity {quantity!r}") from None


def fem_comparison(mesh: object) -> str:
    """Name of the FEM comparison for a mesh preset: ``"fem-quick"``, ``"fem-default"`` or ``"fem-fine"``.

    Any other mesh argument is judged as the default preset.
    """
    return f"fem-{mesh}" if mesh in ("quick", "default", "fine") else "fem-default"

"""threepart: the tilted three-part piecewise-quadratic half-plane contact, verified three ways.

This package holds what every solver shares: the problem, the result shape and
the errors. The solvers and the report are its subpackages; importing this
package loads none of them.

Subpackages
-----------
closedform          -- the paper's closed-form solution (Andresen, Hills & Vazquez)
sie                 -- independent Gauss-Chebyshev solver of the same integral equations
fem                 -- independent finite-element model (scikit-fem on gmsh meshes)
meshes              -- gmsh mesh builders and the mesh manifest
reports             -- the verification run: comparison, tolerance report, baselines
calculix            -- CalculiX: meshes, decks, runs, the one reader of its output (not loaded here)
readers             -- readers of other codes' contact results, registered by format (not loaded here)

Shared modules
--------------
tolerances          -- the one tolerance table, with a physical reason per entry
convergence         -- fitted and three-level observed orders, GCI, Richardson step
problem             -- the punch (eq. 2), the material (eq. 4), the input checks, the case catalogue
results             -- the one result shape, the load cycles, the check of every answer, edge multipliers
halfplane           -- what the half-plane methods share: bulk stress, steady cycles, load histories, Coulomb
stress              -- the stresses in the substrate from any method's tractions
fatigue             -- fretting-fatigue parameters and their table
studies             -- studies above the methods: the matching pad test
output              -- atomic, marked output directories; strict JSON
cli                 -- the ``threepart`` command line

Problem
-------
Punch               -- three-part punch (R1, R2, b, R), profile v(x) and slope v'(x), eq. (2)
compliance          -- A of eq. (4), plane strain, two bodies
similar_pair        -- A = 4(1 - nu^2)/E, two bodies of one material
material_compliance -- A of a material (E in MPa, checked): both bodies (the convention), or a rigid punch
rigid_punch         -- A = 2(1 - nu^2)/E, a rigid punch on an elastic half-plane
TILTS               -- tilt modes "free" and "suppressed"

Solving
-------
solve               -- normal or partial-slip solution by method "auto" (closed form where it
                       holds, else SIE), "closedform", "sie" or "fem"
steady_state        -- the periodic steady state of an in-phase cycle between two states
                       (P, s, Q, sigma_bulk), by method "auto", "closedform" or "sie"
fretting            -- one fretting cycle Q = 0 -> Q_max -> -Q_max -> Q_max at constant P, by
                       method "auto" (closed form where it holds, else SIE), "closedform", "sie" or "fem"
wear                -- fretting wear at constant P, s, Q between +-Q_max: the worn depth marched by
                       Archard's or the energy law with cycle jumping (method "sie"; threepart.fretting_wear)
WearResult          -- its result: cycles, energy, stick_zones, depths, volume, final (a fretting cycle)
METHODS, CHOICES    -- the three methods; what `method` may be

Results
-------
NormalResult        -- a, c, alpha, P, s, pressure(x), peaks(): the shape every solver returns
SlipResult          -- adds Q, f, d, e, stick_zone and shear(x)
Peak                -- a pressure maximum p at x
SteadyStateResult   -- the periodic steady state of an in-phase cycle: d, e, energy, shakedown (threepart.results.cycles)
HistoryResult       -- a load history marched with the memory of slip: stick, shear(x, k), energy (threepart.results.cycles)

Stresses (threepart.stress)
--------
Stress              -- sxx, szz, sxz in the substrate, principal, von Mises, Tresca (tension > 0)
hilbert             -- (1/pi) PV int f(t)/(t - x) dt over the contact, kinks respected

Fretting fatigue (threepart.fatigue)
----------------
stress_history      -- the stresses of a cycle's states at points (x, z)
von_mises_range     -- max over pairs of states of the von Mises stress of the difference
swt                 -- Smith-Watson-Topper on the critical plane
findley             -- Findley on the critical plane, tau_a + k sigma_n,max
ruiz                -- Ruiz's FDP (tau delta) and FFDP (sigma_xx tau delta) at the surface
HotSpot             -- where a parameter is largest, how much, and on which plane
(all four at once: ``threepart.fatigue.fatigue``; the module keeps the name ``fatigue``)

Errors (one family, raised by every solver; all derive from ThreepartError)
------
ThreepartError      -- the base: ``except threepart.ThreepartError`` catches any refusal of threepart's
LiftOffError        -- s (or P) puts a contact edge inside the central segment (ValueError)
SeparationError     -- a concave centre would separate (ValueError)
FullSlidingError    -- |Q| >= f P (ValueError)
StickZoneError      -- the stick zone would end inside the central segment (ValueError)
StickSeparationError -- a stick zone whose corrective pressure breaks Coulomb's law (a StickZoneError)
NoConvergenceError  -- an iteration did not converge (RuntimeError)
ContactZoneError    -- the FE contact reached the end of its mesh zone (RuntimeError)
MeshResolutionError -- a contact end too close to a join for the FE mesh (a ContactZoneError)
SlopeLimitError     -- the contact's slope is past half-plane theory's small-slope limit (ValueError)
ArcExtentError      -- a contact end runs past an edge arc's extent (ValueError)
CoulombError        -- an answer's shear breaks |q| <= f p (a StickZoneError; threepart.results.answer)
ReaderError         -- another code's file that cannot be read, named with why (ValueError)
(the rest of the family, and its tree: ``threepart.errors``)
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from .lazy import lazy_names

#: each public name and the module that defines it; loaded on first use (PEP 562), so that
#: ``import threepart`` (and the console script, before it parses its arguments) loads
#: neither numpy nor scipy, and Ctrl-C during those imports is the command line's to handle
_HOMES = {
    "Punch": "problem.punch", "compliance": "problem.material", "similar_pair": "problem.material",
    "rigid_punch": "problem.material", "material_compliance": "problem.material", "TILTS": "problem.validate",
    "NormalResult": "results.contact", "SlipResult": "results.slip", "Peak": "results.contact",
    "SteadyStateResult": "results.cycles", "HistoryResult": "results.cycles",
    "LiftOffError": "errors", "SeparationError": "errors", "FullSlidingError": "errors",
    "StickZoneError": "errors", "StickSeparationError": "errors",
    "NoConvergenceError": "errors", "ContactZoneError": "errors",
    "MeshResolutionError": "errors", "SlopeLimitError": "errors", "ArcExtentError": "errors",
    "CoulombError": "errors", "ThreepartError": "errors", "ReaderError": "errors",
    "solve": "methods", "METHODS": "methods", "CHOICES": "methods",
    "Stress": "stress.flamant",
    "hilbert": "stress.flamant",
    "stress_history": "fatigue.history", "von_mises_range": "fatigue.functions",
    "swt": "fatigue.functions", "findley": "fatigue.functions", "ruiz": "fatigue.functions",
    "HotSpot": "fatigue.functions",
    "steady_state": "methods", "fretting": "methods",
    "wear": "fretting_wear", "WearResult": "fretting_wear",
}
_SUBPACKAGES = ("closedform", "sie", "fem", "meshes", "reports")

__all__ = list(_HOMES)

if TYPE_CHECKING:   # pragma: no cover - for type checkers and IDEs only
    from .errors import (ArcExtentError, ContactZoneError, CoulombError, FullSlidingError,
                         LiftOffError, MeshResolutionError, NoConvergenceError, SeparationError,
                         ReaderError, SlopeLimitError, StickSeparationError, StickZoneError,
                         ThreepartError)
    from .problem.material import compliance, material_compliance, rigid_punch, similar_pair
    from .methods import CHOICES, METHODS, fretting, solve, steady_state
    from .problem.punch import Punch
    from .results.contact import NormalResult, Peak
    from .results.slip import SlipResult
    from .results.cycles import HistoryResult, SteadyStateResult
    from .fatigue.functions import HotSpot, findley, ruiz, swt, von_mises_range
    from .fatigue.history import stress_history
    from .stress.flamant import Stress, hilbert
    from .fretting_wear import WearResult, wear
    from .problem.checks import TILTS


__getattr__, __dir__ = lazy_names(__name__, _HOMES, _SUBPACKAGES)

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

Shared modules
--------------
catalogue           -- the one case catalogue (cases.json): verify, fem and sie suites
tolerances          -- the one tolerance table, with a physical reason per entry
convergence         -- fitted and three-level observed orders, GCI, Richardson step
output              -- atomic, marked output directories; strict JSON
validate            -- the input checks behind every entry point's ``_*_iv`` helper
cli                 -- the ``threepart`` command line

Problem
-------
Punch               -- three-part punch (R1, R2, b, R), profile v(x) and slope v'(x), eq. (2)
compliance          -- A of eq. (4), plane strain, two bodies
similar_pair        -- A = 4(1 - nu^2)/E, two bodies of one material
rigid_punch         -- A = 2(1 - nu^2)/E, a rigid punch on an elastic half-plane
TILTS               -- tilt modes "free" and "suppressed"

Solving
-------
solve               -- normal or partial-slip solution by method "auto" (closed form where it
                       holds, else SIE), "closedform", "sie" or "fem"
METHODS, CHOICES    -- the three methods; what `method` may be

Results
-------
NormalResult        -- a, c, alpha, P, s, pressure(x), peaks(): the shape every solver returns
SlipResult          -- adds Q, f, d, e, stick_zone and shear(x)
Peak                -- a pressure maximum p at x

Errors (one family, raised by every solver)
------
LiftOffError        -- s (or P) puts a contact edge inside the central segment (ValueError)
SeparationError     -- a concave centre would separate (ValueError)
FullSlidingError    -- |Q| >= f P (ValueError)
StickZoneError      -- the stick zone would end inside the central segment (ValueError)
NoConvergenceError  -- an iteration did not converge (RuntimeError)
ContactZoneError    -- the FE contact reached the end of its mesh zone (RuntimeError)
MeshResolutionError -- a contact end too close to a join for the FE mesh (a ContactZoneError)
"""
from __future__ import annotations

from .methods import CHOICES, METHODS, solve
from .errors import (ContactZoneError, FullSlidingError, LiftOffError, MeshResolutionError,
                     NoConvergenceError, SeparationError, StickZoneError)
from .material import compliance, rigid_punch, similar_pair
from .punch import Punch
from .results import NormalResult, Peak, SlipResult
from .validate import TILTS

__all__ = [
    "Punch", "compliance", "similar_pair", "rigid_punch", "TILTS",
    "NormalResult", "SlipResult", "Peak",
    "LiftOffError", "SeparationError", "FullSlidingError", "StickZoneError",
    "NoConvergenceError", "ContactZoneError", "MeshResolutionError",
    "solve", "METHODS", "CHOICES",
]

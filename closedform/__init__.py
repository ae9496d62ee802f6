"""Closed-form solution of the tilted three-part half-plane contact (Andresen, Hills & Vázquez).

Geometry and shared result shape
--------------------------------
Punch               -- three-part punch (R1, R2, b, R), profile v(x) and slope v'(x), eq. (2)
NormalResult        -- result shape shared by all solvers: a, c, alpha, P, s, pressure(x)
SlipResult          -- partial-slip result shape: adds d, e, shear(x)

Material
--------
compliance          -- A of eq. (4), plane strain, two bodies
similar_pair        -- A = 4(1 - nu^2)/E
rigid_punch         -- A = 2(1 - nu^2)/E

Forward closed forms for a given contact [-a, c] (module ``formulas``)
----------------------------------------------------------------------
formulas.load       -- P, eq. (equilibrium_condition_1), sign corrected
formulas.tilt       -- alpha, eq. (consistency_condition)
formulas.moment     -- P s, eq. (equilibrium_condition_2), sign corrected
formulas.pressure   -- compressive pressure, eq. (pressure_abbreviated)
special             -- case A, case C and Hertz forms from their own equations

Inverse problems
----------------
solve_normal        -- a, c, alpha for P and s (tilt free), or a_hat, c_hat, s* (suppressed)
solve_normal_batch  -- the same for arrays of load cases (vectorised Newton)
lift_off            -- admissible lever arms s_min < s < s_max for a load P
P_min               -- load at which a convex centre first touches both joins
solve_partial_slip  -- Ciavarella-Jaeger stick zone [-(d+e), d-e] and shear q(x)

Errors
------
LiftOffError, FullSlidingError, StickZoneError, SeparationError -- ValueError subclasses
NoConvergenceError  -- a root finder failed
"""
from __future__ import annotations

from . import formulas, special
from threepart.errors import (FullSlidingError, LiftOffError, NoConvergenceError, SeparationError,
                     StickZoneError)
from threepart.punch import Punch
from threepart.material import compliance, rigid_punch, similar_pair
from .normal import (LiftOff, NormalBatch, NormalSolution, P_min, lift_off, solve_normal,
                     solve_normal_batch)
from threepart.results import NormalResult, Peak, SlipResult
from .slip import SlipSolution, solve_partial_slip

__all__ = [
    "Punch", "NormalResult", "SlipResult", "Peak",
    "compliance", "similar_pair", "rigid_punch",
    "formulas", "special",
    "solve_normal", "solve_normal_batch", "lift_off", "P_min", "solve_partial_slip",
    "NormalSolution", "NormalBatch", "LiftOff", "SlipSolution",
    "LiftOffError", "FullSlidingError", "StickZoneError", "SeparationError", "NoConvergenceError",
]

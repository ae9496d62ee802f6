"""Closed-form solution of the tilted three-part half-plane contact (Andresen, Hills & Vázquez).

The problem (``Punch``, the compliances), the result shape and the errors live
in :mod:`threepart` and are re-exported here for convenience.

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
solve_normal_batch  -- the same for arrays of load cases (vectorised)
lift_off            -- admissible lever arms s_min < s < s_max for a load P
P_min               -- least load: both joins touched (convex centre), separation (concave)
solve_partial_slip  -- Ciavarella-Jaeger stick zone [-(d+e), d-e] and shear q(x)
fretting_cycle      -- Q: 0 -> Q_max -> -Q_max -> Q_max by Masing's rule: stick zones, delta, energy per cycle
steady_state        -- periodic steady state of an in-phase cycle between two (P, s, Q, sigma_bulk):
                       permanent stick zone, energy per cycle, shakedown (docs/STEADY_STATE.md)
wear_limit          -- the worn limit of a fretting cycle: singular pressure on the stick zone, worn depth (docs/WEAR.md)

Errors (from :mod:`threepart.errors`)
------
LiftOffError, FullSlidingError, StickZoneError, SeparationError -- ValueError subclasses
StickSeparationError -- a StickZoneError: a stick zone on a concave centre would break |q| <= f p
OneSidedSlipError   -- a StickZoneError: a cycle's permanent stick zone would reach one contact edge only
CycleSlipReversalError -- a SlipReversalError: a point would slip backwards in a cycle's steady state
ArcExtentError, SlopeLimitError -- a solved contact past an arc or past validate.SLOPE_LIMIT
NoConvergenceError  -- a root did not close (never expected on admissible input)
"""
from __future__ import annotations

from threepart.errors import (ArcExtentError, CycleSlipReversalError, FullSlidingError, LiftOffError,
                              NoConvergenceError, OneSidedSlipError, SeparationError, SlopeLimitError,
                              StickSeparationError, StickZoneError)
from threepart.problem.material import compliance, rigid_punch, similar_pair
from threepart.problem.punch import Punch
from threepart.results import NormalResult, Peak, SlipResult

from . import formulas, special
from .normal import (LiftOff, NormalBatch, NormalSolution, P_min, lift_off, solve_normal,
                     solve_normal_batch)
from .slip import SlipSolution, solve_partial_slip
from .fretting import FrettingSolution, fretting_cycle
from .steady import SteadySolution, steady_state

__all__ = [
    "Punch", "NormalResult", "SlipResult", "Peak",
    "compliance", "similar_pair", "rigid_punch",
    "formulas", "special",
    "solve_normal", "solve_normal_batch", "lift_off", "P_min", "solve_partial_slip", "fretting_cycle",
    "steady_state", "SteadySolution", "CycleSlipReversalError", "OneSidedSlipError",
    "NormalSolution", "NormalBatch", "LiftOff", "SlipSolution", "FrettingSolution",
    "LiftOffError", "FullSlidingError", "StickZoneError", "SeparationError", "NoConvergenceError",
    "StickSeparationError", "ArcExtentError", "SlopeLimitError",
]

from . import method as _method  # registers this solver in threepart.registry

# the worn limit of partial-slip fretting (issue 39, docs/WEAR.md)
from .wear import STICK_RULES, WearLimit, wear_limit  # noqa: E402
__all__ += ["wear_limit", "WearLimit", "STICK_RULES"]

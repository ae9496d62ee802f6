"""Independent Gauss–Chebyshev singular-integral-equation solver (normal and partial slip).

Solves paper eq. (integral_equation) numerically, bounded at both ends; imports
only the shared problem, result shape and errors from :mod:`threepart`; it never loads the
closed form.

Solvers
-------
solve_normal        -- contact [-a, c], tilt and pressure under load control ("free"/"suppressed" tilt),
                       also past lift-off and on one corner; a contact in two zones: SeparationError
lift_off            -- lever arms at which a contact edge reaches a join x = ±b (closed form's range)
steady_state        -- periodic steady state of an in-phase cycle between two (P, s, Q, sigma_bulk), also
                       where the permanent stick zone ends on the central segment (docs/STEADY_STATE.md)
solve_partial_slip  -- stick zone (d, e) and shear q(x) by Ciavarella–Jäger, from the discretised equations,
                       also where the stick zone ends on the central segment
fretting_cycle      -- Q: 0 -> Q_max -> -Q_max -> Q_max by Masing's rule on those stick zones: delta, energy
load_history        -- any history of (P, s, Q, sigma_bulk) states, marched with the memory of slip on a
                       log-kernel element grid: stick intervals, shear, slip, energy per cycle
SieNormalResult     -- NormalResult with n, scheme and the interpolating pressure
SieSlipResult       -- SlipResult with n, scheme, corrective pressure and shear
SieFrettingResult   -- FrettingResult with n, scheme; shear, slip and slip amplitude at any Q of a branch
SieSteadyResult     -- SteadyStateResult with n, scheme and the corrective pressure p*
WornProfile         -- the punch less a worn depth w(x) (linear or pchip knots; from_csv reads (x, h))
solve_profile       -- normal contact on a worn profile, bounded ends or a given contact with unbounded ends
ProfileNormalResult -- SieNormalResult with its profile
solve_profile_slip  -- partial slip on a worn profile
profile_fretting_cycle -- the fretting cycle on a worn profile (the wear march: threepart.wear, sie.wear)
NoConvergenceError  -- raised when a root iteration fails (never a silent NaN)

Discretisation
--------------
gauss_chebyshev     -- bounded–bounded Gauss–Chebyshev nodes, weights and collocation points
cauchy_matrix       -- discrete Cauchy operator on those nodes
slope_coefficients  -- exact, segment-wise Chebyshev projection of v'(x) (kink-aware scheme)
SCHEMES             -- "plain" collocation and "projected" (kink-aware) schemes

Convergence
-----------
convergence_study   -- errors against a reference over a list of n, fitted order, Richardson estimate
                    (the one study shape, threepart.convergence.Study)
pressure_by_quadrature -- independent pointwise reference (adaptive quadrature of the inversion formula)

The fitted order and the Richardson step are :mod:`threepart.convergence`'s; the
cases and tolerances of the SIE tests are :mod:`threepart.problem.catalogue`'s (suite
``"sie"``) and :mod:`threepart.tolerances`'.
"""
from __future__ import annotations

from .convergence import convergence_study
from .normal import SieNormalResult, lift_off, solve_normal
from .projection import slope_coefficients
from .quadrature import cauchy_matrix, gauss_chebyshev
from .reference import pressure_by_quadrature
from threepart.errors import NoConvergenceError
from .schemes import SCHEMES
from .slip import SieSlipResult, solve_partial_slip
from .steady import SieSteadyResult, steady_state
from .fretting import SieFrettingResult, fretting_cycle
from .history import load_history
from .profile import ProfileNormalResult, WornProfile, solve_profile
from .wear import profile_fretting_cycle, solve_profile_slip

__all__ = [
    "solve_normal", "solve_partial_slip", "lift_off", "SieNormalResult", "SieSlipResult", "NoConvergenceError",
    "fretting_cycle", "SieFrettingResult", "load_history",
    "gauss_chebyshev", "cauchy_matrix", "slope_coefficients", "SCHEMES",
    "convergence_study", "pressure_by_quadrature",
]
__all__ += ["steady_state", "SieSteadyResult"]
__all__ += ["WornProfile", "solve_profile", "ProfileNormalResult", "solve_profile_slip",
            "profile_fretting_cycle"]

from . import method as _method  # registers this solver in threepart.registry

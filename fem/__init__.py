"""Independent finite-element models: a rigid punch on a block, and two similar bodies with friction.

Solvers
-------
solve_normal        -- load-controlled normal contact (tilt "free" or "suppressed") on a gmsh mesh
FemResult           -- the shared result shape plus delta, nodal pressures and the stress field
solve_partial_slip  -- two similar elastic bodies, P at s then Q (and a bulk stress) in steps, Coulomb friction
fretting_cycle      -- the same model through Q: 0 -> Q_max -> -Q_max -> Q_max (energy per cycle)
load_history        -- the same model through any history of (P, s, Q, sigma_bulk) states, meshed once,
                       with the memory of slip (stick intervals, shear, slip, energy per cycle)
steady_state        -- the periodic steady state of an in-phase cycle between two states, marched until it repeats
FemSlipResult, FemFrettingResult, FemSteadyResult -- their shared result shapes, with the per-step history
solve_finite        -- a punch of real shape (exact arcs, flanks, height H) on a finite block
solve_finite_slip   -- the same punch and block, P at s then Q in steps, Coulomb friction (two-body model)
NoConvergenceError  -- the contact active-set iteration did not converge
ContactZoneError    -- the contact reached the end of the candidate zone of the mesh
SeparationError     -- the contact separates into two zones (from threepart.errors)
MeshResolutionError -- a contact end too close to a join for the mesh, after automatic refinement
locate_contact      -- coarse trial and locate solves that place the zone and the ends (no closed form used)

Every solver checks all of its input before any meshing or numerics (a wrong type is a
``TypeError``, a value out of range a ``ValueError`` naming the argument and the limit),
raises only threepart's errors (a foreign numerical failure becomes ``NoConvergenceError``),
checks its contact against ``threepart.problem.validate.check_contact``, and with ``progress=True``
(default: when stderr is a terminal) prints one line per stage to stderr.

Building blocks
---------------
MeshPreset, PRESETS -- mesh density relative to the contact width ("quick", "default", "fine")
Substrate           -- a scikit-fem triangle mesh with boundaries by physical-group name
read_substrate      -- read a gmsh ``.msh`` through meshio
make_substrate      -- mesh a SubstrateSpec with gmsh and read it back
make_punch          -- mesh a PunchSpec (a finite punch body) with gmsh and read it back, once per spec
SurfaceCompliance   -- elastic body condensed onto the candidate contact nodes
condense            -- P2 plane-strain stiffness, condensed by one ordered factorisation
choose_backend, backends -- CHOLMOD (scikit-sparse, the `fast` extra) or SciPy's SuperLU
solve_contact       -- primal-dual active set with translation and tilt as unknowns
interface, mirror   -- two bodies condensed onto matched interface nodes; a body's mirror image
Interface           -- their flexibility blocks on the matched nodes
bulk_field          -- the substrate's displacement under a unit tension on its end faces
tangential, Step    -- one load step's Coulomb stick/slip states (primal-dual active set)
StressField         -- stresses at arbitrary points from the FE field (L2 projection onto P2)

Export
------
Fields              -- vertex displacement and cell stress of a solution (``solve_normal(fields=True)``)
write_fields        -- write Fields to VTU or XDMF (ParaView) through meshio; never over a file unasked
to_meshio           -- Fields as a meshio.Mesh

Studies
-------
convergence_study   -- >= 4 mesh levels: a threepart.convergence.Study of a, c, alpha and the peaks
domain_study        -- the same quantities as the block size L grows (a Study in L)
"""
from __future__ import annotations

from threepart.errors import (ContactZoneError, MeshResolutionError, NoConvergenceError,
                              SeparationError)

from .contact import ContactSolution, solve_contact
from .elasticity import SurfaceCompliance, backends, choose_backend, condense
from .export import Fields, to_meshio, write_fields
from .coulomb import Step, tangential
from .friction import FemFrettingResult, FemSlipResult, fretting_cycle, solve_partial_slip
from .history import load_history
from .interface import Interface, bulk_field, interface, mirror
from .recovery import StressField
from .finite import solve_finite
from .finite_slip import solve_finite_slip
from .mesh import PRESETS, MeshPreset, Substrate, make_punch, make_substrate, read_substrate
from .solve import FemResult, locate_contact, solve_normal
from .steady import FemSteadyResult, steady_state
from .studies import convergence_study, domain_study

__all__ = ["solve_normal", "FemResult", "solve_partial_slip", "fretting_cycle", "FemSlipResult", "load_history",
           "steady_state", "FemSteadyResult",
           "FemFrettingResult", "solve_finite", "solve_finite_slip", "Interface", "interface", "mirror", "bulk_field", "Step", "tangential",
           "StressField", "NoConvergenceError", "ContactZoneError", "SeparationError",
           "MeshResolutionError", "locate_contact", "MeshPreset", "PRESETS", "Substrate", "read_substrate",
           "make_substrate", "make_punch", "SurfaceCompliance", "condense", "choose_backend", "backends",
           "solve_contact", "ContactSolution", "Fields", "write_fields", "to_meshio",
           "convergence_study", "domain_study"]

from . import method as _method  # registers this solver in threepart.registry
from . import wear as _wear  # registers its wear march in threepart.fretting_wear

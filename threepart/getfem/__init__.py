"""GetFEM as an outside referee of friction: scripts, runs and the reader of what they write.

threepart uses GetFEM 5.4 (Debian's ``python3-getfem``, usually the system
interpreter's, not threepart's) as the second outside finite-element code
(issue 38): two similar elastic bodies in plane strain, P2 triangles, the
half-plane theory's gap (the punch profile of eq. 2) along a fixed normal, and
Coulomb friction by GetFEM's weak-form term ``Coulomb_friction_coupled_projection``.
threepart writes the script (:mod:`.script`), runs it with the interpreter that
imports ``getfem`` (:mod:`.run`) and reads its sidecar (:mod:`.read`, the one
reader of it; ``threepart.readers`` registers it as ``.getfem.json``, and the
VTU files it writes beside are read by ``threepart.readers.meshfile``). The
core (``threepart/*.py``) never imports it. docs/GETFEM.md has the figures.

Scripts (threepart.getfem.script)
---------------------------------
JobSettings  -- mesh (elements across W), block, augmentation, Newton's limits, shear steps
write_script -- the script of partial slip (``Q``, ``sigma_bulk``), a fretting cycle (``Q_max``) or a load
                history (``history``): header, PARAMS, body
header       -- the header alone (what the script models, its conventions, what it writes)
legs         -- the load path: 0 -> Q, 0 -> Q_max -> -Q_max -> Q_max, or a history's states in turn
gap_text     -- the profile v(x) of eq. 2 in GetFEM's weak-form language
params_of    -- the PARAMS of a script's text, read without running it
BODY         -- the script's body

Running (threepart.getfem.run)
------------------------------
getfem_python    -- the interpreter that imports getfem (``THREEPART_GETFEM_PYTHON``, ``python3``, /usr/bin/python3)
getfem_available -- whether one does
run_getfem       -- run a script in a folder (one thread); the path of its sidecar
GetfemError      -- the script ran but failed (the step Newton did not converge at), or wrote nothing
GetfemMissing    -- no interpreter imports getfem

Reading (threepart.getfem.read)
-------------------------------
read_run     -- a run's sidecar ``name.getfem.json``: every state's loads, cap displacement, fields
GetfemRun    -- what read_run returns; State -- one recorded state
loop_energy  -- the energy per cycle: the area of the Q-delta loop (Simpson's rule per branch)
slip_ends    -- the stick zone's ends from the slip field (slip^(2/3) extrapolated to zero)
SLIP_NOISE   -- the slip below which a node sticks, of the largest
last_cycle   -- the last complete cycle of recorded states (any code's)
friction_work -- their friction work, Σ ∫ (q_k + q_k+1)/2 (slip_k+1 - slip_k) dx
slip_amplitude -- half the range of each node's slip over recorded states

One call per problem (threepart.getfem.solve)
---------------------------------------------
partial_slip   -- write, run and read partial slip (with a bulk stress): a GetfemSlip (x, p, q, slip, info)
fretting_cycle -- the same for a fretting cycle: a GetfemCycle (states, energy, info)
load_history   -- the same for a load history (a flight cycle: [state0, state1, state0, state1]): a GetfemCycle
"""
from __future__ import annotations

from .read import (SLIP_NOISE, GetfemRun, State, friction_work, last_cycle, loop_energy, read_run, slip_amplitude,
                   slip_ends)
from .run import GetfemError, GetfemMissing, getfem_available, getfem_python, run_getfem
from .script import BODY, JobSettings, gap_text, header, legs, params_of, write_script
from .solve import GetfemCycle, GetfemSlip, fretting_cycle, load_history, partial_slip

__all__ = ["JobSettings", "write_script", "header", "legs", "gap_text", "params_of", "BODY",
           "getfem_python", "getfem_available", "run_getfem", "GetfemError", "GetfemMissing",
           "read_run", "GetfemRun", "State", "loop_energy", "slip_ends", "SLIP_NOISE",
           "partial_slip", "fretting_cycle", "load_history", "GetfemSlip", "GetfemCycle", "last_cycle",
           "friction_work", "slip_amplitude"]

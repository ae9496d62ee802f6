"""One result shape: what every method returns, checked once when built.

Every solver returns a :class:`NormalResult` (partial slip a :class:`SlipResult`,
a fretting cycle a :class:`FrettingResult`), a load cycle a
:class:`SteadyStateResult` or :class:`HistoryResult`, so that the reports never
special-case a method.

Modules
-------
contact     -- the normal result, its diagnostics and peaks; what every result shares (Answer)
slip        -- partial slip and the fretting cycle
cycles      -- the steady state of a cycle, a marched load history, the marched steady state
answer      -- the check of every answer: p >= 0, |q| <= f p
edges       -- the edge multipliers K_N, K_T every result inherits (``edges()``), the slip zone
fields      -- the peak and the edges' K_N of a nodal field, the stick zone's ends of nodal tractions

Public names
------------
NormalResult        -- a, c, alpha, P, s, pressure(x), peaks(): the shape every solver returns
SlipResult          -- adds Q, f, d, e, stick_zone and shear(x)
FrettingResult      -- one fretting cycle (Masing), its branches' shear and slip
MasingCycle         -- the loading and unloading branches of a fretting cycle
Peak                -- a pressure maximum p at x
Diagnostics         -- a method's discretisation and iteration record
BRANCHES            -- the fretting cycle's branches
SteadyStateResult   -- the periodic steady state of an in-phase cycle
HistoryResult       -- a load history marched with the memory of slip
MarchedSteadyResult -- the steady state as the last cycle of a marched history
"""
from __future__ import annotations

from .contact import Diagnostics, NormalResult, Peak
from .slip import BRANCHES, FrettingResult, MasingCycle, SlipResult
from .cycles import HistoryResult, MarchedSteadyResult, SteadyStateResult

__all__ = ["NormalResult", "SlipResult", "FrettingResult", "MasingCycle", "Peak", "Diagnostics", "BRANCHES",
           "SteadyStateResult", "HistoryResult", "MarchedSteadyResult"]

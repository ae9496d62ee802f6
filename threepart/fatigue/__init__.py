"""Fretting-fatigue parameters from the stress history of a cycle, for any method (docs/FATIGUE.md).

Modules
-------
history         -- the stresses of a cycle's states at points (x, z): :class:`History`
functions       -- the parameters on a history: von Mises range, SWT, Findley, Ruiz; the hot spot
table           -- the table of parameters that :func:`fatigue`, the command line and the report
                    loop over (a new parameter is one row), Crossland's parameter

Public names
------------
fatigue             -- every parameter of the table on points (x, z) of a cycle
Fatigue             -- its record: each parameter's field and hot spot
stress_history      -- the stresses of a cycle's states at points (x, z)
History             -- stacked σxx, σzz, σxz of several states at the same points
von_mises_range     -- max over pairs of states of the von Mises stress of the difference
swt                 -- Smith–Watson–Topper on the critical plane
findley             -- Findley on the critical plane, τa + k σn,max
ruiz                -- Ruiz's FDP (τ δ) and FFDP (σxx τ δ) at the surface
crossland           -- Crossland's parameter
HotSpot             -- where a parameter is largest, how much, and on which plane
hot_spot            -- the one hot-spot rule: the first point within a tie of the largest value
Parameter, Ruiz     -- a parameter's field and hot spot; Ruiz's two
critical_plane      -- max over plane angles of a function of (σn, τ) histories
findley_k           -- Findley's constant checked
K_FINDLEY           -- the default Findley constant
crossland_kappa     -- Crossland's constant checked
KAPPA_CROSSLAND     -- the default Crossland constant

The table (:mod:`threepart.fatigue.table`)
---------
FatigueParameter    -- a row: name, labels, unit, function, critical plane or not, constants
register_parameter  -- add (or replace) a row: a new parameter is one row
parameters          -- the rows, in registration order
parameter           -- the row of a name
reported            -- the names the verification report tabulates
grid, GRID          -- the default points of a cycle's fatigue fields under a contact
"""
from __future__ import annotations

from .functions import (K_FINDLEY, HotSpot, Parameter, Ruiz, critical_plane, findley, findley_k, hot_spot, ruiz,
                        swt, von_mises_range)
from .history import History, stress_history
from .table import (GRID, KAPPA_CROSSLAND, Fatigue, FatigueParameter, crossland, crossland_kappa, fatigue, grid,
                    parameter, parameters, register_parameter, reported)

__all__ = ["fatigue", "Fatigue", "stress_history", "History", "von_mises_range", "swt", "findley", "ruiz",
           "crossland", "HotSpot", "hot_spot", "Parameter", "Ruiz", "critical_plane", "findley_k", "K_FINDLEY",
           "FatigueParameter", "register_parameter", "parameters", "parameter", "reported", "grid", "GRID",
           "crossland_kappa", "KAPPA_CROSSLAND"]

"""The ``threepart`` command line: one module per sub-command, above every other layer.

``threepart --help`` prints :data:`threepart.cli._main.HELP`; ``threepart`` and
``python -m threepart`` enter through :func:`threepart.__main__.main`, which
calls :func:`main`.

Sub-command modules
-------------------
solve        -- ``solve`` and ``slip``: the normal and the partial-slip problem (threepart.solve)
cases        -- ``cases``: the catalogue's cases with their kinds and descriptions, for ``--case NAME``
verify       -- ``verify``: closed form against SIE and FEM, the tolerance report
figures      -- ``figures``: the paper's result figures, with the SIE solution as markers
map          -- ``map``: the finite-body validity map, on dask.distributed
export_refs  -- ``export-refs``: the catalogue's reference solutions as a versioned dataset
fatigue      -- ``fatigue``: fretting-fatigue parameters of a fretting or flight cycle (threepart.fretting)
cycle        -- ``cycle``: the steady state of an in-phase flight cycle, or a load history
match        -- ``match``: the Hertzian pad test that reproduces one edge of a flank
deck         -- ``deck``: a ready-to-run CalculiX input deck
compare      -- ``compare``: judge another code's contact pressure against threepart

Each has ``add_parser(subparsers)``, which adds its sub-command(s) and sets
``func``, and ``run(args) -> int``, the exit status. Adding a sub-command is one
module and one entry in :data:`threepart.cli._main.SUBCOMMANDS` (and its name in
:data:`threepart.__main__.COMMANDS`, which names a command before anything loads).

Shared modules
--------------
_args        -- the parser, number options (real_arg, the ``--s -1e-3`` joining), option groups, ``--case``
_output      -- printing (text and ``--json``), CSV and VTU writers, the units
_main        -- build_parser (one loop over the sub-command modules), main: exit status, one-line errors

Names
-----
main             -- run the command line; the exit status
build_parser     -- the parser of every sub-command
real_arg         -- the type of every number option: a float, or a one-line refusal
UsageError       -- a command-line usage error, already formatted as one line
NUMERIC_OPTIONS  -- the options that take a number (``--s -1e-3`` is read as ``--s=-1e-3``)
LIST_OPTIONS     -- the options that take a comma-separated list of numbers
UNITS            -- the unit of each printed quantity (threepart.problem.units)
COMMANDS         -- the sub-commands' names (threepart.__main__)
"""
from __future__ import annotations

from threepart.__main__ import COMMANDS
from threepart.problem.units import UNITS

from ._args import LIST_OPTIONS, NUMERIC_OPTIONS, UsageError, real_arg
from ._main import build_parser, main

__all__ = ["main", "build_parser", "real_arg", "UNITS", "NUMERIC_OPTIONS", "LIST_OPTIONS", "UsageError",
           "COMMANDS"]

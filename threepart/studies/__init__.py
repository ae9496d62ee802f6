"""Studies above the methods: they solve through :func:`threepart.solve` and compare.

Modules
-------
matching    -- the matching pad test: the cylinder-on-flat test that reproduces one edge of a flank

Public names
------------
match       -- the pad test that reproduces one edge of a flank (docs/EDGES.md §6)
Match       -- its record: the pad, its loads and result, how well its edge field agrees
pad_loads   -- ``(R, P, Q)`` of the Hertzian pad whose edge has given K_N and K_T (E9)
"""
from __future__ import annotations

from .matching import Match, match, pad_loads

__all__ = ["match", "Match", "pad_loads"]

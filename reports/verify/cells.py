"""The cells of the report's tables: numbers as printed, with their units.

fmt        -- a short numeric format for tables
with_unit  -- a number with its unit, if it has one
physical   -- whether a case has a material (its numbers carry units)
unit_of    -- the unit label of a quantity for a case (empty for a nondimensional case)
head_unit  -- a table head ``name [unit]``
"""
from __future__ import annotations

import math
from typing import Any

from threepart.problem.units import UNITS

__all__ = ["fmt", "with_unit", "physical", "unit_of", "head_unit"]


def fmt(v: Any) -> str:
    """Short numeric format for tables."""
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        if not math.isfinite(v):
            return str(v)
        return f"{v:.3e}" if v != 0 and (abs(v) < 1e-3 or abs(v) >= 1e5) else f"{v:.6g}"
    return str(v)


def with_unit(v: Any, unit: str) -> str:
    """``v`` formatted (:func:`fmt`) with its unit, if it has one."""
    return fmt(v) if v is None or not unit else f"{fmt(v)} {unit}"


def physical(case: dict[str, Any]) -> bool:
    """Whether a case has a material, so its numbers carry units (mm, N/mm, MPa)."""
    return case.get("E") is not None


def unit_of(case: dict[str, Any], quantity: str) -> str:
    """The unit label of ``quantity`` for ``case`` (empty for a nondimensional case)."""
    return UNITS[quantity] if physical(case) else ""


def head_unit(name: str, unit: str) -> str:
    """A table head: ``name [unit]``, or ``name`` without a unit."""
    return f"{name} [{unit}]" if unit else name

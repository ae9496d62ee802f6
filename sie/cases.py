"""The catalogue of load cases on which :mod:`sie` is checked against the closed form.

Inputs only (no solution): each case exposes its numbers, and the tests and
``benchmarks/bench_sie.py`` import them. ``near_lift_off`` puts the load at
0.999 of the lift-off lever arm ``s_max = 1.056852585741995`` of case A for
``P = A = 1`` (where the left edge reaches the join, ``a -> b``); a test checks
that number against :func:`closedform.lift_off`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from threepart.punch import Punch

__all__ = ["Case", "CASES", "SLIP_LOADS"]


@dataclass(frozen=True)
class Case:
    """One normal load case: ``solve_normal(punch, P, s, A=A, tilt=tilt)``."""

    punch: Punch
    P: float
    s: float = 0.0
    A: float = 1.0
    tilt: str = "free"


S_MAX_A = 1.056852585741995  # lift-off lever arm of CASES["A"] (closedform.lift_off, P = A = 1)

CASES: dict[str, Case] = {
    "A": Case(Punch(1.0, 2.0, 0.4), P=1.0, s=0.1),
    "B": Case(Punch(1.0, 1.5, 0.3, R=-4.0), P=2.0, s=-0.05),
    "C": Case(Punch(1.0, 3.0, 0.0), P=1.0, s=0.2),
    "general": Case(Punch(1.0, 2.0, 0.3, R=5.0), P=1.0, s=0.05),
    "Hertz": Case(Punch(2.0, 2.0, 0.0), P=3.0, s=0.3, A=1.5),
    "suppressed": Case(Punch(1.0, 2.0, 0.4), P=1.0, tilt="suppressed"),
    "suppressed_general": Case(Punch(1.0, 2.5, 0.3, R=3.0), P=1.0, tilt="suppressed"),
    "near_lift_off": Case(Punch(1.0, 2.0, 0.4), P=1.0, s=0.999 * S_MAX_A),
    "flat_symmetric": Case(Punch(1.0, 1.0, 0.5, R=math.inf), P=1.0),
}

#: Shear loads ``Q/(f P)`` and friction ``f`` for the partial-slip comparison;
#: cases whose stick zone would not contain ``[-b, b]`` are expected to raise.
SLIP_LOADS: tuple[tuple[float, float], ...] = ((0.2, 0.7), (-0.4, 0.7), (0.6, 0.5))

"""Closed-form solution of the tilted three-part half-plane contact (Andresen, Hills & Vázquez).

Geometry and shared result shape
--------------------------------
Punch          -- three-part punch (R1, R2, b, R), profile v(x) and slope v'(x), eq. (2)
NormalResult   -- result shape shared by all solvers: a, c, alpha, P, s, pressure(x)
SlipResult     -- partial-slip result shape: adds d, e, shear(x)
"""
from __future__ import annotations

from .geometry import Punch
from .results import NormalResult, Peak, SlipResult

__all__ = ["Punch", "NormalResult", "SlipResult", "Peak"]

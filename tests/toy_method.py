"""A fourth method in one adapter module: what a newcomer writes to add a solver.

The toy answers one problem, Hertz's (a punch with ``b = 0`` and ``R1 = R2``,
centrally loaded), from its textbook formulas: ``a = c = sqrt(4 P R / (pi E*))``
and ``p(x) = (2P / (pi a)) sqrt(1 - x^2/a^2)`` (Johnson, Contact Mechanics,
eq. 4.45), where ``A`` of eq. (4) is ``2/E*``, so ``a^2 = 2 P R A / pi``.
Everything else it refuses by name. Importing this module registers it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from threepart.problem.punch import Punch
from threepart.registry import Method, register
from threepart.results import NormalResult


@dataclass(frozen=True)
class ToyResult(NormalResult):
    def pressure(self, x):
        x = np.asarray(x, dtype=float)
        p0 = 2 * self.P / (math.pi * self.a)
        return p0 * np.sqrt(np.clip(1 - (x / self.a) ** 2, 0.0, None))


def _normal(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
            nu: float | None = None, terms: int = 1) -> NormalResult:
    if punch.b != 0 or punch.R1 != punch.R2 or s != 0:
        raise ValueError("the toy method solves only Hertz: b = 0, R1 = R2, s = 0")
    a = math.sqrt(2 * P * punch.R1 * A / math.pi)
    return ToyResult(punch=punch, A=A, a=a, c=a, alpha=0.0, P=P, s=0.0, tilt=tilt, method="toy")


#: judged against the reference by the SIE's limits: it is exact where it answers; its label and
#: plot style reach the report's tables and plots with no edit to ``reports/``
METHOD = register(Method("toy", _normal, options=("terms",), comparison=lambda options: "sie",
                         label="toy Hertz", style={"color": "tab:purple", "ls": ":", "lw": 2.0}))

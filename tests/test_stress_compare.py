"""The stress figures of the comparison (``sxx_surface``, ``sxx_peak``, ``stress_depth``) can bite.

Each perturbs one figure of a correct closed-form partial-slip result's stress
field by just over its tolerance (it must fail) and just under (everything must
pass), for every comparison of the table.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pytest

from threepart import Punch, closedform
from threepart.reports.compare import compare, stress_figures
from threepart.problem.material import NU
from threepart.stress import Stress
from threepart.tolerances import COMPARISONS, STRESS_QUANTITIES, tolerance

from .fakes import Stored

#: caseA_moment's punch, nondimensional (A = 1), at Q/fP = 0.4
NORMAL = closedform.solve_normal(Punch(R1=1.0, R2=0.5, b=0.1), 0.01, 0.02, A=1.0)
SLIP = closedform.solve_partial_slip(NORMAL, 0.4 * 0.5 * 0.01, 0.5)


@dataclass(frozen=True)
class Shifted:
    """``base`` with one figure of its stress field moved by ``size`` (normalised as in the table)."""

    base: Any
    quantity: str
    size: float

    def __getattr__(self, name: str) -> Any:
        return getattr(self.base, name)

    def stress(self, x: Any, z: Any, *, nu: float = NU) -> Stress:
        s = self.base.stress(x, z, nu=nu)
        x, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(z, float))
        n = self.base.normal
        W, p_max = n.a + n.c, max(pk.p for pk in n.peaks())
        surface = z == 0
        if self.quantity == "sxx_surface":     # a narrow bump in the middle, where σxx is compressive
            bump = np.exp(-(((x - 0.5 * (n.c - n.a)) / (0.02 * W)) ** 2))
            return replace(s, sxx=s.sxx + surface * self.size * p_max * bump)
        if self.quantity == "sxx_peak":        # the surface σxx scaled about its own tension peak
            top = float(np.abs(s.sxx[surface]).max()) if surface.any() else 0.0
            return replace(s, sxx=np.where(surface & (s.sxx > 0), s.sxx + self.size * top, s.sxx))
        if self.quantity == "stress_depth":
            return replace(s, szz=s.szz + (~surface) * self.size * p_max)
        raise AssertionError(self.quantity)


#: SLIP with its stress fields kept: every comparison below evaluates them at the same points
STORED = Stored(SLIP)


def test_a_correct_result_has_zero_stress_errors():
    assert all(v[2] == 0.0 for v in stress_figures(SLIP, SLIP).values())


@pytest.mark.parametrize("comparison", COMPARISONS)
@pytest.mark.parametrize("quantity", STRESS_QUANTITIES)
def test_a_perturbed_stress_fails_its_tolerance(comparison, quantity):
    limit = tolerance(comparison, quantity).limit
    bad = [c.quantity for c in compare(STORED, Shifted(STORED, quantity, 3 * limit), comparison)
           if not c.passed]
    assert quantity in bad, f"{quantity} moved by 3x its limit {limit:g}: failed {bad}"
    if quantity != "sxx_peak":   # raising the tension peak also moves the surface σxx there
        assert bad == [quantity]
    ok = compare(STORED, Shifted(STORED, quantity, 0.3 * limit), comparison)
    assert all(c.passed for c in ok), [c.quantity for c in ok if not c.passed]


#: how close to a contact end the sampled tension peak must lie, as a fraction of W: the peak
#: is at the end itself, and the sampled line steps 1/2000 of its length
AT_THE_END = 0.01


def test_the_trailing_edge_is_where_the_surface_tension_peaks():
    """For Q > 0 on the substrate, ``σxx = -p + (2/π) PV∫ q/(t - x)`` peaks at the left end ``x = -a``."""
    x = np.linspace(-NORMAL.a - 0.2, NORMAL.c + 0.2, 2001)
    x = x[np.min(np.abs(x[:, None] - [-NORMAL.a, NORMAL.c]), axis=1) > 1e-4]
    s = SLIP.stress(x, 0.0)
    assert abs(x[np.argmax(s.sxx)] + NORMAL.a) < AT_THE_END * (NORMAL.a + NORMAL.c)
    flipped = closedform.solve_partial_slip(NORMAL, -SLIP.Q, SLIP.f).stress(x, 0.0)
    assert abs(x[np.argmax(flipped.sxx)] - NORMAL.c) < AT_THE_END * (NORMAL.a + NORMAL.c)

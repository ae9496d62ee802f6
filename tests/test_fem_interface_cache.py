"""Two bodies condensed onto their interface when one comes from the run's memory and one is condensed now.

Reference: the same interface built with both bodies condensed afresh (their compliances are the
same matrices; only the timings' keys differ: a cached body's has ``cache``, a fresh one's not).
A map point's finite-body slip hit a KeyError here (threepart map --quick, 2026-11-29).
"""
from __future__ import annotations

import numpy as np

from threepart.fem import elasticity
from threepart.fem.interface import interface, mirror
from threepart.fem.mesh import make_substrate
from threepart.meshes import SubstrateSpec

SPEC = SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.1, L=4.0, growth=0.6, breakpoints=(-0.25, 0.25))
E, NU = 210e3, 0.3


def test_a_cached_body_and_a_fresh_one_make_one_interface():
    lower = make_substrate(SPEC)
    upper = mirror(lower)
    elasticity.condense(lower, E, NU, ("u^1", "u^2"))          # the lower body now in the run's memory
    itf = interface(lower, upper, E, NU)
    assert "cache" in itf.timings and all(np.isfinite(v) for v in itf.timings.values())
    elasticity.forget()
    fresh = interface(lower, upper, E, NU)
    for name in ("C_nn", "C_nt", "C_tn", "C_tt"):
        assert np.array_equal(getattr(itf, name), getattr(fresh, name)), name

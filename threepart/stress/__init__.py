"""Stresses in the elastic half-plane under the contact, from any method's tractions.

Modules
-------
flamant     -- Flamant's kernels integrated over the tractions at any points (docs/STRESS.md)
grid        -- the same integrals where the points form a grid, per column of depths

Public names
------------
Stress              -- σxx, σzz, σxz on a grid, with principal, von Mises and Tresca stresses
stress              -- the stress at points (x, z >= 0) from p(x), q(x) and a bulk stress
hilbert             -- (1/π) PV∫ f(t)/(t - x) dt over the contact, the surface's Hilbert transform
flamant_normal      -- Flamant's kernels of a normal line load (Johnson eq. 2.15)
flamant_tangential  -- Flamant's kernels of a tangential line load (Johnson eq. 2.19)
kernel_primitives   -- the kernels' antiderivatives in s = x - t, for the singular subtraction
RULE                -- the composite Gauss–Legendre rule of the remainder
"""
from __future__ import annotations

from .flamant import RULE, Stress, flamant_normal, flamant_tangential, hilbert, kernel_primitives, stress

__all__ = ["Stress", "stress", "hilbert", "flamant_normal", "flamant_tangential", "kernel_primitives", "RULE"]

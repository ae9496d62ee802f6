"""Stresses in the elastic half-plane under the contact, from any method's tractions.

Modules
-------
flamant     -- Flamant's kernels integrated over the tractions at any points (docs/STRESS.md)
grid        -- the same integrals where the points form a grid, per column of depths

Public names
------------
:mod:`.flamant`'s, re-exported here (its docstring says what each is): ``Stress``, ``stress``,
``hilbert``, ``flamant_normal``, ``flamant_tangential``, ``kernel_primitives``, ``RULE``.
"""
from __future__ import annotations

from .flamant import RULE, Stress, flamant_normal, flamant_tangential, hilbert, kernel_primitives, stress

__all__ = ["Stress", "stress", "hilbert", "flamant_normal", "flamant_tangential", "kernel_primitives", "RULE"]

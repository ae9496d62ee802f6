"""The one table of tolerances for checking the SIE solver, each with its reason.

Agreement with the closed form is measured with the ``"projected"`` scheme at
its default ``n``; the plain-collocation entries bound its observed orders and
error levels. Tests and ``benchmarks/bench_sie.py`` read this table only.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Tolerance", "TOLERANCES"]


@dataclass(frozen=True)
class Tolerance:
    """A tolerance ``value`` and the one-line ``reason`` for it."""

    value: float
    reason: str


TOLERANCES: dict[str, Tolerance] = {
    "ends_rel": Tolerance(1e-10, "issue 3 target; projected a, c carry no discretisation error, Newton stops at 1e-14"),
    "ends_width": Tolerance(1e-12, "issue 3 target for a and c as a fraction of the width a + c"),
    "alpha": Tolerance(1e-10, "issue 3 target, relative to max(|alpha|, (a+c)/min(R1,R2)) since alpha may be 0"),
    "s": Tolerance(1e-10, "issue 3 target, relative to max(|s|, a+c) since s may be 0"),
    "pressure_peak": Tolerance(1e-6, "issue 3 target for max|p_sie - p_cf| over the contact, as a fraction of the peak"),
    "stick_rel": Tolerance(1e-8, "issue 3 target for d and e, relative to d"),
    "hertz": Tolerance(1e-13, "Hertz slope is linear: both schemes are exact for any n, up to rounding"),
    "reference_peak": Tolerance(1e-6, "projected pressure vs the adaptive-quadrature inversion integral (n=1024)"),
    "plain_load_order": Tolerance(1.4, "lowest fitted order of the plain load error, n=24..768: theory 2, kink wobble gives 1.5-2.2"),
    "plain_load_level": Tolerance(4e-6, "cap on the plain relative load error for n >= 450 (measured <= 1.5e-6)"),
    "plain_ends_order": Tolerance(1.8, "lowest fitted order of the plain error in a (measured 2.0-2.3)"),
    "plain_pressure_order": Tolerance(0.9, "lowest fitted order of the plain max|dp|/peak (theory 1, measured 1.05-1.10)"),
    "plain_pressure_level": Tolerance(2.5e-3, "cap on plain max|dp|/peak for n >= 450 (measured <= 1.1e-3)"),
    "projected_pressure_order": Tolerance(1.8, "lowest fitted order of the projected max|dp|/peak (theory 2, measured 2.0-2.3)"),
    "projected_pressure_level": Tolerance(1e-6, "cap on projected max|dp|/peak at n = 1024 (measured <= 1.1e-7)"),
}

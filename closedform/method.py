"""The closed form's adapter in :mod:`threepart.registry` (registered on import as ``"closedform"``).

It holds only inside the paper's framework (``framework_only``): past it, it
refuses with a named error and ``method="auto"`` falls back to the SIE.
"""
from __future__ import annotations

from typing import Any

from threepart.problem.punch import Punch
from threepart.registry import Method, register
from threepart.results import FrettingResult, NormalResult, SlipResult

from .edges import edges
from .fretting import fretting_cycle
from .normal import lift_off, solve_normal
from .slip import solve_partial_slip
from .steady import steady_state

__all__ = ["METHOD"]


def _normal(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
            nu: float | None = None, **options: Any) -> NormalResult:
    return solve_normal(punch, P, s, A=A, tilt=tilt, **options)


def _slip(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
          nu: float | None = None, Q: float, f: float, sigma_bulk: float = 0.0,
          normal: NormalResult | None = None, **options: Any) -> SlipResult:
    base = normal if normal is not None else _normal(punch, P, s, A=A, tilt=tilt, **options)
    return solve_partial_slip(base, Q, f, sigma_bulk=sigma_bulk)


def _fretting(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
              nu: float | None = None, Q_max: float, f: float, states: int | None = None,
              sigma_bulk: float = 0.0, normal: NormalResult | None = None, **options: Any) -> FrettingResult:
    base = normal if normal is not None else _normal(punch, P, s, A=A, tilt=tilt, **options)
    extra: dict[str, Any] = {} if states is None else {"states": states}
    return fretting_cycle(base, Q_max, f, sigma_bulk=sigma_bulk, **extra)


def _lift_off(punch: Punch, P: float, A: float) -> tuple[float, float]:
    """``(s_min, s_max)`` of :func:`~threepart.closedform.lift_off` (eqs. Pctob and s_lift-off)."""
    lim = lift_off(punch, P, A)
    return lim.s_min, lim.s_max


METHOD = register(Method("closedform", _normal, _slip, _fretting, framework_only=True, options=("xtol",),
                         lift_off=_lift_off, steady=steady_state, edges=edges, label="closed form",
                         style={"color": "k", "lw": 1.6, "ls": "-"}))

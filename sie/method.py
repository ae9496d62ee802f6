"""The SIE's adapter in :mod:`threepart.registry` (registered on import as ``"sie"``).

Options: ``n`` (Gauss–Chebyshev nodes) and ``scheme`` (see :func:`threepart.sie.solve_normal`).
"""
from __future__ import annotations

from typing import Any

from threepart.problem.punch import Punch
from threepart.registry import Method, register
from threepart.results import FrettingResult, NormalResult, SlipResult

from .edges import edges
from .fretting import fretting_cycle
from .history import load_history
from .normal import DEFAULT_N, DEFAULT_SCHEME, check_scheme, lift_off, solve_normal
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
    return solve_partial_slip(base, Q, f, sigma_bulk=sigma_bulk, **options)


def _fretting(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
              nu: float | None = None, Q_max: float, f: float, states: int | None = None,
              sigma_bulk: float = 0.0, normal: NormalResult | None = None,
              **options: Any) -> FrettingResult:
    base = normal if normal is not None else _normal(punch, P, s, A=A, tilt=tilt, **options)
    extra: dict[str, Any] = {} if states is None else {"states": states}
    return fretting_cycle(base, Q_max, f, sigma_bulk=sigma_bulk, **extra, **options)


def _options_iv(options: dict[str, Any]) -> None:
    """``n`` and ``scheme`` checked before anything is solved (``auto`` may not reach the SIE)."""
    check_scheme(options.get("scheme", DEFAULT_SCHEME), options.get("n", DEFAULT_N))


METHOD = register(Method("sie", _normal, _slip, _fretting, options=("n", "scheme"),
                         options_iv=_options_iv, lift_off=lift_off,
                         comparison=lambda options: "sie", steady=steady_state,
                         history=load_history, edges=edges, label="SIE", study="n",
                         style={"color": "tab:red", "marker": "o", "ms": 3.5, "ls": "none", "mfc": "none"}))

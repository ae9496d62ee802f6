"""The FEM's adapter in :mod:`threepart.registry` (registered on import as ``"fem"``).

The FE models are bodies of finite size and need Young's modulus and Poisson's
ratio; the adapter converts the compliance ``A`` (eq. 4) at ``nu`` (default
:data:`NU`) by the one mapping of :mod:`threepart.problem.material`: the normal problem is
a rigid punch on a block of modulus ``2(1 - nu^2)/A``
(:func:`threepart.problem.material.rigid_punch_modulus`: ``E/2`` for two similar bodies of
``E``, the catalogue's and the command line's convention); partial slip and the
fretting cycle are two similar bodies, each of modulus ``4(1 - nu^2)/A``
(:func:`threepart.problem.material.similar_pair_modulus`), which solve their own normal problem with
the shear; so is the steady state of an in-phase cycle (:func:`fem.steady_state`). In half-plane theory the solution depends on the material only
through ``A``; ``nu`` affects only the finite block's far field.

Option: ``mesh`` (a preset, see :func:`threepart.fem.solve_normal`).
"""
from __future__ import annotations

from typing import Any

from threepart.problem import material
from threepart.problem.material import NU   # re-exported: the FE models' nu when only A is given
from threepart.problem.punch import Punch
from threepart.registry import Method, register
from threepart.results.cycles import HistoryResult, SteadyStateResult
from threepart.results import FrettingResult, NormalResult, SlipResult
from threepart.tolerances import fem_comparison
from threepart.problem.checks import poisson, positive

from .edges import edges
from .friction import fretting_cycle, solve_partial_slip
from .history import load_history
from .solve import solve_normal
from .steady import steady_state

__all__ = ["METHOD", "NU", "rigid_punch_modulus", "pair_modulus"]



def _nu(nu: float | None) -> float:
    return NU if nu is None else poisson(nu)


def rigid_punch_modulus(A: float, nu: float | None = None) -> float:
    """Young's modulus of the block on which a rigid punch has compliance ``A``: ``2(1 - nu^2)/A``."""
    return material.rigid_punch_modulus(A, _nu(nu))


def pair_modulus(A: float, nu: float | None = None) -> float:
    """Young's modulus of each of two similar bodies of composite compliance ``A``: ``4(1 - nu^2)/A``."""
    return material.similar_pair_modulus(positive("A", A), _nu(nu))


def _normal(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
            nu: float | None = None, **options: Any) -> NormalResult:
    nu = _nu(nu)
    return solve_normal(punch, P, s, E=rigid_punch_modulus(A, nu), nu=nu, tilt=tilt,
                        **options)


def _slip(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
          nu: float | None = None, Q: float, f: float, normal: NormalResult | None = None,
          sigma_bulk: float = 0.0, **options: Any) -> SlipResult:
    nu = _nu(nu)
    return solve_partial_slip(punch, P, s, Q=Q, f=f, E=pair_modulus(A, nu), nu=nu, tilt=tilt,
                              sigma_bulk=sigma_bulk, **options)


def _fretting(punch: Punch, P: float, s: float, *, A: float, tilt: str = "free",
              nu: float | None = None, Q_max: float, f: float, states: int | None = None,
              normal: NormalResult | None = None, sigma_bulk: float = 0.0,
              **options: Any) -> FrettingResult:
    extra: dict[str, Any] = {} if states is None else {"states": states}
    nu = _nu(nu)
    return fretting_cycle(punch, P, s, Q_max=Q_max, f=f, E=pair_modulus(A, nu), nu=nu,
                          tilt=tilt, sigma_bulk=sigma_bulk, **extra, **options)


def _steady(punch: Punch, states: Any, f: float, *, A: float, nu: float | None = None,
            **options: Any) -> SteadyStateResult:
    nu = _nu(nu)
    return steady_state(punch, states, f, E=pair_modulus(A, nu), nu=nu, **options)


def _history(punch: Punch, history: Any, f: float, *, A: float, nu: float | None = None,
             **options: Any) -> HistoryResult:
    nu = _nu(nu)
    return load_history(punch, history, f, E=pair_modulus(A, nu), nu=nu, **options)


METHOD = register(Method("fem", _normal, _slip, _fretting, options=("mesh", "progress"),
                         default_nu=NU, steady=_steady, history=_history, edges=edges,
                         comparison=lambda options: fem_comparison(options.get("mesh", "default")),
                         label="FEM", style={"color": "tab:blue", "lw": 1.2, "ls": "--"},
                         field_color="tab:orange", study="h"))

"""The explicit solver adapters: one :class:`Solver` per method, in :data:`SOLVERS`.

Each adapter turns a catalogue case into the call its solver takes and returns
the shared result shape, so that the verification run and the studies never
branch on a method's name. The solvers are imported only when first called.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable

from threepart.results import FrettingResult, NormalResult, SlipResult

if TYPE_CHECKING:  # pragma: no cover
    from .catalogue import Case

__all__ = ["Solver", "SOLVERS", "METHODS"]


@dataclass(frozen=True)
class Solver:
    """A method behind two calls.

    ``normal(case, **options)`` solves the normal problem of a case;
    ``slip(case, normal, **options)`` the partial-slip problem on that normal
    solution, or is ``None`` where the method has no friction model;
    ``fretting(case, normal, states, **options)`` one fretting cycle of
    amplitude ``Q`` (the case's shear load) with ``states`` recorded states per
    branch. The ``options`` are the method's discretisation (``n``, ``scheme``,
    ``mesh``).
    """

    name: str
    normal: Callable[..., NormalResult]
    slip: Callable[..., SlipResult] | None = None
    fretting: Callable[..., FrettingResult] | None = None


def _closedform_normal(case: Case) -> NormalResult:
    from threepart import closedform

    return closedform.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)


def _closedform_slip(case: Case, normal: NormalResult) -> SlipResult:
    from threepart import closedform

    return closedform.solve_partial_slip(normal, *case.shear_load)


def _closedform_fretting(case: Case, normal: NormalResult, states: int) -> FrettingResult:
    from threepart import closedform

    return closedform.fretting_cycle(normal, *case.shear_load, states=states)


def _sie_normal(case: Case, **options: Any) -> NormalResult:
    from threepart import sie

    return sie.solve_normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt, **options)


def _sie_slip(case: Case, normal: NormalResult, **options: Any) -> SlipResult:
    from threepart import sie

    return sie.solve_partial_slip(normal, *case.shear_load, **options)


def _sie_fretting(case: Case, normal: NormalResult, states: int, **options: Any) -> FrettingResult:
    from threepart import sie

    return sie.fretting_cycle(normal, *case.shear_load, states=states, **options)


def _fem_normal(case: Case, mesh: Any = "default") -> NormalResult:
    from threepart import fem

    res = fem.solve_normal(case.punch, case.P, case.s_load, E=case.E, nu=case.nu, tilt=case.tilt,
                           mesh=mesh)
    if not math.isclose(res.A, case.A, rel_tol=1e-12):
        raise ValueError(f"fem result has A = {res.A}, the case needs A = {case.A}")
    return res


def _fem_slip(case: Case, normal: NormalResult, mesh: Any = "default") -> SlipResult:
    """Partial slip of the two-body FE model; it solves its own (two-body) normal problem."""
    from threepart import fem
    from threepart.methods import fem_pair_modulus

    res = fem.solve_partial_slip(case.punch, case.P, case.s_load, Q=case.shear_load[0],
                                 f=case.shear_load[1], E=fem_pair_modulus(case.A, case.nu),
                                 nu=case.nu, tilt=case.tilt, mesh=mesh)
    if not math.isclose(res.normal.A, case.A, rel_tol=1e-12):
        raise ValueError(f"fem result has A = {res.normal.A}, the case needs A = {case.A}")
    return res


def _fem_fretting(case: Case, normal: NormalResult, states: int,
                  mesh: Any = "default") -> FrettingResult:
    """The two-body FE model through the cycle; it solves its own (two-body) normal problem."""
    from threepart import fem
    from threepart.methods import fem_pair_modulus

    Q, f = case.shear_load
    return fem.fretting_cycle(case.punch, case.P, case.s_load, Q_max=Q, f=f,
                              E=fem_pair_modulus(case.A, case.nu), nu=case.nu, tilt=case.tilt,
                              mesh=mesh, states=states)


#: the three methods, in report order; the closed form is the reference of the others
SOLVERS: dict[str, Solver] = {
    "closedform": Solver("closedform", _closedform_normal, _closedform_slip, _closedform_fretting),
    "sie": Solver("sie", _sie_normal, _sie_slip, _sie_fretting),
    "fem": Solver("fem", _fem_normal, _fem_slip, _fem_fretting),
}
METHODS = tuple(SOLVERS)

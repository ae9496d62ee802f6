"""The verification run's view of the methods: a catalogue case in, the shared result shape out.

Every method is reached through :mod:`threepart.registry`; this module only
turns a catalogue case into the adapter's arguments, so that the verification
run and the studies never branch on a method's name. The solvers are imported
only when first called.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from threepart import registry
from threepart.results.cycles import SteadyStateResult
from threepart.results import FrettingResult, NormalResult, SlipResult
from threepart.errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from threepart.problem.catalogue import Case

__all__ = ["METHODS", "normal", "slip", "fretting", "steady"]

#: the methods the verification run compares, in report order; the closed form is the
#: reference of the others
METHODS = tuple(registry.BUILTIN)


def _args(method: str, case: Case, options: dict[str, Any]) -> dict[str, Any]:
    """The adapter's problem arguments for ``case``: ``A``, ``tilt``, and ``nu`` where both have one.

    A half-plane method depends on the material only through ``A``; a method of
    finite bodies also takes the case's Poisson ratio.
    """
    return {"A": case.A, "tilt": case.tilt, **_nu(method, case), **options}


def _nu(method: str, case: Case) -> dict[str, Any]:
    """``nu`` of ``case``'s material for a method of finite bodies; nothing for a half-plane method."""
    if registry.get(method).default_nu is not None and case.material is not None:
        return {"nu": case.material[1]}
    return {}


def normal(method: str, case: Case, **options: Any) -> NormalResult:
    """The normal problem of ``case`` by ``method``."""
    return registry.get(method).normal(case.punch, case.P, case.s_load,
                                       **_args(method, case, options))


def slip(method: str, case: Case, base: NormalResult | None, **options: Any) -> SlipResult:
    """Partial slip of ``case`` by ``method``, on its normal result ``base`` where the method uses one."""
    Q, f = case.shear_load
    return registry.get(method).slip(case.punch, case.P, case.s_load, Q=Q, f=f,  # type: ignore[misc]
                                     normal=base, **_bulk(case), **_args(method, case, options))


def fretting(method: str, case: Case, base: NormalResult | None, states: int,
             **options: Any) -> FrettingResult:
    """One fretting cycle of ``case`` (amplitude its shear load) by ``method``."""
    Q, f = case.shear_load
    return registry.get(method).fretting(  # type: ignore[misc]
        case.punch, case.P, case.s_load, Q_max=Q, f=f, states=states, normal=base,
        **_bulk(case), **_args(method, case, options))


def _bulk(case: Case) -> dict[str, float]:
    """``sigma_bulk`` for a case that has one (no keyword otherwise, so every adapter takes it)."""
    return {"sigma_bulk": case.sigma_bulk} if case.sigma_bulk else {}


def steady(method: str, case: Case, **options: Any) -> SteadyStateResult:
    """The periodic steady state of ``case``'s cycle between its two ``states`` by ``method``."""
    if case.states is None or case.f is None:
        raise InputError(f"case {case.name!r} has no cycle (`states` and `f`)")
    call = registry.get(method).steady
    if call is None:
        raise InputError(f"method {method!r} has no steady state (Method.steady)")
    return call(case.punch, case.states, case.f, A=case.A, **_nu(method, case), **options)

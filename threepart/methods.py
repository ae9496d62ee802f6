"""One entry point, every method: the closed form where it holds, the SIE past it, or the FEM.

``solve(punch, P, s, A=..., method=...)`` answers the normal problem and,
with ``Q`` and ``f``, the partial-slip problem, by the method asked for:

``"closedform"``
    The paper's closed form (:mod:`threepart.closedform`). It refuses what
    its framework excludes: ``LiftOffError`` (an edge would reach the
    central segment), ``StickZoneError`` (the stick zone would end on it),
    ``SeparationError`` (a concave centre off its single contact).
``"sie"``
    The Gauss–Chebyshev solver (:mod:`threepart.sie`): the same integral
    equations, any single contact, including past lift-off, the punch on one
    corner and stick zones that end on the central segment.
``"fem"``
    The finite-element models (:mod:`threepart.fem`): a rigid punch on an
    elastic block for the normal problem; two similar elastic bodies with
    Coulomb friction, loaded by ``P`` then ``Q``, for partial slip.
``"auto"`` (default)
    The closed form where it holds; where it refuses with ``LiftOffError``,
    ``StickZoneError`` or ``SeparationError``, the SIE, which either answers
    (the result's ``info["auto"]`` says why the closed form did not) or
    refuses in its turn: a contact that separates into two zones is refused
    by every method with ``SeparationError``.

Every method is reached through :mod:`threepart.registry`; the solvers are
imported only when called: importing :mod:`threepart` loads none of them.

Whatever the method, and whether it is called here or directly, its answer
has passed one check when it was built (:mod:`threepart.results.answer`, from the
results' ``__post_init__``): a compressive pressure, else
``SeparationError``, and for partial slip ``|q| <= f p``, else
``CoulombError`` (a ``StickZoneError``, on which ``auto`` falls back).
"""
from __future__ import annotations

from typing import Any, Callable

from . import registry
from .errors import (CycleSlipReversalError, DisjointContactsError, InputError, LiftOffError, NoConvergenceError,
                     OneSidedSlipError, SeparationError, StickZoneError)
from .problem.punch import Punch
from .results.cycles import MarchedSteadyResult, SteadyStateResult
from .results.contact import NormalResult
from .results.slip import FrettingResult, SlipResult
from .halfplane.bulk import check_sigma_bulk
from .problem.checks import check_positive, integer

__all__ = ["METHODS", "CHOICES", "AUTO", "solve", "steady_state", "march_steady_state", "fretting", "describe"]

#: the three built-in solvers, in report order
METHODS = tuple(registry.BUILTIN)
#: what ``method`` may be (and any method registered since, see :mod:`threepart.registry`)
CHOICES = ("auto", *METHODS)
#: ``method="auto"``: the first where it holds, else the second (:data:`threepart.registry.REFERENCE`
#: and :data:`~threepart.registry.BEYOND_REFERENCE`)
AUTO = (registry.REFERENCE, registry.BEYOND_REFERENCE)
#: the closed form's refusals past its framework, on which ``auto`` falls back
FALLBACK_ON = (LiftOffError, StickZoneError, SeparationError)
#: the superposition's refusals of an admissible cycle (closed form and SIE), on which the steady
#: state's ``auto`` marches the SIE's load history until two cycles agree
MARCH_ON = (OneSidedSlipError, CycleSlipReversalError, DisjointContactsError)
#: the marched cycle: states a half-cycle (and of the first loading from rest), the cycles of the
#: first march (doubled until two cycles agree) and the most marched
MARCH_STEPS, MARCH_FIRST, MARCH_CYCLES = 24, 4, 64
#: the states a half-cycle ``march_steady_state`` takes
MARCH_STEPS_RANGE = (2, 1000)


def _one(name: str, punch: Punch, P: float, s: float, A: float, tilt: str, Q: float | None,
         f: float | None, nu: float | None, options: dict[str, Any],
         sigma_bulk: float = 0.0) -> NormalResult | SlipResult:
    m = _checked(name, options, nu)
    if Q is None or f is None:
        return m.normal(punch, P, s, A=A, tilt=tilt, nu=nu, **options)
    if m.slip is None:
        raise InputError(f"method {name!r} has no partial-slip model")
    return m.slip(punch, P, s, A=A, tilt=tilt, nu=nu, Q=Q, f=f, **_bulk(m, sigma_bulk, "partial slip"),
                  **options)


def _bulk(m: registry.Method, sigma_bulk: float, what: str) -> dict[str, float]:
    """The keyword that passes ``sigma_bulk`` to ``m``: none at 0 (a method that predates the bulk
    stress is still reached), and a refusal by name where ``m`` declares it takes none."""
    if not sigma_bulk:
        return {}
    if not m.bulk_stress:
        raise InputError(f"`sigma_bulk` = {sigma_bulk:g}: method {m.name!r} does not take a bulk "
                         f"stress in its {what}; give sigma_bulk=0 or another method")
    return {"sigma_bulk": sigma_bulk}


def solve(punch: Punch, P: float, s: float = 0.0, *, A: float, tilt: str = "free",
          Q: float | None = None, f: float | None = None, method: str = "auto",
          nu: float | None = None, sigma_bulk: float = 0.0, **options: Any) -> NormalResult | SlipResult:
    """Normal (and, with ``Q`` and ``f``, partial-slip) solution by ``method``.

    Parameters
    ----------
    punch
        Three-part punch geometry (eq. 2).
    P, s
        Compressive load, > 0, and its lever arm (eq. vertical, eq. rotational).
    A
        Compliance (eq. 4), > 0.
    tilt
        ``"free"`` or ``"suppressed"`` (then ``s`` is returned).
    Q, f
        Shear force and coefficient of friction, both or neither.
    method
        ``"auto"`` (default), ``"closedform"``, ``"sie"``, ``"fem"`` or any
        method registered in :mod:`threepart.registry`; see the module
        docstring.
    nu
        Poisson's ratio, for a method that models bodies of finite size (the
        FEM; default 0.3 there). A half-plane method refuses it.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate (tension positive) at ``Q``, rising
        with ``Q`` in proportion after the normal load; partial slip only
        (docs/BULK_STRESS.md). Where it reverses the slip at one end the closed
        form refuses with ``SlipReversalError`` (a ``StickZoneError``), on which
        ``"auto"`` falls back.
    **options
        The method's discretisation: ``n`` and ``scheme`` for the SIE,
        ``mesh`` for the FEM. With ``"auto"`` they go to the SIE.

    Returns
    -------
    NormalResult or SlipResult
        The shared result shape; ``result.method`` names the method that
        answered, ``result.within_paper`` whether the closed form's framework
        holds, ``result.segments`` which segments are in contact. With
        ``"auto"`` and a fallback, ``result.info["auto"]`` holds the closed
        form's refusal.

    Raises
    ------
    ValueError
        For invalid input (the message names the argument and its limit), and
        the named refusals (``SeparationError`` and, with ``"closedform"``,
        ``LiftOffError`` and ``StickZoneError``; ``FullSlidingError`` for
        ``|Q| >= f P``; ``SlopeLimitError`` and ``ArcExtentError`` past
        half-plane theory).
    NoConvergenceError, ContactZoneError
        If a numerical method does not converge or its mesh zone is too small.
    """
    if method != "auto":
        registry.get(method, also=("auto",))   # an unknown name is refused before anything else
    if (Q is None) != (f is None):
        raise InputError("give both `Q` and `f` for partial slip, or neither")
    sigma_bulk = check_sigma_bulk(sigma_bulk)
    if sigma_bulk and Q is None:
        raise InputError(f"`sigma_bulk` = {sigma_bulk:g} applies to partial slip only: give `Q` and `f`")
    check_positive(A=A)
    if method != "auto":
        return _one(method, punch, P, s, A, tilt, Q, f, nu, options, sigma_bulk)
    result = _auto(lambda name, opts: _one(name, punch, P, s, A, tilt, Q, f, nu, opts, sigma_bulk),
                   options)
    if isinstance(result, SlipResult) and "auto" in result.info:
        result.normal.info["auto"] = result.info["auto"]
    return result


def _checked(name: str, options: dict[str, Any], nu: float | None) -> registry.Method:
    """The method called ``name``, once its options and ``nu`` are checked."""
    m = registry.get(name)
    m.check_options(options)
    _check_nu(m, nu)
    return m


def _check_nu(m: registry.Method, nu: float | None) -> None:
    """``nu`` only for a method of finite bodies: a half-plane method depends on the material only through ``A``."""
    if nu is not None and m.default_nu is None:
        raise InputError(f"`nu` is not used by method {m.name!r}: a half-plane solution depends on "
                         "the material only through `A`")


def _auto(call: Callable[[str, dict[str, Any]], Any], options: dict[str, Any]) -> Any:
    """``method="auto"``: ``call`` by the closed form, or by the SIE (with ``options``) where it refuses
    with one of :data:`FALLBACK_ON`; the SIE's result says why in ``info["auto"]``."""
    first, fallback = AUTO
    registry.get(fallback).check_options(options, called=repr("auto"))
    try:
        return call(first, {})
    except FALLBACK_ON as refusal:
        why = f"the closed form does not hold here: {' '.join(str(refusal).split())}"
    result = call(fallback, options)
    result.info["auto"] = why
    return result


def _steady(name: str, punch: Punch, states: Any, f: float, A: float, nu: float | None,
            options: dict[str, Any]) -> SteadyStateResult:
    m = _checked(name, options, nu)
    if m.steady is None:
        raise InputError(f"method {name!r} has no steady-state model of a cycle")
    return m.steady(punch, states, f, A=A, **({} if nu is None else {"nu": nu}), **options)


def steady_state(punch: Punch, states: Any, f: float, *, A: float, method: str = "auto",
                 nu: float | None = None, **options: Any) -> SteadyStateResult:
    """The periodic steady state of an in-phase cycle between two states, by ``method``.

    Parameters
    ----------
    punch
        Three-part punch geometry (eq. 2).
    states
        The two ends of the cycle, each ``(P, s, Q, sigma_bulk)``; the four move
        linearly between them, in phase (docs/STEADY_STATE.md).
    f
        Coefficient of friction, > 0.
    A
        Compliance of the elastically similar pair (eq. 4), > 0.
    method
        ``"auto"`` (default: the closed form, and the SIE where it refuses with
        one of :data:`FALLBACK_ON`, as :func:`solve`), ``"closedform"``, ``"sie"``
        or any registered method with a ``steady`` call.
    nu
        Poisson's ratio, for a method that models bodies of finite size (the
        FEM; default 0.3 there). A half-plane method refuses it, as in :func:`solve`.
    **options
        The method's discretisation (``n``, ``scheme`` for the SIE, ``mesh`` for the
        FEM; with ``"auto"`` they go to the SIE).

    Returns
    -------
    SteadyStateResult
        ``d``, ``e``, ``energy``, ``shakedown``, ``normals``, ``shear(x, state)``,
        ``slip_amplitude(x)``, ``stress(x, z, state)``; with ``"auto"`` and a
        fallback, ``info["auto"]`` holds the closed form's refusal.

    Raises
    ------
    ValueError
        For invalid input and the named refusals of the method (with ``"auto"``,
        those of the SIE): ``FullSlidingError``, ``OneSidedSlipError``,
        ``CycleSlipReversalError``, ``SeparationError``, ...
    """
    if method != "auto":
        registry.get(method, also=("auto",))
    check_positive(A=A)
    if method != "auto":
        return _steady(method, punch, states, f, A, nu, options)
    try:
        return _auto(lambda name, opts: _steady(name, punch, states, f, A, nu, opts), options)
    except MARCH_ON as refusal:
        why = f"the superposition does not model this cycle: {' '.join(str(refusal).split())}"
    return march_steady_state(punch, states, f, A=A, why=why)


def march_steady_state(punch: Punch, states: Any, f: float, *, A: float, why: str = "",
                       steps: int = MARCH_STEPS) -> MarchedSteadyResult:
    """The steady state of the cycle between ``states[0]`` and ``states[1]``, by the SIE's load history.

    The cycle is marched from rest (:func:`threepart.halfplane.steady.cycle_states`, ``steps``
    states a half-cycle), :data:`MARCH_FIRST` cycles, then twice as many, ... until the
    energies of the last two cycles agree to ``tolerance("auto-march", "settle")``;
    the last cycle is the steady state (:class:`~threepart.results.cycles.MarchedSteadyResult`).

    Returns
    -------
    MarchedSteadyResult
        ``method`` ``"sie-march"``; ``info["auto"]``: ``why`` and how the march settled;
        ``info["march"]``: ``cycles`` marched, ``steps`` a half-cycle, ``agreement`` (the
        last two cycles' relative difference), the history's ``n`` and its ``resolved``.

    Raises
    ------
    NoConvergenceError
        If the energies have not settled in :data:`MARCH_CYCLES` cycles.
    """
    from .halfplane.steady import check_cycle_states, cycle_states
    from .tolerances import tolerance

    check_positive(A=A)
    (st0, st1), f = check_cycle_states(states, f)
    steps = integer("steps", steps, *MARCH_STEPS_RANGE)
    march = registry.get(AUTO[1]).history
    assert march is not None     # the SIE registers its load history (sie/method.py)
    settle = tolerance("auto-march", "settle").limit
    cycles = MARCH_FIRST
    while True:
        try:
            hist = march(punch, cycle_states(st0, st1, steps, cycles), f, A=A, period=2 * steps)
        except NoConvergenceError as exc:
            raise NoConvergenceError(f"{why + '; ' if why else ''}the SIE's load history could not march the "
                                     f"cycle either: {exc}") from None
        e0, e1 = (float(v) for v in hist.energy[-2:])
        change = abs(e1 - e0) / max(abs(e0), abs(e1)) if max(abs(e0), abs(e1)) > 0 else 0.0
        if change <= settle:
            break
        if 2 * cycles > MARCH_CYCLES:
            raise NoConvergenceError(
                f"the marched cycle did not settle in {cycles} cycles: the friction work of the last two was "
                f"{e0:.6g} and {e1:.6g} N·mm/mm (relative change {change:.3g} > {settle:g}); no result is returned")
        cycles *= 2
    done = (f"marched by the SIE's load history, {cycles} cycles of {steps} states a half-cycle: the last two "
            f"cycles' energies agree to {change:.2g} (within {settle:g})")
    info = {"auto": f"{why}; {done}" if why else done,
            "march": {"cycles": cycles, "steps": steps, "agreement": change, "n": hist.diagnostics.n,
                      "resolved": hist.info.get("resolved", True)}}
    return MarchedSteadyResult.from_history(hist, (st0, st1), f, steps,
                                            tolerance("auto-march", "shakedown").limit, "sie-march", info)


def _cycle(name: str, punch: Punch, P: float, s: float, A: float, tilt: str, Q_max: float, f: float,
           states: int | None, nu: float | None, sigma_bulk: float,
           options: dict[str, Any]) -> FrettingResult:
    m = _checked(name, options, nu)
    if m.fretting is None:
        raise InputError(f"method {name!r} has no fretting cycle")
    bulk = _bulk(m, sigma_bulk, "fretting cycle")
    return m.fretting(punch, P, s, A=A, tilt=tilt, nu=nu, Q_max=Q_max, f=f, states=states,
                      normal=None, **bulk, **options)


def fretting(punch: Punch, P: float, s: float = 0.0, *, A: float, Q_max: float, f: float,
             tilt: str = "free", states: int | None = None, method: str = "auto",
             nu: float | None = None, sigma_bulk: float = 0.0, **options: Any) -> FrettingResult:
    """One fretting cycle ``Q = 0 -> Q_max -> -Q_max -> Q_max`` at constant ``P``, by ``method``.

    Parameters
    ----------
    punch
        Three-part punch geometry (eq. 2).
    P, s
        Compressive load, > 0, and its lever arm, held through the cycle.
    A
        Compliance of the elastically similar pair (eq. 4), > 0.
    Q_max, f
        Amplitude of the shear force, ``0 < Q_max < f P``, and the coefficient of friction.
    tilt
        ``"free"`` or ``"suppressed"``.
    states
        Recorded states per branch of the cycle (default: the method's).
    method
        ``"auto"`` (default: the closed form, and the SIE where it refuses with
        one of :data:`FALLBACK_ON`, as :func:`solve`), ``"closedform"``,
        ``"sie"``, ``"fem"`` or any registered method with a ``fretting`` call.
    nu
        Poisson's ratio, for a method that models bodies of finite size (the
        FEM; default 0.3 there). A half-plane method refuses it, as in :func:`solve`.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate at ``Q_max``, in phase with ``Q``
        (docs/BULK_STRESS.md); refused by a method that declares
        ``bulk_stress=False`` in :mod:`threepart.registry`.
    **options
        The method's discretisation (with ``"auto"`` they go to the SIE).

    Returns
    -------
    FrettingResult
        ``normal``, ``Q``, the stick zones of each recorded state, ``stress``;
        with ``"auto"`` and a fallback, ``info["auto"]`` holds the closed form's refusal.

    Raises
    ------
    ValueError
        For invalid input and the named refusals of the method (with ``"auto"``,
        those of the SIE).
    """
    if method != "auto":
        registry.get(method, also=("auto",))
    sigma_bulk = check_sigma_bulk(sigma_bulk)
    check_positive(A=A)
    if method != "auto":
        return _cycle(method, punch, P, s, A, tilt, Q_max, f, states, nu, sigma_bulk, options)
    return _auto(lambda name, opts: _cycle(name, punch, P, s, A, tilt, Q_max, f, states, nu,
                                           sigma_bulk, opts), options)


def describe(result: NormalResult | SlipResult) -> str:
    """One line: the method that answered and, if ``auto`` fell back, why."""
    why = result.info.get("auto")
    line = f"method: {result.method}"
    return f"{line} ({why})" if why else line

"""Fretting wear at constant ``P``, ``s`` and ``Q`` between ``±Q_max`` (issue 39; docs/WEAR.md).

``threepart.wear(...)`` marches the worn depth through fretting cycles by a
method's marcher, registered here by name as readers register themselves
(:func:`register_marcher`); the SIE's is :func:`threepart.sie.wear.march`. The
worn depth is the two bodies' wear together (the gap they open), shared in any
fixed proportion: the contact sees only the sum (docs/WEAR.md, section 4).

wear             -- the march: ``cycles``, ``energy``, ``stick_zones``, ``depths``, ``volume``, ``final``
WearResult       -- its result
register_marcher -- a method's march under its name
has_marcher      -- whether a method marches wear
marchers         -- every method that marches wear; needs_material: whether one takes E and nu (its solver package loaded to register it)
WearCase         -- a catalogue wear case: a fretting case of threepart/problem/cases.json with its law, ``k`` and cycles
wear_cases       -- the catalogue's wear cases (suite ``"wear"``: fretting cases with a ``wear`` law, ``k``, cycles)
wear_case        -- one of them by name
jump_size        -- the cycle-jumping control every marcher uses (depth per jump, Euler's stability)
march_depth      -- the march every marcher shares, on its own states (MarchState)
LAWS             -- "archard" (``Δw = k p |slip|``) and "energy" (``Δw = k q·slip``, Fouvry)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable

import numpy as np

from threepart.problem.catalogue import Case
from threepart.errors import InputError, InputTypeError, NoConvergenceError
from threepart.problem.punch import Punch
from threepart.results import FrettingResult
from threepart.problem.checks import check_tilt, integer, positive
from threepart.problem.validate import check_punch, lever_arm

__all__ = ["wear", "WearResult", "register_marcher", "has_marcher", "WearCase", "wear_cases", "wear_case",
           "LAWS", "jump_size", "march_depth", "MarchState", "DEPTH_STEP", "STABILITY", "marchers", "needs_material", "DEFAULT_MARCHER"]

#: the wear laws: depth ``k p |slip|`` (Archard) and ``k q·slip`` (energy, Fouvry)
LAWS = ("archard", "energy")
#: the most cycles a march takes (a fan-blade flank's life is 1e6 to 1e8)
MAX_CYCLES = 10**10

_MARCHERS: dict[str, Callable[..., "WearResult"]] = {}
#: the marchers that model bodies of a material: they take ``E=`` and ``nu=`` besides ``A``
_MATERIAL: set[str] = set()
#: the method :func:`wear` marches with by default; the others are compared with it
DEFAULT_MARCHER = "sie"

#: the depth worn per jump, as a fraction of the elastic approach A P/π (:func:`jump_size`)
DEPTH_STEP = 0.01
#: ΔN (Δw/p) π/(A Δx): Euler's stability bound for the grid's shortest ripple is 2 (:func:`jump_size`)
STABILITY = 1.5


def register_marcher(name: str, march: Callable[..., "WearResult"], *, material: bool = False) -> None:
    """Register ``march(punch, P, s, Q_max, f, *, A, law, k, cycles, jump, tilt, **options)`` as ``name``.

    ``material``: the march models bodies of a material and takes ``E=`` and ``nu=`` (:func:`needs_material`).
    """
    _MARCHERS[name] = march
    if material:
        _MATERIAL.add(name)


@dataclass(frozen=True)
class WearResult:
    """A fretting-wear march (:func:`wear`) at its recorded cycles (every jump).

    Attributes
    ----------
    x
        Knots of the worn depth.
    cycles
        The recorded cycle counts, from 0.
    energy
        Friction work per cycle at each (``∫ q·slip dx`` over a cycle).
    stick_zones
        ``(x1, x2)`` of the stick zone at ``Q_max`` at each.
    depths
        The worn depth at the knots at each, ``(len(cycles), len(x))``: both bodies together
        (the gap they open). A body that takes the fixed fraction ``φ`` of the wear is worn
        ``φ depths``; the contact, the shear and the energy do not depend on ``φ``.
    volumes
        ``∫ w dx`` at each: the worn area per unit length (both bodies).
    contacts, alphas
        The contact ``(-a, c)`` and the tilt at each.
    final_cycle
        Solves the fretting cycle on the last worn profile: :attr:`final` calls it once.
    pressures
        The pressure at the knots ``x`` at each recorded cycle, ``(len(cycles), len(x))`` (0 off the
        contact), or None where the marcher does not record it.
    """

    punch: Punch
    P: float
    s: float
    Q_max: float
    f: float
    A: float
    law: str
    k: float
    x: np.ndarray = field(repr=False)
    cycles: np.ndarray = field(repr=False)
    energy: np.ndarray = field(repr=False)
    stick_zones: np.ndarray = field(repr=False)
    depths: np.ndarray = field(repr=False)
    volumes: np.ndarray = field(repr=False)
    contacts: np.ndarray = field(repr=False)
    alphas: np.ndarray = field(repr=False)
    final_cycle: Callable[[], FrettingResult] = field(repr=False, compare=False)
    method: str = ""
    info: dict[str, Any] = field(default_factory=dict, repr=False)
    pressures: np.ndarray | None = field(default=None, repr=False)

    @cached_property
    def final(self) -> FrettingResult:
        """The fretting cycle on the last worn profile: ``pressure(x)``, ``shear``, ``stress``, ``edges()``.

        Solved when first asked for: it costs more than the march's steps together (measured 60 %
        of the fan-blade flank's march with it). It raises the solver's named error where the cycle
        cannot be solved (a stick zone of the cycle's lower loads not found on the scar's steep edge).
        """
        return self.final_cycle()

    @property
    def volume(self) -> float:
        """The worn area per unit length at the last cycle (both bodies)."""
        return float(self.volumes[-1])

    def depth(self, x: Any, record: int = -1) -> np.ndarray:
        """The worn depth at ``x`` at a recorded cycle (the last by default), linear between knots."""
        return np.interp(np.asarray(x, dtype=float), self.x, self.depths[record])


def jump_size(rate: np.ndarray, travel: np.ndarray, k: float, A: float, P: float, spacing: np.ndarray,
          law_factor: float) -> int:
    """The jump's ``ΔN``: the depth bound and Euler's stability bound, at least 1 (0: nothing wears).

    A step of ``ΔN`` cycles grows the depth by ``ΔN Δw`` (explicit Euler in ``N``);
    ``ΔN`` is the largest whole number with

    * ``max ΔN Δw <= DEPTH_STEP A P/π`` (the depth per jump a fraction of the elastic
      approach ``A P/π``), and
    * ``ΔN (Δw/p)_i <= STABILITY A Δx_i/π`` at every node ``i`` (local spacing ``Δx_i``):
      a depth ripple of wavenumber ``κ`` changes the pressure by ``κ/A`` times itself, so
      Euler is stable for ``ΔN (Δw/p) κ/A < 2`` up to the nodes' ``κ = π/Δx``;
      :data:`STABILITY` < 2 keeps it so.

    ``rate`` is ``p ∮|ds|`` and ``travel`` ``∮|ds|`` at the nodes, ``law_factor`` ``f`` for the
    energy law and 1 for Archard's.

    The stability bound is taken knot by knot with the local spacing ``Δx_i``:
    ``ΔN c_i π/(A Δx_i) <= STABILITY``, ``c_i = k ∮|ds|`` there.
    """
    top = k * law_factor * float(np.max(rate))
    c = k * law_factor * travel
    stiff = float(np.max(c / spacing))
    bounds = [DEPTH_STEP * A * P / math.pi / top if top > 0 else math.inf,
              STABILITY * A / (math.pi * stiff) if stiff > 0 else math.inf]
    dN = min(bounds)
    return max(1, int(dN)) if math.isfinite(dN) else 0


@dataclass(frozen=True)
class MarchState:
    """One worn state as a marcher gives it to :func:`march_depth`.

    ``rate`` is ``p ∮|ds|`` and ``travel`` ``∮|ds|`` at the depth's points; ``work`` the
    friction work per cycle; ``stick`` the stick zone at ``Q_max``; ``contact``, ``alpha`` and
    ``pressure`` (at the points) the normal contact's; ``solved`` the marcher's own object.
    """

    rate: np.ndarray
    travel: np.ndarray
    work: float
    stick: tuple[float, float]
    contact: tuple[float, float]
    alpha: float
    pressure: np.ndarray
    solved: Any = None


def march_depth(solve: Callable[[np.ndarray, Any], MarchState], weights: np.ndarray, spacing: np.ndarray, *,
                k: float, law_factor: float, A: float, P: float, cycles: int, jump: int | None,
                failures: tuple[type[BaseException], ...]) -> tuple[dict[str, np.ndarray], str, Any]:
    """The march every marcher shares: solve the worn state, record it, grow the depth by ``ΔN`` cycles.

    ``solve(depth, last)`` is the marcher's state of the worn ``depth`` at its points (``last``: the
    previous state's ``solved``, to start from); ``weights`` the points' shares of the length (the
    worn area is ``Σ depth weights``); ``spacing`` their local spacing (:func:`jump_size`). A state
    that raises one of ``failures`` ends the march early (never the first: its error is the caller's).

    Returns
    -------
    records, stopped, solved
        :class:`WearResult`'s fields ``cycles``, ``energy``, ``stick_zones``, ``depths``, ``volumes``,
        ``contacts``, ``alphas``, ``pressures``; why the march ended early (``""``: it did not);
        the last state's ``solved``.
    """
    rec: dict[str, list] = {name: [] for name in ("cycles", "energy", "stick_zones", "depths", "volumes",
                                                  "contacts", "alphas", "pressures")}
    depth, N, stopped, last = np.zeros(weights.size), 0, "", None
    while True:
        try:
            state = solve(depth, last)
        except failures as exc:
            if not rec["cycles"]:
                raise
            stopped = f"at cycle {N} the worn contact or its stick zone at Q_max was not found: {exc}"
            break
        last = state.solved
        for key, value in (("cycles", N), ("energy", state.work), ("stick_zones", state.stick),
                           ("depths", depth.copy()), ("volumes", float(np.sum(depth * weights))),
                           ("contacts", state.contact), ("alphas", state.alpha), ("pressures", state.pressure)):
            rec[key].append(value)
        if N >= cycles:
            break
        dN = jump if jump is not None else jump_size(state.rate, state.travel, k, A, P, spacing, law_factor)
        if dN == 0:     # nothing slips: the worn limit
            dN = cycles - N
        dN = min(dN, cycles - N)
        depth = depth + dN * k * law_factor * state.rate
        N += dN
    if not np.all(np.isfinite(depth)):
        raise NoConvergenceError("wear: the worn depth is not finite; no result is returned")
    return {key: np.array(values) for key, values in rec.items()}, stopped, last


def _wear_iv(punch: Punch, P: float, s: float, Q_max: float, f: float, A: float, law: str, k: float,
             cycles: int, jump: int | None, tilt: str) -> tuple[float, float, float, float, float, float, int]:
    check_punch(punch)
    P, A, f, k = positive("P", P), positive("A", A), positive("f", f), positive("k", k)
    Q_max = positive("Q_max", Q_max)
    s = lever_arm(punch, s)
    check_tilt(tilt)
    if Q_max >= f * P:
        raise InputError(f"`Q_max` = {Q_max:.6g} must be below f P = {f * P:.6g}: full sliding, "
                         "there is no stick zone to fret about")
    if law not in LAWS:
        raise InputError(f"`law` = {law!r} must be one of {', '.join(LAWS)}")
    cycles = integer("cycles", cycles, 0, MAX_CYCLES)
    if jump is not None:
        jump = integer("jump", jump, 1, MAX_CYCLES)
    return P, s, Q_max, f, A, k, cycles


def wear(punch: Punch, P: float, s: float, Q_max: float, f: float, *, A: float, law: str = "archard",
         k: float, cycles: int, method: str = "sie", jump: int | None = None, tilt: str = "free",
         **options: Any) -> WearResult:
    """Fretting cycles at constant ``P``, ``s`` with ``Q`` between ``±Q_max``, the depth grown by wear.

    Parameters
    ----------
    punch, P, s, A, tilt
        The problem (eq. 2, eq. 4), as :func:`threepart.solve`.
    Q_max, f
        The shear amplitude and the coefficient of friction, ``0 < Q_max < f P``.
    law
        ``"archard"``: depth ``k p |slip|`` per unit slip; ``"energy"``: ``k q·slip``
        (Fouvry), so that the worn area per cycle is ``k`` times the friction work (eq. W15).
    k
        The wear coefficient (mm²/N for Archard, mm³/(N mm) per unit length for the energy law).
    cycles
        Cycles to march, >= 0.
    method
        The marcher: ``"sie"``.
    jump
        Cycles per step; None (default): the method's stated step control
        (:mod:`threepart.sie.wear`: the depth per jump and Euler's stability bound).
    options
        The marcher's own (``n``, ``points`` for the SIE).

    Returns
    -------
    WearResult

    Raises
    ------
    ValueError
        A bad value, named with its limit; ``Q_max >= f P``; an unknown ``law`` or ``method``.
    TypeError
        ``punch`` not a Punch, ``cycles`` or ``jump`` not an integer; an option the method's
        march does not take.
    """
    if not isinstance(method, str):
        raise InputTypeError(f"`method` must be a string, not {type(method).__name__}")
    P, s, Q_max, f, A, k, cycles = _wear_iv(punch, P, s, Q_max, f, A, law, k, cycles, jump, tilt)
    if not has_marcher(method):
        raise InputError(f"`method` = {method!r} has no wear march (not yet); marchers: "
                         f"{', '.join(sorted(_MARCHERS)) or 'none'}")
    march = _MARCHERS[method]
    own = _own_options(march)
    unknown = sorted(set(options) - own)
    if unknown:
        raise InputTypeError(f"{', '.join(f'`{name}`' for name in unknown)} is not an option of method "
                             f"{method!r}'s wear march (its options: {', '.join(sorted(own)) or 'none'})")
    return march(punch, P, s, Q_max, f, A=A, law=law, k=k, cycles=cycles, jump=jump, tilt=tilt, **options)


#: the arguments every marcher takes from :func:`wear` itself
_COMMON = frozenset({"A", "law", "k", "cycles", "jump", "tilt"})


def _own_options(march: Callable[..., Any]) -> set[str]:
    """A marcher's own keyword options (``n``, ``points`` for the SIE; ``E``, ``nu``, ``mesh`` for the FEM)."""
    import inspect

    params = inspect.signature(march).parameters.values()
    return {p.name for p in params if p.kind is p.KEYWORD_ONLY} - _COMMON


def marchers() -> list[str]:
    """Every method that marches wear, the built-in ones loaded first: :data:`DEFAULT_MARCHER` first."""
    from threepart import registry
    for name in registry.BUILTIN:
        has_marcher(name)
    return sorted(_MARCHERS, key=lambda name: (name != DEFAULT_MARCHER, name))


def needs_material(method: str) -> bool:
    """Whether ``method``'s march takes the bodies' ``E`` and ``nu`` (:func:`register_marcher`)."""
    return has_marcher(method) and method in _MATERIAL


def has_marcher(method: str) -> bool:
    """Whether ``method`` marches wear: a built-in method's package is loaded first (it registers its march)."""
    if method not in _MARCHERS:
        from threepart import registry
        if method in registry.BUILTIN:
            registry.get(method)      # the solver package registers its marcher on import
    return method in _MARCHERS


@dataclass(frozen=True)
class WearCase:
    """A catalogue wear case (threepart/problem/cases.json, suite ``"wear"``): a fretting ``case`` (punch, material,
    ``P``, ``s``, ``f``, ``Q_max``) worn by ``law`` with coefficient ``k`` over ``cycles``."""

    case: Case
    law: str
    k: float
    cycles: int
    source: str = ""

    @classmethod
    def of(cls, case: Case) -> "WearCase":
        """The wear case of a catalogue ``case`` of kind ``"wear"``; its law is checked here."""
        if case.wear is None or case.Q is None or case.f is None:
            raise InputError(f"case {case.name!r} is not a wear case (it has no `wear`, `f` and `Q_over_fP`)")
        if case.wear.law not in LAWS:
            raise InputError(f"case {case.name!r}: `law` = {case.wear.law!r} must be one of {', '.join(LAWS)}")
        return cls(case, case.wear.law, case.wear.k, case.wear.cycles, case.wear.source)

    @property
    def name(self) -> str:
        """The case's name (``threepart wear --case NAME``)."""
        return self.case.name

    @property
    def Q_max(self) -> float:
        """The shear amplitude ``Q_over_fP f P``."""
        assert self.case.Q is not None      # checked by :meth:`of`
        return self.case.Q

    def run(self, **options: Any) -> WearResult:
        """:func:`wear` of this case; ``options`` replace its ``law``, ``k``, ``cycles`` or add the marcher's."""
        c = self.case
        kw: dict[str, Any] = {"law": self.law, "k": self.k, "cycles": self.cycles, **options}
        return wear(c.punch, c.P, c.s_load, self.Q_max, c.f, A=c.A, tilt=c.tilt, **kw)   # type: ignore[arg-type]


def wear_cases(path: str | None = None) -> list[WearCase]:
    """The catalogue's wear cases (suite ``"wear"`` of :func:`threepart.problem.catalogue.load_cases`), in file order."""
    from threepart.problem.catalogue import CASES_FILE, load_cases

    cases = load_cases("wear", path)          # names the file in its own errors
    try:
        return [WearCase.of(c) for c in cases]
    except InputError as exc:
        raise InputError(f"`path` = {str(path or CASES_FILE)!r}, {exc}") from None


def wear_case(name: str, path: str | None = None) -> WearCase:
    """The catalogue's wear case ``name``; ``InputError`` listing the wear cases if there is none."""
    cases = wear_cases(path)
    for c in cases:
        if c.name == name:
            return c
    raise InputError(f"`name` = {name!r} is not a wear case of the catalogue (its wear cases: "
                     f"{', '.join(c.name for c in cases) or 'none'})")
"""One registry of methods: a name and a small adapter for every solver.

Every caller that picks a method by name (:func:`threepart.solve`, the command
line, the verification run, the figures, the map) dispatches through
:func:`get`; none of them branches on a method's name. A method registers
itself, as meshio's file formats do: the module that defines its adapter calls
:func:`register` when it is imported. The built-in methods live in the solver
packages (``threepart.closedform``, ``threepart.sie``, ``threepart.fem``),
which are imported only when their name is first asked for, so that importing
:mod:`threepart` loads no solver.

Adding a method
---------------
Write one module that builds a :class:`Method` from three functions and calls
``register`` on it; import that module, and ``threepart.solve(...,
method="yours")`` and :func:`get` find it. Its ``label`` and ``style`` name and
draw it in the report's tables and plots, its ``study`` names the parameter of
its convergence study; none is needed (its name, matplotlib's next colour).
``tests/test_registry.py`` does this with a toy method.

The adapter's calls
-------------------
Every call takes the problem in the shared terms: the punch, ``P``, ``s``, the
compliance ``A`` (eq. 4) and ``tilt``; ``nu`` is Poisson's ratio where a
method models a body of finite size (the FEM; half-plane methods depend on the
material only through ``A`` and ignore it); then the method's own
discretisation options, named in :attr:`Method.options`.

``normal(punch, P, s, *, A, tilt, nu, **options)``
    The normal problem: a :class:`~threepart.results.NormalResult`.
``slip(punch, P, s, *, A, tilt, nu, Q, f, normal, **options)``
    Partial slip: a :class:`~threepart.results.SlipResult`. ``normal`` is a
    normal result of this method for the same problem, or None; a method that
    solves its own normal problem with the shear (the FEM) ignores it.
``fretting(punch, P, s, *, A, tilt, nu, Q_max, f, states, normal, **options)``
    One fretting cycle: a :class:`~threepart.results.FrettingResult`.
    ``slip`` and ``fretting`` also take ``sigma_bulk`` (the bulk stress along
    x, docs/BULK_STRESS.md), passed only when it is not 0, unless the method
    declares ``bulk_stress=False``; a nonzero one is then refused by name.
``steady(punch, states, f, *, A, **options)``
    The periodic steady state of a cycle between two states ``(P, s, Q,
    sigma_bulk)``: a :class:`~threepart.results.SteadyStateResult`
    (docs/STEADY_STATE.md); the adapter is the method's own ``steady_state``.
``lift_off(punch, P, A)``
    The lever arms ``(s_min, s_max)`` at which, with the tilt free, a contact
    end reaches a join ``x = -+b``: the range of ``s`` with both ends on the
    edge arcs (eq. s_lift-off). The shared package asks a method by name for
    it (the case catalogue, the command line) and never imports a solver.

Names
-----
Method      -- a method's adapter: name, calls, options, capabilities
register    -- add (or replace) a method in the registry
get         -- the method of a name, importing a built-in solver on first use
names       -- every method's name: the built-in ones first, in report order
lift_off    -- the lift-off lever arms (s_min, s_max) by a method of a name
BUILTIN     -- the built-in methods and the packages that register them
REFERENCE   -- the method the others are compared with (the closed form)
BEYOND_REFERENCE -- the reference past the closed form's framework, and ``auto``'s fallback (the SIE)
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Mapping
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:  # pragma: no cover
    from .problem.punch import Punch
    from .results.cycles import HistoryResult, SteadyStateResult
    from .results.contact import NormalResult
    from .results.slip import FrettingResult, SlipResult

__all__ = ["Method", "register", "get", "names", "lift_off", "BUILTIN", "REFERENCE", "BEYOND_REFERENCE"]

#: the built-in methods, in report order (the closed form is the reference of the others),
#: and the package whose import registers each
BUILTIN: dict[str, str] = {"closedform": "threepart.closedform", "sie": "threepart.sie",
                           "fem": "threepart.fem"}
#: the method the others are compared with wherever it answers (the paper's closed form; also the
#: one whose lift-off range resolves a catalogue case's lever-arm fraction); a case past its
#: framework names another (``Case.reference``), and the report tells such cases by that
REFERENCE = "closedform"
#: the reference past the closed form's framework (lift-off, a stick zone on the central segment):
#: ``Case.reference`` of such a case, and the method ``auto`` falls back on (``methods.AUTO``)
BEYOND_REFERENCE = "sie"


@dataclass(frozen=True)
class Method:
    """A method behind three calls (see the module docstring for their signatures).

    Attributes
    ----------
    name
        What ``method=`` names it by.
    normal, slip, fretting
        The calls; ``slip`` and ``fretting`` are None where the method has no
        friction model.
    options
        The discretisation options its calls take (e.g. ``("n", "scheme")``).
    framework_only
        True if the method holds only inside the paper's framework and refuses
        the rest (the closed form); ``method="auto"`` then falls back.
    default_nu
        Poisson's ratio the method assumes when none is given, for a method
        that models bodies of finite size (the FEM); None for a half-plane
        method, which depends on the material only through ``A``.
    options_iv
        Checks the values of the options (a ``TypeError`` or ``ValueError``
        naming the option) before anything is solved, or None.
    lift_off
        The lift-off lever arms ``(s_min, s_max)`` at ``(punch, P, A)``, or
        None where the method does not compute them.
    steady
        The steady state of an in-phase cycle between two states, or None
        where the method has none.
    bulk_stress
        True (default) if ``slip`` and ``fretting`` take ``sigma_bulk``; False
        for a method that predates the bulk stress, to which :func:`threepart.solve`
        and :func:`threepart.fretting` (and the command line) refuse a nonzero
        one by name before calling it.
    history
        ``history(punch, states, f, *, A, nu, **options)``: a load history of
        ``(P, s, Q, sigma_bulk)`` states marched with the memory of slip
        (:class:`~threepart.results.cycles.HistoryResult`), or None where the method
        has none.
    edges
        ``edges(normal)``: the pressure's edge multipliers ``((K_N, fit_error),
        (K_N, fit_error))`` at ``-a`` and ``c`` of a normal result of this
        method (:mod:`threepart.results.edges`, docs/EDGES.md); ``fit_error`` is
        None where ``K_N`` is exact. None where the method has none.
    comparison
        The row group of :data:`threepart.tolerances.TOLERANCES` that judges
        this method's results against the reference, from the options it was
        run with (the FEM's limits depend on its mesh); None for a method that
        is only ever the reference (the closed form).
    label
        How the report and the plots name it ("" for its name).
    style
        How the plots draw it: matplotlib line keywords (``color``, ``ls``,
        ``marker``, ...); empty for matplotlib's next colour. A method drawn as
        markers alone (``ls="none"``) is sampled at fewer points.
    field_color
        The colour of its contours over another method's filled field; None
        for its style's colour (white where it has none).
    study
        The discretisation parameter its convergence study varies (``"n"``,
        ``"h"``), as the report names it; None for a method without one.
    """

    name: str
    normal: Callable[..., NormalResult]
    slip: Callable[..., SlipResult] | None = None
    fretting: Callable[..., FrettingResult] | None = None
    options: tuple[str, ...] = ()
    framework_only: bool = False
    default_nu: float | None = None
    options_iv: Callable[[dict[str, Any]], None] | None = None
    lift_off: Callable[[Punch, float, float], tuple[float, float]] | None = None
    comparison: Callable[[dict[str, Any]], str] | None = None
    steady: Callable[..., SteadyStateResult] | None = None
    history: Callable[..., HistoryResult] | None = None
    edges: Callable[[NormalResult], tuple[tuple[float, float | None], tuple[float, float | None]]] | None = None
    bulk_stress: bool = True
    label: str = ""
    style: Mapping[str, Any] = field(default_factory=dict)
    field_color: str | None = None
    study: str | None = None

    @property
    def title(self) -> str:
        """How the report names it: its label, else its name."""
        return self.label or self.name

    def plot_style(self) -> dict[str, Any]:
        """Its matplotlib line keywords with its title as the label."""
        return {**self.style, "label": self.title}

    @property
    def markers(self) -> bool:
        """True if it is drawn as markers alone (``ls="none"``): the plots sample it sparsely."""
        return self.style.get("ls", self.style.get("linestyle")) == "none"

    @property
    def contour_color(self) -> str:
        """The colour of its contours over a filled field."""
        return self.field_color or str(self.style.get("color", "w"))

    def check_options(self, options: dict[str, Any], called: str | None = None) -> None:
        """``ValueError`` naming the first option this method does not take; then the values.

        ``called`` is the name the user gave, when it differs (``"auto"``).
        """
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            raise InputError(f"`{unknown[0]}` is not an option of method {called or repr(self.name)} "
                             f"(its options: {', '.join(self.options) or 'none'})")
        if self.options_iv is not None:
            self.options_iv(options)


_REGISTRY: dict[str, Method] = {}


def register(method: Method) -> Method:
    """Add ``method`` to the registry (replacing one of the same name) and return it."""
    if not isinstance(method, Method):
        raise InputTypeError(f"`method` must be a threepart.registry.Method, not {type(method).__name__}")
    _REGISTRY[method.name] = method
    return method


def names() -> tuple[str, ...]:
    """Every method's name: the built-in ones in report order, then those registered since."""
    return (*BUILTIN, *(n for n in _REGISTRY if n not in BUILTIN))


def get(name: Any, also: tuple[str, ...] = ()) -> Method:
    """The method called ``name``; a built-in solver package is imported on first use.

    Raises
    ------
    ValueError
        If no method of that name is registered; the message lists them, after
        the names in ``also`` that the caller accepts besides (``"auto"``).
    """
    if isinstance(name, str) and name not in _REGISTRY and name in BUILTIN:
        # the package registers itself on import; read its adapter again in case the
        # package was imported earlier and its entry has been replaced since
        register(importlib.import_module(f"{BUILTIN[name]}.method").METHOD)
    try:
        return _REGISTRY[name]
    except (KeyError, TypeError):
        raise InputError(f"`method` = {name!r} must be one of "
                         f"{', '.join((*also, *names()))}") from None


def lift_off(name: str, punch: Punch, P: float, A: float) -> tuple[float, float]:
    """The lever arms ``(s_min, s_max)`` at which a contact end reaches a join, by the method ``name``.

    Raises
    ------
    ValueError
        If no method of that name is registered, or it does not compute them;
        or as the method's ``lift_off`` raises (e.g. ``b = 0``: no join).
    """
    method = get(name)
    if method.lift_off is None:
        raise InputError(f"`method` = {name!r} does not compute lift-off lever arms")
    return method.lift_off(punch, P, A)

"""One entry point, three methods: the closed form where it holds, the SIE past it, or the FEM.

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

The solvers are imported only when called: importing :mod:`threepart` loads
none of them.
"""
from __future__ import annotations

from typing import Any

from .errors import LiftOffError, SeparationError, StickZoneError
from .punch import Punch
from .results import NormalResult, SlipResult
from .validate import check_positive

__all__ = ["METHODS", "CHOICES", "solve", "describe", "fem_modulus", "fem_pair_modulus"]

#: the three solvers, in report order
METHODS = ("closedform", "sie", "fem")
#: what ``method`` may be
CHOICES = ("auto", *METHODS)
#: the discretisation options each method takes (``auto`` passes them to the SIE)
OPTIONS: dict[str, tuple[str, ...]] = {"closedform": (), "sie": ("n", "scheme"),
                                       "fem": ("mesh", "nu"), "auto": ("n", "scheme")}
#: Poisson's ratio the FEM is given when only the compliance is known (see :func:`fem_modulus`)
FEM_NU = 0.3


def fem_modulus(A: float, nu: float = FEM_NU) -> float:
    """Young's modulus of the FE block that has compliance ``A`` as a rigid punch: ``2(1 - ν²)/A``.

    In half-plane theory the normal solution depends on the material only
    through ``A`` (eq. 4), so a similar pair of compliance ``A`` is modelled
    by a rigid punch on a block of this modulus; ``nu`` affects only the far
    field of the finite block.
    """
    return 2.0 * (1.0 - nu * nu) / A


def fem_pair_modulus(A: float, nu: float = FEM_NU) -> float:
    """Young's modulus of each of two similar FE bodies of composite compliance ``A``: ``4(1 - ν²)/A``."""
    return 2.0 * fem_modulus(A, nu)


def _normal(method: str, punch: Punch, P: float, s: float, A: float, tilt: str,
            options: dict[str, Any]) -> NormalResult:
    if method == "closedform":
        from . import closedform

        return closedform.solve_normal(punch, P, s, A=A, tilt=tilt)
    if method == "sie":
        from . import sie

        return sie.solve_normal(punch, P, s, A=A, tilt=tilt, **options)
    from . import fem

    nu = options.pop("nu", FEM_NU)
    return fem.solve_normal(punch, P, s, E=fem_modulus(A, nu), nu=nu, tilt=tilt, **options)


def _slip(method: str, normal: NormalResult, Q: float, f: float,
          options: dict[str, Any]) -> SlipResult:
    if method == "closedform":
        from . import closedform

        return closedform.solve_partial_slip(normal, Q, f)
    from . import sie

    return sie.solve_partial_slip(normal, Q, f, **options)


def _fem_slip(punch: Punch, P: float, s: float, A: float, tilt: str, Q: float, f: float,
              options: dict[str, Any]) -> SlipResult:
    """Partial slip by the two-body FE model, which solves its own normal problem first."""
    from . import fem

    nu = options.pop("nu", FEM_NU)
    return fem.solve_partial_slip(punch, P, s, Q=Q, f=f, E=fem_pair_modulus(A, nu), nu=nu,
                                  tilt=tilt, **options)


def _one(method: str, punch: Punch, P: float, s: float, A: float, tilt: str, Q: float | None,
         f: float | None, options: dict[str, Any]) -> NormalResult | SlipResult:
    if method == "fem" and Q is not None and f is not None:
        return _fem_slip(punch, P, s, A, tilt, Q, f, dict(options))
    normal = _normal(method, punch, P, s, A, tilt, dict(options))
    if Q is None or f is None:
        return normal
    slip_options = {k: v for k, v in options.items() if k in OPTIONS["sie"]}
    return _slip(method, normal, Q, f, slip_options)


def solve(punch: Punch, P: float, s: float = 0.0, *, A: float, tilt: str = "free",
          Q: float | None = None, f: float | None = None, method: str = "auto",
          **options: Any) -> NormalResult | SlipResult:
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
        ``"auto"`` (default), ``"closedform"``, ``"sie"`` or ``"fem"``; see
        the module docstring.
    **options
        The method's discretisation: ``n`` and ``scheme`` for the SIE,
        ``mesh`` (and ``nu``, default 0.3) for the FEM. With ``"auto"`` they
        go to the SIE.

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
        ``|Q| >= f P``).
    NoConvergenceError, ContactZoneError
        If a numerical method does not converge or its mesh zone is too small.
    """
    if method not in CHOICES:
        raise ValueError(f"`method` = {method!r} must be one of {', '.join(CHOICES)}")
    allowed = OPTIONS[method]
    unknown = sorted(set(options) - set(allowed))
    if unknown:
        raise ValueError(f"`{unknown[0]}` is not an option of method {method!r} "
                         f"(its options: {', '.join(allowed) or 'none'})")
    if (Q is None) != (f is None):
        raise ValueError("give both `Q` and `f` for partial slip, or neither")
    check_positive(A=A)
    if method != "auto":
        return _one(method, punch, P, s, A, tilt, Q, f, options)
    try:
        return _one("closedform", punch, P, s, A, tilt, Q, f, {})
    except (LiftOffError, StickZoneError, SeparationError) as refusal:
        why = f"the closed form does not hold here: {' '.join(str(refusal).split())}"
    result = _one("sie", punch, P, s, A, tilt, Q, f, options)
    result.info["auto"] = why
    if isinstance(result, SlipResult):
        result.normal.info["auto"] = why
    return result


def describe(result: NormalResult | SlipResult) -> str:
    """One line: the method that answered and, if ``auto`` fell back, why."""
    why = result.info.get("auto")
    line = f"method: {result.method}"
    return f"{line} ({why})" if why else line


"""Input checks shared by every entry point, in the style of SciPy's ``_*_iv`` helpers.

The contract, the same in every method:

- a value of the wrong type (a bool, a string, ``None``, a complex number,
  bytes) is a :class:`TypeError` that names the argument;
- a value out of its range is a :class:`ValueError` (or a subclass from
  :mod:`threepart.errors`) whose message names the argument and the limit;
- every real number that passes (numpy scalars of any float width,
  ``np.longdouble``, :class:`fractions.Fraction`, Python ints) is returned as
  a float64, so that no solver computes in float16 or in object arithmetic.

Bad input thus never surfaces later as a NaN, an overflow or a foreign error.

Range checks
------------
LENGTH_RANGE        -- magnitudes of lengths and loads, ``[1e-60, 1e60]``
lever_arm           -- ``s`` inside the punch's footprint ``(-(b + R1), b + R2)``
SLOPE_LIMIT         -- the small-slope limit of half-plane theory (tilt and profile slopes)
check_contact       -- a solved contact: inside the arcs' extents and within SLOPE_LIMIT
integer             -- a discretisation count (``n``, ``steps``) between bounds
"""
from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["real", "finite", "positive", "check_finite", "check_positive", "TILTS", "check_tilt",
           "LENGTH_RANGE", "integer", "lever_arm", "SLOPE_LIMIT", "check_contact", "check_punch"]

#: tilt modes: the tilt ``alpha`` follows from the moment, or is held at zero
TILTS = ("free", "suppressed")
#: lengths and loads are kept inside this magnitude range, so that squares, cubes and
#: reciprocals of them stay finite in double precision
LENGTH_RANGE = (1e-60, 1e60)


def _show(value: Any) -> str:
    """``repr(value)``, cut to 40 characters, for a one-line message."""
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:18]}...{text[-18:]} ({len(text)} characters)"


def _number(name: str, value: Any) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating,
                                                                      np.integer)):
        raise TypeError(f"`{name}` = {_show(value)} must be a real number, not {type(value).__name__}")
    try:
        v = float(value)      # float64, whatever the width or kind of the real number given
    except OverflowError:
        raise ValueError(f"`{name}` = {_show(value)} is outside the double-precision range") from None
    if math.isinf(v) and not (isinstance(value, (float, np.floating)) and math.isinf(value)):
        # e.g. np.longdouble(1e4000): finite as given, infinite in float64
        raise ValueError(f"`{name}` = {_show(value)} is outside the double-precision range")
    return v


def real(name: str, value: Any) -> float:
    """``value`` as a float (``inf`` allowed); ``ValueError`` unless it is a real number, not NaN or a bool."""
    v = _number(name, value)
    if math.isnan(v):
        raise ValueError(f"`{name}` = nan is not a number")
    return v


def finite(name: str, value: Any) -> float:
    """``value`` as a finite float, else ``ValueError``."""
    v = _number(name, value)
    if not math.isfinite(v):
        raise ValueError(f"`{name}` = {_show(value)} must be a finite number")
    return v


def positive(name: str, value: Any, limits: tuple[float, float] = LENGTH_RANGE) -> float:
    """``value`` as a float in ``[limits[0], limits[1]]`` (a positive magnitude), else ``ValueError``."""
    v = finite(name, value)
    if v <= 0:
        raise ValueError(f"`{name}` = {_show(value)} must be > 0")
    lo, hi = limits
    if not lo <= v <= hi:
        raise ValueError(f"`{name}` = {_show(value)} is outside [{lo:g}, {hi:g}], the range this "
                         "library computes in double precision")
    return v


def check_finite(**values: Any) -> None:
    """Raise ``ValueError`` naming the first argument that is not a finite real number."""
    for name, value in values.items():
        finite(name, value)


def check_positive(**values: Any) -> None:
    """Raise ``ValueError`` naming the first argument that is not a finite number > 0."""
    for name, value in values.items():
        positive(name, value)


def check_tilt(tilt: Any) -> str:
    """``tilt`` if it is one of :data:`TILTS`, else ``ValueError``."""
    if not isinstance(tilt, str) or tilt not in TILTS:
        raise ValueError(f"`tilt` = {tilt!r} must be one of {TILTS}")
    return tilt


def integer(name: str, value: Any, lo: int, hi: int) -> int:
    """``value`` as an int in ``[lo, hi]``: a discretisation count such as ``n`` or ``steps``.

    A bool, a float or any non-integer type is a ``TypeError``; a count out of
    range is a ``ValueError`` naming both bounds (the upper bound keeps a
    solve within this machine's memory and time).
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        raise TypeError(f"`{name}` = {_show(value)} must be an integer, not {type(value).__name__}")
    v = int(value)
    if not lo <= v <= hi:
        raise ValueError(f"`{name}` = {v} must lie in [{lo}, {hi}]")
    return v


def check_punch(punch: Any) -> Any:
    """``punch`` if it is a :class:`threepart.Punch`, else ``TypeError``."""
    from .punch import Punch

    if not isinstance(punch, Punch):
        raise TypeError(f"`punch` must be a threepart.Punch, not {type(punch).__name__}")
    return punch


def lever_arm(punch: Any, s: Any) -> float:
    """``s`` as a float if it lies inside the punch's footprint ``(-(b + R1), b + R2)``.

    An arc of radius ``R1`` (``R2``) that meets the central segment at ``x = -b``
    (``+b``) ends within ``R1`` (``R2``) of its join, so every contact
    ``[-a, c]`` lies in the footprint, and the load's lever arm, which is the
    pressure's centroid, lies inside the contact. A lever arm outside it has no
    half-plane answer; it is refused before any numerics.
    """
    v = finite("s", s)
    lo, hi = -(punch.b + punch.R1), punch.b + punch.R2
    if not lo < v < hi:
        raise ValueError(f"`s` = {s!r} lies outside the punch's footprint ({lo:g}, {hi:g}) = "
                         "(-(b + R1), b + R2): the load's centroid must lie on the punch")
    return v


#: The small-slope limit of half-plane theory: the largest slope of a contact that any solver
#: answers, the largest of the tilt, the profile's slope and the surface slope over the
#: contact (:meth:`threepart.Punch.max_slope`).
#: Half-plane theory measures the gap vertically and the tractions on the undeformed
#: surface; its error grows in proportion to the slope (about 1 % in the peak pressure at
#: a slope of 0.1, measured with a finite-deformation model: see docs/SMALL_SLOPE.md).
SLOPE_LIMIT = 0.3


def check_contact(punch: Any, a: float, c: float, alpha: float) -> float:
    """Check a solved contact ``[-a, c]`` against the limits of half-plane theory.

    Returns
    -------
    float
        The contact's slope, :meth:`threepart.Punch.max_slope`.

    Raises
    ------
    ArcExtentError
        If a contact end runs past an arc's geometric extent (``a > b + R1``
        or ``c > b + R2``): the punch's profile ends there.
    SlopeLimitError
        If the slope exceeds :data:`SLOPE_LIMIT`.
    """
    from .errors import ArcExtentError, SlopeLimitError

    if a > punch.b + punch.R1:
        raise ArcExtentError(f"the contact end x = {-a:.6g} runs past the R1 arc's extent "
                             f"-(b + R1) = {-(punch.b + punch.R1):g}: the punch's profile ends "
                             "there, half-plane theory has no answer")
    if c > punch.b + punch.R2:
        raise ArcExtentError(f"the contact end x = {c:.6g} runs past the R2 arc's extent "
                             f"b + R2 = {punch.b + punch.R2:g}: the punch's profile ends there, "
                             "half-plane theory has no answer")
    slope = punch.max_slope(a, c, alpha)
    if not slope <= SLOPE_LIMIT:
        raise SlopeLimitError(f"the contact's slope (tilt, profile or surface) reaches {slope:.3g} (tilt "
                              f"alpha = {alpha:.3g} rad), past the small-slope limit "
                              f"{SLOPE_LIMIT:g} of half-plane theory; reduce the load or the "
                              "lever arm `s`")
    return slope

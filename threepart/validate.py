"""Input checks shared by every entry point, in the style of SciPy's ``_*_iv`` helpers.

Each check raises a :class:`ValueError` whose message names the argument and
the limit. Booleans, strings, ``None`` and other non-real types are refused
before any arithmetic, so that bad input never surfaces later as a NaN, a
``TypeError`` or an overflow.
"""
from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = ["real", "finite", "positive", "check_finite", "check_positive", "TILTS", "check_tilt",
           "LENGTH_RANGE"]

#: tilt modes: the tilt ``alpha`` follows from the moment, or is held at zero
TILTS = ("free", "suppressed")
#: lengths and loads are kept inside this magnitude range, so that squares, cubes and
#: reciprocals of them stay finite in double precision
LENGTH_RANGE = (1e-60, 1e60)


def _number(name: str, value: Any) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating,
                                                                      np.integer)):
        raise ValueError(f"`{name}` = {value!r} must be a real number, not {type(value).__name__}")
    return float(value)


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
        raise ValueError(f"`{name}` = {value!r} must be a finite number")
    return v


def positive(name: str, value: Any, limits: tuple[float, float] = LENGTH_RANGE) -> float:
    """``value`` as a float in ``[limits[0], limits[1]]`` (a positive magnitude), else ``ValueError``."""
    v = finite(name, value)
    if v <= 0:
        raise ValueError(f"`{name}` = {value!r} must be > 0")
    lo, hi = limits
    if not lo <= v <= hi:
        raise ValueError(f"`{name}` = {value!r} is outside [{lo:g}, {hi:g}], the range this "
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

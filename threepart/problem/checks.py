"""Checks of plain values (numbers, arrays, coordinates, flags): the leaf every module's input passes through.

The contract, the same in every method:

- a value of the wrong type (a bool, a string, ``None``, a complex number,
  bytes) is a :class:`TypeError` that names the argument;
- a value out of its range is a :class:`ValueError` whose message names the
  argument and the limit;
- every real number that passes (numpy scalars of any float width,
  ``np.longdouble``, :class:`fractions.Fraction`, Python ints) is returned as
  a float64, so that no solver computes in float16 or in object arithmetic.

This module imports nothing of threepart's, so that the problem types
(:mod:`threepart.problem.punch`, :mod:`threepart.results`, :mod:`threepart.stress`) use it
and the checks of a problem (:mod:`threepart.problem.validate`, which re-exports these
names) can use the problem types, without an import circle.

show            -- a value as a message quotes it
real, finite    -- a real number (finite: and not inf or NaN) as a float
positive        -- a positive number inside limits (default LENGTH_RANGE)
check_finite, check_positive -- the same for several keyword arguments at once
TILTS, check_tilt -- the tilt modes ``"free"`` and ``"suppressed"``
LENGTH_RANGE    -- magnitudes of lengths and loads, ``[1e-60, 1e60]``
integer         -- a discretisation count (``n``, ``steps``) between bounds
NU_RANGE, poisson -- Poisson's ratio inside ``(-1, 0.5)``
reals           -- an array of real numbers as float64 (the batch solvers' ``P`` and ``s``)
coordinates     -- the ``x`` (``z``) of a result's pressure, shear, slip or stress: finite reals
flag            -- a yes/no option (``beyond_small_slopes``): a Python or numpy bool
"""
from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np
from threepart.errors import InputError, InputTypeError

__all__ = ["real", "finite", "positive", "check_finite", "check_positive", "TILTS", "check_tilt",
           "LENGTH_RANGE", "show", "NU_RANGE", "poisson", "integer", "reals", "coordinates", "flag"]


#: tilt modes: the tilt ``alpha`` follows from the moment, or is held at zero
TILTS = ("free", "suppressed")


#: lengths and loads are kept inside this magnitude range, so that squares, cubes and
#: reciprocals of them stay finite in double precision
LENGTH_RANGE = (1e-60, 1e60)


def show(value: Any) -> str:
    """``repr(value)``, cut to 40 characters, for a one-line message (every check's messages use it)."""
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:18]}...{text[-18:]} ({len(text)} characters)"


def _number(name: str, value: Any) -> float:
    if type(value) is float:      # the common case, without the checks' cost (a single solve's inputs)
        return value
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating,
                                                                      np.integer)):
        raise InputTypeError(f"`{name}` = {show(value)} must be a real number, not {type(value).__name__}")
    try:
        v = float(value)      # float64, whatever the width or kind of the real number given
    except OverflowError:
        raise InputError(f"`{name}` = {show(value)} is outside the double-precision range") from None
    if math.isinf(v) and not (isinstance(value, (float, np.floating)) and np.isinf(value)):
        # e.g. np.longdouble(1e4000): finite as given, infinite in float64
        raise InputError(f"`{name}` = {show(value)} is outside the double-precision range")
    return v


def real(name: str, value: Any) -> float:
    """``value`` as a float (``inf`` allowed); ``ValueError`` unless it is a real number, not NaN or a bool."""
    v = _number(name, value)
    if math.isnan(v):
        raise InputError(f"`{name}` = nan is not a number")
    return v


def finite(name: str, value: Any) -> float:
    """``value`` as a finite float, else ``ValueError``."""
    v = _number(name, value)
    if not math.isfinite(v):
        raise InputError(f"`{name}` = {show(value)} must be a finite number")
    return v


def positive(name: str, value: Any, limits: tuple[float, float] = LENGTH_RANGE) -> float:
    """``value`` as a float in ``[limits[0], limits[1]]`` (a positive magnitude), else ``ValueError``."""
    v = finite(name, value)
    if v <= 0:
        raise InputError(f"`{name}` = {show(value)} must be > 0")
    lo, hi = limits
    if not lo <= v <= hi:
        raise InputError(f"`{name}` = {show(value)} is outside [{lo:g}, {hi:g}], the range this "
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
        raise InputError(f"`tilt` = {tilt!r} must be one of {TILTS}")
    return tilt


def integer(name: str, value: Any, lo: int, hi: int) -> int:
    """``value`` as an int in ``[lo, hi]``: a discretisation count such as ``n`` or ``steps``.

    A bool, a float or any non-integer type is a ``TypeError``; a count out of
    range is a ``ValueError`` naming both bounds (the upper bound keeps a
    solve within this machine's memory and time).
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        raise InputTypeError(f"`{name}` = {show(value)} must be an integer, not {type(value).__name__}")
    v = int(value)
    if not lo <= v <= hi:
        raise InputError(f"`{name}` = {v} must lie in [{lo}, {hi}]")
    return v


#: Poisson's ratio of a stable isotropic solid lies in this open interval
NU_RANGE = (-1.0, 0.5)


def poisson(nu: Any) -> float:
    """``nu`` as a float inside :data:`NU_RANGE`, else ``ValueError`` naming ``nu`` and the range."""
    v = finite("nu", nu)
    lo, hi = NU_RANGE
    if not lo < v < hi:
        raise InputError(f"`nu` = {nu!r} must lie in ({lo:g}, {hi:g}), Poisson's ratio of a "
                         "stable isotropic solid")
    return v


def reals(name: str, value: Any) -> np.ndarray:
    """``value`` (a real number or an array of them) as a 1-D float64 array.

    A bool, a string, bytes, ``None``, a complex number or an object array of
    anything but real numbers is a ``TypeError`` naming ``name``; NaN is a
    ``ValueError``. Every float width (and ``np.longdouble``) is promoted to
    float64; a value outside float64's range is a ``ValueError``.
    """
    if isinstance(value, (str, bytes)) or value is None:
        raise InputTypeError(f"`{name}` = {show(value)} must be real numbers, not {type(value).__name__}")
    try:
        # a list is checked element by element: numpy would turn True into 1.0
        arr = np.asarray(value, dtype=object if isinstance(value, (list, tuple)) else None)
    except ValueError:
        raise InputTypeError(f"`{name}` = {show(value)} must be a flat array of real numbers") from None
    kind = arr.dtype.kind
    if kind == "O":
        out = np.empty(arr.size)
        for i, v in enumerate(arr.ravel()):
            try:
                out[i] = _number(name, v)
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"{exc} (element {i})") from None
            if math.isinf(out[i]) and not math.isinf(v):
                raise InputError(f"`{name}` = {show(v)} is outside the double-precision range "
                                 f"(element {i})")
            if math.isnan(out[i]):
                raise InputError(f"`{name}` = nan is not a number (element {i})")
        return out
    if kind not in "iuf":
        raise InputTypeError(f"`{name}` must be real numbers, not an array of {arr.dtype} "
                        f"(first value {show(arr.ravel()[0] if arr.size else arr)})")
    with np.errstate(over="ignore"):
        out = arr.astype(float).ravel()
    bad = np.isinf(out) & ~np.isinf(arr.ravel()) if kind == "f" else np.isinf(out)
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"`{name}` = {show(arr.ravel()[i])} is outside the double-precision range "
                         f"(element {i})")
    if np.isnan(out).any():
        raise InputError(f"`{name}` = nan is not a number (element {int(np.argmax(np.isnan(out)))})")
    return out


def coordinates(name: str, value: Any) -> Any:
    """``value``, a coordinate or an array of them, as finite float64 (the same shape).

    Every result's ``pressure(x)``, ``shear(x)``, ``slip_amplitude(x)`` and
    ``stress(x, z)`` pass their coordinates through here (wrapped once in
    :class:`threepart.results.NormalResult`), so every method refuses alike:
    ``None``, a string, bytes, a bool or a complex number (alone or in an
    array) is a ``TypeError`` naming ``name``; NaN, an infinity or a number
    outside float64's range (``10**400``) is a ``ValueError`` naming it. A
    float array, the solvers' own calls, costs one ``isfinite`` pass.
    """
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        with np.errstate(over="ignore"):      # a longdouble past float64's range becomes inf
            arr = value if value.dtype == np.float64 else value.astype(float)
    elif isinstance(value, (numbers.Real, np.floating, np.integer)) and not isinstance(value, (bool, np.bool_)):
        return finite(name, value)
    elif isinstance(value, (list, tuple, np.ndarray)):
        arr = _coordinate_array(name, value)
    else:
        raise InputTypeError(f"`{name}` = {show(value)} must be a real number or an array of them, not "
                        f"{type(value).__name__}")
    bad = ~np.isfinite(arr)
    if bad.any():
        i = int(np.argmax(bad.ravel()))
        raise InputError(f"`{name}` = {show(arr.ravel()[i])} (element {i}) must be a finite coordinate")
    return arr


def _coordinate_array(name: str, value: Any) -> np.ndarray:
    """An array (or nested list) of coordinates as float64, element by element if it is not numeric."""
    try:
        arr = np.asarray(value, dtype=object if isinstance(value, (list, tuple)) else None)
    except ValueError:
        raise InputTypeError(f"`{name}` = {show(value)} must be a regular array of real numbers") from None
    if arr.dtype.kind in "iu":
        return arr.astype(float)
    if arr.dtype.kind != "O":
        raise InputTypeError(f"`{name}` must be real numbers, not an array of {arr.dtype}")
    out = np.empty(arr.shape)
    for i, v in enumerate(arr.ravel()):
        try:
            out.flat[i] = finite(name, v)
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"{exc} (element {i})") from None
    return out


def flag(name: str, value: Any) -> bool:
    """``value`` as a bool if it is one (Python's or numpy's), else ``TypeError`` naming ``name``.

    A yes/no option such as ``beyond_small_slopes``: ``1``, ``"yes"`` or
    ``None`` are refused rather than read by their truth value.
    """
    if not isinstance(value, (bool, np.bool_)):
        raise InputTypeError(f"`{name}` = {show(value)} must be True or False, not {type(value).__name__}")
    return bool(value)

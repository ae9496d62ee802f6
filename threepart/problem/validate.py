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
check_arcs          -- a contact inside the arcs' extents (ArcExtentError), the first half of that
first_refused       -- the first of a batch of contacts that check_contact refuses, in one array pass
integer             -- a discretisation count (``n``, ``steps``) between bounds
poisson             -- Poisson's ratio inside NU_RANGE, ``(-1, 0.5)``
SLOPE_WARNING       -- the slope past which the measured small-slope error exceeds 5 %
MAX_STATES          -- the most recorded states per fretting branch (``check_states``)
reals               -- an array of real numbers as float64 (the batch solvers' ``P`` and ``s``)
load_scale          -- ``A P max(R1, R2, b)`` inside ``LENGTH_RANGE**2`` (the contact scale squared)
shear_load          -- ``Q`` (or ``Q_max``) and ``f`` for a load ``P``: ``|Q| < f P`` (FullSlidingError)
SLIP_RATIO_LIMIT    -- the largest ``|Q|/(fP)`` a numerical stick zone is solved for (1 - 1e-6)
coordinates         -- the ``x`` (``z``) of a result's pressure, shear, slip or stress: finite reals
flag                -- a yes/no option (``beyond_small_slopes``): a Python or numpy bool
"""
from __future__ import annotations

from typing import Any

import numpy as np

from .checks import (LENGTH_RANGE, NU_RANGE, TILTS, check_finite, check_positive, check_tilt, coordinates,
                     finite, flag, integer, poisson, positive, real, reals, show)
from .punch import Punch
from threepart.errors import InputError, InputTypeError

#: the checks of a problem; the plain-value checks (finite, positive, integer, poisson, ...) are
#: threepart.problem.checks's, their one home, imported from there
__all__ = ["lever_arm", "SLOPE_LIMIT", "SLOPE_WARNING", "check_contact", "check_punch", "MAX_STATES",
           "check_states", "load_scale", "shear_load", "SLIP_RATIO_LIMIT", "check_arcs", "first_refused"]


def check_punch(punch: Any) -> Any:
    """``punch`` if it is a :class:`threepart.Punch`, else ``TypeError``."""
    if not isinstance(punch, Punch):
        raise InputTypeError(f"`punch` must be a threepart.Punch, not {type(punch).__name__}")
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
        raise InputError(f"`s` = {s!r} lies outside the punch's footprint ({lo:g}, {hi:g}) = "
                         "(-(b + R1), b + R2): the load's centroid must lie on the punch")
    return v


#: The small-slope limit of half-plane theory: the largest slope of a contact that any solver
#: answers, the largest of the tilt, the profile's slope and the surface slope over the
#: contact (:meth:`threepart.Punch.max_slope`). Half-plane theory measures the gap vertically
#: and puts the tractions on the undeformed surface; its error grows in proportion to the
#: slope. Measured against a finite-deformation CalculiX model of Hertz (docs/SMALL_SLOPE.md):
#: the peak pressure is too high by about 0.43 slope^1.1 (3.3 % at 0.1, 12 % at 0.3); an
#: outside first-increment measurement put it at about 1 % at 0.1. The limit is 0.5, not
#: lower, because the paper's own figure set b reaches 0.31 and the validity map
#: (reports/map/validity.py) measures the formulas' error up to there; past 0.5 (27 degrees) an
#: answer is refused, e.g. a tilt of -0.8 rad. Past :data:`SLOPE_WARNING` the command line
#: says that the small-slope error may exceed 5 %.
SLOPE_LIMIT = 0.5


#: the slope at which the measured small-slope error in the peak pressure reaches 5 %
#: (0.43 slope^1.1 = 0.05 at 0.142; docs/SMALL_SLOPE.md)
SLOPE_WARNING = 0.14


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
    from ..errors import SlopeLimitError

    check_arcs(punch, a, c)
    slope = punch.max_slope(a, c, alpha)
    if not slope <= SLOPE_LIMIT:
        raise SlopeLimitError(f"the contact's slope (tilt, profile or surface) reaches {slope:.3g} (tilt "
                              f"alpha = {alpha:.3g} rad), past the small-slope limit "
                              f"{SLOPE_LIMIT:g} of half-plane theory; reduce the load or the "
                              "lever arm `s`")
    return slope


def first_refused(punch: Any, a: np.ndarray, c: np.ndarray, alpha: np.ndarray) -> int | None:
    """Index of the first contact ``[-a[i], c[i]]`` that :func:`check_contact` refuses, or None.

    The same limits as :func:`check_contact` (the arcs' extents, then
    :data:`SLOPE_LIMIT` on :meth:`threepart.Punch.max_slope`), as array
    operations over the whole batch; the caller raises that case's own error
    with :func:`check_contact`.
    """
    bad = ((a > punch.b + punch.R1) | (c > punch.b + punch.R2)
           | ~(punch.max_slope(a, c, alpha) <= SLOPE_LIMIT))
    return int(np.argmax(bad)) if bad.any() else None


def check_arcs(punch: Any, a: float, c: float) -> None:
    """``ArcExtentError`` if a contact end of ``[-a, c]`` runs past an arc's extent (``a > b + R1``, ``c > b + R2``).

    The punch's profile ends there (eq. 2): half-plane theory has no answer.
    Part of :func:`check_contact`; alone, it holds the lift-off contacts.
    """
    from ..errors import ArcExtentError

    if a > punch.b + punch.R1:
        raise ArcExtentError(f"the contact end x = {-a:.6g} runs past the R1 arc's extent "
                             f"-(b + R1) = {-(punch.b + punch.R1):g}: the punch's profile ends "
                             "there, half-plane theory has no answer")
    if c > punch.b + punch.R2:
        raise ArcExtentError(f"the contact end x = {c:.6g} runs past the R2 arc's extent "
                             f"b + R2 = {punch.b + punch.R2:g}: the punch's profile ends there, "
                             "half-plane theory has no answer")


#: the most recorded states per branch of a fretting cycle (each is a slip solve)
MAX_STATES = 10_000


def check_states(states: Any, most: int = MAX_STATES) -> int:
    """``states``, the recorded states per fretting branch, as an int in ``[2, most]``.

    Both ends of each branch are recorded, so at least 2; a bool or a
    non-integer is a ``TypeError``. Shared by every method's fretting cycle; a
    method whose states cost more (the FEM: a contact solve each) passes a
    smaller ``most``.
    """
    return integer("states", states, 2, most)


def load_scale(punch: Any, P: Any, A: float, name: str = "P") -> None:
    """Refuse a load whose contact scale ``A P max(R1, R2, b)`` leaves ``LENGTH_RANGE**2``.

    The contact's half-width is about ``sqrt(2 A P R / pi)``; its square and
    cube must stay representable. ``P`` may be an array (the first offender
    is named).
    """
    lo, hi = LENGTH_RANGE[0] ** 2, LENGTH_RANGE[1] ** 2
    if isinstance(P, float):      # one load: the same product, in Python's floats (which do not warn)
        if lo <= A * P * max(punch.R1, punch.R2, punch.b) <= hi:
            return
    P = np.atleast_1d(np.asarray(P, dtype=float))
    with np.errstate(over="ignore", under="ignore"):
        scale = A * P * max(punch.R1, punch.R2, punch.b)
    out = (scale < lo) | (scale > hi)
    if out.any():
        i = int(np.argmax(out))
        raise InputError(
            f"`{name}` = {float(P.flat[i])!r} gives A P max(R1, R2, b) = {float(scale.flat[i]):.3g}, "
            f"outside [{lo:g}, {hi:g}] (length^2), the range this library computes in double precision")


#: the largest ``|Q|/(f P)`` a numerical stick zone is solved for: closer to full sliding
#: the stick zone is narrower than about 1e-3 of the contact and, where it straddles a
#: join, its equations are too ill-conditioned to converge (the SIE failed on 16 of 211
#: random cases with ``1 - |Q|/(fP)`` in [1e-12, 1e-6]); the closed form has no such limit
SLIP_RATIO_LIMIT = 1.0 - 1e-6


def shear_load(Q: Any, f: Any, P: float, name: str = "Q", what: str = "there is no stick zone",
               limit: float = 1.0) -> tuple[float, float]:
    """``(Q, f)`` as floats for a shear load on a contact carrying ``P``; refuse ``|Q| >= f P``.

    ``f`` must lie in :data:`LENGTH_RANGE`; ``Q`` (``name``) must be finite
    (``Q_max`` > 0). ``|Q| >= f P`` is a :class:`~threepart.errors.FullSlidingError`
    with the one wording of :func:`threepart.errors.full_sliding`; a numerical
    method passes ``limit=SLIP_RATIO_LIMIT`` and ``|Q|/(fP)`` above it is a
    ``FullSlidingError`` that names that limit. Shared by every method.
    """
    from ..errors import FullSlidingError, full_sliding

    Q = positive(name, Q) if name == "Q_max" else finite(name, Q)
    f = positive("f", f)
    if abs(Q) >= f * P:
        raise full_sliding(name, Q, f, P, what)
    ratio = abs(Q) / (f * P)
    if ratio > limit:
        raise FullSlidingError(
            f"|`{name}`|/(f P) = {ratio!r} is within {1 - limit:.0e} of full sliding, past "
            f"{limit!r} (threepart.problem.validate.SLIP_RATIO_LIMIT), the closest to full sliding this "
            "method resolves the stick zone; the closed form has no such limit")
    return Q, f

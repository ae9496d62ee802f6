"""Another code's pressure points as a result of the shared shape, and the file they come from.

Names
-----
PointsResult    -- a NormalResult whose pressure interpolates given points
from_points     -- build one: the ends from the data (square-root fit), P and s its moments
square_root_end -- the right end of a square-root pressure from its last loaded points
check_points    -- refuse points whose load or centroid overflows, and a tilt that is no small slope
read_pressure   -- the points ``(x, p, info)`` of a file, by the reader its suffix picks (threepart.readers)
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from threepart import readers
from threepart.results.fields import contact_run
from threepart.results import Diagnostics, NormalResult
from threepart.errors import InputError

__all__ = ["PointsResult", "from_points", "square_root_end", "check_points", "read_pressure"]


@dataclass(frozen=True)
class PointsResult(NormalResult):
    """A normal result from pressure points: ``pressure(x)`` interpolates them linearly.

    ``x_nodes`` and ``p_nodes`` are the points as given (sorted); the
    comparison samples the field there (:func:`reports.compare.sample_points`).
    ``P`` and ``s`` are the points' own load and centroid, ``a`` and ``c``
    their ends (see :func:`from_points`).
    """

    checks_answer = False    # another code's pressure, judged by the comparison, not refused

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)
    p_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """The points' pressure, linear between them and 0 outside ``[-a, c]``."""
        x = np.asarray(x, dtype=float)
        p = np.interp(x, self.x_nodes, np.maximum(self.p_nodes, 0.0), left=0.0, right=0.0)
        return np.where((x >= -self.a) & (x <= self.c), p, 0.0)


def square_root_end(x: np.ndarray, p: np.ndarray, k: int = 4) -> float:
    """The right end of a square-root pressure: the root of ``p^2``, linear over the last ``k`` nodes.

    ``x`` ascending; the contact is the loaded run of nodes that holds the peak
    (:func:`threepart.results.fields.contact_run`: a code's noise outside it, below
    :data:`~threepart.results.fields.CONTACT_LOAD` of the peak, is no contact), and the end lies
    between its last node and the next one.
    """
    on = contact_run(p)
    last = int(on[-1])
    j = on[max(0, len(on) - k):]
    hi = x[last + 1] if last + 1 < len(x) else x[last]
    if len(j) >= 2:
        slope, icpt = np.polyfit(x[j], p[j] ** 2, 1)
        if slope < 0:
            return float(np.clip(-icpt / slope, x[last], hi))
    return float(x[last])


def from_points(x: ArrayLike, p: ArrayLike, ref: NormalResult, *, alpha: float | None = None,
                ends: tuple[float, float] | None = None, method: str = "points",
                info: dict[str, Any] | None = None) -> PointsResult:
    """A :class:`PointsResult` of the case that ``ref`` solved.

    Parameters
    ----------
    x, p
        Positions (along the surface, the README's x) and pressures (>= 0
        compressive); at least 8 points, finite, two or more with ``p > 0``.
    ref
        The reference result of the same case: it gives the punch, ``A`` and
        the tilt mode, never a figure of the points.
    alpha
        The tilt, if the other code reports it; otherwise the reference's, and
        the comparison leaves ``alpha`` out.
    ends
        ``(a, c)``, if the other code locates them (CalculiX: from the gap);
        otherwise from the points.

    The ends ``a``, ``c`` come from the points (the root of ``p^2`` fitted over
    the last four loaded nodes at each end); ``P = ∫p dx`` and ``s = ∫x p dx / P``
    by the trapezoidal rule over the contact's pressures (the loaded run of nodes that
    holds the peak, :func:`threepart.results.fields.contact_run`).
    """
    x = np.asarray(x, dtype=float).ravel()
    p = np.asarray(p, dtype=float).ravel()
    if x.shape != p.shape:
        raise InputError(f"`x` and `p` must have the same length, not {x.size} and {p.size}")
    if x.size < 8:
        raise InputError(f"the pressure has {x.size} points; at least 8 are needed")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(p))):
        raise InputError("the pressure holds a non-finite x or p (NaN or inf)")
    check_points(x, p, alpha)
    order = np.argsort(x, kind="stable")
    x, p = x[order], p[order]
    if np.any(np.diff(x) <= 0):
        raise InputError("the pressure's `x` repeats a position; give each point once")
    if np.count_nonzero(p > 0) < 2:
        raise InputError("the pressure has fewer than 2 points with p > 0: no contact to judge")
    if ends is None:
        c = square_root_end(x, p)
        a = square_root_end(-x[::-1], p[::-1])       # the left end, mirrored
    else:
        a, c = (float(v) for v in ends)
    pp = np.zeros_like(p)                             # the contact's pressures; noise outside it is none
    run = contact_run(p)
    pp[run] = p[run]
    P = float(np.trapezoid(pp, x))
    s = float(np.trapezoid(x * pp, x) / P)
    return PointsResult(punch=ref.punch, A=ref.A, a=a, c=c,
                        alpha=float(ref.alpha if alpha is None else alpha), P=P, s=s,
                        tilt=ref.tilt, method=method,
                        diagnostics=Diagnostics(h=float(np.median(np.diff(x))), dofs=int(x.size)),
                        info=dict(info or {}, alpha_given=alpha is not None),
                        x_nodes=x, p_nodes=p)


def check_points(x: np.ndarray, p: np.ndarray, alpha: float | None) -> None:
    """Refuse points whose load or centroid overflows, and a tilt that is no small slope.

    ``x`` and ``p`` stay within :data:`threepart.problem.checks.LENGTH_RANGE` in magnitude
    (lengths and loads, so that ``∫p dx`` and ``∫x p dx`` stay finite); ``alpha``
    is finite and within :data:`threepart.problem.validate.SLOPE_LIMIT`.
    """
    from threepart.problem.checks import LENGTH_RANGE, finite
    from threepart.problem.validate import SLOPE_LIMIT

    hi = LENGTH_RANGE[1]
    for name, v in (("x", x), ("p", p)):
        if v.size and not float(np.max(np.abs(v))) <= hi:
            raise InputError(f"the pressure's `{name}` reaches {float(np.max(np.abs(v))):.3g} in "
                             f"magnitude, past {hi:g}, the range this library computes in double "
                             "precision (its load and centroid would overflow)")
    if alpha is not None and not abs(finite("alpha", alpha)) <= SLOPE_LIMIT:
        raise InputError(f"`alpha` = {alpha!r} exceeds the small-slope limit {SLOPE_LIMIT:g} of "
                         "half-plane theory in magnitude")



def read_pressure(path: str | Path, *, arg: str = "--pressure", **options: Any
                  ) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """The points of a pressure file: ``(x, p, info)``, read by :func:`threepart.readers.read`.

    The file's suffix picks its reader from the table of :mod:`threepart.readers`:
    ``.csv`` (columns ``x, p``), CalculiX's ``.frd`` and ``.dat`` (the nodal
    contact forces over the nodes' shares of the quadratic faces,
    :func:`threepart.calculix.read.contact_pressure`), and through meshio the
    VTU, XDMF, MED and Exodus files of FEniCSx/dolfinx, Code_Aster and MOOSE
    (a point field of the pressure on the contact surface; ``options``:
    ``field``, ``surface``, ...). ``info`` holds the source and what the reader
    knows besides (CalculiX: the forces, the penalty, the increments).
    """
    record = readers.read(path, arg=arg, **options)
    return record.x, record.p, record.info

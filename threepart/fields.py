"""The peak of a nodal field: one rule for every place that reads a peak off nodal values.

A method that returns a field at nodes (the FEM's ``p_nodes``, CalculiX's
surface pressures) has its peak read here; a field known as a function
(:meth:`threepart.results.NormalResult.peaks`) is refined by a bounded search
on the function itself instead.

peak  -- the peak ``(x, p)`` of nodal values ``p`` at ``x``
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["peak", "FIT_SAMPLES"]

#: points on which a least-squares fit is searched for its maximum, over ``± half_width``
FIT_SAMPLES = 2001


def peak(x: ArrayLike, p: ArrayLike, *, half_width: float | None = None, degree: int = 4,
         smooth: int = 5, passes: int = 2, symmetric: bool = False) -> tuple[float, float]:
    """The peak ``(x, p)`` of the nodal values ``p`` at the sorted positions ``x``.

    The rule depends on whether the nodal values scatter:

    - ``half_width`` None (a smooth field, e.g. the FEM's nodal pressures): the vertex of the
      parabola through the largest node and its two neighbours; the largest node itself at
      an end of the nodes, or where the three do not curve downward.
    - ``half_width`` given (values that scatter, e.g. CalculiX's nodal stresses): the maximum
      of the least-squares polynomial of ``degree`` over the nodes within ``half_width`` of the
      centre, on :data:`FIT_SAMPLES` points over ``± half_width``; the centre is first the node
      of the largest ``smooth``-node moving average (``smooth = 1``: the largest node), then,
      for each further of the ``passes``, the node nearest the previous fit's maximum.
    - ``symmetric`` (a field symmetric about ``x = 0``, with ``half_width``): the polynomial of
      degree ``degree`` in ``x`` with even powers only, fitted over ``|x| < half_width``, at
      ``x = 0``.

    Raises
    ------
    ValueError
        Fewer than ``degree + 2`` nodes within ``half_width``; ``symmetric`` without it.
    """
    xa, pa = np.asarray(x, float), np.asarray(p, float)
    if symmetric:
        if half_width is None:
            raise ValueError("`symmetric` needs a `half_width`: the even fit's")
        m = np.abs(xa) < half_width
        return 0.0, float(np.polyfit(xa[m] ** 2, pa[m], degree // 2)[-1])
    if half_width is None:
        return _vertex(xa, pa)
    if passes < 1 or smooth < 1:
        raise ValueError(f"`passes` = {passes} and `smooth` = {smooth} must be >= 1")
    i = int(np.argmax(np.convolve(pa, np.ones(smooth) / smooth, "same")))
    t = np.linspace(-half_width, half_width, FIT_SAMPLES)
    for _ in range(passes):
        m = np.abs(xa - xa[i]) < half_width
        if np.count_nonzero(m) < degree + 2:
            raise ValueError(f"`half_width` = {half_width:g} holds {np.count_nonzero(m)} nodes; "
                             f"the degree-{degree} fit needs at least {degree + 2}")
        v = np.polyval(np.polyfit(xa[m] - xa[i], pa[m], degree), t)
        j = int(np.argmax(v))
        x_peak, p_peak = float(xa[i] + t[j]), float(v[j])
        i = int(np.argmin(np.abs(xa - x_peak)))
    return x_peak, p_peak


def _vertex(x: np.ndarray, p: np.ndarray) -> tuple[float, float]:
    """The vertex of the parabola through the largest node and its neighbours (the node at an end)."""
    k = int(np.argmax(p))
    if k == 0 or k == p.size - 1:
        return float(x[k]), float(p[k])
    (x0, x1, x2), (p0, p1, p2) = x[k - 1:k + 2], p[k - 1:k + 2]
    d01, d12 = (p1 - p0) / (x1 - x0), (p2 - p1) / (x2 - x1)
    curve = (d12 - d01) / (x2 - x0)            # half the second derivative
    if not curve < 0:
        return float(x1), float(p1)
    xv = 0.5 * (x0 + x1) - d01 / (2 * curve)   # where the parabola's slope vanishes
    return float(xv), float(p1 + (xv - x1) * (d01 + curve * (xv - x0)))

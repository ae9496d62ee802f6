"""Nodal fields: one rule for every place that reads a peak or an edge off nodal values.

A method that returns a field at nodes (the FEM's ``p_nodes``, CalculiX's
surface pressures, another code's file read by :mod:`threepart.readers`) has its
peak and its edges' multipliers read here; a field known as a function
(:meth:`threepart.results.NormalResult.peaks`, a method's own ``edges``) is
evaluated on the function itself instead.

The edge multiplier: near an edge, ``p² = K_N² (r - r0) + O(r²)`` with ``r`` the
distance inside the contact's own end and ``r0`` that end's error, so ``K_N²``
is the slope at its root of a polynomial fitted to ``p²`` (the end's error drops
out). The fit skips the edge node (a lumped pressure carries the square-root
edge inside one element) and stops short of the nearer join ``x = ±b`` (the
pressure's ``(x ∓ b) ln|x ∓ b|``): at most :data:`JOIN_SHARE` of the way to it.
It is made on :data:`WINDOWS` nodes by polynomials of the degrees
:data:`DEGREES`; ``K_N`` is their median and its ``fit_error`` their largest
distance from it (docs/EDGES.md, E8).

peak             -- the peak ``(x, p)`` of nodal values ``p`` at ``x``
edge_multipliers -- ``((K_N, fit_error), (K_N, fit_error))`` at ``-a`` and ``c`` of nodal pressures
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..errors import InputError, MeshResolutionError

__all__ = ["peak", "FIT_SAMPLES", "edge_multipliers", "WINDOWS", "DEGREES", "JOIN_SHARE", "MIN_NODES",
           "stick_ends", "STICK_MARGIN", "STICK_NODES", "STICK_LOAD", "contact_run", "CONTACT_LOAD"]

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
            raise InputError("`symmetric` needs a `half_width`: the even fit's")
        m = np.abs(xa) < half_width
        return 0.0, float(np.polyfit(xa[m] ** 2, pa[m], degree // 2)[-1])
    if half_width is None:
        return _vertex(xa, pa)
    if passes < 1 or smooth < 1:
        raise InputError(f"`passes` = {passes} and `smooth` = {smooth} must be >= 1")
    i = int(np.argmax(np.convolve(pa, np.ones(smooth) / smooth, "same")))
    t = np.linspace(-half_width, half_width, FIT_SAMPLES)
    for _ in range(passes):
        m = np.abs(xa - xa[i]) < half_width
        if np.count_nonzero(m) < degree + 2:
            raise InputError(f"`half_width` = {half_width:g} holds {np.count_nonzero(m)} nodes; "
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


#: nodes after the edge node of each fit (the smaller windows resolve a short arc, the larger
#: average the nodal noise; their spread is the fit's error)
WINDOWS = (12, 18, 24, 32)
#: degrees of the polynomial in r fitted to p² (the second: K_N² r + the r² term; the third adds r³)
DEGREES = (2, 3)
#: share of the distance from the edge to the nearer join that a fit may span
JOIN_SHARE = 0.5
#: least nodes a fit needs (a third-degree fit and two to spare)
MIN_NODES = 6


def _one_edge(r: np.ndarray, p: np.ndarray, reach: float) -> tuple[float, float]:
    """``(K_N, fit_error)`` from nodal ``p`` at distances ``r`` inside one edge, fits within ``reach``."""
    keep = (r > 0) & (p > 0)
    order = np.argsort(r[keep])
    rs, ps = r[keep][order][1:], p[keep][order][1:]        # the edge node skipped
    rs, ps = rs[rs <= reach], ps[rs <= reach]
    if rs.size < MIN_NODES:
        raise MeshResolutionError(f"the FE mesh has {rs.size} nodes between the contact end and "
                                  f"{JOIN_SHARE:g} of the way to the join, fewer than the {MIN_NODES} "
                                  "the edge multiplier's fit needs: refine the mesh at the ends")
    windows = sorted({min(n, rs.size) for n in WINDOWS})   # distinct: a short run of nodes is one
    fits = [(m, deg) for m in windows for deg in DEGREES]
    Ks = []
    for m, deg in fits:
        coef = np.polyfit(rs[:m], ps[:m] ** 2, deg)
        root = -coef[-1] / coef[-2]
        slope = np.polyval(np.polyder(coef), root)
        if slope > 0:
            Ks.append(float(np.sqrt(slope)))
    if len(Ks) < 2 or 2 * len(Ks) < len(fits):
        raise MeshResolutionError(f"only {len(Ks)} of the {len(fits)} fits of p² near the contact "
                                  "end rise into the contact: the nodal pressure does not resolve "
                                  "the square-root edge there")
    K = float(np.median(Ks))
    return K, float(max(abs(k - K) for k in Ks))


def edge_multipliers(x: np.ndarray, p: np.ndarray, a: float, c: float, b: float
                     ) -> tuple[tuple[float, float], tuple[float, float]]:
    """``((K_N, fit_error), (K_N, fit_error))`` at ``-a`` and ``c`` from nodal pressures ``p`` at ``x``.

    Raises
    ------
    MeshResolutionError
        If fewer than :data:`MIN_NODES` nodes lie between an edge and
        :data:`JOIN_SHARE` of the way to the nearer join.
    """
    W = a + c
    joins_left = [j for j in (-b, b) if -a < j < c]
    reach_l = JOIN_SHARE * (min(joins_left) + a) if joins_left else W
    reach_r = JOIN_SHARE * (c - max(joins_left)) if joins_left else W
    return _one_edge(x + a, p, reach_l), _one_edge(c - x, p, reach_r)


#: a node sticks where ``1 - |q|/(f p)`` exceeds this: a penalty or augmented friction law leaves
#: the slip zones' nodes a little below ``f p`` (CalculiX's, GetFEM's), and they must not enter the fit
STICK_MARGIN = 0.02
#: the sticking nodes next to each end that the fit of ``(f p - |q|)^2`` takes (past the end's own):
#: ten average a field that oscillates from node to node (GetFEM's multiplier, +-8 % of ``f p*`` on
#: slip_Q0.4 at W/h = 64), which six followed (docs/GETFEM.md's table of the fits)
STICK_NODES = 10
#: nodes loaded below this fraction of the peak pressure are not judged: next to a contact end (within
#: ~1e-4 of its width) or outside it, where a code's noise in p makes q/p meaningless (GetFEM's
#: multiplier at W/h = 32: p ~ 1e-4 of the peak outside the contact, with |q|/(f p) = 0.98)
STICK_LOAD = 1e-2


#: nodes loaded below this fraction of the peak pressure are outside the contact: another code's noise
#: there (GetFEM's multiplier: p ~ 1e-4 of the peak outside the contact at W/h = 64) must not move its
#: ends. A node inside a square-root end at distance r carries p/p_max ~ sqrt(r/W), so this floor
#: leaves out only nodes within ~1e-6 W of an end, where the fit of p^2 lands anyway
CONTACT_LOAD = 1e-3


def contact_run(p: ArrayLike) -> np.ndarray:
    """The indices of the contact: the run of consecutive nodes loaded above :data:`CONTACT_LOAD` of the
    peak that holds the peak (nodes in order along the surface; empty if no node is loaded)."""
    p = np.asarray(p, dtype=float)
    top = float(np.max(p, initial=0.0))
    if not top > 0:
        return np.zeros(0, dtype=int)
    on = p > CONTACT_LOAD * top
    k = int(np.argmax(p))
    lo, hi = k, k
    while lo > 0 and on[lo - 1]:
        lo -= 1
    while hi + 1 < p.size and on[hi + 1]:
        hi += 1
    return np.arange(lo, hi + 1)


def stick_ends(x: ArrayLike, p: ArrayLike, q: ArrayLike, f: float, *, margin: float = STICK_MARGIN,
               k: int = STICK_NODES) -> tuple[float, float]:
    """The stick zone's ends of nodal tractions: where ``f p - |q|`` falls to 0, from a fit inside it.

    In a slip zone ``|q| = f p``; inside the stick zone ``|q| = f (p - p*)``, with
    ``p*`` the corrective pressure of eq. integral_equation_2 (Ciavarella–Jäger), the
    pressure of a contact on the stick zone alone, bounded at its ends: ``p*`` rises
    from each end as a square root times a smooth function, so ``p*^2 = (p - |q|/f)^2``
    is a low polynomial there (exactly ``∝ c^2 - x^2`` on Mindlin's traction). The
    stick zone is the longest run of nodes loaded above :data:`STICK_LOAD` of the peak
    whose ``1 - |q|/(f p)`` exceeds ``margin``; a polynomial of degree up to 2 is fitted
    to ``p*^2`` over ``k`` nodes of the run next to each end, and its root nearest them
    is the end if it lies between the run's end node and its outer neighbour, where the
    nodes place it; else the fit is not to be trusted (a field that oscillates from node
    to node: GetFEM's multiplier at W/h = 32) and the end is midway between them. The run's end
    node itself is left out of the fit when the run is longer than ``k + 1``: the element
    holding the end smears the kink over it (GetFEM at W/h = 64 on Hertz: ``p*`` 5 % high
    there, which moved the end by 3.3e-3 W; without it 4e-5 W). The ratio ``1 - |q|/(f p)``
    squared, fitted before over six nodes (it is not a polynomial where the stick zone's end
    nears the contact's), read the exact Mindlin traction at W/h = 64 2.3e-3 W off. ``x``
    ascending; ``(nan, nan)`` if fewer than two nodes stick.
    """
    x, p, q = (np.asarray(v, dtype=float) for v in (x, p, q))
    on = p > STICK_LOAD * float(np.max(p, initial=0.0))
    r = np.zeros(len(x))
    r[on] = 1.0 - np.abs(q[on]) / (f * p[on])
    sticks = (on & (r > margin)).astype(np.int8)
    edges = np.diff(np.concatenate(([0], sticks, [0])))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    if starts.size == 0 or int(np.max(stops - starts)) < 2:
        return math.nan, math.nan
    longest = int(np.argmax(x[stops - 1] - x[starts]))
    run = np.arange(starts[longest], stops[longest])
    corrective = (f * p - np.abs(q)) ** 2                  # (f p*)^2
    skip = 1 if run.size > k + 1 else 0
    ends = []
    for side, outer in ((run, run[0] - 1), (run[::-1], run[-1] + 1)):
        idx = side[skip:skip + k]
        lo, hi = sorted((float(x[side[0]]), float(x[min(max(outer, 0), len(x) - 1)])))
        roots = np.roots(np.polyfit(x[idx], corrective[idx], min(2, idx.size - 1)))
        roots = roots[np.isreal(roots)].real
        end = float(roots[np.argmin(np.abs(roots - x[side[0]]))]) if roots.size else math.nan
        ends.append(end if lo <= end <= hi else 0.5 * (lo + hi))
    return ends[0], ends[1]

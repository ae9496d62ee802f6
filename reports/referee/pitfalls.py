"""The known pitfalls of contact FE results, each found with the number that shows it.

Each limit is a row of the tolerance table's ``"referee-pitfall"`` group
(:mod:`threepart.tolerances`), with its reason there.

Names
-----
Pitfall     -- one diagnosed pitfall: its name, the number, the limit and what to do
diagnose    -- every pitfall a pressure shows against the case the reference solved
oscillation -- the amplitude of the node-to-node (odd-even) part of nodal values
NEGATIVE, LOAD, END_NODES, OSCILLATION, PENETRATION -- the limits, read from the table
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from threepart.output import json_safe
from threepart.results import NormalResult
from threepart.tolerances import tolerance

from ..compare import EDGE_FRACTION
from .points import PointsResult

__all__ = ["Pitfall", "diagnose", "oscillation", "NEGATIVE", "LOAD", "END_NODES", "OSCILLATION",
           "PENETRATION", "PITFALLS"]

#: the tolerance table's group of the pitfalls' limits
PITFALLS = "referee-pitfall"
#: tension (of the peak) above which negative pressures are reported
NEGATIVE = tolerance(PITFALLS, "negative").limit
#: |∫p - P| / P above which the load is reported
LOAD = tolerance(PITFALLS, "load").limit
#: fewest nodes within EDGE_FRACTION * W of a contact end that resolve it
END_NODES = int(tolerance(PITFALLS, "end_nodes").limit)
#: node-to-node oscillation (of the peak) above which the peak is the mesh's
OSCILLATION = tolerance(PITFALLS, "oscillation").limit
#: overclosure p_max / K (of the profile's rise over the contact) above which the penalty is reported
PENETRATION = tolerance(PITFALLS, "penetration").limit


@dataclass(frozen=True)
class Pitfall:
    """One pitfall a pressure shows: its name, the figure that shows it, and the message."""

    name: str
    value: float
    limit: float
    message: str

    def as_dict(self) -> dict[str, Any]:
        return json_safe({"name": self.name, "value": self.value, "limit": self.limit,
                          "message": self.message})


def oscillation(p: np.ndarray) -> float:
    """The amplitude of the node-to-node (odd-even) part of ``p``, zero when there is none.

    Half the second difference ``d_i = p_i - (p_{i-1} + p_{i+1})/2`` is that amplitude
    for ``p = smooth + eps (-1)^i``; its median is taken over the nodes where ``d``
    flips sign from node to node, if it does at most (>= 60 %) of them.
    """
    if p.size < 5:
        return 0.0
    d = p[1:-1] - 0.5 * (p[:-2] + p[2:])
    flips = np.sign(d[1:]) * np.sign(d[:-1]) < 0
    if flips.mean() < 0.6:
        return 0.0
    both = np.zeros_like(d, dtype=bool)
    both[1:] |= flips
    both[:-1] |= flips
    return float(0.5 * np.median(np.abs(d[both])))


def diagnose(res: PointsResult, ref: NormalResult, *, penalty: float | None = None) -> list[Pitfall]:
    """The known pitfalls ``res`` shows against the case ``ref`` solved, each with its number."""
    peak = float(max(pk.p for pk in ref.peaks()))
    out = _tension(res.p_nodes, peak) + _load(res, ref) + _increments(res) + _ends(res, ref)
    out += _mesh_peak(res, ref, peak)
    K = penalty if penalty is not None else res.info.get("penalty")
    if K is not None and math.isfinite(K) and K > 0:
        out += _penalty(res, ref, K)
    return out


def _tension(p: np.ndarray, peak: float) -> list[Pitfall]:
    tension = float(-min(p.min(), 0.0)) / peak
    if tension <= NEGATIVE:
        return []
    k = int(np.count_nonzero(p < -NEGATIVE * peak))
    return [Pitfall("negative-pressure", tension, NEGATIVE,
                    f"{k} points carry tension, down to -{tension:.3g} of the peak: a penalty "
                    "contact writes CPRESS = -K*COPEN at open nodes; read p only where the "
                    "contact is closed (COPEN <= 0) or use the nodal forces -2 CELS/COPEN "
                    "(*CONTACT PRINT CELS)")]


def _load(res: PointsResult, ref: NormalResult) -> list[Pitfall]:
    load = abs(res.P - ref.P) / ref.P
    if load <= LOAD:
        return []
    return [Pitfall("load", load, LOAD,
                    f"∫p dx = {res.P:.6g} differs from P = {ref.P:.6g} by {load:.3g} of P: "
                    "analyse the first increment (a later one re-pairs the surfaces on the "
                    "deformed geometry), check the thickness and a half model's factor 2")]


def _increments(res: PointsResult) -> list[Pitfall]:
    """The normal step cut into increments. A friction run's ``.frd`` gives each step's count
    (``{step: increments}``): its first step is the normal load, the later ones the shear's,
    loaded in increments by design."""
    steps = res.info.get("increments")
    if isinstance(steps, dict):
        steps = steps[min(steps)] if steps else None
    if steps is None or steps <= 1:
        return []
    return [Pitfall("increments", float(steps), 1.0,
                    f"the run took {steps} increments (its .sta): the whole load did not converge "
                    "in one, and each later increment pairs the faces again on the deformed "
                    "geometry; at large slopes or strains (the deck's header gives them) the "
                    "closed form's model does not hold either: scale the radii up and the load "
                    "down (docs/CALCULIX.md)")]


def _ends(res: PointsResult, ref: NormalResult) -> list[Pitfall]:
    x, p = res.x_nodes, res.p_nodes
    W = ref.a + ref.c
    margin = EDGE_FRACTION * W
    out = []
    for side, (lo, hi) in (("left", (-res.a, -res.a + margin)), ("right", (res.c - margin, res.c))):
        n = int(np.count_nonzero((p > 0) & (x >= lo) & (x <= hi)))
        if n < END_NODES:
            out.append(Pitfall("end-resolution", float(n), float(END_NODES),
                               f"the {side} end is resolved by {n} nodes within {EDGE_FRACTION:g} W "
                               f"(W = {W:.6g}) of it; refine there to at least {END_NODES}"))
    return out


def _mesh_peak(res: PointsResult, ref: NormalResult, peak: float) -> list[Pitfall]:
    x, p = res.x_nodes, res.p_nodes
    W = ref.a + ref.c
    inside = p > 0
    on = np.flatnonzero(inside)
    i_max = int(np.argmax(p))
    out = []
    if i_max <= on[0] + 1 or i_max >= on[-1] - 1:
        out.append(Pitfall("mesh-peak", float(abs(x[i_max] - (res.c if i_max >= on[-1] - 1 else -res.a)) / W),
                           0.0, f"the largest pressure sits at a node next to a contact end "
                                f"(x = {x[i_max]:.6g}): the mesh, not the solution, sets it"))
    osc = oscillation(p[inside]) / peak
    if osc > OSCILLATION:
        out.append(Pitfall("mesh-peak", osc, OSCILLATION,
                           f"the pressure oscillates from node to node by {osc:.3g} of the peak "
                           "(vertex against midside nodes of quadratic faces): a peak read at one "
                           "node carries that error; divide the nodal forces (-2 CELS/COPEN) by the nodes' "
                           "shares of the face, h/3 and 2h/3 (threepart compare does, given CELS)"))
    return out


def _penalty(res: PointsResult, ref: NormalResult, K: float) -> list[Pitfall]:
    p = res.p_nodes
    rise = float(np.max(ref.punch.profile(np.array([-ref.a, ref.c]))) - np.min(
        ref.punch.profile(np.linspace(-ref.a, ref.c, 201))))
    pen = float(p.max()) / K / rise if rise > 0 else math.inf
    if pen <= PENETRATION:
        return []
    return [Pitfall("penalty", pen, PENETRATION,
                    f"the penalty's overclosure p_max/K = {float(p.max()) / K:.3g} (a length, "
                    f"K = {K:.4g} read at the closed nodes) is "
                    f"{pen:.3g} of the profile's rise over the contact ({rise:.3g}); "
                    "the peak error falls as 1/K: rerun with 10 K and compare")]

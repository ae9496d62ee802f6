"""Another code's partial slip as a result of the shared shape, and the known friction pitfalls.

A file that carries the shear ``q`` beside the pressure ``p`` (CalculiX's CSTR, a
GetFEM or any VTU's ``contact_shear``, a CSV's third column) becomes a
:class:`SlipPointsResult`, a :class:`~threepart.results.SlipResult` whose normal
is the :class:`~.points.PointsResult` of its pressure and whose shear
interpolates its points. The verification run's own comparison then judges it
as it judges the SIE or the FEM (``d``, ``e``, ``q`` against the reference,
``∫q = Q``, Coulomb's bound, the stresses), and :func:`friction_pitfalls` names
what typically goes wrong in a frictional FE model, each with its number.

Names
-----
SlipPointsResult  -- a SlipResult whose shear interpolates given points
slip_from_points  -- build one: the stick zone's ends by threepart.results.fields.stick_ends
friction_pitfalls -- the friction pitfalls the points show against the reference
STICK_MARGIN (threepart.results.fields), SHIFT, SLOPE, SLIPPING (the tolerance table) -- the limits
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from threepart.errors import InputError
from threepart.results.fields import STICK_MARGIN, stick_ends
from threepart.results import SlipResult
from threepart.tolerances import tolerance

from .pitfalls import PITFALLS, Pitfall
from .points import from_points

__all__ = ["SlipPointsResult", "slip_from_points", "friction_pitfalls", "STICK_MARGIN", "SHIFT", "SLOPE",
           "SLIPPING"]

#: a stick zone shifted (of W) past this while its width is right names the normal-shear coupling
SHIFT = tolerance(PITFALLS, "stick_shift").limit
#: the stick slope's creep ``1/(K_t A W)`` past which the slope is named too soft
SLOPE = tolerance(PITFALLS, "stick_slope").limit
#: the fraction of the reference's slip zones that must slip in the points
SLIPPING = tolerance(PITFALLS, "slipping").limit


@dataclass(frozen=True)
class SlipPointsResult(SlipResult):
    """A partial-slip result from points: ``shear(x)`` interpolates them linearly.

    ``normal`` is the :class:`~.points.PointsResult` of the same points'
    pressure; ``Q`` is the applied shear force (the reference's), so that the
    comparison's ``∫q = Q`` judges the points; ``d``, ``e`` are the stick zone
    found in the points (:func:`threepart.results.fields.stick_ends`).
    """

    checks_answer = False    # another code's shear, judged by the comparison, not refused

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)
    q_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """The points' shear, linear between them and 0 outside ``[-a, c]``."""
        x = np.asarray(x, dtype=float)
        q = np.interp(x, self.x_nodes, self.q_nodes, left=0.0, right=0.0)
        return np.where((x >= -self.a) & (x <= self.c), q, 0.0)


def slip_from_points(x: ArrayLike, p: ArrayLike, q: ArrayLike, ref: SlipResult, *,
                     alpha: float | None = None, method: str = "points",
                     info: dict | None = None) -> SlipPointsResult:
    """A :class:`SlipPointsResult` of the partial slip ``ref`` solved (its Q and f).

    The normal part is :func:`~.points.from_points` of ``(x, p)``; the shear
    points must be as many as the pressure's and finite.
    """
    x = np.asarray(x, dtype=float).ravel()
    q = np.asarray(q, dtype=float).ravel()
    if q.shape != x.shape:
        raise InputError(f"`x` and `q` must have the same length, not {x.size} and {q.size}")
    if not np.all(np.isfinite(q)):
        raise InputError("the shear holds a non-finite q (NaN or inf)")
    normal = from_points(x, p, ref.normal, alpha=alpha, method=method, info=info)
    order = np.argsort(x, kind="stable")
    xs, qs = x[order], q[order]
    lo, hi = stick_ends(xs, normal.p_nodes, qs, ref.f)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise InputError(f"no two points stick (1 - |q|/(f p) > {STICK_MARGIN:g} at fewer than two): the "
                         "points slide as a whole, there is no stick zone to judge")
    return SlipPointsResult(normal=normal, Q=ref.Q, f=ref.f, d=0.5 * (hi - lo), e=-0.5 * (hi + lo),
                            method=method, sigma_bulk=ref.sigma_bulk,
                            diagnostics=normal.diagnostics, info=dict(normal.info),
                            x_nodes=xs, q_nodes=qs)


def friction_pitfalls(res: SlipPointsResult, ref: SlipResult, *,
                      stick_slope: float | None = None) -> list[Pitfall]:
    """The friction pitfalls ``res`` shows against the partial slip ``ref`` solved, each with its number.

    ``shear-sign``: ``∫q`` has the sign opposite to ``Q``. ``no-slip``: the
    points stick over most of the reference's slip zones. ``coupling``: the
    stick zone is shifted while its width is right. ``stick-slope``: the
    penalty in shear ``K_t`` (given, or read by the reader) lets the stick
    zone creep by more than :data:`SLOPE` of the elastic displacements.
    """
    W = ref.a + ref.c
    x, q = res.x_nodes, res.q_nodes
    integral = float(np.trapezoid(q, x))
    out = []
    if integral * ref.Q < 0:
        out.append(Pitfall("shear-sign", integral / ref.Q, 0.0,
                           f"∫q dx = {integral:.6g} against Q = {ref.Q:.6g}: the shear's sign is "
                           "flipped; threepart's q is the shear the punch exerts on the substrate "
                           "along +x (∫q dx = Q): a code's contact shear on the slave (lower) surface "
                           "often has the other sign"))
        return out      # the rest reads the sense of slip, which a flipped sign confuses
    slipping = _slipping_fraction(res, ref)
    if slipping < SLIPPING:
        out.append(Pitfall("no-slip", slipping, SLIPPING,
                           f"only {slipping:.3g} of the reference's slip zones slip in the points "
                           f"(|q| >= (1 - {STICK_MARGIN:g}) f p): the shear was not applied in full, "
                           "or a stick slope too soft creeps elastically instead of slipping"))
    shift = abs(res.e - ref.e) / W
    width = abs(res.d - ref.d) / W
    if shift > SHIFT and shift > 2.0 * width:
        out.append(Pitfall("coupling", shift, SHIFT,
                           f"the stick zone is shifted by {shift:.3g} W while its width is within "
                           f"{width:.3g} W: normal and shear couple, as under a rigid punch or "
                           "dissimilar bodies (Dundurs beta != 0); the half-plane theory here is that "
                           "of two similar elastic bodies: model the punch as an elastic body of the "
                           "substrate's material"))
    K_t = stick_slope if stick_slope is not None else res.info.get("stick_slope")
    if K_t is not None and math.isfinite(K_t) and K_t > 0:
        creep = 1.0 / (K_t * ref.normal.A * W)
        if creep > SLOPE:
            out.append(Pitfall("stick-slope", creep, SLOPE,
                               f"the stick slope K_t = {K_t:.4g} MPa/mm lets the stick zone creep by "
                               f"q/K_t, {creep:.3g} of the elastic displacements A q W across the "
                               f"contact: raise it to at least {1.0 / (SLOPE * ref.normal.A * W):.3g} "
                               "MPa/mm (CalculiX: the second number of *FRICTION)"))
    return out


def _slipping_fraction(res: SlipPointsResult, ref: SlipResult) -> float:
    """The fraction of the reference's slip zones' width where the points slip."""
    lo, hi = ref.stick_zone
    x = np.linspace(-ref.a, ref.c, 2001)[1:-1]
    outside = (x < lo) | (x > hi)
    if not outside.any():
        return 1.0
    p = res.pressure(x)
    slips = (p > 0) & (np.abs(res.shear(x)) >= (1.0 - STICK_MARGIN) * res.f * p)
    return float(np.count_nonzero(slips & outside) / np.count_nonzero(outside))

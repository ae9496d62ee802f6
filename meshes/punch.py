"""gmsh builder for a punch of real shape: flat centre, exact edge arcs, straight flanks, height H.

The punch stands on ``y = 0`` with its flat central segment ``[-b, b]``. Beyond
``x = ±b`` its lower face follows the circles of radius ``R1`` (left) and ``R2``
(right), tangent to the centre, up to the flank angle ``theta`` (the arc's
slope there is ``tan theta``); straight free flanks then continue the tangent up
to the top ``y = H``, where the punch is welded to its loading plate (group
``"base"``, clamped in the FE model, which adds the plate's rigid motion). A
``"parabola"`` profile replaces the circles by the paper's parabolas (eq. 2),
the map's control.

Inside the contact zone of a substrate spec the lower face has a vertex at
each of the substrate's surface vertices (:meth:`SubstrateSpec.contact_vertices`),
on the exact curve, one gmsh line per element: the two bodies' interface nodes
match, so :mod:`fem.finite` pairs them node by node. Physical groups: ``"contact"``
(the zone), ``"face"`` (the rest of the lower face), ``"flank"``, ``"base"``
(curves) and ``"punch"`` (the surface); the file holds one entity per group
(:func:`meshes.substrate.write_grouped`), which meshio reads in one block each.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import gmsh
import numpy as np

from .substrate import SubstrateSpec, gmsh_session, size_field, write_grouped
from threepart.errors import InputError, InputTypeError

__all__ = ["PunchSpec", "build_punch", "PROFILES"]

#: lower-face shapes beyond the central segment
PROFILES = ("arc", "parabola")


@dataclass(frozen=True)
class PunchSpec:
    """Parameters of a punch mesh (lengths in the units of the problem).

    Parameters
    ----------
    zone
        The substrate spec whose contact-zone vertices the punch's lower face matches.
    b, R1, R2
        Half-width of the flat centre and the edge radii.
    H
        Height of the punch (its top is welded to the loading plate).
    theta
        Flank angle (radians): where the edge arcs end and the straight flanks begin.
    profile
        ``"arc"`` (exact circles) or ``"parabola"`` (eq. 2).
    growth
        Size growth rate away from the contact zone.
    """

    zone: SubstrateSpec
    b: float
    R1: float
    R2: float
    H: float
    theta: float = math.pi / 4
    profile: str = "arc"
    growth: float = 0.15

    def __post_init__(self) -> None:
        for name in ("b", "R1", "R2", "H", "theta", "growth"):
            value = getattr(self, name)
            if isinstance(value, bool):
                raise InputTypeError(f"`{name}` = {value!r} must be a real number, not bool")
            if not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
                raise InputError(f"`{name}` = {value!r} must be a finite number >= 0")
        if self.R1 <= 0 or self.R2 <= 0 or self.H <= 0:
            raise InputError("`R1`, `R2` and `H` must be > 0")
        if not 0 < self.theta < math.pi / 2:
            raise InputError(f"`theta` = {self.theta!r} must lie in (0, pi/2)")
        if self.profile not in PROFILES:
            raise InputError(f"`profile` = {self.profile!r} must be one of {PROFILES}")
        lo, hi = self.edge_x("left"), self.edge_x("right")
        if not (lo < self.zone.x_lo and self.zone.x_hi < hi):
            raise InputError(f"the contact zone [{self.zone.x_lo:.6g}, {self.zone.x_hi:.6g}] must lie "
                             f"on the punch's lower face [{lo:.6g}, {hi:.6g}] (before the flanks)")
        top = float(np.max(self.height(np.array([self.zone.x_lo, self.zone.x_hi]))))
        if not top < 0.8 * self.H:
            raise InputError(f"`H` = {self.H!r} is too low: the contact zone rises to {top:.6g} "
                             "on the lower face (it must stay below 0.8 H)")

    def radius(self, side: str) -> float:
        return self.R1 if side == "left" else self.R2

    def edge_x(self, side: str) -> float:
        """Where the lower face ends on ``side``: at the flank angle, or at the top if that comes first."""
        R = self.radius(side)
        if self.profile == "arc":
            reach = R * math.sin(self.theta)
            if R * (1 - math.cos(self.theta)) >= self.H:     # the arc reaches the top first
                reach = math.sqrt(max(R * R - (R - self.H) ** 2, 0.0))
        else:
            reach = min(R * math.tan(self.theta), math.sqrt(2 * R * self.H))
        x = self.b + reach
        return -x if side == "left" else x

    def height(self, x: np.ndarray) -> np.ndarray:
        """Height of the lower face above ``y = 0`` at ``x`` (on the face, before the flanks)."""
        x = np.asarray(x, dtype=float)
        over = np.maximum(np.abs(x) - self.b, 0.0)
        R = np.where(x < 0, self.R1, self.R2)
        if self.profile == "parabola":
            return over**2 / (2 * R)
        return R - np.sqrt(np.maximum(R * R - over * over, 0.0))


def _geometry(spec: PunchSpec) -> dict[str, list[int]]:
    geo = gmsh.model.geo
    xs = spec.zone.contact_vertices()
    ys = spec.height(xs)
    zone_pts = [geo.addPoint(float(x), float(y), 0.0) for x, y in zip(xs, ys)]
    contact = [geo.addLine(p, q) for p, q in zip(zone_pts[:-1], zone_pts[1:])]
    face: list[int] = []
    flank: dict[str, list[int]] = {"right": [], "left": []}
    ends = {}
    for side, start in (("right", zone_pts[-1]), ("left", zone_pts[0])):
        xe = spec.edge_x(side)
        ye = float(spec.height(np.array([xe]))[0])
        end = geo.addPoint(xe, ye, 0.0)
        if spec.profile == "arc":
            sign = 1.0 if side == "right" else -1.0
            centre = geo.addPoint(sign * spec.b, spec.radius(side), 0.0)
            face.append(geo.addCircleArc(start, centre, end) if side == "right"
                        else geo.addCircleArc(end, centre, start))
        else:
            x0 = spec.zone.x_hi if side == "right" else spec.zone.x_lo
            xm = np.linspace(x0, xe, 12)[1:-1]
            mids = [geo.addPoint(float(x), float(spec.height(np.array([x]))[0]), 0.0) for x in xm]
            chain = [start, *mids, end] if side == "right" else [end, *mids[::-1], start]
            face.append(geo.addSpline(chain))
        if ye >= spec.H * (1 - 1e-12):   # the face reaches the top: no flank on this side
            ends[side] = end
            continue
        # the flank continues the face's tangent (slope tan theta) up to the top
        xt = xe + (1.0 if side == "right" else -1.0) * (spec.H - ye) / math.tan(spec.theta)
        top = geo.addPoint(xt, spec.H, 0.0)
        flank[side].append(geo.addLine(end, top) if side == "right" else geo.addLine(top, end))
        ends[side] = top
    base = geo.addLine(ends["right"], ends["left"])
    # counter-clockwise: zone (left to right), right face, right flank, top, left flank, left face
    loop = geo.addCurveLoop([*contact, face[0], *flank["right"], base, *flank["left"], face[1]])
    surface = geo.addPlaneSurface([loop])
    geo.synchronize()
    for tag in contact:
        gmsh.model.mesh.setTransfiniteCurve(tag, 2)
    groups = {"contact": contact, "face": face, "flank": flank["right"] + flank["left"],
              "base": [base]}
    for name, tags in groups.items():
        if not tags:
            continue
        gmsh.model.addPhysicalGroup(1, tags, name=name)
    gmsh.model.addPhysicalGroup(2, [surface], name="punch")
    return {**groups, "punch": [surface]}


def _size_field(spec: PunchSpec, contact: list[int]) -> None:
    """The zone's sizes on the punch's face, refined around its points at the face's height."""
    zone = spec.zone
    points = tuple((x0, float(spec.height(np.array([x0]))[0]))
                   for x0 in (zone.refine_at if zone.graded else ()))
    size_field(contact, h=zone.h, growth=spec.growth, sampling=4, refine_at=points, h_fine=zone.h_fine,
               size_max=max(spec.H, spec.edge_x("right") - spec.edge_x("left")) / 8)


def build_punch(spec: PunchSpec, path: str | Path) -> Path:
    """Mesh the punch with gmsh and write it to ``path`` (``.msh``, MSH 4.1, physical groups)."""
    path = Path(path)
    with gmsh_session():
        gmsh.model.add("punch")
        groups = _geometry(spec)
        _size_field(spec, groups["contact"])
        gmsh.model.mesh.generate(2)
        surface = groups.pop("punch")[0]
        write_grouped(path, groups, ("punch", surface))
    return path

"""gmsh builder for the plane-strain substrate block under a rigid punch.

The block occupies ``[-L/2, L/2] x [-L, 0]`` (the surface is ``y = 0``). The
top is split into the *contact* zone ``[x_lo, x_hi]``, where the candidate
contact nodes live and the element size is ``h``, and the free *top* outside it.
Points are placed at the zone ends and at every breakpoint (the punch's ``x = ±b``
and, when they are known, the contact ends), so the surface has nodes there. Away
from the zone the size grows linearly with the distance to it, ``h + growth * d``,
up to ``h_max``.

Where the contact pressure is not smooth -- the square-root decay at a contact end,
the logarithmic kink at a join ``x = ±b`` -- a spec may ask for finer elements:
around each point of ``refine_at`` the size is ``h_fine + growth * r`` (``r`` the
distance to the point), on the surface and in the body alike. The surface nodes
of a graded zone are placed by this module (:meth:`SubstrateSpec.surface_nodes`),
so that a spec mirrored about ``x = 0`` has mirrored surface nodes.

Physical groups, looked up by name: ``"contact"``, ``"top"``, ``"base"``,
``"left"``, ``"right"`` (curves) and ``"substrate"`` (the surface).
"""
from __future__ import annotations

import contextlib
import math
import numbers
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

import gmsh
import numpy as np
from threepart.errors import InputError, InputTypeError

__all__ = ["SubstrateSpec", "build_substrate", "gmsh_session", "size_field", "write_grouped",
           "PHYSICAL_CURVES"]

#: Bounds that keep a mesh within this machine's memory and time: the size growth rate
#: away from the zone, the zone's elements, the block in elements of the zone, and
#: the end refinement. The FE presets (``fem.mesh.PRESET_BOUNDS``) stay inside them.
GROWTH_RANGE = (0.01, 10.0)
MAX_ZONE_ELEMENTS = 20_000
MAX_BLOCK_RATIO = 1e8
MAX_FINE_RATIO = 1e4

#: Names of the physical curve groups, in the order they are created.
PHYSICAL_CURVES = ("contact", "top", "base", "left", "right")


@dataclass(frozen=True)
class SubstrateSpec:
    """Parameters of a substrate mesh (all lengths in the units of the punch).

    Parameters
    ----------
    x_lo, x_hi
        Ends of the refined contact zone on the surface, ``x_lo < x_hi``.
    h
        Element size inside the contact zone (uniform along the surface).
    L
        Width and depth of the block; the zone must lie inside ``(-L/2, L/2)``.
    growth
        Linear size growth rate away from the zone, ``size = h + growth * d``.
    h_max
        Largest element size; ``0`` means ``L / 20``.
    breakpoints
        Surface points inside the zone that must be mesh nodes (``x = ±b``).
    refine_at
        Surface points around which the size falls to ``h_fine`` (contact ends, joins).
    h_fine
        Element size at the ``refine_at`` points; ``0`` means no refinement (a uniform zone).

    Notes
    -----
    Bounds: ``growth`` in :data:`GROWTH_RANGE`, at most :data:`MAX_ZONE_ELEMENTS`
    along the zone, ``L / h`` at most :data:`MAX_BLOCK_RATIO`, ``h / h_fine`` at
    most :data:`MAX_FINE_RATIO`. A bool or a non-number is a ``TypeError``.
    """

    x_lo: float
    x_hi: float
    h: float
    L: float
    growth: float = 0.15
    h_max: float = 0.0
    breakpoints: tuple[float, ...] = field(default_factory=tuple)
    refine_at: tuple[float, ...] = field(default_factory=tuple)
    h_fine: float = 0.0

    def __post_init__(self) -> None:
        for name in ("x_lo", "x_hi", "h", "L", "growth", "h_max", "h_fine"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise InputTypeError(f"`{name}` = {value!r} must be a real number, not "
                                f"{type(value).__name__}")
            if not math.isfinite(value):
                raise InputError(f"`{name}` = {value!r} must be a finite number")
        if not self.x_hi > self.x_lo:
            raise InputError(f"`x_hi` = {self.x_hi!r} must exceed `x_lo` = {self.x_lo!r}")
        if self.h <= 0 or self.h > self.x_hi - self.x_lo:
            raise InputError(f"`h` = {self.h!r} must be > 0 and <= the zone length "
                             f"{self.x_hi - self.x_lo!r}")
        if not (-self.L / 2 < self.x_lo and self.x_hi < self.L / 2):
            raise InputError(f"`L` = {self.L!r} is too small: the zone [{self.x_lo}, {self.x_hi}] "
                             f"must lie inside (-L/2, L/2)")
        lo, hi = GROWTH_RANGE
        if not lo <= self.growth <= hi:
            raise InputError(f"`growth` = {self.growth!r} must lie in [{lo:g}, {hi:g}]: a slower "
                             "growth away from the zone fills the block with elements")
        if self.h_max < 0:
            raise InputError(f"`h_max` = {self.h_max!r} must be >= 0 (0 means L/20)")
        if not (isinstance(self.h_fine, (int, float)) and 0 <= self.h_fine <= self.h):
            raise InputError(f"`h_fine` = {self.h_fine!r} must lie in [0, h = {self.h!r}] "
                             "(0: no refinement)")
        for x in (*self.breakpoints, *self.refine_at):
            if not isinstance(x, (int, float)) or not math.isfinite(x):
                raise InputError(f"breakpoint or `refine_at` point {x!r} must be a finite number")
        zone = (self.x_hi - self.x_lo) / self.h
        if zone > MAX_ZONE_ELEMENTS:
            raise InputError(f"`h` = {self.h!r} puts {zone:.3g} elements along the zone "
                             f"[{self.x_lo!r}, {self.x_hi!r}], more than {MAX_ZONE_ELEMENTS}")
        if self.L / self.h > MAX_BLOCK_RATIO:
            raise InputError(f"`L` = {self.L!r} is {self.L / self.h:.3g} elements `h`, more than "
                             f"{MAX_BLOCK_RATIO:g}: the block's coordinates would swamp the zone's")
        if self.h_fine > 0 and self.h / self.h_fine > MAX_FINE_RATIO:
            raise InputError(f"`h_fine` = {self.h_fine!r} is {self.h / self.h_fine:.3g} times "
                             f"finer than `h`, more than {MAX_FINE_RATIO:g}")

    @property
    def graded(self) -> bool:
        """Whether the zone is refined around ``refine_at`` (else uniform ``h``)."""
        return self.h_fine > 0 and len(self.refine_at) > 0

    def size(self, x: np.ndarray) -> np.ndarray:
        """Element size along the surface inside the zone: ``h``, refined around ``refine_at``."""
        x = np.asarray(x, dtype=float)
        size = np.full(x.shape, float(self.h))
        if self.graded:
            for x0 in self.refine_at:
                size = np.minimum(size, self.h_fine + self.growth * np.abs(x - x0))
        return size

    def surface_nodes(self) -> np.ndarray:
        """Vertex positions along the zone: the surface points, and between them nodes of size :meth:`size`.

        Each piece between consecutive surface points gets ``ceil`` of its
        integrated ``1 / size`` elements, placed at equal steps of that integral,
        so the nodes of a spec mirrored about ``x = 0`` are mirrored too.
        """
        pts = self.surface_points()
        out = [np.array([pts[0]])]
        for x0, x1 in zip(pts[:-1], pts[1:]):
            xs = np.linspace(x0, x1, 4097)
            density = 1.0 / self.size(xs)
            cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1])
                                                   * np.diff(xs))])
            n_el = max(1, math.ceil(cum[-1] - 1e-9))
            inner = np.interp(np.linspace(0.0, cum[-1], n_el + 1)[1:-1], cum, xs)
            out.append(np.concatenate([inner, [x1]]))
        return np.concatenate(out)

    def contact_vertices(self) -> np.ndarray:
        """The mesh's vertex positions along the contact zone, as :func:`build_substrate` places them.

        Graded: :meth:`surface_nodes`; uniform: each piece between surface
        points split into ``ceil(length / h)`` equal elements.
        """
        if self.graded:
            return self.surface_nodes()
        pts = self.surface_points()
        pieces = [np.linspace(x0, x1, max(1, math.ceil((x1 - x0) / self.h - 1e-9)) + 1)[:-1]
                  for x0, x1 in zip(pts[:-1], pts[1:])]
        return np.concatenate([*pieces, [pts[-1]]])

    @property
    def size_max(self) -> float:
        """The effective largest element size."""
        return self.h_max if self.h_max > 0 else self.L / 20

    def surface_points(self) -> list[float]:
        """Zone ends and the breakpoints strictly inside the zone, sorted."""
        tol = 1e-9 * (self.x_hi - self.x_lo)
        inner = sorted({float(x) for x in self.breakpoints
                        if self.x_lo + tol < x < self.x_hi - tol})
        inner = [x for i, x in enumerate(inner) if i == 0 or x - inner[i - 1] > tol]
        return [self.x_lo, *inner, self.x_hi]


@contextlib.contextmanager
def gmsh_session() -> Iterator[None]:
    """Initialize gmsh quietly and always finalize it, even when an error is raised."""
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.option.setNumber("General.NumThreads", 1)
        yield
    finally:
        gmsh.finalize()


def _geometry(spec: SubstrateSpec) -> dict[str, list[int]]:
    """Create points and curves of the block; return curve tags per physical name."""
    geo = gmsh.model.geo
    half, depth = spec.L / 2, spec.L
    xs = list(spec.surface_nodes()) if spec.graded else spec.surface_points()
    top_pts = [geo.addPoint(x, 0.0, 0.0) for x in xs]
    right_top = geo.addPoint(half, 0.0, 0.0)
    right_bot = geo.addPoint(half, -depth, 0.0)
    left_bot = geo.addPoint(-half, -depth, 0.0)
    left_top = geo.addPoint(-half, 0.0, 0.0)

    contact = [geo.addLine(p, q) for p, q in zip(top_pts[:-1], top_pts[1:])]
    top_right = geo.addLine(top_pts[-1], right_top)
    right = geo.addLine(right_top, right_bot)
    base = geo.addLine(right_bot, left_bot)
    left = geo.addLine(left_bot, left_top)
    top_left = geo.addLine(left_top, top_pts[0])
    loop = geo.addCurveLoop([*contact, top_right, right, base, left, top_left])
    surface = geo.addPlaneSurface([loop])
    geo.synchronize()

    # uniform spacing h on each contact sub-segment, ending exactly on the points; a
    # graded zone has one segment per element, placed by SubstrateSpec.surface_nodes
    for tag, (x0, x1) in zip(contact, zip(xs[:-1], xs[1:])):
        n_el = 1 if spec.graded else max(1, math.ceil((x1 - x0) / spec.h - 1e-9))
        gmsh.model.mesh.setTransfiniteCurve(tag, n_el + 1)

    groups = {"contact": contact, "top": [top_left, top_right], "base": [base],
              "left": [left], "right": [right]}
    for name in PHYSICAL_CURVES:
        gmsh.model.addPhysicalGroup(1, groups[name], name=name)
    gmsh.model.addPhysicalGroup(2, [surface], name="substrate")
    groups["substrate"] = [surface]
    return groups


def size_field(contact: list[int], *, h: float, growth: float, sampling: int,
               refine_at: tuple[tuple[float, float], ...] = (), h_fine: float = 0.0,
               size_max: float) -> None:
    """gmsh's background size: ``h + growth * distance(contact)``, refined around points.

    Around each point ``(x0, y0)`` of ``refine_at`` the size is
    ``h_fine + growth * |(x, y) - (x0, y0)|`` (the exact distance); the smallest
    size wins, capped at ``size_max``. Shared by the substrate and the punch.
    """
    fld = gmsh.model.mesh.field
    dist = fld.add("Distance")
    fld.setNumbers(dist, "CurvesList", contact)
    fld.setNumber(dist, "Sampling", sampling)
    size = fld.add("MathEval")
    fld.setString(size, "F", f"{h!r} + {growth!r} * F{dist}")
    if refine_at:
        sizes = [size]
        for x0, y0 in refine_at:
            sizes.append(fld.add("MathEval"))
            fld.setString(sizes[-1], "F", f"{h_fine!r} + {growth!r} * "
                                          f"Sqrt((x - ({x0!r}))^2 + (y - ({y0!r}))^2)")
        size = fld.add("Min")
        fld.setNumbers(size, "FieldsList", sizes)
    fld.setAsBackgroundMesh(size)
    opt = gmsh.option.setNumber
    # otherwise the boundary/point sizes override the field
    opt("Mesh.MeshSizeExtendFromBoundary", 0)
    opt("Mesh.MeshSizeFromPoints", 0)
    opt("Mesh.MeshSizeFromCurvature", 0)
    opt("Mesh.MeshSizeMax", size_max)
    opt("Mesh.MeshSizeMin", h_fine if refine_at else h)
    opt("Mesh.Algorithm", 6)  # Frontal-Delaunay: good quality, deterministic
    opt("Mesh.ElementOrder", 1)  # fem raises the order (P2 on straight edges)
    opt("Mesh.MshFileVersion", 4.1)


def write_grouped(path: Path, curves: dict[str, list[int]], surface: tuple[str, int]) -> None:
    """Write the meshed model to ``path`` as one gmsh entity per physical group.

    A graded contact zone is built of one curve per element (the element ends are
    placed exactly), and MSH 4.1 writes each curve, and each of its end points, as
    an entity block of its own, which meshio reads one by one (most of its time on
    such a mesh). The same nodes, in the order gmsh would write them (those of no
    element of a group left out, as gmsh leaves them out), and the same elements
    in their order are moved into one discrete surface holding every node and one
    discrete curve per group of ``curves``; ``surface`` names the triangles'
    group and its entity.
    """
    model = gmsh.model
    tags, xyz, _ = model.mesh.getNodes()
    blocks: dict[str, tuple[int, int, np.ndarray]] = {}
    for name, dim, entities in [(surface[0], 2, [surface[1]]),
                                *((n, 1, ts) for n, ts in curves.items() if ts)]:
        kind = 2 if dim == 2 else 1       # gmsh's element types: 3-node triangle, 2-node line
        per_entity = [model.mesh.getElementsByType(kind, e)[1] for e in entities]
        blocks[name] = (dim, kind, np.concatenate(per_entity).astype(np.int64))
    used = np.zeros(int(tags.max()) + 1, dtype=bool)
    for _, _, nodes in blocks.values():
        used[nodes] = True
    keep = used[tags.astype(np.int64)]
    renumber = np.zeros(used.size, dtype=np.int64)
    renumber[tags[keep].astype(np.int64)] = np.arange(1, int(keep.sum()) + 1)
    model.add(f"{model.getCurrent()}-grouped")
    body = model.addDiscreteEntity(2)
    model.mesh.addNodes(2, body, renumber[tags[keep].astype(np.int64)],
                        xyz.reshape(-1, 3)[keep].ravel())
    for name, (dim, kind, nodes) in blocks.items():
        entity = body if dim == 2 else model.addDiscreteEntity(1)
        model.mesh.addElementsByType(entity, kind, [], renumber[nodes])
        model.addPhysicalGroup(dim, [entity], name=name)
    gmsh.write(str(path))


def _size_field(spec: SubstrateSpec, contact: list[int]) -> None:
    """Size ``h + growth * distance(contact zone)``, refined around ``refine_at``, capped at ``size_max``."""
    n_zone = (spec.x_hi - spec.x_lo) / spec.h
    size_field(contact, h=spec.h, growth=spec.growth,
               sampling=4 if spec.graded else int(max(20, 2 * n_zone / len(contact))),
               refine_at=tuple((x0, 0.0) for x0 in spec.refine_at) if spec.graded else (),
               h_fine=spec.h_fine, size_max=spec.size_max)


def build_substrate(spec: SubstrateSpec, path: str | Path) -> Path:
    """Mesh the substrate block with gmsh and write it to ``path`` (``.msh``).

    Parameters
    ----------
    spec
        Mesh parameters.
    path
        Output file; its parent directory must exist.

    Returns
    -------
    Path
        ``path``, written in MSH 4.1 with the physical groups of this module.
    """
    path = Path(path)
    with gmsh_session():
        gmsh.model.add("substrate")
        groups = _geometry(spec)
        _size_field(spec, groups["contact"])
        gmsh.model.mesh.generate(2)
        surface = groups.pop("substrate")[0]
        write_grouped(path, groups, ("substrate", surface))
    return path

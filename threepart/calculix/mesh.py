"""The meshes of CalculiX's models, built with gmsh: the half model and the whole and finite models.

Names
-----
Mesh               -- a two-body plane mesh of the small-slope benchmark's half model
build_half_mesh    -- the half model ``x >= 0`` of a symmetric punch (second order)
Model              -- a whole two-body plane mesh of a punch on a block, ready for ``write_deck``
build_model        -- the whole-model two-body gmsh mesh (second order) of a three-part punch
build_finite_model -- the validity map's finite punch (exact arcs, flanks, height H) on its block, or its half
GMSH_TO_CCX        -- gmsh element type -> (CalculiX element, number of corner nodes)
MASTER_RATIO       -- the punch's (master) element size over the block's (slave) at the contact
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..problem.punch import Punch
from ..problem.checks import positive
from .deck import DeckSettings
from threepart.errors import InputError, InputTypeError

__all__ = ["Mesh", "build_half_mesh", "Model", "build_model", "build_finite_model", "GMSH_TO_CCX",
           "MASTER_RATIO"]

#: the punch's (master) element size over the block's (slave) at the contact
MASTER_RATIO = 1.37
#: gmsh element type -> (CalculiX element, number of corner nodes)
GMSH_TO_CCX = {16: ("CPE8", 4), 9: ("CPE6", 3)}


# --------------------------------------------------------------------------- mesh
@dataclass
class Mesh:
    """A two-body plane mesh, half model ``x >= 0``, ready for a CalculiX deck.

    Attributes
    ----------
    xy
        Node coordinates, row ``i`` is node ``i + 1``.
    elements
        ``{body: [(ccx type, connectivity 1-based), ...]}`` for ``"block"`` and ``"punch"``.
    nsets
        Named node sets (1-based node numbers).
    master
        The punch's contact faces as ``(element number, face label "S1".."S4")``.
    slave
        The block's top faces over the fine zone, likewise.
    h0
        Element size at the contact.
    """

    xy: np.ndarray
    elements: dict[str, list[tuple[str, np.ndarray]]]
    nsets: dict[str, np.ndarray]
    master: list[tuple[int, str]]
    slave: list[tuple[int, str]]
    h0: float
    numbers: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def n_elements(self) -> int:
        return sum(len(v) for v in self.elements.values())


def build_half_mesh(punch: Punch, a: float, *, h0: float, x_fine: float, grading: float = 0.25,
               block: float = 20.0) -> Mesh:
    """Mesh the half model: the punch's right half above ``y = 0``, the block below.

    Parameters
    ----------
    punch
        Symmetric punch (``R1 = R2``); its right half is the flat ``[0, b]``
        and the arc of radius ``R2`` up to its quarter point (eq. 2).
    a
        Expected contact half-width: it sets the block, ``block * a`` wide
        (the half) and ``2 * block * a`` deep, so the whole block is
        ``20 W`` wide and deep for ``block = 20``.
    h0
        Element size on both surfaces over ``0 <= x <= x_fine``.
    x_fine
        End of the fine zone on both surfaces.
    grading
        Growth of the element size with the distance from the fine zone.
    """
    import gmsh

    from ..meshes import gmsh_session

    b, R2 = punch.b, punch.R2
    Lx, D = block * a, 2 * block * a
    with gmsh_session():
        occ = gmsh.model.occ
        # block: top split at x_fine
        p = [occ.addPoint(0, 0, 0), occ.addPoint(x_fine, 0, 0), occ.addPoint(Lx, 0, 0),
             occ.addPoint(Lx, -D, 0), occ.addPoint(0, -D, 0)]
        lb = [occ.addLine(p[i], p[(i + 1) % 5]) for i in range(5)]
        s_block = occ.addPlaneSurface([occ.addCurveLoop(lb)])
        # punch: flat [0, b], arc of radius R2 centred (b, R2) split at x_fine, top y = R2
        q0 = occ.addPoint(0, 0, 0)
        qc = occ.addPoint(b, R2, 0)
        th = math.asin(min((x_fine - b) / R2, 1.0))
        qf = occ.addPoint(b + R2 * math.sin(th), R2 * (1 - math.cos(th)), 0)
        qe = occ.addPoint(b + R2, R2, 0)
        qt = occ.addPoint(0, R2, 0)
        curves, fine = [], []
        if b > 0:
            qb = occ.addPoint(b, 0, 0)
            curves.append(occ.addLine(q0, qb))
            fine.append(curves[-1])
            start = qb
        else:
            start = q0
        curves.append(occ.addCircleArc(start, qc, qf))
        fine.append(curves[-1])
        curves.append(occ.addCircleArc(qf, qc, qe))
        coarse_arc = curves[-1]
        top = occ.addLine(qe, qt)
        sym = occ.addLine(qt, q0)
        s_punch = occ.addPlaneSurface([occ.addCurveLoop(curves + [top, sym])])
        occ.synchronize()

        groups = {"block": (2, [s_block]), "punch": (2, [s_punch]),
                  "block_top": (1, [lb[0], lb[1]]), "block_fine": (1, [lb[0]]),
                  "block_bottom": (1, [lb[3]]), "block_sym": (1, [lb[4]]),
                  "punch_contact": (1, fine + [coarse_arc]), "punch_fine": (1, fine),
                  "punch_top": (1, [top]), "punch_sym": (1, [sym])}
        tags = {name: gmsh.model.addPhysicalGroup(dim, ents, name=name)
                for name, (dim, ents) in groups.items()}

        _half_size_field(gmsh, [lb[0]] + fine, h0=h0, x_fine=x_fine, h_max=D / 8, grading=grading)

        xy, elements, nsets = _collect(gmsh, {"block": s_block, "punch": s_punch}, tags,
                                       ("block_top", "block_fine", "block_bottom", "block_sym",
                                        "punch_contact", "punch_fine", "punch_top", "punch_sym"))

    # number the elements, block first, and find the punch's faces on its contact curves
    numbers, n = {}, 0
    for body in ("block", "punch"):
        numbers[body] = np.arange(n + 1, n + 1 + len(elements[body]))
        n += len(elements[body])
    master = face_elements(elements["punch"], numbers["punch"], nsets["punch_contact"], xy, x_fine)
    slave = face_elements(elements["block"], numbers["block"], nsets["block_fine"], xy, x_fine)
    return Mesh(xy, elements, nsets, master, slave, h0, numbers)


def _half_size_field(gmsh: Any, curves: list[int], *, h0: float, x_fine: float, h_max: float,
                     grading: float) -> None:
    """Mesh the half model: ``h0`` along ``curves`` growing by ``grading`` to ``h_max``, second order."""
    f_dist = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(f_dist, "CurvesList", curves)
    gmsh.model.mesh.field.setNumber(f_dist, "Sampling", int(4 * x_fine / h0) + 10)
    f_th = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(f_th, "InField", f_dist)
    gmsh.model.mesh.field.setNumber(f_th, "SizeMin", h0)
    gmsh.model.mesh.field.setNumber(f_th, "SizeMax", h_max)
    gmsh.model.mesh.field.setNumber(f_th, "DistMin", 0.5 * h0)
    gmsh.model.mesh.field.setNumber(f_th, "DistMax", 0.5 * h0 + (h_max - h0) / grading)
    gmsh.model.mesh.field.setAsBackgroundMesh(f_th)
    for name, value in [("Mesh.MeshSizeExtendFromBoundary", 0), ("Mesh.MeshSizeFromPoints", 0),
                        ("Mesh.MeshSizeFromCurvature", 0), ("Mesh.Algorithm", 8),
                        ("Mesh.RecombineAll", 1), ("Mesh.RecombinationAlgorithm", 1),
                        ("Mesh.SecondOrderIncomplete", 1)]:
        gmsh.option.setNumber(name, value)
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(2)


def face_elements(elements: list[tuple[str, np.ndarray]], numbers: np.ndarray, on: np.ndarray,
           xy: np.ndarray, x_max: float) -> list[tuple[int, str]]:
    """Element faces ``(element, "Sk")`` with both corners in the node set ``on`` and ``x <= x_max``.

    Face ``k`` of a CPE8/CPE6 element runs from corner ``k`` to corner ``k + 1``.
    """
    mark = np.zeros(len(xy) + 1, bool)
    mark[on] = True
    faces = []
    for num, (kind, conn) in zip(numbers, elements):
        nc = 4 if kind == "CPE8" else 3
        for k in range(nc):
            i, j = conn[k], conn[(k + 1) % nc]
            if mark[i] and mark[j] and min(xy[i - 1, 0], xy[j - 1, 0]) <= x_max:
                faces.append((int(num), f"S{k + 1}"))
    return faces


def _counterclockwise(conn: np.ndarray, xy: np.ndarray, n_corner: int) -> np.ndarray:
    """The element's nodes ordered counterclockwise (as CalculiX requires)."""
    c = xy[conn[:n_corner] - 1]
    area2 = np.sum(c[:, 0] * np.roll(c[:, 1], -1) - np.roll(c[:, 0], -1) * c[:, 1])
    if area2 > 0:
        return conn
    corners = conn[:n_corner][::-1]
    # reversing the corners 1..n reverses the edges: mid (i, i+1) becomes mid (n-i-1, n-i)
    mids = conn[n_corner:][::-1]
    mids = np.roll(mids, -1)
    return np.concatenate([corners, mids])


@dataclass
class Model:
    """A whole two-body plane mesh of a punch on a block, ready for :func:`write_deck`.

    Attributes
    ----------
    punch, a, c
        The punch and the contact ``[-a, c]`` the mesh was sized for.
    xy, elements, numbers, nsets, master, slave, h0
        As :class:`Mesh`; ``nsets`` holds ``"block_surface"`` (the block's top over
        the fine zone), ``"punch_profile"``, ``"block_base"``, ``"punch_top"`` and, on
        :func:`build_model`'s pair, the block's sides ``"block_left"``, ``"block_right"``
        (where a friction deck's bulk stress acts).
    lift
        How far the punch's profile was lowered from eq. (2)'s so that it just touches ``y = 0``.
    """

    punch: Punch
    a: float
    c: float
    xy: np.ndarray
    elements: dict[str, list[tuple[str, np.ndarray]]]
    numbers: dict[str, np.ndarray]
    nsets: dict[str, np.ndarray]
    master: list[tuple[int, str]]
    slave: list[tuple[int, str]]
    h0: float
    lift: float

    @property
    def n_nodes(self) -> int:
        return len(self.xy)

    @property
    def n_elements(self) -> int:
        return sum(len(v) for v in self.elements.values())

    def control_nodes(self) -> tuple[int, int]:
        """The punch's two top corners (left, right): the load and the tilt act there."""
        top = self.nsets["punch_top"]
        x = self.xy[top - 1, 0]
        return int(top[np.argmin(x)]), int(top[np.argmax(x)])


def _parabola(occ: Any, punch: Punch, ends: tuple[int, int], x0: float, x1: float,
              lift: float) -> int:
    """The profile ``v(x)`` of eq. (2) over ``[x0, x1]`` (one segment) as an exact quadratic Bezier.

    ``ends`` are the gmsh points at ``x0`` and ``x1``; the middle control point is where
    the tangents at both ends meet.
    """
    if -punch.b <= x0 and x1 <= punch.b:      # the flat centre of case A (a Hertz face, b = 0, has none)
        return occ.addLine(ends[0], ends[1])
    g0 = float(punch.profile(x0)) - lift
    s0 = float(punch.slope(x0 + 1e-12 * (x1 - x0)))
    pm = occ.addPoint(0.5 * (x0 + x1), g0 + 0.5 * s0 * (x1 - x0), 0)
    curve = occ.addBezier([ends[0], pm, ends[1]])
    occ.remove([(0, pm)])            # a free point would carry a node of its own
    return curve


def build_model(punch: Punch, a: float, c: float, settings: DeckSettings = DeckSettings()) -> Model:
    """Mesh the punch on the block with gmsh: second-order quadrilaterals (CPE8), named groups.

    The block is ``settings.block * W`` wide and deep, its top ``y = 0``; the
    punch's face is the profile of eq. (2) (exact parabolas, raised to touch
    ``y = 0``) over the contact zone ``[-a - 2m, c + 2m]``, ``m = margin W``,
    and its top is a straight lid. With ``pair`` the punch is as large as the
    block (ledges continue its face outwards). Elements are ``h`` long along
    both faces over ``[-a - m, c + m]`` and grow away from it.
    """
    import gmsh

    from ..meshes import gmsh_session

    a, c = positive("a", a, (1e-12, 1e12)), positive("c", c, (1e-12, 1e12))
    W = a + c
    h0 = settings.size(W)
    m = settings.margin * W
    xf0, xf1 = -a - m, c + m             # fine zone
    xl, xr = -a - 2 * m, c + 2 * m       # the punch's face
    xm = 0.5 * (c - a)
    half, depth = 0.5 * settings.block * W, settings.block * W
    # the face's pieces meet at -b and b; a Hertz face (b = 0, R1 = R2) is one parabola, not split
    kinks = () if punch.b == 0 and punch.R1 == punch.R2 else (-punch.b, punch.b)
    breaks = sorted({xl, xr, xf0, xf1, *(x for x in kinks if xl < x < xr)})
    xs = np.union1d(np.linspace(xl, xr, 4001), breaks)
    lift = float(np.min(punch.profile(xs)))     # the face just touches y = 0
    with gmsh_session():
        occ = gmsh.model.occ
        # block: the top split at the fine zone
        # its fine zone ends 0.37 h further right than the punch's: the two faces' node
        # patterns are then not symmetric about the same point, so no node lies on another
        q = [occ.addPoint(xm - half, 0, 0), occ.addPoint(xf0, 0, 0),
             occ.addPoint(xf1 + 0.37 * h0, 0, 0),
             occ.addPoint(xm + half, 0, 0), occ.addPoint(xm + half, -depth, 0),
             occ.addPoint(xm - half, -depth, 0)]
        lb = [occ.addLine(q[i], q[(i + 1) % 6]) for i in range(6)]
        s_block = occ.addPlaneSurface([occ.addCurveLoop(lb)])
        # punch: the profile, piece by piece, then its sides and its top
        pts = [occ.addPoint(x, float(punch.profile(x)) - lift, 0) for x in breaks]
        face = [_parabola(occ, punch, (pts[i], pts[i + 1]), u, v, lift)
                for i, (u, v) in enumerate(zip(breaks, breaks[1:]))]
        fine = [f for f, (u, v) in zip(face, zip(breaks, breaks[1:])) if xf0 <= u and v <= xf1]
        gl, gr = (float(punch.profile(x)) - lift for x in (xl, xr))
        p_l, p_r = pts[0], pts[-1]
        # the punch is as large as the block, so that it too is a half-plane (eq. 4)
        top_y = max(gl, gr) + depth
        L0, R0 = occ.addPoint(xm - half, gl, 0), occ.addPoint(xm + half, gr, 0)
        T0, T1 = occ.addPoint(xm - half, top_y, 0), occ.addPoint(xm + half, top_y, 0)
        sides = [occ.addLine(p_r, R0), occ.addLine(R0, T1)]
        top = occ.addLine(T1, T0)
        sides += [occ.addLine(T0, L0), occ.addLine(L0, p_l)]
        loop = face + sides[: len(sides) // 2] + [top] + sides[len(sides) // 2:]
        s_punch = occ.addPlaneSurface([occ.addCurveLoop(loop)])
        occ.synchronize()
        groups = {"block": (2, [s_block]), "punch": (2, [s_punch]),
                  "block_surface": (1, [lb[1]]), "block_base": (1, [lb[4]]),
                  "block_left": (1, [lb[5]]), "block_right": (1, [lb[3]]),
                  "punch_profile": (1, face), "punch_top": (1, [top])}
        xy, elements, nsets = _mesh_pair(gmsh, groups, [lb[1], *fine], face, h0=h0,
                                         growth=settings.growth, span=xf1 - xf0, depth=depth)
    return _model(punch, a, c, xy, elements, nsets, h0, lift)


def build_finite_model(punch: Punch, a: float, c: float, *, H: float, theta: float,
                       settings: DeckSettings = DeckSettings(pair=True), block: float = 200.0,
                       half: bool = False) -> Model:
    """Mesh the finite punch of :func:`fem.solve_finite` on its block (the validity map's model).

    The punch: the flat centre ``[-b, b]``, exact circular arcs of radius
    ``R1`` (left) and ``R2`` (right) tangent to it up to the flank angle
    ``theta`` (or to the top, if they reach it first), straight flanks up to
    its top ``y = H`` (:class:`threepart.meshes.punch.PunchSpec`'s geometry).
    The block: ``block * W`` wide and deep, its top ``y = 0``, as the FEM's
    default mesh preset (``L = 200 W``). Elements are ``h`` long along both
    faces over ``[-a - m, c + m]`` (``m = margin W``), the punch's face
    ``MASTER_RATIO`` times coarser, growing away from it; second order (CPE8,
    CPE6). Node sets as :func:`build_model`'s (``lift = 0``: the flat touches
    ``y = 0``). :func:`write_deck` with ``clamped=True`` then clamps the
    block's base and welds the punch's top to a rigid plate (``u_x = 0``,
    ``u_y`` linear between its corners: free tilt), as :mod:`fem.finite` does.

    ``half``: a symmetric problem (``R1 = R2``, ``a = c``, the load at
    ``s = 0``) as its half ``x >= 0``, as :func:`build_half_mesh` does for the
    small-slope benchmark: the block ``block * W / 2`` wide and ``block * W``
    deep, the punch's flat ``[0, b]`` and its right arc; the node sets
    ``"block_sym"`` and ``"punch_sym"`` on ``x = 0``, which :func:`write_deck`
    holds at ``u_x = 0`` (and the plate level: its tilt is zero by symmetry).
    """
    from ..meshes.punch import PunchSpec
    from ..meshes.substrate import SubstrateSpec

    a, c = positive("a", a, (1e-12, 1e12)), positive("c", c, (1e-12, 1e12))
    W = a + c
    h0 = settings.size(W)
    m = settings.margin * W
    xf0, xf1 = -a - m, c + m
    width, depth = 0.5 * block * W, block * W
    spec = PunchSpec(zone=SubstrateSpec(x_lo=xf0, x_hi=xf1, h=h0, L=depth), b=punch.b, R1=punch.R1,
                     R2=punch.R2, H=H, theta=theta)       # checks that the zone lies on the face
    if not (xf0 < -punch.b and punch.b < xf1):
        raise InputError(f"the fine zone [{xf0:.6g}, {xf1:.6g}] must hold the flat centre [-b, b]")
    if not isinstance(half, bool):
        raise InputTypeError(f"`half` = {half!r} must be a bool")
    if half:
        if punch.R1 != punch.R2 or a != c:
            raise InputError(f"`half` needs a symmetric problem: R1 = {punch.R1:g} and R2 = {punch.R2:g}, "
                             f"a = {a:g} and c = {c:g} must be equal")
        return _finite_half_model(punch, c, spec, h0=h0, xf1=xf1, H=H, theta=theta, width=width,
                                  depth=depth, settings=settings)
    return _finite_whole_model(punch, a, c, spec, h0=h0, xf0=xf0, xf1=xf1, H=H, theta=theta,
                               width=width, depth=depth, settings=settings)


def _finite_whole_model(punch: Punch, a: float, c: float, spec: Any, *, h0: float, xf0: float,
                        xf1: float, H: float, theta: float, width: float, depth: float,
                        settings: DeckSettings) -> Model:
    """The whole model of :func:`build_finite_model` (``half=False``): the punch's face, flanks and top."""
    import gmsh

    from ..meshes import gmsh_session

    with gmsh_session():
        occ = gmsh.model.occ
        q = [occ.addPoint(-width, 0, 0), occ.addPoint(xf0, 0, 0), occ.addPoint(xf1 + 0.37 * h0, 0, 0),
             occ.addPoint(width, 0, 0), occ.addPoint(width, -depth, 0), occ.addPoint(-width, -depth, 0)]
        lb = [occ.addLine(q[i], q[(i + 1) % 6]) for i in range(6)]
        s_block = occ.addPlaneSurface([occ.addCurveLoop(lb)])

        def on_face(x: float) -> int:
            return occ.addPoint(x, float(spec.height(np.array([x]))[0]), 0)

        pl, pr = occ.addPoint(-punch.b, 0, 0), occ.addPoint(punch.b, 0, 0)
        fl, fr = on_face(xf0), on_face(xf1)
        cl, cr = occ.addPoint(-punch.b, punch.R1, 0), occ.addPoint(punch.b, punch.R2, 0)
        xel, xer = spec.edge_x("left"), spec.edge_x("right")
        el, er = on_face(xel), on_face(xer)
        fine = [occ.addCircleArc(fl, cl, pl), occ.addLine(pl, pr), occ.addCircleArc(pr, cr, fr)]
        face = [occ.addCircleArc(el, cl, fl), *fine, occ.addCircleArc(fr, cr, er)]
        # counterclockwise: the face left to right, the right flank up, the top, the left flank down
        tops, flanks = {}, {}
        for side, e, xe in (("right", er, xer), ("left", el, xel)):
            ye = float(spec.height(np.array([xe]))[0])
            if ye < H * (1 - 1e-12):          # a straight flank continues the arc's tangent
                xt = xe + (1.0 if side == "right" else -1.0) * (H - ye) / math.tan(theta)
                tops[side] = occ.addPoint(xt, H, 0)
                flanks[side] = [occ.addLine(e, tops[side]) if side == "right" else occ.addLine(tops[side], e)]
            else:                             # the arc reaches the top first
                tops[side], flanks[side] = e, []
        top = occ.addLine(tops["right"], tops["left"])
        loop = [*face, *flanks["right"], top, *flanks["left"]]
        s_punch = occ.addPlaneSurface([occ.addCurveLoop(loop)])
        occ.synchronize()
        groups = {"block": (2, [s_block]), "punch": (2, [s_punch]),
                  "block_surface": (1, [lb[1]]), "block_base": (1, [lb[4]]),
                  "punch_profile": (1, fine), "punch_top": (1, [top])}
        xy, elements, nsets = _mesh_pair(gmsh, groups, [lb[1], *fine], fine, h0=h0,
                                         growth=settings.growth, span=xf1 - xf0, depth=depth)
    return _model(punch, a, c, xy, elements, nsets, h0, 0.0)


def _finite_half_model(punch: Punch, c: float, spec: Any, *, h0: float, xf1: float, H: float,
                       theta: float, width: float, depth: float, settings: DeckSettings) -> Model:
    """The half ``x >= 0`` of :func:`build_finite_model`'s model (``half=True``), meshed alike."""
    import gmsh

    from ..meshes import gmsh_session

    with gmsh_session():
        occ = gmsh.model.occ
        # block: its top split where the fine zone ends (0.37 h beyond the punch's, as the whole model)
        q = [occ.addPoint(0, 0, 0), occ.addPoint(xf1 + 0.37 * h0, 0, 0), occ.addPoint(width, 0, 0),
             occ.addPoint(width, -depth, 0), occ.addPoint(0, -depth, 0)]
        lb = [occ.addLine(q[i], q[(i + 1) % 5]) for i in range(5)]
        s_block = occ.addPlaneSurface([occ.addCurveLoop(lb)])
        # punch: the flat [0, b], the arc up to the fine zone's end and on, the flank, the top, x = 0
        p0, pr = occ.addPoint(0, 0, 0), occ.addPoint(punch.b, 0, 0)
        cr = occ.addPoint(punch.b, punch.R2, 0)
        fr = occ.addPoint(xf1, float(spec.height(np.array([xf1]))[0]), 0)
        xer = spec.edge_x("right")
        ye = float(spec.height(np.array([xer]))[0])
        er = occ.addPoint(xer, ye, 0)
        fine = [occ.addLine(p0, pr), occ.addCircleArc(pr, cr, fr)]
        curves = [*fine, occ.addCircleArc(fr, cr, er)]
        if ye < H * (1 - 1e-12):              # a straight flank continues the arc's tangent
            tr = occ.addPoint(xer + (H - ye) / math.tan(theta), H, 0)
            curves.append(occ.addLine(er, tr))
        else:                                 # the arc reaches the top first
            tr = er
        t0 = occ.addPoint(0, H, 0)
        top = occ.addLine(tr, t0)
        sym = occ.addLine(t0, p0)
        s_punch = occ.addPlaneSurface([occ.addCurveLoop([*curves, top, sym])])
        occ.synchronize()
        groups = {"block": (2, [s_block]), "punch": (2, [s_punch]),
                  "block_surface": (1, [lb[0]]), "block_base": (1, [lb[3]]), "block_sym": (1, [lb[4]]),
                  "punch_profile": (1, fine), "punch_top": (1, [top]), "punch_sym": (1, [sym])}
        xy, elements, nsets = _mesh_pair(gmsh, groups, [lb[0], *fine], fine, h0=h0,
                                         growth=settings.growth, span=xf1, depth=depth)
    return _model(punch, c, c, xy, elements, nsets, h0, 0.0)


def _mesh_pair(gmsh: Any, groups: dict[str, tuple[int, list[int]]], refined: list[int],
               master: list[int], *, h0: float, growth: float, span: float, depth: float
               ) -> tuple[np.ndarray, dict[str, list[tuple[str, np.ndarray]]], dict[str, np.ndarray]]:
    """Mesh the synchronised block and punch of ``groups`` (second order) and collect them.

    ``groups`` maps each physical group to ``(dim, entities)``, with the two
    surfaces ``"block"`` and ``"punch"``; ``h0`` along the ``refined`` curves
    (over a zone ``span`` long), growing by ``growth`` to ``depth / 8``; the
    punch's face (the ``master`` curves) uniformly ``MASTER_RATIO`` times
    coarser, so that no node of one face lies on a node of the other
    (CalculiX's expansion of plane elements fails on coinciding nodes).
    """
    from ..meshes.substrate import size_field

    tags = {name: gmsh.model.addPhysicalGroup(dim, ents, name=name)
            for name, (dim, ents) in groups.items()}
    size_field(refined, h=h0, growth=growth, sampling=int(4 * span / h0) + 10, size_max=depth / 8)
    for f in master:
        length = gmsh.model.occ.getMass(1, f)
        gmsh.model.mesh.setTransfiniteCurve(f, max(2, math.ceil(length / (MASTER_RATIO * h0)) + 1))
    for name, value in [("Mesh.Algorithm", 8), ("Mesh.RecombineAll", 1),
                        ("Mesh.RecombinationAlgorithm", 1), ("Mesh.SecondOrderIncomplete", 1)]:
        gmsh.option.setNumber(name, value)
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(2)
    surfaces = {body: groups[body][1][0] for body in ("block", "punch")}
    return _collect(gmsh, surfaces, tags, tuple(n for n, (dim, _) in groups.items() if dim == 1))


def _model(punch: Punch, a: float, c: float, xy: np.ndarray,
           elements: dict[str, list[tuple[str, np.ndarray]]], nsets: dict[str, np.ndarray],
           h0: float, lift: float) -> Model:
    """The :class:`Model` of a meshed pair: elements numbered block first, the contact's faces."""
    numbers, n = {}, 0
    for body in ("block", "punch"):
        numbers[body] = np.arange(n + 1, n + 1 + len(elements[body]))
        n += len(elements[body])
    master = face_elements(elements["punch"], numbers["punch"], nsets["punch_profile"], xy, math.inf)
    slave = face_elements(elements["block"], numbers["block"], nsets["block_surface"], xy, math.inf)
    return Model(punch, a, c, xy, elements, numbers, nsets, master, slave, h0, lift)


def _collect(gmsh: Any, surfaces: dict[str, int], tags: dict[str, int],
             names: tuple[str, ...]) -> tuple[np.ndarray, dict[str, list[tuple[str, np.ndarray]]],
                                              dict[str, np.ndarray]]:
    """Nodes (renumbered 1..N), CalculiX elements per body and node sets from gmsh's model."""
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    # only the nodes of the 2-D elements: a free geometric point (a Bezier's control point)
    # carries an orphan node, which CalculiX's expansion of plane elements does not survive
    used = np.unique(np.concatenate([np.concatenate(gmsh.model.mesh.getElements(2, s)[2])
                                     for s in surfaces.values()]).astype(np.int64))
    keep = np.isin(node_tags.astype(np.int64), used)
    node_tags, coords = node_tags[keep], coords.reshape(-1, 3)[keep]
    index = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
    index[node_tags.astype(np.int64)] = np.arange(1, node_tags.size + 1)
    xy = coords[:, :2].copy()
    # gmsh's round-off leaves x = -4e-14 where 0 was meant (-7e-9 on the finite punch's top,
    # 1.4e-11 of the 200 W block); CalculiX's expansion of plane elements fails on such a node
    # ("nonpositive jacobian"): snap to 0
    xy[np.abs(xy) < 1e-10 * np.max(np.abs(xy))] = 0.0
    elements: dict[str, list[tuple[str, np.ndarray]]] = {}
    for body, s in surfaces.items():
        elements[body] = []
        etypes, _, enodes = gmsh.model.mesh.getElements(2, s)
        for et, en in zip(etypes, enodes):
            kind, n_corner = GMSH_TO_CCX[int(et)]
            conn = index[en.astype(np.int64)].reshape(-1, 2 * n_corner)
            for row in conn:
                elements[body].append((kind, _counterclockwise(row, xy, n_corner)))
    nsets = {}
    for name in names:
        t, _ = gmsh.model.mesh.getNodesForPhysicalGroup(1, tags[name])
        nsets[name] = np.unique(index[t.astype(np.int64)])
    return xy, elements, nsets


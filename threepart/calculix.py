"""CalculiX input decks and result readers: the one home of threepart's CalculiX model.

threepart uses CalculiX (``ccx``, Debian's ``calculix-ccx``) as an outside
referee: an independent finite-element code, with its own elements (CPE8,
plane strain) and its own penalty contact, that is judged against the closed
form. This module writes its decks (CalculiX's dialect of the Abaqus input
format), runs ``ccx`` and reads its results back. It imports no solver.

Decks
-----
DeckSettings    -- mesh size, penalty stiffness, punch stiffening, pair or stiff punch, block size
build_model     -- the whole-model two-body gmsh mesh (second order) of a three-part punch
build_finite_model -- the validity map's finite punch (exact arcs, flanks, height H) on its block, or its half
write_deck      -- the deck of a model: sets, materials, contact, load at ``s``, free or suppressed tilt
CONVENTIONS     -- the comment block every deck carries (units, conventions, pitfalls)
parse_deck      -- a minimal keyword parser (``*KEYWORD, PARAM=...`` and data lines) for checks

Running and reading
-------------------
ccx_available   -- whether ``ccx`` is on the PATH
run_ccx         -- run ``ccx`` on a deck in a directory (one thread); raises CcxMissing, CcxError
read_frd        -- the nodal result blocks of an ``.frd`` file (DISP, STRESS, CONTACT), last increment
read_frd_nodes  -- the node coordinates of an ``.frd`` file
read_reaction   -- the total reaction force of a printed node set (``.dat``)
read_increments -- how many increments the step took (``.sta``)
read_dat        -- the printed blocks of a ``.dat`` file (node sets, contact output), last time
nodal_forces    -- the contact's force at each slave node, ``-2 CELS / COPEN`` (plane models)
nodal_areas     -- the nodes' shares ``∫N_i dx`` of a quadratic surface (L/6, 2L/3, L/6)
dealternate     -- nodal values freed of the vertex/midside alternation (a local fit)
force_pressure  -- the contact pressure from the nodal forces: over the shares, de-alternated
surface_pressure -- the contact pressure along the block's surface from a run (x, p, gap, CPRESS)
contact_edge    -- a contact end from the gap just outside it (``gap^(2/3)`` linear)

The half model of the small-slope benchmark (``benchmarks/small_slope_calculix.py``)
is built from the same pieces: :func:`build_half_mesh` and :func:`half_deck`.
"""
from __future__ import annotations

import math
import os
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .material import compliance
from .punch import Punch
from .validate import check_tilt, finite, positive

__all__ = ["DeckSettings", "Model", "build_model", "build_finite_model", "write_deck", "CONVENTIONS", "parse_deck",
           "Keyword", "ccx_available", "run_ccx", "CcxMissing", "CcxError", "read_frd",
           "read_frd_nodes", "read_reaction", "read_dat", "nodal_forces", "nodal_areas", "dealternate",
           "force_pressure", "DEALTERNATE_NODES", "read_descent", "surface_pressure", "SurfacePressure",
           "contact_edge", "centre_pressure", "Material", "Mesh", "build_half_mesh", "half_deck",
           "nodes_text", "elements_text", "nset_text", "surface_text", "material_text",
           "contact_text", "equation_text", "boundary_text", "step_text", "GMSH_TO_CCX", "W_OVER_H",
           "check_mesh_size", "read_increments"]

#: the punch's (master) element size over the block's (slave) at the contact
MASTER_RATIO = 1.37
#: gmsh element type -> (CalculiX element, number of corner nodes)
GMSH_TO_CCX = {16: ("CPE8", 4), 9: ("CPE6", 3)}
#: the admissible mesh, in elements across the contact width W = a + c (W/h): at least 4
#: resolve it at all; at most 1000, 5 x the default 200 (caseA_sym at W/h = 1000: 38 975
#: nodes, 3 s of CPU and 155 MB for the deck; --h 1e-5, W/h = 4e5, ran past 2 minutes and
#: 1e-9 took gmsh to 3.7 GB and a traceback)
W_OVER_H = (4.0, 1000.0)


# --------------------------------------------------------------------------- material
@dataclass(frozen=True)
class Material:
    """Linear elastic block, and the punch ``stiffening`` times stiffer (nearly rigid)."""

    E: float = 210e3
    nu: float = 0.3
    stiffening: float = 1e3

    @property
    def A(self) -> float:
        """Compliance ``A`` of eq. (4) of the block and the (not quite rigid) punch."""
        return compliance(self.E, self.nu, self.E * self.stiffening, self.nu)


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

    from .meshes import gmsh_session

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

        f_dist = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(f_dist, "CurvesList", [lb[0]] + fine)
        gmsh.model.mesh.field.setNumber(f_dist, "Sampling", int(4 * x_fine / h0) + 10)
        h_max = D / 8
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

        xy, elements, nsets = _collect(gmsh, {"block": s_block, "punch": s_punch}, tags,
                                       ("block_top", "block_fine", "block_bottom", "block_sym",
                                        "punch_contact", "punch_fine", "punch_top", "punch_sym"))

    # number the elements, block first, and find the punch's faces on its contact curves
    numbers, n = {}, 0
    for body in ("block", "punch"):
        numbers[body] = np.arange(n + 1, n + 1 + len(elements[body]))
        n += len(elements[body])
    master = _faces(elements["punch"], numbers["punch"], nsets["punch_contact"], xy, x_fine)
    slave = _faces(elements["block"], numbers["block"], nsets["block_fine"], xy, x_fine)
    return Mesh(xy, elements, nsets, master, slave, h0, numbers)


def _faces(elements: list[tuple[str, np.ndarray]], numbers: np.ndarray, on: np.ndarray,
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


# --------------------------------------------------------------------------- deck text
def _rows(values: np.ndarray, per_line: int = 16) -> str:
    """Integers as comma-separated lines of at most ``per_line`` (CalculiX's limit)."""
    v = [str(int(x)) for x in values]
    return "\n".join(", ".join(v[i:i + per_line]) for i in range(0, len(v), per_line))


def nodes_text(xy: np.ndarray) -> str:
    """``*NODE`` card: node ``i + 1`` at ``xy[i]``."""
    lines = [f"{i + 1}, {x:.15g}, {y:.15g}" for i, (x, y) in enumerate(xy)]
    return "*NODE, NSET=NALL\n" + "\n".join(lines) + "\n"


def elements_text(elements: list[tuple[str, np.ndarray]], numbers: np.ndarray, elset: str) -> str:
    """``*ELEMENT`` cards for one body, one card per element type, in element set ``elset``."""
    out = []
    for kind in sorted({k for k, _ in elements}):
        rows = [f"{num}, " + ", ".join(str(int(n)) for n in conn)
                for num, (k, conn) in zip(numbers, elements) if k == kind]
        out.append(f"*ELEMENT, TYPE={kind}, ELSET={elset}\n" + "\n".join(rows) + "\n")
    return "".join(out)


def nset_text(name: str, nodes: np.ndarray) -> str:
    """``*NSET`` card."""
    return f"*NSET, NSET={name}\n{_rows(nodes)}\n"


def surface_text(name: str, *, nset: str | None = None,
                 faces: list[tuple[int, str]] | None = None) -> str:
    """``*SURFACE`` card: a node surface from ``nset``, or an element-face surface."""
    if nset is not None:
        return f"*SURFACE, NAME={name}, TYPE=NODE\n{nset}\n"
    assert faces is not None
    return f"*SURFACE, NAME={name}, TYPE=ELEMENT\n" + "\n".join(f"{e}, {s}" for e, s in faces) + "\n"


def material_text(name: str, E: float, nu: float, elset: str) -> str:
    """``*MATERIAL``/``*ELASTIC`` and a plane-strain ``*SOLID SECTION`` of unit thickness."""
    return (f"*MATERIAL, NAME={name}\n*ELASTIC\n{E:.15g}, {nu:.15g}\n"
            f"*SOLID SECTION, ELSET={elset}, MATERIAL={name}\n1.\n")


def contact_text(slave: str, master: str, K: float, sigma_inf: float) -> str:
    """Frictionless node-to-surface penalty contact, linear pressure-overclosure.

    ``K`` is the penalty stiffness (pressure per overclosure) and
    ``sigma_inf`` the tension that open pairs carry at large clearance
    (CalculiX's regularisation of the open pairs).
    """
    return (f"*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE\n{slave}, {master}\n"
            f"*SURFACE INTERACTION, NAME=SI\n"
            f"*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{K:.6g}, {sigma_inf:.6g}\n")


def equation_text(nodes: np.ndarray, ref: int, dof: int) -> str:
    """``*EQUATION``: degree ``dof`` of each node in ``nodes`` equals that of node ``ref``."""
    rows = [f"2\n{int(n)}, {dof}, 1., {ref}, {dof}, -1." for n in nodes if int(n) != ref]
    return "*EQUATION\n" + "\n".join(rows) + "\n"


def boundary_text(fixed: list[tuple[str, int]]) -> str:
    """``*BOUNDARY``: each ``(set or node, dof)`` held at zero."""
    return "*BOUNDARY\n" + "\n".join(f"{s}, {d}, {d}" for s, d in fixed) + "\n"


def step_text(*, nlgeom: bool, ref: int, F: float | None = None, delta: float | None = None,
              increments: int = 1) -> str:
    """One static step at node ``ref``: the vertical force ``-F``, or the descent ``delta``.

    The step is applied in ``increments`` equal increments (cut back if one
    does not converge, and never longer). It writes the
    displacements and stresses of the output set ``NOUT`` to the ``.frd``
    file, and the base's total reaction and the displacement of ``ref`` to
    the ``.dat``.
    """
    dt = 1.0 / increments
    head = "*STEP, NLGEOM, INC=1000" if nlgeom else "*STEP, INC=1000"
    # room for the contact's Newton iterations in each increment
    controls = "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n40, 60, 9, 200, 10, 4, 12, 40\n"
    if (F is None) == (delta is None):
        raise ValueError("give the force `F` or the descent `delta`, not both or neither")
    if F is not None:
        load = f"*CLOAD\n{ref}, 2, {-F:.15g}\n"
    else:
        assert delta is not None
        load = f"*BOUNDARY\n{ref}, 2, 2, {-delta:.15g}\n"
    # fixed increments unless one fails to converge: then CalculiX may cut it down to 1/64
    return (f"{head}\n{controls}*STATIC\n{dt:.15g}, 1., {dt / 64:.15g}, {dt:.15g}\n{load}"
            "*NODE FILE, NSET=NOUT\nU, S\n"
            "*NODE PRINT, NSET=NBOTTOM, TOTALS=ONLY\nRF\n"
            "*NODE PRINT, NSET=NREF\nU\n"
            "*END STEP\n")


def half_deck(mesh: Mesh, mat: Material, *, K: float, sigma_inf: float, nlgeom: bool,
               F: float | None = None, delta: float | None = None, increments: int = 1) -> str:
    """The whole CalculiX deck for the half model: the half load ``F`` (per unit thickness),
    or the punch's descent ``delta``."""
    ref = int(mesh.nsets["punch_top"][0])
    parts = ["*HEADING\nthreepart small-slope benchmark (half model, plane strain)\n",
             nodes_text(mesh.xy),
             elements_text(mesh.elements["block"], mesh.numbers["block"], "BLOCK"),
             elements_text(mesh.elements["punch"], mesh.numbers["punch"], "PUNCH")]
    sym = np.union1d(mesh.nsets["block_sym"], mesh.nsets["punch_sym"])
    out = np.union1d(mesh.nsets["block_fine"], mesh.nsets["punch_fine"])
    parts += [nset_text("NSYM", sym), nset_text("NBOTTOM", mesh.nsets["block_bottom"]),
              nset_text("NOUT", out), nset_text("NREF", np.array([ref]))]
    parts += [material_text("BLOCK_MAT", mat.E, mat.nu, "BLOCK"),
              material_text("PUNCH_MAT", mat.E * mat.stiffening, mat.nu, "PUNCH")]
    parts += [surface_text("SSLAVE", faces=mesh.slave), surface_text("SMASTER", faces=mesh.master),
              contact_text("SSLAVE", "SMASTER", K, sigma_inf)]
    parts += [equation_text(mesh.nsets["punch_top"], ref, 2),
              boundary_text([("NSYM", 1), ("NBOTTOM", 2)])]
    parts += [step_text(nlgeom=nlgeom, ref=ref, F=F, delta=delta, increments=increments)]
    return "".join(parts)



# --------------------------------------------------------------------------- the whole model
#: The comment block at the top of every deck (``**`` lines are comments in CalculiX and Abaqus).
CONVENTIONS = """\
** Units: any consistent set; threepart labels lengths mm, loads per unit thickness N/mm,
**   stresses, moduli and the penalty stiffness MPa (K: MPa/mm), the tilt rad.
** Plane strain (CPE8/CPE6), unit thickness: forces are per unit length of the contact.
** Conventions (threepart's README): x along the surface, y = -z up, z >= 0 depth into the
**   block (the substrate); tension positive; the contact pressure p = -S22 of the block's
**   surface >= 0 is compressive; the punch (set PUNCH) is pressed down onto the block (BLOCK)
**   by P, whose line of action is x = s.
** Contact: frictionless node-to-surface penalty (PRESSURE-OVERCLOSURE=LINEAR, stiffness K).
**   CPRESS at an open node is a tension, not zero: -K*COPEN up to the law's sigma_inf (its
**   second data item below), sigma_inf beyond: read the pressure where COPEN <= 0 only, and
**   K as CPRESS/-COPEN at closed nodes.
**   On quadratic faces CPRESS alternates between vertex and midside nodes by up to 2: it is
**   the force over CalculiX's own nodal area (about h/2 at every node), not over the node's
**   share of the face (h/3 at a vertex, 2h/3 at a midside node). The nodal force is
**   -2*CELS/COPEN (*CONTACT PRINT CSTR, CDIS, CELS below; summed over the 2 or 3 expanded
**   nodes N + 3(n - 1) + 1..3 of node n of N); threepart compare reads it from this .dat.
**   The pressure's error falls as 1/K: check that a stiffer K changes nothing you use.
** Analyse the FIRST increment only: one increment of the linear step. A later increment
**   pairs the surfaces again on the deformed geometry and integral(p) overshoots P.
** The closed form and this linear step both assume small slopes and strains (the line
**   above the units gives this deck's). At the paper's load (caseA_sym: slope 0.1, P/W
**   over E 0.034) ccx cut the step into 21 increments and the pressure differed from the
**   closed form by about 1 % of its peak; at slope 0.005 (radii x 20, P / 20) it converged
**   in one increment within 1e-3 (docs/CALCULIX.md).
** Sets: BLOCK, PUNCH (elements); NSURF (the block's surface in the contact zone), NPROFILE
**   (the punch's face there), NBASE (the block's base), NTOP (the punch's top), NCTRL (its two
**   control nodes), SSLAVE/SMASTER (the contact faces).
"""


@dataclass(frozen=True)
class DeckSettings:
    """How a CalculiX model of one contact is built.

    Parameters
    ----------
    h
        Element size along both surfaces over the contact zone (a length);
        ``None``: ``W / n`` with ``W = a + c``.
    n
        Elements across the contact width when ``h`` is not given.
    penalty
        Penalty stiffness ``K`` (pressure per overclosure, MPa/mm);
        ``None``: ``penalty_factor * E / h`` (200 E/h: 2e9 MPa/mm for steel at h = 0.02 mm;
        at 20 E/h the load read from the surface stress is 6e-3 short, see docs/CALCULIX.md).
    penalty_factor
        ``K`` in units of ``E / h`` when ``penalty`` is not given.
    pair
        ``True``: two similar elastic bodies (``A = 4(1 - nu^2)/E``);
        ``False``: a stiff punch, ``stiffening`` times the block's modulus.
    stiffening
        The stiff punch's modulus over the block's (1000: the punch's own
        deformation, interpolated by its quadratic face, put a 0.5 % node-to-node
        scatter into the contact forces at 10, and the default deck then needed 12
        increments, 114 s of CPU, instead of one, 10 s; docs/CALCULIX.md).
    tilt
        ``"free"`` (the load at ``s``, the punch free to tilt) or
        ``"suppressed"`` (the punch's top held level).
    block
        The block's width and depth in contact widths ``W``.
    margin
        The fine zone reaches ``margin * W`` beyond each expected contact end.
    growth
        Growth of the element size with the distance from the fine zone.
    """

    h: float | None = None
    n: float = 200.0
    penalty: float | None = None
    penalty_factor: float = 200.0
    pair: bool = False
    stiffening: float = 1000.0
    tilt: str = "free"
    block: float = 20.0
    margin: float = 0.15
    growth: float = 0.25

    def __post_init__(self) -> None:
        if self.h is not None:
            positive("h", self.h, (1e-9, 1e9))
        positive("n", self.n, W_OVER_H)
        if self.penalty is not None:
            positive("penalty", self.penalty, (1e-6, 1e20))
        positive("penalty_factor", self.penalty_factor, (1e-3, 1e6))
        positive("stiffening", self.stiffening, (1.0, 1e9))
        positive("block", self.block, (4.0, 1e4))
        positive("margin", self.margin, (0.01, 2.0))
        positive("growth", self.growth, (0.01, 2.0))
        check_tilt(self.tilt)
        if not isinstance(self.pair, bool):
            raise TypeError(f"`pair` = {self.pair!r} must be a bool")

    def size(self, W: float) -> float:
        """The element size at the contact for a contact width ``W`` (checked: :func:`check_mesh_size`)."""
        return check_mesh_size(float(self.h) if self.h is not None else W / self.n, W)

    def K(self, E: float, W: float) -> float:
        """The penalty stiffness for a block modulus ``E`` and a contact width ``W``."""
        return float(self.penalty) if self.penalty is not None else self.penalty_factor * E / self.size(W)


def check_mesh_size(h: float, W: float) -> float:
    """``h`` if the contact width ``W`` holds :data:`W_OVER_H` elements (W/h in that range), else ``ValueError``.

    Checked before gmsh starts: a mesh far finer than the range exhausts the
    memory in gmsh, one far coarser does not resolve the contact.
    """
    lo, hi = W_OVER_H
    if not lo <= W / h <= hi:
        raise ValueError(f"`h` (`--h`) = {h:.4g} gives W/h = {W / h:.4g} elements across the contact "
                         f"width W = a + c = {W:.6g}; give W/h from {lo:g} to {hi:g}, h from "
                         f"{W / hi:.4g} to {W / lo:.4g}")
    return h


@dataclass
class Model:
    """A whole two-body plane mesh of a punch on a block, ready for :func:`write_deck`.

    Attributes
    ----------
    punch, a, c
        The punch and the contact ``[-a, c]`` the mesh was sized for.
    xy, elements, numbers, nsets, master, slave, h0
        As :class:`Mesh`; ``nsets`` holds ``"block_surface"`` (the block's top over
        the fine zone), ``"punch_profile"``, ``"block_base"``, ``"punch_top"``.
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
    if float(punch.curvature(0.5 * (x0 + x1))) == 0.0:     # the flat centre of case A
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

    from .meshes import gmsh_session

    a, c = positive("a", a, (1e-12, 1e12)), positive("c", c, (1e-12, 1e12))
    W = a + c
    h0 = settings.size(W)
    m = settings.margin * W
    xf0, xf1 = -a - m, c + m             # fine zone
    xl, xr = -a - 2 * m, c + 2 * m       # the punch's face
    xm = 0.5 * (c - a)
    half, depth = 0.5 * settings.block * W, settings.block * W
    breaks = sorted({xl, xr, xf0, xf1, *(x for x in (-punch.b, punch.b) if xl < x < xr)})
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
    import gmsh

    from .meshes import gmsh_session
    from .meshes.punch import PunchSpec
    from .meshes.substrate import SubstrateSpec

    a, c = positive("a", a, (1e-12, 1e12)), positive("c", c, (1e-12, 1e12))
    W = a + c
    h0 = settings.size(W)
    m = settings.margin * W
    xf0, xf1 = -a - m, c + m
    width, depth = 0.5 * block * W, block * W
    spec = PunchSpec(zone=SubstrateSpec(x_lo=xf0, x_hi=xf1, h=h0, L=depth), b=punch.b, R1=punch.R1,
                     R2=punch.R2, H=H, theta=theta)       # checks that the zone lies on the face
    if not (xf0 < -punch.b and punch.b < xf1):
        raise ValueError(f"the fine zone [{xf0:.6g}, {xf1:.6g}] must hold the flat centre [-b, b]")
    if not isinstance(half, bool):
        raise TypeError(f"`half` = {half!r} must be a bool")
    if half:
        if punch.R1 != punch.R2 or a != c:
            raise ValueError(f"`half` needs a symmetric problem: R1 = {punch.R1:g} and R2 = {punch.R2:g}, "
                             f"a = {a:g} and c = {c:g} must be equal")
        return _finite_half_model(punch, c, spec, h0=h0, xf1=xf1, H=H, theta=theta, width=width,
                                  depth=depth, settings=settings)
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

    from .meshes import gmsh_session

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
    from .meshes.substrate import size_field

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
    master = _faces(elements["punch"], numbers["punch"], nsets["punch_profile"], xy, math.inf)
    slave = _faces(elements["block"], numbers["block"], nsets["block_surface"], xy, math.inf)
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


def write_deck(model: Model, *, P: float, s: float, E: float, nu: float,
               settings: DeckSettings = DeckSettings(), title: str = "", clamped: bool = False,
               increment: tuple[float, float] = (1.0, 1.0 / 64)) -> str:
    """The CalculiX deck of ``model`` under the load ``P`` at ``x = s`` (per unit thickness).

    The punch's top is a lid: every top node's vertical displacement is the
    linear interpolant of its two corners' (free tilt) or equal to the left
    corner's (tilt suppressed, then all of ``P`` acts there and ``s`` is an
    outcome). ``P`` at ``s`` is split over the corners so that their
    resultant and its moment are ``P`` and ``P s``. The punch's left corner is
    held in ``x``, the block's base in ``y`` and its middle node in ``x``;
    ``clamped``: the block's base in ``x`` and ``y`` and the punch's whole top
    in ``x`` (the finite body of :func:`build_finite_model`, welded to its plate).
    One linear static step in one increment; ``increment`` = (first, smallest)
    increment of the step (CalculiX cuts an increment that does not converge).

    A half model (``build_finite_model(..., half=True)``, ``clamped`` and
    ``s = 0`` only) carries ``P / 2`` on its plate, which stays level (every top
    node's ``u_y`` equals the corner's at ``x = 0``), and both bodies' nodes on
    ``x = 0`` are held at ``u_x = 0`` (set NSYM).
    """
    P, s = positive("P", P, (1e-12, 1e15)), finite("s", s)
    E, nu = positive("E", E, (1e-6, 1e15)), finite("nu", nu)
    W = model.a + model.c
    K = settings.K(E, W)
    tl, tr = model.control_nodes()
    xL, xR = model.xy[tl - 1, 0], model.xy[tr - 1, 0]
    half = "block_sym" in model.nsets
    if half and not (s == 0.0 and clamped):
        raise ValueError(f"a half model needs `s` = 0 (got {s:g}) and `clamped` (got {clamped})")
    if not half and settings.tilt == "free" and not xL < s < xR:
        raise ValueError(f"`s` = {s:g} must lie on the punch's top, between {xL:g} and {xR:g}")
    top = model.nsets["punch_top"]
    base = model.nsets["block_base"]
    mid = int(base[np.argmin(np.abs(model.xy[base - 1, 0] - 0.5 * (model.c - model.a)))])
    E_punch = E if settings.pair else E * settings.stiffening
    p_est = 2 * P / (math.pi * W)
    head = (f"** threepart deck: {title or 'a three-part punch on an elastic block'}\n"
            f"** punch R1 = {model.punch.R1:.15g}, R2 = {model.punch.R2:.15g}, b = {model.punch.b:.15g},"
            f" R = {model.punch.R:.15g} (eq. 2); P = {P:.15g} at s = {s:.15g}, tilt {settings.tilt}\n"
            f"** expected contact [-a, c] = [{-model.a:.10g}, {model.c:.10g}]; h = {model.h0:.6g},"
            f" K = {K:.6g}; {'two similar bodies' if settings.pair else f'punch {settings.stiffening:g} x stiffer'}"
            f"; the face is raised by {model.lift:.6g} to touch y = 0\n"
            f"** small slopes and strains: the largest slope over the contact is "
            f"{model.punch.max_slope(model.a, model.c):.3g}, the mean pressure P/W over E "
            f"{P / (W * E):.3g}\n" + CONVENTIONS)
    parts = [head, "*HEADING\nthreepart: a three-part punch on an elastic block, plane strain\n",
             nodes_text(model.xy),
             elements_text(model.elements["block"], model.numbers["block"], "BLOCK"),
             elements_text(model.elements["punch"], model.numbers["punch"], "PUNCH"),
             nset_text("NSURF", model.nsets["block_surface"]),
             nset_text("NPROFILE", model.nsets["punch_profile"]),
             nset_text("NBASE", base), nset_text("NTOP", top),
             nset_text("NCTRL", np.array([tl, tr])), nset_text("NMID", np.array([mid])),
             nset_text("NOUT", np.union1d(model.nsets["block_surface"], model.nsets["punch_profile"])),
             material_text("BLOCK_MAT", E, nu, "BLOCK"),
             material_text("PUNCH_MAT", E_punch, nu, "PUNCH"),
             surface_text("SSLAVE", faces=model.slave), surface_text("SMASTER", faces=model.master),
             contact_text("SSLAVE", "SMASTER", K, 1e-6 * p_est)]
    rows = []
    for n in top:
        n = int(n)
        if n == tl or (n == tr and not half):
            continue
        if half:                 # the plate's tilt is zero by symmetry
            rows.append(f"2\n{n}, 2, 1., {tl}, 2, -1.")
        elif settings.tilt == "free":
            t = (model.xy[n - 1, 0] - xL) / (xR - xL)
            rows.append(f"3\n{n}, 2, 1., {tl}, 2, {-(1 - t):.15g}, {tr}, 2, {-t:.15g}")
        else:
            rows.append(f"2\n{n}, 2, 1., {tl}, 2, -1.")
    if half:
        loads = f"{tl}, 2, {-0.5 * P:.15g}\n"
    elif settings.tilt == "suppressed":
        rows.append(f"2\n{tr}, 2, 1., {tl}, 2, -1.")
        loads = f"{tl}, 2, {-P:.15g}\n"
    else:
        F_R = P * (s - xL) / (xR - xL)
        loads = f"{tl}, 2, {-(P - F_R):.15g}\n{tr}, 2, {-F_R:.15g}\n"
    parts.append("*EQUATION\n" + "\n".join(rows) + "\n")
    if half:
        parts.append(nset_text("NSYM", np.union1d(model.nsets["block_sym"], model.nsets["punch_sym"])))
    parts.append(boundary_text([("NBASE", 1), ("NBASE", 2), ("NTOP", 1)] + [("NSYM", 1)] * half
                               if clamped else
                               [("NBASE", 2), ("NMID", 1), (str(tl), 1)]))
    parts.append("*STEP, INC=1000\n*CONTROLS, PARAMETERS=TIME INCREMENTATION\n"
                 f"40, 60, 9, 200, 10, 4, 12, 40\n*STATIC\n{increment[0]:.15g}, 1., {increment[1]:.15g}, "
                 f"{increment[0]:.15g}\n*CLOAD\n" + loads +
                 "*NODE FILE, NSET=NOUT\nU, S\n*CONTACT FILE\nCDIS, CSTR, CELS\n"
                 "*NODE PRINT, NSET=NBASE, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=NCTRL\nU\n"
                 "*NODE PRINT, NSET=NSURF\nU\n*CONTACT PRINT\nCSTR, CDIS, CELS\n*END STEP\n")
    return "".join(parts)


# --------------------------------------------------------------------------- a minimal parser
@dataclass(frozen=True)
class Keyword:
    """One keyword card of a deck: its name, parameters and data lines."""

    name: str
    params: dict[str, str]
    data: list[list[str]]
    line: int


def parse_deck(text: str) -> list[Keyword]:
    """Split a deck into keyword cards (``*NAME, KEY=VALUE, FLAG``), skipping ``**`` comments.

    A minimal parser of the Abaqus/CalculiX input format, enough to check a
    deck without ``ccx``: it raises ``ValueError`` (naming the line) for data
    before the first keyword, an empty keyword or a malformed parameter.
    """
    cards: list[Keyword] = []
    for i, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            items = [t.strip() for t in line[1:].split(",")]
            if not items[0]:
                raise ValueError(f"line {i}: empty keyword")
            params = {}
            for it in items[1:]:
                if not it:
                    continue
                key, eq, value = it.partition("=")
                if eq and not (key.strip() and value.strip()):
                    raise ValueError(f"line {i}: malformed parameter {it!r}")
                params[key.strip().upper()] = value.strip()
            cards.append(Keyword(items[0].upper(), params, [], i))
        else:
            if not cards:
                raise ValueError(f"line {i}: data before the first keyword")
            cards[-1].data.append([t.strip() for t in line.split(",") if t.strip()])
    return cards


# --------------------------------------------------------------------------- reading a run
@dataclass(frozen=True)
class SurfacePressure:
    """The contact pressure along the block's surface after one run.

    ``x`` are the block's surface nodes (deformed positions, sorted), ``p``
    the contact pressure there from CalculiX's nodal contact forces ``f``
    (:func:`force_pressure`), ``s22`` the block's surface stress ``-S22``
    (for comparison), ``gap`` the distance up to the punch's deformed face
    and ``cpress``/``copen`` CalculiX's contact output at those nodes where it
    was written (NaN elsewhere); ``P`` the load the base carries; ``a``, ``c``
    the contact ends from the gap (:func:`contact_edge`); ``vertex`` flags the
    vertex nodes of the quadratic faces.
    """

    x: np.ndarray
    p: np.ndarray
    gap: np.ndarray
    cpress: np.ndarray
    copen: np.ndarray
    P: float
    a: float
    c: float
    vertex: np.ndarray
    f: np.ndarray
    s22: np.ndarray


def surface_pressure(model: Model, stem: Path) -> SurfacePressure:
    """Read one run of :func:`write_deck`: pressure, gap, contact output, load and contact ends.

    The pressure is the contact's nodal forces (``*CONTACT PRINT`` CELS and
    CDIS in the ``.dat``, :func:`nodal_forces`) over the nodes' shares of the
    block's quadratic faces, freed of the vertex/midside alternation
    (:func:`force_pressure`); the shares are taken on the undeformed surface
    (small strain: a force per unit length of the reference surface).
    """
    frd = read_frd(stem)
    dat = read_dat(stem)
    U, S = frd["DISP"], frd["STRESS"]
    nb, npu = model.nsets["block_surface"], model.nsets["punch_profile"]
    ub = np.array([U[n][:2] for n in nb])
    up = np.array([U[n][:2] for n in npu])
    xb, yb = (model.xy[nb - 1] + ub).T
    xp, yp = (model.xy[npu - 1] + up).T
    order = np.argsort(xp)
    # the punch's face between its nodes by a cubic spline: a chord's sag h^2/(8R) would
    # exceed a stiff penalty's overclosure p/K and hide which nodes are closed
    from scipy.interpolate import CubicSpline

    gap = CubicSpline(xp[order], yp[order])(xb) - yb
    s22 = -np.array([S[n][1] for n in nb])
    cp = np.full(len(nb), np.nan)
    co = np.full(len(nb), np.nan)
    contact = frd.get("CONTACT", {})
    for k, n in enumerate(nb):
        if int(n) in contact:
            co[k], cp[k] = contact[int(n)][0], contact[int(n)][3]
    if "contact print energy" not in dat or "relative contact displacement" not in dat:
        raise CcxError(f"{stem}.dat holds no `*CONTACT PRINT` CDIS, CELS: the deck must request them")
    forces = nodal_forces(dat["relative contact displacement"], dat["contact print energy"],
                          model.n_nodes)
    f = np.array([forces.get(int(n), (0.0, 0))[0] for n in nb])
    vertex = np.zeros(len(model.xy) + 1, bool)
    for kind, conn in model.elements["block"]:
        vertex[conn[:4 if kind == "CPE8" else 3]] = True
    vertex = vertex[nb]
    order = np.argsort(xb)
    x, gap, cp, co, vertex, f, s22 = (v[order] for v in (xb, gap, cp, co, vertex, f, s22))
    p = force_pressure(model.xy[nb[order] - 1, 0], f, vertex)
    c = contact_edge(x, gap)
    a = contact_edge(-x[::-1], gap[::-1])
    P = float(read_reaction(stem)[1])
    return SurfacePressure(x, p, gap, cp, co, P, a, c, vertex, f, s22)


def ccx_available() -> bool:
    """Whether ``ccx`` (CalculiX) is on the PATH."""
    return shutil.which("ccx") is not None


class CcxError(RuntimeError):
    """``ccx`` ran but failed, or wrote no result."""

# --------------------------------------------------------------------------- run and read
class CcxMissing(OSError):
    """``ccx`` is not on the PATH."""



def run_ccx(deck: str, workdir: Path, name: str = "job", timeout: float = 900.0) -> Path:
    """Write ``deck`` to ``workdir/name.inp`` and run ``ccx`` on one thread; the job's stem.

    Raises
    ------
    CcxMissing
        If ``ccx`` is not installed.
    CcxError
        If ``ccx`` fails, or writes no result.
    """
    if not ccx_available():
        raise CcxMissing("`ccx` (CalculiX) is not on the PATH: apt-get install calculix-ccx")
    (workdir / f"{name}.inp").write_text(deck)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    proc = subprocess.run(["ccx", "-i", name], cwd=workdir, env=env, capture_output=True,
                          text=True, timeout=timeout)
    frd = workdir / f"{name}.frd"
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not frd.exists():
        err = [ln.strip() for ln in proc.stdout.splitlines() if "ERROR" in ln][:2]
        raise CcxError(f"ccx failed on {name}.inp in {workdir}: {' | '.join(err) or proc.stdout[-200:]}")
    return workdir / name


def read_frd(stem: Path) -> dict[str, dict[int, np.ndarray]]:
    """The last increment's nodal blocks of ``stem.frd``: ``{"DISP": {node: values}, "STRESS": ...}``."""
    out: dict[str, dict[int, np.ndarray]] = {}
    current: dict[int, np.ndarray] | None = None
    with open(f"{stem}.frd") as f:
        for line in f:
            if line.startswith(" -4"):
                current = {}
                out[line.split()[1]] = current          # later increments overwrite earlier
            elif line.startswith(" -1") and current is not None:
                n = int(line[3:13])
                vals = line[13:].rstrip("\n")
                current[n] = np.array([float(vals[12 * j:12 * j + 12]) for j in range(len(vals) // 12)])
            elif line.startswith(" -3"):
                current = None
    return out


def read_frd_nodes(stem: Path) -> dict[int, np.ndarray]:
    """The node coordinates of ``stem.frd`` (its ``2C`` block): ``{node: (x, y, z)}``."""
    out: dict[int, np.ndarray] = {}
    inside = False
    with open(f"{stem}.frd") as f:
        for line in f:
            if line.startswith("    2C"):
                inside = True
            elif inside and line.startswith(" -1"):
                out[int(line[3:13])] = np.array([float(line[13 + 12 * j:25 + 12 * j]) for j in range(3)])
            elif inside and line.startswith(" -3"):
                break
    return out


def read_descent(stem: Path) -> float:
    """The punch's descent: minus the last printed ``u_y`` of the reference node."""
    lines = Path(f"{stem}.dat").read_text().splitlines()
    i = max(k for k, ln in enumerate(lines) if ln.strip().startswith("displacements"))
    return -float(lines[i + 2].split()[2])


def read_increments(stem: Path) -> int | None:
    """How many increments the run's step took: the converged rows of ``stem.sta`` (None without it).

    A row whose attempt column ends in ``U`` is an attempt that did not
    converge and was cut back; the deck's model is one increment of the whole load.
    """
    sta = Path(f"{stem}.sta")
    if not sta.is_file():
        return None
    rows = [ln.split() for ln in sta.read_text().splitlines()[2:]]
    return sum(1 for r in rows if len(r) >= 3 and not r[2].endswith("U"))


def read_reaction(stem: Path) -> np.ndarray:
    """The last printed total reaction ``(RFx, RFy)`` of the block's base."""
    lines = Path(f"{stem}.dat").read_text().splitlines()
    i = max(k for k, ln in enumerate(lines) if ln.strip().startswith("total force"))
    return np.array([float(v) for v in lines[i + 2].split()[:2]])



# --------------------------------------------------------------------------- the contact's nodal forces
#: the nodes on each side of a node of the local fit that removes the vertex/midside alternation
#: (:func:`dealternate`): 9 nodes, 4 elements of a quadratic face
DEALTERNATE_NODES = 4


def read_dat(stem: Path) -> dict[str, dict[int, np.ndarray]]:
    """The printed blocks of ``stem.dat`` at the last time: ``{title: {node: values}}``.

    The title is the block's heading up to its first ``(``, followed by the set's
    name where the heading names one (``"displacements NSURF"``, ``"contact stress"``,
    ``"relative contact displacement"``, ``"contact print energy"``,
    ``"total force NBASE"``); a later time's block replaces an earlier one's.
    """
    out: dict[str, dict[int, np.ndarray]] = {}
    current: dict[int, np.ndarray] | None = None
    with open(f"{stem}.dat") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0][0].isalpha():
                title = line.split("(")[0].strip()
                if " for set " in line:
                    title += " " + line.split(" for set ")[1].split()[0]
                current = {}
                out[title] = current
                continue
            if current is not None and len(words) > 1:
                try:
                    current[int(words[0])] = np.array([float(w) for w in words[1:]])
                except ValueError:
                    current = None
    return out


def nodal_forces(copen: dict[int, np.ndarray], energy: dict[int, np.ndarray],
                 n_nodes: int) -> dict[int, tuple[float, int]]:
    """The contact's force at each slave node of a plane model: ``{node: (force, expanded nodes)}``.

    CalculiX expands a plane element to a 3-D one and writes the contact
    output on the expanded nodes: node ``n`` of ``n_nodes`` becomes
    ``n_nodes + 3(n - 1) + 1..3`` (three for a vertex node, two for a midside
    node of a quadratic face). The linear penalty law stores the energy
    ``K g^2 A / 2`` in a contact element of overclosure ``g = -COPEN`` and
    nodal area ``A``, and carries the force ``K g A``, so the force is
    ``-2 CELS / COPEN`` (compressive positive; an open element's ``-K COPEN``
    tension gives a small negative force). The forces of one plane node's
    expanded nodes are summed.
    """
    out: dict[int, tuple[float, int]] = {}
    for k, e in energy.items():
        if k not in copen:
            continue
        n = k if k <= n_nodes else (k - n_nodes - 1) // 3 + 1
        g = float(copen[k][0])
        f = -2.0 * float(e[0]) / g if g != 0.0 else 0.0
        prev = out.get(n, (0.0, 0))
        out[n] = (prev[0] + f, prev[1] + 1)
    return out


def nodal_areas(x: np.ndarray, vertex: np.ndarray, *, cut: bool = False) -> np.ndarray:
    """The shares ``∫ N_i dx`` of the nodes ``x`` (sorted) of a quadratic surface: ``L/6`` at a
    vertex from each element, ``2 L/3`` at a midside node, ``L`` the element's length.

    ``vertex`` flags the vertex nodes; they and the midside nodes alternate.
    ``cut``: the nodes are cut from a longer face (CalculiX's contact output
    covers the slave nodes near the master only), so an end vertex's missing
    element is taken as long as its neighbour.
    """
    w = np.zeros(len(x))
    for i in (int(k) for k in np.flatnonzero(~vertex)):
        lo, hi = max(i - 1, 0), min(i + 1, len(x) - 1)
        L = (x[hi] - x[lo]) * (2 if hi - lo == 1 else 1)
        w[i] += 2 * L / 3
        if hi - lo == 2:
            w[lo] += L / 6
            w[hi] += L / 6
    if cut:
        for j, step in ((0, 2), (1, 2), (len(x) - 1, -2), (len(x) - 2, -2)):
            if 0 <= j < len(x) and vertex[j] and 0 <= j + step < len(x) and not 0 <= j - step < len(x):
                w[j] *= 2
    return w


def dealternate(x: np.ndarray, p: np.ndarray, vertex: np.ndarray,
                m: int = DEALTERNATE_NODES) -> np.ndarray:
    """``p`` without its vertex/midside alternation: at each node, the value of the local fit
    ``q(x) + d_i`` over the ``2 m + 1`` nodes centred on it, ``q`` quadratic and ``d_i = 2 delta``
    at a vertex, ``-delta`` at a midside node; the ``m`` nodes at each end keep their value.

    A node-to-surface penalty's nodal forces over the nodes' shares of a
    quadratic face (:func:`nodal_areas`) still alternate between vertex and
    midside nodes by about 1 % of the peak; the offsets ``2 delta``,
    ``-delta`` carry no force over an element (``2 delta L/3 - delta 2 L/3 = 0``).
    The fit reproduces any quadratic exactly (no ``h^2 p''`` bias, unlike an
    average over an element).
    """
    n = len(x)
    d = np.where(vertex, 2.0, -1.0)
    out = np.array(p, dtype=float)
    if n < 2 * m + 1:
        return out
    for i in range(m, n - m):            # centred windows only: no extrapolation at the ends
        lo, hi = i - m, i + m + 1
        t = (x[lo:hi] - x[i]) / (x[hi - 1] - x[lo])
        A = np.c_[np.ones(hi - lo), t, t * t, d[lo:hi]]
        out[i] = np.linalg.lstsq(A, p[lo:hi], rcond=None)[0][0]
    return out


def force_pressure(x: np.ndarray, f: np.ndarray, vertex: np.ndarray, *, cut: bool = False) -> np.ndarray:
    """The contact pressure at the nodes ``x`` (sorted) of a quadratic slave face from their forces
    ``f``: ``f / ∫N_i dx`` (:func:`nodal_areas`) freed of the vertex/midside alternation
    (:func:`dealternate`) between the first and the last loaded node (``f > 0``).
    ``cut``: as :func:`nodal_areas`."""
    w = nodal_areas(x, vertex, cut=cut)
    p = np.divide(f, w, out=np.zeros_like(f), where=w > 0)
    on = np.flatnonzero(f > 0)
    if on.size:
        # the fit stays inside the loaded nodes: across a contact end it would spread the
        # square-root end's curvature onto the open nodes; the DEALTERNATE_NODES nodes next to
        # each end keep f / share (better for ∫p than an average over an element there:
        # 8.5e-4 against 1.0e-3 of P on the default deck)
        i, j = on[0], on[-1] + 1
        p[i:j] = dealternate(x[i:j], p[i:j], vertex[i:j])
    return p


def contact_edge(x: np.ndarray, gap: np.ndarray, k: int = 8) -> float:
    """The contact end from the gap just outside it: ``gap^(2/3)`` linear in ``x`` over ``k`` nodes.

    Outside a square-root pressure end the gap opens as ``(x - a)^(3/2)``
    (half-plane theory), so ``gap^(2/3)`` is linear there and its root is
    the end; the fit stays clear of the penalty's penetration inside.
    """
    closed = np.nonzero(gap <= 0)[0]
    j = np.arange(closed[-1] + 1, min(closed[-1] + 1 + k, len(x)))
    if len(j) < 2:            # the zone ends before k open nodes: the last closed node
        return float(x[closed[-1]])
    coef = np.polyfit(x[j], gap[j] ** (2 / 3), 1)
    return float(-coef[1] / coef[0])


def centre_pressure(x: np.ndarray, p: np.ndarray, a: float) -> float:
    """``p(0)`` of a symmetric pressure: ``p = c0 + c1 x^2 + c2 x^4`` fitted over ``|x| < 0.3 a``.

    The fit smooths the nodal stresses' scatter; a Hertz pressure departs from
    the quartic by ``(x/a)^6/16 < 5e-5`` of its peak there.
    """
    from threepart.fields import peak
    return peak(x, p, half_width=0.3 * a, degree=4, symmetric=True)[1]



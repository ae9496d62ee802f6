"""The small-slope error of half-plane theory, measured with finite-deformation FE (CalculiX).

Half-plane theory (the paper's eqs. 1-4, and every solver in threepart) takes
the contact on the undeformed, flat surface and the strains as small. Both
fail as the surface slope ``max |v'(x)|`` over the contact grows. This
benchmark presses a stiff punch of threepart's profile (eq. 2) onto a large
elastic block in CalculiX, once geometrically linear and once with ``NLGEOM``
(finite deformation), on the same mesh with the same penalty, and reports, as
a function of the slope,

- the relative change of the peak pressure and of the contact half-width
  from the linear run to the finite-deformation run (the small-slope error);
- the linear run against threepart's closed form (the FE model's own error,
  which must stay well below the effect measured).

The model is independent of threepart's FEM (``fem/``): its own gmsh mesh,
CalculiX's CPE8 elements and node-to-surface penalty contact. Only the closed
form (``threepart.closedform.solve_normal``) is used, as the reference for the
linear run and to size the mesh and choose the loads.

The deck is built by small functions -- mesh to ``*NODE``/``*ELEMENT`` text,
node sets, surfaces, material, contact, constraints, step -- so that a later
``threepart deck --format calculix`` can reuse them.

Usage::

    python benchmarks/small_slope_calculix.py                 # Hertz, the default slopes
    python benchmarks/small_slope_calculix.py --slopes 0.02 0.1 --n-fine 200   # mesh check

It needs ``ccx`` (Debian: ``apt-get install calculix-ccx``) and exits with
status 2 and one line when ``ccx`` is missing. It is not part of the test run.
The method, the deck settings and the measured table: ``docs/SMALL_SLOPE.md``.
"""
from __future__ import annotations

import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from threepart.closedform import solve_normal
from threepart.material import compliance
from threepart.punch import Punch

__all__ = ["Material", "Mesh", "build_mesh", "nodes_text", "elements_text", "nset_text",
           "surface_text", "material_text", "contact_text", "equation_text", "boundary_text",
           "step_text", "write_deck", "run_ccx", "read_frd", "read_reaction", "read_descent",
           "ContactProfile", "contact_edge", "centre_pressure", "profile", "Row", "load_for_slope",
           "run_case", "fit_law", "slope_at", "table", "main"]

#: gmsh element type -> (CalculiX element, number of corner nodes)
GMSH_TO_CCX = {16: ("CPE8", 4), 9: ("CPE6", 3)}


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


def build_mesh(punch: Punch, a: float, *, h0: float, x_fine: float, grading: float = 0.25,
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

    b, R2 = punch.b, punch.R2
    Lx, D = block * a, 2 * block * a
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
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

        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
        index[node_tags.astype(np.int64)] = np.arange(1, node_tags.size + 1)
        xy = coords.reshape(-1, 3)[:, :2].copy()

        elements: dict[str, list[tuple[str, np.ndarray]]] = {}
        for body, s in (("block", s_block), ("punch", s_punch)):
            elements[body] = []
            etypes, _, enodes = gmsh.model.mesh.getElements(2, s)
            for et, en in zip(etypes, enodes):
                kind, n_corner = GMSH_TO_CCX[int(et)]
                conn = index[en.astype(np.int64)].reshape(-1, 2 * n_corner)
                for row in conn:
                    elements[body].append((kind, _counterclockwise(row, xy, n_corner)))
        nsets = {}
        for name in ("block_top", "block_fine", "block_bottom", "block_sym", "punch_contact",
                     "punch_fine", "punch_top", "punch_sym"):
            t, _ = gmsh.model.mesh.getNodesForPhysicalGroup(1, tags[name])
            nsets[name] = np.unique(index[t.astype(np.int64)])
    finally:
        gmsh.finalize()

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


def write_deck(mesh: Mesh, mat: Material, *, K: float, sigma_inf: float, nlgeom: bool,
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


# --------------------------------------------------------------------------- run and read
class CcxMissing(OSError):
    """``ccx`` is not on the PATH."""


def run_ccx(deck: str, workdir: Path, name: str = "job", timeout: float = 900.0) -> Path:
    """Write ``deck`` to ``workdir/name.inp`` and run ``ccx`` on one thread; the job's stem.

    Raises
    ------
    CcxMissing
        If ``ccx`` is not installed.
    RuntimeError
        If ``ccx`` fails, or writes no result.
    """
    if shutil.which("ccx") is None:
        raise CcxMissing("`ccx` (CalculiX) is not on the PATH: apt-get install calculix-ccx")
    (workdir / f"{name}.inp").write_text(deck)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    proc = subprocess.run(["ccx", "-i", name], cwd=workdir, env=env, capture_output=True,
                          text=True, timeout=timeout)
    frd = workdir / f"{name}.frd"
    if proc.returncode != 0 or "*ERROR" in proc.stdout or not frd.exists():
        err = [ln.strip() for ln in proc.stdout.splitlines() if "ERROR" in ln][:2]
        raise RuntimeError(f"ccx failed on {name}.inp in {workdir}: {' | '.join(err) or proc.stdout[-200:]}")
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


def read_descent(stem: Path) -> float:
    """The punch's descent: minus the last printed ``u_y`` of the reference node."""
    lines = Path(f"{stem}.dat").read_text().splitlines()
    i = max(k for k, ln in enumerate(lines) if ln.strip().startswith("displacements"))
    return -float(lines[i + 2].split()[2])


def read_reaction(stem: Path) -> np.ndarray:
    """The last printed total reaction ``(RFx, RFy)`` of the block's base."""
    lines = Path(f"{stem}.dat").read_text().splitlines()
    i = max(k for k, ln in enumerate(lines) if ln.strip().startswith("total force"))
    return np.array([float(v) for v in lines[i + 2].split()[:2]])


# --------------------------------------------------------------------------- analysis
@dataclass(frozen=True)
class ContactProfile:
    """The contact after one CalculiX run.

    ``x`` are the block's surface nodes (deformed positions), ``p`` the
    normal stress ``-sigma_yy`` there and ``gap`` their distance up to the
    deformed punch; ``P`` the whole
    load (twice the half model's base reaction); ``peak`` the pressure at
    ``x = 0`` and ``a`` the contact's half-width.
    """

    x: np.ndarray
    p: np.ndarray
    gap: np.ndarray
    P: float
    peak: float
    a: float


def contact_edge(x: np.ndarray, gap: np.ndarray, k: int = 8) -> float:
    """The contact end from the gap just outside it: ``gap^(2/3)`` linear in ``x`` over ``k`` nodes.

    Outside a square-root pressure end the gap opens as ``(x - a)^(3/2)``
    (half-plane theory), so ``gap^(2/3)`` is linear there and its root is
    the end; the fit stays clear of the penalty's penetration inside.
    """
    closed = np.nonzero(gap <= 0)[0]
    j = np.arange(closed[-1] + 1, closed[-1] + 1 + k)
    coef = np.polyfit(x[j], gap[j] ** (2 / 3), 1)
    return float(-coef[1] / coef[0])


def centre_pressure(x: np.ndarray, p: np.ndarray, a: float) -> float:
    """``p(0)`` of a symmetric pressure: ``p = c0 + c1 x^2 + c2 x^4`` fitted over ``|x| < 0.3 a``.

    The fit smooths the nodal stresses' scatter; a Hertz pressure departs from
    the quartic by ``(x/a)^6/16 < 5e-5`` of its peak there.
    """
    m = np.abs(x) < 0.3 * a
    return float(np.polyfit(x[m] ** 2, p[m], 2)[-1])


def profile(mesh: Mesh, stem: Path) -> ContactProfile:
    """Read one run: the surface pressure, the gap to the punch, the load, peak and half-width.

    Positions are deformed (``X + u``) in both runs: CalculiX pairs the
    contact on the current surfaces even in a geometrically linear step.
    The pressure is the block's ``-sigma_yy`` at its surface nodes (Cauchy
    stress with ``NLGEOM``; at ``x = 0`` the surface normal stays vertical by
    symmetry, so it is the contact pressure there). The node-to-surface
    penalty on quadratic faces leaves the vertex nodes about 5 % above the
    midside nodes, so the peak is the mean of two fits, one over each kind.
    """
    frd = read_frd(stem)
    U, S = frd["DISP"], frd["STRESS"]
    nb, npu = mesh.nsets["block_fine"], mesh.nsets["punch_fine"]
    ub = np.array([U[n][:2] for n in nb])
    up = np.array([U[n][:2] for n in npu])
    xb, yb = (mesh.xy[nb - 1] + ub).T
    xp, yp = (mesh.xy[npu - 1] + up).T
    order = np.argsort(xp)
    gap = np.interp(xb, xp[order], yp[order]) - yb
    p = -np.array([S[n][1] for n in nb])
    vertex = np.zeros(len(mesh.xy) + 1, bool)
    for kind, conn in mesh.elements["block"]:
        vertex[conn[:4 if kind == "CPE8" else 3]] = True
    vertex = vertex[nb]
    order = np.argsort(xb)
    x, p, gap, vertex = xb[order], p[order], gap[order], vertex[order]
    a = contact_edge(x, gap)
    peak = 0.5 * (centre_pressure(x[vertex], p[vertex], a) + centre_pressure(x[~vertex], p[~vertex], a))
    P = 2 * float(read_reaction(stem)[1])
    return ContactProfile(x, p, gap, P, peak, a)


# --------------------------------------------------------------------------- the study
@dataclass(frozen=True)
class Row:
    """One load: the closed form, the linear run and the finite-deformation run.

    The linear run carries the load ``P``; the finite-deformation run is
    driven by the linear run's descent (displacement control converges in one
    increment, force control does not), so it carries a slightly different
    load ``nl.P``. Its peak and half-width are brought back to ``P`` with the
    closed form's local exponents ``s_p = dln p(0)/dln P`` and
    ``s_a = dln a/dln P`` (1/2 and 1/2 for Hertz).
    """

    slope: float
    P: float
    load: float                 # 4PA/b (case A) or P (Hertz)
    a_cf: float
    p_cf: float
    s_p: float
    s_a: float
    lin: ContactProfile
    nl: ContactProfile
    seconds: float
    nodes: int

    @property
    def nl_peak(self) -> float:
        """The finite-deformation peak at the load ``P``."""
        return self.nl.peak * (self.P / self.nl.P) ** self.s_p

    @property
    def nl_a(self) -> float:
        """The finite-deformation half-width at the load ``P``."""
        return self.nl.a * (self.P / self.nl.P) ** self.s_a

    @property
    def d_peak(self) -> float:
        """Small-slope error of the peak: NLGEOM over linear, minus 1, at the load ``P``."""
        return self.nl_peak / self.lin.peak - 1

    @property
    def d_a(self) -> float:
        """Small-slope error of the half-width: NLGEOM over linear, minus 1, at the load ``P``."""
        return self.nl_a / self.lin.a - 1

    @property
    def lin_peak(self) -> float:
        """The linear run's peak against the closed form (its own error)."""
        return self.lin.peak / self.p_cf - 1

    @property
    def lin_a(self) -> float:
        """The linear run's half-width against the closed form."""
        return self.lin.a / self.a_cf - 1

    @property
    def nl_peak_cf(self) -> float:
        """The finite-deformation peak against the closed form: half-plane theory's whole error."""
        return self.nl_peak / self.p_cf - 1

    @property
    def nl_a_cf(self) -> float:
        """The finite-deformation half-width against the closed form."""
        return self.nl_a / self.a_cf - 1


def load_for_slope(punch: Punch, slope: float, A: float) -> float:
    """Load ``P`` whose symmetric contact reaches the edge slope ``slope``.

    On the arcs ``|v'(a)| = (a - b)/R2`` (eq. 2), so ``a = b + slope R2``,
    and ``P`` is eq. (equilibrium_condition_1) at ``a = c``.
    """
    from threepart.closedform import formulas

    a = punch.b + slope * punch.R2
    return float(formulas.load(punch, a, a, A))


def _closed_form(punch: Punch, P: float, A: float) -> tuple[float, float]:
    """Closed-form half-width and centre pressure at ``P``."""
    cf = solve_normal(punch, P, 0.0, A=A)
    return cf.a, float(cf.pressure(np.array([0.0]))[0])


def run_case(punch: Punch, slope: float, mat: Material, workdir: Path, *, n_fine: int = 300,
             penalty: float = 20.0, increments: int | None = None) -> Row:
    """Both runs at the load of edge slope ``slope``; ``h0 = a/n_fine``, ``K = penalty E/h0``.

    The NLGEOM step takes ``increments`` fixed increments, by default
    ``max(5, 40 slope)``: the surface slides along the punch by about a
    mesh cell per increment at most, which keeps its Newton iteration
    converging.
    """
    if increments is None:
        increments = max(5, round(40 * slope))
    P = load_for_slope(punch, slope, mat.A)
    a_cf, p_cf = _closed_form(punch, P, mat.A)
    (a_m, p_m), (a_p, p_p) = (_closed_form(punch, P * f, mat.A) for f in (1 - 1e-4, 1 + 1e-4))
    d = math.log((1 + 1e-4) / (1 - 1e-4))
    s_p, s_a = math.log(p_p / p_m) / d, math.log(a_p / a_m) / d
    h0 = a_cf / n_fine
    t0 = time.perf_counter()
    mesh = build_mesh(punch, a_cf, h0=h0, x_fine=1.3 * a_cf)
    K, sigma_inf = penalty * mat.E / h0, 1e-6 * p_cf
    stem = run_ccx(write_deck(mesh, mat, nlgeom=False, F=P / 2, K=K, sigma_inf=sigma_inf),
                   workdir, f"s{slope:g}_lin")
    lin = profile(mesh, stem)
    stem = run_ccx(write_deck(mesh, mat, nlgeom=True, delta=read_descent(stem),
                              increments=increments, K=K, sigma_inf=sigma_inf),
                   workdir, f"s{slope:g}_nl")
    nl = profile(mesh, stem)
    load = 4 * P * mat.A / punch.b if punch.b > 0 else P
    return Row(slope, P, load, a_cf, p_cf, s_p, s_a, lin, nl, time.perf_counter() - t0, len(mesh.xy))


def fit_law(slopes: np.ndarray, errors: np.ndarray) -> tuple[float, float]:
    """``|error| = k slope^m`` fitted on logs (``np.polyfit``); returns ``(k, m)``."""
    m, logk = np.polyfit(np.log(slopes), np.log(np.abs(errors)), 1)
    return float(np.exp(logk)), float(m)


def slope_at(k: float, m: float, error: float) -> float:
    """The slope at which the fitted law ``k slope^m`` reaches ``error``."""
    return float((error / k) ** (1 / m))


def table(rows: list[Row]) -> str:
    """The results as a Markdown table (relative changes in per cent)."""
    head = ("| slope a/R or (a-b)/R2 | P (N/mm) | 4PA/b | peak NLGEOM/lin - 1 | a NLGEOM/lin - 1 "
            "| peak NLGEOM/closed form - 1 | a NLGEOM/closed form - 1 | peak lin/closed form - 1 "
            "| a lin/closed form - 1 | P_nl/P | nodes | s |\n" + "|---" * 12 + "|\n")
    out = []
    for r in rows:
        pct = [f"{100 * v:+.2f} %" for v in (r.d_peak, r.d_a, r.nl_peak_cf, r.nl_a_cf, r.lin_peak, r.lin_a)]
        load = f"{r.load:.4g}" if r.load != r.P else "-"
        out.append(f"| {r.slope:g} | {r.P:.5g} | {load} | " + " | ".join(pct)
                   + f" | {r.nl.P / r.P:.4f} | {r.nodes} | {r.seconds:.0f} |")
    return head + "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slopes", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.2, 0.3],
                        help="edge slopes |v'(a)| to run")
    parser.add_argument("--n-fine", type=int, default=100, help="elements per half-width a at the contact")
    parser.add_argument("--penalty", type=float, default=20.0, help="penalty stiffness K in E/h0")
    parser.add_argument("--increments", type=int, default=None,
                        help="increments of the NLGEOM step (default max(5, 40 slope))")
    parser.add_argument("--keep", type=Path, default=None, help="keep the decks and results here")
    args = parser.parse_args(argv)
    if shutil.which("ccx") is None:
        print("small_slope_calculix: `ccx` (CalculiX) is not on the PATH; "
              "install it with `apt-get install calculix-ccx`", file=sys.stderr)
        return 2
    punch = Punch(10.0, 10.0, 0.0)        # Hertz: the peak is measured at x = 0
    mat = Material()
    rows = []
    with tempfile.TemporaryDirectory(prefix="small_slope_") as tmp:
        workdir = args.keep or Path(tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        for slope in args.slopes:
            try:
                row = run_case(punch, slope, mat, workdir, n_fine=args.n_fine,
                               penalty=args.penalty, increments=args.increments)
            except RuntimeError as exc:          # one load that does not converge ends no study
                print(f"slope {slope:g}: {exc}", file=sys.stderr, flush=True)
                continue
            rows.append(row)
            print(f"slope {slope:g}: peak {100 * row.d_peak:+.3f} %, a {100 * row.d_a:+.3f} % "
                  f"({row.seconds:.0f} s)", file=sys.stderr, flush=True)
    print(f"Hertz, R = {punch.R1:g} mm, n_fine = {args.n_fine}, K = {args.penalty:g} E/h0, "
          f"NLGEOM increments {args.increments or 'max(5, 40 slope)'}\n")
    print(table(rows))
    if len(rows) >= 2:
        s = np.array([r.slope for r in rows])
        for name, err in (("peak", [r.d_peak for r in rows]), ("a", [r.d_a for r in rows]),
                          ("peak vs closed form", [r.nl_peak_cf for r in rows])):
            k, m = fit_law(s, np.array(err))
            print(f"|{name}| ~ {k:.3g} slope^{m:.2f}: 1 % at slope {slope_at(k, m, 0.01):.3g}, "
                  f"5 % at slope {slope_at(k, m, 0.05):.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The text of a CalculiX deck (CalculiX's dialect of the Abaqus input format), and a parser to check it.

Names
-----
DeckSettings     -- mesh size, penalty stiffness, punch stiffening, pair or stiff punch, block size
check_mesh_size  -- ``h`` if the contact width holds :data:`W_OVER_H` elements, else ValueError
W_OVER_H         -- the admissible elements across the contact width W = a + c
Material         -- the half model's block and its stiffened punch (E, nu, stiffening)
write_deck       -- the deck of a model: sets, materials, contact, load at ``s``, free or suppressed tilt
half_deck        -- the deck of the small-slope benchmark's half model (a force or a descent)
CONVENTIONS      -- the comment block every deck carries (units, conventions, pitfalls)
nodes_text, elements_text, nset_text, surface_text, material_text, contact_text,
equation_text, boundary_text, step_text -- one card (or a few) each
Keyword          -- one keyword card: its name, parameters and data lines
parse_deck       -- a minimal keyword parser (``*KEYWORD, PARAM=...`` and data lines) for checks
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..problem.material import compliance
from ..problem.checks import check_tilt, finite, positive
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:   # pragma: no cover - the models' types only; mesh.py imports this module
    from .mesh import Mesh, Model

__all__ = ["DeckSettings", "check_mesh_size", "W_OVER_H", "Material", "write_deck", "half_deck",
           "CONVENTIONS", "nodes_text", "elements_text", "nset_text", "surface_text", "material_text",
           "contact_text", "equation_text", "boundary_text", "step_text", "Keyword", "parse_deck",
           "deck_head", "lid_nodes"]

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
        raise InputError("give the force `F` or the descent `delta`, not both or neither")
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
            raise InputTypeError(f"`pair` = {self.pair!r} must be a bool")

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
        raise InputError(f"`h` (`--h`) = {h:.4g} gives W/h = {W / h:.4g} elements across the contact "
                         f"width W = a + c = {W:.6g}; give W/h from {lo:g} to {hi:g}, h from "
                         f"{W / hi:.4g} to {W / lo:.4g}")
    return h


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
        raise InputError(f"a half model needs `s` = 0 (got {s:g}) and `clamped` (got {clamped})")
    if not half and settings.tilt == "free" and not xL < s < xR:
        raise InputError(f"`s` = {s:g} must lie on the punch's top, between {xL:g} and {xR:g}")
    top = model.nsets["punch_top"]
    base = model.nsets["block_base"]
    mid = int(base[np.argmin(np.abs(model.xy[base - 1, 0] - 0.5 * (model.c - model.a)))])
    E_punch = E if settings.pair else E * settings.stiffening
    p_est = 2 * P / (math.pi * W)
    parts = [deck_head(model, P=P, s=s, E=E, K=K, settings=settings, title=title),
             "*HEADING\nthreepart: a three-part punch on an elastic block, plane strain\n",
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
    rows, loads = lid_nodes(model, P=P, s=s, tilt=settings.tilt, half=half)
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


def deck_head(model: Model, *, P: float, s: float, E: float, K: float, settings: DeckSettings,
               title: str) -> str:
    """The deck's comment header: the punch, the load, the mesh, the slopes, then :data:`CONVENTIONS`."""
    W = model.a + model.c
    return (f"** threepart deck: {title or 'a three-part punch on an elastic block'}\n"
            f"** punch R1 = {model.punch.R1:.15g}, R2 = {model.punch.R2:.15g}, b = {model.punch.b:.15g},"
            f" R = {model.punch.R:.15g} (eq. 2); P = {P:.15g} at s = {s:.15g}, tilt {settings.tilt}\n"
            f"** expected contact [-a, c] = [{-model.a:.10g}, {model.c:.10g}]; h = {model.h0:.6g},"
            f" K = {K:.6g}; {'two similar bodies' if settings.pair else f'punch {settings.stiffening:g} x stiffer'}"
            f"; the face is raised by {model.lift:.6g} to touch y = 0\n"
            f"** small slopes and strains: the largest slope over the contact is "
            f"{model.punch.max_slope(model.a, model.c):.3g}, the mean pressure P/W over E "
            f"{P / (W * E):.3g}\n" + CONVENTIONS)


def lid_nodes(model: Model, *, P: float, s: float, tilt: str, half: bool) -> tuple[list[str], str]:
    """The punch's top as a lid: the ``*EQUATION`` rows tying its nodes to its two control
    nodes, and the ``*CLOAD`` lines that put ``P`` at ``s`` on them (``P / 2`` on a half model)."""
    tl, tr = model.control_nodes()
    xL, xR = model.xy[tl - 1, 0], model.xy[tr - 1, 0]
    rows = []
    for n in model.nsets["punch_top"]:
        n = int(n)
        if n == tl or (n == tr and not half):
            continue
        if half:                 # the plate's tilt is zero by symmetry
            rows.append(f"2\n{n}, 2, 1., {tl}, 2, -1.")
        elif tilt == "free":
            t = (model.xy[n - 1, 0] - xL) / (xR - xL)
            rows.append(f"3\n{n}, 2, 1., {tl}, 2, {-(1 - t):.15g}, {tr}, 2, {-t:.15g}")
        else:
            rows.append(f"2\n{n}, 2, 1., {tl}, 2, -1.")
    if half:
        loads = f"{tl}, 2, {-0.5 * P:.15g}\n"
    elif tilt == "suppressed":
        rows.append(f"2\n{tr}, 2, 1., {tl}, 2, -1.")
        loads = f"{tl}, 2, {-P:.15g}\n"
    else:
        F_R = P * (s - xL) / (xR - xL)
        loads = f"{tl}, 2, {-(P - F_R):.15g}\n{tr}, 2, {-F_R:.15g}\n"
    return rows, loads


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
                raise InputError(f"line {i}: empty keyword")
            params = {}
            for it in items[1:]:
                if not it:
                    continue
                key, eq, value = it.partition("=")
                if eq and not (key.strip() and value.strip()):
                    raise InputError(f"line {i}: malformed parameter {it!r}")
                params[key.strip().upper()] = value.strip()
            cards.append(Keyword(items[0].upper(), params, [], i))
        else:
            if not cards:
                raise InputError(f"line {i}: data before the first keyword")
            cards[-1].data.append([t.strip() for t in line.split(",") if t.strip()])
    return cards


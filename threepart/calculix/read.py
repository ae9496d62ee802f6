"""Every reader of CalculiX's output: the ``.frd``, ``.dat`` and ``.sta`` files of a run, and the
contact pressure made from them.

Files
-----
read_frd         -- the nodal result blocks of an ``.frd`` file (DISP, STRESS, CONTACT, CELS), last increment
read_frd_nodes   -- the node coordinates of an ``.frd`` file
read_dat         -- the printed blocks of a ``.dat`` file (node sets, contact output), last time
read_reaction    -- the total reaction force of a printed node set (``.dat``)
read_descent     -- the punch's descent: the last printed ``u_y`` of its reference node (``.dat``)
read_increments  -- how many increments the step took (``.sta``)
deck_nodes       -- the node coordinates of a deck's ``*NODE`` cards (a ``.dat`` has none)

The contact pressure
--------------------
nodal_forces     -- the contact's force at each slave node, ``-2 CELS / COPEN`` (plane models)
nodal_areas      -- the nodes' shares ``∫N_i dx`` of a quadratic surface (L/6, 2L/3, L/6)
vertex_flags     -- which slave nodes are vertices, from their counts of expanded nodes
element_vertices -- which nodes are vertices, from the elements' connectivity
dealternate      -- nodal values freed of the vertex/midside alternation (a local fit)
DEALTERNATE_NODES -- the nodes on each side of the local fit
force_pressure   -- the contact pressure from the nodal forces: over the shares, de-alternated
penalty_stiffness -- the penalty ``K = CPRESS / -COPEN`` at the closed nodes
contact_pressure -- the pressure points ``(x, p, info)`` of a run's ``.frd`` or ``.dat`` alone
surface_gap      -- the block's surface nodes (deformed), their gap to the punch's face and ``-S22``
surface_pressure -- the contact pressure along the block's surface of a model's run (x, p, gap, CPRESS)
SurfacePressure  -- what :func:`surface_pressure` returns
contact_edge     -- a contact end from the gap just outside it (``gap^(2/3)`` linear)
centre_pressure  -- ``p(0)`` of a symmetric pressure from a quartic fit about the centre

Every file's text is read and checked line by line in :mod:`.files`: a missing,
binary or truncated file, a number that does not read or is not finite, is one
:class:`~threepart.errors.ReaderError` naming the file (and the line), never NaN.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from threepart.results.fields import peak

from .deck import parse_deck
from .files import file_label, frd_blocks, last_printed, run_file
from .run import CcxError
from threepart.errors import InputError, ReaderError
from threepart.textfile import finite_row, read_text

if TYPE_CHECKING:   # pragma: no cover - the model's type only
    from .mesh import Model

__all__ = ["read_frd", "read_frd_nodes", "read_dat", "read_reaction", "read_descent", "read_increments",
           "deck_nodes", "nodal_forces", "nodal_areas", "vertex_flags", "element_vertices", "dealternate", "DEALTERNATE_NODES",
           "force_pressure", "penalty_stiffness", "contact_pressure", "surface_gap", "surface_pressure",
           "SurfacePressure", "contact_edge", "centre_pressure"]

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
    nb, npu = model.nsets["block_surface"], model.nsets["punch_profile"]
    xb, gap = surface_gap(model.xy, frd["DISP"], nb, npu)
    s22 = -np.array([frd["STRESS"][n][1] for n in nb])
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
    vertex = element_vertices(model.elements["block"], nb, model.n_nodes)
    order = np.argsort(xb)
    x, gap, cp, co, vertex, f, s22 = (v[order] for v in (xb, gap, cp, co, vertex, f, s22))
    p = force_pressure(model.xy[nb[order] - 1, 0], f, vertex)
    c = contact_edge(x, gap)
    a = contact_edge(-x[::-1], gap[::-1])
    P = float(read_reaction(stem)[1])
    return SurfacePressure(x, p, gap, cp, co, P, a, c, vertex, f, s22)


def surface_gap(xy: np.ndarray, disp: dict[int, np.ndarray], block: np.ndarray, punch: np.ndarray,
                *, spline: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """The block's surface nodes ``block`` at their deformed ``x`` (unsorted), and their gap up
    to the punch's deformed face through its nodes ``punch``.

    ``xy`` are the undeformed coordinates (row ``n - 1`` is node ``n``), ``disp`` the
    ``.frd``'s DISP block. ``spline``: the punch's face between its nodes by a
    cubic spline (a chord's sag ``h^2/(8R)`` would exceed a stiff penalty's
    overclosure ``p/K`` and hide which nodes are closed); otherwise by its chords.
    """
    from scipy.interpolate import CubicSpline

    ub = np.array([disp[n][:2] for n in block])
    up = np.array([disp[n][:2] for n in punch])
    xb, yb = (xy[block - 1] + ub).T
    xp, yp = (xy[punch - 1] + up).T
    order = np.argsort(xp)
    face = CubicSpline(xp[order], yp[order])(xb) if spline else np.interp(xb, xp[order], yp[order])
    return xb, face - yb


def element_vertices(elements: list[tuple[str, np.ndarray]], nodes: np.ndarray, n_nodes: int) -> np.ndarray:
    """Which of ``nodes`` are corner (vertex) nodes of the CPE8/CPE6 ``elements``, not midside nodes."""
    vertex = np.zeros(n_nodes + 1, bool)
    for kind, conn in elements:
        vertex[conn[:4 if kind == "CPE8" else 3]] = True
    return vertex[nodes]


def read_frd(stem: str | Path, *, arg: str | None = None) -> dict[str, dict[int, np.ndarray]]:
    """The last increment's nodal blocks of ``stem.frd`` (or of ``stem`` itself if it ends in
    ``.frd``): ``{"DISP": {node: values}, "STRESS": ...}``. ReaderError (naming ``arg`` and the
    line): not UTF-8 text, a number that does not read or is not finite, a truncated file."""
    path = run_file(stem, ".frd")
    blocks = frd_blocks(path, file_label(path, arg))
    blocks.pop("2C", None)
    return blocks


def read_frd_nodes(stem: str | Path, *, arg: str | None = None) -> dict[int, np.ndarray]:
    """The node coordinates of ``stem.frd`` (its ``2C`` block): ``{node: (x, y, z)}``;
    ReaderError as :func:`read_frd`, and if the file has no node block."""
    path = run_file(stem, ".frd")
    label = file_label(path, arg)
    nodes = frd_blocks(path, label).get("2C")
    if not nodes:
        raise ReaderError(f"{label} has no node coordinates (no 2C block of -1 lines): not a "
                          "CalculiX result, or one cut down too far")
    return nodes


def read_descent(stem: str | Path) -> float:
    """The punch's descent: minus the last printed ``u_y`` of the reference node."""
    where, words = last_printed(stem, "displacements")
    return -finite_row(words[2:3] or ["(none)"], where)[0]


def read_increments(stem: Path) -> int | None:
    """How many increments the run's step took: the converged rows of ``stem.sta`` (None without it).

    A row whose attempt column ends in ``U`` is an attempt that did not
    converge and was cut back; the deck's model is one increment of the whole load.
    """
    sta = run_file(stem, ".sta")
    if not sta.is_file():
        return None
    rows = [ln.split() for ln in read_text(sta, file_label(sta, None)).splitlines()[2:]]
    return sum(1 for r in rows if len(r) >= 3 and not r[2].endswith("U"))


def read_reaction(stem: str | Path) -> np.ndarray:
    """The last printed total reaction ``(RFx, RFy)`` of the block's base."""
    where, words = last_printed(stem, "total force")
    if len(words) < 2:
        raise ReaderError(f"{where}: {' '.join(words)!r} is not a total force RFx RFy")
    return np.array(finite_row(words[:2], where))



# --------------------------------------------------------------------------- the contact's nodal forces
#: the nodes on each side of a node of the local fit that removes the vertex/midside alternation
#: (:func:`dealternate`): 9 nodes, 4 elements of a quadratic face
DEALTERNATE_NODES = 4


def read_dat(stem: str | Path, *, arg: str | None = None) -> dict[str, dict[int, np.ndarray]]:
    """The printed blocks of ``stem.dat`` at the last time: ``{title: {node: values}}``.

    The title is the block's heading up to its first ``(``, followed by the set's
    name where the heading names one (``"displacements NSURF"``, ``"contact stress"``,
    ``"relative contact displacement"``, ``"contact print energy"``,
    ``"total force NBASE"``); a later time's block replaces an earlier one's. ``stem`` may
    name the ``.dat`` itself; ``arg`` names it in the messages. A row of numbers that is not
    finite (``NaN``, ``Infinity``) is a :class:`ReaderError` naming the file and the line.
    """
    path = run_file(stem, ".dat")
    label = file_label(path, arg)
    out: dict[str, dict[int, np.ndarray]] = {}
    current: dict[int, np.ndarray] | None = None
    for i, line in enumerate(read_text(path, label).splitlines(), start=1):
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
                n = int(words[0])
            except ValueError:          # not a node's row (a total force's): the block ends
                current = None
                continue
            current[n] = np.array(finite_row(words[1:], f"{label}, line {i} (node {n})"))
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
    return peak(x, p, half_width=0.3 * a, degree=4, symmetric=True)[1]




# --------------------------------------------------------------------------- a run's file alone
def deck_nodes(inp: str | Path, *, beside: str | None = None) -> dict[int, np.ndarray]:
    """The node coordinates of a deck's ``*NODE`` cards: ``{node: (x, y)}``; a node number or
    coordinate that does not read, or is not finite, is a ReaderError naming the deck (and
    ``beside``, how the messages name the ``.dat`` it gives the coordinates of)."""
    label = file_label(Path(inp), None) if beside is None else f"the deck {str(inp)!r} beside {beside}"
    out: dict[int, np.ndarray] = {}
    try:
        cards = parse_deck(read_text(inp, label))
    except InputError as exc:
        raise ReaderError(f"{label}, {exc}") from None
    for card in cards:
        if card.name == "NODE":
            for row in card.data:
                where = f"{label}, *NODE row {', '.join(map(str, row))!r}"
                if len(row) < 3 or not str(row[0]).strip().isdigit():
                    raise ReaderError(f"{where}: not a node number and two coordinates")
                out[int(row[0])] = np.array(finite_row([str(v) for v in row[1:3]], where))
    return out


def vertex_flags(counts: np.ndarray) -> np.ndarray:
    """Which of the slave nodes (sorted along the face) are vertices of its quadratic faces.

    CalculiX writes three expanded nodes of a vertex node and two of a midside
    node; the two alternate, and the parity that most counts agree with decides.
    """
    even = np.arange(counts.size) % 2 == 0
    agree = np.count_nonzero((counts == 3) == even)
    return even if agree >= counts.size - agree else ~even


def penalty_stiffness(copen: np.ndarray, cpress: np.ndarray) -> float:
    """The penalty stiffness ``K = CPRESS / -COPEN`` at the closed nodes (NaN if fewer than 3).

    ``PRESSURE-OVERCLOSURE=LINEAR`` is linear where the contact is closed
    (``COPEN < 0``); at an open node CalculiX writes the tension ``sigma_inf``
    of the law's second data item instead (``threepart deck``: 1e-6 of the mean
    pressure), so ``-CPRESS / COPEN`` there is ``sigma_inf / COPEN``, not ``K``
    (on caseA_sym it read 86 MPa/mm for the deck's 2.09e9).
    """
    closed = (copen < 0) & (cpress > 0)
    return float(np.median(cpress[closed] / -copen[closed])) if np.count_nonzero(closed) >= 3 else math.nan


def contact_pressure(path: str | Path, *, arg: str = "path") -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """The contact pressure points ``(x, p, info)`` of one run's ``.frd`` or ``.dat`` file alone.

    ``.frd`` (``*CONTACT FILE`` CDIS, CSTR, CELS) or ``.dat`` (``*CONTACT PRINT``
    CSTR, CDIS, CELS, with the deck ``job.inp`` beside ``job.dat`` for the
    coordinates, which a ``.dat`` lacks): the contact's nodal forces over the
    nodes' shares of the quadratic slave faces, freed of the vertex/midside
    alternation (:func:`force_pressure`), at the slave nodes' positions
    (deformed where the file holds their displacements: the ``.frd``'s DISP,
    the ``.dat``'s ``*NODE PRINT, NSET=NSURF`` U). A ``.frd`` without CELS
    gives CalculiX's CPRESS itself (not the pressure on quadratic faces).
    ``info`` holds the source, the nodal forces, the penalty ``K``
    (:func:`penalty_stiffness`) and the step's increments (:func:`read_increments`).
    ``arg`` names the file in the messages (the command line's ``--pressure``).

    Raises
    ------
    ReaderError
        One line naming ``arg`` and the file (the file is looked up as given:
        ``job.FRD`` is read as it is): a ``.dat`` without its deck beside it, a
        file without contact output or node coordinates, fewer than 8 slave
        nodes with coordinates, what :func:`read_frd`, :func:`read_dat` and
        :func:`deck_nodes` refuse (binary or non-UTF-8 text, a number that does
        not read or is not finite, a truncated file), and a pressure that
        comes out non-finite (coincident nodes).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    stem = path.with_suffix("")
    label = file_label(path, arg)
    if suffix == ".dat":
        inp = next((p for p in (path.with_suffix(".inp"), path.with_suffix(".INP")) if p.is_file()), None)
        if inp is None:
            raise ReaderError(f"{label}: a .dat holds no coordinates and the deck "
                              f"{path.with_suffix('.inp').name!r} is not beside it; put the job's .inp "
                              "there (same stem) or give its .frd")
        blocks = read_dat(path, arg=arg)
        if "contact print energy" not in blocks or "relative contact displacement" not in blocks:
            raise ReaderError(f"{label} holds no contact output: request "
                              "`*CONTACT PRINT` with CSTR, CDIS, CELS in the step (threepart deck does)")
        xy = deck_nodes(inp, beside=label)
        disp = blocks.get("displacements NSURF", {})
        copen = blocks["relative contact displacement"]
        energy = blocks["contact print energy"]
        cpress = {k: v[0] for k, v in blocks.get("contact stress", {}).items()}
    else:
        frd = read_frd(path, arg=arg)
        if not frd:
            raise ReaderError(f"{label} holds no result block (no -4 line): empty, or not CalculiX's .frd")
        if "CONTACT" not in frd:
            raise ReaderError(f"{label} has no CONTACT block: request "
                              "`*CONTACT FILE` with CDIS, CSTR, CELS in the step")
        if any(v.size < 4 for v in frd["CONTACT"].values()):
            raise ReaderError(f"{label}: its CONTACT block has fewer than 4 components (COPEN to CPRESS)")
        xy = read_frd_nodes(path, arg=arg)
        disp = frd.get("DISP", {})
        if "CELS" not in frd:
            return _finite_points(*_cpress_points(path, frd, xy, disp, arg), label)
        copen = {k: v[:1] for k, v in frd["CONTACT"].items()}
        energy = frd["CELS"]
        cpress = {k: v[3] for k, v in frd["CONTACT"].items()}
    if not xy:
        raise ReaderError(f"{label}: its deck has no *NODE coordinates")
    forces = {n: v for n, v in nodal_forces(copen, energy, max(xy)).items() if n in xy}
    if len(forces) < 8:
        raise ReaderError(f"{label}: {len(forces)} slave nodes with coordinates "
                          "and contact output; at least 8 are needed")
    nodes = np.array(sorted(forces, key=lambda n: xy[n][0]))
    x0 = np.array([xy[n][0] for n in nodes])
    f = np.array([forces[n][0] for n in nodes])
    vertex = vertex_flags(np.array([forces[n][1] for n in nodes]))
    p = force_pressure(x0, f, vertex, cut=True)
    x = x0 + np.array([disp[n][0] if n in disp else 0.0 for n in nodes])
    ks = list(copen)
    K = penalty_stiffness(np.array([copen[k][0] for k in ks]), np.array([cpress.get(k, math.nan) for k in ks]))
    return _finite_points(x, p, {"source": suffix[1:], "forces": f, "penalty": K,
                                 "increments": read_increments(stem)}, label)


def _finite_points(x: np.ndarray, p: np.ndarray, info: dict[str, Any], label: str
                   ) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """``(x, p, info)`` if every position and pressure is finite; else ReaderError naming the file."""
    bad = np.flatnonzero(~(np.isfinite(x) & np.isfinite(p)))
    if bad.size:
        raise ReaderError(f"{label}: the pressure is not finite at {bad.size} of its {x.size} nodes "
                          f"(the first at x = {x[bad[0]]:g}; coincident nodes?)")
    return x, p, info


def _cpress_points(path: Path, blocks: dict[str, dict[int, np.ndarray]], xyz: dict[int, np.ndarray],
                   disp: dict[int, np.ndarray], arg: str) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """CPRESS of a ``.frd`` without CELS, averaged over each plane node's expanded nodes."""
    by_x: dict[float, list[tuple[float, float]]] = {}
    N = max(xyz)
    for k, v in blocks["CONTACT"].items():
        # a plane model's node n is written as its three expanded nodes N + 3(n - 1) + 1..3
        n = k if k <= N else (k - N - 1) // 3 + 1
        if n not in xyz:
            continue
        x = xyz[n][0] + (disp[n][0] if n in disp else 0.0)
        by_x.setdefault(round(float(x), 9), []).append((float(v[3]), float(v[0])))
    if not by_x:
        raise InputError(f"`{arg}` = {str(path)!r}: no contact node has coordinates")
    xs = np.array(sorted(by_x))
    cp = np.array([np.mean([t[0] for t in by_x[k]]) for k in xs])
    co = np.array([np.mean([t[1] for t in by_x[k]]) for k in xs])
    return xs, cp, {"source": "frd CPRESS (no CELS)", "copen": co, "penalty": penalty_stiffness(co, cp)}

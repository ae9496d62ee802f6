"""``threepart compare --pressure FILE``: a pressure from another code, judged against threepart.

A user's finite-element (or any) contact pressure, given as points ``x, p``
(a CSV file, or CalculiX's ``.frd`` contact output), becomes a result of the
shared shape (:class:`PointsResult`, a :class:`~threepart.results.NormalResult`)
and is compared with the reference of the same case -- the closed form where
it holds, the SIE past lift-off (``threepart.methods.solve(method="auto")``)
-- by the verification run's own comparison (:func:`reports.compare.compare`)
and the tolerance table's ``"referee"`` rows. :func:`diagnose` then looks for
the known pitfalls of contact FE results, each with the number that shows it:

``negative-pressure``
    Tension outside (or inside) the contact: CalculiX writes CPRESS = -K COPEN
    at open nodes, so a penalty contact shows negative "pressures" beyond its ends.
``load``
    ``∫p dx`` differs from ``P`` (a second increment re-paired on the deformed
    geometry, a wrong thickness, a half model).
``end-resolution``
    An end of the contact resolved by fewer than :data:`END_NODES` nodes
    within ``EDGE_FRACTION * W`` of it.
``mesh-peak``
    A peak set by the mesh: the largest pressure at a node next to an end, or
    an element-scale (node-to-node) oscillation larger than :data:`OSCILLATION`
    of the peak.
``increments``
    A CalculiX run whose step took more than one increment (its ``.sta``):
    the deck's model is one increment of the whole load.
``penalty``
    The penalty's overclosure ``p_max / K`` (a length; ``K`` read where the
    contact is closed) against the profile's rise over the contact: the peak
    error falls as ``1/K``.

Names
-----
PointsResult    -- a NormalResult whose pressure interpolates given points
from_points     -- build one: the ends from the data (square-root fit), P and s its moments
read_pressure   -- the points of a CSV file (``x, p``) or of a CalculiX ``.frd`` (CPRESS)
Pitfall         -- one diagnosed pitfall: its name, the number and what to do
diagnose        -- every pitfall a pressure shows
judge           -- compare and diagnose: the document of the report
write_report    -- the report directory (md, html, json) through threepart.output

CalculiX in the verification run
--------------------------------
calculix_result  -- one CalculiX run of a case (threepart.calculix) as a PointsResult
calculix_studies -- its convergence in h and in the penalty K against the closed form
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np
from numpy.typing import ArrayLike

from threepart.output import atomic_dir, json_safe, strict_json
from threepart.results import Diagnostics, NormalResult

from .compare import EDGE_FRACTION, Check, compare
from .verify.sections import Bullets, Document, Item, Section, Status, Table, Verdict, fmt, words

__all__ = ["PointsResult", "from_points", "read_pressure", "Pitfall", "diagnose", "judge",
           "write_report", "calculix_result", "calculix_studies", "CALCULIX_CASE", "SLOPE_SCALE",
           "CALCULIX_N", "CALCULIX_K", "END_NODES", "OSCILLATION", "NEGATIVE", "LOAD", "PENETRATION",
           "COMPARISON"]

#: the tolerance table's rows a pressure from outside is judged by
COMPARISON = "referee"
#: fewest nodes within EDGE_FRACTION * W of a contact end that resolve it
END_NODES = 3
#: node-to-node oscillation (of the peak) above which the peak is the mesh's
OSCILLATION = 2e-3
#: tension (of the peak) above which negative pressures are reported
NEGATIVE = 1e-3
#: |∫p - P| / P above which the load is reported
LOAD = 1e-3
#: overclosure p_max / K (of the profile's rise over the contact) above which the penalty is reported
PENETRATION = 1e-3


@dataclass(frozen=True)
class PointsResult(NormalResult):
    """A normal result from pressure points: ``pressure(x)`` interpolates them linearly.

    ``x_nodes`` and ``p_nodes`` are the points as given (sorted); the
    comparison samples the field there (:func:`reports.compare.sample_points`).
    ``P`` and ``s`` are the points' own load and centroid, ``a`` and ``c``
    their ends (see :func:`from_points`).
    """

    checks_answer = False    # another code's pressure, judged by the comparison, not refused

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)
    p_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """The points' pressure, linear between them and 0 outside ``[-a, c]``."""
        x = np.asarray(x, dtype=float)
        p = np.interp(x, self.x_nodes, np.maximum(self.p_nodes, 0.0), left=0.0, right=0.0)
        return np.where((x >= -self.a) & (x <= self.c), p, 0.0)


def _end(x: np.ndarray, p: np.ndarray, k: int = 4) -> float:
    """The right end of a square-root pressure: the root of ``p^2``, linear over the last ``k`` nodes.

    ``x`` ascending; the end lies between the last node with ``p > 0`` and the next one.
    """
    on = np.flatnonzero(p > 0)
    last = int(on[-1])
    j = on[max(0, len(on) - k):]
    hi = x[last + 1] if last + 1 < len(x) else x[last]
    if len(j) >= 2:
        slope, icpt = np.polyfit(x[j], p[j] ** 2, 1)
        if slope < 0:
            return float(np.clip(-icpt / slope, x[last], hi))
    return float(x[last])


def from_points(x: ArrayLike, p: ArrayLike, ref: NormalResult, *, alpha: float | None = None,
                ends: tuple[float, float] | None = None, method: str = "points",
                info: dict[str, Any] | None = None) -> PointsResult:
    """A :class:`PointsResult` of the case that ``ref`` solved.

    Parameters
    ----------
    x, p
        Positions (along the surface, the README's x) and pressures (>= 0
        compressive); at least 8 points, finite, two or more with ``p > 0``.
    ref
        The reference result of the same case: it gives the punch, ``A`` and
        the tilt mode, never a figure of the points.
    alpha
        The tilt, if the other code reports it; otherwise the reference's, and
        the comparison leaves ``alpha`` out.
    ends
        ``(a, c)``, if the other code locates them (CalculiX: from the gap);
        otherwise from the points.

    The ends ``a``, ``c`` come from the points (the root of ``p^2`` fitted over
    the last four loaded nodes at each end); ``P = ∫p dx`` and ``s = ∫x p dx / P``
    by the trapezoidal rule over the positive pressures.
    """
    x = np.asarray(x, dtype=float).ravel()
    p = np.asarray(p, dtype=float).ravel()
    if x.shape != p.shape:
        raise ValueError(f"`x` and `p` must have the same length, not {x.size} and {p.size}")
    if x.size < 8:
        raise ValueError(f"the pressure has {x.size} points; at least 8 are needed")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(p))):
        raise ValueError("the pressure holds a non-finite x or p (NaN or inf)")
    _in_range(x, p, alpha)
    order = np.argsort(x, kind="stable")
    x, p = x[order], p[order]
    if np.any(np.diff(x) <= 0):
        raise ValueError("the pressure's `x` repeats a position; give each point once")
    if np.count_nonzero(p > 0) < 2:
        raise ValueError("the pressure has fewer than 2 points with p > 0: no contact to judge")
    if ends is None:
        c = _end(x, p)
        a = _end(-x[::-1], p[::-1])       # the left end, mirrored
    else:
        a, c = (float(v) for v in ends)
    pp = np.maximum(p, 0.0)
    P = float(np.trapezoid(pp, x))
    s = float(np.trapezoid(x * pp, x) / P)
    return PointsResult(punch=ref.punch, A=ref.A, a=a, c=c,
                        alpha=float(ref.alpha if alpha is None else alpha), P=P, s=s,
                        tilt=ref.tilt, method=method,
                        diagnostics=Diagnostics(h=float(np.median(np.diff(x))), dofs=int(x.size)),
                        info=dict(info or {}, alpha_given=alpha is not None),
                        x_nodes=x, p_nodes=p)


def _in_range(x: np.ndarray, p: np.ndarray, alpha: float | None) -> None:
    """Refuse points whose load or centroid overflows, and a tilt that is no small slope.

    ``x`` and ``p`` stay within :data:`threepart.validate.LENGTH_RANGE` in magnitude
    (lengths and loads, so that ``∫p dx`` and ``∫x p dx`` stay finite); ``alpha``
    is finite and within :data:`threepart.validate.SLOPE_LIMIT`.
    """
    from threepart.validate import LENGTH_RANGE, SLOPE_LIMIT, finite

    hi = LENGTH_RANGE[1]
    for name, v in (("x", x), ("p", p)):
        if v.size and not float(np.max(np.abs(v))) <= hi:
            raise ValueError(f"the pressure's `{name}` reaches {float(np.max(np.abs(v))):.3g} in "
                             f"magnitude, past {hi:g}, the range this library computes in double "
                             "precision (its load and centroid would overflow)")
    if alpha is not None and not abs(finite("alpha", alpha)) <= SLOPE_LIMIT:
        raise ValueError(f"`alpha` = {alpha!r} exceeds the small-slope limit {SLOPE_LIMIT:g} of "
                         "half-plane theory in magnitude")


def read_pressure(path: str | Path) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """The points of a pressure file: ``(x, p, info)``.

    ``.csv`` (or ``.txt``): two columns ``x, p``, an optional header line,
    ``#`` comments. CalculiX's ``.frd`` (``*CONTACT FILE`` CDIS, CSTR, CELS) or
    ``.dat`` (``*CONTACT PRINT`` CSTR, CDIS, CELS, with the deck ``job.inp``
    beside ``job.dat`` for the coordinates, which a ``.dat`` lacks): the
    contact's nodal forces over the nodes' shares of the quadratic slave faces,
    freed of the vertex/midside alternation
    (:func:`threepart.calculix.force_pressure`), at the slave nodes' positions
    (deformed where the file holds their displacements: the ``.frd``'s DISP,
    the ``.dat``'s ``*NODE PRINT, NSET=NSURF`` U). A ``.frd`` without CELS
    gives CalculiX's CPRESS itself (not the pressure on quadratic faces: the
    diagnosis names it). ``info`` holds the source, COPEN and the penalty
    ``K = CPRESS / -COPEN`` at the closed nodes (:func:`_penalty`).
    """
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"`--pressure` = {str(path)!r} is not a file")
    suffix = path.suffix.lower()
    if suffix in (".frd", ".dat"):
        return _read_calculix(path, suffix)
    if suffix not in (".csv", ".txt"):
        raise ValueError(f"`--pressure` = {str(path)!r}: give a .csv (x, p) or CalculiX's .frd or "
                         f".dat, not {suffix or 'a file without a suffix'}")
    rows = []
    with open(path, newline="", encoding="utf-8") as f:
        for i, row in enumerate(csv.reader(line for line in f if not line.lstrip().startswith("#"))):
            if not row or not "".join(row).strip():
                continue
            try:
                rows.append((float(row[0]), float(row[1])))
            except (ValueError, IndexError):
                if i == 0 and not rows:
                    continue          # a header line
                raise ValueError(f"`--pressure` = {str(path)!r}: row {i + 1} is not two numbers "
                                 f"x, p: {','.join(row)!r}") from None
    if not rows:
        raise ValueError(f"`--pressure` = {str(path)!r} holds no x, p rows")
    xp = np.array(rows)
    return xp[:, 0], xp[:, 1], {"source": "csv"}


def _deck_nodes(inp: Path) -> dict[int, np.ndarray]:
    """The node coordinates of a deck's ``*NODE`` cards: ``{node: (x, y)}``."""
    from threepart.calculix import parse_deck

    out: dict[int, np.ndarray] = {}
    for card in parse_deck(inp.read_text()):
        if card.name == "NODE":
            for row in card.data:
                out[int(row[0])] = np.array([float(v) for v in row[1:3]])
    return out


def _vertex_flags(counts: np.ndarray) -> np.ndarray:
    """Which of the slave nodes (sorted along the face) are vertices of its quadratic faces.

    CalculiX writes three expanded nodes of a vertex node and two of a midside
    node; the two alternate, and the parity that most counts agree with decides.
    """
    even = np.arange(counts.size) % 2 == 0
    agree = np.count_nonzero((counts == 3) == even)
    return even if agree >= counts.size - agree else ~even


def _read_calculix(path: Path, suffix: str) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    from threepart.calculix import (force_pressure, nodal_forces, read_dat, read_frd, read_frd_nodes,
                                    read_increments)

    stem = path.with_suffix("")
    if suffix == ".dat":
        inp = path.with_suffix(".inp")
        if not inp.is_file():
            raise ValueError(f"`--pressure` = {str(path)!r}: a .dat holds no coordinates and the deck "
                             f"{inp.name!r} is not beside it; put the job's .inp there (same stem) or "
                             "give its .frd")
        blocks = read_dat(stem)
        if "contact print energy" not in blocks or "relative contact displacement" not in blocks:
            raise ValueError(f"`--pressure` = {str(path)!r} holds no contact output: request "
                             "`*CONTACT PRINT` with CSTR, CDIS, CELS in the step (threepart deck does)")
        xy = _deck_nodes(inp)
        disp = blocks.get("displacements NSURF", {})
        copen = blocks["relative contact displacement"]
        energy = blocks["contact print energy"]
        cpress = {k: v[0] for k, v in blocks.get("contact stress", {}).items()}
    else:
        frd = read_frd(stem)
        if "CONTACT" not in frd:
            raise ValueError(f"`--pressure` = {str(path)!r} has no CONTACT block: request "
                             "`*CONTACT FILE` with CDIS, CSTR, CELS in the step")
        xy = read_frd_nodes(stem)
        disp = frd.get("DISP", {})
        if "CELS" not in frd:
            return _read_cpress(path, frd, xy, disp)
        copen = {k: v[:1] for k, v in frd["CONTACT"].items()}
        energy = frd["CELS"]
        cpress = {k: v[3] for k, v in frd["CONTACT"].items()}
    N = max(xy)
    forces = {n: v for n, v in nodal_forces(copen, energy, N).items() if n in xy}
    if len(forces) < 8:
        raise ValueError(f"`--pressure` = {str(path)!r}: {len(forces)} slave nodes with coordinates "
                         "and contact output; at least 8 are needed")
    nodes = np.array(sorted(forces, key=lambda n: xy[n][0]))
    x0 = np.array([xy[n][0] for n in nodes])
    f = np.array([forces[n][0] for n in nodes])
    vertex = _vertex_flags(np.array([forces[n][1] for n in nodes]))
    p = force_pressure(x0, f, vertex, cut=True)
    x = x0 + np.array([disp[n][0] if n in disp else 0.0 for n in nodes])
    ks = list(copen)
    K = _penalty(np.array([copen[k][0] for k in ks]), np.array([cpress.get(k, math.nan) for k in ks]))
    return x, p, {"source": suffix[1:], "forces": f, "penalty": K, "increments": read_increments(stem)}


def _penalty(copen: np.ndarray, cpress: np.ndarray) -> float:
    """The penalty stiffness ``K = CPRESS / -COPEN`` at the closed nodes (NaN if fewer than 3).

    ``PRESSURE-OVERCLOSURE=LINEAR`` is linear where the contact is closed
    (``COPEN < 0``); at an open node CalculiX writes the tension ``sigma_inf``
    of the law's second data item instead (``threepart deck``: 1e-6 of the mean
    pressure), so ``-CPRESS / COPEN`` there is ``sigma_inf / COPEN``, not ``K``
    (on caseA_sym it read 86 MPa/mm for the deck's 2.09e9).
    """
    closed = (copen < 0) & (cpress > 0)
    return float(np.median(cpress[closed] / -copen[closed])) if np.count_nonzero(closed) >= 3 else math.nan


def _read_cpress(path: Path, blocks: dict[str, dict[int, np.ndarray]], xyz: dict[int, np.ndarray],
                 disp: dict[int, np.ndarray]) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
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
        raise ValueError(f"`--pressure` = {str(path)!r}: no contact node has coordinates")
    xs = np.array(sorted(by_x))
    cp = np.array([np.mean([t[0] for t in by_x[k]]) for k in xs])
    co = np.array([np.mean([t[1] for t in by_x[k]]) for k in xs])
    return xs, cp, {"source": "frd CPRESS (no CELS)", "copen": co, "penalty": _penalty(co, cp)}


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


def _oscillation(p: np.ndarray) -> float:
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
    x, p = res.x_nodes, res.p_nodes
    W = ref.a + ref.c
    peak = float(max(pk.p for pk in ref.peaks()))
    out: list[Pitfall] = []
    tension = float(-min(p.min(), 0.0)) / peak
    if tension > NEGATIVE:
        k = int(np.count_nonzero(p < -NEGATIVE * peak))
        out.append(Pitfall("negative-pressure", tension, NEGATIVE,
                           f"{k} points carry tension, down to -{tension:.3g} of the peak: a penalty "
                           "contact writes CPRESS = -K*COPEN at open nodes; read p only where the "
                           "contact is closed (COPEN <= 0) or use the nodal forces -2 CELS/COPEN "
                           "(*CONTACT PRINT CELS)"))
    load = abs(res.P - ref.P) / ref.P
    if load > LOAD:
        out.append(Pitfall("load", load, LOAD,
                           f"∫p dx = {res.P:.6g} differs from P = {ref.P:.6g} by {load:.3g} of P: "
                           "analyse the first increment (a later one re-pairs the surfaces on the "
                           "deformed geometry), check the thickness and a half model's factor 2"))
    steps = res.info.get("increments")
    if steps is not None and steps > 1:
        out.append(Pitfall("increments", float(steps), 1.0,
                           f"the run took {steps} increments (its .sta): the whole load did not converge "
                           "in one, and each later increment pairs the faces again on the deformed "
                           "geometry; at large slopes or strains (the deck's header gives them) the "
                           "closed form's model does not hold either: scale the radii up and the load "
                           "down (docs/CALCULIX.md)"))
    margin = EDGE_FRACTION * W
    inside = p > 0
    for side, (lo, hi) in (("left", (-res.a, -res.a + margin)), ("right", (res.c - margin, res.c))):
        n = int(np.count_nonzero(inside & (x >= lo) & (x <= hi)))
        if n < END_NODES:
            out.append(Pitfall("end-resolution", float(n), float(END_NODES),
                               f"the {side} end is resolved by {n} nodes within {EDGE_FRACTION:g} W "
                               f"(W = {W:.6g}) of it; refine there to at least {END_NODES}"))
    on = np.flatnonzero(inside)
    i_max = int(np.argmax(p))
    if i_max <= on[0] + 1 or i_max >= on[-1] - 1:
        out.append(Pitfall("mesh-peak", float(abs(x[i_max] - (res.c if i_max >= on[-1] - 1 else -res.a)) / W),
                           0.0, f"the largest pressure sits at a node next to a contact end "
                                f"(x = {x[i_max]:.6g}): the mesh, not the solution, sets it"))
    osc = _oscillation(p[inside]) / peak
    if osc > OSCILLATION:
        out.append(Pitfall("mesh-peak", osc, OSCILLATION,
                           f"the pressure oscillates from node to node by {osc:.3g} of the peak "
                           "(vertex against midside nodes of quadratic faces): a peak read at one "
                           "node carries that error; divide the nodal forces (-2 CELS/COPEN) by the nodes' "
                           "shares of the face, h/3 and 2h/3 (threepart compare does, given CELS)"))
    K = penalty if penalty is not None else res.info.get("penalty")
    if K is not None and math.isfinite(K) and K > 0:
        rise = float(np.max(ref.punch.profile(np.array([-ref.a, ref.c]))) - np.min(
            ref.punch.profile(np.linspace(-ref.a, ref.c, 201))))
        pen = float(p.max()) / K / rise if rise > 0 else math.inf
        if pen > PENETRATION:
            out.append(Pitfall("penalty", pen, PENETRATION,
                               f"the penalty's overclosure p_max/K = {float(p.max()) / K:.3g} (a length, "
                               f"K = {K:.4g} read at the closed nodes) is "
                               f"{pen:.3g} of the profile's rise over the contact ({rise:.3g}); "
                               "the peak error falls as 1/K: rerun with 10 K and compare"))
    return out


def judge(res: PointsResult, ref: NormalResult, *, penalty: float | None = None,
          source: str = "") -> dict[str, Any]:
    """The comparison and the diagnosis of ``res`` against ``ref``, as a JSON-safe document."""
    checks = [c for c in compare(ref, res, COMPARISON)
              if c.quantity != "alpha" or res.info.get("alpha_given")]
    pitfalls = diagnose(res, ref, penalty=penalty)
    return json_safe({
        "tool": "threepart compare", "source": source,
        "reference": {"method": ref.method, "a": ref.a, "c": ref.c, "alpha": ref.alpha,
                      "P": ref.P, "s": ref.s, "note": ref.info.get("auto", "")},
        "obtained": {"a": res.a, "c": res.c, "P": res.P, "s": res.s, "points": int(res.x_nodes.size)},
        "passed": all(c.passed for c in checks) and not pitfalls,
        "checks": [c.as_dict() for c in checks],
        "pitfalls": [q.as_dict() for q in pitfalls],
    })


def _document(doc: dict[str, Any]) -> Document:
    ok = bool(doc["passed"])
    rows = tuple((c["quantity"], fmt(c["reference"]), fmt(c["obtained"]), fmt(c["error"]),
                  fmt(c["limit"]), Verdict(Status.of(bool(c["passed"]))), words(c["reason"]))
                 for c in doc["checks"])
    table = Table(("quantity", "reference", "obtained", "error", "limit", "verdict", "reason"), rows)
    items = tuple(Item(words(f"{q['name']}: {q['message']}")) for q in doc["pitfalls"]) or \
        (Item(("none of the known pitfalls was found",)),)
    ref = doc["reference"]
    intro = (words(f"`{doc['source']}` ({doc['obtained']['points']} points) against the "
                   f"{ref['method']} reference" + (f" ({ref['note']})" if ref["note"] else "") +
                   "; errors normalised as in the verification report, limits from the tolerance "
                   f"table's `{COMPARISON}` rows."),)
    return Document("threepart compare", "PASSED" if ok else "FAILED", Status.of(ok), (
        Section("Checks", "checks", intro, (table,), status=Status.of(all(c["passed"] for c in doc["checks"]))),
        Section("Pitfalls", "pitfalls", (Bullets(items),), status=Status.of(not doc["pitfalls"]))))


def write_report(doc: dict[str, Any], out: str | Path) -> None:
    """Write ``report.md``, ``report.html`` and ``report.json`` into the new directory ``out``."""
    from .verify.render import render_html, render_markdown

    with atomic_dir(out, command="compare") as tmp:
        d = _document(doc)
        (tmp / "report.json").write_text(strict_json(doc, indent=1), encoding="utf-8")
        (tmp / "report.md").write_text(render_markdown(d), encoding="utf-8")
        (tmp / "report.html").write_text(render_html(d, tmp), encoding="utf-8")


def main(pressure: str | Path, ref: NormalResult, *, out: str | Path, alpha: float | None = None,
         penalty: float | None = None, say: Callable[[str], None] = print) -> int:
    """Read, judge and report; 0 when every check holds and no pitfall shows, else 1."""
    x, p, info = read_pressure(pressure)
    res = from_points(x, p, ref, alpha=alpha, info={k: v for k, v in info.items()
                                                   if k in ("source", "penalty", "increments")})
    doc = judge(res, ref, penalty=penalty, source=str(pressure))
    write_report(doc, out)
    failed = [c for c in doc["checks"] if not c["passed"]]
    say(f"{'PASSED' if doc['passed'] else 'FAILED'}: {len(doc['checks']) - len(failed)}/"
        f"{len(doc['checks'])} checks within tolerance, {len(doc['pitfalls'])} pitfalls -> "
        f"{Path(out) / 'report.html'}")
    for c in failed:
        say(f"  failed: {c['quantity']}: error {c['error']:.3g} > {c['limit']:.3g}")
    for q in doc["pitfalls"]:
        say(f"  pitfall {q['name']}: {q['message']}")
    return 0 if doc["passed"] else 1


# --------------------------------------------------------------------------- CalculiX in verify
#: the case of the CalculiX column: the symmetric flat rounded punch
CALCULIX_CASE = "caseA_sym"
#: its radii times this and P over it: the same contact [-a, c] and pressure shape, slopes and
#: pressures divided by it (half-plane theory is linear in them): small slopes for the FE model
SLOPE_SCALE = 20.0
#: elements across W at the contact of the mesh study, up to the deck's default (200); the
#: penalty study is run at the middle one (the column: about 30 s of CPU, measured)
CALCULIX_N = (50, 100, 200)
#: the penalty K in units of E/h of the penalty study (at W/h = CALCULIX_N[1]); the mesh study
#: runs at the deck's default, 200 E/h
CALCULIX_K = (20.0, 80.0, 320.0)
#: the penalty of the mesh study, in E/h (the deck's default)
CALCULIX_K_MESH = 200.0
#: what the CalculiX study follows (errors normalised as in the tolerance table)
CALCULIX_QUANTITIES = ("a", "c", "P", "p_left", "p_right", "p_interior_max")


def calculix_result(case: Any, n: float, penalty_factor: float, workdir: Path,
                    scale: float = SLOPE_SCALE) -> tuple[PointsResult, NormalResult]:
    """One CalculiX run of ``case`` scaled to small slopes: ``(result, closed-form reference)``.

    The pressure is CalculiX's nodal contact forces over the nodes' shares of
    the block's quadratic faces, freed of the vertex/midside alternation
    (:func:`threepart.calculix.surface_pressure`); the ends come from the gap
    (:func:`threepart.calculix.contact_edge`), ``P`` from the points.
    """
    from dataclasses import replace as _replace

    from threepart import calculix
    from threepart.material import compliance
    from threepart.methods import solve

    case = case.resolved()
    E, nu = case.material
    settings = calculix.DeckSettings(n=n, penalty_factor=penalty_factor)
    A = compliance(E, nu, E * settings.stiffening, nu)
    punch = _replace(case.punch, R1=scale * case.punch.R1, R2=scale * case.punch.R2,
                     R=scale * case.punch.R)
    P, s = case.P / scale, float(case.s or 0.0)
    ref = solve(punch, P, s, A=A, tilt=case.tilt)
    assert isinstance(ref, NormalResult)
    model = calculix.build_model(punch, ref.a, ref.c, settings)
    stem = calculix.run_ccx(calculix.write_deck(model, P=P, s=s, E=E, nu=nu, settings=settings,
                                                title=f"{case.name}, radii x {scale:g}, P / {scale:g}"),
                            workdir, f"n{n:g}_K{penalty_factor:g}")
    sp = calculix.surface_pressure(model, stem)
    res = from_points(sp.x, sp.p, ref, ends=(sp.a, sp.c), method="calculix",
                      info={"penalty": settings.K(E, ref.a + ref.c)})
    return _replace(res, diagnostics=Diagnostics(h=model.h0, dofs=2 * model.n_nodes)), ref


def calculix_studies(say: Callable[[str], None] = print) -> list[Any]:
    """The CalculiX column of the verification run: convergence in h, then in K, on one case.

    Without ``ccx`` on the PATH, one empty study whose note says so.
    """
    import tempfile

    from threepart import calculix
    from threepart.catalogue import get_case
    from threepart.convergence import Study, run_study

    from .compare import normal_figures

    if not calculix.ccx_available():
        st = Study("h", method="calculix", case=CALCULIX_CASE)
        st.notes.append("`ccx` (CalculiX) is not on the PATH: the CalculiX column was not run "
                        "(Debian: apt-get install calculix-ccx)")
        return [st]
    case = get_case(CALCULIX_CASE)
    cache: dict[tuple[float, float], tuple[PointsResult, NormalResult]] = {}
    with tempfile.TemporaryDirectory(prefix="threepart-ccx-") as tmp:
        def level(n: float, k: float, param: str) -> tuple[float, dict[str, float], dict[str, Any],
                                                          dict[str, float]]:
            if (n, k) not in cache:
                cache[n, k] = calculix_result(case, n, k, Path(tmp))
            res, ref = cache[n, k]
            fig = normal_figures(ref, res)
            err = {q: fig[q][2] for q in CALCULIX_QUANTITIES}
            raw = {q: (fig[q][1] if q != "p_interior_max" else fig[q][2]) for q in CALCULIX_QUANTITIES}
            say(f"[study]   calculix W/h = {n:g}, K = {k:g} E/h: peak error {max(err['p_left'], err['p_right']):.3g}, "
                f"a {err['a']:.3g} W, c {err['c']:.3g} W")
            h = float(res.diagnostics.h or math.nan)
            E = float(case.material[0]) if case.material else math.nan
            return (h if param == "h" else h / (k * E), raw, {"dofs": res.diagnostics.dofs}, err)

        mesh = run_study(lambda n: level(n, CALCULIX_K_MESH, "h"), list(CALCULIX_N), param="h",
                         error_only=("p_interior_max",), skip=(calculix.CcxError,),
                         method="calculix", case=CALCULIX_CASE, scheme=f"K = {CALCULIX_K_MESH:g} E/h")
        penalty = run_study(lambda k: level(CALCULIX_N[1], k, "1/K"), list(CALCULIX_K), param="1/K",
                            error_only=("p_interior_max",), skip=(calculix.CcxError,),
                            method="calculix", case=CALCULIX_CASE, scheme=f"W/h = {CALCULIX_N[1]}")
    for st in (mesh, penalty):
        st.notes.append(f"{CALCULIX_CASE} with the radii x {SLOPE_SCALE:g} and P / {SLOPE_SCALE:g} "
                        "(the same contact, slopes / 20); punch 1000 x stiffer than the block (in A); "
                        "pressure = the nodal contact forces -2 CELS/COPEN over the nodes' shares of the "
                        "quadratic faces, vertex/midside alternation fitted out; a, c from the gap")
    return [mesh, penalty]

"""``threepart export-refs``: the catalogue's reference solutions as a versioned dataset.

Every case of the one case catalogue (:mod:`threepart.problem.catalogue`) is solved by
its reference method (:attr:`threepart.problem.catalogue.Case.reference`): the closed
form where the paper's framework holds, and past it the SIE, whose projected
scheme gives the contact and stick-zone ends exactly for any ``n``; its
tractions are then evaluated by the bounded inversion integral at those ends
by adaptive quadrature (:func:`threepart.sie.pressure_by_quadrature`), which
owes nothing to ``n``. Each quantity states the precision it claims, from the
tolerance table (comparison ``"refs"`` of :mod:`threepart.tolerances`), and
``tests/test_refs.py`` checks each claim against an independent evaluation.

The directory holds ``dataset.json`` (the index: versions, conventions, units,
precision claims, cases), ``refs.schema.json`` (JSON schema, draft 2020-12,
that every JSON file of the dataset validates against) and, per case,
``<case>.json`` with ``<case>.fields.csv`` (``x``, ``p``, ``q``, surface
``sxx``), ``<case>.subsurface.csv`` and, for a fretting cycle,
``<case>.cycle.csv``. Format: ``docs/REFERENCE_DATA.md``. It is written
through :func:`threepart.output.atomic_dir`: a new or empty directory, or
threepart's own unchanged earlier export, never anything else.

Names
-----
DATASET_VERSION  -- version of the dataset's layout
SCHEMA_FILE      -- the JSON schema of every JSON file of the dataset
GRID             -- points of the fields over ``[-a, c]``, both ends included
SUBSURFACE       -- the subsurface points, as ``(x - m)/W`` and ``z/W``
precision        -- the precision claims of a case of one kind
reference        -- one case's JSON document
index            -- the dataset's index document
export_refs      -- write the dataset for the catalogue (or some cases) to a directory
load_refs        -- read a dataset back, checking every CSV against its JSON exactly
validate         -- validate a JSON document of the dataset against the schema
main             -- the command's entry point
"""
from __future__ import annotations

import csv
import datetime as _dt
import io
import json
import math
from importlib import metadata
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np
from scipy.optimize import minimize_scalar

from threepart.registry import REFERENCE
from threepart.problem.catalogue import Case, load_cases
from threepart.output import atomic_dir, json_safe, strict_json, validate_json
from threepart.tolerances import TOLERANCES

from .verify.runs import MODES, solve
from .compare import normal_of
from threepart.errors import InputError

__all__ = ["DATASET_VERSION", "SCHEMA_FILE", "GRID", "SUBSURFACE", "CONVENTIONS", "PRECISION_OF",
           "precision", "index", "reference", "export_refs", "load_refs", "validate", "main", "INDEX"]

#: version of the dataset's layout (a change of its fields or files changes it)
DATASET_VERSION = "1.0"
SCHEMA_FILE = Path(__file__).with_name("refs.schema.json")
#: file name of the dataset's index
INDEX = "dataset.json"
#: points of the fields p(x), q(x) and the surface sxx over [-a, c], both ends included
GRID = 201
#: subsurface points: ``x = m + u W`` for each ``u`` and ``z = w W`` for each ``w``
#: (``m = (c - a)/2`` the contact's middle, ``W = a + c``)
SUBSURFACE = {"u": (-0.25, 0.0, 0.25), "w": (0.1, 0.3, 0.6)}
#: the conventions every file of the dataset follows (README)
CONVENTIONS = (
    "x runs along the surface, z >= 0 is the depth into the substrate; the contact is [-a, c]",
    "plane strain, elastically similar bodies; A is the compliance of eq. (4)",
    "p(x) >= 0 is the compressive pressure the punch exerts on the substrate; P > 0 its resultant, "
    "s its lever arm (the pressure centroid), positive to the right",
    "q(x) and Q > 0 are the shear traction and force the punch exerts on the substrate along +x; "
    "the stick zone is [-(d+e), d-e]",
    "stresses: tension positive; sxx, szz, sxz in the substrate; sigma_bulk > 0 a tension along x "
    "(0 in every catalogue case)",
    "load path: P at s first, then Q; a fretting cycle takes Q from 0 to Q_max, to -Q_max and back",
    "alpha is the punch's tilt (eq. 2), 0 when the tilt is suppressed (then s is the result s*)",
    "a non-finite number (R = inf, a flat centre) is written as null",
)
#: each exported quantity and its precision claim: ``(tolerance-table quantity, what it is a fraction of)``
PRECISION_OF: dict[str, tuple[str, str]] = {
    "a": ("a", "W"), "c": ("c", "W"), "alpha": ("alpha", "slope"), "s": ("s", "W"),
    "p": ("p", "peak"), "P_integral": ("p_integral", "P"), "s_centroid": ("p_integral", "W"),
    "peak_p": ("p_peak", "peak"), "peak_x": ("x_peak", "W"),
    "d": ("d", "d"), "e": ("e", "d"), "q": ("q", "max|q|"),
    "energy": ("energy", "energy"), "loop": ("loop", "loop"), "stick": ("loop", "d"),
    "sxx_surface": ("stress", "peak"), "subsurface": ("stress", "peak"),
}
_SLIP_ONLY = ("d", "e", "q")
_FRETTING_ONLY = ("energy", "loop", "stick")


def _version() -> str:
    try:
        return metadata.version("threepart")
    except metadata.PackageNotFoundError:  # pragma: no cover - run from a source tree
        return "unknown"


def precision(kind: str) -> dict[str, dict[str, Any]]:
    """The precision claims of a case of ``kind`` (``"normal"``, ``"slip"``, ``"fretting"``)."""
    out = {}
    for name, (quantity, of) in PRECISION_OF.items():
        if (name in _SLIP_ONLY and kind == "normal") or (name in _FRETTING_ONLY and kind != "fretting"):
            continue
        tol = TOLERANCES["refs", quantity]
        out[name] = {"limit": tol.limit, "of": of, "reason": tol.reason}
    return out


class _Source:
    """A case's reference result and its tractions at any points, with the method that gave them."""

    def __init__(self, case: Case) -> None:
        self.case = case
        self.result, _ = solve(case, case.reference, MODES["default"])
        self.normal = normal_of(self.result)
        self.sie = case.reference != REFERENCE   # past the closed form's framework: the SIE's

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """The pressure: the closed form, or the inversion integral at the SIE's ends."""
        if not self.sie:
            return np.asarray(self.normal.pressure(x), float)
        from threepart.sie import pressure_by_quadrature

        n = self.normal
        return pressure_by_quadrature(n.punch, n.A, n.a, n.c, n.alpha, x)

    def shear(self, x: np.ndarray) -> np.ndarray:
        """The shear of a slip case at Q, or of a fretting cycle at Q_max on loading."""
        res = self.result
        if self.case.kind == "fretting":
            return np.asarray(res.shear(x, res.Q_max, "loading"), float)
        if not self.sie:
            return np.asarray(res.shear(x), float)
        from threepart.sie import pressure_by_quadrature

        n = self.normal   # Ciavarella-Jaeger: q = f (p - p*), p* the same punch on the stick zone
        corrective = pressure_by_quadrature(n.punch, n.A, res.d + res.e, res.d - res.e, n.alpha, x)
        return math.copysign(res.f, res.Q) * (self.pressure(x) - corrective)

    def stress(self, x: np.ndarray, z: np.ndarray) -> Any:
        res = self.result
        if self.case.kind == "fretting":
            return res.stress(x, z, res.Q_max, "loading")
        return res.stress(x, z)

    def peaks(self) -> dict[str, dict[str, Any]]:
        """Both peaks; past lift-off the SIE's, refined on the quadrature pressure."""
        out = {}
        n = self.normal
        W = n.a + n.c
        for side, pk in zip(("left", "right"), n.peaks()):
            x, p = pk.x, pk.p
            if self.sie:
                lo, hi = max(x - 1e-3 * W, -n.a), min(x + 1e-3 * W, n.c)
                if pk.interior:
                    r = minimize_scalar(lambda t: -float(self.pressure(np.array([t]))[0]),
                                        bounds=(lo, hi), method="bounded",
                                        options={"xatol": 1e-12 * W})
                    x = float(r.x)
                p = float(self.pressure(np.array([x]))[0])
            out[side] = {"x": x, "p": p, "interior": pk.interior}
        return out


def _units(case: Case) -> str:
    """The units of a case and what its material means (the one convention, :mod:`threepart.problem.material`)."""
    if case.material is None:
        return "nondimensional (consistent units; A given)"
    if case.bodies == "rigid punch":
        return "mm, N/mm, MPa; E, nu of the half-plane under a rigid punch, A = 2(1 - nu^2)/E"
    return "mm, N/mm, MPa; E, nu of both bodies (two similar bodies), A = 4(1 - nu^2)/E"


def _inputs(case: Case) -> dict[str, Any]:
    d = case.as_dict()
    inputs = {"punch": {k: d["punch"][k] for k in ("R1", "R2", "b", "R")},
              "A": d["A"], "E": d["E"], "nu": d["nu"], "P": d["P"], "s": d["s"], "tilt": d["tilt"],
              "sigma_bulk": 0.0}
    if case.kind != "normal":
        inputs.update({"Q": case.Q, "f": case.f})
    if case.kind == "fretting":
        inputs["Q_max"] = case.Q
    return inputs


#: the kinds of case the dataset holds (:attr:`Case.kind <threepart.problem.catalogue.Case.kind>`)
KINDS = ("normal", "slip", "fretting")


def reference(case: Case) -> dict[str, Any]:
    """The JSON document of one catalogue case (see ``docs/REFERENCE_DATA.md``).

    Parameters
    ----------
    case
        A catalogue case (resolved here if given by its lift-off fraction).

    Returns
    -------
    dict
        JSON-ready: inputs, solution, fields on :data:`GRID` points, subsurface
        stresses, the cycle (fretting) and the precision claimed per quantity.
    """
    if case.kind not in KINDS:
        raise InputError(f"case {case.name!r} is a {case.kind} case: the reference dataset holds "
                         f"{', '.join(KINDS)} cases only (a flight cycle's steady state is not yet in it)")
    case = case.resolved()
    src = _Source(case)
    n, res = src.normal, src.result
    W = n.a + n.c
    x = np.linspace(-n.a, n.c, GRID)
    x[0], x[-1] = -n.a, n.c
    fields: dict[str, list[float]] = {"x": x.tolist(), "p": src.pressure(x).tolist()}
    if case.kind != "normal":
        fields["q"] = src.shear(x).tolist()
    fields["sxx_surface"] = np.asarray(src.stress(x, np.zeros_like(x)).sxx, float).tolist()
    m = 0.5 * (n.c - n.a)
    xs = np.repeat([m + u * W for u in SUBSURFACE["u"]], len(SUBSURFACE["w"]))
    zs = np.tile([w * W for w in SUBSURFACE["w"]], len(SUBSURFACE["u"]))
    st = src.stress(xs, zs)
    solution: dict[str, Any] = {"a": n.a, "c": n.c, "alpha": n.alpha, "P": n.P, "s": n.s, "W": W,
                                "segments": list(n.segments), "within_paper": n.within_paper,
                                "peaks": src.peaks()}
    doc: dict[str, Any] = {
        "document": "case", "dataset_version": DATASET_VERSION, "threepart_version": _version(),
        "name": case.name, "description": case.description, "kind": case.kind,
        "units": _units(case),
        "source": _source(case, src),
        "inputs": _inputs(case),
        "solution": solution,
        "fields": fields,
        "subsurface": {"x": xs.tolist(), "z": zs.tolist(),
                       "sxx": np.asarray(st.sxx, float).tolist(), "szz": np.asarray(st.szz, float).tolist(),
                       "sxz": np.asarray(st.sxz, float).tolist()},
        "precision": precision(case.kind),
        "files": _files(case),
    }
    if case.kind == "slip":
        lo, hi = res.stick_zone
        solution.update({"d": res.d, "e": res.e, "stick_zone": [lo, hi]})
    if case.kind == "fretting":
        at_max = int(np.flatnonzero(res.branch == "loading")[-1])
        lo, hi = (float(v) for v in res.stick[at_max])
        solution.update({"d": 0.5 * (hi - lo), "e": -0.5 * (hi + lo), "stick_zone": [lo, hi],
                         "energy": res.energy})
        Q, loop = res.loop()
        doc["cycle"] = {"branch": [str(b) for b in res.branch], "Q": np.asarray(Q, float).tolist(),
                        "stick_left": np.asarray(res.stick[:, 0], float).tolist(),
                        "stick_right": np.asarray(res.stick[:, 1], float).tolist(),
                        "loop": np.asarray(loop, float).tolist()}
    return json_safe(doc)


def _source(case: Case, src: _Source) -> dict[str, Any]:
    if not src.sie:
        return {"method": "closedform", "n": None,
                "fields": "the paper's closed form (eq. pressure_abbreviated; partial slip, Ciavarella-Jaeger)"}
    return {"method": "sie", "n": src.normal.diagnostics.n or _sie_n(src.normal),
            "fields": "the SIE's ends (a, c, alpha, d, e), exact for any n; p and q by the bounded "
                      "inversion integral at those ends by adaptive quadrature (sie.reference); the "
                      "stresses from the SIE's tractions at n"}


def _sie_n(normal: Any) -> int | None:
    n = getattr(normal, "n", None)
    return int(n) if n is not None else None


def _files(case: Case) -> dict[str, str]:
    files = {"fields": f"{case.name}.fields.csv", "subsurface": f"{case.name}.subsurface.csv"}
    if case.kind == "fretting":
        files["cycle"] = f"{case.name}.cycle.csv"
    return files


def _columns(doc: dict[str, Any], table: str) -> dict[str, list[Any]]:
    """The columns of one CSV table of a case document, in file order."""
    if table == "fields":
        return dict(doc["fields"])
    if table == "subsurface":
        return dict(doc["subsurface"])
    return dict(doc["cycle"])


def _csv(columns: dict[str, list[Any]]) -> str:
    """The columns as CSV; numbers by ``repr``, which reads back to the same double."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(columns)
    for row in zip(*columns.values()):
        w.writerow([v if isinstance(v, str) else repr(float(v)) for v in row])
    return buf.getvalue()


def index(docs: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """The dataset's index document (``dataset.json``)."""
    from threepart.tolerances import NORMALISATION

    return json_safe({
        "document": "dataset", "dataset_version": DATASET_VERSION, "threepart_version": _version(),
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "schema": SCHEMA_FILE.name, "conventions": list(CONVENTIONS),
        "grid": {"points": GRID, "subsurface": {k: list(v) for k, v in SUBSURFACE.items()}},
        "normalisation": {of: NORMALISATION[of] for of in sorted({of for _, of in PRECISION_OF.values()})},
        "cases": [{"name": d["name"], "kind": d["kind"], "method": d["source"]["method"],
                   "file": f"{d['name']}.json", "files": d["files"]} for d in docs],
    })


def validate(doc: Any) -> None:
    """Validate a JSON document of the dataset against :data:`SCHEMA_FILE` (needs ``jsonschema``)."""
    validate_json(doc, SCHEMA_FILE)


def export_refs(out: str | Path, cases: Sequence[Case] | None = None, force: bool = False,
                progress: Callable[[str], None] | None = None) -> list[dict[str, Any]]:
    """Write the reference dataset of ``cases`` (default: every catalogue case) to ``out``.

    Parameters
    ----------
    out
        Output directory: missing, empty, or threepart's own unchanged earlier
        export (replaced); anything else is refused before any work
        (:func:`threepart.output.atomic_dir`).
    cases
        The cases to export (default: the whole catalogue, every suite, but the kinds
        the dataset does not hold, :data:`KINDS`).
    force
        Kept for the command line's signature; it changes nothing.
    progress
        Called with one line per case.

    Returns
    -------
    list of dict
        The case documents written.
    """
    say = progress or (lambda msg: None)
    with atomic_dir(out, force, command="export-refs") as tmp:
        docs = []
        for case in (load_cases(None) if cases is None else cases):
            if cases is None and case.kind not in KINDS:
                continue   # by default the catalogue's cases the dataset holds
            doc = reference(case)
            validate(doc)
            docs.append(doc)
            (tmp / f"{case.name}.json").write_text(strict_json(doc, indent=1) + "\n", encoding="utf-8")
            for table, name in doc["files"].items():
                (tmp / name).write_text(_csv(_columns(doc, table)), encoding="utf-8")
            say(f"{case.name}: {doc['kind']}, {doc['source']['method']}")
        idx = index(docs)
        validate(idx)
        (tmp / INDEX).write_text(strict_json(idx, indent=1) + "\n", encoding="utf-8")
        (tmp / SCHEMA_FILE.name).write_bytes(SCHEMA_FILE.read_bytes())
    return docs


def _read_csv(path: Path) -> dict[str, list[Any]]:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    cols: dict[str, list[Any]] = {h: [] for h in rows[0]}
    for row in rows[1:]:
        for h, v in zip(rows[0], row):
            cols[h].append(v if h == "branch" else float(v))
    return cols


def load_refs(directory: str | Path) -> dict[str, dict[str, Any]]:
    """Read a dataset back: ``name -> case document``, every CSV checked against its JSON.

    Raises
    ------
    ValueError
        If the dataset's version is not :data:`DATASET_VERSION`, or a CSV
        differs from its JSON in any bit (the message names the file and column).
    """
    directory = Path(directory)
    idx = json.loads((directory / INDEX).read_text(encoding="utf-8"))
    if idx.get("dataset_version") != DATASET_VERSION:
        raise InputError(f"`directory` = {str(directory)!r} holds dataset version "
                         f"{idx.get('dataset_version')!r}; this threepart reads {DATASET_VERSION!r}")
    docs = {}
    for entry in idx["cases"]:
        doc = json.loads((directory / entry["file"]).read_text(encoding="utf-8"))
        for table, name in doc["files"].items():
            cols = _read_csv(directory / name)
            want = _columns(doc, table)
            for col, values in want.items():
                if cols.get(col) != values:
                    raise InputError(f"{name}: column {col!r} differs from {entry['file']}")
        docs[doc["name"]] = doc
    return docs


def main(out: str | Path = "refs", force: bool = False, cases: Sequence[str] | None = None,
         quiet: bool = False) -> int:
    """Export the reference dataset of ``cases`` (names; default every case) to ``out``; 0 when written.

    Raises
    ------
    ValueError
        For a name that is not a catalogue case (the message lists them), before any work.
    """
    def say(msg: str) -> None:
        if not quiet:
            print(msg, flush=True)

    chosen = None
    if cases is not None:
        known = {c.name: c for c in load_cases(None)}
        unknown = [n for n in cases if n not in known]
        if unknown or not cases:
            raise InputError(f"`--cases` = {','.join(cases)!r}: {unknown[0] if unknown else 'empty'!r} "
                             f"is not a catalogue case (one of {', '.join(known)})")
        chosen = [known[n] for n in dict.fromkeys(cases)]
    docs = export_refs(out, cases=chosen, force=force, progress=say)
    say(f"threepart export-refs: {len(docs)} cases, dataset version {DATASET_VERSION} -> {out}")
    return 0

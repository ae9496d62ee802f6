"""The reference dataset of ``threepart export-refs``: its format, and every precision it claims.

The dataset is exported once, through the command line, for the whole
catalogue. Each claim (``doc["precision"]``, the tolerance table's ``"refs"``
rows) is checked against an evaluation that owes nothing to the exported
numbers: the SIE at its default ``n`` against the closed form, the bounded
inversion integral by adaptive quadrature (:mod:`tests.quad_reference`), the
shifted punch's forward formulas past lift-off (:mod:`tests.beyond_reference`),
the quadrature identities ``∫p = P``, ``∫x p = P s`` and ``∫q = Q``, and
Flamant's kernels integrated by QUADPACK for the stresses.
"""
from __future__ import annotations

import json
import math
import shutil
from importlib import metadata

import jsonschema
import numpy as np
import pytest

from threepart import registry
from threepart.problem.catalogue import get_case, load_cases
from threepart.output import OutputExistsError
from threepart.reports import refs
from threepart.sie.reference import pressure_by_quadrature, quiet_quad
from threepart.tolerances import TOLERANCES

from . import beyond_reference, quad_reference


#: the cases exported in the default run: every kind, both tilts, b = 0, a nondimensional case,
#: and past the framework an edge on the centre, the punch on one corner and a stick zone on the centre
SUBSET = ("general", "suppressed", "caseC", "slip_Q0.4", "fretting_Q0.4", "beyond_edge_on_flat",
          "beyond_corner", "beyond_stick_centre", "nd_hertz")


@pytest.fixture(scope="module", params=["subset", pytest.param("catalogue", marks=pytest.mark.slow)])
def dataset(request, tmp_path_factory):
    """Cases exported by ``threepart export-refs``: (directory, name -> document).

    The default run exports :data:`SUBSET`; ``-m slow`` the whole catalogue.
    """
    from threepart.cli import main

    out = tmp_path_factory.mktemp("refs") / "refs"
    names = ["--cases", ",".join(SUBSET)] if request.param == "subset" else []
    assert main(["export-refs", "--out", str(out), *names]) == 0
    return out, refs.load_refs(out)


def _claim(doc, name):
    """The limit a document claims for ``name``; it must be the tolerance table's."""
    claim = doc["precision"][name]
    quantity, of = refs.PRECISION_OF[name]
    assert claim["limit"] == TOLERANCES["refs", quantity].limit and claim["of"] == of
    return claim["limit"]


def _case(doc):
    return get_case(doc["name"]).resolved()


def _grid_subset(doc, step=20):
    """Every ``step``-th interior grid point: ``(x, p)`` arrays."""
    x = np.asarray(doc["fields"]["x"])[1:-1:step]
    p = np.asarray(doc["fields"]["p"])[1:-1:step]
    return x, p


def _integral(fun, a, c, breaks=()):
    """``∫ fun dx`` over ``[-a, c]`` with ``x = m + h cos φ``: a bounded fun with sqrt ends becomes smooth."""
    m, h = 0.5 * (c - a), 0.5 * (a + c)
    kinks = sorted(math.acos((t - m) / h) for t in breaks if -a < t < c)
    return quiet_quad(lambda phi: float(fun(m + h * math.cos(phi))) * h * math.sin(phi), 0.0, math.pi,
                      points=kinks or None, limit=400, epsabs=0.0, epsrel=1e-13)[0]


def _peak(doc):
    pk = doc["solution"]["peaks"]
    return max(pk["left"]["p"], pk["right"]["p"])


# --- format -----------------------------------------------------------------------------------
def test_every_case_is_exported_and_every_json_validates(dataset):
    out, docs = dataset
    names = [c.name for c in load_cases(None) if c.kind in refs.KINDS]   # the kinds the dataset holds
    assert sorted(docs) == sorted(names if len(docs) > len(SUBSET) else SUBSET)
    schema = json.loads(refs.SCHEMA_FILE.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    assert json.loads((out / "refs.schema.json").read_text(encoding="utf-8")) == schema
    index = json.loads((out / refs.INDEX).read_text(encoding="utf-8"))
    for doc in [index, *docs.values()]:
        jsonschema.Draft202012Validator(schema).validate(doc)
    assert index["dataset_version"] == refs.DATASET_VERSION
    assert index["threepart_version"] == metadata.version("threepart")
    assert index["conventions"] == list(refs.CONVENTIONS)
    kinds = {d["kind"] for d in docs.values()}
    assert kinds == {"normal", "slip", "fretting"}
    beyond = {d["name"] for d in docs.values() if d["source"]["method"] == "sie"}
    assert beyond == {c.name for c in load_cases(None) if c.beyond and c.name in docs}


def test_the_schema_rejects_a_case_without_its_fields(dataset):
    _, docs = dataset
    doc = json.loads(json.dumps(docs["slip_Q0.4"]))
    del doc["fields"]["q"]   # a slip case must carry q(x)
    with pytest.raises(jsonschema.ValidationError):
        refs.validate(doc)
    doc = json.loads(json.dumps(docs["general"]))
    doc["inputs"]["P"] = -1.0
    with pytest.raises(jsonschema.ValidationError):
        refs.validate(doc)


def test_reimport_is_exact_and_a_one_ulp_change_is_found(dataset, tmp_path):
    out, docs = dataset
    doc = refs.reference(get_case("slip_Q0.4"))
    assert doc == docs["slip_Q0.4"]   # JSON and CSV read back to the very doubles computed
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    path = copy / "slip_Q0.4.fields.csv"
    lines = path.read_text(encoding="utf-8").splitlines()
    row = lines[50].split(",")
    row[2] = repr(float(np.nextafter(float(row[2]), math.inf)))   # q, one ulp up
    lines[50] = ",".join(row)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"slip_Q0.4.fields.csv: column 'q' differs"):
        refs.load_refs(copy)


def test_export_never_writes_over_what_threepart_did_not_write(tmp_path, capsys):
    from threepart.cli import main

    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("keep me", encoding="utf-8")
    with pytest.raises(OutputExistsError, match="notes.txt"):
        refs.export_refs(foreign, cases=[get_case("hertz")])
    assert main(["export-refs", "--out", str(foreign)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "threepart export-refs: error:" in err and "notes.txt" in err
    assert (foreign / "notes.txt").read_text(encoding="utf-8") == "keep me"


# --- precision: ends, tilt, lever arm ----------------------------------------------------------
def test_closed_form_ends_and_tilt_against_the_sie(dataset):
    sie = registry.get("sie")
    for doc in dataset[1].values():
        if doc["source"]["method"] != "closedform":
            continue
        case, sol = _case(doc), doc["solution"]
        other = sie.normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        W = sol["W"]
        ds = float(case.punch.slope(sol["c"]) - case.punch.slope(-sol["a"]))
        errors = {"a": abs(other.a - sol["a"]) / W, "c": abs(other.c - sol["c"]) / W,
                  "alpha": abs(other.alpha - sol["alpha"]) / max(abs(sol["alpha"]), ds),
                  "s": abs(other.s - sol["s"]) / W}
        for q, err in errors.items():
            assert err <= _claim(doc, q), f"{doc['name']}: {q} error {err:.2e}"


def test_sie_ends_past_lift_off_against_the_shifted_punch(dataset):
    beyond = [d for d in dataset[1].values() if d["source"]["method"] == "sie" and d["kind"] == "normal"]
    assert beyond
    for doc in beyond:
        name = doc["name"]
        case, sol = _case(doc), doc["solution"]
        if case.punch.b < case.s - math.sqrt(2 * case.P * case.A * case.punch.R2 / math.pi):   # on R2 alone
            left, right, alpha = beyond_reference.on_corner(case.punch, case.P, case.s, case.A)
        else:
            left, right = beyond_reference.edge_on_centre(case.punch, case.P, case.A, s=case.s)
            alpha = beyond_reference.forward(case.punch, left, right, case.A)[2]
        W = sol["W"]
        assert abs(-left - sol["a"]) / W <= _claim(doc, "a"), name
        assert abs(right - sol["c"]) / W <= _claim(doc, "c"), name
        ds = float(case.punch.slope(sol["c"]) - case.punch.slope(-sol["a"]))
        assert abs(alpha - sol["alpha"]) / max(abs(alpha), ds) <= _claim(doc, "alpha"), name
        # the forward integrals at the exported ends, by quadrature of the slope: P and P s
        P, M = quad_reference.load(case.punch, sol["a"], sol["c"], case.A), \
            quad_reference.moment(case.punch, sol["a"], sol["c"], case.A)
        assert abs(P - case.P) / case.P <= _claim(doc, "P_integral"), name
        assert abs(M / P - case.s) / W <= _claim(doc, "s_centroid"), name


# --- precision: the pressure -------------------------------------------------------------------
def test_pressure_against_the_inversion_integral_and_its_integrals(dataset):
    """Pointwise against the quadrature, and ∫p = P, ∫x p = P s of the function behind the data."""
    solvers = {m: registry.get(m) for m in ("closedform", "sie")}
    for doc in dataset[1].values():
        case, sol = _case(doc), doc["solution"]
        x, p = _grid_subset(doc)
        ref = pressure_by_quadrature(case.punch, case.A, sol["a"], sol["c"], sol["alpha"], x)
        err = float(np.max(np.abs(p - ref))) / _peak(doc)
        assert err <= _claim(doc, "p"), f"{doc['name']}: p error {err:.2e} of the peak"
        if doc["source"]["method"] != "closedform":
            continue
        res = solvers["closedform"].normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
        assert np.array_equal(res.pressure(np.asarray(doc["fields"]["x"])), doc["fields"]["p"])
        breaks = (-case.punch.b, case.punch.b)
        P = _integral(res.pressure, sol["a"], sol["c"], breaks)
        M = _integral(lambda t: t * res.pressure(t), sol["a"], sol["c"], breaks)
        assert abs(P - case.P) / case.P <= _claim(doc, "P_integral"), doc["name"]
        assert abs(M / P - sol["s"]) / sol["W"] <= _claim(doc, "s_centroid"), doc["name"]


@pytest.mark.slow
def test_sie_pressure_past_lift_off_carries_the_load(dataset):
    """The SIE's ends past lift-off: ∫p = P and ∫x p = P s of the exported pressure (nested quadrature)."""
    for doc in dataset[1].values():
        if doc["source"]["method"] != "sie":
            continue
        case, sol = _case(doc), doc["solution"]
        a, c = sol["a"], sol["c"]

        def p(x: float) -> float:
            return float(pressure_by_quadrature(case.punch, case.A, a, c, sol["alpha"], x)[0])

        breaks = (-case.punch.b, case.punch.b)
        P, M = _integral(p, a, c, breaks), _integral(lambda x: x * p(x), a, c, breaks)
        assert abs(P - case.P) / case.P <= _claim(doc, "P_integral"), doc["name"]
        assert abs(M / P - case.s) / sol["W"] <= _claim(doc, "s_centroid"), doc["name"]


def test_peaks_are_maxima_of_the_pressure(dataset):
    for doc in dataset[1].values():
        case, sol = _case(doc), doc["solution"]
        W = sol["W"]
        for side, pk in sol["peaks"].items():
            if not pk["interior"]:
                continue
            dx = _claim(doc, "peak_x") * W
            x = np.array([pk["x"] - dx, pk["x"], pk["x"] + dx])
            p = pressure_by_quadrature(case.punch, case.A, sol["a"], sol["c"], sol["alpha"], x)
            assert abs(p[1] - pk["p"]) / _peak(doc) <= _claim(doc, "peak_p"), (doc["name"], side)
            # a maximum within dx: p falls on both sides (up to the claimed precision of p)
            assert max(p[0], p[2]) <= pk["p"] * (1 + _claim(doc, "peak_p")), (doc["name"], side)


# --- precision: partial slip and the fretting cycle ----------------------------------------------
def test_stick_zone_and_shear(dataset):
    """d, e against the SIE (or past the framework the shifted punch); q = f (p - p*) by quadrature; ∫q = Q."""
    sie = registry.get("sie")
    for doc in dataset[1].values():
        if doc["kind"] != "slip":
            continue
        case, sol = _case(doc), doc["solution"]
        Q, f = case.shear_load
        if doc["source"]["method"] == "closedform":
            other = sie.slip(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt, Q=Q, f=f)
            lo, hi = other.stick_zone
        else:   # the stick zone is the corrective contact at P - |Q|/f and the contact's tilt
            lo, hi = beyond_reference.edge_on_centre(case.punch, case.P - abs(Q) / f, case.A,
                                                    alpha=sol["alpha"])
        d, e = 0.5 * (hi - lo), -0.5 * (hi + lo)
        assert abs(d - sol["d"]) / sol["d"] <= _claim(doc, "d"), doc["name"]
        assert abs(e - sol["e"]) / sol["d"] <= _claim(doc, "e"), doc["name"]
        x = np.asarray(doc["fields"]["x"])[1:-1:10]
        q = np.asarray(doc["fields"]["q"])[1:-1:10]
        p = pressure_by_quadrature(case.punch, case.A, sol["a"], sol["c"], sol["alpha"], x)
        pstar = pressure_by_quadrature(case.punch, case.A, sol["d"] + sol["e"], sol["d"] - sol["e"],
                                       sol["alpha"], x)
        ref = math.copysign(f, Q) * (p - pstar)
        scale = float(np.max(np.abs(doc["fields"]["q"])))
        err = float(np.max(np.abs(q - ref))) / scale
        assert err <= _claim(doc, "q"), f"{doc['name']}: q error {err:.2e}"
        if doc["source"]["method"] == "closedform":
            res = registry.get("closedform").slip(case.punch, case.P, case.s_load, A=case.A,
                                                  tilt=case.tilt, Q=Q, f=f)
            got = _integral(res.shear, sol["a"], sol["c"], (-case.punch.b, case.punch.b, lo, hi))
            assert abs(got - Q) / abs(Q) <= _claim(doc, "q"), doc["name"]


def test_fretting_cycle_against_the_sie(dataset):
    doc = dataset[1]["fretting_Q0.4"]
    case = _case(doc)
    Q, f = case.shear_load
    sie = registry.get("sie")
    base = sie.normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt)
    other = sie.fretting(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt, Q_max=Q, f=f,
                         states=len(doc["cycle"]["Q"]) // 3, normal=base)
    sol, cyc = doc["solution"], doc["cycle"]
    assert np.array_equal(other.branch, cyc["branch"])
    assert abs(other.energy - sol["energy"]) / sol["energy"] <= _claim(doc, "energy")
    _, loop = other.loop()
    assert np.max(np.abs(loop - cyc["loop"])) / np.max(np.abs(cyc["loop"])) <= _claim(doc, "loop")
    stick = np.column_stack([cyc["stick_left"], cyc["stick_right"]])
    assert np.max(np.abs(other.stick - stick)) / sol["d"] <= _claim(doc, "stick")


# --- precision: the stresses ----------------------------------------------------------------------
def test_surface_stress_of_a_normal_contact_is_minus_the_pressure(dataset):
    """At z = 0 with no shear, σxx = -p(x) (Johnson eq. 2.25 at the surface)."""
    for doc in dataset[1].values():
        if doc["kind"] != "normal":
            continue
        err = np.max(np.abs(np.add(doc["fields"]["sxx_surface"], doc["fields"]["p"]))) / _peak(doc)
        assert err <= _claim(doc, "sxx_surface"), f"{doc['name']}: {err:.2e}"


def _flamant(pressure, shear, a, c, breaks, x, z):
    """σxx, σzz, σxz at (x, z > 0) by QUADPACK over Johnson's eqs. (2.23)-(2.25), typed in here."""
    def comp(kernel):
        pts = sorted({*breaks, min(max(x, -a), c)})
        return quiet_quad(kernel, -a, c, points=[t for t in pts if -a < t < c] or None, limit=400,
                          epsabs=0.0, epsrel=1e-10)[0]

    def r4(t):
        return ((x - t) ** 2 + z * z) ** 2

    sxx = -2 * z / math.pi * comp(lambda t: pressure(t) * (x - t) ** 2 / r4(t)) \
        - 2 / math.pi * comp(lambda t: shear(t) * (x - t) ** 3 / r4(t))
    szz = -2 * z**3 / math.pi * comp(lambda t: pressure(t) / r4(t)) \
        - 2 * z * z / math.pi * comp(lambda t: shear(t) * (x - t) / r4(t))
    sxz = -2 * z * z / math.pi * comp(lambda t: pressure(t) * (x - t) / r4(t)) \
        - 2 * z / math.pi * comp(lambda t: shear(t) * (x - t) ** 2 / r4(t))
    return sxx, szz, sxz


@pytest.mark.parametrize("name", ["general", "slip_Q0.4",
                                  pytest.param("beyond_edge_on_flat", marks=pytest.mark.slow)])
def test_subsurface_stresses_against_flamant_by_quadrature(dataset, name):
    doc = dataset[1][name]
    case, sol = _case(doc), doc["solution"]
    a, c = sol["a"], sol["c"]
    # the tractions: the closed form (checked against the inversion integral above), or past
    # lift-off the SIE at 4n (its pressure within 1.3e-10 of the peak of that integral)
    method, options = ("sie", {"n": 4096}) if case.beyond else ("closedform", {})
    res = registry.get(method).normal(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt, **options)
    breaks = [-case.punch.b, case.punch.b]
    shear = (lambda t: 0.0)
    if doc["kind"] == "slip":
        res = registry.get(method).slip(case.punch, case.P, case.s_load, A=case.A, tilt=case.tilt,
                                        Q=case.Q, f=case.f, normal=res, **options)
        breaks += sol["stick_zone"]
        shear = (lambda t: float(res.shear(t)))

    def pressure(t):
        return float(res.pressure(t))

    sub = doc["subsurface"]
    worst = 0.0
    for i in (0, 8):   # the shallowest point on the left, the deepest on the right
        ref = _flamant(pressure, shear, a, c, breaks, sub["x"][i], sub["z"][i])
        got = (sub["sxx"][i], sub["szz"][i], sub["sxz"][i])
        worst = max(worst, *(abs(g - r) / _peak(doc) for g, r in zip(got, ref)))
    assert worst <= _claim(doc, "subsurface"), f"{name}: stress error {worst:.2e} of the peak"

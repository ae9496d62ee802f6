"""CalculiX decks (``threepart deck``): the deck's structure checked by a keyword parser, and a run.

Without ``ccx`` every check here still runs: the deck is parsed
(:func:`threepart.calculix.parse_deck`) and its mesh, sets, loads and
constraints are checked against what they stand for -- the load and its
moment against ``P`` and ``P s``, every element counterclockwise, the tied
lid, no node of one body on a node of the other. With ``ccx`` on the PATH the
slow test runs the deck and checks the load the base carries and the contact
against the closed form.
"""
from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from threepart import calculix
from threepart.problem.catalogue import get_case
from threepart.cli import main
from threepart.tolerances import tolerance

#: gmsh leaves coordinates like -4e-14 where 0 was meant; the deck snaps them: none left below this
SNAPPED = 1e-12
#: sums and ratios of a few floats: exact up to rounding (the table's closed-form entries)
EXACT = tolerance("closedform", "exact").limit
ROUND_OFF = tolerance("closedform", "round_off").limit
#: the deck prints the penalty stiffness K with six significant digits
PRINTED = 1e-5
#: ccx's base reaction against the applied P: its Newton solve's convergence
REACTION = 1e-9
#: the user's guide page whose CalculiX walkthrough the slow test runs as written
README = Path(__file__).resolve().parents[1] / "docs" / "guide" / "verification.md"



def _deck(tmp_path: Path, *extra: str) -> tuple[str, list[calculix.Keyword]]:
    out = tmp_path / "job.inp"
    assert main(["deck", "--R1", "10", "--R2", "5", "--b", "1", "--P", "1442.3", "--s", "0.1",
                 "--E", "210000", "--nu", "0.3", "--h", "0.4", "--out", str(out), *extra]) == 0
    text = out.read_text()
    return text, calculix.parse_deck(text)


def _nodes(cards: list[calculix.Keyword]) -> dict[int, np.ndarray]:
    card = next(c for c in cards if c.name == "NODE")
    return {int(r[0]): np.array([float(r[1]), float(r[2])]) for r in card.data}


def _nset(cards: list[calculix.Keyword], name: str) -> list[int]:
    card = next(c for c in cards if c.name == "NSET" and c.params["NSET"] == name)
    return [int(v) for r in card.data for v in r]


def test_deck_parses_and_holds_the_model(tmp_path):
    text, cards = _deck(tmp_path)
    kinds = [c.name for c in cards]
    for k in ("HEADING", "NODE", "ELEMENT", "NSET", "MATERIAL", "ELASTIC", "SOLID SECTION", "SURFACE",
              "CONTACT PAIR", "SURFACE BEHAVIOR", "EQUATION", "BOUNDARY", "STEP", "STATIC", "CLOAD",
              "NODE FILE", "CONTACT FILE", "NODE PRINT", "END STEP"):
        assert k in kinds, k
    assert "** Units:" in text and "-K*COPEN" in text and "FIRST increment" in text
    nodes = _nodes(cards)
    # every element is counterclockwise (positive area) and second order
    for card in (c for c in cards if c.name == "ELEMENT"):
        assert card.params["TYPE"] in ("CPE8", "CPE6")
        nc = 4 if card.params["TYPE"] == "CPE8" else 3
        for row in card.data:
            xy = np.array([nodes[int(n)] for n in row[1:1 + nc]])
            area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
            assert area > 0, row[0]
            assert len(row) == 1 + 2 * nc
    # no node of the punch lies on a node of the block (ccx fails on that), no x = -4e-14
    xy = np.array(list(nodes.values()))
    assert len(np.unique(np.round(xy, 10), axis=0)) == len(xy)
    assert not np.any((np.abs(xy) < SNAPPED) & (xy != 0))
    # the load: resultant P and moment P s (free tilt), on the punch's two top corners
    load = next(c for c in cards if c.name == "CLOAD").data
    F = np.array([float(r[2]) for r in load])
    xs = np.array([nodes[int(r[0])][0] for r in load])
    assert [r[1] for r in load] == ["2", "2"]
    assert -F.sum() == pytest.approx(1442.3, rel=EXACT)
    assert -(F * xs).sum() == pytest.approx(1442.3 * 0.1, rel=ROUND_OFF)
    # the lid: every other top node follows the corners linearly (three-term equations)
    top, ctrl = _nset(cards, "NTOP"), _nset(cards, "NCTRL")
    eq = next(c for c in cards if c.name == "EQUATION").data
    assert len(eq) == 2 * (len(top) - 2) and all(r == ["3"] for r in eq[::2])
    for r in eq[1::2]:
        n, t = int(r[0]), -float(r[8])
        assert [int(r[3]), int(r[6])] == ctrl
        xl, xr = nodes[ctrl[0]][0], nodes[ctrl[1]][0]
        assert t == pytest.approx((nodes[n][0] - xl) / (xr - xl), abs=EXACT)
    # the penalty: K = 200 E / h, E the block's: 210000/2 under the stiff punch for two similar
    # bodies of --E 210000 (threepart.problem.material.rigid_punch_modulus, the one material convention)
    K = float(next(c for c in cards if c.name == "SURFACE BEHAVIOR").data[0][0])
    assert K == pytest.approx(200 * 105000 / 0.4, rel=PRINTED)


def test_deck_options(tmp_path):
    _, cards = _deck(tmp_path, "--tilt", "suppressed", "--s", "0", "--pair", "--penalty", "1e9")
    eq = next(c for c in cards if c.name == "EQUATION").data
    assert all(r == ["2"] for r in eq[::2])            # the lid held level
    mats = [c for c in cards if c.name == "ELASTIC"]
    assert mats[0].data == mats[1].data                 # two similar bodies
    assert float(next(c for c in cards if c.name == "SURFACE BEHAVIOR").data[0][0]) == 1e9


def test_parse_deck_refuses_malformed_text():
    with pytest.raises(ValueError, match="line 1: data before the first keyword"):
        calculix.parse_deck("1, 2, 3\n*NODE\n")
    with pytest.raises(ValueError, match="line 2: malformed parameter"):
        calculix.parse_deck("** c\n*NSET, NSET=\n1\n")


@pytest.mark.parametrize("argv, match", [
    (["--case", "caseA_sym", "--h", "-1"], "`h` = -1"),
    (["--case", "caseA_sym", "--format", "abaqus"], "argument --format: invalid choice: 'abaqus'"),
    (["--case", "caseA_sym", "--R1", "3"], "give `--case` or the punch and loads, not both"),
])
def test_deck_bad_input(tmp_path, capsys, argv, match):
    assert main(["deck", *argv, "--out", str(tmp_path / "x.inp")]) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("h", ["1e-9", "1e-5", "2"])
def test_deck_refuses_a_mesh_size_out_of_range_before_meshing(tmp_path, capsys, monkeypatch, h):
    """``--h`` far below W/1000 (gmsh climbed to 3.7 GB at 1e-9) or above W/4 is refused in one
    line naming ``--h`` and the range, exit 2, before gmsh starts; ``--help`` states the range."""
    import gmsh

    def no_gmsh(*args, **kwargs):
        raise AssertionError("gmsh started for a refused --h")

    monkeypatch.setattr(gmsh, "initialize", no_gmsh)
    out = tmp_path / "x.inp"
    assert main(["deck", "--case", "caseA_sym", "--h", h, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    W = 2 * 2.010875491               # caseA_sym's contact width a + c (the deck prints a, c)
    lo, hi = calculix.W_OVER_H
    assert len(err.strip().splitlines()) == 1 and not out.exists()
    assert f"`--h`) = {float(h):.4g}" in err and f"W/h from {lo:g} to {hi:g}" in err, err
    assert f"h from {W / hi:.4g} to {W / lo:.4g}" in err, err
    assert main(["deck", "--help"]) == 0
    assert f"W/{hi:g}" in capsys.readouterr().out.replace("\n", " ")


@pytest.mark.slow
def test_ccx_default_deck_meets_the_issue_targets(tmp_path):
    """The deck at its defaults (W/h = 200, K = 200 E/h, punch 1000 x stiffer) on ``caseA_sym``
    scaled to small slopes (the CalculiX column's case), against the closed form: the base
    carries P, the contact's nodal forces sum to P, a and c within 1e-3 W and both peaks
    within 1e-3 (issue 22; about 10 s of ccx CPU).

    Without ``ccx`` the run is refused with the named error and the install hint.
    """
    from threepart.reports.compare import normal_figures
    from threepart.reports.referee import SLOPE_SCALE, calculix_result

    if shutil.which("ccx") is None:
        with pytest.raises(calculix.CcxMissing, match="apt-get install calculix-ccx"):
            calculix.run_ccx("*HEADING\n", tmp_path)
        return
    res, ref = calculix_result(get_case("caseA_sym"), calculix.DeckSettings().n,
                               calculix.DeckSettings().penalty_factor, tmp_path)
    W = ref.a + ref.c
    sp_P = calculix.read_reaction(next(tmp_path.glob("*.dat")).with_suffix(""))[1]
    assert sp_P == pytest.approx(get_case("caseA_sym").resolved().P / SLOPE_SCALE, rel=REACTION)
    fig = normal_figures(ref, res)
    for q in ("p_left", "p_right"):
        assert fig[q][2] < tolerance("referee", q).limit, (q, fig[q])
    assert abs(res.a - ref.a) < tolerance("referee", "a").limit * W
    assert abs(res.c - ref.c) < tolerance("referee", "c").limit * W
    assert abs(res.P / ref.P - 1) < tolerance("referee", "P").limit


def test_verify_column_without_ccx_says_so(monkeypatch):
    """Without ccx the CalculiX column is one empty study whose note says so, and the report
    that carries it is valid against the schema and shows the note."""
    from threepart.reports.verify import render
    from threepart.reports.verify.runs import MODES
    from threepart.reports.referee import calculix_studies
    from threepart.reports.verify.report import build_report, validate

    monkeypatch.setattr(calculix, "ccx_available", lambda: False)
    studies = calculix_studies(say=lambda m: None)
    assert len(studies) == 1 and not studies[0].values
    assert "not on the PATH" in studies[0].notes[0] and studies[0].method == "calculix"
    doc = build_report(MODES["quick"], [], studies, {}, {})
    validate(doc)
    md = render.markdown(doc)
    assert "CalculiX convergence in h" in md and "apt-get install calculix-ccx" in md


def _walkthrough() -> list[str]:
    """The README's CalculiX walkthrough: the three lines from ``threepart deck`` on."""
    lines = README.read_text(encoding="utf-8").splitlines()
    i = next(k for k, ln in enumerate(lines) if ln.strip().startswith("threepart deck --"))
    return [ln.strip() for ln in lines[i:i + 3]]


@pytest.mark.slow
def test_the_readme_calculix_walkthrough_passes(tmp_path, monkeypatch, capsys):
    """The README's three lines run as written (``<the A deck printed>`` replaced by the A the
    deck printed): ccx converges in one increment, as the deck's header says it must, and
    ``compare`` passes every check of the tolerance table's ``referee`` rows against the closed
    form with no pitfall (6.5 s of ccx CPU, about a minute on a loaded machine)."""
    if shutil.which("ccx") is None:
        pytest.skip("ccx (CalculiX) is not on the PATH: apt-get install calculix-ccx")
    deck, ccx, compare = _walkthrough()
    assert deck.startswith("threepart deck ") and compare.startswith("threepart compare "), (deck, compare)
    monkeypatch.chdir(tmp_path)
    assert main(shlex.split(deck)[1:]) == 0
    A = re.search(r"compliance A = (\S+) ", capsys.readouterr().out)
    assert A is not None
    words = shlex.split(ccx)
    env = dict(os.environ, **dict(w.split("=", 1) for w in words if "=" in w))
    subprocess.run([w for w in words if "=" not in w], env=env, cwd=tmp_path, check=True,
                   capture_output=True, timeout=1800, start_new_session=True)
    assert calculix.read_increments(tmp_path / "job") == 1
    argv = shlex.split(compare.replace("<the A deck printed>", A.group(1)))
    assert main(argv[1:]) == 0
    doc = json.loads((tmp_path / "compare" / "report.json").read_text())
    assert doc["passed"] and not doc["pitfalls"]
    assert {"a", "c", "P", "p_left", "p_right"} <= {c["quantity"] for c in doc["checks"]}
    for c in doc["checks"]:
        assert c["error"] < tolerance("referee", c["quantity"]).limit, c

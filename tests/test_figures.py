"""``threepart figures`` writes the paper's four figures atomically and refuses to overwrite."""
from __future__ import annotations

import json

import pytest

from threepart import rigid_punch, sie
from threepart.output import MARKER, OutputExistsError, read_marker
from threepart.problem.punch import Punch
from threepart.tolerances import tolerance
from threepart.reports import figures

#: set (b) as the paper's figure reads: the right peak rises by more than a fifth, the left one and
#: a/c move by a few per cent at most
SET_B_RIGHT_RISE, SET_B_LEFT_SPREAD, SET_B_RATIO_SPREAD = 1.2, 1.06, 1.1


def test_figures_are_written_once(tmp_path):
    out = tmp_path / "figs"
    assert figures.main(out=out, sie=False) == 0
    names = sorted(p.name for p in out.iterdir() if p.name != MARKER)
    assert names == ["figures.json", "pressure_a.png", "pressure_b.png", "shear_a.png", "shear_b.png"]
    assert sorted(read_marker(out)["files"]) == names    # the marker lists exactly what was written
    data = json.loads((out / "figures.json").read_text())
    assert set(data["sets"]) == {"a", "b"}
    # the plotted figures of set (a) are the SIE's at the same parameters (an independent method)
    b, R1 = figures.GEOMETRY["b"], figures.GEOMETRY["R1"]
    A = rigid_punch(figures.E, figures.NU)
    P = data["4PA/b"] * b / (4 * A)
    a = data["sets"]["a"]
    for i, (s, r) in enumerate(zip(a["s/R1"], a["R2/R1"])):
        ref = sie.solve_normal(Punch(R1=R1, R2=r * R1, b=b), P, s * R1, A=A)
        W, p0 = ref.width, P / (2 * b)
        left, right = ref.peaks()
        assert abs(a["a/b"][i] * b - ref.a) / W < tolerance("sie", "a").limit
        assert abs(a["c/b"][i] * b - ref.c) / W < tolerance("sie", "c").limit
        assert abs(a["p_left"][i] * p0 - left.p) / max(left.p, right.p) < tolerance("sie", "p_left").limit
        assert abs(a["p_right"][i] * p0 - right.p) / max(left.p, right.p) < tolerance("sie", "p_right").limit
    # set (a): the right peak grows and the left one falls with the clockwise moment (paper, Results)
    a = data["sets"]["a"]
    assert a["p_right"] == sorted(a["p_right"]) and a["p_left"] == sorted(a["p_left"], reverse=True)
    assert figures.main(out=out, sie=False) == 0          # a rerun replaces threepart's own figures
    (out / "notes.txt").write_text("mine")
    with pytest.raises(OutputExistsError, match="'notes.txt', which threepart did not write"):
        figures.main(out=out, sie=False)
    (out / "notes.txt").unlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["figs"]


def test_set_b_matches_the_papers_reading():
    """Smaller R2/R1 at s/R1 = 0.25: the right peak grows a lot, the left one barely moves,
    and a/c stays almost constant (paper, Results)."""
    b = figures.figure_data("b", sie=False)
    assert b["p_right"] == sorted(b["p_right"])
    assert b["p_right"][-1] / b["p_right"][0] > SET_B_RIGHT_RISE
    assert max(b["p_left"]) / min(b["p_left"]) < SET_B_LEFT_SPREAD
    ratio = [a / c for a, c in zip(b["a/b"], b["c/b"])]
    assert max(ratio) / min(ratio) < SET_B_RATIO_SPREAD

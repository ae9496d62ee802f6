"""The verification report's fretting-wear section (issue 39): a march's record, judged and rendered.

References: the closed-form worn limit (its stick zone, against which the record's
distances are measured), the tolerance table's rows (each target's limit), and the
march's own volumes and energies (eq. W15 recomputed here from the records).
"""
from __future__ import annotations

import numpy as np
import pytest

import threepart
from threepart import Punch
from threepart.reports.verify import build_report, render, validate
from threepart.reports.verify.runs import MODES
from threepart.reports.verify.wear_section import (TARGETS, depth_at, march_record, peer_depth, study_record,
                                                   wear_section)
from threepart.tolerances import tolerance

A = 4 * (1 - 0.09) / 210e3
HERTZ = Punch(R1=10, R2=10, b=0)
#: linear interpolation and a ratio of maxima: rounding
ROUND = tolerance("wear-limit", "round_off").limit


@pytest.fixture(scope="module")
def march():
    return threepart.wear(HERTZ, 400.0, 0.0, 100.0, 0.5, A=A, law="energy", k=1e-5, cycles=10)


def test_the_record_judges_each_target_by_its_tolerance_row(march):
    rec = march_record(march)
    assert set(rec["targets"]) == set(TARGETS) - {"peer_depth", "peer_depth_early"}      # no other method's march given: no target of it
    for key, t in rec["targets"].items():
        row = TARGETS[key][1]
        assert t["limit"] == (None if row is None else tolerance(*row).limit)
        value = rec["figures"][key]
        assert t["met"] == (bool(value) if row is None else value <= t["limit"])
    # eq. W15 recomputed from the records: the worn area per cycle against k times the work
    dV = np.diff(march.volumes) / np.diff(march.cycles)
    assert rec["identity"] == pytest.approx(np.max(np.abs(dV / (march.k * march.energy[:-1]) - 1)),
                                            rel=tolerance("wear-limit", "round_off").limit)
    # a symmetric contact: the stick zone stays, and it is the limit's (docs/WEAR.md, section 1)
    W = march.contacts[0, 1] - march.contacts[0, 0]
    assert rec["targets"]["stick_zone"]["met"]
    assert np.allclose(rec["limit"]["stick_zone"], march.stick_zones[-1], rtol=0,
                       atol=tolerance("wear", "stick_zone").limit * W)
    # early wear: the pressure nears the limit at every step, the energy still rises (the contact grows)
    assert np.all(np.diff(rec["distance"]) < 0) and rec["targets"]["limit_monotone"]["met"]
    assert rec["energy_peak_cycle"] == march.cycles[-1]
    assert np.all(np.diff(march.energy) > 0)


def test_the_section_renders_every_target_in_md_and_html(march, tmp_path):
    doc = build_report(MODES["quick"], [], [], {}, {})
    doc["wear"] = study_record(march, tmp_path, "hertz_short", 1.0)
    validate(doc)
    md = render.markdown(doc)
    assert "## Fretting wear" in md and "hertz_short" in md and "MISSED" in md
    for key, (label, _) in TARGETS.items():
        assert (label in md) == (key in doc["wear"]["targets"])
    html = render.html(doc, tmp_path)
    assert "id='wear'" in html and "data:image/png;base64," in html
    assert (tmp_path / doc["wear"]["plot"]).read_bytes()[:4] == b"\x89PNG"
    # before the environment, after the tolerance table
    assert md.index("## Fretting wear") < md.index("## Environment")


def test_a_peer_is_compared_at_any_cycle_linearly_between_its_records(march):
    """depth_at at a record is that record, half-way it is the two records' mean; a peer whose depth is
    (1 + eps) times the march's, on other points of the same profile, is eps off at every cycle."""
    from types import SimpleNamespace

    i = len(march.cycles) // 2
    assert np.array_equal(depth_at(march, march.cycles[i]), march.depths[i])
    mid = 0.5 * (march.cycles[i] + march.cycles[i + 1])
    assert np.allclose(depth_at(march, mid), 0.5 * (march.depths[i] + march.depths[i + 1]), rtol=ROUND, atol=0)
    x = march.x[::3]
    eps = 0.02
    peer = SimpleNamespace(x=x, cycles=march.cycles,
                           depths=(1 + eps) * np.array([np.interp(x, march.x, d) for d in march.depths]))
    for N in (march.cycles[1], mid, march.cycles[-1]):
        expected = eps * np.max(np.interp(x, march.x, depth_at(march, N))) / np.max(depth_at(march, N))
        assert peer_depth(march, peer, N) == pytest.approx(expected, rel=ROUND)
    assert peer_depth(march, march, mid) == 0.0


def test_no_wear_record_no_section():
    assert wear_section(build_report(MODES["quick"], [], [], {}, {})) is None

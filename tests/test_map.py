"""The sweep engine of the validity map (:mod:`reports.map.sweep`), on fake physics.

Every test injects a fake ``evaluate`` whose numbers are a known analytic
surface of the point (:func:`expected`) and a fake control, so nothing here
runs the finite-body FEM. The fakes run on real dask workers: most tests share
one module-wide ``LocalCluster`` (its address passed as ``scheduler=``, as for
an existing cluster); one starts the default local cluster itself. Worker
processes count their calls by touching a file per call.
"""
from __future__ import annotations

import csv
import functools
import json
import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path
from typing import Callable

import jsonschema
import pytest

from threepart.cli import main as cli_main
from threepart.output import MARKER, OutputExistsError, atomic_dir, foreign_entries, read_marker
from threepart.reports.map import sweep as map_mod
from threepart.reports.map.sweep import (COLUMNS, CONTROL_LIMIT, MAX_WORKERS, below_level,
                                   designer_sentence, exit_status, run_map)
from threepart.reports.map.schema import BOUNDARY_COLUMNS, POINT_FIELDS
from threepart.reports.map.validity import EDGE_KEYS, RESULT_KEYS, MapPoint

from .fakes import sketch

ROOT = Path(__file__).resolve().parents[1]
#: the fake grid: two R2/R1, one H/b, 3 x 3 in b/R1 and (a-b)/R1
POINTS = [MapPoint(r, b, ab, 4.0) for r in (1.0, 0.5) for b in (0.1, 0.3, 1.0)
          for ab in (0.01, 0.03, 0.1)]
KEYS = [p.key() for p in POINTS]
CONTROL_ERROR = 2.5e-4


def surface(p: MapPoint) -> float:
    """The fake peak-pressure error: 0.3 % at (a-b)/R1 = 0.01, b/R1 = 0.1, R2/R1 = 1, linear in each."""
    return 0.003 * (p.a_minus_b_over_R1 / 0.01) * (p.b_over_R1 / 0.1) * (2.0 - p.R2_over_R1)


def expected(p: MapPoint) -> dict[str, float]:
    """What the fake evaluate returns at ``p`` (every key of RESULT_KEYS and EDGE_KEYS, distinct values)."""
    e = surface(p)
    return {"peak_rel_error": e, "p_left_rel_error": e, "p_right_rel_error": 0.5 * e,
            "a_rel_error": e / 3, "c_rel_error": -e / 7, "alpha_error": e / 11,
            "fem_error_estimate": 1e-4 * p.b_over_R1, "P": 100.0 * p.a_minus_b_over_R1,
            "s": 0.1 * p.s_over_lift, "time_s": 0.01 + p.b_over_R1,
            "K_N_left_rel_error": e / 13, "K_N_right_rel_error": -e / 17}


def steps(doc: dict) -> set[str]:
    """The keys of the bisection's points of a map."""
    return {s["key"] for b in doc["boundaries"] for s in b["steps"]}


def everything(doc: dict) -> list[str]:
    """Every point key a map evaluates: the grid and the bisection's steps (each once)."""
    return sorted(set(KEYS) | steps(doc))


#: the largest (a-b)/R1 below 1 % for each (R2/R1, b/R1), worked out by hand from surface()
LIMITS_1PCT = {(1.0, 0.1): 0.03, (1.0, 0.3): 0.01, (1.0, 1.0): None,
               (0.5, 0.1): 0.01, (0.5, 0.3): None, (0.5, 1.0): None}


class FakeEvaluate:
    """``evaluate(point, quick)`` of :func:`expected`; touches ``calls/<key>.<id>`` per call.

    ``hold_after``: only the first ``hold_after`` calls over all workers (each takes one of as
    many slots, files made exclusively beside ``calls``) return; the later ones stay in progress
    until their worker is killed, a run interrupted meanwhile.
    """

    def __init__(self, calls: Path, fail: frozenset[str] = frozenset(), sleep: float = 0.0,
                 hold_after: int | None = None):
        self.calls, self.fail, self.sleep, self.hold_after = calls, fail, sleep, hold_after

    def __call__(self, point: MapPoint, quick: bool) -> dict[str, float]:
        (self.calls / f"{point.key()}.{uuid.uuid4().hex}").touch()
        time.sleep(self.sleep)
        if self.hold_after is not None and not self._slot(self.hold_after):
            time.sleep(BUSY_S)     # the close of the map's own cluster kills it (tested below)
        if point.key() in self.fail:
            raise RuntimeError(f"mesh failed at {point.key()}")
        return expected(point)

    def _slot(self, n: int) -> bool:
        """Whether this call takes one of the ``n`` slots (a count of the calls' files would race:
        a worker slow between its touch and its count counts a later call of the other's)."""
        slots = self.calls.with_name(f"{self.calls.name}-slots")
        slots.mkdir(exist_ok=True)
        for k in range(n):
            try:
                (slots / str(k)).touch(exist_ok=False)
                return True
            except FileExistsError:
                continue
        return False


def fake_control(quick: bool) -> dict[str, object]:
    return {"control_rel_error": CONTROL_ERROR, "P": 3.0, "point": {"b_over_R1": 0.3}}


def bad_control(quick: bool) -> dict[str, object]:
    return {"control_rel_error": 3 * CONTROL_LIMIT}


def calls(d: Path) -> list[str]:
    """The keys evaluated (one entry per call)."""
    return sorted(f.name.rsplit(".", 1)[0] for f in d.iterdir())


def logged(out: Path) -> list[str]:
    """The point keys in points.jsonl (without the control)."""
    lines = (out / "points.jsonl").read_text().splitlines()
    return [json.loads(x)["key"] for x in lines if json.loads(x)["key"] != "control"]


def logged_so_far(out: Path) -> list[str]:
    """:func:`logged` of a file another process is writing: its complete lines only."""
    if not (out / "points.jsonl").exists():
        return []
    text = (out / "points.jsonl").read_text()
    lines = text[:text.rfind("\n") + 1].splitlines()
    return [k for k in (json.loads(x)["key"] for x in lines) if k != "control"]


def fresh(counter: Path) -> Path:
    """A new, empty calls directory beside ``counter``, for the next run's calls.

    A task of a stopped or killed run can still be running on the shared cluster (a client's
    end does not stop its worker's task); it touches its own run's directory, never the new
    one, so no clock has to let it drain first.
    """
    d = counter.parent / f"calls-{uuid.uuid4().hex[:8]}"
    d.mkdir()
    return d


#: the longest a test waits for a child process to reach the state it polls for: a hang guard,
#: not a timing (the wait ends once the state is reached, and fails, never proceeds, without it)
REACH_GUARD_S = 900
#: seconds between two looks at a child's files
POLL_S = 0.02


def wait_until(reached: Callable[[], bool], proc: subprocess.Popen, what: str) -> None:
    """Poll until ``reached()``; fail if ``proc`` ends first or the guard runs out (then ``proc``
    and the processes of its own session, a map's workers, are killed: none outlives the test)."""
    t0 = time.monotonic()
    while not reached():
        if proc.poll() is not None:
            pytest.fail(f"the child ended (status {proc.returncode}) before {what}: "
                        f"{proc.stderr.read() if proc.stderr else ''}")
        if time.monotonic() - t0 > REACH_GUARD_S:
            if os.getsid(proc.pid) == proc.pid:
                os.killpg(proc.pid, signal.SIGKILL)
            proc.kill()
            pytest.fail(f"the child did not reach {what} within {REACH_GUARD_S} s")
        time.sleep(POLL_S)


def snapshot(d: Path) -> dict[str, bytes]:
    return {str(p.relative_to(d)): p.read_bytes() for p in sorted(d.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def scheduler():
    """A 2-worker cluster on this machine, shared by the module, as an existing scheduler.

    Its workers are threads of this process on a TCP scheduler (the child processes of the
    tests reach it by address): no worker process can vanish under the module, as both of a
    process cluster once did in a full-suite run, leaving the sweep to wait (the map's watchdog
    now ends such a wait, see the last test).
    """
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp",
                      dashboard_address=":0") as cluster:
        yield cluster.scheduler_address


@pytest.fixture
def counter(tmp_path):
    d = tmp_path / "calls"
    d.mkdir()
    return d


@pytest.fixture
def sketched(monkeypatch):
    """The map's three plot functions replaced by :func:`sketch` in this process.

    For the tests of resuming, refusing and replacing a map, which assert on its points, logs and
    files, never on a plot's pixels: each file is still written, listed and checked through the
    map directory (:class:`threepart.output.ResumableDir`) as a drawn one is. Drawing takes half a
    sweep's time (two figures by matplotlib, 1.4 s). The drawn plots are checked on the module's
    whole maps (``finished``, ``studied``), a failed point's and a failed study's map, and the
    signed boundaries' map, which keep the real functions.
    """
    for name in ("contour", "stick_zone", "slope_plot"):
        monkeypatch.setattr(map_mod, name, sketch)


def sweep(out, scheduler, evaluate, **kw):
    kw.setdefault("say", lambda m: None)
    return run_map(out, scheduler=scheduler, evaluate=evaluate, points=kw.pop("points", POINTS),
                   control=kw.pop("control", fake_control), **kw)


@pytest.fixture(scope="module")
def finished(tmp_path_factory, scheduler):
    """One uninterrupted map (read only): its directory, document and calls."""
    root = tmp_path_factory.mktemp("finished")
    c = root / "calls"
    c.mkdir()
    lines: list[str] = []
    doc = sweep(root / "map", scheduler, FakeEvaluate(c), say=lines.append)
    return root / "map", doc, calls(c), lines


# ---------------------------------------------------------------------------------------
# a whole map
# ---------------------------------------------------------------------------------------
def test_the_map_holds_the_fake_numbers_and_validates(finished, scheduler):
    out, doc, evaluated, lines = finished
    schema = json.loads((ROOT / "reports" / "map" / "map.schema.json").read_text())
    on_disk = json.loads((out / "map.json").read_text())
    jsonschema.validate(on_disk, schema)
    assert on_disk == doc
    assert [p["key"] for p in doc["points"]] == KEYS            # grid order, not arrival order
    for p, point in zip(doc["points"], POINTS):
        assert {k: p[k] for k in (*RESULT_KEYS, *EDGE_KEYS)} == expected(point)
        assert (p["R2_over_R1"], p["b_over_R1"], p["a_minus_b_over_R1"], p["H_over_b"],
                p["s_over_lift"]) == (point.R2_over_R1, point.b_over_R1, point.a_minus_b_over_R1,
                                      point.H_over_b, point.s_over_lift)
        assert p["error"] is None
    assert doc["control_rel_error"] == CONTROL_ERROR and doc["control"]["P"] == 3.0
    assert doc["engine"] == {"kind": "dask.distributed", "scheduler": scheduler, "workers": 2,
                             "dask_version": __import__("dask").__version__}
    assert doc["summary"]["points"] == 18 and doc["summary"]["failed"] == 0
    assert doc["summary"]["computed"] == 18 and doc["summary"]["resumed"] == 0
    assert evaluated == everything(doc)                         # each point exactly once
    assert steps(doc) and not steps(doc) & set(KEYS)
    assert exit_status(doc) == 0
    progress = [m for m in lines if m.startswith("[")]
    # one line a task; the bisection's steps join the count as its curves start, mid-grid
    n = 19 + len(steps(doc))
    assert len(progress) == n and progress[-1].startswith(f"[{n}/{n}]")
    assert [int(m[1:m.index("/")]) for m in progress] == list(range(1, n + 1))
    assert all("elapsed" in m and "ETA" in m for m in progress)


def test_the_output_directory_is_threepart_s_own_and_finished(finished):
    out, doc, _, _ = finished
    marker = read_marker(out)
    assert marker is not None and marker["command"] == "map" and marker["state"] == "complete"
    assert foreign_entries(out) == []
    names = sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file())
    assert names == sorted([MARKER, "map.json", "map.csv", "boundaries.csv", "points.jsonl",
                            "plots/peak_error_R2R1_0.5_Hb_4_sL_0.png",
                            "plots/peak_error_R2R1_1_Hb_4_sL_0.png"])
    assert [p["file"] for p in doc["plots"]] == ["plots/peak_error_R2R1_1_Hb_4_sL_0.png",
                                                 "plots/peak_error_R2R1_0.5_Hb_4_sL_0.png"]
    for p in doc["plots"]:
        assert (out / p["file"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_csv_matches_the_json(finished):
    out, doc, _, _ = finished
    with open(out / "map.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == list(COLUMNS)
    assert len(rows) == len(doc["points"])
    for row, p in zip(rows, doc["points"]):
        for k in COLUMNS:
            if p[k] is None:
                assert row[k] == ""
            elif isinstance(p[k], str):
                assert row[k] == p[k]
            else:
                assert float(row[k]) == p[k]                    # exact: written with 17 digits
    with open(out / "boundaries.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == list(BOUNDARY_COLUMNS) and len(rows) == len(doc["boundaries"])
    for row, b in zip(rows, doc["boundaries"]):
        assert float(row["a_minus_b_over_R1"]) == b["a_minus_b_over_R1"]
        assert [float(row["band_lo"]), float(row["band_hi"])] == b["band"]
        assert int(row["steps"]) == len(b["steps"]) and row["status"] == b["status"]


def test_the_designer_sentence_gives_the_1_percent_boundary_and_its_sign(finished):
    import re

    _, doc, _, _ = finished
    for plot in doc["plots"]:
        r = plot["R2_over_R1"]
        got = {(r, row["b_over_R1"]): row["limit"] for row in plot["below_1_percent"]}
        assert got == {k: v for k, v in LIMITS_1PCT.items() if k[0] == r}
    one = next(p for p in doc["plots"] if p["R2_over_R1"] == 1.0)["sentence"]
    assert one.startswith("For R2/R1 = 1, H/b = 4 and s = 0, the closed form's peak pressure is "
                          "within 1 % of the finite body's at b/R1 = 0.1 for (a−b)/R1 from the "
                          "lightest load swept, 0.01 to ≈ ")
    # the located +1 % crossings of surface() = 0.3 (b/R1 / 0.1) (a-b)/R1, to within the
    # bisection's final bracket (3 steps from a grid bracket of a factor 10/3 or 3)
    for b, exact in ((0.1, 1 / 30), (0.3, 1 / 90)):
        got = float(re.search(rf"at b/R1 = {b:g} for \(a−b\)/R1 from the lightest load swept, "
                              rf"0.01 to ≈ ([0-9.]+) \(FEM band [0-9.]+–[0-9.]+\) \(conservative\)",
                              one).group(1))
        assert abs(got / exact - 1) < BRACKET_3_STEPS - 1, (b, got)
    assert "at heavier loads it over-predicts the peak by up to 3 %: conservative" in one
    assert "at no load swept at b/R1 = 1 (it over-predicts the peak by up to 30 %: conservative)" in one


#: the final bracket's ratio hi/lo after 3 halvings in log of a grid bracket of a factor 10/3
BRACKET_3_STEPS = (10 / 3) ** (1 / 8)


def test_below_level_says_why_the_scan_stopped_and_whether_it_is_conservative():
    def pt(b, ab, e):
        return {"b_over_R1": b, "a_minus_b_over_R1": ab, "peak_rel_error": e,
                "fem_error_estimate": 0.02 if b == 3 else 1e-4}

    pts = [pt(1, 0.01, 0.001), pt(1, 0.1, 0.002),                    # below all the way
           pt(2, 0.01, 0.001), pt(2, 0.1, None), pt(2, 0.3, 0.001),  # a failed point stops it
           pt(3, 0.01, None), pt(3, 0.1, 0.5),                       # the first point failed
           pt(4, 0.01, -0.004), pt(4, 0.1, -0.03),                   # under-predicts: |e| counts
           pt(5, 0.01, 0.02), pt(5, 0.1, 0.004), pt(5, 0.3, -0.002),  # in, from a located crossing
           pt(6, 0.01, 0.02), pt(6, 0.1, -0.03),                     # a window between two points
           pt(7, 0.01, 0.02), pt(7, 0.1, -0.005), pt(7, 0.3, -0.03)]  # + above, - inside and below
    rows = {r["b_over_R1"]: (r["limit"], r["stop"]) for r in below_level(pts)}
    assert rows == {1: (0.1, "end"), 2: (0.01, "failed"), 3: (None, "failed"), 4: (0.01, "level"),
                    5: (None, "level"), 6: (None, "level"), 7: (None, "level")}

    def crossing(b, level, x, band):
        return {"b_over_R1": b, "level": level, "a_minus_b_over_R1": x, "band": band,
                "status": "converged", "steps": []}

    text = designer_sentence(pts, 1.0, 4.0, boundaries=[
        crossing(5, 0.01, 0.05, [0.04, 0.06]), crossing(6, -0.01, 0.05, [0.045, 0.055]),
        crossing(6, 0.01, 0.03, [0.025, 0.035]), crossing(7, 0.01, 0.05, [0.04, 0.06]),
        crossing(7, -0.01, 0.2, [0.15, 0.25])])
    assert ("at b/R1 = 1 for (a−b)/R1 from the lightest load swept, 0.01 to the end of the sweep, "
            "0.1 (conservative)") in text
    assert ("at b/R1 = 2 for (a−b)/R1 from the lightest load swept, 0.01 to 0.01 (the next point "
            "failed) (conservative) and (a−b)/R1 from 0.3 (the point before failed) to the end of "
            "the sweep, 0.3 (conservative)") in text
    assert "at no load swept at b/R1 = 3 (it over-predicts the peak by up to 50 %: conservative)" in text
    assert ("at b/R1 = 4 for (a−b)/R1 from the lightest load swept, 0.01 to between 0.01 and 0.1 "
            "(not conservative); at heavier loads it under-predicts the peak by up to 3 %: not "
            "conservative") in text
    assert ("at b/R1 = 5 for (a−b)/R1 from ≈ 0.05 (FEM band 0.04–0.06) to the end of the sweep, 0.3 "
            "(changing sign there: not conservative everywhere); at lighter loads it over-predicts "
            "the peak by up to 2 %: conservative") in text
    assert ("at b/R1 = 6 for (a−b)/R1 from ≈ 0.03 (FEM band 0.025–0.035) to ≈ 0.05 (FEM band "
            "0.045–0.055) (changing sign there: not conservative everywhere); at lighter loads it "
            "over-predicts the peak by up to 2 %: conservative; at heavier loads it under-predicts "
            "the peak by up to 3 %: not conservative") in text
    # its one inside point under-predicts, but the run starts at the +1 % crossing: the sign changes
    assert ("at b/R1 = 7 for (a−b)/R1 from ≈ 0.05 (FEM band 0.04–0.06) to ≈ 0.2 (FEM band "
            "0.15–0.25) (changing sign there: not conservative everywhere)") in text
    assert "the FEM's own error estimate reaches 2 %" in text
    everywhere = [pt(1, 0.01, 0.02), pt(1, 0.1, 0.5), pt(2, 0.01, -0.04), pt(2, 0.1, 0.01)]
    assert designer_sentence(everywhere, 0.5, 1.0, 0.5) == (
        "For R2/R1 = 0.5, H/b = 1 and s = 0.5 of the lift-off lever arm, the closed form's peak "
        "pressure is off by 2 % to -4 % already at the lightest load swept, (a−b)/R1 = 0.01, and "
        "more than 1 % everywhere (it over-predicts the peak by up to 50 % and under-predicts it by "
        "up to 4 %: not conservative everywhere): over this whole range, design with a finite-body "
        "model.")


def test_the_schema_rejects_what_it_should(finished):
    schema = map_mod.load_schema()
    doc = finished[1]
    map_mod.validate(doc)
    for broken in ({**doc, "points": [{k: v for k, v in doc["points"][0].items() if k != "peak_rel_error"}]},
                   {**doc, "points": [{**doc["points"][0], "fem_error_estimate": -0.1}]},
                   {**doc, "boundaries": [{**doc["boundaries"][0], "band": [0.1]}]},
                   {k: v for k, v in doc.items() if k != "boundaries"},
                   {**doc, "engine": {**doc["engine"], "workers": "2"}},
                   {k: v for k, v in doc.items() if k != "control_rel_error"}):
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(broken, schema)
    for k in COLUMNS:   # every field is documented
        assert schema["$defs"]["point"]["properties"][k].get("description"), k


def test_the_design_space_is_declared_once_and_agrees_with_the_point_and_the_schema():
    """A new map axis (issue 23) must appear in MapPoint, the axes of reports.map.schema and the schema."""
    import dataclasses

    from threepart.reports.map.schema import COORDINATES, FILE_LABELS, GROUP_AXES, PLOT_AXES

    fields = [f.name for f in dataclasses.fields(MapPoint)]
    assert sorted(COORDINATES) == sorted(fields) and len(set(COORDINATES)) == len(COORDINATES)
    assert set(GROUP_AXES) | set(PLOT_AXES) == set(fields) and not set(GROUP_AXES) & set(PLOT_AXES)
    assert set(FILE_LABELS) == set(GROUP_AXES)
    point = map_mod.load_schema()["$defs"]["point"]
    assert point["required"] == list(COLUMNS) and set(point["properties"]) == set(COLUMNS)


# ---------------------------------------------------------------------------------------
# interruption and resume
# ---------------------------------------------------------------------------------------
class StopAfter:
    """A ``say`` that presses Ctrl-C after ``k`` progress lines."""

    def __init__(self, k: int):
        self.k, self.n = k, 0

    def __call__(self, msg: str) -> None:
        if msg.startswith("["):
            self.n += 1
            if self.n == self.k:
                raise KeyboardInterrupt


def test_an_interrupted_sweep_resumes_with_the_same_numbers(sketched, tmp_path, counter, scheduler, finished):
    out = tmp_path / "map"
    with pytest.raises(KeyboardInterrupt):
        sweep(out, scheduler, FakeEvaluate(counter), say=StopAfter(7))
    lines = (out / "points.jsonl").read_text().splitlines()
    assert len(lines) == 7                                      # every finished task, on disk
    first = logged(out)
    assert read_marker(out)["state"] == "writing" and not (out / "map.json").exists()
    counter = fresh(counter)
    doc = sweep(out, scheduler, FakeEvaluate(counter))
    assert calls(counter) == sorted(set(everything(doc)) - set(first))  # nothing finished is redone
    assert doc["summary"]["resumed"] == len(first)
    assert doc["points"] == finished[1]["points"]               # the uninterrupted numbers
    assert [{k: p[k] for k in (*RESULT_KEYS, *EDGE_KEYS)} for p in doc["points"]] == [expected(p) for p in POINTS]
    assert read_marker(out)["state"] == "complete" and exit_status(doc) == 0


KILLED_RUN = """
import sys
from pathlib import Path
from tests.test_map import POINTS, FakeEvaluate, fake_control
from threepart.reports.map.sweep import run_map
run_map(sys.argv[1], scheduler=sys.argv[2], evaluate=FakeEvaluate(Path(sys.argv[3]), sleep=0.2),
        points=POINTS, control=fake_control, say=lambda m: print(m, flush=True))
"""


def test_a_killed_run_resumes(sketched, tmp_path, counter, scheduler):
    out = tmp_path / "map"
    proc = subprocess.Popen([sys.executable, "-c", KILLED_RUN, str(out), scheduler, str(counter)],
                            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wait_until(lambda: len(logged_so_far(out)) >= 3, proc, "3 logged points")
    proc.send_signal(signal.SIGKILL)
    proc.communicate()
    done = logged(out)
    assert 3 <= len(done) < len(KEYS), proc.stderr
    with open(out / "points.jsonl", "a") as fh:                 # a line torn by the kill
        fh.write('{"key": "R2R1=1_bR1=0.1_abR1=0.0')
    counter = fresh(counter)
    doc = sweep(out, scheduler, FakeEvaluate(counter))
    assert calls(counter) == sorted(set(everything(doc)) - set(done))
    assert [{k: p[k] for k in (*RESULT_KEYS, *EDGE_KEYS)} for p in doc["points"]] == [expected(p) for p in POINTS]
    assert all(json.loads(x) for x in (out / "points.jsonl").read_text().splitlines())


def test_a_quick_map_is_not_resumed_as_a_full_one(tmp_path, counter, scheduler):
    out = tmp_path / "map"
    with pytest.raises(KeyboardInterrupt):
        sweep(out, scheduler, FakeEvaluate(counter), quick=True, say=StopAfter(2))
    before = snapshot(out)
    with pytest.raises(OutputExistsError, match="unfinished quick map.*--force"):
        sweep(out, scheduler, FakeEvaluate(counter))
    assert snapshot(out) == before


# ---------------------------------------------------------------------------------------
# the output directory
# ---------------------------------------------------------------------------------------
def test_a_foreign_directory_is_refused_and_left_untouched(sketched, tmp_path, counter, scheduler, finished):
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "notes.txt").write_text("mine")
    report = tmp_path / "report"                                 # threepart's own, of another command
    with atomic_dir(report, command="verify") as tmp:
        (tmp / "r.md").write_text("a report")
    copied = tmp_path / "copied"                                 # a finished map, copied: not ours here
    copied.mkdir()
    for f in finished[0].iterdir():
        if f.is_file():
            (copied / f.name).write_bytes(f.read_bytes())
    (copied / "plots").mkdir()
    for f in (finished[0] / "plots").iterdir():
        (copied / "plots" / f.name).write_bytes(f.read_bytes())
    polluted = tmp_path / "polluted"                             # a map of ours, with a file added
    sweep(polluted, scheduler, FakeEvaluate(tmp_path))
    (polluted / "plots" / "my_sketch.png").write_bytes(b"not threepart's")
    edited = tmp_path / "edited"                                 # a map of ours, one of its files edited
    sweep(edited, scheduler, FakeEvaluate(tmp_path))
    with open(edited / "map.csv", "a") as fh:
        fh.write("my note\n")
    cases = [(plain, "holds 'notes.txt'"), (report, "threepart verify`, not a map"),
             (copied, "holds a .threepart-output.json that threepart did not write there"),
             (polluted, "holds 'plots/my_sketch.png', which threepart did not write"),
             (edited, "holds 'map.csv', which was changed after threepart wrote it")]
    for d, match in cases:
        before = snapshot(d)
        for force in (False, True):
            with pytest.raises(OutputExistsError, match=match) as info:
                sweep(d, "tcp://127.0.0.1:9", FakeEvaluate(counter), force=force)
            assert "\n" not in str(info.value) and str(d) in str(info.value)
            assert snapshot(d) == before
    assert calls(counter) == []                                  # refused before any work


def test_force_replaces_a_finished_map_only(sketched, tmp_path, counter, scheduler):
    out = tmp_path / "map"
    sweep(out, scheduler, FakeEvaluate(counter))
    before = snapshot(out)
    with pytest.raises(OutputExistsError, match="holds a finished map; pass --force"):
        sweep(out, scheduler, FakeEvaluate(counter))
    assert snapshot(out) == before
    counter = fresh(counter)
    doc = sweep(out, scheduler, FakeEvaluate(counter), force=True)
    assert calls(counter) == everything(doc)                   # recomputed from scratch
    assert doc["summary"]["resumed"] == 0 and len(logged(out)) == len(everything(doc))
    assert foreign_entries(out) == [] and read_marker(out)["state"] == "complete"
    # an unfinished map is resumed, even with --force: nothing finished is thrown away
    interrupted = tmp_path / "interrupted"
    with pytest.raises(KeyboardInterrupt):
        sweep(interrupted, scheduler, FakeEvaluate(counter), say=StopAfter(5))
    done = logged(interrupted)
    counter = fresh(counter)
    doc = sweep(interrupted, scheduler, FakeEvaluate(counter), force=True)
    assert calls(counter) == sorted(set(everything(doc)) - set(done))
    assert doc["summary"]["resumed"] == len(done)


# ---------------------------------------------------------------------------------------
# failures and the exit status
# ---------------------------------------------------------------------------------------
def test_a_failed_point_is_recorded_exits_1_and_is_retried(tmp_path, counter, scheduler):
    out = tmp_path / "map"
    bad = KEYS[4]
    doc = sweep(out, scheduler, FakeEvaluate(counter, fail=frozenset({bad})))
    p = doc["points"][4]
    assert p["error"] == f"RuntimeError: mesh failed at {bad}"
    assert all(p[k] is None for k in RESULT_KEYS)
    assert doc["summary"]["failed"] == 1 and exit_status(doc) == 1
    assert [{k: q[k] for k in POINT_FIELDS} for q in doc["points"] if q["key"] != bad] == [
        {"key": k.key(), "R2_over_R1": k.R2_over_R1, "H_over_b": k.H_over_b,
         "s_over_lift": k.s_over_lift, "b_over_R1": k.b_over_R1,
         "a_minus_b_over_R1": k.a_minus_b_over_R1, **expected(k),
         "error": None} for k in POINTS if k.key() != bad]
    with open(out / "map.csv", newline="") as fh:
        row = list(csv.DictReader(fh))[4]
    assert row["error"] == p["error"] and row["peak_rel_error"] == ""
    assert read_marker(out)["state"] == "writing"             # unfinished: the next run retries
    counter = fresh(counter)
    before = steps(doc)
    doc = sweep(out, scheduler, FakeEvaluate(counter))
    assert calls(counter) == sorted({bad} | (steps(doc) - before))   # its curve's new steps only
    assert {k: doc["points"][4][k] for k in (*RESULT_KEYS, *EDGE_KEYS)} == expected(POINTS[4])
    assert exit_status(doc) == 0 and read_marker(out)["state"] == "complete"


def test_a_control_beyond_its_limit_exits_1(sketched, tmp_path, counter, scheduler):
    doc = sweep(tmp_path / "map", scheduler, FakeEvaluate(counter), control=bad_control)
    assert doc["summary"]["failed"] == 0 and doc["control_rel_error"] == 3 * CONTROL_LIMIT
    assert exit_status(doc) == 1


def test_the_command_line_exit_status(sketched, tmp_path, counter, scheduler, monkeypatch, capsys):
    fake = functools.partial(map_mod.run_map, evaluate=FakeEvaluate(counter, fail=frozenset({KEYS[0]})),
                             points=POINTS, control=fake_control)
    monkeypatch.setattr(map_mod, "run_map", fake)
    assert cli_main(["map", "--out", str(tmp_path / "a"), "--scheduler", scheduler]) == 1
    assert f"failed: {KEYS[0]}: RuntimeError" in capsys.readouterr().out
    fake.keywords["evaluate"] = FakeEvaluate(counter)
    assert cli_main(["map", "--out", str(tmp_path / "a"), "--scheduler", scheduler]) == 0
    assert "DONE: 18/18 points (1 computed now)" in capsys.readouterr().out

    def interrupted(*args, **kw):
        raise KeyboardInterrupt

    monkeypatch.setattr(map_mod, "run_map", interrupted)
    assert cli_main(["map", "--out", str(tmp_path / "b")]) == 130


@pytest.mark.parametrize("args, match", [
    (["--workers", "0"], rf"`--workers` = 0 must lie in \[1, {MAX_WORKERS}\], the CPUs of this machine"),
    (["--workers", "-3"], rf"`--workers` = -3 must lie in \[1, {MAX_WORKERS}\]"),
    (["--workers", str(MAX_WORKERS + 1)], rf"`--workers` = {MAX_WORKERS + 1} must lie in \[1, {MAX_WORKERS}\]"),
    (["--workers", "100000"], rf"`--workers` = 100000 must lie in \[1, {MAX_WORKERS}\], the CPUs"),
    (["--workers", "two"], r"argument --workers: invalid int value: 'two'"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"], r"`--workers`.*`--scheduler`.*not both"),
    (["--scheduler", " "], r"`--scheduler` = ' ' must be a scheduler address"),
    (["--scheduler", "nonsense"], r"cannot reach the dask scheduler `--scheduler` = 'nonsense'"),
    (["--scheduler", "tcp://127.0.0.1:9"], r"cannot reach the dask scheduler .*Timed out"),
    (["--frobnicate"], r"unrecognized arguments: --frobnicate"),
])
def test_bad_arguments_are_one_line_with_exit_status_2(tmp_path, counter, capsys, monkeypatch,
                                                       args, match):
    import re

    monkeypatch.setattr(map_mod, "CONNECT_TIMEOUT", 1)
    monkeypatch.setattr(map_mod, "run_map", functools.partial(
        map_mod.run_map, evaluate=FakeEvaluate(counter), points=POINTS, control=fake_control))
    assert cli_main(["map", "--out", str(tmp_path / "m"), *args]) == 2
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and err.startswith("threepart map: error: "), err
    assert re.search(match, err), err
    assert "Traceback" not in out and calls(counter) == []
    assert not (tmp_path / "m").exists()                         # refused before `out` is made


def test_a_foreign_out_is_one_line_with_exit_status_2(tmp_path, capsys):
    (tmp_path / "keep.txt").write_text("x")
    assert cli_main(["map", "--out", str(tmp_path), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'keep.txt'" in err and str(tmp_path) in err
    assert (tmp_path / "keep.txt").read_text() == "x" and sorted(os.listdir(tmp_path)) == ["keep.txt"]


# ---------------------------------------------------------------------------------------
# the default engine
# ---------------------------------------------------------------------------------------
def test_the_default_engine_is_a_local_cluster_of_its_own(sketched, tmp_path, counter):
    lines: list[str] = []
    doc = run_map(tmp_path / "map", workers=1, evaluate=FakeEvaluate(counter), points=POINTS[:6],
                  control=fake_control, say=lines.append)
    assert doc["engine"]["workers"] == 1 and doc["engine"]["scheduler"].startswith("tcp://127.0.0.1:")
    assert [{k: p[k] for k in (*RESULT_KEYS, *EDGE_KEYS)} for p in doc["points"]] == [expected(p) for p in POINTS[:6]]
    assert calls(counter) == sorted(set(KEYS[:6]) | steps(doc)) and exit_status(doc) == 0
    assert doc["timings"]["startup_s"] > 0


def busy_until_killed(started: str) -> None:
    """A task that says it started (the dask Event ``started``), then keeps its worker busy."""
    from dask.distributed import Event

    Event(started).set()
    time.sleep(BUSY_S)


#: how long busy_until_killed keeps its worker: far past any close, which kills it first
BUSY_S = 3600
#: the longest a test waits for a task on a fresh local cluster to start (a hang guard, not a
#: timing: the wait ends as soon as the task says so)
START_GUARD_S = 600


def test_killing_a_busy_worker_at_the_close_of_the_map_s_own_cluster_prints_nothing(caplog):
    """A worker still busy when the map closes its own cluster is killed by its nanny, as the close
    asks: no "distributed.nanny - WARNING" line; an error of the nanny still shows. The close is the
    map's own, with its short grace (``engine.CLOSE_GRACE_S``; distributed's 5 s held an interrupted
    map 4 s on such a worker): the nanny names its reason."""
    import logging
    import uuid as _uuid

    from dask.distributed import Event

    from threepart.reports.map.engine import open_engine

    caplog.set_level(logging.INFO, logger="distributed.nanny")
    started = f"threepart-test-{_uuid.uuid4().hex}"
    with open_engine(None, 1, map_mod.CONNECT_TIMEOUT) as (client, _):
        task = client.submit(busy_until_killed, started, pure=False)
        assert Event(started, client=client).wait(START_GUARD_S), task.status
        logging.getLogger("distributed.nanny").error("a real fault")
    nanny = [(r.levelname, r.getMessage()) for r in caplog.records if r.name == "distributed.nanny"]
    assert ("ERROR", "a real fault") in nanny                    # errors still show
    assert not [m for level, m in nanny if level == "WARNING"], nanny
    assert ("INFO", "Nanny asking worker to close. Reason: threepart-map-close") in nanny, nanny


def worker_heap_setting() -> str | None:
    """The worker process's ``MALLOC_TRIM_THRESHOLD_`` (glibc reads it when the process starts)."""
    return os.environ.get("MALLOC_TRIM_THRESHOLD_")


def test_the_map_s_own_workers_keep_glibc_s_heap(monkeypatch):
    """Issue 41: distributed starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536`` (its own
    default, read back here), which cost the quick map a third of its CPU in page faults; the
    map's own cluster starts them without it, and leaves this process's environment as it was."""
    import dask

    from threepart.reports.map.engine import open_engine

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    assert "MALLOC_TRIM_THRESHOLD_" in dask.config.get("distributed.nanny.pre-spawn-environ")
    with open_engine(None, 1, map_mod.CONNECT_TIMEOUT) as (client, _):
        seen = client.run(worker_heap_setting)
    assert len(seen) == 1 and list(seen.values()) == [None]
    assert "MALLOC_TRIM_THRESHOLD_" not in os.environ


# ---------------------------------------------------------------------------------------
# Ctrl-C, a full disk, the help
# ---------------------------------------------------------------------------------------
CTRL_C_RUN = """
import functools, sys
from pathlib import Path
from tests.test_map import POINTS, FakeEvaluate, fake_control
from threepart.reports.map import sweep as map_mod
from threepart.cli import main
if __name__ == "__main__":
    map_mod.run_map = functools.partial(map_mod.run_map, points=POINTS, control=fake_control,
                                        evaluate=FakeEvaluate(Path(sys.argv[2]), hold_after=2))
    sys.exit(main(["map", "--out", sys.argv[1], "--workers", "2"]))
"""


def test_ctrl_c_prints_one_line_and_the_points_in_progress_are_rerun(sketched, tmp_path, counter, scheduler):
    """A terminal's Ctrl-C (SIGINT to the whole process group, workers included) on the default cluster."""
    out = tmp_path / "map"
    script = tmp_path / "run.py"
    script.write_text(CTRL_C_RUN)
    # SIGINT's default disposition, as a terminal's foreground job has (a background `pytest &`
    # starts with it ignored, and its children would inherit that)
    proc = subprocess.Popen([sys.executable, str(script), str(out), str(counter)], cwd=ROOT,
                            env={**os.environ, "PYTHONPATH": str(ROOT)}, start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    # two points done and a next one in progress (held until the interrupt ends its worker)
    wait_until(lambda: len(logged_so_far(out)) >= 2
               and bool(set(calls(counter)) - set(logged_so_far(out)) - {"control"}), proc,
               "2 logged points and one in progress")
    os.killpg(proc.pid, signal.SIGINT)                         # its own session: not the runner's
    stdout, stderr = proc.communicate(timeout=REACH_GUARD_S)
    assert proc.returncode == 130, stderr
    assert stderr == "threepart map: interrupted; run it again to resume\n"
    done = logged(out)
    started = set(calls(counter))
    in_progress = started - set(done)
    assert 2 <= len(done) < len(KEYS) and in_progress, (done, started)
    counter = fresh(counter)
    doc = sweep(out, scheduler, FakeEvaluate(counter))
    assert calls(counter) == sorted(set(everything(doc)) - set(done))   # nothing finished is redone ...
    assert in_progress <= set(calls(counter)) - {"control"}     # ... and nothing in progress is lost
    assert [{k: p[k] for k in (*RESULT_KEYS, *EDGE_KEYS)} for p in doc["points"]] == [expected(p) for p in POINTS]


def test_a_full_disk_while_the_map_is_written_leaves_nothing_half_written(sketched, tmp_path, counter,
                                                                        scheduler,
                                                                        monkeypatch):
    import errno
    import fnmatch

    real = os.fsync

    def fsync(fd):
        name = os.path.basename(os.readlink(f"/proc/self/fd/{fd}"))
        if fnmatch.fnmatch(name, ".map.json.*.part") or name == MARKER + ".part" and full[0]:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real(fd)

    out = tmp_path / "map"
    full = [False]
    monkeypatch.setattr(os, "fsync", fsync)
    with pytest.raises(OSError, match=r"^cannot write '.*map\.json': No space left on device$"):
        sweep(out, scheduler, FakeEvaluate(counter))
    assert not (out / "map.json").exists()
    assert [p.name for p in out.rglob("*.part")] == []
    full[0] = True                                               # and the marker itself: the next run
    with pytest.raises(OSError, match=r"^cannot write '.*\.threepart-output\.json': No space left"):
        sweep(out, scheduler, FakeEvaluate(counter))
    assert [p.name for p in out.rglob("*.part")] == []           # no .threepart-output.json.part
    monkeypatch.undo()
    counter = fresh(counter)
    doc = sweep(out, scheduler, FakeEvaluate(counter))           # resumes: every point was logged
    assert calls(counter) == [] and doc["summary"]["resumed"] == len(KEYS)
    assert steps(doc)                                            # the bisection's steps resumed too
    assert read_marker(out)["state"] == "complete"


def test_the_help_counts_the_quick_grid(capsys):
    from threepart.reports.map.validity import map_points

    assert cli_main(["map", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert f"the quick grid ({len(map_points(True))} points and the control" in text


# ---------------------------------------------------------------------------------------
# the boundary: bisection on synthetic curves (no FEM), in the map, and its resume
# ---------------------------------------------------------------------------------------
#: the grid of overhangs of the synthetic curves
OVERHANGS = (0.01, 0.03, 0.1, 0.3)


def grid_samples(f, xs=OVERHANGS):
    from threepart.reports.map.boundary import Sample

    return [Sample(x, *f(x), f"x={x:g}") for x in xs]


def test_bisection_finds_the_exact_crossing_of_a_curve_linear_in_log_overhang():
    """e = k ln(x / x0): the interpolation in log overhang is exact, and so is the band's width."""
    import math

    from threepart.reports.map.boundary import REL_WIDTH, locate

    k, x0, u = 0.02, 0.02, 0.002
    f = lambda x: (k * math.log(x / x0), u)                     # noqa: E731
    for level in (-0.01, 0.01):
        (r,) = locate(f, grid_samples(f), level, cap=10)
        exact = x0 * math.exp(level / k)
        assert r["a_minus_b_over_R1"] == pytest.approx(exact, rel=ROUND_OFF)
        assert r["status"] == "converged" and r["bracket"][1] / r["bracket"][0] - 1 <= REL_WIDTH
        assert r["bracket"][0] < exact < r["bracket"][1] and r["crossed_once"]
        assert r["band"] == pytest.approx([x0 * math.exp((level - u) / k), x0 * math.exp((level + u) / k)],
                                          rel=ROUND_OFF)
        assert r["band_open"] == [False, False]


#: the relative accuracy of an interpolation that is exact in real numbers (a few logs and exps)
ROUND_OFF = 1e-12


def test_bisection_of_a_monotone_curve_and_of_one_that_changes_sign():
    """The crossings against the exact ones: inside the final bracket, within its relative width."""
    import math

    from threepart.reports.map.boundary import REL_WIDTH, locate

    monotone = lambda x: (0.3 * x, 1e-4)                        # noqa: E731  (surface(), b/R1 = 0.1)
    (r,) = locate(monotone, grid_samples(monotone), 0.01, cap=10)
    assert r["bracket"][0] < 1 / 30 < r["bracket"][1]
    assert abs(r["a_minus_b_over_R1"] / (1 / 30) - 1) <= REL_WIDTH
    assert len(r["steps"]) == 4                                  # [0.03, 0.1]: 4 halvings to 10 %
    capped = locate(monotone, grid_samples(monotone), 0.01, cap=2)[0]
    assert capped["status"] == "capped" and len(capped["steps"]) == 2
    assert capped["bracket"][0] < 1 / 30 < capped["bracket"][1]

    # over-predicts at light loads and under-predicts at heavy ones (issue 23's curve):
    # e = 0.012 - 0.024 t^2 with t = ln(x/0.01) / ln(30), zero at t^2 = 0.5
    def turning(x):
        t = math.log(x / 0.01) / math.log(30)
        return 0.012 - 0.024 * t * t, 5e-4

    def exact(level):
        return 0.01 * 30 ** math.sqrt((0.012 - level) / 0.024)

    for level in (-0.01, 0.01, 0.0):
        (r,) = locate(turning, grid_samples(turning), level, cap=10)
        assert r["bracket"][0] < exact(level) < r["bracket"][1], level
        assert abs(r["a_minus_b_over_R1"] / exact(level) - 1) <= REL_WIDTH, level
        lo, hi = r["band"]
        assert lo < r["a_minus_b_over_R1"] < hi
    # a curve that crosses +1 % twice: two records, each flagged, each at its exact crossing
    hump = lambda x: (0.02 - 0.03 * (math.log(x / 0.05) / math.log(6)) ** 2, 1e-4)   # noqa: E731
    twice = locate(hump, grid_samples(hump), 0.01, cap=10)
    exact_twice = [0.05 * 6 ** (-math.sqrt(1 / 3)), 0.05 * 6 ** math.sqrt(1 / 3)]
    assert [r["crossed_once"] for r in twice] == [False, False]
    for r, x in zip(twice, exact_twice):
        assert r["bracket"][0] < x < r["bracket"][1] and abs(r["a_minus_b_over_R1"] / x - 1) <= REL_WIDTH


#: a signed grid: one R2/R1 and H/b, both lever arms, two b/R1
SIGNED_POINTS = [MapPoint(1.0, b, ab, 4.0, sl) for sl in (0.0, 0.5) for b in (0.1, 0.3)
                 for ab in OVERHANGS]
#: the half-width of every signed point's FEM estimate
SIGNED_U = 1e-3


def signed_surface(p: MapPoint) -> float:
    """+1.2 % at (a-b)/R1 = 0.01, falling linearly in log overhang, faster at larger b/R1 and s."""
    import math

    return 0.012 - 0.01 * (p.b_over_R1 / 0.1) ** 0.5 * (1 + p.s_over_lift) * math.log10(
        p.a_minus_b_over_R1 / 0.01)


def signed_crossing(b: float, sl: float, level: float) -> float:
    """The exact overhang where signed_surface() equals ``level``."""
    return 0.01 * 10 ** ((0.012 - level) / (0.01 * (b / 0.1) ** 0.5 * (1 + sl)))


class SignedEvaluate(FakeEvaluate):
    def __call__(self, point: MapPoint, quick: bool) -> dict[str, float]:
        base = super().__call__(point, quick)
        e = signed_surface(point)
        return {**base, "peak_rel_error": e, "p_left_rel_error": e, "p_right_rel_error": e / 2,
                "fem_error_estimate": SIGNED_U}


def test_the_map_locates_each_signed_boundary_and_resumes_its_bisection(tmp_path, counter, scheduler):
    """The boundaries in map.json against the exact crossings; a run stopped mid-bisection resumes."""
    import math

    from threepart.reports.map.boundary import LEVELS

    def run(out, **kw):
        kw.setdefault("say", lambda m: None)
        return run_map(out, scheduler=scheduler, evaluate=SignedEvaluate(counter), quick=True,
                       points=SIGNED_POINTS, control=fake_control, **kw)

    doc = run(tmp_path / "whole")
    found = {(b["b_over_R1"], b["s_over_lift"], b["level"]): b for b in doc["boundaries"]}
    want = {(b, sl, lv) for b in (0.1, 0.3) for sl in (0.0, 0.5) for lv in LEVELS
            if 0.01 < signed_crossing(b, sl, lv) < 0.3}
    assert set(found) == want and len(want) >= 6
    for (b, sl, lv), r in found.items():
        x = signed_crossing(b, sl, lv)
        assert r["a_minus_b_over_R1"] == pytest.approx(x, rel=ROUND_OFF)      # linear in log: exact
        g = 0.01 * (b / 0.1) ** 0.5 * (1 + sl)                                # the slope per decade
        band = [x * 10 ** (-SIGNED_U / g), x * 10 ** (SIGNED_U / g)]   # e falls with the overhang
        ends = (OVERHANGS[0], OVERHANGS[-1])                           # an open end stops at the sweep's
        assert r["band_open"] == [band[0] < ends[0], band[1] > ends[1]]
        assert r["band"] == pytest.approx([max(band[0], ends[0]), min(band[1], ends[1])], rel=ROUND_OFF)
        assert r["crossed_once"] and r["status"] in ("converged", "capped") and r["steps"]
        assert all(math.isfinite(s["peak_rel_error"]) for s in r["steps"])
    assert exit_status(doc) == 0
    # stopped in the bisection (its first steps logged), then resumed: no step is computed twice
    grid = len(SIGNED_POINTS) + 1
    counter = fresh(counter)
    out = tmp_path / "stopped"
    with pytest.raises(KeyboardInterrupt):
        run(out, say=StopAfter(grid + len(doc["boundaries"]) + 2))
    first = logged(out)
    assert len(first) > len(SIGNED_POINTS) and set(first) - set(p.key() for p in SIGNED_POINTS)
    counter = fresh(counter)
    again = run(out)
    every = set(p.key() for p in SIGNED_POINTS) | steps(doc)
    assert calls(counter) == sorted(every - set(first))
    assert again["boundaries"] == doc["boundaries"]


def test_signed_contours_do_not_fold_back_where_the_error_changes_sign():
    """Issue 23: |error| folds the 1 % line back on itself across a sign change; the signed field does not.

    The field over-predicts at light loads and under-predicts at heavy ones (as
    at b/R1 = 0.1 in the finite-body map). On every horizontal line b/R1 =
    const between the grid rows, a contour of the signed field at each level
    crosses once; the same level of the magnitude crosses twice (its line
    runs up one side of the zero line and back down the other).
    """
    import numpy as np

    from threepart.reports.map.plots import level_paths

    xs = np.geomspace(0.01, 0.5, 7)
    bs = np.geomspace(0.1, 3.0, 5)
    points = [{"a_minus_b_over_R1": x, "b_over_R1": b,
               "peak_rel_error": 0.015 - 0.03 * np.log(x / 0.01) / np.log(50) * (1 + 0.2 * np.log10(b / 0.1))}
              for x in xs for b in bs]
    magnitude = [{**p, "peak_rel_error": abs(p["peak_rel_error"])} for p in points]
    rows = np.log10(np.sqrt(bs[1:] * bs[:-1]))                    # between the grid rows

    def crossings(paths, y):
        n = 0
        for v in paths:
            dy = v[:, 1] - y
            n += int(np.sum((dy[:-1] < 0) != (dy[1:] < 0)))
        return n

    signed = level_paths(points, levels=(-0.01, 0.0, 0.01))
    folded = level_paths(magnitude, levels=(0.01,))
    for level, paths in signed.items():
        assert paths, level
        for y in rows:
            assert crossings(paths, y) == 1, (level, y)
        for v in paths:                                            # each line monotone in b/R1
            d = np.diff(v[:, 1])
            assert np.all(d >= 0) or np.all(d <= 0), level
    assert all(crossings(folded[0.01], y) == 2 for y in rows)      # the old failure, on |e|


# ---------------------------------------------------------------------------------------
# the lever-arm axis (no FEM)
# ---------------------------------------------------------------------------------------
#: the closed form's own root: the load's brentq closes to 1e-13 relative
LOAD_ROOT = 1e-10
#: Gauss-Chebyshev quadrature of the closed form's pressure, 4000 nodes: its slope has
#: logarithmic singularities at the joins x = -b, b, which cost the rule its spectral accuracy
#: (400 nodes: 2.5e-6)
CENTROID_QUADRATURE = 1e-6


@pytest.mark.parametrize("point", [MapPoint(1.0, 0.1, 0.03, 4.0, 0.5), MapPoint(0.5, 1.0, 0.2, 4.0, 0.5),
                                   MapPoint(0.5, 0.3, 0.1, 16.0, 0.0)])
def test_a_point_with_a_moment_is_loaded_at_its_overhang_and_half_its_lift_off_arm(point):
    """s = s_over_lift * s_max(P) from the registry's lift-off capability; max(a, c) - b the overhang;
    the centroid of the closed form's pressure (quadrature) is s and its integral is P."""
    import numpy as np

    from threepart import closedform, registry
    from threepart.problem.material import similar_pair
    from threepart.reports.map import validity

    punch, P, s = validity.point_case(point)
    A = similar_pair(validity.E, validity.NU)
    s_max = registry.lift_off("closedform", punch, P, A)[1]
    assert s == point.s_over_lift * s_max
    cf = closedform.solve_normal(punch, P, s, A=A, beyond_small_slopes=True)
    assert max(cf.a, cf.c) - punch.b == pytest.approx(point.a_minus_b_over_R1 * validity.R1,
                                                      rel=LOAD_ROOT)
    if point.s_over_lift > 0:
        assert cf.c > cf.a                                      # the load towards the R2 edge
    # Gauss-Chebyshev of the second kind on [-a, c]: p(x) sqrt-vanishes at both ends
    n = 4000
    k = np.arange(1, n + 1)
    t = np.cos(k * np.pi / (n + 1))
    w = np.pi / (n + 1) * np.sin(k * np.pi / (n + 1)) ** 2
    half, mid = (cf.a + cf.c) / 2, (cf.c - cf.a) / 2
    x = mid + half * t
    g = cf.pressure(x) / np.sqrt(1 - t**2)
    force = half * np.sum(w * g)
    assert force == pytest.approx(P, rel=CENTROID_QUADRATURE)
    assert half * np.sum(w * g * x) / force == pytest.approx(s, abs=CENTROID_QUADRATURE * cf.width)


KILLED_IN_BISECTION = """
import sys
from pathlib import Path
from tests.test_map import SIGNED_POINTS, SignedEvaluate, fake_control
from threepart.reports.map.sweep import run_map
run_map(sys.argv[1], scheduler=sys.argv[2], evaluate=SignedEvaluate(Path(sys.argv[3]), sleep=0.1),
        points=SIGNED_POINTS, control=fake_control, quick=True, say=lambda m: print(m, flush=True))
"""


def test_a_run_killed_in_the_bisection_resumes_with_its_finished_steps(sketched, tmp_path, counter,
                                                                       scheduler):
    """SIGKILL once the bisection's first steps are logged (the grid's last point may still be running,
    as each curve's bisection starts when its own points are in): nothing finished is redone."""
    out = tmp_path / "map"
    grid = {p.key() for p in SIGNED_POINTS}
    proc = subprocess.Popen([sys.executable, "-c", KILLED_IN_BISECTION, str(out), scheduler, str(counter)],
                            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wait_until(lambda: len(set(logged_so_far(out)) - grid) >= 2, proc, "2 logged bisection steps")
    proc.send_signal(signal.SIGKILL)
    proc.communicate()
    done = logged(out)
    assert len(set(done) - grid) >= 2, proc.stderr
    counter = fresh(counter)
    doc = run_map(out, scheduler=scheduler, evaluate=SignedEvaluate(counter), quick=True,
                  points=SIGNED_POINTS, control=fake_control, say=lambda m: None)
    assert calls(counter) == sorted((grid | steps(doc)) - set(done))
    assert set(done) - grid < steps(doc)                        # the finished steps were used
    for r in doc["boundaries"]:                                 # and the crossings are exact
        assert r["a_minus_b_over_R1"] == pytest.approx(
            signed_crossing(r["b_over_R1"], r["s_over_lift"], r["level"]), rel=ROUND_OFF)


def test_the_errors_are_signed_closed_form_minus_finite_body():
    """A heavier load presses harder: as the 'closed form' against a lighter 'finite body' every
    error is positive, swapped every one is negative, and each magnitude is the comparator's."""
    from threepart import closedform
    from threepart.problem.material import similar_pair
    from threepart.reports.map import validity
    from threepart.reports.compare import normal_figures

    punch, A = validity.point_punch(MapPoint(0.5, 0.3, 0.1, 4.0)), similar_pair(validity.E, validity.NU)
    light = closedform.solve_normal(punch, 0.1, 0.05, A=A, beyond_small_slopes=True)
    heavy = closedform.solve_normal(punch, 0.12, 0.05, A=A, beyond_small_slopes=True)
    for fe, cf, sign in ((light, heavy, 1.0), (heavy, light, -1.0)):
        e = validity._errors(fe, cf)
        fig = normal_figures(fe, cf)
        for k, q in (("p_left_rel_error", "p_left"), ("p_right_rel_error", "p_right")):
            assert e[k] * sign > 0 and abs(e[k]) == fig[q][2]
        assert e["a_rel_error"] == (cf.a - fe.a) / fe.a and e["a_rel_error"] * sign > 0
        assert e["c_rel_error"] == (cf.c - fe.c) / fe.c and e["c_rel_error"] * sign > 0
        assert abs(e["alpha_error"]) == fig["alpha"][2]
        assert e["peak_rel_error"] == max(e["p_left_rel_error"], e["p_right_rel_error"], key=abs)


# ---------------------------------------------------------------------------------------
# the studies on subsets (issue 23): partial slip, the small-slope load axis, CalculiX
# ---------------------------------------------------------------------------------------
from threepart.calculix import CcxMissing  # noqa: E402
from threepart.reports.map.schema import SLIP_COLUMNS, SLOPE_COLUMNS  # noqa: E402
from threepart.reports.map.studies import FIGURES, Studies, curve_name  # noqa: E402
from threepart.reports.map.validity import SLIP_SUBSET, SLOPE_SUBSET, slope_curves, subset  # noqa: E402
from threepart.reports.map.validity_slip import SLIP_RESULT_KEYS  # noqa: E402
from threepart.reports.map.validity_slope import SLOPE_RESULT_KEYS  # noqa: E402

#: the fake grid's studies: slip on R2/R1 = 1 and 0.5 (SLIP_SUBSET: all of POINTS), small slope
#: on R2/R1 = 1 (SLOPE_SUBSET), three crossings, two referee points
SLIP_POINTS = subset(POINTS, SLIP_SUBSET)
SLOPE_POINTS = subset(POINTS, SLOPE_SUBSET)
CURVES = slope_curves(POINTS)
REFEREE = (POINTS[1], POINTS[2])
#: a grid of one curve (R2/R1 = 1, b/R1 = 0.1), for the cheaper maps of the failure test
ONE_CURVE = POINTS[:3]


def fake_load_level(p: MapPoint) -> float:
    """The fake p0/E*: proportional to the overhang (as Hertz, p0/E* = a/(2R))."""
    return 0.4 * p.a_minus_b_over_R1 * (1 + p.b_over_R1)


def slip_expected(p: MapPoint) -> dict[str, float]:
    """The fake stick zone: d error from -0.3 % to +0.6 % over the points, distinct values."""
    return {"d_rel_error": 0.003 * (p.a_minus_b_over_R1 / 0.01) ** 0.5 - 0.006 * p.b_over_R1,
            "e_rel_error": -1e-3 * p.b_over_R1, "slip_fem_error_estimate": 2e-4,
            "d": 0.5 + p.a_minus_b_over_R1, "e": 0.01 * p.R2_over_R1, "slip_time_s": 0.02}


def slope_expected(p: MapPoint) -> dict[str, float]:
    """The fake small-slope cost: grows as the load level."""
    return {"load_level": fake_load_level(p), "slope_peak_rel_error": 0.2 * fake_load_level(p),
            "slope_a_rel_error": -0.1 * fake_load_level(p), "slope_time_s": 0.03}


def crossing_expected(r: float, b: float, h: float) -> dict[str, object]:
    """The fake crossing: within the grid but at b/R1 = 1."""
    x = None if b == 1.0 else 0.05 + b / 10
    return {"load_level": None if x is None else 0.05, "a_minus_b_over_R1": x,
            "ends": [(0.01, 0.001), (0.5, 0.04 if x else 0.002)], "evaluations": 5, "time_s": 0.1}


def referee_expected(p: MapPoint) -> dict[str, object]:
    """A fake CalculiX run: CalculiX's peaks 0.4 % above the FEM's, the closed form 1 % above."""
    fem = {"p_left": 1.0 + p.a_minus_b_over_R1, "p_right": 1.0 + p.a_minus_b_over_R1, "a": 1.2, "c": 1.2}
    ccx = {q: v * 1.004 for q, v in fem.items()}
    cf = {q: v * 1.01 for q, v in fem.items()}

    def rel(mine, other):
        return {q: (other[q] - mine[q]) / mine[q] for q in FIGURES}

    return {"point": p.as_dict(), "calculix": {**ccx, "P_base": 3.0}, "fem": fem, "closed_form": cf,
            "fem_minus_calculix": rel(ccx, fem), "closed_form_minus_calculix": rel(ccx, cf),
            "closed_form_minus_fem": rel(fem, cf), "n": 100.0, "time_calculix_s": 60.0}


class FakeStudy:
    """One study's fake: touches ``calls/<kind>:<name>.<id>`` per call (the map's task key)."""

    def __init__(self, calls: Path, kind: str, fail: frozenset[str] = frozenset()):
        self.calls, self.kind, self.fail = calls, kind, fail

    def __call__(self, *args):
        name = curve_name(args[:3]) if self.kind == "crossing" else args[0].key()
        key = f"{self.kind}:{name}"
        (self.calls / f"{key}.{uuid.uuid4().hex}").touch()
        if key in self.fail:
            raise RuntimeError(f"{self.kind} failed at {name}")
        if self.kind == "referee" and "ccx" in self.fail:
            raise CcxMissing("`ccx` (CalculiX) is not on the PATH: apt-get install calculix-ccx")
        if self.kind == "crossing":
            return crossing_expected(*args[:3])
        return {"slip": slip_expected, "slope": slope_expected,
                "referee": referee_expected}[self.kind](args[0])


def fake_studies(calls: Path, fail: frozenset[str] = frozenset(), small: bool = False) -> Studies:
    """The fake studies on the fake grid's subsets (``small``: partial slip and CalculiX on
    :data:`ONE_CURVE` only)."""
    return Studies(*(FakeStudy(calls, k, fail) for k in ("slip", "slope", "crossing", "referee")),
                   load_level=fake_load_level, slip_points=ONE_CURVE if small else SLIP_POINTS,
                   slope_points=() if small else SLOPE_POINTS, slope_curves=() if small else CURVES,
                   referee_points=REFEREE)


def study_keys() -> list[str]:
    return sorted([f"slip:{p.key()}" for p in SLIP_POINTS] + [f"slope:{p.key()}" for p in SLOPE_POINTS]
                  + [f"crossing:{curve_name(c)}" for c in CURVES]
                  + [f"referee:{p.key()}" for p in REFEREE])


def only(keys: list[str], prefix: bool) -> list[str]:
    """The study keys (``prefix``) or the point keys of a list of calls."""
    return [k for k in keys if (":" in k) == prefix]


@pytest.fixture(scope="module")
def studied(tmp_path_factory, scheduler):
    """One uninterrupted map with every study (fakes): its directory, document and calls."""
    root = tmp_path_factory.mktemp("studied")
    c = root / "calls"
    c.mkdir()
    doc = sweep(root / "map", scheduler, FakeEvaluate(c), studies=fake_studies(c))
    return root / "map", doc, calls(c)


def test_the_studies_are_columns_and_sections_of_the_map_and_validate(studied):
    out, doc, made = studied
    map_mod.validate(doc)
    assert doc["schema_version"] == "3.1" and exit_status(doc) == 0
    assert only(made, True) == study_keys()                    # each study task ran once
    slipped, sloped = {p.key() for p in SLIP_POINTS}, {p.key() for p in SLOPE_POINTS}
    for p, row in zip(POINTS, doc["points"]):
        assert row["load_level"] == fake_load_level(p)
        want = slip_expected(p) if p.key() in slipped else dict.fromkeys(SLIP_RESULT_KEYS)
        assert {k: row[k] for k in SLIP_RESULT_KEYS} == want and row["slip_error"] is None
        got = {k: row[k] for k in SLOPE_COLUMNS[:-1]}
        assert got == ({k: slope_expected(p)[k] for k in got} if p.key() in sloped
                       else dict.fromkeys(got))
    with open(out / "map.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(r["d_rel_error"]) for r in rows] == [slip_expected(p)["d_rel_error"] for p in POINTS]
    assert [r["slope_peak_rel_error"] == "" for r in rows] == [p.key() not in sloped for p in POINTS]
    # the small-slope crossings: one per curve, "not within the grid" at b/R1 = 1
    section = doc["small_slope"]
    assert section["level"] == 0.01 and section["plot"] == "plots/small_slope.png"
    for c, row in zip(CURVES, section["curves"]):
        want = crossing_expected(*c)
        assert (row["a_minus_b_over_R1"], row["within_grid"]) == (
            want["a_minus_b_over_R1"], want["a_minus_b_over_R1"] is not None)
    # the referee: each difference is the identity (other - CalculiX)/CalculiX of its own figures
    assert doc["referee"]["note"] is None and len(doc["referee"]["points"]) == 2
    for pt, row in zip(REFEREE, doc["referee"]["points"]):
        assert row["key"] == pt.key() and row["a_minus_b_over_R1"] == pt.a_minus_b_over_R1
        for q in FIGURES:
            for other, diff in (("fem", "fem_minus_calculix"), ("closed_form", "closed_form_minus_calculix")):
                ref = (row[other][q] - row["calculix"][q]) / row["calculix"][q]
                assert row[diff][q] == pytest.approx(ref, rel=ROUND_OFF, abs=ROUND_OFF)
    # the plots: a stick-zone plot for each group with slip points, the small-slope plot
    files = {p["file"] for p in doc["stick_zone_plots"]}
    assert files == {"plots/stick_zone_R2R1_1_Hb_4_sL_0.png", "plots/stick_zone_R2R1_0.5_Hb_4_sL_0.png"}
    for f in (*files, "plots/small_slope.png"):
        assert (out / f).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert read_marker(out)["state"] == "complete"


def test_the_stick_zone_sentence_states_what_the_sign_means():
    from threepart.reports.map.plots import stick_sentence

    def pts(*d):
        return [{"d_rel_error": x, "e_rel_error": 0.0, "slip_fem_error_estimate": 1e-4} for x in d]

    assert "WIDER" in stick_sentence(pts(0.002, 0.003)) and "not conservative" in stick_sentence(pts(0.002))
    narrower = stick_sentence(pts(-0.002, -0.001))
    assert "NARROWER" in narrower and "conservative" in narrower and "not conservative" not in narrower
    assert "sign changes" in stick_sentence(pts(-0.002, 0.001))
    assert "as large as the errors" in stick_sentence(
        [{"d_rel_error": 1e-5, "e_rel_error": 0.0, "slip_fem_error_estimate": 1e-4}])


def test_an_interrupted_map_recomputes_none_of_its_finished_studies(sketched, tmp_path, scheduler, studied):
    out = tmp_path / "map"
    first, second = tmp_path / "c1", tmp_path / "c2"
    first.mkdir()
    second.mkdir()
    with pytest.raises(KeyboardInterrupt):
        sweep(out, scheduler, FakeEvaluate(first), studies=fake_studies(first), say=StopAfter(12))
    logged_first = {json.loads(x)["key"] for x in (out / "points.jsonl").read_text().splitlines()}
    assert len(only(sorted(logged_first), True)) > 0           # some studies finished before the stop
    doc = sweep(out, scheduler, FakeEvaluate(second), studies=fake_studies(second))
    again = set(calls(second))
    assert not again & logged_first                            # nothing finished is computed again
    assert sorted(set(only(sorted(logged_first), True)) | set(only(sorted(again), True))) == study_keys()
    for k in ("points", "small_slope", "referee"):
        assert doc[k] == studied[1][k]                         # the uninterrupted numbers
    assert exit_status(doc) == 0


def test_a_failed_study_fails_the_map_and_is_retried_and_a_missing_ccx_is_a_note(tmp_path, scheduler):
    out, c = tmp_path / "map", tmp_path / "calls"
    c.mkdir()
    bad = f"slip:{ONE_CURVE[2].key()}"
    doc = sweep(out, scheduler, FakeEvaluate(c), points=ONE_CURVE,
                studies=fake_studies(c, frozenset({bad, "ccx"}), small=True))
    map_mod.validate(doc)
    assert doc["points"][2]["slip_error"] == f"RuntimeError: slip failed at {ONE_CURVE[2].key()}"
    assert doc["points"][2]["d_rel_error"] is None
    assert doc["summary"]["failed"] == 1 and exit_status(doc) == 1      # the note is not a failure
    assert "not on the PATH" in doc["referee"]["note"]
    assert all(r["note"].startswith("CcxMissing") and r["error"] is None and r["calculix"] is None
               for r in doc["referee"]["points"])
    for f in c.iterdir():
        f.unlink()
    doc = sweep(out, scheduler, FakeEvaluate(c), points=ONE_CURVE,
                studies=fake_studies(c, small=True))                   # ccx is there now
    assert calls(c) == sorted([bad, *(f"referee:{p.key()}" for p in REFEREE)])
    assert doc["points"][2]["d_rel_error"] == slip_expected(ONE_CURVE[2])["d_rel_error"]
    assert exit_status(doc) == 0 and doc["referee"]["note"] is None


#: the watchdog's periods in the test below: a look every 10 ms, giving up after 50 ms without a
#: worker (the cluster there never has one, so the outcome does not depend on these times)
WATCH_CHECK_S, WATCH_GIVE_UP_S = 0.01, 0.05


def test_a_cluster_without_workers_stops_the_map_with_the_reason_instead_of_waiting(tmp_path, counter,
                                                                                   monkeypatch):
    """A scheduler whose workers are gone (here: one that never had any) never runs a task; the
    sweep's watchdog cancels the pending tasks and the map stops with a one-line reason that says a
    rerun resumes, instead of waiting forever (a full-suite run once sat in this wait)."""
    from dask.distributed import LocalCluster

    from threepart.reports.map import engine

    monkeypatch.setattr(engine, "WORKER_CHECK_S", WATCH_CHECK_S)
    monkeypatch.setattr(engine, "NO_WORKERS_S", WATCH_GIVE_UP_S)
    with LocalCluster(n_workers=0, processes=False, dashboard_address=":0") as empty:
        with pytest.raises(RuntimeError, match=r"^the dask cluster has had no worker for 0 s, so the "
                                               r"map's pending tasks cannot run; .* rerun: the map "
                                               r"resumes where it stopped$"):
            sweep(tmp_path / "map", empty.scheduler_address, FakeEvaluate(counter))
    assert calls(counter) == []

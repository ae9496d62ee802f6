"""The report's drawing in parallel (issue 41): every plot and number of the serial drawing, and
the figures' layout computed once.

Fast: the solvers are fakes (tests/fakes.py); no timing is asserted.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from threepart.errors import InputError
from threepart.problem import catalogue
from threepart.reports.verify import report as verify
from threepart.reports.verify.report import Job, run_jobs

from .fakes import install_fakes

#: one case of each kind the report draws apart: a normal case, a partial-slip case, past lift-off
NAMES = ("caseA_moment", "slip_Q0.4", "beyond_edge_on_flat")
#: the plots of a case by its kind, as the report's sections describe them (overlay and error
#: curves of every case with more than one method; a partial-slip case's two stress plots)
KINDS = {"normal": ("overlay", "errors"), "slip": ("overlay", "errors", "stress", "von_mises")}


def _report(tmp_path: Path, monkeypatch, processes: int) -> tuple[dict, Path]:
    cases = [c for c in catalogue.load_cases() if c.name in NAMES]
    install_fakes(monkeypatch)
    monkeypatch.setattr(verify, "STUDY_CASE", "caseA_moment")
    monkeypatch.setattr(verify, "workers", lambda: processes)
    out = tmp_path / f"rep{processes}"
    verify.main(mode="quick", out=out, cases=cases, quiet=True)
    return json.loads((out / "report.json").read_text()), out


def _numbers(doc: dict) -> dict:
    """The document less what differs between two runs (times, dates, the environment)."""
    doc = {k: v for k, v in doc.items() if k not in ("created", "timings", "environment")}
    for case in doc["cases"]:
        for res in case["results"].values():
            res.pop("time_s")
    for study in doc["studies"]:
        study.pop("times")
    return doc


def test_the_parallel_drawing_writes_every_plot_and_number_of_the_serial_one(tmp_path, monkeypatch):
    serial, out1 = _report(tmp_path, monkeypatch, 1)
    parallel, out2 = _report(tmp_path, monkeypatch, 2)
    kinds = {c.name: c.kind for c in catalogue.load_cases() if c.name in NAMES}
    expected = {f"{name}_{kind}.png" for name, k in kinds.items() for kind in KINDS[k]}
    files = {p.name for p in (out2 / "plots").iterdir()}
    assert expected <= files, expected - files
    studies = {Path(p).name for p in parallel["plots"]}
    asymptote = {"edge_asymptote.png"} if parallel["edge_asymptote"]["curves"] else set()
    assert studies and files == expected | studies | asymptote, files
    assert files == {p.name for p in (out1 / "plots").iterdir()}
    for case in parallel["cases"]:       # listed in the order the sections show them
        assert [Path(p).name for p in case["plots"]] == [f"{case['name']}_{k}.png" for k in KINDS[kinds[case["name"]]]]
    assert _numbers(parallel) == _numbers(serial)
    slip = next(c for c in parallel["cases"] if c["name"] == "slip_Q0.4")
    assert set(slip["stress"]["hot_spots"]) == set(slip["results"])


def _square(i: int) -> int:
    return i * i


def _total(given: dict) -> int:
    return sum(given.values())


def _refuse() -> None:
    raise InputError("`job` = 3 is refused (a job that raises)")


@pytest.mark.parametrize("processes", [1, 2])
def test_a_job_runs_after_the_jobs_it_needs_and_its_error_reaches_the_caller(processes):
    from functools import partial

    squares = [Job(("sq", str(i)), partial(_square, i), cost=float(i)) for i in range(5)]
    total = Job(("total",), _total, needs=tuple(j.key for j in squares))
    done = run_jobs([total, *squares], processes)     # the user listed before its inputs
    assert done[("total",)] == sum(i * i for i in range(5)) == 30
    assert [done[("sq", str(i))] for i in range(5)] == [0, 1, 4, 9, 16]
    with pytest.raises(InputError, match="refused"):
        run_jobs([*squares, Job(("bad",), _refuse)], processes)
    # a job marked `here` (a result's stresses: the FE recovery's OpenMP) never runs in a worker
    pids = run_jobs([Job(("here",), os.getpid, here=True), Job(("worker",), os.getpid),
                     Job(("other",), os.getpid)], processes)
    assert pids[("here",)] == os.getpid()
    assert (pids[("worker",)] != os.getpid()) == (processes > 1)


def test_the_layout_computed_once_is_matplotlibs_constrained_layout():
    """A figure saved with its layout fixed first (one draw) is, pixel for pixel, the one
    matplotlib's savefig lays out itself (a layout draw, then the drawing)."""
    import io

    from PIL import Image

    from threepart.reports.verify import plots

    def figure():
        fig, axes = plots.new_figure(2)
        for ax in axes[0]:
            ax.semilogy(np.linspace(-1, 1, 500), np.exp(np.linspace(0, 30, 500)), label="a long label")
            ax.set_title("a title over the panel\nand its second line", fontsize=10)
            ax.set_ylabel("a label of the y axis")
            ax.legend(loc="best", fontsize=7)
        return fig

    def png(fig, fixed: bool) -> np.ndarray:
        if fixed:
            plots.fix_layout(fig, plots.DPI)
            assert fig.get_layout_engine() is None
        buf = io.BytesIO()
        fig.savefig(buf, dpi=plots.DPI, format="png", facecolor="white")
        return np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"))

    own, fixed = png(figure(), False), png(figure(), True)
    assert own.shape == fixed.shape and np.array_equal(own, fixed)

"""The verification run's studies beside its cases (issue 41): the same studies, the same numbers.

The reference is the serial path: the same functions run in this process. The studies are the
real ones at small levels (a few seconds); no timing is asserted.
"""
from __future__ import annotations

import time

import numpy as np
import pytest

from threepart.errors import InputError
from threepart.problem import catalogue
from threepart.registry import REFERENCE
from threepart.reports.verify import side
from threepart.reports.verify.runs import Mode, run_case

#: the convergence studies' case and the two-body FEM's partial-slip case
NAMES = ("caseA_moment", "slip_Q0.4")
SCHEMES = ("plain", "projected")
#: small levels of the real studies: two SIE n, two FE meshes of the default family
SMALL = Mode("quick", None, "quick", (8, 16), (38, 75))


def _numbers(studies):
    """The studies' documents less their seconds."""
    out = []
    for st in studies:
        d = st.as_dict()
        d.pop("times")
        out.append(d)
    return out


def _cases(*names):
    return [c for c in catalogue.load_cases() if c.name in names]


def test_the_studies_beside_the_cases_are_the_studies_run_here():
    cases = _cases(*NAMES)
    timings: dict[str, float] = {}
    here, friction = side.study_run(SMALL, cases, lambda m: None, False, timings, NAMES, SCHEMES)
    assert [(s.method, s.scheme, s.param) for s in here] == [
        ("sie", "plain", "n"), ("sie", "projected", "n"), ("fem", "", "h"), ("fem", "", "h")]
    with side.beside(SMALL, cases, False, NAMES, SCHEMES, None, time.perf_counter(), True, 2) as aside:
        assert aside is not None and aside.process.pid is not None
        got = aside.result()
    assert _numbers(got.studies) == _numbers(here)
    assert got.friction == friction == [] and got.wear is None and set(got.timings) == set(timings)
    assert aside.process.poll() is not None


def test_one_process_runs_no_side_process():
    with side.beside(SMALL, _cases(*NAMES), False, NAMES, SCHEMES, None, 0.0, True, 1) as aside:
        assert aside is None


def test_a_side_process_that_ends_without_an_answer_leaves_its_studies_to_this_one(capsys):
    import io

    ended = io.BytesIO(b"")               # the side process ended: its answer's stream is empty
    cases = _cases(NAMES[0])
    mode = Mode("quick", None, "quick", (8, 16), ())
    args = (mode, cases, False, NAMES, ("plain",), None, time.perf_counter(), False, ())
    got = side.Side(None, ended, args, side.sayer(time.perf_counter(), False)).result()
    here, _ = side.study_run(mode, cases, lambda m: None, False, {}, NAMES, ("plain",))
    assert _numbers(got.studies) == _numbers(here)
    assert "ended without an answer" in capsys.readouterr().out


def test_the_load_step_study_takes_the_closed_form_cycle_of_the_catalogue_run():
    """The side process solves the fretting case's closed-form cycle itself: it is the one the
    catalogue's run would hand the load-step study (run_case's reference result)."""
    (case,) = _cases("fretting_Q0.4")
    found = side.fretting_cycle(SMALL, _cases("caseA_moment", "fretting_Q0.4"))
    assert found is not None
    run = run_case(case, SMALL, {}, methods=(REFERENCE,))
    mine, theirs = found[1], run.results[REFERENCE]
    assert found[0] == run.case
    assert mine.energy == theirs.energy and mine.Q_max == theirs.Q_max
    assert np.array_equal(mine.Q, theirs.Q) and np.array_equal(mine.stick, theirs.stick)
    assert side.fretting_cycle(SMALL, _cases(*NAMES)) is None


def test_an_error_of_the_side_process_is_raised_here():
    """One SIE level is no study (run_study refuses it): the side process's InputError reaches the caller."""
    one = Mode("quick", None, "quick", (8,), ())
    with side.beside(one, _cases(NAMES[0]), False, NAMES, ("plain",), None, 0.0, True, 2) as aside:
        assert aside is not None
        with pytest.raises(InputError, match="at least two levels"):
            aside.result()


#: how long a worker's job waits for a file another job writes (a guard against a hang, not a timing)
WAIT_S = 60.0


def _wait_for(path):
    """The worker's job: wait for ``path`` (written by a job this process took) and return its pid."""
    import os
    from pathlib import Path

    t0 = time.monotonic()
    while not Path(path).exists() and time.monotonic() - t0 < WAIT_S:
        time.sleep(0.01)
    return os.getpid() if Path(path).exists() else None


def _write(path):
    import os
    from pathlib import Path

    Path(path).write_text("done")
    return os.getpid()


def test_the_drawing_process_takes_the_cheapest_job_no_worker_has_started(tmp_path):
    """Two processes: one forked worker and this one. The worker's first job waits for a file that
    only a later job writes; the worker has the next job queued already, so this process must take
    the last one, or the first never ends (it gives up after WAIT_S and returns None)."""
    import os
    from functools import partial

    from threepart.reports.verify.report import Job, run_jobs

    flag = tmp_path / "flag"
    jobs = [Job(("wait",), partial(_wait_for, flag), cost=10.0),
            Job(("queued",), os.getpid, cost=2.0),
            Job(("write",), partial(_write, flag), cost=1.0)]
    done = run_jobs(jobs, 2)
    assert done[("write",)] == os.getpid()
    assert done[("wait",)] not in (None, os.getpid())


def test_a_flight_cycle_judged_with_its_history_marched_apart_has_the_checks_of_its_own_run():
    """The verification run marches the flight cycle's history beside its cases and judges it
    when both are in: the checks, in their order, of run_case marching it itself."""
    from threepart.reports.verify.runs import judge_histories

    (case,) = [c for c in catalogue.load_cases() if c.kind == "steady"][:1]
    methods = (REFERENCE, "sie")
    own = run_case(case, SMALL, {}, methods=methods)
    later = run_case(case, SMALL, {}, methods=methods, histories=False)
    assert own.histories and not later.histories
    assert [c.comparison for c in later.checks] == [c.comparison for c in own.checks
                                                    if not c.comparison.endswith("-history")]
    judge_histories(later, own.histories)
    assert later.checks == own.checks and later.histories == own.histories and not later.errors
    judge_histories(later, {"sie": "NoConvergenceError: a march that raised"})
    assert later.errors == {"sie-history": "NoConvergenceError: a march that raised"}

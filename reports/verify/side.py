"""The verification run's studies, and the studies run beside the cases in a second process (issue 41).

The convergence studies, the outside codes' columns, the FE load-step study, the flight
cycles' marched histories and the fretting-wear section need nothing of the catalogue's runs
(the load-step study needs only the closed form's fretting cycle, which is computed again in a
moment; the histories are judged against the runs' steady states when both are in). On a machine with
more than one core they run in one more process, started when the run starts, while this one
solves the cases: the same functions on the same inputs, so the same numbers and the same
order of studies. The process is a new interpreter, not a fork: CHOLMOD's OpenMP hangs in a
child forked after its parent has factorised a matrix, and a new interpreter has used nothing
(nor does it run the caller's main script again, as multiprocessing's ``spawn`` would).
Its BLAS and OpenMP run on one thread; its progress lines go to the same terminal. A side
process that dies without an answer is said so, and its studies are run here after all.

Names
-----
study_run       -- the studies of a mode that need no run, in report order, and the friction columns
step_study      -- the FE fretting energy in the load step, on a fretting case's closed-form cycle
fretting_cycle  -- the first fretting case whose closed-form cycle solves, and that cycle
sayer           -- the run's one progress printer (seconds since ``t0``)
beside          -- the side process as a context manager (None where it does not run)
serve           -- the side process's own entry
Side            -- its handle: :meth:`Side.result` waits for the studies, :attr:`Side.wear` the wear record
Studies         -- what the side process hands back
"""
from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence

from threepart.problem.catalogue import Case
from threepart.progress import heartbeat
from threepart.registry import REFERENCE

from ..referee import CALCULIX_CASE, CALCULIX_K, CALCULIX_N, calculix_studies
from ..referee.friction_studies import friction_studies
from .runs import Mode, marched_histories, solve
from .studies import STEP_STATES, Study, fem_slip_study, fem_step_study, fem_study, sie_study

__all__ = ["study_run", "step_study", "fretting_cycle", "sayer", "beside", "serve", "Side", "Studies"]

Say = Callable[[str], None]


def sayer(t0: float, quiet: bool) -> Say:
    """The run's progress printer: each line after the seconds since ``t0`` (``time.perf_counter``,
    the same clock in every process of the machine); nothing when ``quiet``."""
    def say(msg: str) -> None:
        if not quiet:
            print(f"{time.perf_counter() - t0:7.1f}s  {msg}", flush=True)

    return say


def study_run(mode: Mode, cases: Sequence[Case], say: Say, calculix: bool, timings: dict[str, float],
              names: tuple[str, str], schemes: Sequence[str]) -> tuple[list[Study], list[Study]]:
    """The studies of ``mode`` that need no case's run, each timed into ``timings``, in report order;
    and the friction referees' columns among them.

    ``names`` are the case of the convergence studies (default: the first case) and the
    partial-slip case of the two-body FEM's; ``schemes`` the SIE schemes studied in n;
    ``calculix`` adds, past the quick mode, the outside codes' columns.
    """
    studies: list[Study] = []
    study_case = next((c for c in cases if c.name == names[0]), cases[0] if cases else None)
    if study_case is not None and mode.sie_study_n:
        t1 = time.perf_counter()
        for scheme in schemes:
            say(f"[study] SIE ({scheme}) convergence in n on {study_case.name}: n = {list(mode.sie_study_n)}")
            with heartbeat(say, lambda: f"[study]   SIE ({scheme})"):
                studies.append(sie_study(study_case, mode.sie_study_n, scheme=scheme,
                                         progress=lambda m: say(f"[study]   {m}")))
        timings["sie_study_s"] = time.perf_counter() - t1
    if study_case is not None and mode.fem_study_n:
        t1 = time.perf_counter()
        say(f"[study] FEM convergence in h on {study_case.name}: W/h = {list(mode.fem_study_n)}")
        with heartbeat(say, lambda: "[study]   FEM"):
            studies.append(fem_study(study_case, mode.fem_study_n, progress=lambda m: say(f"[study]   {m}")))
        timings["fem_study_s"] = time.perf_counter() - t1
    slip_case = next((c for c in cases if c.name == names[1]), None)
    if slip_case is not None and mode.fem_study_n:
        t1 = time.perf_counter()
        say(f"[study] two-body friction FEM convergence in h on {slip_case.name}: "
            f"W/h = {list(mode.fem_study_n)}")
        with heartbeat(say, lambda: "[study]   two-body friction FEM"):
            studies.append(fem_slip_study(slip_case, mode.fem_study_n, progress=lambda m: say(f"[study]   {m}")))
        timings["fem_slip_study_s"] = time.perf_counter() - t1
    friction: list[Study] = []
    if calculix and mode.name != "quick":
        t1 = time.perf_counter()
        say(f"[study] CalculiX convergence in h (W/h = {list(CALCULIX_N)}) and in the penalty "
            f"(K = {list(CALCULIX_K)} E/h) on {CALCULIX_CASE}, scaled to small slopes")
        with heartbeat(say, lambda: "[study]   CalculiX"):
            studies.extend(calculix_studies(say))
        timings["calculix_study_s"] = time.perf_counter() - t1
        t1 = time.perf_counter()
        say("[study] the friction referees (CalculiX, GetFEM): partial slip of two similar bodies "
            "(Hertz, slip_Q0.4), converging in h" + (", its bulk-stress case, the fretting and the "
                                                     "flight cycles" if mode.name == "full" else ""))
        with heartbeat(say, lambda: "[study]   friction referees"):
            friction = friction_studies(say, fretting=mode.name == "full")
        studies.extend(friction)
        timings["friction_referee_s"] = time.perf_counter() - t1
    return studies, friction


def step_study(case: Case, reference: Any, say: Say, timings: dict[str, float],
               states: Sequence[int] = STEP_STATES) -> Study:
    """The FE fretting energy in the load step on ``case`` (the quick mesh), against the closed
    form's cycle ``reference``; timed into ``timings``."""
    t1 = time.perf_counter()
    say(f"[study] FEM fretting energy in the load step on {case.name} (quick mesh): "
        f"states per branch = {list(states)}")
    with heartbeat(say, lambda: "[study]   FEM fretting cycle"):
        st = fem_step_study(case, reference, "quick", states, progress=lambda m: say(f"[study]   {m}"))
    timings["fem_step_study_s"] = time.perf_counter() - t1
    return st


def fretting_cycle(mode: Mode, cases: Sequence[Case]) -> tuple[Case, Any] | None:
    """The first fretting case whose closed-form cycle solves (resolved), and that cycle: what the
    load-step study takes from the catalogue's runs (:func:`reports.verify.runs.run_case`)."""
    for case in cases:
        if case.kind != "fretting":
            continue
        try:
            case = case.resolved()
            return case, solve(case, REFERENCE, mode)[0]
        except Exception:  # noqa: BLE001 - as run_case, which records it: no cycle of this case
            continue
    return None


@dataclass
class Studies:
    """What the side process hands back: the studies in report order, the friction columns among
    them, their timings, the wear section's record (None in the quick mode) and the flight
    cycles' marched histories by case and method (:func:`reports.verify.runs.marched_histories`)."""

    studies: list[Study]
    friction: list[Study]
    timings: dict[str, float]
    wear: dict[str, Any] | None = None
    histories: dict[str, dict[str, Any]] = field(default_factory=dict)


def _side(mode: Mode, cases: Sequence[Case], calculix: bool, names: tuple[str, str],
          schemes: Sequence[str], wear_root: Path | None, t0: float, quiet: bool,
          states: Sequence[int]) -> Studies:
    """The side process's work (see :func:`beside`)."""
    say = sayer(t0, quiet)
    timings: dict[str, float] = {}
    studies, friction = study_run(mode, cases, say, calculix, timings, names, schemes)
    cycle = fretting_cycle(mode, cases)
    if cycle is not None:
        studies.append(step_study(cycle[0], cycle[1], say, timings, states))
    histories: dict[str, dict[str, Any]] = {}
    for case in (c for c in cases if c.kind == "steady"):
        try:
            case = case.resolved()
        except Exception:  # noqa: BLE001 - the case's run records it, and has no reference to judge by
            continue
        tag = f"[history] {case.name}:"
        histories[case.name] = marched_histories(case, say=lambda m: say(f"{tag} {m}"))
    wear = None
    if wear_root is not None:
        from .wear_section import wear_study

        wear = wear_study(wear_root, say)
    return Studies(studies, friction, timings, wear, histories)


def serve() -> None:
    """The side process (``python -c``, see :func:`beside`): its arguments pickled on stdin, its
    answer or its error pickled to the descriptor named by ``sys.argv[1]``; one BLAS and OpenMP thread."""
    import pickle
    import sys

    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)
    args = pickle.load(sys.stdin.buffer)
    try:
        answer: tuple[str, Any] = ("ok", _side(*args))
    except BaseException as exc:  # noqa: BLE001 - raised again in the parent
        answer = ("error", exc)
    with open(int(sys.argv[1]), "wb") as out:
        try:
            data = pickle.dumps(answer)
        except Exception as exc:  # noqa: BLE001 - an error that does not pickle: its text
            data = pickle.dumps(("error", RuntimeError(f"{type(answer[1]).__name__}: {answer[1]}"
                                                       if answer[0] == "error" else f"unpicklable answer: {exc}")))
        out.write(data)


@dataclass
class Side:
    """The side process of one verification run (:func:`beside`): ``answer`` its pickled answer's
    stream, ``args`` its arguments (to run its work here if it ends without one)."""

    process: Any
    answer: Any
    args: tuple[Any, ...]
    say: Say
    wear: dict[str, Any] | None = None
    _done: Studies | None = field(default=None, repr=False)

    def result(self) -> Studies:
        """Wait for the side process's studies (run here if it ended without an answer)."""
        import pickle

        if self._done is None:
            try:
                kind, value = pickle.load(self.answer)
            except (EOFError, OSError, pickle.UnpicklingError):
                self.say("[study] the side process ended without an answer: its studies run here")
                kind, value = "ok", _side(*self.args)
            if kind == "error":
                raise value
            self._done = value
            self.wear = value.wear
        return self._done


@contextmanager
def beside(mode: Mode, cases: Sequence[Case], calculix: bool, names: tuple[str, str],
           schemes: Sequence[str], wear_root: Path | None, t0: float, quiet: bool,
           processes: int, states: Sequence[int] = STEP_STATES) -> Iterator[Side | None]:
    """The studies of :func:`study_run` and :func:`step_study`, and the wear section drawn into
    ``wear_root`` (None: not run), in a process started now (None for ``processes <= 1``).

    The process is a new interpreter (``python -c``, :func:`serve`): nothing of this one's
    state, no re-run of its main script; it is ended when the block ends, answered or not.
    """
    if processes <= 1:
        yield None
        return
    import os
    import pickle
    import subprocess
    import sys

    args = (mode, list(cases), calculix, names, tuple(schemes), wear_root, t0, quiet, tuple(states))
    theirs_r, theirs_w = os.pipe()
    # its own process group: a terminal's Ctrl-C reaches this process alone, which ends it below
    # (no second "interrupted" line, no traceback of its own)
    process = subprocess.Popen([sys.executable, "-c", "from threepart.reports.verify.side import serve; serve()",
                                str(theirs_w)], stdin=subprocess.PIPE, pass_fds=(theirs_w,), process_group=0)
    os.close(theirs_w)
    answer = os.fdopen(theirs_r, "rb")
    try:
        assert process.stdin is not None
        with process.stdin as stdin:
            stdin.write(pickle.dumps(args))
        yield Side(process, answer, args, sayer(t0, quiet))
    finally:
        if process.poll() is None:
            process.kill()
        process.wait()
        answer.close()

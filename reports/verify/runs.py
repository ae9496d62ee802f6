"""Runs of the catalogue's cases: every method on one case, timed and compared.

A :class:`~threepart.problem.catalogue.Case` of the one case catalogue
(:mod:`threepart.problem.catalogue`, ``threepart/problem/cases.json``) holds the inputs of one
case; :func:`run_case` solves it with each method of the registry
(:mod:`threepart.registry`) and compares the others with the reference. Like
scikit-fem's examples, a case exposes its numbers (a :class:`CaseRun` holds
every result, time and check) and nothing is plotted here: :mod:`reports.verify.plots`
draws only when a report is written.

Names
-----
Mode            -- the discretisation settings of one verification mode
MODES           -- ``quick``, ``default`` and ``full``
run_case        -- solve one case with every method and compare
marched_histories, judge_histories -- a flight cycle's marched histories, and their checks
CaseRun         -- every result, time, error and check of one case
solve           -- one case by one method: normal, partial slip or a fretting cycle, timed
solve_normal    -- the normal problem of one case by one method
METHODS         -- the methods compared, in report order
FRETTING_STATES -- recorded states per branch of a fretting cycle
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

from threepart import registry
from threepart.registry import REFERENCE
from threepart.problem.catalogue import Case
from threepart.tolerances import tolerance

from ..compare import Check, compare
from .flight import HISTORY_METHODS, history_checks, march
from .. import solvers
from ..solvers import METHODS
from threepart.errors import InputError

__all__ = ["CaseRun", "Mode", "MODES", "run_case", "solve", "solve_normal", "METHODS",
           "FRETTING_STATES", "marched_histories", "judge_histories"]

#: recorded states per branch of a fretting cycle (odd: Q = 0 is a state after each reversal)
FRETTING_STATES = 21


@dataclass(frozen=True)
class Mode:
    """Discretisation settings of one verification mode.

    ``sie_n`` (None: the solver's default) and ``fem_mesh`` (a preset name, or
    any mesh argument ``fem.solve_normal`` takes) are used for the catalogue;
    ``sie_study_n`` and ``fem_study_n`` (elements across the contact width of
    the default FE mesh's self-similar family) for the convergence studies
    (empty: skipped).
    """

    name: str
    sie_n: int | None
    fem_mesh: Any
    sie_study_n: tuple[int, ...]
    fem_study_n: tuple[int, ...]

    @property
    def settings(self) -> dict[str, Any]:
        """The settings by the option name a method's adapter takes them under (None: its default)."""
        return {"n": self.sie_n, "mesh": self.fem_mesh}

    def options(self, method: str) -> dict[str, Any]:
        """The keywords of ``method``'s adapter: those of its options (:attr:`Method.options
        <threepart.registry.Method.options>`) that this mode sets."""
        settings = self.settings
        return {k: settings[k] for k in registry.get(method).options
                if settings.get(k) is not None}


MODES: dict[str, Mode] = {
    "quick": Mode("quick", None, "quick", (8, 16, 32, 64, 128, 256), (38, 75, 150)),
    "default": Mode("default", None, "default", (8, 16, 32, 64, 128, 256, 512, 1024),
                    (38, 75, 150, 300)),
    "full": Mode("full", None, "fine", (8, 16, 32, 64, 128, 256, 512, 1024, 2048),
                 (38, 75, 150, 300, 600)),
}


def solve_normal(case: Case, method: str, mode: Mode) -> Any:
    """Solve the normal problem of ``case`` with ``method`` at ``mode``'s discretisation."""
    return solvers.normal(method, case, **mode.options(method))


def solve(case: Case, method: str, mode: Mode,
          cache: dict[Any, Any] | None = None) -> tuple[Any, float]:
    """Result of ``case`` by ``method`` and its wall time (s): normal, partial slip, a fretting cycle
    or the steady state of a flight cycle.

    ``cache`` maps ``(method, case.normal_key())`` to a normal result already
    computed, so that the partial-slip cases share their normal problem.
    """
    t0 = time.perf_counter()
    if case.kind == "steady":   # the cycle's own end states: no shared normal problem
        steady = solvers.steady(method, case, **mode.options(method))
        return steady, time.perf_counter() - t0
    key = (method, case.normal_key())
    if cache is not None and key in cache:
        normal, t_normal = cache[key]
    else:
        normal = solve_normal(case, method, mode)
        t_normal = time.perf_counter() - t0
        if cache is not None:
            cache[key] = (normal, t_normal)
    if case.kind == "normal":
        return normal, t_normal
    t1 = time.perf_counter()
    res: Any
    if case.kind == "fretting":
        res = solvers.fretting(method, case, normal, FRETTING_STATES, **mode.options(method))
    else:
        res = solvers.slip(method, case, normal, **mode.options(method))
    return res, t_normal + time.perf_counter() - t1


@dataclass
class CaseRun:
    """Everything one case produced: results, times, errors and checks, by method.

    ``refusals`` holds the messages of the closed form's expected refusals
    (a case past its framework); they are checked, not errors. ``histories``
    holds a flight cycle's marched histories by method (:mod:`reports.verify.flight`).
    """

    case: Case
    results: dict[str, Any] = field(default_factory=dict)
    times: dict[str, float] = field(default_factory=dict)
    errors: dict[str, str] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    refusals: dict[str, str] = field(default_factory=dict)
    histories: dict[str, Any] = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return not self.errors and bool(self.checks) and all(c.passed for c in self.checks)

    def failed(self) -> list[Check]:
        return [c for c in self.checks if not c.passed]


def refusal_check(case: Case, raised: BaseException | None) -> Check:
    """The check that the closed form refused ``case`` with the error the catalogue names.

    ``error`` is 0 for the named error class, 1 for an answer or another error.
    """
    expected = case.closedform_refuses
    right = raised is not None and type(raised).__name__ == expected
    got = "an answer" if raised is None else type(raised).__name__
    tol = tolerance("refusal", REFERENCE)
    return Check(comparison="refusal", quantity=REFERENCE, reference=1.0, obtained=float(right),
                 error=0.0 if right else 1.0, limit=tol.limit,
                 reason=f"{tol.reason}: expected {expected}, got {got}")


def run_case(case: Case, mode: Mode, cache: dict[Any, Any] | None = None,
             methods: tuple[str, ...] = METHODS,
             progress: Callable[[str], None] | None = None, histories: bool = True) -> CaseRun:
    """Solve ``case`` with each method and compare the others with its reference method.

    The reference is the closed form; past its framework (``case.beyond``)
    it is the SIE, and the closed form must refuse with the error the case
    names. A solver that raises otherwise is recorded in ``errors`` (and
    fails the case) rather than aborting the run. ``histories=False`` leaves a
    flight cycle's marched histories to the caller (:func:`marched_histories`,
    :func:`judge_histories`: the verification run marches them beside its cases).
    """
    say = progress or (lambda msg: None)
    run = CaseRun(case)
    try:
        case = case.resolved()
        run.case = case
    except Exception as exc:  # noqa: BLE001 - recorded in the report
        run.errors[REFERENCE] = f"lift-off range: {type(exc).__name__}: {exc}"
        return run
    if case.kind == "steady":   # only the methods with a steady state (Method.steady) take part
        methods = tuple(m for m in methods if registry.get(m).steady is not None)
    for method in methods:
        reused = cache is not None and (method, case.normal_key()) in cache
        try:
            res, dt = solve(case, method, mode, cache)
        except Exception as exc:  # noqa: BLE001 - recorded in the report
            if case.beyond and registry.get(method).framework_only:
                run.checks.append(refusal_check(case, exc))
                run.refusals[method] = f"{type(exc).__name__}: {exc}"
                say(f"{method} refuses ({type(exc).__name__})")
                continue
            run.errors[method] = f"{type(exc).__name__}: {exc}"
            say(f"{method} FAILED ({type(exc).__name__}: {exc})")
            continue
        if case.beyond and registry.get(method).framework_only:
            run.checks.append(refusal_check(case, None))   # it answered: a failed check
        run.results[method] = res
        run.times[method] = dt
        say(f"{method} {_fmt_time(dt)}" + (" (normal problem shared with an earlier case)" if reused else ""))
    ref = run.results.get(case.reference)
    if ref is None:
        return run
    for method in methods:
        if method in (case.reference, REFERENCE) or method not in run.results:
            continue
        judged_by = registry.get(method).comparison
        try:
            if judged_by is None:
                raise InputError(f"method {method!r} names no tolerance group (Method.comparison)")
            run.checks.extend(compare(ref, run.results[method], judged_by(mode.options(method))))
        except Exception as exc:  # noqa: BLE001
            run.errors[f"compare-{method}"] = f"{type(exc).__name__}: {exc}"
    if case.kind == "steady" and histories:
        judge_histories(run, marched_histories(run.case, methods, say), say)
    return run


def marched_histories(case: Case, methods: tuple[str, ...] = METHODS,
                      say: Callable[[str], None] | None = None) -> dict[str, Any]:
    """A flight cycle's marched histories (:data:`reports.verify.flight.HISTORY_METHODS` among
    ``methods``) by method; a march that raised: its message. ``case`` is resolved."""
    say = say or (lambda msg: None)
    out: dict[str, Any] = {}
    for method in (m for m in HISTORY_METHODS if m in methods and registry.get(m).steady is not None):
        t0 = time.perf_counter()
        try:
            out[method] = hist = march(method, case)
        except Exception as exc:  # noqa: BLE001 - recorded in the report
            out[method] = f"{type(exc).__name__}: {exc}"
            say(f"{method} history FAILED ({out[method]})")
            continue
        say(f"{method} history, {len(hist.cycles)} cycles marched, {_fmt_time(time.perf_counter() - t0)}")
    return out


def judge_histories(run: CaseRun, marched: dict[str, Any], say: Callable[[str], None] | None = None) -> None:
    """``marched`` (:func:`marched_histories`) judged against the reference's steady state of ``run``:
    the checks, the histories and the errors of ``run``; nothing without its reference."""
    ref = run.results.get(run.case.reference)
    if ref is None:
        return
    for method, hist in marched.items():
        try:
            if isinstance(hist, str):
                run.errors[f"{method}-history"] = hist
                continue
            run.checks.extend(history_checks(ref, hist, method))
        except Exception as exc:  # noqa: BLE001 - recorded in the report
            run.errors[f"{method}-history"] = f"{type(exc).__name__}: {exc}"
            if say:
                say(f"{method} history FAILED ({type(exc).__name__}: {exc})")
            continue
        run.histories[method] = hist


def _fmt_time(dt: float) -> str:
    return f"{dt * 1e3:.1f} ms" if dt < 1 else f"{dt:.2f} s"

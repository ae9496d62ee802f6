"""``threepart verify``: run the catalogue through all three solvers and write the report.

The report directory holds ``report.md``, a self-contained ``report.html`` (the
PNGs embedded as data URIs), ``report.json`` (valid against
``reports/verify/report.schema.json``) and ``plots/*.png``. It is written into a
temporary sibling directory and renamed into place only when complete, so a
report is never half-written; an existing directory is replaced only if it is
threepart's own unchanged earlier output (see :mod:`threepart.output`). The
exit status is 0 when every tolerance holds, 1 otherwise.
"""
from __future__ import annotations

import datetime as _dt
import json
import platform
import subprocess
import sys
import time
from dataclasses import dataclass, fields
from functools import partial
from importlib import metadata
from pathlib import Path
from typing import Any, Callable, Sequence

from threepart.problem.catalogue import Case, load_cases
from threepart.fatigue.table import reported
from threepart.registry import REFERENCE
from threepart.progress import heartbeat
from threepart.output import atomic_dir, json_safe, strict_json, validate_json

from . import render, side
from .runs import FRETTING_STATES, MODES, CaseRun, Mode, judge_histories, run_case
from ..referee.friction_studies import FRICTION_METHOD
from .friction import FRICTION_PLOT, friction_record, friction_runs
from ..compare import is_steady, normal_of
from .sections import MAP_JSON, plot_path, study_plot_path
from .edges import ASYMPTOTE_PLOT, asymptote_study, draw_asymptote
from .speed import speed_record
from .wear_section import wear_study
from .stress import StressFields, case_hot_spots, fatigue_hot_spots, joined_fatigue, stress_fields, stress_nu
from ..solvers import METHODS
from .studies import Study
from threepart.errors import InputError
from threepart.tolerances import tolerance

__all__ = ["main", "run", "build_report", "write_report", "stress_record",
           "SCHEMA_FILE", "load_schema", "validate", "STUDY_CASE", "SLIP_STUDY_CASE",
           "SCHEMA_VERSION"]

SCHEMA_FILE = Path(__file__).with_name("report.schema.json")
SCHEMA_VERSION = "1.0"
#: the catalogue case on which the convergence studies are run
STUDY_CASE = "caseA_moment"
#: the partial-slip case of the two-body friction FEM's convergence study
SLIP_STUDY_CASE = "slip_Q0.4"
#: SIE schemes whose convergence in n is studied: plain collocation and the kink-aware projection
SIE_SCHEMES = ("plain", "projected")
#: how many of the tightest checks (error/limit, worst first) the report lists on top
TIGHTEST = 10
PACKAGES = ("threepart", "numpy", "scipy", "matplotlib", "scikit-fem", "gmsh", "meshio",
            "threadpoolctl", "numba")


def _versions() -> dict[str, str | None]:
    out: dict[str, str | None] = {}
    for name in PACKAGES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    return out


def _git() -> dict[str, Any]:
    root = Path(__file__).resolve().parents[1]
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=root, capture_output=True,
                                text=True, timeout=10, check=True).stdout.strip()
        dirty = bool(subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root,
                                    capture_output=True, text=True, timeout=10).stdout.strip())
        return {"commit": commit, "dirty": dirty}
    except (OSError, subprocess.SubprocessError):
        return {"commit": None, "dirty": None}


def _metadata(normal: Any) -> dict[str, Any]:
    """The scalar discretisation metadata of a result: its typed diagnostics, then its ``info``."""
    dg = getattr(normal, "diagnostics", None)
    typed = {} if dg is None else {f.name: getattr(dg, f.name) for f in fields(dg)}
    return {k: v for k, v in {**typed, **dict(normal.info)}.items()
            if isinstance(v, (int, float, str, bool))}


def _result_dict(res: Any, dt: float) -> dict[str, Any]:
    normal = normal_of(res)
    left, right = normal.peaks()
    d: dict[str, Any] = {"a": normal.a, "c": normal.c, "alpha": normal.alpha, "P": normal.P,
                         "s": normal.s, "tilt": normal.tilt,
                         "peak_left": {"x": left.x, "p": left.p},
                         "peak_right": {"x": right.x, "p": right.p},
                         "time_s": dt, "info": _metadata(normal)}
    if is_steady(res):   # a flight cycle: its permanent stick zone, the wider end state's contact
        d.update({"f": res.f, "energy": res.energy, "d": res.d, "e": res.e, "shakedown": res.shakedown})
    elif hasattr(res, "energy"):   # a fretting cycle: its stick zone at Q_max
        left, right = res.stick[(res.branch == "loading")][-1]
        d.update({"Q_max": res.Q_max, "f": res.f, "energy": res.energy,
                  "d": 0.5 * (right - left), "e": -0.5 * (right + left)})
    elif res is not normal:
        d.update({"Q": res.Q, "f": res.f, "d": res.d, "e": res.e})
    return d


def run(mode: Mode, cases: Sequence[Case], say: Callable[[str], None],
        calculix: bool = False, robustness: bool = False,
        aside: side.Side | None = None) -> tuple[list[CaseRun], list[Study], dict[str, float]]:
    """Solve and compare every case, then the convergence studies; return the numbers.

    ``calculix`` adds the CalculiX column (:func:`reports.referee.calculix_studies`),
    except in the quick mode; ``robustness`` adds, in the full mode only, the
    robustness study (:func:`reports.verify.robustness.study`) as one more run of checks.
    ``aside``: the studies run beside the cases (:func:`reports.verify.side.beside`), read
    when the cases are done; None: run here after them.
    """
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    runs = _run_cases(mode, cases, say, histories=aside is None)
    timings["cases_s"] = time.perf_counter() - t0
    if robustness and mode.name == "full":
        _robustness(runs, timings, say)
    if aside is None:
        studies = _studies(mode, cases, runs, say, calculix, timings)
    else:
        done = aside.result()
        for r in runs:   # the flight cycles' histories, marched beside the cases
            if r.case.name in done.histories:
                judge_histories(r, done.histories[r.case.name], say)
        studies = done.studies
        runs.extend(friction_runs(done.friction))   # each column's verdict, as _studies adds it
        timings.update(done.timings)
    return runs, studies, timings


def _run_cases(mode: Mode, cases: Sequence[Case], say: Callable[[str], None],
               histories: bool = True) -> list[CaseRun]:
    """Solve and compare every case, one progress line each (and a heartbeat while it runs);
    ``histories=False``: a flight cycle's marched histories are judged later (:func:`run`)."""
    runs: list[CaseRun] = []
    cache: dict[Any, Any] = {}
    for i, case in enumerate(cases, 1):
        tag = f"[{i:>2}/{len(cases)}] {case.name:<14}"
        note = (f" (a fretting cycle: 3 branches of {FRETTING_STATES} load states by each method)"
                if case.kind == "fretting" else "")
        say(f"{tag} solving ...{note}")
        tc = time.perf_counter()
        pending = list(METHODS)   # the methods not yet reported: the first one is running

        def progress(m: str, tag: str = tag, pending: list[str] = pending) -> None:
            if m.split(" ", 1)[0] in pending:
                pending.remove(m.split(" ", 1)[0])
            say(f"{tag}   {m}")

        def running(tag: str = tag, pending: list[str] = pending) -> str:
            return f"{tag}   {pending[0] if pending else 'comparison'}"

        with heartbeat(say, running):
            r = run_case(case, mode, cache, progress=progress, histories=histories)
        failed = r.failed()
        verdict = "PASS" if r.passed else (
            "FAIL " + ", ".join(f"{c.comparison}:{c.quantity}" for c in failed) if failed else "ERROR")
        later = "; its marched history judged with the studies" if case.kind == "steady" and not histories else ""
        say(f"{tag} {verdict}  ({time.perf_counter() - tc:.2f} s{later})")
        runs.append(r)
    return runs


def _studies(mode: Mode, cases: Sequence[Case], runs: list[CaseRun], say: Callable[[str], None],
             calculix: bool, timings: dict[str, float]) -> list[Study]:
    """The convergence studies of the mode, each timed into ``timings``; the friction columns'
    verdicts join ``runs`` (:func:`reports.verify.side.study_run`, :func:`~reports.verify.side.step_study`)."""
    studies, friction = side.study_run(mode, cases, say, calculix, timings, (STUDY_CASE, SLIP_STUDY_CASE),
                                       SIE_SCHEMES)
    runs.extend(friction_runs(friction))   # each column's verdict: checks counted in the total
    cycle = next((r for r in runs if r.case.kind == "fretting" and REFERENCE in r.results), None)
    if cycle is not None:
        studies.append(side.step_study(cycle.case, cycle.results[REFERENCE], say, timings))
    return studies


def _robustness(runs: list[CaseRun], timings: dict[str, float], say: Callable[[str], None]) -> None:
    """The robustness study (:mod:`reports.verify.robustness`) as one more run of checks, timed."""
    from . import robustness

    t1 = time.perf_counter()
    drawn = ", ".join(f"{n} {g}" for g, n in robustness.COUNTS.items())
    say(f"[study] robustness: a seeded wide draw ({drawn}), the closed form against the SIE")
    with heartbeat(say, lambda: "[study]   robustness"):
        r = robustness.study(say=lambda m: say(f"[study]   {m}"))
    failed = r.failed()
    say("[study] robustness " + ("PASS" if r.passed else "FAIL " + ", ".join(c.quantity for c in failed)))
    runs.append(r)
    timings["robustness_study_s"] = time.perf_counter() - t1


def build_report(mode: Mode, runs: Sequence[CaseRun], studies: Sequence[Study],
                 timings: dict[str, float], plots: dict[str, list[str]],
                 stress: dict[str, dict[str, Any]] | None = None,
                 fatigue: dict[str, dict[str, Any]] | None = None) -> dict[str, Any]:
    """The ``report.json`` document (see ``reports/verify/report.schema.json``).

    ``stress`` maps a partial-slip case to its stress record (Poisson's ratio,
    bulk stress, hot spots by method; :func:`stress_record`), ``fatigue`` a
    fretting case to its fatigue parameters' hot spots by method
    (:func:`reports.verify.stress.fatigue_hot_spots`).
    """
    stress = stress or {}
    fatigue = fatigue or {}
    from threepart.tolerances import ERROR_UNITS, TOLERANCES
    from .edges import edge_rows

    checks = [c for r in runs for c in r.checks]
    failed = [f"{r.case.name}/{c.comparison}/{c.quantity}" for r in runs for c in r.failed()]
    errors = [f"{r.case.name}/{m}: {e}" for r in runs for m, e in r.errors.items()]
    comparisons = sorted({c.comparison for c in checks})
    by_comparison = {cmp: {"checks": sum(c.comparison == cmp for c in checks),
                           "failed": sum(c.comparison == cmp and not c.passed for c in checks)}
                     for cmp in comparisons}
    ranked = sorted(((c.error / c.limit if c.limit > 0 else 0.0, r.case.name, c)
                     for r in runs for c in r.checks), key=lambda t: -t[0])
    tightest = [{"case": name, "comparison": c.comparison, "quantity": c.quantity,
                 "error": c.error, "limit": c.limit, "ratio": ratio,
                 "unit": ERROR_UNITS[c.quantity]} for ratio, name, c in ranked[:TIGHTEST]]
    cases = []
    for r in runs:
        worst = max((c.error / c.limit for c in r.checks if c.limit > 0), default=None)
        extra = {**({"stress": stress[r.case.name]} if r.case.name in stress else {}),
                 **({"fatigue": fatigue[r.case.name]} if r.case.name in fatigue else {})}
        cases.append({
            **r.case.as_dict(),
            "passed": r.passed,
            "results": {m: _result_dict(res, r.times[m]) for m, res in r.results.items()},
            "errors": dict(r.errors),
            "reference": r.case.reference,
            "worst_ratio": worst,
            "refusals": dict(r.refusals),
            "checks": [c.as_dict() for c in r.checks],
            "plots": plots.get(r.case.name, []),
            **extra,
        })
    doc = {
        "schema_version": SCHEMA_VERSION,
        "tool": "threepart verify",
        "mode": mode.name,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "passed": bool(runs) and not failed and not errors,
        "summary": {"cases": len(runs), "checks": len(checks), "failed_checks": len(failed),
                    "errors": len(errors), "failed": failed, "error_messages": errors,
                    "by_comparison": by_comparison, "tightest": tightest},
        "settings": {"sie_n": mode.sie_n, "fem_mesh": str(mode.fem_mesh),
                     "sie_study_n": list(mode.sie_study_n),
                     "fem_study_n": list(mode.fem_study_n), "study_case": STUDY_CASE},
        "environment": {"python": sys.version.split()[0], "platform": platform.platform(),
                        "packages": _versions(), "git": _git()},
        "timings": dict(timings),
        "tolerances": [{"comparison": k[0], "quantity": k[1], "limit": t.limit, "reason": t.reason}
                       for k, t in TOLERANCES.items()],
        "cases": cases,
        "studies": [s.as_dict() for s in studies],
        "plots": plots.get("_studies", []),
        "edges": edge_rows(runs),   # the edge multipliers by method (reports/verify/edges.py)
    }
    return json_safe(doc)


def stress_record(run: CaseRun, fields: dict[str, StressFields] | None = None) -> dict[str, Any]:
    """The stress record of a partial-slip case: ν, the bulk stress and each method's hot spots.

    ``fields``: each method's stresses, if computed already (:func:`reports.verify.stress.stress_fields`).
    """
    ref = run.results[run.case.reference]
    nu = stress_nu(run.case.material)
    return {"nu": nu, "sigma_bulk": float(getattr(ref, "sigma_bulk", 0.0)),
            "hot_spots": case_hot_spots(run.results, nu, run.case.reference, fields)}


def load_schema() -> dict[str, Any]:
    """The JSON schema of ``report.json``, the fatigue parameters' names from their table."""
    schema: dict[str, Any] = json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))
    schema["$defs"]["fatigue_parameter"]["enum"] = list(reported())
    return schema


def validate(doc: dict[str, Any]) -> None:
    """Validate ``doc`` against the schema (needs ``jsonschema``; skipped without it)."""
    validate_json(doc, load_schema())


#: a job of the report's drawing is named by a tuple: ("plot", case, kind), ("fields", case,
#: method), ("fatigue", case, method), ("study", path), ("friction",), ("asymptote",)
Key = tuple[str, ...]


@dataclass(frozen=True)
class Job:
    """One piece of the report's drawing: a plot written, or the numbers of a case's hot spots.

    ``run()`` does it (``run(given=...)`` if it ``needs`` other jobs' values: ``given`` maps
    their keys to them) and returns a picklable value; ``cost`` (seconds, roughly) puts the dearest
    jobs first, so that the workers finish together. ``here``: run in this process, never in a
    forked worker: a result's stresses may call its solver again (the FE stress recovery
    factorises the block by CHOLMOD, whose GNU OpenMP hangs in a child forked after the run used it).
    """

    key: Key
    run: Callable[..., Any]
    cost: float = 1.0
    needs: tuple[Key, ...] = ()
    here: bool = False


#: the jobs of the running :func:`run_jobs`, read by its forked workers by index
_JOBS: list[Job] = []
#: the most processes :func:`run_jobs` forks (each holds a copy-on-write image of the run)
MAX_WORKERS = 4


def workers() -> int:
    """The processes that draw the report: the CPUs this process may use (at most
    :data:`MAX_WORKERS`) on Linux, else 1 (macOS's system libraries are not safe to fork)."""
    import os

    if not sys.platform.startswith("linux"):
        return 1
    return max(1, min(len(os.sched_getaffinity(0)), MAX_WORKERS))


def _one_thread() -> None:
    """A worker's BLAS on one thread: the workers share the cores."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)


def _work(i: int, given: dict[Key, Any] | None) -> Any:
    job = _JOBS[i]
    return job.run(given=given) if job.needs else job.run()


def run_jobs(jobs: Sequence[Job], processes: int) -> dict[Key, Any]:
    """Every job's value by its key: in this process and ``processes - 1`` forked workers (dearest
    job first, a job as soon as the jobs it needs are done), or one after another here for
    ``processes <= 1``.

    The workers inherit the run (its results are never pickled); a job's value comes back
    pickled. The jobs marked ``here`` run in this process meanwhile (a job that needs others
    must not be one); then this process takes the cheapest jobs no worker has started, so that
    it is one of the ``processes`` and no core is asked to run two. A job that raises raises
    here, and the jobs not yet started are dropped.
    """
    from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
    from multiprocessing import get_context

    done: dict[Key, Any] = {}
    if processes <= 1 or len(jobs) <= 1:
        for job in sorted(jobs, key=lambda j: len(j.needs)):   # stable: inputs before their users
            done[job.key] = job.run(given={k: done[k] for k in job.needs}) if job.needs else job.run()
        return done
    _JOBS[:] = jobs
    waiting = [i for i, j in enumerate(jobs) if j.needs]
    needed = {k for i in waiting for k in jobs[i].needs}     # those first: their users go to the workers
    here = sorted((i for i, j in enumerate(jobs) if j.here and not j.needs),
                  key=lambda i: (jobs[i].key not in needed, -jobs[i].cost))
    pool = ProcessPoolExecutor(max(1, min(processes - 1, len(jobs) - len(here))),
                               mp_context=get_context("fork"), initializer=_one_thread)
    given: dict[int, dict[Key, Any] | None] = {}
    pending: dict[Future[Any], int] = {}

    def submit(i: int, inputs: dict[Key, Any] | None) -> None:
        given[i] = inputs
        pending[pool.submit(_work, i, inputs)] = i

    try:
        for i in sorted(set(range(len(jobs))) - set(waiting) - set(here), key=lambda i: -jobs[i].cost):
            submit(i, None)
        while pending or here:
            if here:
                i = here.pop(0)
                done[jobs[i].key] = jobs[i].run()
            elif (stolen := _steal(pending, jobs)) is not None:   # a job no worker has started
                done[jobs[stolen].key] = _work(stolen, given[stolen])
            else:
                wait(pending, return_when=FIRST_COMPLETED)
            for future in [f for f in pending if f.done()]:
                done[jobs[pending.pop(future)].key] = future.result()
            for i in [i for i in waiting if all(k in done for k in jobs[i].needs)]:
                waiting.remove(i)
                submit(i, {k: done[k] for k in jobs[i].needs})
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
        _JOBS.clear()
    return done


def _steal(pending: dict[Any, int], jobs: Sequence[Job]) -> int | None:
    """The cheapest (latest submitted) pending job that no worker has started, taken from the
    pool (its future cancelled and dropped from ``pending``), or None."""
    for future in sorted(pending, key=lambda f: (jobs[pending[f]].cost, -pending[f])):
        if future.cancel():
            return pending.pop(future)
    return None


def _case_jobs(tmp: Path, r: CaseRun) -> list[Job]:
    """A case's jobs: its plots, and for partial slip its stress fields, for a cycle its fatigue."""
    from . import plots

    name, ref, res = r.case.name, r.case.reference, r.results
    kw: dict[str, Any] = {"reference": ref, "physical": r.case.material is not None}

    def plot(kind: str, draw: Callable[..., Any], cost: float = 1.0, **more: Any) -> Job:
        return Job(("plot", name, kind), partial(draw, res, name, tmp / plot_path(name, kind), **kw, **more),
                   cost)

    if r.case.kind in ("steady", "fretting"):
        fatigue = [Job(("fatigue", name, m), partial(fatigue_hot_spots, res, r.case.material, ref, [m]), 10.0,
                       here=True) for m in res]
        drawn = (plot("steady", plots.steady, 2.0, histories=r.histories) if r.case.kind == "steady"
                 else plot("cycle", plots.fretting, 2.0))
        return [drawn, *fatigue]
    jobs = [plot("overlay", plots.overlay)]
    if len(res) > 1:
        jobs.append(plot("errors", plots.error_curves))
    if r.case.kind == "slip":
        nu = stress_nu(r.case.material)
        fields = tuple(("fields", name, m) for m in res)
        jobs += [Job(k, partial(stress_fields, res[k[2]], nu, res[ref]), 3.0, here=True) for k in fields]
        for kind, draw in (("stress", plots.stress_surface), ("von_mises", plots.von_mises)):
            jobs.append(Job(("plot", name, kind), partial(_draw_with_fields, draw, res, name,
                                                          tmp / plot_path(name, kind), nu=nu, **kw),
                            needs=fields))
    return jobs


def _draw_with_fields(draw: Callable[..., Any], *args: Any, given: dict[Key, Any] | None = None,
                      **kw: Any) -> Any:
    """``draw`` given the case's :class:`StressFields` by method (the ``("fields", case, method)`` jobs)."""
    return draw(*args, fields={k[2]: v for k, v in (given or {}).items()}, **kw)


def _draw_jobs(tmp: Path, todo: Sequence[CaseRun], studies: Sequence[Study]) -> list[Job]:
    """Every job of the report's drawing: the cases', the studies' plots, the friction referees'
    and the edge asymptote's study and plot."""
    from . import plots

    jobs = [j for r in todo for j in _case_jobs(tmp, r)]
    for st in studies:
        if not st.values or st.method == "calculix" or st.method.endswith(FRICTION_METHOD):   # referees: tables only
            continue
        name = study_plot_path(st.method, st.scheme, st.case)
        draw = {"n": plots.sie_convergence, "h": plots.fem_convergence, "dQ": plots.step_convergence}[st.param]
        jobs.append(Job(("study", name), partial(draw, st, tmp / name)))
    friction = friction_record(studies)     # issue 38: the friction referee columns
    if friction and any(c["rows"] for c in friction["columns"]):
        jobs.append(Job(("friction",), partial(plots.friction_stick, friction["columns"],
                                               tolerance("referee", "stick_ends").limit, tmp / FRICTION_PLOT)))
    jobs.append(Job(("asymptote",), partial(_asymptote, tmp / ASYMPTOTE_PLOT), 2.0))
    return jobs


def _asymptote(path: Path) -> dict[str, Any]:
    """Issue 32's study of the asymptotic slip zone as Q/fP -> 0, drawn to ``path``."""
    study = asymptote_study()
    draw_asymptote(study, path)
    return study


def write_report(tmp: Path, mode: Mode, runs: Sequence[CaseRun], studies: Sequence[Study],
                 timings: dict[str, float], say: Callable[[str], None],
                 wear: dict[str, Any] | None = None) -> dict[str, Any]:
    """Draw the plots and write md, html and json into the directory ``tmp``.

    The plots and the hot spots are drawn and computed by :func:`run_jobs` in
    :func:`workers` processes. The validity map is linked only when ``threepart map``
    has written one beside the report (``tmp`` is a sibling of the report directory).
    ``wear``: the wear section's record if drawn into ``tmp`` already (the side process's),
    else it is run here, except in the quick mode.
    """
    t0 = time.perf_counter()
    todo = [r for r in runs if r.case.reference in r.results]
    jobs = _draw_jobs(tmp, todo, studies)
    n = min(workers(), len(jobs))
    say(f"[report] drawing the plots of {len(todo)} cases and {len(studies)} studies "
        f"({len(jobs)} jobs, {n} process{'es' if n > 1 else ''}) ...")
    with heartbeat(say, lambda: "[report] drawing the plots"):
        done = run_jobs(jobs, n)
    drawn: dict[str, list[str]] = {}
    stressed: dict[str, dict[str, Any]] = {}
    tired: dict[str, dict[str, Any]] = {}
    for r in todo:
        name = r.case.name
        drawn[name] = [plot_path(name, k[2]) for k in (j.key for j in jobs) if k[:2] == ("plot", name)]
        if r.case.kind == "slip":
            stressed[name] = stress_record(r, {m: done[("fields", name, m)] for m in r.results})
        if r.case.kind in ("steady", "fretting"):
            tired[name] = joined_fatigue([done[("fatigue", name, m)] for m in r.results])
    drawn["_studies"] = [j.key[1] for j in jobs if j.key[0] == "study"]
    friction = friction_record(studies)
    if friction and ("friction",) in done:
        friction["plot"] = FRICTION_PLOT
    edge_study = done[("asymptote",)]
    timings = dict(timings, plots_s=time.perf_counter() - t0)
    timings["total_s"] = timings.get("solve_s", 0.0) + timings["plots_s"]
    doc = build_report(mode, runs, studies, timings, drawn, stressed, tired)
    doc["edge_asymptote"] = json_safe({**edge_study, "plot": ASYMPTOTE_PLOT})
    if friction:
        doc["friction_referees"] = json_safe(friction)
    if mode.name != "quick":   # issue 33: the speed ratios, measured in the run (reports/verify/speed.py)
        doc["speed"] = json_safe(speed_record(mode.name != "full", say))   # --full at the full sizes
        doc["wear"] = json_safe(wear_study(tmp, say) if wear is None else wear)   # issue 39 (wear_section.py)
    validate(doc)
    map_link = MAP_JSON if (tmp / MAP_JSON).is_file() else None
    (tmp / "report.json").write_text(strict_json(doc, indent=1), encoding="utf-8")
    (tmp / "report.md").write_text(render.markdown(doc, map_link), encoding="utf-8")
    (tmp / "report.html").write_text(render.html(doc, tmp, map_link), encoding="utf-8")
    say(f"report written ({time.perf_counter() - t0:.1f} s for plots and files)")
    return doc


def main(mode: str = "default", out: str | Path = "report", force: bool = False,
         cases: Sequence[Case] | None = None, quiet: bool = False) -> int:
    """Run the verification and write the report to ``out``; return the exit status.

    Parameters
    ----------
    mode
        ``"quick"`` (quick FEM mesh, short studies), ``"default"`` or ``"full"``
        (adds the slow study levels).
    out
        Report directory: missing or empty, or a report that threepart wrote
        earlier and that is unchanged, which is replaced (see
        :func:`threepart.output.atomic_dir`).
    force
        Kept for compatibility; it changes nothing (a directory holding
        anything threepart did not write, or edited, is never replaced).
    cases
        Cases to run (default: the whole catalogue, and then, except in the quick
        mode, the CalculiX column: :func:`reports.referee.calculix_studies`, which
        says so when ``ccx`` is not on the PATH).
    quiet
        Print no progress.

    Returns
    -------
    int
        0 when every check passed, 1 when a tolerance failed or a solver raised.

    Raises
    ------
    threepart.output.OutputExistsError
        If ``out`` may not be written; checked before any work.
    """
    if mode not in MODES:
        raise InputError(f"`mode` = {mode!r} must be one of {sorted(MODES)}")
    out = Path(out)
    t0 = time.perf_counter()
    say = side.sayer(t0, quiet)
    with atomic_dir(out, force, command="verify") as tmp:
        m = MODES[mode]
        whole = cases is None          # the CalculiX column goes with the whole catalogue
        cases = list(load_cases() if cases is None else cases)
        say(f"threepart verify --{mode}: {len(cases)} cases, FEM mesh {m.fem_mesh!r}, report -> {out}")
        # the whole catalogue's studies beside its cases (given cases, as a test's fakes, stay here)
        with side.beside(m, cases, whole, (STUDY_CASE, SLIP_STUDY_CASE), SIE_SCHEMES,
                         tmp if m.name != "quick" else None, t0, quiet,
                         workers() if whole else 1) as aside:
            runs, studies, timings = run(m, cases, say, calculix=whole, robustness=whole, aside=aside)
        timings["solve_s"] = time.perf_counter() - t0
        wear = {} if aside is None else {"wear": aside.wear}   # drawn beside the cases already
        doc = write_report(tmp, m, runs, studies, timings, say, **wear)
    s = doc["summary"]
    verdict = "PASSED" if doc["passed"] else "FAILED"
    say(f"{verdict}: {s['checks'] - s['failed_checks']}/{s['checks']} checks within tolerance, "
        f"{s['errors']} solver errors, {time.perf_counter() - t0:.1f} s -> {out / 'report.html'}")
    for f in s["failed"]:
        say(f"  failed: {f}")
    for e in s["error_messages"]:
        say(f"  error: {e}")
    return 0 if doc["passed"] else 1

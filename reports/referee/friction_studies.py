"""The friction referee columns of the verification run: CalculiX and GetFEM against the closed form.

Each outside code that carries Coulomb friction is one row of :data:`REFEREES`
(its name, whether it is installed, its partial-slip, fretting and load-history runs,
how to install it, its levels and the tolerance rows where its documented figures
miss issue 38's targets); a new code is one row. Every column solves the problems of
:data:`~.friction_problems.FRICTION_PROBLEMS` (two similar elastic bodies scaled to
small slopes as the CalculiX normal column, :data:`~.studies.SLOPE_SCALE`) that its
mode runs:

- a partial slip (Hertz against Mindlin's ``c/a = sqrt(1 - Q/fP)``, ``slip_Q0.4``, its
  bulk-stress case) at each code's levels of elements across the contact width W
  (:attr:`Referee.levels`): the stick zone's half-width and centre (of W), the shear
  away from the ends, ``∫q = Q`` (:func:`slip_from_points`, judged by the
  verification run's own comparison);
- a fretting cycle (``fretting_Q0.4``) at the finest level: its energy per cycle against
  the closed form's (Masing) and its stick zone at ``Q_max``;
- the flight cycle at the finest level: its energy per cycle against the steady state's.

A column that is not run is a study without levels whose ``scheme`` says why
(:data:`NOT_RUN`): the code is not installed, it lacks what the problem needs
("not yet"), or the problem runs in ``--full`` only. :func:`.verdict.column_verdict`
judges the finest level of a column that ran.

Names
-----
Referee          -- one outside code: its runs and how to tell it is there
REFEREES         -- the table of outside codes with friction, by name
register_referee -- add one
referee          -- one row of it, by name
supports         -- whether a code has what a problem needs
friction_problem -- the scaled Hertz pair of the columns, with its closed-form references
friction_studies -- every column the mode runs: a Study in h each (or one that says why not)
run_level        -- one level of a column: a code's run of a problem and its errors
FRICTION_QUANTITIES, FRICTION_RATIO, FRICTION_F, FRICTION_METHOD, RUN_SCHEME, NOT_RUN -- settings
"""
from __future__ import annotations

import inspect
import math
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from threepart.errors import InputError, ThreepartError

from .friction import slip_from_points
from .friction_problems import FRICTION_F, FRICTION_PROBLEMS, FRICTION_RATIO, FrictionProblem, hertz

__all__ = ["Referee", "REFEREES", "register_referee", "referee", "supports", "friction_problem", "friction_studies", "run_level",
           "FRICTION_METHOD", "FRICTION_QUANTITIES", "FRICTION_RATIO", "FRICTION_F", "RUN_SCHEME", "NOT_RUN"]

#: the suffix of a friction column's method name in its Study (``"calculix-friction"``)
FRICTION_METHOD = "-friction"
#: what a partial-slip level records as errors: the stick zone's ends, half-width and centre (of W),
#: the shear away from the ends (of its peak), ∫q (of Q), and the comparison's d and e (of d)
FRICTION_QUANTITIES = ("stick_ends", "stick_width", "stick_shift", "q_interior_max", "q_integral", "d", "e")
#: the quantities whose values are their errors (:func:`threepart.convergence.analyse`'s ``error_only``)
ERROR_ONLY = ("stick_ends", "stick_width", "stick_shift", "q_interior_max")
#: the scheme of a column that ran
RUN_SCHEME = "two similar elastic bodies, Coulomb friction"
#: the scheme of a column that did not run, by why
NOT_RUN = {"missing": "not installed", "not yet": "not yet", "full": "in --full only"}


@dataclass(frozen=True)
class Referee:
    """One outside code with Coulomb friction.

    ``partial_slip(punch, P, s, Q, f, E, nu, *, n, tilt, workdir)`` returns an object with
    the surface points ``x, p, q`` and ``info`` (``h``); ``fretting(punch, P, s, Q_max, f,
    E, nu, *, n, tilt, workdir)`` one with the points at the last ``Q_max`` and whose
    ``energy`` is the energy per cycle (or ``info["energy"]``); ``load_history(punch,
    history, f, E, nu, *, n, tilt, workdir)`` (None: the code has none) one with the
    energy per cycle. ``available()`` says whether the code is installed, ``missing`` how
    to install it, ``errors`` what a failed run raises, ``levels`` the elements across W of
    its mesh study, coarse to fine. ``documented`` maps a judged quantity (or
    ``"problem/quantity"``, for one problem) to the tolerance row of the code's own
    documented figure, which judges it where it is wider than issue 38's target.
    """

    name: str
    available: Callable[[], bool]
    partial_slip: Callable[..., Any]
    fretting: Callable[..., Any]
    missing: str
    errors: tuple[type[BaseException], ...]
    levels: tuple[float, ...]
    documented: Mapping[str, tuple[str, str]] = field(default_factory=dict)
    load_history: Callable[..., Any] | None = None


#: the outside codes with friction, by name (:func:`register_referee`)
REFEREES: dict[str, Referee] = {}


def register_referee(referee: Referee) -> None:
    """Add an outside code to :data:`REFEREES` (by name)."""
    REFEREES[referee.name] = referee


def _calculix() -> Referee:
    from threepart import calculix
    from threepart.calculix import cycle, friction
    from threepart.errors import CcxError

    def fretting(*args: Any, **kwargs: Any) -> Any:
        return friction.fretting_cycle(*args, **kwargs)[-1]     # the last Q_max; info["energy"]

    def load_history(*args: Any, **kwargs: Any) -> Any:
        return cycle.load_history(*args, **kwargs)[-1]          # the last state; info["energy"]

    rows = {q: ("calculix-friction", q) for q in ("q_integral", "q_interior_max", "energy", "stick_shift")}
    ends = ("calculix-friction", "stick_end")
    return Referee("calculix", calculix.ccx_available, friction.partial_slip, fretting,
                   "`ccx` (CalculiX) is not on the PATH (Debian: apt-get install calculix-ccx)",
                   (CcxError,), (50.0, 100.0),
                   {**rows, "stick_ends": ends, "stick_width": ends,
                    "fretting_Q0.4/q_integral": ("calculix-friction", "cycle_q_integral")},
                   load_history)


#: GetFEM's steps from one state of a load history to the next in the flight column
FLIGHT_STEPS = 16


def _getfem() -> Referee:
    from types import SimpleNamespace

    from threepart import getfem
    from threepart.errors import GetfemError

    def fretting(*args: Any, **kwargs: Any) -> Any:
        cyc = getfem.fretting_cycle(*args, **kwargs)
        last = cyc.states[-1]
        return SimpleNamespace(x=last.x, p=last.p, q=last.q, energy=cyc.energy, info=cyc.info)

    def load_history(*args: Any, **kwargs: Any) -> Any:
        # 16 states a half-cycle: the friction work summed over the states converges as the step
        # squared, -2.60 % at 8 and -1.35 % at 16 on the flight cycle at W/h = 64 (docs/GETFEM.md)
        return getfem.load_history(*args, steps=FLIGHT_STEPS, **kwargs)

    rows = {q: ("getfem", q) for q in ("q_integral", "q_interior_max", "energy")}
    return Referee("getfem", getfem.getfem_available, getfem.partial_slip, fretting,
                   "no Python interpreter imports getfem (Debian: apt-get install python3-getfem; "
                   "or set THREEPART_GETFEM_PYTHON)", (GetfemError,), (32.0, 64.0),
                   {**rows, "stick_width": ("getfem", "stick_end")}, load_history)


def _builtin() -> None:
    for make in (_calculix, _getfem):
        ref = make()
        REFEREES.setdefault(ref.name, ref)


def referee(name: str) -> Referee:
    """The row ``name`` of :data:`REFEREES` (the built-in codes registered first)."""
    from threepart.errors import InputError

    _builtin()
    if name not in REFEREES:
        raise InputError(f"`code` = {name!r} is not one of the friction referees {sorted(REFEREES)}")
    return REFEREES[name]


def supports(code: Referee, needs: str) -> bool:
    """Whether ``code`` has what a problem needs: nothing, a ``load_history`` call, or a keyword
    of its ``partial_slip`` (``"sigma_bulk"``)."""
    if not needs:
        return True
    if needs == "load_history":
        return code.load_history is not None
    try:
        params = inspect.signature(code.partial_slip).parameters
    except (TypeError, ValueError):
        return False
    return needs in params


def friction_problem() -> dict[str, Any]:
    """The scaled Hertz pair of the columns and its closed-form references (partial slip, fretting):
    two steel bodies, radius ``10 SLOPE_SCALE`` mm, ``P = 400 / SLOPE_SCALE`` N/mm,
    ``Q = FRICTION_RATIO f P`` (:func:`.friction_problems.hertz`)."""
    return hertz()


def _not_run(code: Referee, problem: FrictionProblem, why: str, title: str = "") -> Any:
    """The study of a column that did not run, its scheme :data:`NOT_RUN` ``[why]`` and a note saying why."""
    from threepart.convergence import Study

    st = Study("h", method=code.name + FRICTION_METHOD, case=problem.name, scheme=NOT_RUN[why])
    st.notes.append({"missing": f"{code.missing}: the {code.name} friction column was not run",
                     "not yet": f"{code.name} has no `{problem.needs}` yet: {problem.name} was not run",
                     "full": f"{problem.name} runs in `threepart verify --full` only"}[why]
                    + (f" ({title})" if title else ""))
    return st


def friction_studies(say: Callable[[str], None] = print, codes: tuple[str, ...] | None = None, *,
                     fretting: bool = False, levels: tuple[float, ...] | None = None,
                     problems: tuple[str, ...] | None = None) -> list[Any]:
    """Every friction column: a Study in h per code and problem of the mode.

    ``codes`` picks rows of :data:`REFEREES` (default: all), ``problems`` rows of
    :data:`~.friction_problems.FRICTION_PROBLEMS` (default: all), ``levels`` overrides the
    codes' levels; ``fretting`` (``threepart verify --full``) runs the ``"full"`` problems too.

    A code that is not installed gives one study without levels that says so; so does a
    problem it cannot run yet, or one of ``--full`` in the default mode.
    """
    _builtin()
    out = []
    names = codes if codes is not None else tuple(REFEREES)
    for name in names:
        code = REFEREES[name]
        if not code.available():
            out.append(_not_run(code, FrictionProblem("all", hertz, "slip", "default"), "missing"))
            continue
        for problem in FRICTION_PROBLEMS:
            if (problems is not None and problem.name not in problems) or \
                    (problem.codes and name not in problem.codes):
                continue
            if problem.mode == "full" and not fretting:
                out.append(_not_run(code, problem, "full"))
            elif not supports(code, problem.needs):
                out.append(_not_run(code, problem, "not yet"))
            else:
                out.append(_column(code, problem, levels or code.levels, say))
    return out


def _column(code: Referee, problem: FrictionProblem, levels: tuple[float, ...],
            say: Callable[[str], None]) -> Any:
    """One column: ``problem`` by ``code`` at ``levels`` (a cycle: the finest only), as a Study in h."""
    from threepart.convergence import Study, analyse, run_study

    pr = problem.build()
    if problem.kind != "slip":
        levels = tuple(levels)[-1:]
    with tempfile.TemporaryDirectory(prefix=f"threepart-{code.name}-friction-") as tmp:
        def level(n: float) -> tuple[float, dict[str, float], dict[str, Any], dict[str, float]]:
            workdir = Path(tmp) / f"{problem.name}_n{n:g}"
            workdir.mkdir()
            return run_level(code, problem, pr, n, workdir, say)

        kw = dict(param="h", method=code.name + FRICTION_METHOD, case=problem.name, scheme=RUN_SCHEME)
        if len(levels) >= 2:
            st = run_study(level, list(levels), error_only=ERROR_ONLY, require_monotone=False,
                           **kw)   # type: ignore[arg-type]
        else:
            st = Study(**kw)    # type: ignore[arg-type]
            h, raw, info, err = level(levels[0])
            st.labels, st.sizes, st.info = [str(levels[0])], [h], [info]
            st.times = [float(info.get("seconds") or math.nan)]
            st.values = {q: [v] for q, v in raw.items()}
            st.errors = {q: [e] for q, e in err.items()}
            st = analyse(st, ERROR_ONLY, require_monotone=False)
    st.notes.extend(f"W/h = {lab}: the run failed, its errors are not known: {inf['failed']}"
                    for lab, inf in zip(st.labels, st.info) if "failed" in inf)
    st.notes.extend(f"W/h = {lab}: {code.name}'s files from threepart's cache (the same input ran before; "
                    "`threepart cache --clear` runs it again)" for lab, inf in zip(st.labels, st.info)
                    if inf.get("cached"))
    ref = pr.get("slip")
    st.reference = {**({"d": ref.d, "e": ref.e, "q_integral": ref.Q} if ref is not None else {}),
                    **({"energy": pr[k].energy for k in ("cycle", "steady") if k in pr and problem.kind != "slip"})}
    st.notes.append(pr["title"])
    return st


def run_level(code: Referee, problem: FrictionProblem, pr: dict[str, Any], n: float, workdir: Path,
              say: Callable[[str], None]) -> tuple[float, dict[str, float], dict[str, Any], dict[str, float]]:
    """One level of a column: ``(h, values, info, errors)``; a failed run (``code.errors``) gives
    NaN errors, so that the level stays in the study and a verdict of it fails, naming the error."""
    import time

    t0 = time.perf_counter()
    W = pr["slip"].a + pr["slip"].c if "slip" in pr else pr["W"]
    args = dict(n=n, tilt=pr["tilt"], workdir=workdir)
    failures: tuple[type[BaseException], ...] = (*code.errors, ThreepartError)
    try:
        if problem.kind == "flight":
            history = np.array([*pr["states"], *pr["states"]], dtype=float)   # two cycles: the last judged
            run = code.load_history(pr["punch"], history, pr["f"], pr["E"], pr["nu"], **args)  # type: ignore[misc]
        elif problem.kind == "fretting":
            run = code.fretting(pr["punch"], pr["P"], pr["s"], pr["Q"], pr["f"], pr["E"], pr["nu"], **args)
        else:
            bulk = {"sigma_bulk": pr["sigma_bulk"]} if problem.needs == "sigma_bulk" else {}
            run = code.partial_slip(pr["punch"], pr["P"], pr["s"], pr["Q"], pr["f"], pr["E"], pr["nu"],
                                    **args, **bulk)
        raw, err = _errors(code, problem, pr, run)
    except failures as exc:   # a failed run, or points that cannot be judged
        say(f"[study]   {code.name} {problem.name} W/h = {n:g} failed: {type(exc).__name__}: {exc}")
        nan = {q: math.nan for q in _judged(problem)}
        return W / n, nan, {"failed": f"{type(exc).__name__}: {exc}", "seconds": time.perf_counter() - t0}, nan
    seconds = time.perf_counter() - t0
    info = getattr(run, "info", {})
    h = float(info.get("h", W / n))
    cached = bool(info.get("cached"))      # the same input ran before: its files from threepart's cache
    say(f"[study]   {code.name} {problem.name} W/h = {n:g} ({seconds:.0f} s{', cached' if cached else ''}): " +
        ", ".join(f"{q} {e:.3g}" for q, e in err.items()))
    return h, raw, {"seconds": seconds, "cached": cached}, err


def _judged(problem: FrictionProblem) -> tuple[str, ...]:
    """The errors a level of ``problem`` records."""
    return {"slip": FRICTION_QUANTITIES, "fretting": (*FRICTION_QUANTITIES, "energy"),
            "flight": ("energy",)}[problem.kind]


def _shear_away(ref: Any, res: Any) -> float:
    """The largest error of the shear over the largest ``|q|`` of ``ref``, away from the ends:
    ``EDGE_FRACTION W`` in from the contact's and from the stick zone's ends (where the shear's
    square-root cusp is smeared over an element), as the codes' documented rows measure it
    (``("getfem", "q_interior_max")``, ``("calculix-friction", "q_interior_max")``)."""
    from ..compare import shear_field_errors

    return shear_field_errors(ref, res, away_from_stick_ends=True).interior_max


def _errors(code: Referee, problem: FrictionProblem, pr: dict[str, Any], run: Any
            ) -> tuple[dict[str, float], dict[str, float]]:
    """A level's values and errors: the stick zone (of W), the shear, ∫q; a cycle's energy."""
    from ..compare import compare

    raw: dict[str, float] = {}
    err: dict[str, float] = {}
    if problem.kind != "flight":
        ref = pr["slip"]
        W = ref.a + ref.c
        res = slip_from_points(run.x, run.p, run.q, ref, method=code.name)
        checks = {c.quantity: c for c in compare(ref, res, "referee", stresses=False)}
        raw = {"d": res.d, "e": res.e, "q_integral": checks["q_integral"].obtained}
        ends = max(abs(got - want) for got, want in zip(res.stick_zone, ref.stick_zone)) / W
        err = {"stick_ends": ends, "stick_width": abs(res.d - ref.d) / W, "stick_shift": abs(res.e - ref.e) / W,
               "q_interior_max": _shear_away(ref, res),
               **{q: checks[q].error for q in ("q_integral", "d", "e")}}
        raw.update({q: err[q] for q in ERROR_ONLY})     # values that are errors: their order is fitted
    if problem.kind in ("fretting", "flight"):
        energy = getattr(run, "energy", None)
        energy = float(getattr(run, "info", {}).get("energy", math.nan) if energy is None else energy)
        if not math.isfinite(energy):
            raise InputError(f"{code.name}'s {problem.kind} run gives no finite energy per cycle ({energy})")
        expected = (pr["cycle"] if problem.kind == "fretting" else pr["steady"]).energy
        raw["energy"] = energy
        err["energy"] = abs(energy - expected) / abs(expected)
    return raw, err

"""The case catalogue (``cases.json``) and the one place that calls all three solvers.

A :class:`Case` holds the numbers of one verification case; :func:`run_case`
solves it with closedform, sie and fem and compares the last two with the
first. Like scikit-fem's examples, a case exposes its numbers (a
:class:`CaseRun` holds every result, time and check) and nothing is plotted
here: :mod:`reports.plots` draws only when a report is written.
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Callable

from threepart.punch import Punch

from .compare import Check, compare
from .solvers import METHODS, SOLVERS
from .tolerances import fem_comparison

__all__ = ["Case", "CaseRun", "Mode", "MODES", "CASES_FILE", "load_cases", "get_case",
           "run_case", "solve", "solve_normal", "METHODS"]

CASES_FILE = Path(__file__).with_name("cases.json")


@dataclass(frozen=True)
class Mode:
    """Discretisation settings of one verification mode.

    ``sie_n`` (None: the solver's default) and ``fem_mesh`` (a preset name, or
    any mesh argument ``fem.solve_normal`` takes) are used for the catalogue;
    ``sie_study_n`` and ``fem_study_n`` (elements across the contact width,
    same grading and domain) for the convergence studies (empty: skipped).
    """

    name: str
    sie_n: int | None
    fem_mesh: Any
    sie_study_n: tuple[int, ...]
    fem_study_n: tuple[int, ...]

    def options(self, method: str) -> dict[str, Any]:
        """Discretisation keywords of ``method``'s adapter (:data:`reports.solvers.SOLVERS`)."""
        if method == "sie":
            return {} if self.sie_n is None else {"n": self.sie_n}
        if method == "fem":
            return {"mesh": self.fem_mesh}
        return {}


MODES: dict[str, Mode] = {
    "quick": Mode("quick", None, "quick", (8, 16, 32, 64, 128, 256), (30, 60, 120)),
    "default": Mode("default", None, "default", (8, 16, 32, 64, 128, 256, 512, 1024),
                    (30, 60, 120, 240, 480)),
    "full": Mode("full", None, "fine", (8, 16, 32, 64, 128, 256, 512, 1024, 2048),
                 (30, 60, 120, 240, 480, 960)),
}


@dataclass(frozen=True)
class Case:
    """One case of the catalogue: punch, material, loads and (for partial slip) Q and f.

    ``s`` is the lever arm in mm; when ``s_lift_off_fraction`` is set instead,
    :meth:`resolved` computes ``s`` from the closed-form lift-off range.
    """

    name: str
    description: str
    punch: Punch
    E: float
    nu: float
    P: float
    s: float | None = 0.0
    tilt: str = "free"
    s_lift_off_fraction: float | None = None
    f: float | None = None
    Q_over_fP: float | None = None

    @property
    def A(self) -> float:
        """Compliance of a rigid punch on the elastic half-plane, ``2(1 - nu^2)/E`` (eq. 4)."""
        return 2.0 * (1.0 - self.nu**2) / self.E

    @property
    def kind(self) -> str:
        """``"slip"`` when a shear load is applied, else ``"normal"``."""
        return "slip" if self.Q_over_fP is not None else "normal"

    @property
    def Q(self) -> float | None:
        """Shear force ``Q = (Q/fP) f P``."""
        if self.Q_over_fP is None or self.f is None:
            return None
        return self.Q_over_fP * self.f * self.P

    @property
    def load_4PA_over_b(self) -> float:
        """The paper's dimensionless load ``4PA/b`` (inf for b = 0)."""
        return 4 * self.P * self.A / self.punch.b if self.punch.b > 0 else math.inf

    @property
    def shear_load(self) -> tuple[float, float]:
        """``(Q, f)`` of a partial-slip case; ``ValueError`` for a normal case."""
        if self.Q is None or self.f is None:
            raise ValueError(f"case {self.name!r} has no shear load (`Q_over_fP` and `f`)")
        return self.Q, self.f

    @property
    def s_load(self) -> float:
        """The lever arm passed to a solver: ``s``, or 0 when the tilt is suppressed (``s*`` is returned)."""
        return 0.0 if self.tilt == "suppressed" else float(self.s or 0.0)

    def normal_key(self) -> tuple[Any, ...]:
        """Cases with equal keys share one normal problem (partial slip reuses it)."""
        return (self.punch, self.E, self.nu, self.P, self.s, self.tilt)

    def resolved(self) -> "Case":
        """This case with ``s`` in mm (from the lift-off fraction if one is given)."""
        if self.s_lift_off_fraction is None:
            return self
        from threepart import closedform

        lim = closedform.lift_off(self.punch, self.P, self.A)
        frac = self.s_lift_off_fraction
        s = frac * (lim.s_max if frac >= 0 else -lim.s_min)
        return replace(self, s=float(s))

    def as_dict(self) -> dict[str, Any]:
        p = self.punch
        return {"name": self.name, "description": self.description, "kind": self.kind,
                "punch": {"R1": p.R1, "R2": p.R2, "b": p.b, "R": None if math.isinf(p.R) else p.R,
                          "case": p.case},
                "E": self.E, "nu": self.nu, "A": self.A, "P": self.P, "s": self.s, "tilt": self.tilt,
                "s_lift_off_fraction": self.s_lift_off_fraction, "load_4PA_over_b":
                    None if math.isinf(self.load_4PA_over_b) else self.load_4PA_over_b,
                "f": self.f, "Q_over_fP": self.Q_over_fP, "Q": self.Q}


def load_cases(path: str | Path | None = None) -> list[Case]:
    """Read the catalogue (default: ``reports/cases.json``) into :class:`Case` records."""
    data = json.loads(Path(path or CASES_FILE).read_text(encoding="utf-8"))
    mat = data["material"]
    cases = []
    for c in data["cases"]:
        pd = dict(c["punch"])
        R = pd.pop("R", None)
        punch = Punch(R=math.inf if R is None else float(R), **pd)
        cases.append(Case(name=c["name"], description=c.get("description", ""), punch=punch,
                          E=float(c.get("E", mat["E"])), nu=float(c.get("nu", mat["nu"])),
                          P=float(c["P"]), s=c.get("s", None if "s_lift_off_fraction" in c else 0.0),
                          tilt=c.get("tilt", "free"), s_lift_off_fraction=c.get("s_lift_off_fraction"),
                          f=c.get("f"), Q_over_fP=c.get("Q_over_fP")))
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        raise ValueError(f"case names in {path or CASES_FILE} are not unique: {names}")
    return cases


def get_case(name: str, path: str | Path | None = None) -> Case:
    """The catalogue case called ``name``."""
    for c in load_cases(path):
        if c.name == name:
            return c
    raise KeyError(f"no case {name!r} in the catalogue")


def solve_normal(case: Case, method: str, mode: Mode) -> Any:
    """Solve the normal problem of ``case`` with ``method`` at ``mode``'s discretisation."""
    return SOLVERS[method].normal(case, **mode.options(method))


def solve(case: Case, method: str, mode: Mode,
          cache: dict[Any, Any] | None = None) -> tuple[Any, float]:
    """Result of ``case`` by ``method`` and its wall time (s); slip for slip cases but fem.

    ``cache`` maps ``(method, case.normal_key())`` to a normal result already
    computed, so that the partial-slip cases share their normal problem.
    """
    t0 = time.perf_counter()
    key = (method, case.normal_key())
    if cache is not None and key in cache:
        normal, t_normal = cache[key]
    else:
        normal = solve_normal(case, method, mode)
        t_normal = time.perf_counter() - t0
        if cache is not None:
            cache[key] = (normal, t_normal)
    slip = SOLVERS[method].slip
    if case.kind == "slip" and slip is not None:
        t1 = time.perf_counter()
        res = slip(case, normal, **mode.options(method))
        return res, t_normal + time.perf_counter() - t1
    return normal, t_normal


@dataclass
class CaseRun:
    """Everything one case produced: results, times, errors and checks, by method."""

    case: Case
    results: dict[str, Any] = field(default_factory=dict)
    times: dict[str, float] = field(default_factory=dict)
    errors: dict[str, str] = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return not self.errors and bool(self.checks) and all(c.passed for c in self.checks)

    def failed(self) -> list[Check]:
        return [c for c in self.checks if not c.passed]


def run_case(case: Case, mode: Mode, cache: dict[Any, Any] | None = None,
             methods: tuple[str, ...] = METHODS,
             progress: Callable[[str], None] | None = None) -> CaseRun:
    """Solve ``case`` with each method and compare sie and fem with closedform.

    A solver that raises is recorded in ``errors`` (and fails the case) rather
    than aborting the run.
    """
    say = progress or (lambda msg: None)
    run = CaseRun(case)
    try:
        case = case.resolved()
        run.case = case
    except Exception as exc:  # noqa: BLE001 - recorded in the report
        run.errors["closedform"] = f"lift-off range: {type(exc).__name__}: {exc}"
        return run
    for method in methods:
        reused = cache is not None and (method, case.normal_key()) in cache
        try:
            res, dt = solve(case, method, mode, cache)
        except Exception as exc:  # noqa: BLE001 - recorded in the report
            run.errors[method] = f"{type(exc).__name__}: {exc}"
            say(f"{method} FAILED ({type(exc).__name__}: {exc})")
            continue
        run.results[method] = res
        run.times[method] = dt
        say(f"{method} {_fmt_time(dt)}" + (" (normal problem shared with an earlier case)" if reused else ""))
    ref = run.results.get("closedform")
    if ref is None:
        return run
    for method in methods[1:]:
        if method not in run.results:
            continue
        comparison = "sie" if method == "sie" else fem_comparison(mode.fem_mesh)
        try:
            run.checks.extend(compare(ref, run.results[method], comparison))
        except Exception as exc:  # noqa: BLE001
            run.errors[f"compare-{method}"] = f"{type(exc).__name__}: {exc}"
    return run


def _fmt_time(dt: float) -> str:
    return f"{dt * 1e3:.1f} ms" if dt < 1 else f"{dt:.2f} s"

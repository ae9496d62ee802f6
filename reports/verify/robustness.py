"""The robustness study of ``threepart verify --full``: a wide seeded draw, the closed form against the SIE.

The default test suite draws a few hundred random cases (``tests/test_robustness.py``,
``tests/test_answers.py``, ``tests/test_sie_wide.py``, issue 29); this study draws
thousands from a seeded :class:`numpy.random.Generator`, as a designer's sweep would:

* radii ``R1``, ``R2`` log-uniform over ``0.03 b`` to ``1000 b``; a flat, convex or
  concave centre; a rigid punch on steel or two steel bodies;
* loads from just above their threshold (:func:`threepart.closedform.P_min`, or for
  a flat centre the load that spreads a Hertz contact of ``R1`` over ``2 b``) to
  ``1e4`` times it;
* lever arms across the SIE's lift-off range (:func:`threepart.sie.lift_off`), or
  a suppressed tilt;
* for partial slip a shear ratio of either sign, ``f`` and, for half the draws, a
  bulk stress; fretting cycles with a bulk stress.

Each draw is a :class:`~threepart.problem.catalogue.Case` solved through the registry
(:mod:`reports.solvers`) and judged by the rules of the tests: where both methods
answer they agree (contact ends, fields, stick zones, friction work); where one
refuses, the other refuses too, by the named error the SIE's ``within_paper``
implies; ``NoConvergenceError`` is never an answer; every answer has ``p >= 0``
and ``|q| <= f p``. The outcome is a :class:`~reports.verify.runs.CaseRun` whose checks
(comparison ``"robustness"``) are judged against the tolerance table and listed
with the catalogue's; a failed rule names its first offending draw.

Names
-----
draw             -- one random case from a generator
draws            -- the seeded sample of one group (normal, slip, fretting)
study            -- run the study and return its CaseRun
Tally            -- the worst figure of each rule and where it was found
reproduce        -- a draw's parameters to full precision, to reproduce it
SEED, COUNTS     -- the seed and the draw counts of ``verify --full``
RULES            -- the rules, each a check of the report
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any, Callable

import numpy as np

from threepart import Punch, closedform, sie
from threepart.problem.catalogue import Case
from threepart.errors import NoConvergenceError, StickZoneError
from threepart.problem.material import E_STEEL, NU
from threepart.tolerances import tolerance

from ..compare import Check
from .runs import CaseRun
from .. import solvers

__all__ = ["SEED", "COUNTS", "RULES", "R_LOW", "R_HIGH", "Tally", "draw", "draws", "reproduce", "study"]

#: the study's seed: the draw is the same on every run
SEED = 29
#: draws of each group in ``verify --full``: normal, partial slip (half with a bulk stress),
#: fretting cycles with a bulk stress
COUNTS = {"normal": 4000, "slip": 1500, "fretting": 300}
#: the range of R1 and R2, in units of b (log-uniform)
R_LOW, R_HIGH = 0.03, 1000.0
#: the rules, in report order: (quantity of the check, what it measures)
RULES = {
    "a": "largest |Δa|, |Δc| of every draw's normal problem, of W",
    "p_interior_max": "largest |Δp| of every draw's normal problem, of the peak, 1e-6 W inside the ends",
    "d": "largest |Δd|, |Δe| of the slip and fretting draws, of d",
    "q_interior_max": "largest |Δq| of the slip draw, of max|q|",
    "energy": "largest relative |ΔE| of the fretting draw's friction work",
    "stick": "largest |Δ| of the fretting draw's stick-zone ends, of d at Q_max",
    "p_min": "largest -min p of any answer, of its peak",
    "q_bound": "largest |q| - f p of any slip answer, of f p_max",
    "wrong_refusals": "draws where one method refused and the other answered (or refused otherwise)",
    "no_convergence": "draws where a method raised NoConvergenceError or an unnamed error",
}
#: pointwise comparisons stay this fraction of W inside the ends, where the square root makes
#: p ill-conditioned (a rounding of an end moves p by ~sqrt(eps) of the peak), as the tests do
END_MARGIN = 1e-6
#: grid points over a contact on which the fields and the laws are judged (as the tests)
GRID = 2001
#: states per branch of a fretting cycle of the study
CYCLE_STATES = 3
#: E of steel (MPa) and ν: a rigid punch on steel, or two steel bodies (E / 2)
STEEL = (E_STEEL, NU)


def draw(rng: np.random.Generator, group: str, i: int) -> Case:
    """One random case of ``group`` (``"normal"``, ``"slip"``, ``"fretting"``), the ``i``-th."""
    R1, R2 = 10 ** rng.uniform(math.log10(R_LOW), math.log10(R_HIGH), 2)
    kind = rng.choice(["flat", "flat", "convex", "concave"])
    big = max(R1, R2)
    R = {"flat": math.inf, "convex": 10 ** rng.uniform(1, 2) * big,
         "concave": -10 ** rng.uniform(1.5, 2.5) * big}[str(kind)]
    punch = Punch(R1=float(R1), R2=float(R2), b=1.0, R=float(R))
    material = (STEEL[0] / float(rng.choice([1.0, 2.0])), STEEL[1])
    case = Case(name=f"robustness_{group}_{i}", description="", punch=punch, P=1.0, material=material)
    P0 = closedform.P_min(punch, case.A)
    P = (P0 if P0 > 0 else math.pi * punch.b ** 2 / (2 * case.A * punch.R1)) * 10 ** rng.uniform(
        math.log10(1.001), 4.0)
    tilt = str(rng.choice(["free", "free", "suppressed"]))
    frac = float(rng.uniform(-0.98, 0.98))
    ratio = float(rng.uniform(0.02, 0.95)) * float(rng.choice([-1.0, 1.0]))
    f = float(rng.uniform(0.1, 1.0))
    bulk = float(rng.uniform(-1.5, 1.5)) * (group == "fretting" or bool(rng.integers(2)))
    case = replace(case, P=float(P), tilt=tilt, s=0.0 if tilt == "suppressed" else _lever_arm(case, frac))
    if group == "normal":
        return case
    Q = abs(ratio) * f * P if group == "fretting" else ratio * f * P
    W = _width_guess(case)
    return replace(case, f=f, Q_over_fP=Q / (f * P), cycle=group == "fretting",
                   sigma_bulk=bulk * 8 * abs(Q) / (math.pi * W))


def _lever_arm(case: Case, frac: float) -> float:
    """``frac`` of the way to the SIE's lift-off lever arm (0 where that lift-off is refused)."""
    try:
        s_min, s_max = sie.lift_off(case.punch, case.P, case.A)
    except ValueError:      # ArcExtentError, SlopeLimitError: a central load instead
        return 0.0
    return float(frac * s_max if frac > 0 else -frac * s_min)


def _width_guess(case: Case) -> float:
    """A contact width to scale the bulk stress by: the lift-off-free Hertz width of the
    larger radius, at least ``2 b`` (the scale only sets the bulk stress's size)."""
    return max(2 * case.punch.b, 2 * math.sqrt(2 * case.P * case.A * max(case.punch.R1, case.punch.R2) / math.pi))


def draws(group: str, count: int, seed: int = SEED) -> list[Case]:
    """The seeded sample of ``group``: ``count`` cases from its own stream of ``seed``."""
    stream = {"normal": 0, "slip": 1, "fretting": 2}[group]
    rng = np.random.default_rng([seed, stream])
    return [draw(rng, group, i) for i in range(count)]


def reproduce(case: Case) -> str:
    """The call that reproduces a draw: punch, loads and compliance to full precision."""
    p = case.punch
    txt = (f"Punch(R1={p.R1!r}, R2={p.R2!r}, b={p.b!r}, R={p.R!r}), P={case.P!r}, s={case.s!r}, "
           f"A={case.A!r}, tilt={case.tilt!r}")
    if case.Q is not None:
        txt += f", Q={case.Q!r}, f={case.f!r}, sigma_bulk={case.sigma_bulk!r}"
    return txt + (" (a fretting cycle, Q_max = Q)" if case.cycle else "")


@dataclass
class Tally:
    """The worst figure of each rule over the draw, and the first draw that broke each rule."""

    worst: dict[str, float] = field(default_factory=lambda: {q: 0.0 for q in RULES})
    at: dict[str, Case | None] = field(default_factory=lambda: {q: None for q in RULES})
    first: dict[str, tuple[Case, str] | None] = field(default_factory=lambda: {q: None for q in RULES})
    counts: dict[str, int] = field(default_factory=dict)

    def see(self, quantity: str, value: float, case: Case, why: str = "") -> None:
        """Record ``value`` of ``quantity`` on ``case`` (a count rule adds 1 per call)."""
        if quantity in COUNT_RULES:
            self.worst[quantity] += 1.0
        elif not value <= self.worst[quantity] and not math.isnan(self.worst[quantity]):
            # a NaN is recorded (and kept), and breaks the rule
            self.worst[quantity], self.at[quantity] = value, case
        if self.first[quantity] is None and not value <= limit(quantity):
            self.first[quantity] = (case, why)


#: rules whose figure is a count of offending draws
COUNT_RULES = ("wrong_refusals", "no_convergence")


def limit(quantity: str) -> float:
    """The tolerance table's limit of a rule (count rules: any offence, value 1, breaks it)."""
    return tolerance("robustness", quantity).limit


def _inside(n: Any) -> np.ndarray:
    """Points over a normal result's contact, END_MARGIN W inside its ends, and next to the joins."""
    W = n.a + n.c
    x = np.concatenate([np.linspace(-n.a, n.c, GRID)[1:-1],
                        [j + d for j in (-n.punch.b, n.punch.b) for d in (-1e-7, 1e-7, -1e-4, 1e-4)]])
    return x[(x > -n.a + END_MARGIN * W) & (x < n.c - END_MARGIN * W)]


def _laws(t: Tally, case: Case, res: Any, method: str) -> None:
    """``p >= 0`` of every answer and ``|q| <= f p`` of a slip answer, on the grid of its contact."""
    n = getattr(res, "normal", res)
    x = np.linspace(-n.a, n.c, GRID)[1:-1]
    p = n.pressure(x)
    t.see("p_min", float(max(-p.min(), 0.0) / p.max()), case, f"{method}: min p = {p.min():.3g}")
    if hasattr(res, "shear"):
        lo, hi = res.stick_zone
        xs = np.concatenate([x, np.linspace(max(lo, -n.a), min(hi, n.c), GRID)[1:-1]])
        excess = np.abs(res.shear(xs)) - res.f * res.pressure(xs)
        t.see("q_bound", float(max(excess.max(), 0.0) / (res.f * p.max())), case,
              f"{method}: |q| - f p = {excess.max():.3g}")


def _solve(t: Tally, case: Case, call: Callable[[str], Any]) -> dict[str, Any] | None:
    """Both methods' answers (or named refusals, as the exception) by ``call(method)``; None after
    a NoConvergenceError or an unnamed error (counted)."""
    out: dict[str, Any] = {}
    for method in ("closedform", "sie"):
        try:
            out[method] = call(method)
        except (NoConvergenceError, ArithmeticError, RuntimeError, LookupError, TypeError) as exc:
            t.see("no_convergence", 1.0, case, f"{method}: {type(exc).__name__}: {exc}")
            return None
        except ValueError as exc:     # the named refusals (LiftOffError, SeparationError, ...)
            out[method] = exc
    return out


def _refused(res: Any) -> bool:
    return isinstance(res, BaseException)


def _judged(t: Tally, case: Case, solve: Callable[[str], Any]) -> dict[str, Any] | None:
    """Both methods' answers of ``case`` (or their refusals), each answer held to p >= 0 and |q| <= f p."""
    got = _solve(t, case, solve)
    for m, r in (got or {}).items():
        if not _refused(r):
            _laws(t, case, r, m)
    return got


def _normal_rules(t: Tally, case: Case) -> dict[str, Any] | None:
    """The normal problem of ``case`` by both methods, judged; both answers, or None."""
    got = _judged(t, case, lambda m: solvers.normal(m, case))
    if got is None:
        return None
    c, g = got["closedform"], got["sie"]
    if _refused(g) or not g.within_paper:
        if not _refused(c):
            why = f"SIE refused ({type(g).__name__})" if _refused(g) else \
                f"the SIE's contact [{-g.a:.6g}, {g.c:.6g}] is beyond the paper"
            t.see("wrong_refusals", 1.0, case, f"{why}, the closed form answered")
        return None
    W = g.a + g.c
    t.counts["normal pairs"] = t.counts.get("normal pairs", 0) + 1
    if _refused(c):
        if not _edge_refusal(c, g, case):
            t.see("wrong_refusals", 1.0, case, f"the SIE answered within the paper, the closed form "
                                                f"refused: {type(c).__name__}: {c}")
        return None
    t.see("a", max(abs(c.a - g.a), abs(c.c - g.c)) / W, case, f"a, c: ({c.a!r}, {c.c!r}) against ({g.a!r}, {g.c!r})")
    x = _inside(c)
    pc = c.pressure(x)
    t.see("p_interior_max", float(np.max(np.abs(g.pressure(x) - pc)) / np.max(pc)), case, "pressure")
    return got


def _edge_refusal(c: BaseException, g: Any, case: Case) -> bool:
    """Whether the closed form's refusal of an SIE contact within the paper is the edge's own:
    an end within the table's SIE limit of a join (lift-off), or a centre whose least pressure
    is within the answer check's limit of 0 (separation)."""
    b, W = case.punch.b, g.a + g.c
    if min(g.a, g.c) - b <= tolerance("sie", "a").limit * W:
        return True
    x = np.linspace(-b, b, GRID)
    p = g.pressure(x)
    return bool(type(c).__name__ == "SeparationError" and
                p.min() <= tolerance("answer", "p_min").limit * np.max(g.pressure(_inside(g))))


def _slip_rules(t: Tally, case: Case, normals: dict[str, Any]) -> dict[str, Any] | None:
    """Partial slip of ``case`` by both methods on their normal answers, judged; both answers, or None."""
    got = _judged(t, case, lambda m: solvers.slip(m, case, normals[m]))
    if got is None:
        return None
    c, g = got["closedform"], got["sie"]
    if _refused(g) or not g.within_paper:
        if not (_refused(c) and (_refused(g) or isinstance(c, StickZoneError))):
            why = f"the SIE refused ({type(g).__name__})" if _refused(g) else \
                f"the SIE's stick zone {g.stick_zone} is beyond the paper"
            t.see("wrong_refusals", 1.0, case, f"{why}, the closed form: "
                                                f"{type(c).__name__ if _refused(c) else 'an answer'}")
        return None
    if _refused(c):
        lo, hi = g.stick_zone
        b = case.punch.b
        if min(abs(lo + b), abs(hi - b)) > tolerance("sie", "d").limit * g.d:
            t.see("wrong_refusals", 1.0, case, f"the SIE's stick zone {g.stick_zone} is within the paper, "
                                                f"the closed form refused: {type(c).__name__}: {c}")
        return None
    t.counts["slip pairs"] = t.counts.get("slip pairs", 0) + 1
    t.see("d", max(abs(c.d - g.d), abs(c.e - g.e)) / c.d, case, f"d, e: ({c.d!r}, {c.e!r}) against ({g.d!r}, {g.e!r})")
    x = _inside(c.normal)
    qc = c.shear(x)
    t.see("q_interior_max", float(np.max(np.abs(g.shear(x) - qc)) / np.max(np.abs(qc))), case, "shear")
    return got


def _cycle_rules(t: Tally, case: Case, normals: dict[str, Any], slips: dict[str, Any]) -> None:
    """A fretting cycle of ``case`` by both methods: friction work and stick zones, judged."""
    got = _solve(t, case, lambda m: solvers.fretting(m, case, normals[m], CYCLE_STATES))
    if got is None:
        return
    c, g = got["closedform"], got["sie"]
    if _refused(c) or _refused(g):
        if _refused(c) != _refused(g):
            t.see("wrong_refusals", 1.0, case, f"cycle: the closed form {type(c).__name__}, the SIE {type(g).__name__}")
        return
    t.counts["cycle pairs"] = t.counts.get("cycle pairs", 0) + 1
    t.see("energy", abs(g.energy - c.energy) / abs(c.energy), case, f"energy {g.energy!r} against {c.energy!r}")
    t.see("stick", float(np.max(np.abs(np.asarray(c.stick) - np.asarray(g.stick)))) / slips["closedform"].d,
          case, "the cycle's stick zones")


def _judge(t: Tally, case: Case) -> None:
    """Every rule of ``case``'s group on ``case``; an unexpected exception counts as an unnamed error."""
    try:
        normals = _normal_rules(t, case)
        if normals is None or case.Q is None:
            return
        slips = _slip_rules(t, case, normals)
        if slips is not None and case.cycle:
            _cycle_rules(t, case, normals, slips)
    except Exception as exc:  # noqa: BLE001 - an unnamed error is a finding of the study
        t.see("no_convergence", 1.0, case, f"{type(exc).__name__}: {exc}")


def study(counts: dict[str, int] | None = None, seed: int = SEED,
          say: Callable[[str], None] | None = None) -> CaseRun:
    """Run the robustness study and return it as a :class:`CaseRun` of ``"robustness"`` checks.

    Parameters
    ----------
    counts
        Draws per group, ``{"normal": ..., "slip": ..., "fretting": ...}`` (default
        :data:`COUNTS`; a missing group is not drawn).
    seed
        Seed of the draw (:data:`SEED`); each group has its own stream of it.
    say
        Progress, one line per group.

    Returns
    -------
    CaseRun
        One check per rule (:data:`RULES`). Its case is the first draw that broke a
        rule, or else the draw nearest its limit, and its description says which
        and how to reproduce it.
    """
    counts = dict(COUNTS if counts is None else counts)
    t = Tally()
    for group, count in counts.items():
        t0 = time.perf_counter()
        for case in draws(group, count, seed):
            _judge(t, case)
        if say:
            say(f"{count} {group} draws: {time.perf_counter() - t0:.1f} s")
    return _run_of(t, counts, seed)


def _run_of(t: Tally, counts: dict[str, int], seed: int) -> CaseRun:
    """The tally as a CaseRun: one check per rule, the case the first failure or the tightest draw."""
    checks = []
    for q, what in RULES.items():
        tol = tolerance("robustness", q)
        first, at = t.first[q], t.at[q]
        where = (f"first offending draw {first[0].name}: {reproduce(first[0])}: {first[1]}" if first
                 else f"worst draw {at.name}: {reproduce(at)}" if at is not None else "every draw at 0")
        checks.append(Check(comparison="robustness", quantity=q, reference=0.0, obtained=t.worst[q],
                            error=t.worst[q], limit=tol.limit, reason=f"{what}; {where}; {tol.reason}"))
    drawn = ", ".join(f"{n} {g}" for g, n in counts.items())
    failed = [(q, t.first[q]) for q in RULES if t.first[q] is not None]
    if failed:
        q, (case, why) = failed[0]   # type: ignore[misc]
        text = f"first failure, rule {q}: draw {case.name}: {reproduce(case)}: {why}"
    else:
        ratios = [(t.worst[q] / limit(q), q) for q in RULES if t.at[q] is not None and q not in COUNT_RULES]
        ratio, q = max(ratios, default=(0.0, "a"))
        case = t.at[q] or draws("normal", 1, seed)[0]
        text = f"every rule holds; shown: the draw nearest its limit ({ratio:.2g} of rule {q}), {case.name}"
    pairs = ", ".join(f"{n} {k}" for k, n in t.counts.items()) or "none"
    description = (f"robustness study, seed {seed}: {drawn} draws, closed form against the SIE "
                   f"(both answered: {pairs}; the rest refused by both); {text}")
    run = CaseRun(replace(case, name="robustness_study", description=description))
    run.checks = checks
    return run

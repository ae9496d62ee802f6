"""The validity map's boundary: where the signed peak error crosses a level, by bracketed bisection.

A *curve* of the map is one combination of :data:`CURVE_AXES` (the group axes
and ``b/R1``): the signed peak-pressure error as a function of the overhang
``(a - b)/R1`` alone. For each curve and each level of :data:`LEVELS` whose
crossing is bracketed by two adjacent grid points, a :class:`Bisection`
halves the bracket in ``log((a - b)/R1)`` until it is within
:data:`REL_WIDTH` (relative) or after :data:`STEP_CAP` steps. The map runs
each curve's bisections once its grid points are in, each step one point
with its own key, submitted when the step before is logged (so a resumed map
reuses the finished steps). Nothing here
runs the FEM: a step's point is evaluated by the map's engine, and
:func:`locate` runs the same bisection serially on any function (the tests).

Names
-----
LEVELS      -- the signed levels of the boundary (-5 %, -1 %, +1 %, +5 %)
REL_WIDTH   -- the final bracket's relative width in the overhang
STEP_CAP    -- the most bisection steps per crossing, per map mode
CURVE_AXES  -- the coordinates that fix one curve (the group axes and b/R1)
X           -- the coordinate along a curve, the overhang (a - b)/R1
Sample      -- one evaluated point of a curve: overhang, signed error, FEM estimate, key
curves      -- the finite samples of every curve of a list of points
brackets    -- the adjacent samples of one curve that bracket a level
Bisection   -- one crossing being located: its bracket, steps and result
start       -- the bisections of every bracketed crossing of every curve and level
locate      -- run one bisection serially on a function (no engine)
interpolate -- the crossing of a level by linear interpolation in log overhang
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

from threepart.tolerances import MAP_LEVELS

from .schema import GROUP_AXES, finite

__all__ = ["LEVELS", "REL_WIDTH", "STEP_CAP", "CURVE_AXES", "X", "Sample", "curves", "brackets",
           "Bisection", "start", "locate", "interpolate"]

#: issue 23: the designer's boundaries, where the closed form's signed peak error crosses
#: -5 %, -1 %, +1 % and +5 % of the finite body's peak (threepart.tolerances.MAP_LEVELS)
LEVELS = MAP_LEVELS
#: the bisection stops once the bracket's ends are within 10 % of each other (hi/lo - 1): finer
#: than the FEM's own error estimate resolves on most curves, at 1 to 4 steps per crossing
REL_WIDTH = 0.10
#: the most steps per crossing (a grid bracket of a factor 3.33 needs 4 halvings in log to 10 %);
#: the full map's budget (issue 23: an hour on 2 workers) allows 3 on its default meshes
STEP_CAP = {"quick": 4, "full": 3}
#: the coordinates that fix one curve of the map
CURVE_AXES = (*GROUP_AXES, "b_over_R1")
#: the coordinate along a curve
X = "a_minus_b_over_R1"


@dataclass(frozen=True)
class Sample:
    """One evaluated point of a curve: overhang ``x``, signed peak error ``e``, FEM estimate ``u``."""

    x: float
    e: float
    u: float
    key: str

    def as_dict(self) -> dict[str, Any]:
        return {X: self.x, "peak_rel_error": self.e, "fem_error_estimate": self.u, "key": self.key}


def _sample(p: dict[str, Any]) -> Sample | None:
    if not (finite(p.get("peak_rel_error")) and finite(p.get(X))):
        return None
    u: Any = p.get("fem_error_estimate")
    return Sample(float(p[X]), float(p["peak_rel_error"]), float(u) if finite(u) else 0.0, p["key"])


def curves(points: Sequence[dict[str, Any]]) -> dict[tuple[float, ...], list[Sample]]:
    """The finite samples of every curve (a value of :data:`CURVE_AXES`), each sorted by overhang."""
    out: dict[tuple[float, ...], list[Sample]] = {}
    for p in points:
        c = tuple(float(p[a]) for a in CURVE_AXES)
        s = _sample(p)
        out.setdefault(c, [])
        if s is not None:
            out[c].append(s)
    return {c: sorted(v, key=lambda s: s.x) for c, v in out.items()}


def brackets(samples: Sequence[Sample], level: float) -> list[tuple[Sample, Sample]]:
    """The adjacent ``samples`` (sorted by overhang) on either side of ``level`` (``e >= level`` is above)."""
    return [(p, q) for p, q in zip(samples, samples[1:]) if (p.e >= level) != (q.e >= level)]


def interpolate(lo: Sample, hi: Sample, level: float) -> float:
    """The overhang where the line through ``lo`` and ``hi`` in ``(log x, e)`` takes the value ``level``."""
    t = (level - lo.e) / (hi.e - lo.e)
    return math.exp(math.log(lo.x) + t * (math.log(hi.x) - math.log(lo.x)))


def _midpoint(lo: float, hi: float) -> float:
    """The geometric mean of ``lo`` and ``hi`` to 6 significant digits (the precision of a point's key)."""
    return float(f"{math.sqrt(lo * hi):.6g}")


@dataclass
class Bisection:
    """One crossing of ``level`` on one curve, located by bisection in ``log`` overhang.

    ``curve`` maps :data:`CURVE_AXES` to the curve's values; ``lo`` and ``hi``
    are the current bracket (``lo.x < hi.x``); ``samples`` the curve's grid
    samples (for the uncertainty band); ``crossings`` how many brackets of
    this level the curve's grid has (1: the level is crossed once).
    """

    curve: dict[str, float]
    level: float
    lo: Sample
    hi: Sample
    samples: list[Sample]
    crossings: int
    steps: list[Sample] = field(default_factory=list)
    failed: str | None = None

    def next_x(self, cap: int, width: float = REL_WIDTH) -> float | None:
        """The overhang of the next step, or None once the bracket is narrow enough or capped."""
        if self.failed is not None or self.hi.x / self.lo.x - 1 <= width or len(self.steps) >= cap:
            return None
        x = _midpoint(self.lo.x, self.hi.x)
        return x if self.lo.x < x < self.hi.x else None

    def take(self, s: Sample) -> None:
        """Narrow the bracket with the step ``s`` (at the overhang :meth:`next_x` gave)."""
        self.steps.append(s)
        if (s.e >= self.level) == (self.lo.e >= self.level):
            self.lo = s
        else:
            self.hi = s

    def fail(self, error: str) -> None:
        """Stop: a step's point has no result (the map is unfinished; a rerun retries it)."""
        self.failed = error

    def result(self, cap: int, width: float = REL_WIDTH) -> dict[str, Any]:
        """The boundary record: crossing overhang, its FEM uncertainty band, bracket and steps.

        The crossing interpolates the signed error linearly in ``log``
        overhang inside the final bracket. The band is the overhang range,
        around the crossing, over which the error stays within ``level +- u``
        (``u`` the larger FEM estimate of the bracket's ends) on the
        piecewise-linear curve through the grid samples and the steps; an end
        that the curve never leaves the band towards is the last sample, and
        is flagged in ``band_open``.
        """
        x = interpolate(self.lo, self.hi, self.level)
        u = max(self.lo.u, self.hi.u)
        line = sorted({s.x: s for s in (*self.samples, *self.steps)}.values(), key=lambda s: s.x)
        lo, lo_open = _band_edge(line, x, self.level, u, -1)
        hi, hi_open = _band_edge(line, x, self.level, u, +1)
        status = ("failed" if self.failed is not None else
                  "converged" if self.hi.x / self.lo.x - 1 <= width else "capped")
        return {**self.curve, "level": self.level, X: x, "band": [lo, hi],
                "band_open": [lo_open, hi_open], "bracket": [self.lo.x, self.hi.x],
                "bracket_errors": [self.lo.e, self.hi.e], "fem_error_estimate": u,
                "steps": [s.as_dict() for s in self.steps], "crossed_once": self.crossings == 1,
                "status": status, "error": self.failed}


def _band_edge(line: Sequence[Sample], x: float, level: float, u: float, way: int) -> tuple[float, bool]:
    """From the crossing ``x`` along ``line`` in direction ``way``: where ``|e - level|`` first reaches ``u``."""
    if u <= 0:
        return x, False
    prev = Sample(x, level, u, "")
    for s in (line if way > 0 else line[::-1]):
        if (s.x - x) * way <= 0:
            continue
        if abs(s.e - level) >= u:
            target = level + math.copysign(u, s.e - level)
            return interpolate(prev, s, target) if prev.e != s.e else s.x, False
        prev = s
    return prev.x, True


def start(points: Sequence[dict[str, Any]], levels: Sequence[float] = LEVELS) -> list[Bisection]:
    """A :class:`Bisection` for every bracketed crossing of every level on every curve of ``points``."""
    out = []
    for c, samples in curves(points).items():
        for level in levels:
            found = brackets(samples, level)
            for lo, hi in found:
                out.append(Bisection(dict(zip(CURVE_AXES, c)), level, lo, hi, list(samples), len(found)))
    return out


def locate(f: Callable[[float], tuple[float, float]], samples: Sequence[Sample], level: float,
           cap: int, width: float = REL_WIDTH) -> list[dict[str, Any]]:
    """Every bracketed crossing of ``level`` on the curve ``f``, bisected serially (no engine).

    ``f(x)`` returns the signed error and the FEM estimate at the overhang
    ``x``; ``samples`` are the curve's grid samples. The map itself runs the
    same :class:`Bisection` on its engine, step by step as results arrive.
    """
    found = brackets(sorted(samples, key=lambda s: s.x), level)
    results = []
    for lo, hi in found:
        b = Bisection({}, level, lo, hi, list(samples), len(found))
        while (x := b.next_x(cap, width)) is not None:
            e, u = f(x)
            b.take(Sample(x, e, u, f"x={x:.6g}"))
        results.append(b.result(cap, width))
    return results

"""threepart's pytest plugin: validate any contact code against the catalogue's reference solutions.

Installed with threepart (entry point ``pytest11``: ``threepart``), it adds two
fixtures and a marker to every pytest run; a test that asks for neither is
left alone (not parametrised, nothing imported).

``threepart_case``
    A catalogue case (:class:`threepart.problem.catalogue.Case`, resolved): a test
    that asks for it runs once per case of the one case catalogue, or per
    case the marker selects.
``threepart_check(result, case, *, comparison="fem-default", tolerances=None)``
    Compares ``result`` with the case's reference solution (the closed form,
    or past its framework the SIE; :attr:`Case.reference`) by
    :func:`threepart.reports.compare.compare`, judges each figure by the
    tolerance table (:mod:`threepart.tolerances`, row group ``comparison``) or
    by the limits in ``tolerances`` (``quantity -> limit``), prints the
    margins and fails the test naming every quantity out of tolerance. It
    returns the :class:`~threepart.reports.compare.Check` list.

    ``result`` is anything with ``a``, ``c`` (the contact is ``[-a, c]``) and
    ``pressure(x)`` (compressive, vectorised); optionally ``alpha``, ``P``
    and ``s``, and for a partial-slip case ``shear(x)`` with ``d`` and ``e``
    (stick zone ``[-(d+e), d-e]``); ``x_nodes`` for a nodal code, whose field
    is then compared at its own nodes. Figures it cannot give are not
    compared.
``@pytest.mark.threepart_cases(*names, suite=None, kinds=None)``
    Selects the cases ``threepart_case`` runs over: by name, by suite
    (``"verify"``, ``"fem"``, ``"sie"``) or by kind (``"normal"``, ``"slip"``,
    ``"fretting"``).

The margins of every check are also listed at the end of the run (section
"threepart margins"). Example: ``examples/test_tamaas_plugin.py``; the
plugin's own tests: ``tests/test_plugin.py``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Mapping

import pytest
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:  # pragma: no cover
    from threepart.problem.catalogue import Case
    from threepart.reports.compare import Check

__all__ = ["threepart_case", "threepart_check", "check", "reference", "margins_table"]

MARKER = "threepart_cases"
_PROPERTY = "threepart_margins"
#: the row group of the tolerance table a result is judged by, unless the test says otherwise:
#: the limits threepart's own finite-element model meets on its default mesh
DEFAULT_COMPARISON = "fem-default"


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", f"{MARKER}(*names, suite=None, kinds=None): the catalogue cases that the "
        "threepart_case fixture runs over (threepart's pytest plugin)")
    config.pluginmanager.register(_Margins(), "threepart-margins")


def _selected(marker: pytest.Mark | None) -> list[Case]:
    from threepart.problem.catalogue import SUITES, load_cases

    cases = load_cases(None)
    if marker is None:
        return cases
    names, suite, kinds = marker.args, marker.kwargs.get("suite"), marker.kwargs.get("kinds")
    unknown = sorted(set(marker.kwargs) - {"suite", "kinds"})
    if unknown:
        raise pytest.UsageError(f"@pytest.mark.{MARKER}: unknown keyword `{unknown[0]}` (give names, "
                                "`suite` or `kinds`)")
    known = [c.name for c in cases]
    missing = [n for n in names if n not in known]
    if missing:
        raise pytest.UsageError(f"@pytest.mark.{MARKER}: {missing[0]!r} is not a catalogue case "
                                f"(one of {', '.join(known)})")
    if suite is not None and suite not in SUITES:
        raise pytest.UsageError(f"@pytest.mark.{MARKER}: `suite` = {suite!r} must be one of {SUITES}")
    chosen = [c for c in cases if (not names or c.name in names)
              and (suite is None or suite in c.suites)
              and (kinds is None or c.kind in ((kinds,) if isinstance(kinds, str) else kinds))]
    if not chosen:
        raise pytest.UsageError(f"@pytest.mark.{MARKER}{marker.args}: selects no case")
    return chosen


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """Parametrise a test that asks for ``threepart_case`` over the selected catalogue cases."""
    if "threepart_case" not in metafunc.fixturenames:
        return
    cases = _selected(metafunc.definition.get_closest_marker(MARKER))
    metafunc.parametrize("threepart_case", [c.resolved() for c in cases], ids=[c.name for c in cases],
                         indirect=True)


@pytest.fixture
def threepart_case(request: pytest.FixtureRequest) -> Case:
    """A case of threepart's catalogue (resolved), one per parametrised test."""
    return request.param  # type: ignore[no-any-return]


@lru_cache(maxsize=None)
def reference(case: Case) -> Any:
    """The reference solution of ``case``: the closed form, or past its framework the SIE (cached)."""
    from threepart.reports.verify.runs import MODES, solve

    case = case.resolved()
    return solve(case, case.reference, MODES["default"])[0]


def _float(result: Any, name: str) -> float:
    try:
        value = float(getattr(result, name))
    except AttributeError:
        raise InputTypeError(f"`result` has no attribute `{name}`: threepart_check needs `a`, `c` and "
                        "`pressure(x)`") from None
    except (TypeError, ValueError):
        raise InputTypeError(f"`result.{name}` must be a number, not {type(getattr(result, name)).__name__}") \
            from None
    if not math.isfinite(value):
        raise InputError(f"`result.{name}` = {value} must be finite")
    return value


def _adapt(result: Any, ref: Any) -> tuple[Any, tuple[str, ...]]:
    """``result`` in the shared result shape (on the reference's punch), and the figures it lacks."""
    import numpy as np

    from threepart.reports.compare import is_fretting, is_slip, normal_of

    Normal, Slip = _shapes()
    a, c = _float(result, "a"), _float(result, "c")
    if not callable(getattr(result, "pressure", None)):
        raise InputTypeError("`result` has no callable `pressure(x)`: threepart_check needs `a`, `c` and "
                        "`pressure(x)`")
    if not a + c > 0:
        raise InputError(f"`result` has an empty contact: a + c = {a + c:g} must be > 0")
    base = normal_of(ref)
    missing = tuple(q for q in ("alpha", "P", "s") if getattr(result, q, None) is None)
    normal = Normal(punch=base.punch, A=base.A, a=a, c=c,
                     alpha=math.nan if "alpha" in missing else _float(result, "alpha"),
                     P=base.P if "P" in missing else _float(result, "P"),
                     s=base.s if "s" in missing else _float(result, "s"),
                     tilt=base.tilt, method="checked", fn=result.pressure,
                     x_nodes=None if getattr(result, "x_nodes", None) is None
                     else np.asarray(result.x_nodes, float))
    slip = (is_slip(ref) or is_fretting(ref)) and callable(getattr(result, "shear", None)) \
        and getattr(result, "d", None) is not None and getattr(result, "e", None) is not None
    if not (is_slip(ref) and slip):
        return normal, missing
    return Slip(normal=normal, Q=ref.Q, f=ref.f, d=_float(result, "d"), e=_float(result, "e"),
                 method="checked", fn=result.shear), missing


@lru_cache(maxsize=None)
def _shapes() -> tuple[type, type]:
    """The shared result shape around a user's fields (built on first use: no numpy at plugin load)."""
    import numpy as np

    from threepart.results import NormalResult, SlipResult

    def wrap(fn: Callable[[Any], Any], x: Any) -> Any:
        x = np.asarray(x, dtype=float)
        return np.asarray(fn(x), dtype=float).reshape(x.shape)

    @dataclass(frozen=True)
    class Normal(NormalResult):
        """A user's normal result in the shared shape: its pressure, on the reference's punch."""

        checks_answer = False    # judged by the comparison, not refused on construction

        fn: Callable[[Any], Any] = field(default=lambda x: x, compare=False)
        x_nodes: Any = field(default=None, compare=False)

        def pressure(self, x: Any) -> Any:
            return wrap(self.fn, x)

    @dataclass(frozen=True)
    class Slip(SlipResult):
        """A user's partial-slip result in the shared shape: its shear and stick zone."""

        checks_answer = False    # judged by the comparison (q_bound), not refused on construction

        fn: Callable[[Any], Any] = field(default=lambda x: x, compare=False)

        def shear(self, x: Any) -> Any:
            return wrap(self.fn, x)

    return Normal, Slip


def check(result: Any, case: Case, *, comparison: str = DEFAULT_COMPARISON,
          tolerances: Mapping[str, float] | None = None) -> list[Check]:
    """The judged comparison of ``result`` with ``case``'s reference (no printing, no failing).

    Parameters
    ----------
    result
        Anything with ``a``, ``c`` and ``pressure(x)``; see the module docstring.
    case
        A catalogue case (the ``threepart_case`` fixture, or
        :func:`threepart.problem.catalogue.get_case`).
    comparison
        Row group of :data:`threepart.tolerances.TOLERANCES` whose limits apply.
    tolerances
        ``quantity -> limit`` that replace the table's, e.g. ``{"a": 1e-3}``
        (errors normalised as in :mod:`threepart.tolerances`).

    Returns
    -------
    list of Check
        One per compared figure; ``Check.passed`` is the verdict.

    Raises
    ------
    TypeError, ValueError
        For a result without ``a``, ``c`` and ``pressure(x)``, an unknown
        ``comparison``, or a tolerance for a quantity not compared (or not > 0).
    """
    from threepart.reports.compare import Check, compare
    from threepart.tolerances import TOLERANCES

    if not any(k[0] == comparison for k in TOLERANCES):
        groups = sorted({k[0] for k in TOLERANCES})
        raise InputError(f"`comparison` = {comparison!r} is not a row group of the tolerance table "
                         f"(one of {', '.join(groups)})")
    ref = reference(case)
    other, missing = _adapt(result, ref)
    checks = [c for c in compare(ref, other, comparison) if c.quantity not in missing]
    tolerances = dict(tolerances or {})
    compared = {c.quantity for c in checks}
    for q, limit in tolerances.items():
        if q not in compared:
            raise InputError(f"`tolerances` names {q!r}, which is not compared for this result "
                             f"(compared: {', '.join(sorted(compared))})")
        if not (isinstance(limit, (int, float)) and limit > 0):
            raise InputError(f"`tolerances[{q!r}]` = {limit!r} must be a number > 0")
    return [Check(c.comparison, c.quantity, c.reference, c.obtained, c.error,
                  float(tolerances[c.quantity]), "given by the test")
            if c.quantity in tolerances else c for c in checks]


def _margin(c: Check) -> float:
    """``limit / error``: how many times the error fits in its limit (``inf`` for no error)."""
    return math.inf if c.error == 0 else c.limit / c.error


def margins_table(checks: list[Check], case: str) -> str:
    """The checks as a text table: quantity, value, reference, error, limit, margin."""
    from threepart.tolerances import ERROR_UNITS

    lines = [f"threepart_check {case} (errors normalised per threepart.tolerances; "
             "margin = limit/error, > 1 passes)",
             f"  {'quantity':<15} {'value':>13} {'reference':>13} {'error':>9} {'limit':>9} "
             f"{'margin':>9}  of"]
    for c in checks:
        lines.append(f"  {c.quantity:<15} {c.obtained:>13.6g} {c.reference:>13.6g} {c.error:>9.2e} "
                     f"{c.limit:>9.1e} {_margin(c):>9.3g}  {ERROR_UNITS.get(c.quantity, '')}"
                     f"{'' if c.passed else '  FAILED'}")
    return "\n".join(lines)


@pytest.fixture
def threepart_check(request: pytest.FixtureRequest) -> Callable[..., list[Check]]:
    """``threepart_check(result, case, *, comparison=..., tolerances=None)``: judge, print, fail."""
    def run(result: Any, case: Case, *, comparison: str = DEFAULT_COMPARISON,
            tolerances: Mapping[str, float] | None = None) -> list[Check]:
        checks = check(result, case, comparison=comparison, tolerances=tolerances)
        table = margins_table(checks, case.name)
        print(table)
        request.node.user_properties.append((_PROPERTY, table))
        failed = [c for c in checks if not c.passed]
        if failed:
            worst = "; ".join(f"{c.quantity} error {c.error:.3g} > limit {c.limit:.3g} "
                              f"(value {c.obtained:.6g}, reference {c.reference:.6g})" for c in failed)
            pytest.fail(f"threepart_check {case.name}: out of tolerance: {worst}", pytrace=False)
        return checks

    return run


class _Margins:
    """Collects the margins tables of a run and lists them at its end."""

    def __init__(self) -> None:
        self.tables: dict[str, list[str]] = {}

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        if report.when == "call":
            for key, table in report.user_properties:
                if key == _PROPERTY:
                    self.tables.setdefault(report.nodeid, []).append(str(table))

    def pytest_terminal_summary(self, terminalreporter: Any) -> None:
        """The margins of every ``threepart_check`` of the run (nothing if there was none)."""
        if not self.tables:
            return
        terminalreporter.section("threepart margins")
        for nodeid, tables in self.tables.items():
            terminalreporter.write_line(nodeid)
            for t in tables:
                terminalreporter.write_line(t)

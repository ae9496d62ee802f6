"""Hostile input to every solver entry point: a named refusal, never a crash or a quiet answer.

The validation contract (:mod:`threepart.problem.validate`): a value of the wrong type
is a ``TypeError``; a value out of range a ``ValueError`` (or a subclass from
:mod:`threepart.errors`) that names the argument; every real number that
passes is computed in float64. Hypothesis draws an entry point of
:mod:`threepart.closedform`, :mod:`threepart.sie` and :func:`threepart.solve`
(closedform, sie, auto), one of its arguments and a hostile value for it
(bool, str, bytes, None, complex, NaN, ±inf, 0, negative, 1e-320, 1e308,
10**400, a float16 infinity, a list, a huge count) and asserts that the call
raises from that family and names the argument; or a valid value in another
numeric type (float16, float32, longdouble, Fraction), and asserts that the
answer is bit for bit the one for the same number given as a float64.

The reference is the contract itself: which values are bad is decided here,
by the argument's documented range, not by the code under test.
"""
from __future__ import annotations

import fractions
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import threepart
from threepart import Punch, closedform, rigid_punch, sie

A = rigid_punch(210e3, 0.3)
PUNCH = Punch(10.0, 5.0, 1.0)
P, S, Q, F = 400.0, 0.1, 10.0, 0.5
NORMAL_CF = closedform.solve_normal(PUNCH, P, S, A=A)
NORMAL_SIE = sie.solve_normal(PUNCH, P, S, A=A, n=16)

#: argument kinds and the values that are bad for every argument of that kind
_NOT_REAL = {"bool": True, "np.bool_": np.bool_(True), "str": "1.0", "bytes": b"1", "None": None,
             "complex": 1 + 0j, "list": [1.0, 2.0]}
_NOT_FINITE = {"nan": math.nan, "inf": math.inf, "-inf": -math.inf, "float16 inf": np.float16(np.inf),
               "1e308": 1e308, "10**400": 10**400}
_NOT_POSITIVE = {"0": 0.0, "negative": -3.0, "1e-320": 1e-320}
BAD: dict[str, dict[str, Any]] = {
    "positive": {**_NOT_REAL, **_NOT_FINITE, **_NOT_POSITIVE},
    "signed": {**_NOT_REAL, **_NOT_FINITE},      # 0, negatives and 1e-320 are lever arms/forces
    "batch": {k: v for k, v in {**_NOT_REAL, **_NOT_FINITE, **_NOT_POSITIVE}.items() if k != "list"},
    "punch": {"tuple": (10.0, 5.0, 1.0), "None": None, "str": "Punch", "float": 1.0},
    "normal": {"str": "normal", "None": None, "dict": {"a": 1.0}, "punch": PUNCH},
    "count": {"bool": True, "float": 16.0, "str": "16", "None-like str": "None", "complex": 16 + 0j,
              "0": 0, "negative": -4, "10**9": 10**9, "2**70": 2**70},
    "states": {"bool": True, "float": 3.0, "str": "3", "None": None, "1": 1, "10**9": 10**9},
    "choice": {"unknown": "sideways", "None": None, "int": 3, "bytes": b"free"},
}
#: valid values in other numeric types: the answer must be the float64 one
WRAPPERS: dict[str, Callable[[float], Any]] = {
    "float16": np.float16, "float32": np.float32, "longdouble": np.longdouble,
    "Fraction": lambda v: fractions.Fraction(v),
}

#: entry point -> (function, valid keyword arguments, kind of each argument)
ENTRIES: dict[str, tuple[Callable[..., Any], dict[str, Any], dict[str, str]]] = {
    "closedform.solve_normal": (closedform.solve_normal, dict(punch=PUNCH, P=P, s=S, A=A, tilt="free"),
                                dict(punch="punch", P="positive", s="signed", A="positive", tilt="choice")),
    "closedform.solve_normal_batch": (closedform.solve_normal_batch, dict(punch=PUNCH, P=P, s=S, A=A),
                                      dict(punch="punch", P="batch", s="signed", A="positive")),
    "closedform.lift_off": (closedform.lift_off, dict(punch=PUNCH, P=P, A=A),
                            dict(punch="punch", P="positive", A="positive")),
    "closedform.P_min": (closedform.P_min, dict(punch=PUNCH, A=A, s=S, tilt="free"),
                         dict(punch="punch", A="positive", s="signed", tilt="choice")),
    "closedform.solve_partial_slip": (closedform.solve_partial_slip,
                                      dict(normal_solution=NORMAL_CF, Q=Q, f=F),
                                      dict(normal_solution="normal", Q="signed", f="positive")),
    "closedform.fretting_cycle": (closedform.fretting_cycle,
                                  dict(normal_solution=NORMAL_CF, Q_max=Q, f=F, states=3),
                                  dict(normal_solution="normal", Q_max="positive", f="positive",
                                       states="states")),
    "sie.solve_normal": (sie.solve_normal, dict(punch=PUNCH, P=P, s=S, A=A, tilt="free", n=16),
                         dict(punch="punch", P="positive", s="signed", A="positive", tilt="choice",
                              n="count")),
    "sie.lift_off": (sie.lift_off, dict(punch=PUNCH, P=P, A=A),
                     dict(punch="punch", P="positive", A="positive")),
    "sie.solve_partial_slip": (sie.solve_partial_slip, dict(normal=NORMAL_SIE, Q=Q, f=F, n=16),
                               dict(normal="normal", Q="signed", f="positive", n="count")),
    "sie.fretting_cycle": (sie.fretting_cycle, dict(normal=NORMAL_SIE, Q_max=Q, f=F, n=16, states=3),
                           dict(normal="normal", Q_max="positive", f="positive", n="count",
                                states="states")),
    "sie.gauss_chebyshev": (sie.gauss_chebyshev, dict(n=16), dict(n="count")),
}
for _method in ("closedform", "sie", "auto"):
    _kw = dict(punch=PUNCH, P=P, s=S, A=A, tilt="free", method=_method)
    _kinds = dict(punch="punch", P="positive", s="signed", A="positive", tilt="choice", method="choice")
    if _method == "sie":     # auto passes n to the SIE only where it falls back
        _kw["n"], _kinds["n"] = 16, "count"
    ENTRIES[f"solve[{_method}]"] = (threepart.solve, _kw, _kinds)
    ENTRIES[f"solve[{_method}] slip"] = (threepart.solve, {**_kw, "Q": Q, "f": F},
                                         {**_kinds, "Q": "signed", "f": "positive"})


def in_family(exc: BaseException) -> bool:
    """A ``TypeError``, or a ``ValueError``/``RuntimeError`` raised by threepart's contract."""
    if isinstance(exc, TypeError):
        return True
    return isinstance(exc, (ValueError, RuntimeError)) and (
        type(exc) is ValueError or type(exc).__module__ == "threepart.errors")


def numbers(result: Any) -> list[Any]:
    """The result's numbers that must be float64."""
    if isinstance(result, tuple):
        return list(result)
    if isinstance(result, float):
        return [result]
    return [getattr(result, k) for k in ("a", "c", "alpha", "P", "s", "d", "e", "energy", "s_min",
                                         "s_max", "weights") if hasattr(result, k)]


@settings(max_examples=400, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_hostile_values_are_refused_by_name(data):
    name = data.draw(st.sampled_from(sorted(ENTRIES)), label="entry point")
    fun, valid, kinds = ENTRIES[name]
    arg = data.draw(st.sampled_from(sorted(kinds)), label="argument")
    label = data.draw(st.sampled_from(sorted(BAD[kinds[arg]])), label="hostile value")
    kwargs = {**valid, arg: BAD[kinds[arg]][label]}
    with pytest.raises(Exception) as info:
        fun(**kwargs)
    exc = info.value
    assert in_family(exc), f"{name}({arg}={label}): {type(exc).__name__}: {exc}"
    assert "\n" not in str(exc).strip(), f"{name}({arg}={label}): a message of more than one line"
    assert f"`{arg}`" in str(exc), f"{name}({arg}={label}) does not name `{arg}`: {exc}"


REAL_ARGS = sorted((name, arg) for name, (_, valid, kinds) in ENTRIES.items() for arg in kinds
                   if kinds[arg] in ("positive", "signed", "batch") and name != "sie.gauss_chebyshev")


@settings(max_examples=120, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(REAL_ARGS), st.sampled_from(sorted(WRAPPERS)))
def test_every_real_type_is_computed_in_float64(entry, wrapper):
    name, arg = entry
    fun, valid, _ = ENTRIES[name]
    value = WRAPPERS[wrapper](valid[arg])
    ref = fun(**{**valid, arg: float(value)})     # the same number (rounded to its type) in float64
    got = fun(**{**valid, arg: value})
    for r, g in zip(numbers(ref), numbers(got)):
        g_arr = np.asarray(g)
        assert g_arr.dtype == np.float64, f"{name}({arg}={wrapper}) computes in {g_arr.dtype}"
        assert np.array_equal(g_arr, np.asarray(r)), f"{name}({arg}={wrapper}): {g} != {r}"


def test_a_huge_count_is_refused_before_any_work():
    """``n = 10**9`` used to hang; the bound is sie.quadrature.MAX_N = 2**16."""
    with pytest.raises(ValueError, match=r"`n` = 1000000000 must lie in \[2, 65536\]"):
        sie.solve_normal(PUNCH, P, S, A=A, n=10**9)
    with pytest.raises(ValueError, match=r"`n` = 1000000000 must lie in \[2, 65536\]"):
        sie.solve_partial_slip(NORMAL_CF, Q, F, n=10**9)


@pytest.mark.parametrize("P_batch, error, match", [
    ([400.0, True], TypeError, r"`P` = True must be a real number, not bool \(element 1\)"),
    (["400"], TypeError, r"`P` = '400' must be a real number, not str \(element 0\)"),
    (np.array(["400"]), TypeError, r"`P` must be real numbers, not an array of <U3"),
    (b"400", TypeError, r"`P` = b'400' must be real numbers, not bytes"),
    ([400.0, 400 + 1j], TypeError, r"`P` = \(400\+1j\) must be a real number, not complex"),
    (np.array([400.0, 400 + 1j]), TypeError, r"`P` must be real numbers, not an array of complex128"),
    (np.array([True]), TypeError, r"`P` must be real numbers, not an array of bool"),
    ([400.0, np.longdouble("1e4000")], ValueError, r"`P` = .* is outside the double-precision range "
                                                   r"\(element 1\)"),
    (np.array([400.0, np.longdouble("1e4000")]), ValueError, r"`P` = .* is outside the double-precision "
                                                           r"range \(element 1\)"),
    ([400.0, math.nan], ValueError, r"`P` = nan is not a number \(element 1\)"),
])
def test_batch_refuses_what_is_not_real(P_batch, error, match):
    with pytest.raises(error, match=match):
        closedform.solve_normal_batch(PUNCH, P_batch, A=A)


def test_batch_promotes_float16_to_float64():
    got = closedform.solve_normal_batch(PUNCH, np.array([400.0, 800.0], np.float16), A=A)
    ref = closedform.solve_normal(PUNCH, 800.0, A=A)
    assert got.a.dtype == np.float64 and got.a[1] == ref.a


# --- issue 29: coordinates, flags, catalogue and batch shapes ---------------------------------------
#: coordinates that every result's pressure/shear/slip_amplitude/stress refuses, with the error
BAD_X: dict[str, tuple[Any, type[Exception]]] = {
    "None": (None, TypeError), "str": ("0.5", TypeError), "bool": (True, TypeError),
    "np.bool_": (np.True_, TypeError), "complex": (0.5 + 0j, TypeError),
    "list with None": ([0.1, None], TypeError), "bool array": (np.array([True]), TypeError),
    "nan": (math.nan, ValueError), "inf": (math.inf, ValueError), "-inf": (-math.inf, ValueError),
    "10**400": (10**400, ValueError), "nan in array": (np.array([0.1, math.nan]), ValueError),
    "longdouble 1e4000": (np.array([np.longdouble("1e4000")]), ValueError),
}
SLIP_CF = closedform.solve_partial_slip(NORMAL_CF, Q, F)
SLIP_SIE = sie.solve_partial_slip(NORMAL_SIE, Q, F)
CYCLE_CF = closedform.fretting_cycle(NORMAL_CF, Q, F, states=3)
CYCLE_SIE = sie.fretting_cycle(NORMAL_SIE, Q, F, states=3)


@pytest.fixture(scope="module")
def fem_normal():
    from threepart import fem
    return fem.solve_normal(PUNCH, P, S, E=210e3, nu=0.3, mesh="quick")


def _calls(result: Any) -> dict[str, Callable[[Any], Any]]:
    """Each method of ``result`` that takes a coordinate, as a call of that coordinate alone."""
    calls: dict[str, Callable[[Any], Any]] = {"pressure": getattr(result, "pressure", None),
                                              "stress x": lambda v: result.stress(v, 0.1),
                                              "stress z": lambda v: result.stress(0.1, v)}
    if hasattr(result, "Q_max"):
        calls = {"shear": lambda v: result.shear(v, Q, "loading"), "slip_amplitude": result.slip_amplitude,
                 "stress x": lambda v: result.stress(v, 0.1, Q, "loading"),
                 "stress z": lambda v: result.stress(0.1, v, Q, "loading")}
    elif hasattr(result, "shear"):
        calls["shear"] = result.shear
    return {k: v for k, v in calls.items() if v is not None}


RESULTS = {"closedform normal": NORMAL_CF, "sie normal": NORMAL_SIE, "closedform slip": SLIP_CF,
           "sie slip": SLIP_SIE, "closedform cycle": CYCLE_CF, "sie cycle": CYCLE_SIE}


@pytest.mark.parametrize("label", sorted(BAD_X))
@pytest.mark.parametrize("which", [*sorted(RESULTS), "fem normal"])
def test_every_result_refuses_a_bad_coordinate(which, label, request):
    result = request.getfixturevalue("fem_normal") if which == "fem normal" else RESULTS[which]
    value, error = BAD_X[label]
    for call, fun in _calls(result).items():
        name = "z" if call == "stress z" else "x"
        with pytest.raises(error, match=f"`{name}`"):
            fun(value)


@pytest.mark.parametrize("which", sorted(RESULTS))
def test_a_good_coordinate_is_computed_in_float64(which):
    """An int, a float32, a list: the number given as a float64 (the reference), bit for bit."""
    for call, fun in _calls(RESULTS[which]).items():
        if call.startswith("stress"):
            continue
        ref = np.asarray(fun(np.array([1.0, 0.5])))
        assert np.array_equal(np.asarray(fun([1, np.float32(0.5)])), ref), call
        assert np.array_equal(np.asarray(fun(1)), ref[0]), call


@pytest.mark.parametrize("value", [True, np.True_, False, np.False_])
def test_beyond_small_slopes_takes_any_bool(value):
    ref = closedform.solve_normal(PUNCH, P, S, A=A, beyond_small_slopes=bool(value))
    assert closedform.solve_normal(PUNCH, P, S, A=A, beyond_small_slopes=value) == ref


@pytest.mark.parametrize("value", [1, 0, None, "yes", 1.0])
def test_beyond_small_slopes_refuses_what_is_not_a_bool(value):
    with pytest.raises(TypeError, match=r"`beyond_small_slopes` = .* must be True or False"):
        closedform.solve_normal(PUNCH, P, S, A=A, beyond_small_slopes=value)


def test_an_unknown_case_is_a_value_error_listing_the_cases():
    from threepart.problem.catalogue import get_case
    with pytest.raises(ValueError, match=r"`name` = 'nope' is not a case of cases\.json \(its cases: "
                                         r"general, caseA_sym, "):
        get_case("nope")


def _catalogue(tmp_path, text: str) -> str:
    path = tmp_path / "cases.json"
    path.write_text(text, encoding="utf-8")
    return str(path)


_CASE = '{"name": "x", "suites": ["verify"], "punch": {"R1": 10, "R2": 5, "b": 1}%s}'


@pytest.mark.parametrize("text, match", [
    (None, r"`path` = '.*missing\.json' cannot be read: No such file"),
    ("{", r"`path` = '.*cases\.json' is not a JSON case catalogue"),
    ('{"material": {"E": 1, "nu": 0.3}}', r"`path` = '.*' has no field 'cases'"),
    ('{"cases": [%s]}' % (_CASE % ""), r"`path` = '.*', case 'x' has no field 'P'"),
    ('{"cases": [%s]}' % (_CASE % ', "P": NaN, "A": 1'), r"`path` = '.*', case 'x': `P` = nan must be"),
    ('{"cases": [%s]}' % (_CASE % ', "P": 1, "A": 1, "f": Infinity'), r"case 'x': `f` = inf must be"),
    ('{"cases": [%s]}' % (_CASE % ', "P": -1, "A": 1'), r"case 'x': `P` = -1.0 must be > 0"),
])
def test_a_bad_catalogue_file_is_a_value_error_naming_path_and_field(tmp_path, text, match):
    from threepart.problem.catalogue import load_cases
    path = str(tmp_path / "missing.json") if text is None else _catalogue(tmp_path, text)
    with pytest.raises(ValueError, match=match):
        load_cases(path=path)


def test_batch_arrays_of_unequal_length_are_named():
    with pytest.raises(ValueError, match=r"`P` \(shape \(3,\)\) and `s` \(shape \(2,\)\) do not broadcast"):
        closedform.solve_normal_batch(PUNCH, [400.0, 500.0, 600.0], [0.0, 0.1], A=A)


@pytest.mark.parametrize("fun", [threepart.similar_pair, threepart.rigid_punch])
@pytest.mark.parametrize("arg, value, match", [
    ("E", -1.0, r"`E` = -1\.0 must be > 0"), ("nu", 0.7, r"`nu` = 0\.7 must lie in"),
    ("nu", math.nan, r"`nu` = nan"), ("E", "1", r"`E` = '1' must be a real number"),
])
def test_material_messages_name_the_argument(fun, arg, value, match):
    kwargs = {"E": 210e3, "nu": 0.3, arg: value}
    with pytest.raises((TypeError, ValueError), match=match):
        fun(**kwargs)

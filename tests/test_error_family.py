"""One error family: every exception class threepart defines derives from ThreepartError.

Independent of the classes' own declarations: every module of the installed package is
imported and every class that is an Exception and defined there is checked, so that a new
error anywhere that forgets the base fails here.
"""
from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import threepart
from threepart import errors


def _modules():
    yield threepart
    for info in pkgutil.walk_packages(threepart.__path__, "threepart."):
        if info.name.endswith("__main__"):
            continue
        yield importlib.import_module(info.name)


def _exception_classes():
    seen = {}
    for module in _modules():
        for _, obj in inspect.getmembers(module, inspect.isclass):
            if issubclass(obj, BaseException) and obj.__module__.startswith("threepart"):
                seen[f"{obj.__module__}.{obj.__qualname__}"] = obj
    return seen


def test_every_exception_class_of_the_package_is_a_threepart_error():
    classes = _exception_classes()
    assert len(classes) >= 20, sorted(classes)   # the scan reaches the whole package
    strays = sorted(name for name, cls in classes.items() if not issubclass(cls, errors.ThreepartError))
    assert not strays, f"not derived from ThreepartError: {strays}"


@pytest.mark.parametrize("name, builtin", [
    ("LiftOffError", ValueError), ("FullSlidingError", ValueError), ("StickZoneError", ValueError),
    ("NoConvergenceError", RuntimeError), ("ContactZoneError", RuntimeError),
    ("ReaderError", ValueError), ("OutputExistsError", ValueError), ("CcxError", RuntimeError),
    ("CcxMissing", OSError), ("ManifestError", AssertionError), ("DisjointContactsError", ValueError),
])
def test_the_family_keeps_its_builtin_bases(name, builtin):
    cls = getattr(errors, name)
    assert issubclass(cls, errors.ThreepartError) and issubclass(cls, builtin)


def test_the_old_homes_raise_the_same_classes():
    from threepart.calculix import CcxError, CcxMissing
    from threepart.meshes import ManifestError
    from threepart.output import OutputExistsError
    assert (CcxError, CcxMissing, ManifestError, OutputExistsError) == (
        errors.CcxError, errors.CcxMissing, errors.ManifestError, errors.OutputExistsError)


def test_a_refusal_is_caught_as_a_threepart_error():
    with pytest.raises(threepart.ThreepartError, match="`s`"):
        threepart.solve(threepart.Punch(R1=10, R2=5, b=1), 400, 50.0, A=1e-5)


@pytest.mark.parametrize("error", ["InputTypeError", "ManifestError", "CcxError", "ReaderError"])
def test_the_command_line_gives_any_refusal_one_line_and_status_2(monkeypatch, capsys, error):
    """Whatever built-in base a refusal has (TypeError, AssertionError, RuntimeError), the command
    line prints its one line and exits 2, never a traceback."""
    from threepart.cli import _main, solve

    def refuse(args):
        raise getattr(errors, error)(f"`x` = 1 breaks its limit ({error})")

    monkeypatch.setattr(solve, "run", refuse)
    status = _main.main(["solve", "--case", "caseA_sym"])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1 and error in err[0], err

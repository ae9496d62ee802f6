"""Baseline files with a tolerance per quantity, following pytest-regressions' behaviour.

* a missing baseline is written and the test fails;
* a mismatch writes ``<name>.obtained.json`` beside the baseline and fails;
* only ``--force-regen`` (the pytest-regressions option) renews a baseline;
* rows are matched by their ``"case"`` name where the data have that column, so a new
  catalogue case is named as new and every other case is still compared.

JSON is used instead of ``num_regression`` (which needs pandas) so that the
committed baselines are readable and diff well.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Mapping, Sequence

import pytest

BASELINES = Path(__file__).with_name("baselines")
#: the column that names a baseline's rows: rows are matched by it, not by position
KEY = "case"


def _close(x: float | None, y: float | None, rtol: float, atol: float) -> bool:
    if x is None or y is None:
        return x is None and y is None
    if isinstance(x, str) or isinstance(y, str):
        return x == y
    return math.isclose(float(x), float(y), rel_tol=rtol, abs_tol=atol)


def _rows(data: Mapping[str, Sequence[Any]]) -> dict[str, int] | None:
    """Each row's index by its case name, when the data name their rows (a ``"case"`` column)."""
    names = data.get(KEY)
    if names is None:
        return None
    names = [str(n) for n in names]
    if len(set(names)) != len(names):
        raise ValueError(f"the baseline's {KEY!r} column repeats a name: {names}")
    return {n: i for i, n in enumerate(names)}


def _differences(expected: Mapping[str, Sequence[Any]], obtained: Mapping[str, Sequence[Any]],
                 tolerances: Mapping[str, Mapping[str, float]], default: Mapping[str, float]) -> list[str]:
    """Every figure that differs, named ``quantity[case]`` (rows keyed by case name) or ``quantity[i]``.

    With a ``"case"`` column on both sides the rows are matched by name, so that a case added
    to (or removed from) the catalogue is named once and the other cases are still compared.
    """
    out = []
    rows_e, rows_o = _rows(expected), _rows(obtained)
    if rows_e is not None and rows_o is not None:
        out += [f"case {n!r}: only in {'obtained' if n in rows_o else 'baseline'}"
                for n in sorted(set(rows_e) ^ set(rows_o))]
        pairs = [(n, rows_e[n], rows_o[n]) for n in rows_e if n in rows_o]
    for key in sorted(set(expected) | set(obtained)):
        if key not in expected or key not in obtained:
            out.append(f"{key}: only in {'obtained' if key in obtained else 'baseline'}")
            continue
        e, o = list(expected[key]), list(obtained[key])
        if rows_e is None or rows_o is None:
            if len(e) != len(o):
                out.append(f"{key}: {len(o)} values, baseline has {len(e)}")
                continue
            pairs = [(str(i), i, i) for i in range(len(e))]
        tol = {**default, **tolerances.get(key, {})}
        for name, i, j in pairs:
            if not _close(e[i], o[j], tol.get("rtol", 0.0), tol.get("atol", 0.0)):
                out.append(f"{key}[{name}]: obtained {o[j]!r}, baseline {e[i]!r} "
                           f"(rtol {tol.get('rtol', 0.0):g}, atol {tol.get('atol', 0.0):g})")
    return out


def _force_regen(config: Any) -> bool:
    try:
        return bool(config.getoption("force_regen"))
    except ValueError:  # pytest-regressions not installed
        return False


def check_baseline(config: Any, name: str, data: Mapping[str, Sequence[Any]],
                   tolerances: Mapping[str, Mapping[str, float]] | None = None,
                   default: Mapping[str, float] | None = None, directory: Path = BASELINES) -> None:
    """Compare ``data`` (quantity -> list of numbers) with the baseline ``<directory>/<name>.json``.

    ``tolerances[q] = {"rtol": ..., "atol": ...}`` per quantity; ``default`` otherwise.
    """
    tolerances = tolerances or {}
    default = default or {"rtol": 1e-12, "atol": 0.0}
    path = directory / f"{name}.json"
    text = json.dumps({k: list(v) for k, v in data.items()}, indent=1, allow_nan=False) + "\n"
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        pytest.fail(f"baseline not found, created: {path}")
    expected = json.loads(path.read_text(encoding="utf-8"))
    diffs = _differences(expected, json.loads(text), tolerances, default)
    if not diffs:
        return
    if _force_regen(config):
        path.write_text(text, encoding="utf-8")
        pytest.fail(f"baseline differed and --force-regen is set, regenerated: {path}\n" + "\n".join(diffs))
    obtained = path.with_suffix(".obtained.json")
    obtained.write_text(text, encoding="utf-8")
    pytest.fail(f"{len(diffs)} figures differ from {path}; obtained written to {obtained}:\n"
                + "\n".join(diffs))

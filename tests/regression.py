"""Baseline files with a tolerance per quantity, following pytest-regressions' behaviour.

* a missing baseline is written and the test fails;
* a mismatch writes ``<name>.obtained.json`` beside the baseline and fails;
* only ``--force-regen`` (the pytest-regressions option) renews a baseline.

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


def _close(x: float | None, y: float | None, rtol: float, atol: float) -> bool:
    if x is None or y is None:
        return x is None and y is None
    if isinstance(x, str) or isinstance(y, str):
        return x == y
    return math.isclose(float(x), float(y), rel_tol=rtol, abs_tol=atol)


def _differences(expected: Mapping[str, Sequence[Any]], obtained: Mapping[str, Sequence[Any]],
                 tolerances: Mapping[str, Mapping[str, float]], default: Mapping[str, float]) -> list[str]:
    out = []
    for key in sorted(set(expected) | set(obtained)):
        if key not in expected or key not in obtained:
            out.append(f"{key}: only in {'obtained' if key in obtained else 'baseline'}")
            continue
        e, o = list(expected[key]), list(obtained[key])
        if len(e) != len(o):
            out.append(f"{key}: {len(o)} values, baseline has {len(e)}")
            continue
        tol = {**default, **tolerances.get(key, {})}
        for i, (x, y) in enumerate(zip(e, o)):
            if not _close(x, y, tol.get("rtol", 0.0), tol.get("atol", 0.0)):
                out.append(f"{key}[{i}]: obtained {y!r}, baseline {x!r} "
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

"""Strict JSON: the one sanitiser of every JSON threepart writes, and the schema check.

Names
-----
json_safe     -- a JSON-safe copy: non-finite floats as None, numpy scalars as Python numbers
strict_json   -- ``json.dumps`` that writes non-finite numbers as null, never NaN/Infinity
validate_json -- check a document against a JSON schema file (jsonschema)
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

__all__ = ["json_safe", "strict_json", "validate_json"]


def json_safe(v: Any) -> Any:
    """A JSON-safe copy of ``v``: non-finite floats become None, numpy scalars Python numbers.

    The one sanitiser of every JSON that threepart writes (reports, studies,
    the command line's ``--json``). Dict keys become strings; anything that is
    not a JSON scalar, list or dict becomes its ``str``.
    """
    if isinstance(v, dict):
        return {str(k): json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [json_safe(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, (str, bytes)):
        try:
            v = v.item()
        except (ValueError, AttributeError):
            return str(v)
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if v is None or isinstance(v, (bool, int, str)):
        return v
    return str(v)


def strict_json(doc: Any, **kwargs: Any) -> str:
    """``json.dumps(doc)`` as strict JSON: infinite and NaN floats become ``null``.

    Parameters
    ----------
    doc
        Nested dicts, lists and JSON scalars (numpy scalars are converted).
    **kwargs
        Passed on to :func:`json.dumps` (e.g. ``indent``).

    Returns
    -------
    str
        Text that any JSON parser reads; never ``NaN`` or ``Infinity``.
    """
    return json.dumps(json_safe(doc), allow_nan=False, **kwargs)


def validate_json(doc: Any, schema_file: str | Path | dict[str, Any]) -> None:
    """Validate ``doc`` against the JSON schema in ``schema_file``, or that schema itself (skipped without ``jsonschema``).

    Raises
    ------
    jsonschema.ValidationError
        If ``doc`` does not match the schema.
    """
    try:
        import jsonschema
    except ImportError:  # pragma: no cover - jsonschema is in the test extra
        return
    schema = schema_file if isinstance(schema_file, dict) else \
        json.loads(Path(schema_file).read_text(encoding="utf-8"))
    jsonschema.validate(doc, schema)

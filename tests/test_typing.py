"""The packages stay clean under mypy (house style)."""
from __future__ import annotations

from pathlib import Path

from mypy import api

ROOT = Path(__file__).resolve().parents[1]


def test_mypy_is_clean():
    out, err, status = api.run(["--no-incremental", "--config-file", str(ROOT / "pyproject.toml"),
                                *(str(ROOT / p) for p in ("closedform", "sie", "fem", "meshes", "reports"))])
    assert status == 0, out + err

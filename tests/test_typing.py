"""The packages stay clean under mypy (house style).

mypy cannot follow the installed mapping of the top-level folders onto
``threepart.*``, so the test lays out the same tree with symbolic links and
checks it as the package ``threepart``.
"""
from __future__ import annotations

import os
from pathlib import Path

from mypy import api

ROOT = Path(__file__).resolve().parents[1]
SUBPACKAGES = ("closedform", "sie", "fem", "meshes", "reports")


def test_mypy_is_clean(tmp_path):
    pkg = tmp_path / "threepart"
    pkg.mkdir()
    for path in (ROOT / "threepart").iterdir():   # its modules and subpackages (threepart.output)
        if path.suffix == ".py" or (path / "__init__.py").is_file():
            (pkg / path.name).symlink_to(path, target_is_directory=path.is_dir())
    for name in SUBPACKAGES:
        (pkg / name).symlink_to(ROOT / name, target_is_directory=True)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        out, err, status = api.run(["--no-incremental", "--config-file", str(ROOT / "pyproject.toml"),
                                    "-p", "threepart"])
    finally:
        os.chdir(cwd)
    assert status == 0, out + err
    assert "Success" in out

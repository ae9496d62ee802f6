"""The packages stay clean under mypy (house style).

mypy cannot follow the installed mapping of the top-level folders onto
``threepart.*``, so the test lays out the same tree with symbolic links and
checks it as the package ``threepart``.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

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
    # in its own process: mypy's command line ends without tearing down its large object
    # graph, which in this process would cost the garbage collector seconds at the session's end
    done = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental", "--config-file",
                           str(ROOT / "pyproject.toml"), "-p", "threepart"],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Success" in done.stdout

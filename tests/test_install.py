"""threepart installs under one name: no top-level ``closedform``, ``sie``, ``fem``, ``meshes`` or ``reports``.

Three of those names belong to unrelated projects on the package index; a
package that installed them would shadow, or be deleted by, those. The wheel
is built from this checkout and installed into a fresh virtual environment
(which sees this environment's numpy, scipy, gmsh ... but not the checkout).
"""
from __future__ import annotations

import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FOREIGN = ("closedform", "sie", "fem", "meshes", "reports")


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                    "-w", str(out), str(ROOT)], check=True, capture_output=True, text=True)
    (path,) = out.glob("threepart-*.whl")
    return path


def test_wheel_holds_only_the_threepart_package(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    top = {n.split("/")[0] for n in names}
    assert {t for t in top if not t.endswith(".dist-info")} == {"threepart"}
    for sub in FOREIGN:
        assert f"threepart/{sub}/__init__.py" in names
    # data files travel with their packages
    assert "threepart/meshes/reference.msh" in names and "threepart/meshes/manifest.json" in names


def test_fresh_environment_imports_threepart_fem_but_not_fem(wheel, tmp_path):
    env = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env)
    python = env / "bin" / "python"
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "-q",
                    str(wheel)], check=True, capture_output=True, text=True)

    def run(code: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([str(python), "-c", code], cwd=tmp_path, capture_output=True, text=True)

    ok = run("import threepart.fem, threepart.closedform, threepart.sie, threepart.reports; "
             "print(threepart.fem.__file__)")
    assert ok.returncode == 0, ok.stderr
    assert str(env) in ok.stdout  # the installed copy, not the checkout
    for name in FOREIGN:
        bad = run(f"import {name}")
        assert bad.returncode != 0 and "ModuleNotFoundError" in bad.stderr, name
    script = subprocess.run([str(env / "bin" / "threepart"), "solve", "--R1", "10", "--R2", "5", "--b",
                             "1", "--A", "8.67e-6", "--P", "400"], capture_output=True, text=True,
                            cwd=tmp_path)
    assert script.returncode == 0, script.stderr

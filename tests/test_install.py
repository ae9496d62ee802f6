"""threepart installs under one name: no top-level ``closedform``, ``sie``, ``fem``, ``meshes`` or ``reports``.

Three of those names belong to unrelated projects on the package index; a
package that installed them would shadow, or be deleted by, those. The wheel
is built from this checkout and installed into an isolated virtual
environment: one that sees neither this environment's packages nor the base
interpreter's, whatever environment the tests run in (a venv, or the system
interpreter). Of this environment's packages it sees only the wheel's
dependencies: those its metadata names, and theirs in turn, each at a version
its requirement allows, linked in (:func:`dependencies`; installing them anew
took 20 s of the test run, issue 41). So a dependency missing from
``pyproject.toml`` fails here.
"""
from __future__ import annotations

import subprocess
import sys
import venv
import zipfile
from importlib import metadata
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]
FOREIGN = ("closedform", "sie", "fem", "meshes", "reports")
#: the solve below: b and R1 (mm); a symmetric-load contact lies between b and b + R1
B, R1 = 1.0, 10.0


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                    "-w", str(out), str(ROOT)], check=True, capture_output=True, text=True)
    (path,) = out.glob("threepart-*.whl")
    return path


def dependencies(requires: list[str]) -> list[metadata.Distribution]:
    """The distributions of this environment that ``requires`` names, and theirs in turn.

    Each requirement's markers are evaluated for this interpreter and the extras asked
    of it (``dask[distributed]`` brings distributed); each distribution found must be at a
    version its requirement allows. A requirement this environment lacks fails the test.
    """
    found: dict[str, metadata.Distribution] = {}
    extras_of: dict[str, set[str]] = {}
    todo: list[tuple[str, frozenset[str]]] = [(text, frozenset()) for text in requires]
    while todo:
        text, asked = todo.pop()
        req = Requirement(text)
        if req.marker is not None and not any(req.marker.evaluate({"extra": e}) for e in asked or {""}):
            continue
        try:
            dist = metadata.distribution(req.name)
        except metadata.PackageNotFoundError:
            pytest.fail(f"{req} is required but not installed here")
        assert req.specifier.contains(dist.version, prereleases=True), f"{req}: {dist.version} installed"
        key = canonicalize_name(req.name)
        if key in found and set(req.extras) <= extras_of[key]:
            continue
        found[key] = dist
        extras_of.setdefault(key, set()).update(req.extras)
        todo += [(r, frozenset(req.extras)) for r in dist.requires or []]
    return list(found.values())


def link(source: Path, target: Path) -> None:
    """``target`` a link to ``source``; where two distributions share a folder (a namespace
    package), a folder of links to both's entries."""
    if not target.exists() and not target.is_symlink():
        target.symlink_to(source, target_is_directory=source.is_dir())
        return
    if not (source.is_dir() and target.is_dir()):
        return                              # the same file of two distributions: the first stays
    if target.is_symlink():
        first = target.resolve()
        target.unlink()
        target.mkdir()
        for entry in first.iterdir():
            link(entry, target / entry.name)
    for entry in source.iterdir():
        link(entry, target / entry.name)


@pytest.fixture(scope="module")
def isolated(wheel, tmp_path_factory) -> Path:
    """An isolated venv holding the wheel and, linked in, the dependencies its metadata names."""
    root = tmp_path_factory.mktemp("isolated")
    env = root / "venv"
    venv.EnvBuilder(system_site_packages=False, with_pip=False).create(env)
    done = subprocess.run([sys.executable, "-m", "pip", "--python", str(env / "bin" / "python"),
                           "install", "-q", "--no-deps", "--no-compile", str(wheel)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    with zipfile.ZipFile(wheel) as whl:
        (meta,) = [n for n in whl.namelist() if n.endswith(".dist-info/METADATA")]
        requires = [v for k, v in (line.split(": ", 1) for line in whl.read(meta).decode().splitlines()
                                   if ": " in line) if k == "Requires-Dist"]
    deps = root / "dependencies"
    deps.mkdir()
    for dist in dependencies(requires):
        for top in sorted({Path(str(f)).parts[0] for f in dist.files or []} - {"..", "__pycache__"}):
            if not top.endswith(".pth"):
                link(Path(str(dist.locate_file(top))), deps / top)
    (site,) = (env / "lib").glob("python*/site-packages")
    (site / "threepart-dependencies.pth").write_text(f"{deps}\n")
    return env


def test_wheel_holds_only_the_threepart_package(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    top = {n.split("/")[0] for n in names}
    assert {t for t in top if not t.endswith(".dist-info")} == {"threepart"}
    for sub in FOREIGN:
        assert f"threepart/{sub}/__init__.py" in names
    # data files travel with their packages
    assert "threepart/meshes/reference.msh" in names and "threepart/meshes/manifest.json" in names


def test_isolated_environment_sees_nothing_of_this_one(isolated, tmp_path):
    python = isolated / "bin" / "python"
    paths = subprocess.run([str(python), "-c", "import sys; print('\\n'.join(sys.path))"],
                           capture_output=True, text=True, check=True).stdout.split()
    here = {p for p in sys.path if p.endswith("site-packages")}
    assert not here & set(paths), "the isolated venv sees this environment's site-packages"


def test_fresh_environment_imports_threepart_fem_but_not_fem(isolated, tmp_path):
    python = isolated / "bin" / "python"

    def run(code: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([str(python), "-c", code], cwd=tmp_path, capture_output=True, text=True)

    ok = run("import threepart.fem, threepart.closedform, threepart.sie, threepart.reports; "
             "print(threepart.fem.__file__)")
    assert ok.returncode == 0, ok.stderr
    assert str(isolated) in ok.stdout  # the installed copy, not the checkout
    for name in FOREIGN:
        bad = run(f"import {name}")
        assert bad.returncode != 0 and "ModuleNotFoundError" in bad.stderr, name
    script = subprocess.run([str(isolated / "bin" / "threepart"), "solve", "--R1", "10", "--R2", "5",
                             "--b", "1", "--A", "8.67e-6", "--P", "400"], capture_output=True,
                            text=True, cwd=tmp_path)
    assert script.returncode == 0, script.stderr
    # the half-width of this symmetric-load solve, against Hertz-like bounds: b < a < b + R1
    a = float(next(line.split()[1] for line in script.stdout.splitlines()
                   if line.startswith("a ")))
    assert B < a < B + R1

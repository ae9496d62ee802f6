"""Writes that never destroy data: the marker, --force, permissions, leftovers, Ctrl-C.

Every run here uses the fake solvers of :mod:`tests.fakes` on three catalogue
cases, so a whole ``verify`` takes a fraction of a second.
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
import socket
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from threepart import output
from threepart.output import MARKER, OutputExistsError, atomic_dir, read_marker, strict_json
from threepart.problem.catalogue import load_cases
from threepart.reports import figures
from threepart.reports.verify import report as verify

from .fakes import install_fakes

_real_write_report = verify.write_report


@pytest.fixture
def fake_solvers(monkeypatch):
    """Fake solvers on three cases, and a report writer without the (slow) plots."""
    install_fakes(monkeypatch)
    monkeypatch.setattr(verify, "STUDY_CASE", "caseA_moment")
    monkeypatch.setattr(verify, "write_report", _small_report)
    return [c for c in load_cases() if c.name in ("caseA_sym", "slip_Q0.4", "caseA_moment")]


def _small_report(tmp, mode, runs, studies, timings, say):
    """The report's files with the real json but a stand-in plot (drawing takes seconds)."""
    doc = verify.build_report(mode, runs, studies, timings, {"_studies": ["plots/fake.png"]})
    (tmp / "plots").mkdir()
    (tmp / "plots" / "fake.png").write_bytes(b"\x89PNG")
    (tmp / "report.json").write_text(json.dumps(doc), encoding="utf-8")
    (tmp / "report.md").write_text("# report", encoding="utf-8")
    return doc


def _verify(out, fake_solvers, **kw):
    return verify.main(mode="quick", out=out, cases=fake_solvers, quiet=True, **kw)


def _tree(root: Path) -> dict[str, bytes | None]:
    """Every path under ``root`` with its content (None for a directory)."""
    return {str(p.relative_to(root)): (None if p.is_dir() else p.read_bytes())
            for p in sorted(root.rglob("*"))}


def _user_dir(path: Path) -> Path:
    path.mkdir()
    (path / "mine.txt").write_text("keep me")
    (path / ".git").mkdir()
    (path / ".git" / "HEAD").write_text("ref: refs/heads/main")
    return path


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


# ---------------------------------------------------------------------------------------
# the marker and --force
# ---------------------------------------------------------------------------------------
def test_the_marker_lists_every_file_written(tmp_path, fake_solvers, monkeypatch):
    monkeypatch.setattr(verify, "write_report", _real_write_report)   # with every plot
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    marker = read_marker(out)
    assert marker is not None and marker["state"] == "complete" and marker["command"] == "verify"
    written = sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file() and p.name != MARKER)
    assert sorted(marker["files"]) == written and "report.json" in written
    assert marker["dirs"] == ["plots"]
    for name in written:                                    # each with its size and SHA-256 (hashlib)
        data = (out / name).read_bytes()
        assert marker["files"][name] == {"sha256": hashlib.sha256(data).hexdigest(), "size": len(data)}


def test_a_rerun_replaces_threepart_s_own_report_without_force(tmp_path, fake_solvers):
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    (out / "report.md").write_text("# stale")                 # (below: threepart's own, then edited)
    with pytest.raises(OutputExistsError, match=r"holds 'report\.md', which was changed after threepart "
                                                r"wrote it; refusing to replace it"):
        _verify(out, fake_solvers)
    assert (out / "report.md").read_text() == "# stale"       # the user's edit is kept
    (out / "report.md").unlink()                              # a listed file the user removed: nothing lost
    assert _verify(out, fake_solvers) == 0
    assert _verify(out, fake_solvers) == 0                    # and again: a rerun just works
    assert (out / "report.md").read_text() == "# report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]  # no temporary, no .old left behind


def test_force_never_replaces_a_directory_threepart_did_not_write(tmp_path, fake_solvers):
    out = _user_dir(tmp_path / "rep")
    before = _tree(out)
    for force in (False, True):
        with pytest.raises(OutputExistsError,
                           match=r"^`out` = '.*rep' holds '\.git' and no valid \.threepart-output\.json: "
                                 r"threepart did not write it; refusing"):
            _verify(out, fake_solvers, force=force)
        assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]


def test_force_refuses_a_report_that_holds_a_foreign_file(tmp_path, fake_solvers):
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    (out / "plots" / "notes.txt").write_text("my notes")
    before = _tree(out)
    with pytest.raises(OutputExistsError, match=r"holds 'plots/notes\.txt', which threepart did not write"):
        _verify(out, fake_solvers, force=True)
    assert _tree(out) == before
    (out / "plots" / "notes.txt").unlink()
    (out / "extra").mkdir()                                 # an empty directory of the user's
    with pytest.raises(OutputExistsError, match=r"holds 'extra/', which threepart did not write"):
        _verify(out, fake_solvers, force=True)
    assert (out / "extra").is_dir()


def test_a_marker_that_is_not_threepart_s_does_not_count(tmp_path, fake_solvers):
    out = tmp_path / "rep"
    out.mkdir()
    (out / MARKER).write_text('{"tool": "other", "files": ["data.csv"], "dirs": []}')
    (out / "data.csv").write_text("1,2")
    with pytest.raises(OutputExistsError, match=r"no valid \.threepart-output\.json"):
        _verify(out, fake_solvers, force=True)
    assert (out / "data.csv").read_text() == "1,2"


def test_an_empty_directory_is_used_without_force(tmp_path, fake_solvers):
    out = tmp_path / "rep"
    out.mkdir()
    assert _verify(out, fake_solvers) == 0
    assert (out / "report.json").exists() and read_marker(out) is not None
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]


@pytest.mark.parametrize("kind", ["file", "symlink"])
def test_out_that_is_no_directory_is_refused(tmp_path, fake_solvers, kind):
    target = tmp_path / "target"
    _user_dir(target)
    out = tmp_path / "rep"
    if kind == "file":
        out.write_text("a file of the user's")
    else:
        out.symlink_to(target, target_is_directory=True)
    with pytest.raises(OutputExistsError, match="is not a directory" if kind == "file" else "symbolic link"):
        _verify(out, fake_solvers, force=True)
    assert (target / "mine.txt").read_text() == "keep me"


def test_rmtree_is_never_called_on_the_output(tmp_path, fake_solvers, monkeypatch):
    removed: list[str] = []
    real = shutil.rmtree
    monkeypatch.setattr(shutil, "rmtree", lambda p, **k: (removed.append(str(p)), real(p, **k)))
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    assert _verify(out, fake_solvers, force=True) == 0
    assert removed == []

    def half_written(tmp, *a, **k):
        _small_report(tmp, *a, **k)
        raise RuntimeError("disk full")

    monkeypatch.setattr(verify, "write_report", half_written)
    with pytest.raises(RuntimeError, match="disk full"):
        _verify(out, fake_solvers, force=True)
    assert all(any(part.endswith(".tmp") for part in Path(p).parts) for p in removed), removed
    assert removed   # the failed run's temporary plots (below) went through rmtree, nothing else


# ---------------------------------------------------------------------------------------
# crashes, interruptions, leftovers
# ---------------------------------------------------------------------------------------
def test_a_crash_leaves_no_half_written_report(tmp_path, fake_solvers, monkeypatch):
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    before = _tree(out)

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(verify, "write_report", boom)
    with pytest.raises(RuntimeError, match="disk full"):
        _verify(out, fake_solvers, force=True)
    assert _tree(out) == before  # the old report is untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]


def test_ctrl_c_prints_one_line_exits_130_and_leaves_no_temporary(tmp_path, fake_solvers, monkeypatch,
                                                                   capsys):
    from threepart.cli import main

    def interrupted(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(verify, "run", interrupted)
    monkeypatch.chdir(tmp_path)
    try:
        status = main(["verify", "--quick", "--out", "rep"])
    except KeyboardInterrupt:
        pytest.fail("KeyboardInterrupt escaped main()")
    assert status == 130
    assert capsys.readouterr().err == "threepart verify: interrupted\n"
    assert list(tmp_path.iterdir()) == []


KILLED_WRITER = """
import os, sys
from pathlib import Path
from threepart.output import atomic_dir, dirs
out, stage = Path(sys.argv[1]), sys.argv[2]
dirs.clean_stale = lambda out: []         # keep the leftovers of the earlier killed runs here
with atomic_dir(out, command="verify") as tmp:
    (tmp / "plots").mkdir()
    (tmp / "plots" / "a.png").write_bytes(b"png")
    (tmp / "report.md").write_text("half")
    if stage == "writing":
        os._exit(9)                       # killed while writing
    real = os.rename
    os.rename = lambda a, b: os._exit(9)  # killed after the seal, before the rename
"""


def _killed_run(out: Path, stage: str) -> Path:
    """The leftover of a real run of :func:`atomic_dir` killed at ``stage`` (``writing`` or ``sealed``)."""
    before = set(out.parent.iterdir()) if out.parent.exists() else set()
    proc = subprocess.run([sys.executable, "-c", KILLED_WRITER, str(out), stage], capture_output=True)
    assert proc.returncode == 9, proc.stderr
    (left,) = set(out.parent.iterdir()) - before
    return left


def test_leftovers_of_killed_runs_are_removed_only_if_provably_ours(tmp_path, fake_solvers):
    out = tmp_path / "rep"
    writing, sealed = _killed_run(out, "writing"), _killed_run(out, "sealed")
    assert read_marker(writing)["state"] == "writing" and read_marker(sealed)["state"] == "complete"
    other = _killed_run(tmp_path / "report", "writing")                 # another target: not this run's
    users = tmp_path / ".rep.mine.tmp"                                  # no marker
    users.mkdir()
    (users / "thesis.tex").write_text("keep me")
    assert _verify(out, fake_solvers) == 0
    assert not writing.exists() and not sealed.exists()
    assert other.exists() and (users / "thesis.tex").read_text() == "keep me"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([".rep.mine.tmp", other.name, "rep"])


def test_a_forged_marker_in_a_temporary_sibling_protects_nothing(tmp_path):
    """A marker written by hand (or copied from a real leftover) does not make a directory ours."""
    out = tmp_path / "rep"
    real = _killed_run(out, "writing")
    forged = tmp_path / ".rep.f0rg3d.tmp"
    (forged / "sub").mkdir(parents=True)
    (forged / "sub" / "thesis.tex").write_text("keep me")
    (forged / MARKER).write_text((real / MARKER).read_text())       # a real marker, copied
    forged2 = tmp_path / ".rep.h4nd.tmp"
    (forged2 / "data").mkdir(parents=True)
    (forged2 / "data" / "x.csv").write_text("1,2")
    (forged2 / MARKER).write_text(json.dumps(
        {"tool": "threepart", "format": output.MARKER_FORMAT, "command": "verify", "state": "writing",
         "target": "rep", "pid": _dead_pid(), "host": socket.gethostname(),
         "files": {}, "dirs": [], "path": str(forged2), "mac": "0" * 64}))
    assert output.clean_stale(out) == [real]
    assert (forged / "sub" / "thesis.tex").read_text() == "keep me"
    assert (forged2 / "data" / "x.csv").read_text() == "1,2"


def test_an_old_directory_holding_a_foreign_file_is_left(tmp_path):
    out = tmp_path / "rep"
    write = "import sys; from threepart.output import atomic_dir\n" \
            "with atomic_dir(sys.argv[1], command='verify') as tmp: (tmp / 'report.json').write_text('{}')"
    for name, foreign in ((".rep.old-1-2", True), (".rep.old-3-4", False)):
        subprocess.run([sys.executable, "-c", write, str(out)], check=True)   # by a process now gone
        os.rename(out, tmp_path / name)            # as a run killed while swapping leaves it
        if foreign:
            (tmp_path / name / "mine.txt").write_text("keep me")
    assert output.clean_stale(out) == [tmp_path / ".rep.old-3-4"]
    assert (tmp_path / ".rep.old-1-2" / "mine.txt").read_text() == "keep me"
    assert (tmp_path / ".rep.old-1-2" / "report.json").read_text() == "{}"


# ---------------------------------------------------------------------------------------
# permissions
# ---------------------------------------------------------------------------------------
@pytest.fixture
def umask():
    saved = os.umask(0o022)
    os.umask(saved)

    def set_(mask: int) -> None:
        os.umask(mask)

    yield set_
    os.umask(saved)


@pytest.mark.parametrize("mask", [0o022, 0o027])
def test_the_report_has_normal_permissions(tmp_path, fake_solvers, umask, mask):
    umask(mask)
    out = tmp_path / "rep"
    assert _verify(out, fake_solvers) == 0
    for p in [out, *out.rglob("*")]:
        mode = stat.S_IMODE(p.stat().st_mode)
        want = (0o777 if p.is_dir() else 0o666) & ~mask
        assert mode == want, f"{p.relative_to(tmp_path)}: {oct(mode)} != {oct(want)}"


def test_atomic_dir_on_its_own(tmp_path):
    out = tmp_path / "figs"
    with atomic_dir(out, command="test") as tmp:
        assert tmp.parent == tmp_path and tmp.name.startswith(".figs.") and tmp.name.endswith(".tmp")
        assert read_marker(tmp)["state"] == "writing"   # marked from its creation
        (tmp / "a.txt").write_text("a")
    assert list(read_marker(out)["files"]) == ["a.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["figs"]


# ---------------------------------------------------------------------------------------
# the command line
# ---------------------------------------------------------------------------------------
def test_cli_reruns_and_refuses_a_planted_file(tmp_path, fake_solvers, capsys, monkeypatch):
    import functools

    from threepart.cli import main

    monkeypatch.setattr(verify, "main", functools.partial(verify.main, cases=fake_solvers, quiet=True))
    out = tmp_path / "rep"
    assert main(["verify", "--quick", "--out", str(out)]) == 0
    assert main(["verify", "--quick", "--out", str(out)]) == 0      # the rerun replaces its own report
    capsys.readouterr()
    (out / "plots" / "mine.txt").write_text("keep me")
    for force in ([], ["--force"]):
        assert main(["verify", "--quick", "--out", str(out), *force]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith("threepart verify: error:")
        assert "holds 'plots/mine.txt', which threepart did not write" in err
        assert (out / "plots" / "mine.txt").read_text() == "keep me"


def test_verify_out_dot_force_in_a_user_directory_refuses_and_leaves_everything(tmp_path, monkeypatch,
                                                                                  fake_solvers, capsys):
    from threepart.cli import main

    project = _user_dir(tmp_path / "project")
    (project / "src").mkdir()
    (project / "src" / "model.py").write_text("x = 1")
    before = _tree(project)
    monkeypatch.chdir(project)
    assert main(["verify", "--out", ".", "--force"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{str(project)!r} holds '.git'" in err
    assert _tree(project) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["project"]


def test_figures_force_leaves_the_user_s_file(tmp_path, capsys):
    from threepart.cli import main

    out = _user_dir(tmp_path / "figs")
    before = _tree(out)
    assert main(["figures", "--out", str(out), "--force"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "holds '.git'" in err and "threepart did not write it" in err
    assert _tree(out) == before


def test_figures_write_the_marker(tmp_path, monkeypatch):
    monkeypatch.setattr(figures, "_draw", lambda cs, which, field, path: path.write_bytes(b"png"))
    out = tmp_path / "figs"
    assert figures.main(out=out, sie=False) == 0
    assert sorted(read_marker(out)["files"]) == ["figures.json", "pressure_a.png", "pressure_b.png",
                                                 "shear_a.png", "shear_b.png"]
    assert figures.main(out=out, sie=False) == 0          # a rerun replaces its own figures
    (out / "shear_a.png").write_bytes(b"edited")
    with pytest.raises(OutputExistsError, match="'shear_a.png', which was changed after threepart"):
        figures.main(out=out, force=True, sie=False)
    assert (out / "shear_a.png").read_bytes() == b"edited"


def test_strict_json_writes_infinity_as_null():
    def refuse(name):
        raise ValueError(f"not JSON: {name}")

    text = strict_json({"R": float("inf"), "s": [1.0, -float("inf")], "n": {"x": float("nan")}})
    assert json.loads(text, parse_constant=refuse) == {"R": None, "s": [1.0, None], "n": {"x": None}}

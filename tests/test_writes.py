"""Every file threepart writes goes through :mod:`threepart.output`: atomic, guarded, checksummed.

The references here are independent of the code under test: ``hashlib`` for
the checksums, the bytes a test planted for what must survive, meshio's reader
for a written mesh, and a real process killed with ``os._exit`` for a leftover.
A full disk is a ``fsync`` that raises ``ENOSPC`` for the files it names.
"""
from __future__ import annotations

import errno
import fnmatch
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

from threepart import output
from threepart.output import (LEDGER, MARKER, OutputExistsError, atomic_dir, check_out, read_marker,
                              scratch_dir, write_file)

ROOT = Path(__file__).resolve().parents[1]
GEOM = ["--R1", "10", "--R2", "10", "--b", "2", "--P", "100", "--E", "200000", "--nu", "0.3"]


def full_disk(monkeypatch, pattern: str) -> list[str]:
    """Make ``os.fsync`` fail with ENOSPC for files whose name matches ``pattern``; return their names."""
    real = os.fsync
    hit: list[str] = []

    def fsync(fd: int) -> None:
        name = os.path.basename(os.readlink(f"/proc/self/fd/{fd}"))
        if fnmatch.fnmatch(name, pattern):
            hit.append(name)
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    return hit


def _report(out: Path) -> Path:
    with atomic_dir(out, command="verify") as tmp:
        (tmp / "plots").mkdir()
        (tmp / "plots" / "a.png").write_bytes(b"\x89PNG")
        (tmp / "report.md").write_text("# report")
    return out


def _tree(root: Path) -> dict[str, bytes | None]:
    return {str(p.relative_to(root)): (None if p.is_dir() else p.read_bytes())
            for p in sorted(root.rglob("*"))}


# ---------------------------------------------------------------------------------------
# single files
# ---------------------------------------------------------------------------------------
def test_write_file_creates_replaces_its_own_and_refuses_everything_else(tmp_path):
    f = tmp_path / "q.csv"
    write_file(f, "x,p\n1,2\n", arg="--csv")
    ledger = json.loads((tmp_path / LEDGER).read_text())
    assert ledger["files"] == {"q.csv": {"sha256": hashlib.sha256(b"x,p\n1,2\n").hexdigest(), "size": 8}}
    write_file(f, "x,p\n3,4\n", arg="--csv")                    # threepart's own, unchanged: replaced
    assert f.read_text() == "x,p\n3,4\n"
    f.write_text("my edit\n")
    with pytest.raises(OutputExistsError, match=r"^`--csv` = '.*q\.csv' exists and was changed after "
                                                r"threepart wrote it; refusing to overwrite it"):
        write_file(f, "new", arg="--csv")
    assert f.read_text() == "my edit\n"
    mine = tmp_path / "mine.csv"
    mine.write_text("keep me")
    with pytest.raises(OutputExistsError, match=r"`path` = '.*mine\.csv' exists and was not written by "
                                                r"threepart"):
        write_file(mine, "new")
    assert mine.read_text() == "keep me"
    write_file(mine, "new", overwrite=True)                     # replaced only when asked
    assert mine.read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == [LEDGER, "mine.csv", "q.csv"]  # no temporary


def test_write_file_never_writes_through_a_symbolic_link(tmp_path):
    target = tmp_path / "thesis.tex"
    target.write_text("keep me")
    link = tmp_path / "q.csv"
    link.symlink_to(target)
    for overwrite in (False, True):
        with pytest.raises(OutputExistsError, match="exists and is not a regular file"):
            write_file(link, "x", arg="--csv", overwrite=overwrite)
    assert target.read_text() == "keep me" and link.is_symlink()


def test_a_forged_or_copied_ledger_is_not_trusted(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    write_file(a / "q.csv", "1,2\n")
    shutil.copy2(a / "q.csv", b / "q.csv")                       # a copied file and its copied ledger
    shutil.copy2(a / LEDGER, b / LEDGER)
    (b / "q.csv").write_text("mine\n")                           # then a forged entry for the user's file
    doc = json.loads((b / LEDGER).read_text())
    doc["files"]["q.csv"] = {"sha256": hashlib.sha256(b"mine\n").hexdigest(), "size": 5}
    (b / LEDGER).write_text(json.dumps(doc))
    for ledger in (doc, {**doc, "path": str(b)}, {**doc, "mac": "0" * 64}):
        (b / LEDGER).write_text(json.dumps(ledger))
        with pytest.raises(OutputExistsError, match=r"\.threepart-files\.json' is not threepart's"):
            write_file(b / "q.csv", "new\n", arg="--csv")
        assert (b / "q.csv").read_text() == "mine\n"
    copied = tmp_path / "c"
    shutil.copytree(a, copied)                                   # a copy verbatim: not ours there either
    with pytest.raises(OutputExistsError, match="is not threepart's"):
        write_file(copied / "q.csv", "new\n")


def test_a_run_killed_right_after_the_rename_still_owns_its_file(tmp_path, monkeypatch):
    f = tmp_path / "q.csv"
    write_file(f, "old\n")
    real = os.replace

    def killed_after(src, dst):
        real(src, dst)
        if Path(dst) == f:
            raise KeyboardInterrupt                              # before the ledger records it

    monkeypatch.setattr(os, "replace", killed_after)
    with pytest.raises(KeyboardInterrupt):
        write_file(f, "new\n")
    monkeypatch.undo()
    assert f.read_text() == "new\n"
    write_file(f, "newer\n")                                     # still threepart's own
    assert f.read_text() == "newer\n"


def test_a_full_disk_leaves_no_half_written_file(tmp_path, monkeypatch):
    f = tmp_path / "q.csv"
    write_file(f, "old\n", arg="--csv")
    hit = full_disk(monkeypatch, ".q.csv.*.part")
    with pytest.raises(OSError, match=r"^cannot write `--csv` = '.*q\.csv': No space left on device$") as info:
        write_file(f, "new\n" * 1000, arg="--csv")
    assert hit and info.value.errno == errno.ENOSPC
    assert f.read_text() == "old\n"                              # untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == [LEDGER, "q.csv"]
    monkeypatch.undo()
    write_file(f, "new\n", arg="--csv")                          # and still threepart's own
    assert f.read_text() == "new\n"


def test_cli_csv_on_a_full_disk_or_in_a_missing_directory_is_one_line(tmp_path, monkeypatch, capsys):
    from threepart.cli import main

    missing = "/nonexistent/dir/q.csv"
    assert main(["solve", *GEOM, "--grid", "5", "--csv", missing]) == 2
    assert capsys.readouterr().err == (f"threepart solve: error: `--csv` = '{missing}': directory "
                                       "does not exist\n")
    new = tmp_path / "q.csv"
    full_disk(monkeypatch, ".q.csv.*.part")
    assert main(["solve", *GEOM, "--grid", "5", "--csv", str(new)]) == 2
    err = capsys.readouterr().err
    assert err == f"threepart solve: error: cannot write `--csv` = '{new}': No space left on device\n"
    assert list(tmp_path.iterdir()) == []                        # no truncated file, no temporary


def test_write_fields_can_be_rerun(tmp_path, monkeypatch):
    """The README walkthrough: ``write_fields(res.fields, "contact.vtu")`` twice."""
    import meshio

    from threepart.fem.export import Fields, write_fields

    monkeypatch.chdir(tmp_path)
    p = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    fields = Fields(points=p, triangles=np.array([[0, 1, 2], [1, 3, 2]]),
                    displacement=0.01 * p[:, ::-1], stress=np.arange(8.0).reshape(2, 4))
    for _ in range(2):
        assert write_fields(fields, "contact.vtu") == Path("contact.vtu")
    m = meshio.read("contact.vtu")
    assert np.array_equal(m.point_data["displacement"][:, :2], fields.displacement)
    assert np.array_equal(m.cell_data["sigma_yy"][0], fields.stress[:, 1])
    Path("contact.vtu").write_text("edited in ParaView")
    with pytest.raises(OutputExistsError, match=r"`path` = 'contact\.vtu' exists and was changed"):
        write_fields(fields, "contact.vtu")
    assert Path("contact.vtu").read_text() == "edited in ParaView"
    write_fields(fields, "contact.vtu", overwrite=True)          # replaced only when asked
    assert np.array_equal(meshio.read("contact.vtu").points[:, :2], p)


def test_the_mesh_manifest_is_written_through_the_one_writer(tmp_path):
    from threepart.meshes import write_manifest

    path = tmp_path / "manifest.json"
    entries = [{"file": "reference.msh", "nodes": 3}]
    write_manifest(entries, path)
    write_manifest(entries, path)                                # threepart's own: a rerun works
    assert json.loads(path.read_text()) == {"meshes": entries}
    path.write_text('{"meshes": []}')
    with pytest.raises(OutputExistsError, match="was changed after threepart wrote it"):
        write_manifest(entries, path)
    assert path.read_text() == '{"meshes": []}'
    write_manifest(entries, path, overwrite=True)
    assert json.loads(path.read_text()) == {"meshes": entries}


# ---------------------------------------------------------------------------------------
# directories: markers that are refused, not trusted
# ---------------------------------------------------------------------------------------
def test_a_hand_written_marker_with_the_right_checksums_is_refused(tmp_path):
    """Today's hole: a marker written by hand let ``--force`` delete the user's file."""
    out = tmp_path / "rep"
    out.mkdir()
    (out / "data.csv").write_text("1,2")
    digest = {"sha256": hashlib.sha256(b"1,2").hexdigest(), "size": 3}
    for extra in ({}, {"path": str(out), "mac": "f" * 64}):
        (out / MARKER).write_text(json.dumps(
            {"tool": "threepart", "format": output.MARKER_FORMAT, "command": "verify",
             "state": "complete", "target": "rep", "files": {"data.csv": digest}, "dirs": [], **extra}))
        with pytest.raises(OutputExistsError, match=r"holds a \.threepart-output\.json that threepart did "
                                                    r"not write there"):
            check_out(out, force=True)
        with pytest.raises(OutputExistsError):
            with atomic_dir(out, force=True, command="verify") as tmp:
                (tmp / "report.md").write_text("x")
        assert (out / "data.csv").read_text() == "1,2"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]


def test_a_copied_report_is_refused_and_the_original_reruns(tmp_path):
    out = _report(tmp_path / "rep")
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    before = _tree(copy)
    with pytest.raises(OutputExistsError, match="did not write there"):
        _report(copy)
    assert _tree(copy) == before
    assert _report(out) == out                                   # the original is still ours


def test_another_command_s_output_is_not_replaced(tmp_path):
    out = _report(tmp_path / "rep")                              # written by `verify`
    before = _tree(out)
    with pytest.raises(OutputExistsError, match=r"holds the output of `threepart verify`, not of "
                                                r"`threepart figures`"):
        with atomic_dir(out, command="figures") as tmp:
            (tmp / "pressure_a.png").write_bytes(b"png")
    assert _tree(out) == before


def test_a_listed_file_turned_symbolic_link_is_refused(tmp_path):
    out = _report(tmp_path / "rep")
    target = tmp_path / "thesis.md"
    target.write_text("keep me")
    (out / "report.md").unlink()
    (out / "report.md").symlink_to(target)
    with pytest.raises(OutputExistsError, match=r"holds 'report\.md', a symbolic link"):
        _report(out)
    assert target.read_text() == "keep me" and (out / "report.md").is_symlink()


def test_an_old_format_marker_is_refused_and_says_how_to_proceed(tmp_path, capsys):
    from threepart.cli import main

    out = tmp_path / "figs"
    out.mkdir()
    (out / "pressure_a.png").write_bytes(b"png")
    (out / MARKER).write_text(json.dumps({"tool": "threepart", "format": 1, "command": "figures",
                                          "state": "complete", "files": ["pressure_a.png"], "dirs": []}))
    before = _tree(out)
    assert main(["figures", "--out", str(out), "--force"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "of an older threepart (format 1, no checksums)" in err
    assert "remove it yourself, or choose another --out" in err
    assert _tree(out) == before


def test_a_full_disk_while_marking_leaves_nothing(tmp_path, monkeypatch):
    out = _report(tmp_path / "rep")
    before = _tree(out)
    hit = full_disk(monkeypatch, MARKER + ".part")
    with pytest.raises(OSError, match=r"^cannot write .*No space left on device$") as info:
        _report(out)
    assert hit and "\n" not in str(info.value) and str(tmp_path) in str(info.value)
    assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]  # no temporary, no .part
    monkeypatch.undo()
    assert _report(out) == out


# ---------------------------------------------------------------------------------------
# scratch directories (gmsh's)
# ---------------------------------------------------------------------------------------
KILLED_MESHER = """
import os
from threepart.output import scratch_dir
with scratch_dir("threepart-testmesh-") as d:
    (d / "substrate.msh").write_text("half a mesh")
    print(d, flush=True)
    os._exit(9)
"""


def test_scratch_dirs_of_killed_runs_are_cleaned_by_the_next(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    monkeypatch.setattr(tempfile, "tempdir", None)
    proc = subprocess.run([sys.executable, "-c", KILLED_MESHER], capture_output=True, text=True,
                          env={**os.environ, "TMPDIR": str(tmp_path)})
    assert proc.returncode == 9, proc.stderr
    leaked = Path(proc.stdout.strip())
    assert leaked.parent == tmp_path and (leaked / "substrate.msh").exists()
    users = tmp_path / "threepart-testmesh-mine"                 # the prefix, but no marker of ours
    users.mkdir()
    (users / "notes.txt").write_text("keep me")
    with scratch_dir("threepart-testmesh-") as live:
        assert not leaked.exists()
        with scratch_dir("threepart-testmesh-") as other:        # a live one is never removed
            assert live.exists() and other != live
        assert live.exists() and not other.exists()
    assert not live.exists() and (users / "notes.txt").read_text() == "keep me"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["threepart-testmesh-mine"]

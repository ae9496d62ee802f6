"""Another code's run cached by its input (issue 41): the same deck is not run twice.

The references are the bytes the run itself wrote and how many times the run was
called: a hit writes back exactly what the run wrote, and never calls it; any
change of the input, a failed run or a damaged entry runs the code again.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from threepart import cache
from threepart.errors import CcxError


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv(cache.CACHE_VARIABLE, str(tmp_path / "cache"))


class Code:
    """Stands in for ccx: writes a result beside the input and counts its runs."""

    def __init__(self, workdir: Path, fail: bool = False):
        self.workdir, self.fail, self.runs = workdir, fail, 0

    def __call__(self) -> None:
        self.runs += 1
        (self.workdir / "job.frd").write_bytes(bytes(range(256)) * 3 + b"run %d" % self.runs)
        (self.workdir / "job.dat").write_text("  displacements\n 1  0.1  0.2\n")
        if self.fail:
            raise CcxError("ccx failed on job.inp")


def _job(tmp_path: Path, name: str, deck: str = "*NODE\n1, 0, 0\n") -> Path:
    d = tmp_path / name
    d.mkdir()
    (d / "job.inp").write_text(deck)
    return d


def test_a_second_identical_run_writes_back_what_the_first_wrote_without_running(tmp_path):
    first = _job(tmp_path, "first")
    code = Code(first)
    assert cache.cached_run("ccx", {"deck": "d"}, first, code) is False
    assert code.runs == 1 and not cache.restored(first)
    wrote = {f.name: f.read_bytes() for f in first.iterdir()}

    second = _job(tmp_path, "second")
    other = Code(second)
    assert cache.cached_run("ccx", {"deck": "d"}, second, other) is True
    assert other.runs == 0 and cache.restored(second)
    assert {f.name: f.read_bytes() for f in second.iterdir()} == wrote     # the input too, unchanged


def test_another_input_runs_again(tmp_path):
    code = Code(_job(tmp_path, "a"))
    cache.cached_run("ccx", {"deck": "d", "ccx": "Version 2.20"}, code.workdir, code)
    again = Code(_job(tmp_path, "b"))
    assert cache.cached_run("ccx", {"deck": "d", "ccx": "Version 2.21"}, again.workdir, again) is False
    assert again.runs == 1


def test_a_failed_run_is_not_kept(tmp_path):
    failing = Code(_job(tmp_path, "a"), fail=True)
    with pytest.raises(CcxError):
        cache.cached_run("ccx", {"deck": "d"}, failing.workdir, failing)
    assert not [e for e in cache.entries() if e.ours]
    retry = Code(_job(tmp_path, "b"))
    assert cache.cached_run("ccx", {"deck": "d"}, retry.workdir, retry) is False and retry.runs == 1


def test_a_damaged_entry_runs_again_and_is_replaced(tmp_path):
    code = Code(_job(tmp_path, "a"))
    cache.cached_run("ccx", {"deck": "d"}, code.workdir, code)
    (entry,) = [e for e in cache.entries() if e.ours]
    data = bytearray(entry.path.read_bytes())
    data[data.index(bytes(range(256))) + 100] ^= 0xFF        # a byte of the stored result
    entry.path.write_bytes(bytes(data))
    again = Code(_job(tmp_path, "b"))
    assert cache.cached_run("ccx", {"deck": "d"}, again.workdir, again) is False and again.runs == 1
    assert [e.ours for e in cache.entries()] == [True]

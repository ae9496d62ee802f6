"""The test command itself (`python -m pytest` with pyproject.toml's addopts): a worker that dies, and
what pytest rewrites."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import threepart.fem.solve
import threepart.reports.verify.report

ROOT = Path(__file__).resolve().parents[1]
#: the longest the small run below may take: a hang guard (it takes seconds; pytest-xdist 3.8.0's
#: replacement of a dead worker under --dist loadfile could instead wait forever)
RUN_GUARD_S = 600

FILES = {
    "test_a.py": "def test_a1(): pass\ndef test_a2(): pass\n",
    "test_b.py": "import os\ndef test_b1(): pass\ndef test_b2(): os._exit(1)\ndef test_b3(): pass\n",
    "test_c.py": "def test_c1(): pass\n",
}


def test_a_worker_that_dies_ends_the_run_at_once_and_is_named(tmp_path):
    """A test that kills its worker (os._exit) under the project's own options: the run ends,
    status 1, naming the test and the worker once; no replacement worker is started (nor the
    test run again on one)."""
    for name, text in FILES.items():
        (tmp_path / name).write_text(text)
    run = subprocess.run([sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"),
                          "--rootdir", str(tmp_path), "-p", "no:cacheprovider", "-q", *FILES],
                         cwd=tmp_path, capture_output=True, text=True, timeout=RUN_GUARD_S,
                         start_new_session=True)
    out = run.stdout + run.stderr
    assert run.returncode == 1, out                              # tests failed, not interrupted (2)
    assert "replacing crashed worker" not in out, out
    # the failure's own section names the worker and the test once; the short summary names the
    # test once more (its width follows the terminal's, so it is not counted for the worker)
    body = [line for line in out.splitlines() if line.startswith("worker ")]
    assert len(body) == 1 and re.fullmatch(r"worker 'gw\d' crashed while running 'test_b.py::test_b2'",
                                           body[0]), out
    assert out.count("FAILED test_b.py::test_b2") == 1, out
    assert out.count("node down") == 1, out


def test_pytest_rewrites_the_tests_asserts_but_not_the_libraries():
    """tests/conftest.py leaves the installed libraries to plain import (issue 41: rewriting them took
    4 of each worker's 12.6 s of collection): pytest's rewritten modules hold its helper
    ``@py_builtins``: this test file does, a solver's and the report's modules do not."""
    assert "@py_builtins" in vars(sys.modules[__name__])
    for module in (threepart.fem.solve, threepart.reports.verify.report):
        assert "@py_builtins" not in vars(module), module.__name__


def test_auto_starts_a_worker_per_core_and_one_more(request):
    """``-n auto`` (the test command's addopts) asks pytest-xdist's hook for its count: the cores this
    process may run on and one more (tests/conftest.py), so that a worker waiting on a subprocess
    leaves its core to another."""
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    assert request.config.hook.pytest_xdist_auto_num_workers(config=request.config) == cores + 1

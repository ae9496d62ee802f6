"""Shared test set-up: threepart's per-user signing key and its cache live in temporary directories.

Every output threepart writes is signed with a per-user key
(:func:`threepart.output.state_dir`); the tests keep theirs out of the home
directory. The FE condensations are cached on disk (:mod:`threepart.cache`): a test run
never writes the user's cache, but shares one temporary cache between its xdist workers,
unless ``THREEPART_CACHE`` names one. Worker processes (xdist, dask, subprocesses)
inherit both variables.
"""
from __future__ import annotations

import os
import tempfile

import pytest


#: the temporary cache this run made (removed at its end), if ``THREEPART_CACHE`` was unset
_RUN_CACHE: list[tempfile.TemporaryDirectory] = []
#: the thread pools of the BLAS (NumPy's and SciPy's OpenBLAS, CHOLMOD's system OpenBLAS) and of
#: OpenMP (libgomp): one thread each in an xdist worker, unless the variable is set already
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
#: pytest's cache key of each test file's seconds (setup, call and teardown of its tests) in the
#: runs so far: an order for the files only, never a limit of any test
FILE_SECONDS = "threepart/file_seconds"
#: the seconds of each file in this run (the controller's, or the single process's)
_SECONDS: dict[str, float] = {}
#: the files' seconds the controller read when the run began, handed to every worker
_ORDER: dict[str, float] = {}
#: a first run's order (a fresh clone: no seconds cached yet), the longest files of a measured run
#: first (issue 41, 2026-11-29: test_map 53 s, mypy 20 s, test_fem 20 s, ..., the wheel 11 s):
#: xdist's own order, by the number of tests, would start mypy's 1 test and the wheel's 3 near
#: the end of the run
FIRST_RUN_ORDER = ("tests/test_map.py", "tests/test_typing.py", "tests/test_fem.py",
                   "tests/test_finite_slope.py", "tests/test_fem_friction.py", "tests/test_fem_steady.py",
                   "tests/test_finite.py", "tests/test_cli.py", "tests/test_cli_cycle.py",
                   "tests/test_examples.py", "tests/test_plots_speed.py", "tests/test_verify_speed.py",
                   "tests/test_install.py")


def _file_seconds(config: pytest.Config) -> dict[str, float]:
    """The files' seconds of the runs so far (empty on the first run or without the cache)."""
    cache = getattr(config, "cache", None)
    return dict(cache.get(FILE_SECONDS, {})) if cache is not None else {}


#: the installed packages whose modules pytest marks for assertion rewriting, only because they
#: hold a pytest plugin (pytest marks a plugin's whole distribution): their library modules hold
#: no test. Rewriting them took 4 of the 12.6 s each worker spent collecting (issue 41), every
#: run again where ``PYTHONDONTWRITEBYTECODE`` keeps pytest from caching the rewritten code
LIBRARIES_NOT_REWRITTEN = ("threepart", "closedform", "sie", "fem", "meshes", "reports", "hypothesis")


def _rewrite_only_tests(config: pytest.Config) -> None:
    """Leave the libraries of :data:`LIBRARIES_NOT_REWRITTEN` to plain import from here on.

    The test files (``python_files``), the conftest files and the plugin modules already
    imported keep pytest's assertion rewriting; a library imported later by a test is compiled
    as Python compiles it. pytest has no public call to unmark a name: without its
    ``_must_rewrite`` set (another pytest), nothing changes but the time.
    """
    marked = getattr(getattr(config.pluginmanager, "rewrite_hook", None), "_must_rewrite", None)
    if isinstance(marked, set):
        marked.difference_update({name for name in marked
                                  if name.split(".")[0] in LIBRARIES_NOT_REWRITTEN})


#: xdist workers of ``-n auto`` beyond the cores: a worker waiting on a subprocess, a cluster or
#: a file leaves its core to another (issue 41, 2026-11-29, 2 cores: alone 224 s against 226 s
#: with a worker per core; beside two CPU-bound jobs 6 min 15 s against 7 min 23 s, a larger
#: share of a shared machine). ``--maxprocesses`` still caps the count
WORKERS_BEYOND_CORES = 1


def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """``-n auto``: one worker per core this process may run on, and :data:`WORKERS_BEYOND_CORES`."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    return cores + WORKERS_BEYOND_CORES


def pytest_configure(config: pytest.Config) -> None:
    """On the controller, before the xdist workers start: one BLAS thread a worker, one cache a run.

    ``-n auto`` starts a worker per core and one more; each worker's OpenBLAS would start a thread per core
    too, and OpenBLAS's threads spin while they wait: on the 2-core machine a 350 x 350
    ``numpy.linalg.solve`` took 28 ms with 2 threads a process at load 6 against 2.3 ms with one
    (tests/steady_march.py solves hundreds). The workers (and their subprocesses) inherit the
    variables; ``-n 0`` leaves the threads alone. In every process, before any test file is
    imported: pytest rewrites the tests' asserts only (:func:`_rewrite_only_tests`).
    """
    _rewrite_only_tests(config)
    if hasattr(config, "workerinput"):
        return
    if getattr(config.option, "numprocesses", None):
        for name in THREAD_VARIABLES:
            os.environ.setdefault(name, "1")
        # a rank for each of the first run's files, in place of the seconds it does not have
        first = {path: float(len(FIRST_RUN_ORDER) - k) for k, path in enumerate(FIRST_RUN_ORDER)}
        _ORDER.update(_file_seconds(config) or first)
        if _ORDER:                     # the longest files first (below), not the most tests first
            config.option.loadscopereorder = False
    if os.environ.get("THREEPART_CACHE"):
        return
    _RUN_CACHE.append(tempfile.TemporaryDirectory(prefix="threepart-test-cache-"))
    os.environ["THREEPART_CACHE"] = _RUN_CACHE[0].name


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """The files that took longest in the runs so far first, each file's tests in their order.

    ``--dist loadfile`` hands out whole files in this order (xdist's own order, by the number of
    tests, left the mypy, wheel and wide-draw files of one to four long tests for last), so a
    run does not end with one worker on a long file while the other idles. A file not timed yet
    keeps its place after the timed ones. The workers take the seconds the controller read at the
    start (:func:`pytest_configure_node`), not the cache, which another run may write meanwhile:
    all collect alike.
    """
    worker = getattr(config, "workerinput", None)
    seconds = worker.get(FILE_SECONDS, {}) if worker is not None else _file_seconds(config)
    if seconds:
        items.sort(key=lambda item: -seconds.get(item.nodeid.split("::")[0], 0.0))


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node) -> None:
    """pytest-xdist, on the controller: each worker gets the files' seconds read at the start."""
    node.workerinput[FILE_SECONDS] = dict(_ORDER)


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    """Add a test's phase to its file's seconds (in the controller, the workers' reports too)."""
    path = report.nodeid.split("::")[0]
    _SECONDS[path] = _SECONDS.get(path, 0.0) + report.duration


def pytest_unconfigure(config: pytest.Config) -> None:
    """Remove the run's temporary cache (the controller's, after its workers have ended)."""
    while _RUN_CACHE:
        os.environ.pop("THREEPART_CACHE", None)
        _RUN_CACHE.pop().cleanup()


@pytest.fixture(scope="session", autouse=True)
def threepart_state_dir():
    """``THREEPART_STATE_DIR`` for the whole session, in a temporary directory."""
    saved = os.environ.get("THREEPART_STATE_DIR")
    with tempfile.TemporaryDirectory(prefix="threepart-test-state-") as d:
        os.environ["THREEPART_STATE_DIR"] = d
        yield d
        if saved is None:
            os.environ.pop("THREEPART_STATE_DIR", None)
        else:
            os.environ["THREEPART_STATE_DIR"] = saved


@pytest.hookimpl(trylast=True)
def pytest_sessionfinish(session: pytest.Session) -> None:
    """Collect the session's garbage now, then freeze what is left, so the end of a worker is quick.

    pytest's own clean-up at unconfigure collects five times over (to report unraisable
    exceptions); in an xdist worker that holds dask, numpy and the solvers, on a loaded
    machine, that took over 5 s, and execnet sends a worker still busy 5 s after the run's end
    SIGINT, then SIGKILL (seen with strace: the worker in ``gc_collect_harder``). Here the run is
    not over yet (xdist reports it finished after this hook): the collection runs, with the
    unraisable-exception hook still installed, and unconfigure's collections find only what
    came after.
    """
    import gc

    cache = getattr(session.config, "cache", None)
    if _SECONDS and cache is not None and not hasattr(session.config, "workerinput"):
        cache.set(FILE_SECONDS, {**_file_seconds(session.config), **_SECONDS})
    gc.collect()
    gc.freeze()

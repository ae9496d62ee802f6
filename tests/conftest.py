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


def pytest_configure(config: pytest.Config) -> None:
    """On the controller, before the xdist workers start: one temporary cache for the whole run."""
    if hasattr(config, "workerinput") or os.environ.get("THREEPART_CACHE"):
        return
    _RUN_CACHE.append(tempfile.TemporaryDirectory(prefix="threepart-test-cache-"))
    os.environ["THREEPART_CACHE"] = _RUN_CACHE[0].name


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

    gc.collect()
    gc.freeze()

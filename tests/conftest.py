"""Shared test set-up: threepart's per-user signing key lives in a temporary directory.

Every output threepart writes is signed with a per-user key
(:func:`threepart.output.state_dir`); the tests keep theirs out of the home
directory. Worker processes (dask, subprocesses) inherit the variable.
"""
from __future__ import annotations

import os
import tempfile

import pytest


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

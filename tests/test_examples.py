"""The examples run by hand (``examples/``): what they do where their extra is missing."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: pytest on the tamaas example in a fresh interpreter where ``import tamaas`` fails, as it does
#: without the bench extra (whether or not this environment has it)
WITHOUT_TAMAAS = """
import sys
sys.modules["tamaas"] = None      # import tamaas -> ModuleNotFoundError
import pytest
sys.exit(pytest.main(["-p", "no:cacheprovider", "-n", "0", "-q", "-rs", "examples/test_tamaas_plugin.py"]))
"""


def test_the_tamaas_example_without_the_bench_extra_is_one_skip_that_names_it():
    """Not a ModuleNotFoundError traceback per case: one skip whose reason names the extra."""
    run = subprocess.run([sys.executable, "-c", WITHOUT_TAMAAS], cwd=ROOT, capture_output=True,
                         text=True, start_new_session=True)
    # a module-level skip collects no test: pytest's status 5, never 1 (failed) or 2 (errors)
    assert run.returncode == pytest.ExitCode.NO_TESTS_COLLECTED, run.stdout + run.stderr
    assert "1 skipped" in run.stdout and "failed" not in run.stdout and "error" not in run.stdout
    assert 'tamaas is the bench extra: pip install -e ".[bench]"' in run.stdout
    assert "ModuleNotFoundError" not in run.stdout + run.stderr

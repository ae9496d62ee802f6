"""The README's Python snippets run as a new user runs them: each one alone, and all of them twice.

A snippet that needs a name defined in an earlier one fails when pasted on its
own; a walkthrough that writes a file must be rerunnable in the same directory.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
SNIPPETS = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


def run(code: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


def test_the_readme_has_its_snippets():
    assert len(SNIPPETS) >= 4


@pytest.mark.parametrize("i", range(len(SNIPPETS)))
def test_each_snippet_runs_on_its_own(i, tmp_path):
    done = run(SNIPPETS[i], tmp_path)
    assert done.returncode == 0, f"snippet {i + 1} alone:\n{done.stderr[-1500:]}"


def test_the_whole_walkthrough_can_be_rerun_in_the_same_directory(tmp_path):
    script = "\n".join(SNIPPETS)
    for attempt in (1, 2):
        done = run(script, tmp_path)
        assert done.returncode == 0, f"run {attempt}:\n{done.stderr[-1500:]}"

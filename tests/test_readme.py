"""The README's and the user's guide's Python snippets run as a new user runs them: each one alone, and all of them twice.

A snippet that needs a name defined in an earlier one fails when pasted on its
own; a walkthrough that writes a file must be rerunnable in the same directory.
The quick start comes first, with the set-up commands ``.ci/run`` runs, and its
snippet, run as a script, prints Hertz's contact (``a = sqrt(2 A R P/pi)``,
``p0 = 2 P/(pi a)``) and writes nothing into the working directory.
"""
from __future__ import annotations

import math
import re
import subprocess
import sys
import tempfile
import traceback
from pathlib import Path
from typing import Callable

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
#: the README and the user's guide it points to (issue 40: the README keeps what a user needs first)
GUIDE = sorted((ROOT / "docs" / "guide").glob("*.md"))
SNIPPETS = [s for page in (README, *GUIDE)
            for s in re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S)]
#: the most lines of the README (issue 40: what it is, install, the two commands, a quick start, links)
README_LINES = 250
#: the set-up commands of the quick start: install and verify, and the test command .ci/run runs
SETUP = ('python -m pip install -e ".[test]" && threepart verify',
         'python -m pip install -e ".[test]" && python -m pytest')
#: the quick start prints a to 6 decimals and p0 to 3: each within half a unit of its last digit
A_PRINTED, P0_PRINTED = 5e-7, 5e-4


@pytest.fixture
def run(tmp_path, monkeypatch) -> Callable[[str, str], None]:
    """Run a snippet as ``python -c`` runs it, in this interpreter: a fresh ``__main__`` namespace
    (a name defined only in an earlier snippet is a NameError), the working directory ``tmp_path``
    (a file written there is there for the next run), :mod:`tempfile`'s directory inside it.

    The quick start alone runs in a fresh interpreter (below); the others spare an interpreter's
    start and threepart's import each. An exception or a ``sys.exit`` other than 0 fails, named.
    """
    temp = tmp_path / ".tmp"
    temp.mkdir()
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(tempfile, "tempdir", str(temp))
    monkeypatch.setattr(sys, "argv", ["-c"])

    def run_code(code: str, what: str) -> None:
        try:
            exec(compile(code, f"<{what}>", "exec"), {"__name__": "__main__"})
        except SystemExit as stop:
            assert stop.code in (None, 0), f"{what} exited with {stop.code}"
        except Exception:
            pytest.fail(f"{what}:\n{traceback.format_exc()[-1500:]}")
    return run_code


def test_the_readme_has_its_snippets():
    assert len(SNIPPETS) >= 4


def test_the_readme_is_short_and_links_every_guide_page():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= README_LINES
    assert GUIDE and all(f"(docs/guide/{page.name})" in text for page in GUIDE)
    index = (ROOT / "docs" / "index.rst").read_text(encoding="utf-8")
    assert all(f"guide/{page.stem}" in index for page in GUIDE)


@pytest.mark.parametrize("i", range(len(SNIPPETS)))
def test_each_snippet_runs_on_its_own(i, run):
    run(SNIPPETS[i], f"snippet {i + 1} alone")


def test_the_whole_walkthrough_can_be_rerun_in_the_same_directory(run):
    script = "\n".join(SNIPPETS)
    for attempt in (1, 2):
        run(script, f"the walkthrough, run {attempt}")


def _quick_start() -> str:
    """The README's first section after the title and its introduction."""
    sections = re.split(r"^## ", README.read_text(encoding="utf-8"), flags=re.M)
    assert sections[1].startswith("Quick start\n"), f"the first section is {sections[1].splitlines()[0]!r}"
    return sections[1]


def test_the_quick_start_comes_first_with_the_commands_ci_runs():
    text = _quick_start()
    lines = [line.strip() for line in text.splitlines()]
    assert all(command in lines for command in SETUP)
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    i = ci.index("# the README's test command, exactly as written")
    assert ci[i + 1] == SETUP[1]


def test_the_quick_start_runs_as_a_script_prints_hertz_and_writes_nothing(tmp_path):
    text = _quick_start()
    (code,) = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    script, work = tmp_path / "quickstart.py", tmp_path / "work"
    script.write_text(code, encoding="utf-8")
    work.mkdir()
    done = subprocess.run([sys.executable, str(script)], cwd=work, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-1500:]
    assert list(work.iterdir()) == [], "the quick start wrote into the working directory"
    out = done.stdout
    # Hertz, from the snippet's own inputs: two steel bodies, a cylinder R = 10 mm under P = 400 N/mm
    A, R, P = 4 * (1 - 0.3**2) / 210e3, 10.0, 400.0
    assert "A = 4 * (1 - 0.3**2) / 210e3" in code and "P=400.0, s=0.0" in code and "R1=10.0, R2=10.0" in code
    a, p0 = (float(v) for v in re.search(r"Hertz: a = (\S+) mm, p0 = (\S+) MPa", out).groups())
    a_hertz = math.sqrt(2 * A * R * P / math.pi)
    assert abs(a - a_hertz) <= A_PRINTED and abs(p0 - 2 * P / (math.pi * a_hertz)) <= P0_PRINTED, out
    left, right = (float(v) for v in re.search(r"contact \[(\S+), (\S+)\] mm", out).groups())
    lo, hi = (float(v) for v in re.search(r"stick zone \[(\S+), (\S+)\] mm", out).groups())
    assert left < -1 and 1 < right and left < lo < hi < right, out   # the flat [-1, 1] in contact, stick inside
    # the figures the README quotes are the ones the script prints
    quoted = re.findall(r"`([^`]*\d[^`]*)`", text.split("```")[-1].split("At the command line")[0])
    assert len(quoted) == 3 and all(figure in out for figure in quoted), (quoted, out)

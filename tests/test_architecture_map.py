"""ARCHITECTURE.md checked against the disk (issue 40): every module is named in its folder's row.

The "Each folder's job" table has one row per folder; a module ``m.py`` of that folder (or of a
sub-folder the row covers, written ``sub/`` or ``sub/m.py`` there) must appear in that row. A new
module without a line in the map fails here, and so does a row naming a module that is gone.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: each package folder, and the row of the table that describes its modules
ROWS = {"threepart": "threepart/", "threepart/output": "threepart/", "threepart/tolerances": "threepart/",
        "threepart/problem": "threepart/problem/", "threepart/results": "threepart/results/",
        "threepart/halfplane": "threepart/halfplane/", "threepart/stress": "threepart/stress/",
        "threepart/fatigue": "threepart/fatigue/", "threepart/studies": "threepart/studies/",
        "threepart/cli": "threepart/cli/",
        "threepart/calculix": "threepart/calculix/", "threepart/getfem": "threepart/getfem/",
        "threepart/readers": "threepart/readers/", "closedform": "closedform/", "sie": "sie/",
        "fem": "fem/", "meshes": "meshes/", "reports": "reports/", "reports/verify": "reports/",
        "reports/map": "reports/", "reports/referee": "reports/"}


def _table() -> dict[str, str]:
    text = (ROOT / "ARCHITECTURE.md").read_text(encoding="utf-8")
    section = text[text.index("## Each folder's job"):text.index("## Where to add X")]
    rows = {}
    for line in section.splitlines():
        m = re.match(r"\|\s*`([^`]+)`\s*\|(.*)\|\s*$", line)
        if m:
            rows[m.group(1)] = m.group(2)
    return rows


def _named(name: str, row: str) -> bool:
    """``name`` (``x.py``) appears in ``row`` as a file name, not as the tail of another."""
    return re.search(r"(?<![\w.])" + re.escape(name) + r"(?!\w)", row) is not None


def test_every_folder_has_a_row():
    rows = _table()
    assert sorted(set(ROWS.values()) - set(rows)) == []


@pytest.mark.parametrize("folder", sorted(ROWS))
def test_every_module_is_named_in_its_row(folder):
    row = _table()[ROWS[folder]]
    modules = sorted(f.name for f in (ROOT / folder).glob("*.py") if f.name not in ("__init__.py", "__main__.py"))
    assert modules, f"{folder} has no modules: the table above is out of date"
    missing = [m for m in modules if not _named(m, row)]
    assert missing == [], f"ARCHITECTURE.md's `{ROWS[folder]}` row does not name {missing} of {folder}/"


def test_every_named_module_exists():
    """A module the map names in a package row is on the disk (in that folder or a sub-folder)."""
    rows = _table()
    stale = []
    for row_name in sorted(set(ROWS.values())):
        on_disk = {f.name for folder, r in ROWS.items() if r == row_name for f in (ROOT / folder).glob("*.py")}
        on_disk |= {f.name for f in (ROOT / row_name).rglob("*.py")}
        for prefix, name in re.findall(r"`([\w/]*/)?(\w+\.py)`", rows[row_name]):
            elsewhere = prefix and (ROOT / prefix).is_dir() and not prefix.startswith(row_name)
            if elsewhere and not (ROOT / prefix / name).is_file() or not elsewhere and name not in on_disk:
                stale.append(f"{row_name}: {prefix}{name}")
    assert stale == []

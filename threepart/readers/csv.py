"""The CSV reader: columns ``x, p`` (and optionally the shear ``q``), what ``threepart compare`` read first.

An optional header line and ``#`` comment lines are skipped. A third column,
when every row has one, is the shear ``q``. The file is UTF-8 (a byte-order
mark is dropped); every entry must be a finite number.
"""
from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import numpy as np

from . import Record, no_options, register_reader
from threepart.errors import ReaderError
from threepart.textfile import finite_row, read_text

__all__ = ["read_csv", "COLUMNS"]

#: the columns of a pressure CSV, in order (the third is optional)
COLUMNS = ("x", "p", "q")


def read_csv(path: Path, *, arg: str = "path", **options: Any) -> Record:
    """The points of a CSV file: ``x, p`` per row (``x, p, q`` with the shear), compressive ``p`` positive.

    Raises
    ------
    ReaderError
        A file that is not UTF-8 text (:func:`threepart.textfile.read_text`), a
        row (after the header) that is not two or three numbers, an entry that
        is not finite (``nan``, ``inf``, ``1e400``), no rows: one line naming
        the file and the row (counted as the file's lines).
    """
    no_options(path, arg, options, "a CSV takes")
    label = f"`{arg}` = {str(path)!r}"
    rows: list[list[float]] = []
    header_seen = False
    for line, text in enumerate(read_text(path, label).splitlines(), start=1):
        if text.lstrip().startswith("#") or not text.strip():
            continue
        row = next(csv.reader([text]))
        cells = row[:2] + (row[2:3] if len(row) > 2 and row[2].strip() else [])
        if len(cells) < 2 or not _numbers(cells):
            if not rows and not header_seen:
                header_seen = True        # the header line
                continue
            raise ReaderError(f"{label}: row {line} is not two numbers x, p: {text.strip()!r}")
        rows.append(finite_row(cells, f"{label}: row {line}", COLUMNS))
    if not rows:
        raise ReaderError(f"{label} holds no x, p rows")
    x = np.array([r[0] for r in rows])
    p = np.array([r[1] for r in rows])
    q = np.array([r[2] for r in rows]) if all(len(r) == 3 for r in rows) else None
    return Record(x, p, q, {"source": "csv"})


def _numbers(cells: list[str]) -> bool:
    """Whether every cell reads as a number (else the line is a header)."""
    try:
        [float(c) for c in cells]
    except ValueError:
        return False
    return bool(cells)


register_reader("csv", (".csv", ".txt"), read_csv,
                "columns x, p (and the shear q), an optional header")

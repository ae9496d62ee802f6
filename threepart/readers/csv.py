"""The CSV reader: columns ``x, p`` (and optionally the shear ``q``), what ``threepart compare`` read first.

An optional header line and ``#`` comment lines are skipped. A third column,
when every row has one, is the shear ``q``.
"""
from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import numpy as np

from . import Record, register_reader
from threepart.errors import InputError

__all__ = ["read_csv"]


def read_csv(path: Path, *, arg: str = "path", **options: Any) -> Record:
    """The points of a CSV file: ``x, p`` per row (``x, p, q`` with the shear), compressive ``p`` positive."""
    if options:
        raise InputError(f"`{arg}` = {str(path)!r}: a CSV takes no options, not {', '.join(options)}")
    rows: list[list[float]] = []
    with open(path, newline="", encoding="utf-8") as f:
        for i, row in enumerate(csv.reader(line for line in f if not line.lstrip().startswith("#"))):
            if not row or not "".join(row).strip():
                continue
            try:
                values = [float(row[0]), float(row[1])]
                if len(row) > 2 and row[2].strip():
                    values.append(float(row[2]))
            except (ValueError, IndexError):
                if i == 0 and not rows:
                    continue          # a header line
                raise InputError(f"`{arg}` = {str(path)!r}: row {i + 1} is not two numbers "
                                 f"x, p: {','.join(row)!r}") from None
            rows.append(values)
    if not rows:
        raise InputError(f"`{arg}` = {str(path)!r} holds no x, p rows")
    x = np.array([r[0] for r in rows])
    p = np.array([r[1] for r in rows])
    q = np.array([r[2] for r in rows]) if all(len(r) == 3 for r in rows) else None
    return Record(x, p, q, {"source": "csv"})


register_reader("csv", (".csv", ".txt"), read_csv,
                "columns x, p (and the shear q), an optional header")

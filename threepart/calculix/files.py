"""The text of a CalculiX run's files, checked line by line: what :mod:`.read` builds on.

Every file is read through :func:`threepart.textfile.read_text` (a binary,
UTF-16 or Latin-1 file is one :class:`~threepart.errors.ReaderError`), every
number must read and be finite, and an ``.frd`` cut short is named as such, so
that no reader of CalculiX's output fails with a bare ``IndexError``,
``KeyError`` or ``UnicodeDecodeError``, nor returns NaN.

run_file        -- a run's file: ``stem`` + suffix, or ``stem`` itself if it ends in it (``job.FRD``)
file_label      -- how a message names the file (``"`--pressure` = 'job.frd'"``)
frd_blocks      -- every nodal block of an ``.frd`` (the coordinates as ``"2C"``), checked
last_printed    -- the first row under the last printed block of a heading in a ``.dat``
FRD_LINE_VALUES -- the values on one ``-1`` line of an ``.frd``
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from threepart.errors import ReaderError
from threepart.textfile import finite_row, read_text

__all__ = ["run_file", "file_label", "frd_blocks", "last_printed", "FRD_LINE_VALUES", "frd_row"]

#: the values on one ``-1`` line of an ``.frd`` (more components continue on ``-2`` lines)
FRD_LINE_VALUES = 6
#: the columns of one value on an ``.frd``'s ``-1`` line (``E12.5``), after the node's 10
FRD_VALUE_WIDTH = 12


def run_file(stem: str | Path, suffix: str) -> Path:
    """The file of a run: ``stem`` itself if it already ends in ``suffix`` (any case: ``job.FRD``
    is looked up as given), else ``stem`` + ``suffix``."""
    path = Path(stem)
    return path if path.suffix.lower() == suffix else Path(f"{stem}{suffix}")


def file_label(path: Path, arg: str | None) -> str:
    """How a message names the file: ``"`--pressure` = 'job.frd'"``, or the file alone."""
    return f"`{arg}` = {str(path)!r}" if arg else f"CalculiX's file {str(path)!r}"


def frd_row(line: str, i: int, label: str, block: str) -> tuple[int, list[float]]:
    """The node and the finite values of the ``-1`` line ``i`` of an ``.frd`` block: the node
    number in columns 4-13, the values 12 columns each; ReaderError naming the line otherwise."""
    where = f"{label}, line {i}"
    try:
        n = int(line[3:13])
    except ValueError:
        raise ReaderError(f"{where}: {line[3:13].strip()!r} is not a node number ({block} block)") from None
    text = line[13:].rstrip()
    w = FRD_VALUE_WIDTH
    if not text or len(text) % w:
        raise ReaderError(f"{where}: node {n}'s values in the {block} block are cut short "
                          f"({text!r}; {w} columns each): a truncated file?")
    return n, finite_row([text[j:j + w] for j in range(0, len(text), w)],
                         f"{where} (node {n}, {block} block)", ("x", "y", "z") if block == "2C" else None)


def frd_blocks(path: Path, label: str) -> dict[str, dict[int, np.ndarray]]:
    """Every nodal block of the ``.frd`` ``path``, ``{name: {node: values}}``, the node coordinates
    as ``"2C"``; a block's later increment replaces its earlier one.

    Each ``-1`` line must hold as many values as its block's ``-5`` lines name
    (those not flagged absent, as DISP's ``ALL``), each number must be finite and
    each block must end with its ``-3`` line; else one :class:`ReaderError`
    starting with ``label`` and naming the line.
    """
    out: dict[str, dict[int, np.ndarray]] = {}
    current: dict[int, np.ndarray] | None = None
    block, width, start = "", 0, 0
    for i, line in enumerate(read_text(path, label).splitlines(), start=1):
        if line.startswith(" -4") or line.startswith("    2C"):
            words = line.split()
            block = "2C" if words[0] == "2C" else (words[1] if len(words) > 1 else "unnamed")
            current, width, start = {}, 3 if block == "2C" else 0, i
            out[block] = current
        elif line.startswith(" -5") and current is not None:
            words = line.split()
            width += not (len(words) > 6 and words[6][:1] == "1")      # "1ALL": not in the data
        elif line.startswith(" -1") and current is not None:
            n, values = frd_row(line, i, label, block)
            if width and len(values) != min(width, FRD_LINE_VALUES):
                raise ReaderError(f"{label}, line {i}: node {n} has {len(values)} values in the {block} "
                                  f"block, which has {width} components: a truncated or edited file?")
            current[n] = np.array(values)
        elif line.startswith(" -3"):
            current = None
    if current is not None:
        raise ReaderError(f"{label} ends inside its {block} block (from line {start}), without its "
                          "closing -3 line: a truncated file?")
    return out


def last_printed(stem: str | Path, heading: str) -> tuple[str, list[str]]:
    """Where the first row under the last block ``heading`` of ``stem.dat`` is (the file and
    its line, for messages), and that row's words; ReaderError if the file has no such row."""
    path = run_file(stem, ".dat")
    label = file_label(path, None)
    lines = read_text(path, label).splitlines()
    found = [k for k, ln in enumerate(lines) if ln.strip().startswith(heading)]
    if not found or found[-1] + 2 >= len(lines):
        raise ReaderError(f"{label} has no printed {heading!r} block with a row under it")
    return f"{label}, line {found[-1] + 3}", lines[found[-1] + 2].split()

"""The text of a file another program wrote, or one refusal that names the file and what is wrong.

Every reader of a text file (a pressure CSV, a load history, CalculiX's
``.frd``, ``.dat``, ``.sta`` and deck) takes its text from here, so that a
missing, binary, UTF-16 or Latin-1 file is one :class:`~threepart.errors.ReaderError`
naming the file, never a bare ``UnicodeDecodeError``.

read_text  -- a file's text: UTF-8, a leading byte-order mark dropped (``utf-8-sig``)
finite_row -- numbers of one line of a file as floats, each finite, or a ReaderError naming the line
"""
from __future__ import annotations

import codecs
import math
import os
from pathlib import Path
from typing import Sequence

from threepart.errors import ReaderError

__all__ = ["read_text", "finite_row"]

#: byte-order marks of the encodings a text file may be in besides UTF-8 (UTF-32's first:
#: its little-endian mark begins with UTF-16's)
_OTHER_BOMS = ((codecs.BOM_UTF32_LE, "UTF-32"), (codecs.BOM_UTF32_BE, "UTF-32"),
               (codecs.BOM_UTF16_LE, "UTF-16"), (codecs.BOM_UTF16_BE, "UTF-16"))
#: the bytes looked at to tell UTF-16 without a byte-order mark (every other byte NUL) from binary
_SNIFF = 64


def read_text(path: str | os.PathLike[str], label: str) -> str:
    """The text of ``path``, decoded as UTF-8 (a byte-order mark is dropped).

    Parameters
    ----------
    path
        The file, looked up exactly as given (``job.FRD`` is not ``job.frd``).
    label
        How the messages name the file, e.g. ``"`--pressure` = 'job.frd'"``.

    Raises
    ------
    ReaderError
        One line starting with ``label``: the file is missing or is a directory,
        cannot be read, is binary (holds a NUL byte), is UTF-16 or UTF-32, or is
        not UTF-8 (Latin-1 or another code page): the byte and its line.
    """
    try:
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise ReaderError(f"{label} cannot be read: no such file") from None
    except IsADirectoryError:
        raise ReaderError(f"{label} cannot be read: it is a directory") from None
    except OSError as exc:
        raise ReaderError(f"{label} cannot be read: {exc.strerror or type(exc).__name__}") from None
    for bom, name in _OTHER_BOMS:
        if data.startswith(bom):
            raise ReaderError(f"{label} is {name} text; save it as UTF-8")
    nul = data.find(b"\0")
    if nul >= 0:
        head = data[:_SNIFF]
        if len(head) >= 2 and (head[1::2].count(0) == len(head[1::2]) or head[::2].count(0) == len(head[::2])):
            raise ReaderError(f"{label} is UTF-16 text (without a byte-order mark); save it as UTF-8")
        line = data.count(b"\n", 0, nul) + 1
        raise ReaderError(f"{label} is a binary file, not text (a NUL byte on line {line})")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise ReaderError(f"{label} is not UTF-8 text: byte 0x{data[exc.start]:02x} on line {line} "
                          "(Latin-1 or another code page?); save it as UTF-8") from None


def finite_row(texts: Sequence[str], where: str, names: Sequence[str] | None = None) -> list[float]:
    """The numbers ``texts`` of one line of a file as floats, each finite.

    ``where`` names the file and the line (``"`--pressure` = 'p.csv', line 7"``);
    ``names`` the columns, for the message (default: their positions).

    Raises
    ------
    ReaderError
        An entry that is not a number, or is ``nan``, ``inf`` or overflows
        (``1e400``): one line naming ``where``, the column and the entry.
    """
    out = []
    for k, text in enumerate(texts):
        column = f"`{names[k]}`" if names is not None and k < len(names) else f"{k + 1}"
        try:
            v = float(text)
        except ValueError:
            raise ReaderError(f"{where}, column {column}: {text.strip()!r} is not a number") from None
        if not math.isfinite(v):
            raise ReaderError(f"{where}, column {column}: {text.strip()!r} is not a finite number")
        out.append(v)
    return out

"""CalculiX's ``.frd`` and ``.dat``: the contact pressure from the nodal contact forces,
read by :func:`threepart.calculix.read.contact_pressure` (the one reader of CalculiX's output)."""
from __future__ import annotations

from pathlib import Path
from typing import Any

from threepart.calculix.read import contact_pressure

from . import Record, register_reader
from threepart.errors import InputError

__all__ = ["read_calculix"]


def read_calculix(path: Path, *, arg: str = "path", **options: Any) -> Record:
    """The contact pressure of one CalculiX run's ``.frd`` or ``.dat`` (the deck ``.inp`` beside a ``.dat``)."""
    if options:
        raise InputError(f"`{arg}` = {str(path)!r}: CalculiX's files take no options, not "
                         f"{', '.join(options)}")
    x, p, info = contact_pressure(path, arg=arg)
    return Record(x, p, None, info)


register_reader("frd", (".frd",), read_calculix,
                "CalculiX, *CONTACT FILE CDIS, CSTR, CELS")
register_reader("dat", (".dat",), read_calculix,
                "CalculiX, *CONTACT PRINT CSTR, CDIS, CELS, the deck .inp beside it")

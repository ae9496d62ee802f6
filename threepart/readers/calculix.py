"""CalculiX's ``.frd`` and ``.dat``: the contact pressure from the nodal contact forces,
read by :func:`threepart.calculix.read.contact_pressure` (the one reader of CalculiX's output);
a friction run's ``.frd`` (surface-to-surface contact, threepart's friction deck) gives
``x``, ``p`` and the shear ``q`` the punch exerts on the block along ``+x``
(:func:`threepart.calculix.cycle.read_traction`), and in ``info["states"]`` every recorded
increment (:func:`threepart.calculix.cycle.frd_states`: ``P, s, Q, sigma_bulk, x, p, q, slip``,
the loads from threepart's deck beside the file, as GetFEM's sidecar gives its states)."""
from __future__ import annotations

from pathlib import Path
from typing import Any

from threepart.calculix.cycle import frd_states, read_traction
from threepart.calculix.read import contact_pressure

from . import Record, no_options, register_reader

__all__ = ["read_calculix"]


def read_calculix(path: Path, *, arg: str = "path", **options: Any) -> Record:
    """The contact pressure of one CalculiX run's ``.frd`` or ``.dat`` (the deck ``.inp`` beside a ``.dat``)."""
    no_options(path, arg, options, "CalculiX's files take")
    traction = read_traction(path, arg=arg)
    if traction is not None:        # a friction run (surface to surface): p and the shear q
        x, p, q, info = traction
        # every recorded increment: loads (from the deck beside it), x, p, q, slip
        return Record(x, p, q, dict(info, states=frd_states(path, arg=arg)))
    x, p, info = contact_pressure(path, arg=arg)
    return Record(x, p, None, info)


register_reader("frd", (".frd",), read_calculix,
                "CalculiX, *CONTACT FILE CDIS, CSTR, CELS")
register_reader("dat", (".dat",), read_calculix,
                "CalculiX, *CONTACT PRINT CSTR, CDIS, CELS, the deck .inp beside it")

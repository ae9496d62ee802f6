"""Readers of other codes' contact results, registered by format (meshio's ``register_format`` is the model).

``threepart compare`` and the referee (:mod:`threepart.reports.referee`) read
another code's contact pressure through :func:`read`, which picks the reader
by the file's suffix from the table below. Each format's module registers
itself when imported (:func:`register_reader`); a new format is one module
that calls it, imported by its user or listed in :data:`BUILTIN`.

Names
-----
Record          -- what every reader returns: ``x`` along the surface, the pressure ``p``, optionally the shear ``q``
Format          -- one row of the table: name, suffixes, read function, help
register_reader -- add a format to the table (by name; its suffixes pick it)
read            -- read a file by its suffix (or a format named): one :class:`Record`
formats         -- the table's formats, in the order they registered
format_of       -- the format a path's suffix picks (ValueError naming the formats when none does)
describe        -- one line per format (name, suffixes, help), for the command line's help
no_options      -- a reader's refusal of options it does not take, naming the file

Built-in formats (:data:`BUILTIN`, each its own module)
-------------------------------------------------------
csv             -- ``.csv``/``.txt``: columns ``x, p`` (and ``q``) (:mod:`.csv`)
frd, dat        -- CalculiX's ``.frd`` and ``.dat`` through :mod:`threepart.calculix.read` (:mod:`.calculix`)
vtu, xdmf, med, exodus -- any mesh file meshio reads with a contact-pressure point field on
                   the contact surface: FEniCSx/dolfinx, Code_Aster, MOOSE (:mod:`.meshfile`)
getfem          -- ``.getfem.json``: the sidecar of threepart's GetFEM script, every state's loads (:mod:`.getfem`)

The core (``threepart/*.py``) never imports this package.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np
from threepart.errors import InputError, InputTypeError, ReaderError

__all__ = ["Record", "Format", "register_reader", "read", "formats", "format_of", "describe", "BUILTIN",
           "no_options"]

#: the modules of the built-in formats, imported (and so registered) on the table's first use
BUILTIN = ("csv", "calculix", "meshfile", "getfem")


@dataclass(frozen=True)
class Record:
    """Another code's contact result along the surface.

    Attributes
    ----------
    x
        Positions along the surface (the README's ``x``), as the file gives them.
    p
        The contact pressure there (compressive positive).
    q
        The shear traction there, if the file carries it; else ``None``.
    info
        What the reader knows besides: ``source`` (the format) and, for
        CalculiX, the nodal forces, the penalty and the increments.
    """

    x: np.ndarray
    p: np.ndarray
    q: np.ndarray | None = None
    info: dict[str, Any] = field(default_factory=dict)


#: a reader: ``read_function(path, *, arg, **options) -> Record``; ``arg`` names the file in messages
ReadFunction = Callable[..., Record]


@dataclass(frozen=True)
class Format:
    """One format of the table: its name, the suffixes that pick it, its reader and a line of help."""

    name: str
    suffixes: tuple[str, ...]
    read: ReadFunction
    help: str


_FORMATS: dict[str, Format] = {}
_SUFFIXES: dict[str, str] = {}
_loaded = False


def no_options(path: Path, arg: str, options: dict[str, Any], what: str) -> None:
    """Refuse ``options`` of a reader that takes none: one line naming the file and ``what`` it is."""
    if options:
        raise InputError(f"`{arg}` = {str(path)!r}: {what} no options, not {', '.join(options)}")


def register_reader(name: str, suffixes: list[str] | tuple[str, ...], read_function: ReadFunction,
                    help: str) -> None:
    """Add the format ``name`` to the table: files ending in one of ``suffixes`` are read by
    ``read_function(path, *, arg, **options)``, which returns a :class:`Record`.

    A later registration of the same name or suffix replaces the earlier one.
    """
    if not isinstance(name, str) or not name:
        raise InputTypeError(f"`name` = {name!r} must be a non-empty str")
    if not callable(read_function):
        raise InputTypeError(f"`read_function` = {read_function!r} must be callable")
    bad = [s for s in suffixes if not (isinstance(s, str) and s.startswith(".") and len(s) > 1)]
    if bad or not suffixes:
        raise InputError(f"`suffixes` = {list(suffixes)!r} must be one or more strings such as '.csv'")
    _FORMATS[name] = Format(name, tuple(s.lower() for s in suffixes), read_function, help)
    for s in suffixes:
        _SUFFIXES[s.lower()] = name


def _load_builtin() -> None:
    """Import the built-in formats' modules once: each registers itself."""
    global _loaded
    if not _loaded:
        _loaded = True
        for module in BUILTIN:
            importlib.import_module(f".{module}", __name__)


def formats() -> list[Format]:
    """The table's formats: the built-in ones first, in the order of :data:`BUILTIN` (whichever
    module was imported first), then the others in the order they registered."""
    _load_builtin()
    return sorted(_FORMATS.values(), key=_rank)


def _rank(fmt: Format) -> int:
    """The place of the module that registered ``fmt`` in :data:`BUILTIN` (others after them)."""
    module = getattr(fmt.read, "__module__", "") or ""
    name = module[len(__name__) + 1:] if module.startswith(__name__ + ".") else ""
    return BUILTIN.index(name) if name in BUILTIN else len(BUILTIN)


def describe() -> str:
    """One line per format, ``name (.suffix, ...): help``, for the command line's help."""
    return "; ".join(f"{f.name} ({', '.join(f.suffixes)}): {f.help}" for f in formats())


def format_of(path: str | Path, *, arg: str = "path") -> Format:
    """The format whose suffix ``path`` ends in (the longest compound suffix first, ``.vtu``
    before ``.gz``'s ``.vtu.gz``); ValueError naming the formats when none matches."""
    _load_builtin()
    path = Path(path)
    ext = ""
    found = None
    for suffix in reversed(path.suffixes):
        ext = (suffix + ext).lower()
        if ext in _SUFFIXES:
            found = _SUFFIXES[ext]
    if found is None:
        known = ", ".join(f"{f.name} ({' '.join(f.suffixes)})" for f in formats())
        raise InputError(f"`{arg}` = {str(path)!r}: no reader for "
                         f"{path.suffix or 'a file without a suffix'}; the formats: {known}")
    return _FORMATS[found]


def read(path: str | Path, *, arg: str = "path", file_format: str | None = None, **options: Any) -> Record:
    """Read another code's contact result from ``path``: one :class:`Record`.

    Parameters
    ----------
    path
        The file; its suffix picks the format (:func:`format_of`).
    arg
        How messages name the file (the command line passes ``"--pressure"``).
    file_format
        A format's name, to read a file whose suffix is not its own.
    **options
        The format's own options (the mesh formats: ``field``, ``surface``,
        ``shear``, ``component``; see :mod:`.meshfile`).

    Raises
    ------
    ReaderError
        A path that is not a file, or a file the reader refuses (unreadable,
        malformed, a number that is not finite), in one line naming ``arg`` and
        the file; a record with a non-finite or misshapen ``x``, ``p`` or ``q``
        from any reader is refused here, so none is ever returned.
    ValueError
        A suffix (or ``file_format``) no reader registered, or an option the
        reader refuses, in one line naming ``arg``.
    """
    path = Path(path)
    if not path.is_file():
        raise ReaderError(f"`{arg}` = {str(path)!r} is not a file")
    if file_format is not None:
        _load_builtin()
        if file_format not in _FORMATS:
            raise InputError(f"`file_format` = {file_format!r} is not a format; the formats: "
                             f"{', '.join(_FORMATS)}")
        fmt = _FORMATS[file_format]
    else:
        fmt = format_of(path, arg=arg)
    return _checked(fmt.read(path, arg=arg, **options), f"`{arg}` = {str(path)!r}")


def _checked(record: Record, label: str) -> Record:
    """``record`` if its ``x``, ``p`` (and ``q``) are finite 1-D arrays of one length; else ReaderError."""
    n = np.shape(record.x)
    for name in ("x", "p", "q"):
        v = getattr(record, name)
        if v is None and name == "q":
            continue
        v = np.asarray(v)
        if v.ndim != 1 or v.shape != n or v.dtype.kind not in "fiu":
            raise ReaderError(f"{label}: the reader returned `{name}` of shape {v.shape} ({v.dtype}), "
                              f"not real numbers of the shape of `x`, {n}")
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ReaderError(f"{label}: `{name}` is not finite at {bad.size} of its {v.size} points "
                              f"(the first at x = {float(np.asarray(record.x)[bad[0]]):g})")
    return record

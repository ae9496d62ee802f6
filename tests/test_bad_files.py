"""Bad files are refused by name (issue 37, section 5): one ReaderError naming the file and what is wrong.

Each bad file is a good one corrupted here: the CalculiX runs of ``tests/data`` (an
``.frd`` with CELS, one without, a ``.dat`` with its deck), the Hertz pressure CSV and the
mesh files (VTU, XDMF, MED, Exodus) that ``tests/test_readers.py`` writes, and a load
history. The reference of each refusal is the corruption made: the error's class, the
file's name and the fault in its one line, and on the command line one line on stderr
with exit status 2. Nothing non-finite is ever returned, whatever a reader does.
"""
from __future__ import annotations

import codecs
import importlib
import re
import shutil
import sys
from pathlib import Path
from typing import Callable

import meshio
import numpy as np
import pytest

from threepart import readers
from threepart.cli import main
from threepart.errors import InputError, InputTypeError, ReaderError
from threepart.halfplane.load_history import read_history

from .test_readers import FORMATS, HERTZ_ARGS, NX, a_H, hertz, plane_mesh, point_fields

DATA = Path(__file__).parent / "data"
#: a run with CELS (.frd, .dat and its cut-down deck), and one .frd with CONTACT alone (CPRESS)
SMALL = DATA / "calculix_small_slope_h016"
NO_CELS = DATA / "calculix_caseA_sym_h0.1.frd"

# --------------------------------------------------------------------------- corruptions of a text


def _value(text: str, block: str, new: str, column: int = 0) -> str:
    """``text`` of an .frd with one value of the middle ``-1`` line of ``block`` ("2C": the
    coordinates) replaced by ``new``, right-aligned in its 12 columns."""
    lines = text.splitlines(keepends=True)
    head = next(i for i, ln in enumerate(lines)
                if (ln.startswith("    2C") if block == "2C" else ln.split()[:2] == ["-4", block]))
    end = next(i for i in range(head, len(lines)) if lines[i].startswith(" -3"))
    rows = [i for i in range(head, end) if lines[i].startswith(" -1")]
    k = rows[len(rows) // 2]
    start = 13 + 12 * column
    lines[k] = lines[k][:start] + f"{new:>12}" + lines[k][start + 12:]
    return "".join(lines)


def _cut_inside(text: str, block: str, chars: int) -> str:
    """``text`` of an .frd cut ``chars`` characters into the middle ``-1`` line of ``block``
    (``chars = 0``: at that line's start, so that the block lacks its closing ``-3``)."""
    lines = text.splitlines(keepends=True)
    head = next(i for i, ln in enumerate(lines) if ln.split()[:2] == ["-4", block])
    end = next(i for i in range(head, len(lines)) if lines[i].startswith(" -3"))
    k = (head + end) // 2
    return "".join(lines[:k]) + lines[k][:chars]


def _without_nodes(text: str) -> str:
    """``text`` of an .frd without its node block (``2C`` up to its ``-3``)."""
    lines = text.splitlines(keepends=True)
    head = next(i for i, ln in enumerate(lines) if ln.startswith("    2C"))
    end = next(i for i in range(head, len(lines)) if lines[i].startswith(" -3"))
    return "".join(lines[:head] + lines[end + 1:])


def _dat_value(text: str, heading: str, new: str) -> str:
    """``text`` of a .dat with the first value of the first row under ``heading`` replaced by ``new``."""
    lines = text.splitlines(keepends=True)
    head = next(i for i, ln in enumerate(lines) if ln.strip().startswith(heading))
    k = next(i for i in range(head + 1, len(lines)) if lines[i].split())
    words = lines[k].split()
    lines[k] = f"{words[0]:>10}  {new}" + "".join(f"  {w}" for w in words[2:]) + "\n"
    return "".join(lines)


#: binary bytes (every byte value), not a text file
BINARY = bytes(range(256)) * 8
#: a text's heading given a German umlaut, as a code page (Latin-1) writes it
UMLAUT = "Länge"


def _latin1(text: str) -> bytes:
    first, rest = text.split("\n", 1)
    return (first + f" {UMLAUT}\n" + rest).encode("latin-1")


#: (name, the good file's text, the corruption, the fault the message names)
Corruption = tuple[str, Callable[[str], "str | bytes"], str]
TEXT_FAULTS: list[Corruption] = [
    ("binary", lambda t: BINARY, r"is a binary file, not text"),
    ("utf16", lambda t: t.encode("utf-16"), r"is UTF-16 text; save it as UTF-8"),
    ("utf16-no-bom", lambda t: t.encode("utf-16-le"), r"is UTF-16 text \(without a byte-order mark\)"),
    ("latin1", _latin1, r"is not UTF-8 text: byte 0xe4 on line 1 \(Latin-1"),
]
FRD_FAULTS: list[Corruption] = [
    ("nan-coordinate", lambda t: _value(t, "2C", "NaN"), r"line \d+ \(node \d+, 2C block\), column `x`: "
                                                         r"'NaN' is not a finite number"),
    ("inf-coordinate", lambda t: _value(t, "2C", "Infinity", 1),
     r"2C block\), column `y`: 'Infinity' is not a finite number"),
    ("cut-mid-line", lambda t: _cut_inside(t, "CONTACT", 30),
     r"line \d+: node \d+'s values in the CONTACT block are cut short .*a truncated file\?"),
    ("cut-at-a-line", lambda t: _cut_inside(t, "CONTACT", 0),
     r"ends inside its CONTACT block \(from line \d+\), without its closing -3 line: a truncated file\?"),
    ("nan-cels", lambda t: _value(t, "CELS", "NaN"), r"CELS block\), column 1: 'NaN' is not a finite number"),
    ("nan-cpress", lambda t: _value(t, "CONTACT", "NaN", 3),
     r"CONTACT block\), column 4: 'NaN' is not a finite number"),
    ("no-node-block", _without_nodes, r"has no node coordinates \(no 2C block"),
    ("empty", lambda t: "", r"holds no result block \(no -4 line\)"),
    ("bad-number", lambda t: _value(t, "CONTACT", "1.2x4E-01"), r"'1\.2x4E-01' is not a number"),
    ("cut-at-a-field", lambda t: _cut_inside(t, "CONTACT", 13 + 3 * 12),
     r"has 3 values in the CONTACT block, which has 6 components: a truncated or edited file\?"),
] + TEXT_FAULTS
NO_CELS_FAULTS: list[Corruption] = [
    ("nan-coordinate", lambda t: _value(t, "2C", "NaN"), r"column `x`: 'NaN' is not a finite number"),
    ("nan-cpress", lambda t: _value(t, "CONTACT", "NaN", 3), r"column 4: 'NaN' is not a finite number"),
    ("cut-mid-line", lambda t: _cut_inside(t, "CONTACT", 20), r"cut short"),
]
DAT_FAULTS: list[Corruption] = [
    ("nan-energy", lambda t: _dat_value(t, "contact print energy", "NaN"),
     r"line \d+ \(node \d+\), column 1: 'NaN' is not a finite number"),
    ("inf-copen", lambda t: _dat_value(t, "relative contact displacement", "-Infinity"),
     r"'-Infinity' is not a finite number"),
    ("bad-number", lambda t: _dat_value(t, "contact print energy", "1.3x5633E-10"),
     r"line \d+ \(node \d+\), column 1: '1\.3x5633E-10' is not a number"),
] + TEXT_FAULTS
DECK_FAULTS: list[Corruption] = [
    ("nan-coordinate", lambda t: t.replace("\n49, -1.19976915308258, 0", "\n49, nan, 0"),
     r"the deck '.*\.inp' beside `path` = '.*job\.dat', \*NODE row '49, nan, 0'.*'nan' is not a finite number"),
    ("bad-number", lambda t: t.replace("\n49, -1.19976915308258, 0", "\n49, -1.1997x, 0"),
     r"'-1\.1997x' is not a number"),
    ("binary", lambda t: BINARY, r"the deck .* is a binary file"),
]
CSV_FAULTS: list[Corruption] = [
    *[(f"{bad}-in-{col}", (lambda t, bad=bad, k=k: _csv_entry(t, k, bad)),
       rf"row \d+, column `{col}`: '{re.escape(bad)}' is not a finite number")
      for bad in ("nan", "inf", "1e400", "-Infinity") for k, col in enumerate("xpq")],
    ("not-a-number", lambda t: _csv_entry(t, 1, "zero"), r"row \d+ is not two numbers x, p"),
    ("no-rows", lambda t: "x,p,q\n# nothing\n", r"holds no x, p rows"),
    ("empty", lambda t: "", r"holds no x, p rows"),
] + TEXT_FAULTS


def _csv_entry(text: str, column: int, new: str) -> str:
    """``text`` of a CSV with column ``column`` of its middle row replaced by ``new``."""
    lines = text.splitlines(keepends=True)
    k = len(lines) // 2
    cells = lines[k].rstrip("\n").split(",")
    cells[column] = new
    lines[k] = ",".join(cells) + "\n"
    return "".join(lines)


def _hertz_csv() -> str:
    x = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    return "x,p,q\n" + "".join(f"{a!r},{b!r},{0.2 * b!r}\n" for a, b in zip(x.tolist(), hertz(x).tolist()))


def _write(path: Path, content: str | bytes) -> Path:
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return path


def _refused(path: Path, match: str, **options) -> str:
    """The one-line ReaderError of reading ``path``: it names the file and matches ``match``."""
    with pytest.raises(ReaderError) as info:
        readers.read(path, **options)
    msg = str(info.value)
    assert str(path) in msg and "\n" not in msg, msg
    assert re.search(match, msg), msg
    return msg


def _cli_refuses(capsys, tmp_path: Path, path: Path, match: str) -> None:
    """``threepart compare`` on ``path``: exit 2, one line on stderr naming the file, no traceback."""
    assert main(["compare", "--pressure", str(path), *HERTZ_ARGS, "--out", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert str(path) in err and re.search(match, err), err


# --------------------------------------------------------------------------- CalculiX


@pytest.mark.parametrize("name, corrupt, match", FRD_FAULTS, ids=[c[0] for c in FRD_FAULTS])
def test_a_bad_frd_is_refused_by_name(tmp_path, capsys, name, corrupt, match):
    """Every corruption of the run's .frd (with CELS) is one ReaderError naming the file and the fault."""
    path = _write(tmp_path / "job.frd", corrupt(SMALL.with_suffix(".frd").read_text()))
    _refused(path, match)
    if name in ("nan-coordinate", "cut-mid-line", "binary", "no-node-block"):
        _cli_refuses(capsys, tmp_path, path, match)


@pytest.mark.parametrize("name, corrupt, match", NO_CELS_FAULTS, ids=[c[0] for c in NO_CELS_FAULTS])
def test_a_bad_frd_without_cels_is_refused_by_name(tmp_path, name, corrupt, match):
    """The same of an .frd with the CONTACT block alone (CPRESS read as the pressure)."""
    _refused(_write(tmp_path / "job.frd", corrupt(NO_CELS.read_text())), match)


@pytest.mark.parametrize("name, corrupt, match", DAT_FAULTS, ids=[c[0] for c in DAT_FAULTS])
def test_a_bad_dat_is_refused_by_name(tmp_path, name, corrupt, match):
    """A corrupted .dat (its deck beside it, good) is one ReaderError naming the .dat."""
    shutil.copy(SMALL.with_suffix(".inp"), tmp_path / "job.inp")
    _refused(_write(tmp_path / "job.dat", corrupt(SMALL.with_suffix(".dat").read_text())), match)


@pytest.mark.parametrize("name, corrupt, match", DECK_FAULTS, ids=[c[0] for c in DECK_FAULTS])
def test_a_bad_deck_beside_a_dat_is_refused_by_name(tmp_path, name, corrupt, match):
    """The .dat's coordinates come from the deck beside it: a bad deck is named, with the .dat."""
    shutil.copy(SMALL.with_suffix(".dat"), tmp_path / "job.dat")
    deck = _write(tmp_path / "job.inp", corrupt(SMALL.with_suffix(".inp").read_text()))
    msg = _refused(tmp_path / "job.dat", match)
    assert str(deck) in msg


def test_an_upper_case_suffix_is_read_as_given(tmp_path):
    """``job.FRD`` (and ``job.DAT`` with ``job.INP``) are the files read, not ``job.frd``: the same
    points as the lower-case copies of the same bytes."""
    for suffix, beside in ((".frd", None), (".dat", ".inp")):
        lower = tmp_path / "lower"
        upper = tmp_path / "upper"
        for d in (lower, upper):
            d.mkdir(exist_ok=True)
        shutil.copy(SMALL.with_suffix(suffix), lower / f"job{suffix}")
        shutil.copy(SMALL.with_suffix(suffix), upper / f"job{suffix.upper()}")
        if beside:
            shutil.copy(SMALL.with_suffix(beside), lower / f"job{beside}")
            shutil.copy(SMALL.with_suffix(beside), upper / f"job{beside.upper()}")
        want = readers.read(lower / f"job{suffix}")
        got = readers.read(upper / f"job{suffix.upper()}")
        assert np.array_equal(got.x, want.x) and np.array_equal(got.p, want.p)
        assert np.all(np.isfinite(got.p)) and got.x.size >= 8


# --------------------------------------------------------------------------- CSV


@pytest.mark.parametrize("name, corrupt, match", CSV_FAULTS, ids=[c[0] for c in CSV_FAULTS])
def test_a_bad_csv_is_refused_by_name(tmp_path, capsys, name, corrupt, match):
    """nan, inf, 1e400 in x, p or q, a word, no rows, binary, UTF-16 or Latin-1: one ReaderError."""
    path = _write(tmp_path / "p.csv", corrupt(_hertz_csv()))
    _refused(path, match)
    if name in ("nan-in-p", "1e400-in-x", "utf16"):
        _cli_refuses(capsys, tmp_path, path, match)


def test_a_csv_with_a_byte_order_mark_is_read(tmp_path):
    """A UTF-8 byte-order mark (spreadsheets write one) is dropped: the header is still a header."""
    path = tmp_path / "p.csv"
    path.write_bytes(codecs.BOM_UTF8 + _hertz_csv().encode())
    rec = readers.read(path)
    x = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    assert np.array_equal(rec.x, x) and np.array_equal(rec.p, hertz(x))


HISTORY = "P,s,Q,sigma_bulk\n400,0.1,-60,-10\n420,0.12,60,10\n400,0.1,-60,-10\n"
HISTORY_FAULTS: list[Corruption] = [
    *[(f"{bad}-in-{col}", (lambda t, bad=bad, col=col: t.replace("420,0.12,60,10", ",".join(
        bad if c == col else v for c, v in zip(("P", "s", "Q", "sigma_bulk"), "420,0.12,60,10".split(","))))),
       rf"row 3, column `{col}`: '{re.escape(bad)}' must be a finite number")
      for bad in ("inf", "1e400") for col in ("P", "s", "Q", "sigma_bulk")],
] + TEXT_FAULTS


@pytest.mark.parametrize("name, corrupt, match", HISTORY_FAULTS, ids=[c[0] for c in HISTORY_FAULTS])
def test_a_bad_history_is_refused_by_name(tmp_path, capsys, name, corrupt, match):
    """A load history's CSV: the same faults, one ReaderError; ``threepart cycle`` exits 2 with one line."""
    path = _write(tmp_path / "h.csv", corrupt(HISTORY))
    with pytest.raises(ReaderError) as info:
        read_history(path)
    msg = str(info.value)
    assert f"history file {str(path)!r}" in msg and "\n" not in msg and re.search(match, msg), msg
    if name in ("binary", "utf16", "1e400-in-Q"):
        argv = ["cycle", "--R1", "10", "--R2", "10", "--b", "1", "--A", "1e-5", "--f", "0.5", "--history", str(path)]
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "Traceback" not in err and str(path) in err, err


def test_a_history_with_a_byte_order_mark_is_read(tmp_path):
    """Spreadsheets save CSV with a UTF-8 byte-order mark: its header's ``P`` is still ``P``."""
    path = tmp_path / "h.csv"
    path.write_bytes(codecs.BOM_UTF8 + HISTORY.encode())
    got = read_history(path)
    want = np.array([[400, 0.1, -60, -10], [420, 0.12, 60, 10], [400, 0.1, -60, -10]], dtype=float)
    assert np.array_equal(np.column_stack([got.P, got.s, got.Q, got.sigma_bulk]), want)


# --------------------------------------------------------------------------- mesh files


def _mesh_file(tmp_path: Path, file_format: str, suffix: str, name: str, edit: Callable) -> Path:
    """A mesh file of Hertz's field, as test_readers writes it, with ``edit(points, fields)`` applied."""
    points, cells = plane_mesh()
    fields = point_fields(points, name)
    edit(points, fields)
    path = tmp_path / f"bad{suffix}"
    meshio.write(path, meshio.Mesh(points, [("quad", cells)], point_data=fields), file_format=file_format)
    return path


def _surface_node(points: np.ndarray) -> int:
    """A node of the top surface, inside the contact."""
    return int(np.flatnonzero((points[:, 1] == 0.0) & (np.abs(points[:, 0]) < 0.5 * a_H))[0])


def _deep_node(points: np.ndarray) -> int:
    """A node off the surface, at the block's base."""
    return int(np.argmin(points[:, 1]))


def _set(where: Callable[[np.ndarray], int], column: int, value: float) -> Callable:
    def edit(points: np.ndarray, fields: dict) -> None:
        points[where(points), column] = value
    return edit


def _field(value: float) -> Callable:
    def edit(points: np.ndarray, fields: dict) -> None:
        name = next(iter(fields))
        fields[name] = fields[name].copy()
        fields[name][_surface_node(points)] = value
    return edit


MESH_FAULTS = [
    ("nan-y-on-the-surface", _set(_surface_node, 1, np.nan), r"1 of its \d+ nodes have a coordinate that is not finite"),
    ("nan-x-at-the-base", _set(_deep_node, 0, np.nan), r"1 of its \d+ nodes have a coordinate that is not finite"),
    ("inf-x-on-the-surface", _set(_surface_node, 0, np.inf), r"coordinate that is not finite \(node \d+ at \(inf, 0"),
    ("nan-pressure", _field(np.nan), r"the field '\w+' is not finite at 1 of the \d+ surface nodes"),
    ("inf-pressure", _field(np.inf), r"is not finite at 1 of the \d+ surface nodes"),
]


@pytest.mark.parametrize("file_format, suffix, name, options", FORMATS, ids=[f[0] for f in FORMATS])
@pytest.mark.parametrize("fault, edit, match", MESH_FAULTS, ids=[m[0] for m in MESH_FAULTS])
def test_a_bad_mesh_file_is_refused_by_name(tmp_path, capsys, file_format, suffix, name, options,
                                            fault, edit, match):
    """One non-finite coordinate anywhere, or a non-finite pressure on the surface, in each mesh
    format: refused as such, not as "no node lies on the top surface" or "several nodes share an x"."""
    path = _mesh_file(tmp_path, file_format, suffix, name, edit)
    msg = _refused(path, match, **options)
    assert "top surface" not in msg and "share an x" not in msg
    if fault == "nan-x-at-the-base" and file_format == "vtu":
        _cli_refuses(capsys, tmp_path, path, match)


@pytest.mark.parametrize("file_format, suffix, name, options", FORMATS, ids=[f[0] for f in FORMATS])
@pytest.mark.parametrize("fault", ["binary", "truncated", "empty"])
def test_an_unreadable_mesh_file_is_refused_by_name(tmp_path, file_format, suffix, name, options, fault):
    """Binary garbage, the first half of a good file, or no bytes, under each format's suffix."""
    data = _mesh_file(tmp_path, file_format, suffix, name, lambda points, fields: None).read_bytes()
    content = {"binary": BINARY, "truncated": data[:len(data) // 2], "empty": b""}[fault]
    _refused(_write(tmp_path / f"{fault}{suffix}", content), rf"meshio cannot read it as {file_format}: ",
             **options)


def test_a_bad_shear_field_is_refused_by_name(tmp_path):
    path = _mesh_file(tmp_path, "vtu", ".vtu", "contact_pressure",
                      lambda points, fields: fields.update(q=np.where(points[:, 1] == 0, np.nan, 0.0)))
    _refused(path, r"the field 'q' is not finite at \d+ of the \d+ surface nodes", shear="q")


@pytest.mark.parametrize("component, error, match", [
    ("x", InputTypeError, r"`component` = 'x' must be an integer, not str"),
    (1.5, InputTypeError, r"`component` = 1.5 must be an integer, not float"),
    (True, InputTypeError, r"`component` = True must be an integer, not bool"),
    (-1, InputError, r"`component` = -1 must lie in \[0, 8\]"),
    (2, InputError, r"the field 'u' has 2 components; pick one with component=0..1"),
])
def test_component_is_an_integer_in_range(tmp_path, component, error, match):
    """``component`` picks a column of a field with several: a word, a fraction or a flag is refused by name."""
    path = _mesh_file(tmp_path, "vtu", ".vtu", "contact_pressure", lambda points, fields: None)
    with pytest.raises(error, match=match):
        readers.read(path, field="u", component=component)
    # an integer picks the column written: the displacement's second column, zero
    rec = readers.read(path, field="u", component=1)
    assert rec.x.size == NX and not np.any(rec.p)


# --------------------------------------------------------------------------- any reader


NAN_READER = '''
import numpy as np

from threepart.readers import Record, register_reader


def read_nan(path, *, arg="path", **options):
    x = np.linspace(-1.0, 1.0, 5)
    return Record(x, np.where(x == 0.0, np.nan, 1.0 - x * x), None, {"source": "nan"})


register_reader("nanfmt", [".nanfmt"], read_nan, "a reader that lets a NaN through")
'''


def test_no_reader_returns_a_non_finite_number(tmp_path, monkeypatch):
    """A reader module that lets a NaN through (at x = 0) is refused by ``read`` itself, naming the file."""
    monkeypatch.setattr(readers, "_FORMATS", dict(readers._FORMATS))
    monkeypatch.setattr(readers, "_SUFFIXES", dict(readers._SUFFIXES))
    (tmp_path / "nan_reader.py").write_text(NAN_READER)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "nan_reader", raising=False)
    importlib.import_module("nan_reader")
    path = _write(tmp_path / "p.nanfmt", "anything")
    _refused(path, r"`p` is not finite at 1 of its 5 points \(the first at x = 0\)")

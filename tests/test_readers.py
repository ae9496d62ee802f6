"""Readers of other codes' results (``threepart.readers``): each format written by its own writer.

The reference is Hertz's pressure ``p0 sqrt(1 - x^2/a^2)`` (``a^2 = 2 P R A / pi``,
``p0 = 2 P / (pi a)``: the cylinder on a half-plane, not threepart's code) laid as a
point field on the top surface ``y = 0`` of a small plane mesh, written by meshio's
own writer of each format (VTU and XDMF as FEniCSx/dolfinx write them, MED as
Code_Aster, Exodus as MOOSE), read back through :func:`threepart.readers.read`
and judged end to end by ``threepart compare``.
"""
from __future__ import annotations

import importlib
import json
import math
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

from threepart import readers
from threepart.cli import main
from threepart.problem.material import rigid_punch


#: Hertz: a cylinder of radius R under P on a steel half-plane (rigid punch compliance)
R, P, E, NU = 10.0, 100.0, 210e3, 0.3
A = rigid_punch(E, NU)
a_H = math.sqrt(2 * P * R * A / math.pi)
p0_H = 2 * P / (math.pi * a_H)
#: the compliance given as such (``--A``): the reference is a rigid punch, whatever ``--E``'s convention
HERTZ_ARGS = ["--R1", str(R), "--R2", str(R), "--b", "0", "--P", str(P), "--E", str(E), "--nu", str(NU),
              "--A", repr(A)]
#: the files store doubles: the field and the positions read back to round-off (of p0, of a)
READ_BACK = 1e-12
#: nodes along the surface: 600 elements over 3 a (W/h = 400 over the contact, where the
#: referee's trapezoidal load is within its 1e-3; see the referee rows of the tolerance table)
NX = 601


def hertz(x: np.ndarray) -> np.ndarray:
    """Hertz's pressure of the cylinder (0 outside ``|x| < a``)."""
    return p0_H * np.sqrt(np.clip(1.0 - (x / a_H) ** 2, 0.0, None))


def plane_mesh(depth_shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """A block of quadrilaterals ``[-1.5 a, 1.5 a] x [-a, 0]``, three rows of nodes; its
    points (3 columns) and cells. ``depth_shift`` moves it down (no node at y = 0)."""
    xs = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    ys = np.linspace(-a_H, 0.0, 3) - depth_shift
    X, Y = np.meshgrid(xs, ys)
    points = np.c_[X.ravel(), Y.ravel(), np.zeros(X.size)]
    cells = np.array([[j * NX + i, j * NX + i + 1, (j + 1) * NX + i + 1, (j + 1) * NX + i]
                      for j in range(len(ys) - 1) for i in range(NX - 1)])
    return points, cells


def point_fields(points: np.ndarray, name: str = "contact_pressure") -> dict[str, np.ndarray]:
    """The pressure on the surface nodes (0 below it), and a displacement field beside it."""
    top = points[:, 1] == 0.0
    return {name: np.where(top, hertz(points[:, 0]), 0.0), "u": np.zeros((len(points), 2))}


#: (format, suffix, the pressure's field name, the options to read it): the field named as
#: each code's user would (dolfinx: the function's name; Code_Aster: NOM_CHAM_MED; MOOSE:
#: the contact action's aux variable contact_pressure)
FORMATS = [("vtu", ".vtu", "contact_pressure", {}),
           ("xdmf", ".xdmf", "contact_pressure", {}),
           ("med", ".med", "PRES_CONT", {"field": "PRES_CONT"}),
           ("exodus", ".e", "contact_pressure", {})]


def write(tmp_path: Path, file_format: str, suffix: str, name: str, **kw) -> Path:
    points, cells = plane_mesh(**kw)
    path = tmp_path / f"hertz{suffix}"
    meshio.write(path, meshio.Mesh(points, [("quad", cells)], point_data=point_fields(points, name)),
                 file_format=file_format)
    return path


@pytest.mark.parametrize("file_format, suffix, name, options", FORMATS)
def test_each_format_reads_back_hertz(tmp_path, file_format, suffix, name, options):
    """The surface nodes, sorted along x, carry Hertz's field; the record names its source."""
    path = write(tmp_path, file_format, suffix, name)
    rec = readers.read(path, **options)
    x_top = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    assert rec.x.shape == (NX,)
    assert np.max(np.abs(rec.x - x_top)) < READ_BACK * a_H
    assert np.max(np.abs(rec.p - hertz(x_top))) < READ_BACK * p0_H
    assert rec.q is None and rec.info["source"] == file_format and rec.info["field"] == name


@pytest.mark.parametrize("file_format, suffix, name, options", FORMATS)
def test_compare_judges_each_format_end_to_end(tmp_path, capsys, file_format, suffix, name, options):
    """``threepart compare`` on each format's file of Hertz's field: every check passes, no pitfall."""
    path = write(tmp_path, file_format, suffix, name)
    field = ["--field", options["field"]] if "field" in options else []
    assert main(["compare", "--pressure", str(path), *field, *HERTZ_ARGS, "--out", str(tmp_path / "rep")]) == 0
    doc = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert doc["passed"] and not doc["pitfalls"]
    assert doc["obtained"]["points"] == NX
    assert "PASSED" in capsys.readouterr().out


def test_the_last_time_step_is_read(tmp_path, monkeypatch):
    """A time series (dolfinx writes XDMF so, MOOSE its Exodus with the initial state first) is
    read at its last step, not meshio's first: step 0 carries no pressure, step 1 Hertz's."""
    points, cells = plane_mesh()
    x_top = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    monkeypatch.chdir(tmp_path)                 # meshio's TimeSeriesWriter puts its .h5 in the cwd
    xdmf = tmp_path / "series.xdmf"
    with meshio.xdmf.TimeSeriesWriter(xdmf) as writer:
        writer.write_points_cells(points, [("quad", cells)])
        writer.write_data(0.0, point_data={"contact_pressure": np.zeros(len(points))})
        writer.write_data(1.0, point_data=point_fields(points))
    exo = tmp_path / "moose.e"
    meshio.write(exo, meshio.Mesh(points, [("quad", cells)],
                                  point_data={"contact_pressure": np.zeros(len(points))}), file_format="exodus")
    import netCDF4

    with netCDF4.Dataset(exo, "a") as nc:       # a second step, as MOOSE appends them
        nc.variables["time_whole"][1] = 1.0
        nc.variables["vals_nod_var1"][1, :] = point_fields(points)["contact_pressure"]
    for path in (xdmf, exo):
        rec = readers.read(path)
        assert np.max(np.abs(rec.p - hertz(x_top))) < READ_BACK * p0_H, path.name


def test_named_surface_and_shear(tmp_path, capsys):
    """``surface=`` picks a node set (meshio turns it into a marker field for VTU), ``shear=``
    a second field: here the punch's own bottom nodes also lie at y = 0, so y = 0 alone is refused."""
    points, cells = plane_mesh()
    punch = points[points[:, 1] == 0.0] + [0.0, 0.0, 0.0]          # a second body's nodes at y = 0
    allp = np.r_[points, punch]
    top = np.flatnonzero(points[:, 1] == 0.0)
    fields = {"contact_pressure": np.r_[np.where(points[:, 1] == 0.0, hertz(points[:, 0]), 0.0),
                                        np.zeros(len(punch))]}
    fields["q"] = 0.3 * fields["contact_pressure"]
    path = tmp_path / "two.vtu"
    meshio.write(path, meshio.Mesh(allp, [("quad", cells)], point_data=fields, point_sets={"contact": top}))
    with pytest.raises(ValueError, match=r"several surface nodes share an x .* surface=NAME"):
        readers.read(path)
    rec = readers.read(path, surface="contact", shear="q")
    assert rec.q is not None
    assert np.max(np.abs(rec.p - hertz(rec.x))) < READ_BACK * p0_H
    assert np.max(np.abs(rec.q - 0.3 * hertz(rec.x))) < READ_BACK * p0_H
    # the command line's --surface: judged, and refused without it (one line, status 2)
    assert main(["compare", "--pressure", str(path), "--surface", "contact", *HERTZ_ARGS,
                 "--out", str(tmp_path / "rep")]) == 0
    assert main(["compare", "--pressure", str(path), *HERTZ_ARGS, "--out", str(tmp_path / "rep2")]) == 2


def test_unknown_suffix_names_the_formats(tmp_path, capsys):
    path = tmp_path / "p.xyz"
    path.write_text("0 1\n")
    with pytest.raises(ValueError, match=r"^`path` = '.*p.xyz': no reader for .xyz; the formats: csv \(.csv "
                                         r".txt\), frd \(.frd\), dat \(.dat\), vtu \(.vtu\), .*exodus \(.e "):
        readers.read(path)
    assert main(["compare", "--pressure", str(path), *HERTZ_ARGS, "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert "`--pressure`" in err and "no reader for .xyz" in err and len(err.strip().splitlines()) == 1


def test_missing_field_names_the_fields_present(tmp_path, capsys):
    path = write(tmp_path, "vtu", ".vtu", "temperature")
    with pytest.raises(ValueError, match=r"has no point field any of contact_pressure, CPRESS, .*; its point "
                                         r"fields: temperature, u; name the pressure with field=NAME$"):
        readers.read(path)
    with pytest.raises(ValueError, match=r"has no point field 'sigma'; its point fields: temperature, u"):
        readers.read(path, field="sigma")
    assert main(["compare", "--pressure", str(path), *HERTZ_ARGS, "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert "its point fields: temperature, u" in err and len(err.strip().splitlines()) == 1
    # with --field the same file is judged
    assert main(["compare", "--pressure", str(path), "--field", "temperature", *HERTZ_ARGS,
                 "--out", str(tmp_path / "r2")]) == 0


def test_a_file_without_surface_nodes(tmp_path):
    path = write(tmp_path, "vtu", ".vtu", "contact_pressure", depth_shift=a_H)
    with pytest.raises(ValueError, match=r"no node lies on the top surface y = 0 \(y spans \[.*\]\); name the "
                                         r"contact nodes' set with surface=NAME"):
        readers.read(path)
    with pytest.raises(ValueError, match=r"has no node set 'contact'; its point sets: none"):
        readers.read(path, surface="contact")


def test_bad_options_and_files(tmp_path):
    path = write(tmp_path, "vtu", ".vtu", "contact_pressure")
    with pytest.raises(ValueError, match=r"unknown option 'feild'; a mesh file takes field, surface"):
        readers.read(path, feild="p")
    with pytest.raises(ValueError, match=r"the field 'u' has 2 components; pick one with component=0..1"):
        readers.read(path, field="u")
    with pytest.raises(ValueError, match=r"`path` = '.*missing.vtu' is not a file"):
        readers.read(tmp_path / "missing.vtu")
    broken = tmp_path / "broken.vtu"
    broken.write_text("not xml")
    with pytest.raises(ValueError, match=r"meshio cannot read it as vtu"):
        readers.read(broken)
    with pytest.raises(ValueError, match=r"`file_format` = 'nosuch' is not a format"):
        readers.read(path, file_format="nosuch")


TOY = '''
"""A toy format: whitespace-separated ``x p`` rows, registered by this module alone."""
import numpy as np

from threepart.readers import Record, register_reader


def read_toy(path, *, arg="path", **options):
    xp = np.loadtxt(path)
    return Record(xp[:, 0], xp[:, 1], None, {"source": "toy"})


register_reader("toy", [".toy"], read_toy, "whitespace-separated x p")
'''


def test_a_new_reader_module_registers_itself(tmp_path, monkeypatch, capsys):
    """A module that calls register_reader is read by its suffix, listed in the help, and
    judged by ``threepart compare``, with no other edit."""
    monkeypatch.setattr(readers, "_FORMATS", dict(readers._FORMATS))
    monkeypatch.setattr(readers, "_SUFFIXES", dict(readers._SUFFIXES))
    (tmp_path / "toy_reader.py").write_text(TOY)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "toy_reader", raising=False)
    importlib.import_module("toy_reader")
    x = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    path = tmp_path / "hertz.toy"
    np.savetxt(path, np.c_[x, hertz(x)])
    rec = readers.read(path)
    assert rec.info["source"] == "toy" and np.max(np.abs(rec.p - hertz(x))) < READ_BACK * p0_H
    assert "toy (.toy): whitespace-separated x p" in readers.describe()
    assert main(["compare", "--pressure", str(path), *HERTZ_ARGS, "--out", str(tmp_path / "rep")]) == 0
    main(["compare", "--help"])
    assert "toy (.toy)" in capsys.readouterr().out


def test_register_reader_refuses_bad_rows():
    with pytest.raises(ValueError, match=r"`suffixes` = \['csv'\] must be one or more strings such as '.csv'"):
        readers.register_reader("bad", ["csv"], lambda p, **k: None, "")
    with pytest.raises(TypeError, match=r"`read_function` = 3 must be callable"):
        readers.register_reader("bad", [".bad"], 3, "")  # type: ignore[arg-type]


def test_csv_reads_an_optional_shear_column(tmp_path):
    x = np.linspace(-1.5 * a_H, 1.5 * a_H, NX)
    path = tmp_path / "pq.csv"
    np.savetxt(path, np.c_[x, hertz(x), 0.2 * hertz(x)], delimiter=",", header="x,p,q", comments="")
    rec = readers.read(path)
    assert rec.q is not None and np.max(np.abs(rec.q - 0.2 * hertz(x))) < READ_BACK * p0_H

"""Mesh files through meshio: a contact-pressure point field on the contact surface of a plane mesh.

Any code that writes its mesh and a nodal field in a format meshio reads can be
judged: VTU and XDMF (FEniCSx/dolfinx), MED (Code_Aster), Exodus (MOOSE). The
reader keeps the surface nodes -- those on the top surface ``z = 0`` (the
mesh's second coordinate is ``y = -z``, up; the block lies below it), or a node
set named by the option ``surface`` (a point set, or a point field that is
nonzero on the set, as meshio turns point sets into for VTU and XDMF) -- and
the pressure there from a point field: the option ``field``, or the first of
:data:`FIELDS` the file holds. ``x`` is the nodes' first coordinate
(undeformed). Options:

``field``
    The pressure's point field (compressive positive).
``surface``
    The contact nodes' set (default: the nodes at ``y = 0``).
``shear``
    A point field of the shear traction; without it the first of :data:`SHEAR_FIELDS` the
    file has (GetFEM's deck writes ``contact_shear``), else none.
``component``
    Which column of a field with several components (default: a field must have one):
    an integer in ``0..MAX_COMPONENT``.

A file meshio cannot read, a node coordinate that is not finite anywhere in the
mesh (refused before the surface is looked for), or a pressure or shear that is
not finite on the surface is one :class:`~threepart.errors.ReaderError` naming the file.

A file with several time steps is read at its last (XDMF time series by
meshio's ``TimeSeriesReader``, Exodus through netCDF4); meshio alone reads
the first.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from . import Record, register_reader
from threepart.problem.checks import integer
from threepart.errors import InputError, ReaderError

__all__ = ["read_mesh_file", "FIELDS", "SHEAR_FIELDS", "SURFACE_TOLERANCE", "MESHIO_FORMATS", "MAX_COMPONENT"]

#: the pressure fields looked for, in order, when the option ``field`` is not given
FIELDS = ("contact_pressure", "CPRESS", "pressure", "contact pressure", "PRES", "p")
#: the point fields read as the shear when ``shear`` is not given, in this order
SHEAR_FIELDS = ("contact_shear", "CSHEAR")
#: a node lies on the top surface y = 0 within this fraction of the mesh's extent (round-off of
#: the writer's coordinates: single precision in some files, 1.2e-7)
SURFACE_TOLERANCE = 1e-6
#: format name -> (meshio's file format, suffixes, help)
MESHIO_FORMATS = {
    "vtu": ("vtu", (".vtu",), "VTK unstructured grid (FEniCSx/dolfinx, ParaView)"),
    "xdmf": ("xdmf", (".xdmf", ".xmf"), "XDMF and HDF5 (FEniCSx/dolfinx; the last time step)"),
    "med": ("med", (".med", ".rmed"), "MED (Code_Aster, Salome)"),
    "exodus": ("exodus", (".e", ".exo", ".ex2", ".exii"), "Exodus II (MOOSE; the last time step)"),
}
_OPTIONS = ("field", "surface", "shear", "component")
#: the largest ``component`` asked for: a point field has at most 9 (a 3-D tensor's), so 0..8
MAX_COMPONENT = 8
#: what meshio's readers raise on a file they cannot read (a ReadError, or the parser's own
#: error: XML's ParseError is a SyntaxError, HDF5's and netCDF's an OSError)
_UNREADABLE: tuple[type[BaseException], ...] = (ValueError, OSError, KeyError, IndexError, SyntaxError,
                                                 RuntimeError)


def read_mesh_file(path: Path, *, arg: str = "path", file_format: str = "vtu",
                   **options: Any) -> Record:
    """The contact pressure (and shear) along the surface of the plane mesh in ``path``.

    Raises
    ------
    ReaderError
        A file meshio cannot read, a node coordinate that is not finite
        (anywhere in the mesh), no pressure field (the message names the fields
        present), no surface node, a pressure or shear that is not finite on
        the surface.
    ValueError
        An option this reader does not know, a field with several components
        and no ``component``; a ``component`` that is not an integer is a TypeError.
    """
    unknown = [k for k in options if k not in _OPTIONS]
    if unknown:
        raise InputError(f"`{arg}` = {str(path)!r}: unknown option {unknown[0]!r}; "
                         f"a mesh file takes {', '.join(_OPTIONS)}")
    if options.get("component") is not None:
        options["component"] = integer("component", options["component"], 0, MAX_COMPONENT)
    points, point_data, point_sets = _load(path, file_format, arg)
    _finite_points(points, path, arg)
    names = [options["field"]] if options.get("field") else [f for f in FIELDS if f in point_data]
    if not names or names[0] not in point_data:
        looked = repr(options["field"]) if options.get("field") else "any of " + ", ".join(FIELDS)
        raise ReaderError(f"`{arg}` = {str(path)!r} has no point field {looked}; its point fields: "
                         f"{', '.join(sorted(point_data)) or 'none'}; name the pressure with field=NAME")
    nodes = _surface(points, point_data, point_sets, options.get("surface"), path, arg)
    x = points[nodes, 0]
    order = np.argsort(x, kind="stable")
    nodes, x = nodes[order], x[order]
    p = _column(point_data[names[0]], options.get("component"), names[0], path, arg)[nodes]
    q = None
    if not options.get("shear"):
        options["shear"] = next((f for f in SHEAR_FIELDS if f in point_data), None)
    if options.get("shear"):
        if options["shear"] not in point_data:
            raise ReaderError(f"`{arg}` = {str(path)!r} has no point field {options['shear']!r} (shear); "
                             f"its point fields: {', '.join(sorted(point_data))}")
        q = _column(point_data[options["shear"]], options.get("component"), options["shear"], path, arg)[nodes]
    for name, v in ((names[0], p), (options.get("shear"), q)):
        if v is not None and not np.all(np.isfinite(v)):
            raise ReaderError(f"`{arg}` = {str(path)!r}: the field {name!r} is not finite at "
                              f"{int(np.count_nonzero(~np.isfinite(v)))} of the {nodes.size} surface nodes")
    return Record(x, p, q, {"source": file_format, "field": names[0], "nodes": int(nodes.size)})


def _load(path: Path, file_format: str, arg: str
          ) -> tuple[np.ndarray, dict[str, np.ndarray], dict[str, np.ndarray]]:
    """The points, point fields (at the last time step) and point sets of a mesh file."""
    import meshio

    if file_format == "exodus":
        try:
            import netCDF4  # noqa: F401
        except ImportError:
            raise InputError(f"`{arg}` = {str(path)!r}: reading Exodus needs netCDF4 "
                             "(pip install netCDF4)") from None
    # the format's own reader: meshio.read prints and exits the process on a file it cannot read
    try:
        mesh = getattr(meshio, file_format).read(str(path))
    except (meshio.ReadError, *_UNREADABLE) as exc:
        if file_format != "xdmf":
            raise ReaderError(f"`{arg}` = {str(path)!r}: meshio cannot read it as {file_format}: "
                              f"{str(exc).splitlines()[0] if str(exc) else type(exc).__name__}") from None
        return _xdmf_last_step(path, arg)
    point_data = {k: np.asarray(v) for k, v in mesh.point_data.items()}
    if file_format == "exodus":
        point_data.update(_exodus_last_step(path))
    return np.asarray(mesh.points, dtype=float), point_data, \
        {k: np.asarray(v) for k, v in mesh.point_sets.items()}


def _xdmf_last_step(path: Path, arg: str) -> tuple[np.ndarray, dict[str, np.ndarray], dict[str, np.ndarray]]:
    """An XDMF time series (as dolfinx and meshio's ``TimeSeriesWriter`` write it) at its last step."""
    import meshio

    try:
        with meshio.xdmf.TimeSeriesReader(path) as reader:
            points, _ = reader.read_points_cells()
            data: dict[str, np.ndarray] = {}
            for k in range(reader.num_steps):
                _, data, _ = reader.read_data(k)
    except (meshio.ReadError, *_UNREADABLE) as exc:
        raise ReaderError(f"`{arg}` = {str(path)!r}: meshio cannot read it as xdmf: "
                          f"{str(exc).splitlines()[0] if str(exc) else type(exc).__name__}") from None
    return np.asarray(points, dtype=float), {k: np.asarray(v) for k, v in data.items()}, {}


def _exodus_last_step(path: Path) -> dict[str, np.ndarray]:
    """An Exodus file's nodal variables at its last time step (meshio reads the first)."""
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        if "name_nod_var" not in nc.variables or nc.variables["vals_nod_var1"].shape[0] < 2:
            return {}
        var = nc.variables["name_nod_var"]
        var.set_auto_mask(False)
        names = [b"".join(c).decode("utf-8").strip() for c in var[:]]
        out = {}
        for k, name in enumerate(names):
            vals = nc.variables[f"vals_nod_var{k + 1}"]
            vals.set_auto_mask(False)
            out[name] = np.asarray(vals[-1])
        return out


def _finite_points(points: np.ndarray, path: Path, arg: str) -> None:
    """Refuse a mesh with a node coordinate that is not finite, anywhere (before the surface is looked for)."""
    bad = np.flatnonzero(~np.all(np.isfinite(points), axis=1))
    if bad.size:
        where = ", ".join(f"{v:g}" for v in points[bad[0]])
        raise ReaderError(f"`{arg}` = {str(path)!r}: {bad.size} of its {len(points)} nodes have a "
                          f"coordinate that is not finite (node {int(bad[0])} at ({where}))")


def _surface(points: np.ndarray, point_data: dict[str, np.ndarray], point_sets: dict[str, np.ndarray],
             name: str | None, path: Path, arg: str) -> np.ndarray:
    """The surface nodes: the set ``name`` (a point set, or a point field nonzero there), or y = 0."""
    if name is not None:
        # meshio writes point sets "a", "b" to formats without them as one field "a-b": the
        # set's index there, -1 elsewhere
        joined = [k for k in point_data if name in k.split("-") and np.min(point_data[k]) == -1]
        if name in point_sets:
            nodes = np.asarray(point_sets[name], dtype=np.int64).ravel()
        elif joined:
            nodes = np.flatnonzero(np.asarray(point_data[joined[0]]).ravel() == joined[0].split("-").index(name))
        elif name in point_data:
            nodes = np.flatnonzero(np.asarray(point_data[name]).reshape(len(points), -1)[:, 0] != 0)
        else:
            raise ReaderError(f"`{arg}` = {str(path)!r} has no node set {name!r}; its point sets: "
                             f"{', '.join(sorted(point_sets)) or 'none'}, its point fields: "
                             f"{', '.join(sorted(point_data)) or 'none'}")
        where = f"in the set {name!r}"
    else:
        if points.shape[1] < 2:
            raise ReaderError(f"`{arg}` = {str(path)!r}: a mesh of one dimension has no surface y = 0")
        extent = float(np.ptp(points[:, :2], axis=0).max()) or 1.0
        nodes = np.flatnonzero(np.abs(points[:, 1]) <= SURFACE_TOLERANCE * extent)
        where = (f"on the top surface y = 0 (y spans [{points[:, 1].min():.6g}, "
                 f"{points[:, 1].max():.6g}]); name the contact nodes' set with surface=NAME")
    if nodes.size == 0:
        raise ReaderError(f"`{arg}` = {str(path)!r}: no node lies {where}")
    x = points[nodes, 0]
    if np.unique(x).size < x.size:
        raise ReaderError(f"`{arg}` = {str(path)!r}: several surface nodes share an x (two bodies "
                         "touching at y = 0?); name the block's contact nodes with surface=NAME")
    return nodes


def _column(values: np.ndarray, component: int | None, name: str, path: Path, arg: str) -> np.ndarray:
    """One component of a point field: the field itself if it has one, else column ``component``."""
    v = np.asarray(values, dtype=float)
    v = v.reshape(v.shape[0], -1)
    if v.shape[1] == 1:
        return v[:, 0]
    if component is None or not 0 <= component < v.shape[1]:
        raise InputError(f"`{arg}` = {str(path)!r}: the field {name!r} has {v.shape[1]} components; "
                         f"pick one with component=0..{v.shape[1] - 1}")
    return v[:, int(component)]


def _register() -> None:
    for name, (meshio_format, suffixes, help) in MESHIO_FORMATS.items():
        def read(path: Path, *, arg: str = "path", _fmt: str = meshio_format, **options: Any) -> Record:
            return read_mesh_file(path, arg=arg, file_format=_fmt, **options)

        register_reader(name, suffixes, read, help + ", a point field on the contact surface")


_register()

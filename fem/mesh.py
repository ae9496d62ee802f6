"""Substrate meshes for the FE model: named presets, building through :mod:`meshes`, reading.

Meshing and solving stay apart: :mod:`meshes` writes an ``.msh`` file with gmsh,
and this module reads it back through meshio into a scikit-fem ``MeshTri`` with
its boundaries looked up by physical-group name.
"""
from __future__ import annotations

import contextlib
import copy
import functools
import math
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Iterator

import meshio
import numpy as np
from skfem import MeshTri

from threepart import cache
from threepart.errors import InputError, InputTypeError, NoConvergenceError
from threepart.meshes import PunchSpec, SubstrateSpec, build_punch, build_substrate
from threepart.output import scratch_dir
from threepart.problem.checks import finite

from ._boundary import boundary

__all__ = ["MeshPreset", "PRESETS", "Substrate", "read_substrate", "make_substrate", "make_punch",
           "preset"]


#: Bounds of a preset's parameters. The upper bound of ``n`` and the lower bound of
#: ``growth`` keep a solve within this machine's memory and time: 8x the default's
#: elements across ``W`` (the default has ``n = 300``, ``growth = 0.1``), about 8^2 x its DOFs.
PRESET_BOUNDS: dict[str, tuple[float, float]] = {
    "n": (4.0, 2400.0), "growth": (0.0125, 1.0), "L": (4.0, 1e4), "margin": (0.0, 2.0),
    "refine": (1.0, 1024.0)}
PRESET_MEANING = {"n": "elements across the contact width", "growth": "the size growth rate",
                  "L": "the block size in contact widths",
                  "margin": "the zone's margin in contact widths",
                  "refine": "how much finer the elements are at the ends and joins"}


@dataclass(frozen=True)
class MeshPreset:
    """Mesh density relative to the contact width ``W``.

    Parameters
    ----------
    n
        Elements across ``W`` along the surface (``h = W / n``).
    growth
        Size growth rate away from the candidate zone.
    L
        Block size in units of ``W`` (width and depth).
    margin
        Candidate zone extends ``margin * W`` beyond each estimated contact end.
    refine
        Elements are ``refine`` times smaller at the contact ends and the joins
        ``x = ±b`` (where the pressure is not smooth), growing back to ``W/n`` at
        the rate ``growth``; ``1`` keeps the zone uniform. With ``refine > 1`` the
        estimated contact ends are also mesh nodes.

    Notes
    -----
    Each parameter is bounded (:data:`PRESET_BOUNDS`): ``n`` in ``[4, 2400]``,
    ``growth`` in ``[0.0125, 1]``, ``L`` in ``[4, 1e4]``, ``margin`` in
    ``(0, 2]``, ``refine`` in ``[1, 1024]``; a bool or a string is a ``TypeError``.

    Scaling ``n`` by ``k`` and ``growth`` by ``1/k`` at fixed ``refine`` and ``L``
    scales every element size by ``1/k``: a self-similar refinement family.
    """

    n: float
    growth: float = 0.15
    L: float = 200.0
    margin: float = 0.1
    refine: float = 1.0

    def __post_init__(self) -> None:
        for name, (lo, hi) in PRESET_BOUNDS.items():
            v = finite(name, getattr(self, name))   # a bool or a string is a TypeError
            object.__setattr__(self, name, v)
            lo_open = name in ("margin",)
            if not (lo < v if lo_open else lo <= v) or not v <= hi:
                raise InputError(f"`{name}` = {v!r} must lie in {'(' if lo_open else '['}{lo:g}, "
                                 f"{hi:g}]: {PRESET_MEANING[name]}")

    def scaled(self, k: float) -> "MeshPreset":
        """The member of this preset's self-similar family with every size divided by ``k``."""
        return replace(self, n=self.n * k, growth=self.growth / k)

    def spec(self, lo: float, hi: float, breakpoints: tuple[float, ...] = ()) -> SubstrateSpec:
        """Substrate spec for an estimated contact ``[lo, hi]``.

        The estimate's width and zone ends are snapped to a binary grid of
        about W/64 (:func:`snap`), so that a change in their last digits (a
        different BLAS, a faster solver in the trial stage) gives the same
        mesh instead of one that gmsh builds differently.

        With ``refine > 1`` the ends ``lo`` and ``hi``, snapped to a grid of
        ``2^-14`` of that width, become mesh nodes, and the elements are
        ``refine`` times smaller around them and around the breakpoints.
        """
        W, q = snap(hi - lo)
        x_lo = math.floor((lo - self.margin * W) / q) * q
        x_hi = math.ceil((hi + self.margin * W) / q) * q
        h = W / self.n
        if self.refine == 1:
            return SubstrateSpec(x_lo=x_lo, x_hi=x_hi, h=h, L=self.L * W,
                                 growth=self.growth, breakpoints=tuple(breakpoints))
        fine = q / 2.0 ** 8
        ends = (round(lo / fine) * fine, round(hi / fine) * fine)
        return SubstrateSpec(x_lo=x_lo, x_hi=x_hi, h=h, L=self.L * W, growth=self.growth,
                             breakpoints=tuple(breakpoints) + ends,
                             refine_at=tuple(x for x in (*breakpoints, *ends) if x_lo < x < x_hi),
                             h_fine=h / self.refine)


def snap(W: float) -> tuple[float, float]:
    """``(W rounded to the grid, the grid step)``: a binary grid of step ``2^(floor(log2 W) - 6)``."""
    q = 2.0 ** (math.floor(math.log2(W)) - 6)
    return max(q, round(W / q) * q), q


#: The default mesh: 300 elements across W, 8x finer at the contact ends and the joins.
_DEFAULT = MeshPreset(n=300, growth=0.1, L=200.0, refine=8.0)

#: Named presets. ``trial`` and ``locate`` only find the contact for the others (a first
#: estimate, then the ends to about 1e-4 W); ``quick``, ``default`` and ``fine`` are one
#: self-similar family (every element size halved from one to the next).
PRESETS: dict[str, MeshPreset] = {
    "trial": MeshPreset(n=24, growth=0.3, L=100.0, margin=0.5),
    "locate": MeshPreset(n=150, growth=0.2, L=100.0, refine=8.0),
    "quick": _DEFAULT.scaled(0.5),
    "default": _DEFAULT,
    "fine": _DEFAULT.scaled(2.0),
}


def preset(name: str) -> MeshPreset:
    """Look up a preset by name, with a ``ValueError`` listing the names."""
    try:
        return PRESETS[name]
    except KeyError:
        raise InputError(f"`mesh` = {name!r} is not a preset; use one of {sorted(PRESETS)}, "
                         "a MeshPreset, a SubstrateSpec or a .msh path") from None


@dataclass(frozen=True, eq=False)
class Substrate:
    """A triangle mesh of the substrate with its named boundaries.

    Attributes
    ----------
    mesh
        Linear triangles; the FE model raises the order itself.
    boundaries
        Facet indices of each physical curve group (``"contact"``, ``"base"``, ...).
    path
        The ``.msh`` file it was read from.
    """

    mesh: MeshTri
    boundaries: dict[str, np.ndarray]
    path: str


@boundary
def read_substrate(path: str | Path) -> Substrate:
    """Read a gmsh ``.msh`` through meshio; map each physical curve group to facets.

    Raises
    ------
    ValueError
        If the file has no triangles or no ``"contact"`` and ``"base"`` groups.
    """
    # gmsh's reader itself: ".msh" is also ANSYS's extension, and meshio.read prints a
    # line for every reader it tries and exits the process (sys.exit) when none reads it
    try:
        m = meshio.gmsh.read(str(path))
    except (meshio.ReadError, ValueError, KeyError, IndexError, EOFError, UnicodeDecodeError,
            AttributeError, TypeError) as e:
        why = " ".join(str(e).split()) or f"{type(e).__name__}, not an MSH file"
        raise InputError(f"`path` = {str(path)!r} is not a gmsh mesh meshio can read: {why}") from None
    cells = m.cells_dict
    if "triangle" not in cells:
        raise InputError(f"`path` = {str(path)!r} holds no triangles")
    mesh = MeshTri(np.ascontiguousarray(m.points[:, :2].T), np.ascontiguousarray(cells["triangle"].T))
    tags = m.cell_data_dict.get("gmsh:physical", {}).get("line")
    lines = cells.get("line")
    names = {int(v[0]): k for k, v in m.field_data.items() if int(v[1]) == 1}
    # facet index of each (sorted) vertex pair
    key = mesh.facets[0].astype(np.int64) * mesh.p.shape[1] + mesh.facets[1]
    order = np.argsort(key)
    boundaries: dict[str, np.ndarray] = {}
    if lines is not None and tags is not None:
        pair = np.sort(lines, axis=1).astype(np.int64)
        k = pair[:, 0] * mesh.p.shape[1] + pair[:, 1]
        facet = order[np.searchsorted(key, k, sorter=order)]
        for tag, name in names.items():
            boundaries[name] = np.sort(facet[tags == tag])
    missing = {"contact", "base"} - set(boundaries)
    if missing:
        raise InputError(f"`path` = {str(path)!r} lacks the physical groups {sorted(missing)}")
    return Substrate(mesh=mesh, boundaries=boundaries, path=str(path))


#: meshes kept for the run (a default mesh holds about 1 MB, a fine one about 4 MB)
MESH_CACHE_SIZE = 32


@boundary
def make_substrate(spec: SubstrateSpec) -> Substrate:
    """Build the mesh of ``spec`` with gmsh in a temporary file and read it back.

    gmsh runs once per spec in a run: the spec (a frozen dataclass, the
    parameters the manifest records) keys a cache of the last
    ``MESH_CACHE_SIZE`` meshes, and every call returns its own copy, so a
    caller that changes its substrate changes no later one. A failure of gmsh
    is a :class:`NoConvergenceError` (:func:`gmsh_failure`).
    """
    if not isinstance(spec, SubstrateSpec):
        raise InputTypeError(f"`spec` must be a SubstrateSpec, not {type(spec).__name__}")
    return copy.deepcopy(_meshed(spec))


@boundary
def make_punch(spec: PunchSpec) -> Substrate:
    """The punch body of ``spec`` (:func:`threepart.meshes.build_punch`), its top (``"base"``) to be
    clamped; meshed once per spec and kept as :func:`make_substrate` keeps a block's mesh.

    A map point solves its punch on the same meshes more than once (its locating
    mesh for each of its two meshes, the small and first-order kinematics of
    its small-slope study on one mesh), and gmsh's punch, one line per element
    of the contact zone, costs as much as the block's.
    """
    if not isinstance(spec, PunchSpec):
        raise InputTypeError(f"`spec` must be a PunchSpec, not {type(spec).__name__}")
    return copy.deepcopy(_meshed(spec))


@functools.lru_cache(maxsize=MESH_CACHE_SIZE)
def _meshed(spec: SubstrateSpec | PunchSpec) -> Substrate:
    """The cached mesh of ``spec`` (a block's or a punch's); never handed out (:func:`make_substrate`
    and :func:`make_punch` copy it).

    Kept on disk too, in threepart's cache (:func:`_from_disk`), so that gmsh runs once
    per spec across runs as well.
    """
    k = _mesh_key(spec)
    sub = _from_disk(k)
    if sub is not None:
        return sub
    with scratch_dir("threepart-mesh-") as tmp:   # marked: a killed run's is cleaned by the next
        with gmsh_failure("the punch" if isinstance(spec, PunchSpec) else "the substrate"):
            path = (build_punch(spec, Path(tmp) / "punch.msh") if isinstance(spec, PunchSpec)  # mypy narrows here
                    else build_substrate(spec, Path(tmp) / "substrate.msh"))
            sub = read_substrate(path)
    cache.store(_KIND, k, {"p": sub.mesh.p, "t": sub.mesh.t,
                           **{f"group_{name}": f for name, f in sub.boundaries.items()}})
    return sub


#: the kind of the meshes' entries in threepart's cache
_KIND = "mesh"


@functools.cache
def _mesh_key(spec: SubstrateSpec | PunchSpec) -> str:
    """The cache key of the mesh of ``spec``: the spec (its type and every field, a punch's block
    zone too), gmsh's version and the meshing code's source."""
    import gmsh

    import threepart.meshes as meshes

    source = sorted((f.name, f.read_bytes()) for f in Path(meshes.__file__).parent.glob("*.py"))
    return cache.key({"spec": repr(spec), "gmsh": gmsh.__version__, "source": repr(source)})


def _from_disk(k: str) -> Substrate | None:
    """The mesh of key ``k`` from threepart's cache, if whole and consistent; else None."""
    def fits(a: dict[str, np.ndarray]) -> bool:
        p, t = a.get("p"), a.get("t")
        groups = {n for n in a if n.startswith("group_")}
        return (p is not None and t is not None and p.ndim == t.ndim == 2 and p.shape[0] == 2
                and t.shape[0] == 3 and t.dtype.kind in "iu" and t.size > 0
                and int(t.min()) >= 0 and int(t.max()) < p.shape[1]
                and {"group_contact", "group_base"} <= groups
                and all(a[n].dtype.kind in "iu" for n in groups))

    got = cache.load(_KIND, k, fits)
    if got is None:
        return None
    mesh = MeshTri(np.ascontiguousarray(got["p"]), np.ascontiguousarray(got["t"]))
    groups = {n.removeprefix("group_"): got[n] for n in got if n.startswith("group_")}
    if any(len(f) and int(f.max()) >= mesh.facets.shape[1] for f in groups.values()):
        return None
    return Substrate(mesh=mesh, boundaries=groups, path="<threepart cache>")


@contextlib.contextmanager
def gmsh_failure(what: str) -> Iterator[None]:
    """Turn a failure of gmsh, or of reading back what it wrote, into :class:`NoConvergenceError`.

    gmsh raises a bare ``Exception``; a mesh it wrote but could not finish
    fails to read back. Either way the mesh generator, not the input, failed
    (the input was checked before), and no temporary path is named.
    """
    try:
        yield
    except (TypeError, NoConvergenceError):
        raise
    except Exception as e:   # noqa: BLE001 -- gmsh's own exceptions are bare Exceptions
        why = " ".join(str(e).split()[:30]) or type(e).__name__
        why = why.replace(tempfile.gettempdir(), "<tmp>")
        raise NoConvergenceError(f"gmsh could not mesh {what}: {why}") from None

"""Meshes: the committed reference mesh against its manifest, physical groups by name, gmsh hygiene."""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

import gmsh
import meshio
import numpy as np
import pytest

from threepart import meshes
from threepart.meshes import REFERENCE_SPEC, SubstrateSpec, build_substrate, check_manifest, describe

HERE = Path(meshes.__file__).parent
#: node coordinates that gmsh places at given points (joins, zone ends): rounding (mm)
GMSH_ROUND_OFF = 1e-12
#: the contact's node spacing may exceed h by the rounding of gmsh's transfinite placement only
SPACING = 1e-9


def test_reference_mesh_matches_manifest():
    """The manifest's numbers recomputed from the file on disk with meshio and hashlib."""
    assert check_manifest(HERE / "manifest.json") == ["reference.msh"]
    entry = json.loads((HERE / "manifest.json").read_text())["meshes"][0]
    m = meshio.read(HERE / entry["file"])
    assert entry["nodes"] == len(m.points) and entry["triangles"] == len(m.cells_dict["triangle"])
    for name, group in entry["physical_groups"].items():
        tag, dim = m.field_data[name]
        kind = "line" if dim == 1 else "triangle"
        assert group == {"dim": dim, "cells": int(np.sum(m.cell_data_dict["gmsh:physical"][kind] == tag))}
    # SHA-256 of the x, y coordinates rounded to 1e-9 L as little-endian int64 (the manifest's rule)
    grid = 1e-9 * entry["parameters"]["L"]
    q = np.rint(m.points[:, :2] / grid).astype("<i8")
    assert hashlib.sha256(q.tobytes()).hexdigest() == entry["coordinate_checksum"]


def test_manifest_records_gmsh_version_and_parameters():
    entry = json.loads((HERE / "manifest.json").read_text())["meshes"][0]
    assert entry["gmsh_version"].count(".") == 2
    assert entry["parameters"]["h"] == REFERENCE_SPEC.h
    assert entry["nodes"] > 0 and entry["triangles"] > 0


def test_rebuild_reproduces_reference_checksum(tmp_path):
    entry = json.loads((HERE / "manifest.json").read_text())["meshes"][0]
    assert entry["gmsh_version"] == gmsh.__version__, (
        f"manifest made with gmsh {entry['gmsh_version']}, have {gmsh.__version__}: pyproject pins "
        "gmsh; after changing the pin, regenerate with `python -m meshes`")
    path = build_substrate(REFERENCE_SPEC, tmp_path / "again.msh")
    assert describe(path, REFERENCE_SPEC)["coordinate_checksum"] == entry["coordinate_checksum"]


def test_manifest_mismatch_is_reported(tmp_path):
    entry = json.loads((HERE / "manifest.json").read_text())["meshes"][0]
    entry["nodes"] += 1
    (tmp_path / "reference.msh").write_bytes((HERE / "reference.msh").read_bytes())
    meshes.write_manifest([entry], tmp_path / "manifest.json")
    with pytest.raises(meshes.ManifestError, match="`nodes`"):
        check_manifest(tmp_path / "manifest.json")


def _group(m: meshio.Mesh, name: str) -> np.ndarray:
    """Node indices of the line cells in the physical group ``name``."""
    tag = m.field_data[name][0]
    lines = m.cells_dict["line"][m.cell_data_dict["gmsh:physical"]["line"] == tag]
    return np.unique(lines)


def test_physical_groups_by_name():
    m = meshio.read(HERE / "reference.msh")
    spec = REFERENCE_SPEC
    assert set(meshes.PHYSICAL_CURVES) | {"substrate"} == set(m.field_data)
    x, y = m.points[:, 0], m.points[:, 1]
    contact = _group(m, "contact")
    assert np.allclose(y[contact], 0.0)
    assert x[contact].min() == pytest.approx(spec.x_lo) and x[contact].max() == pytest.approx(spec.x_hi)
    for xb in spec.breakpoints:  # nodes at x = ±b
        assert np.min(np.abs(x[contact] - xb)) < GMSH_ROUND_OFF
    assert np.allclose(y[_group(m, "base")], -spec.L)
    assert np.allclose(x[_group(m, "left")], -spec.L / 2)
    assert np.allclose(x[_group(m, "right")], spec.L / 2)
    top = _group(m, "top")
    assert np.allclose(y[top], 0.0) and np.all((x[top] <= spec.x_lo + GMSH_ROUND_OFF) | (x[top] >= spec.x_hi - GMSH_ROUND_OFF))
    # uniform spacing h (or less) along the contact zone
    assert np.diff(np.sort(x[contact])).max() <= spec.h * (1 + SPACING)


def test_gmsh_finalized_after_error(tmp_path, monkeypatch):
    def boom(*args, **kwargs):
        raise RuntimeError("meshing failed on purpose")

    monkeypatch.setattr(gmsh.model.mesh, "generate", boom)
    with pytest.raises(RuntimeError, match="on purpose"):
        build_substrate(REFERENCE_SPEC, tmp_path / "x.msh")
    assert not gmsh.isInitialized()


def test_gmsh_finalized_after_success(tmp_path):
    build_substrate(REFERENCE_SPEC, tmp_path / "x.msh")
    assert not gmsh.isInitialized()


@pytest.mark.parametrize("kwargs, match", [
    (dict(x_lo=1.0, x_hi=0.0, h=0.1, L=10.0), "`x_hi`"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.0, L=10.0), "`h`"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.1, L=1.0), "`L`"),
    (dict(x_lo=-1.0, x_hi=1.0, h=0.1, L=10.0, growth=-1.0), "`growth`"),
    (dict(x_lo=-1.0, x_hi=float("nan"), h=0.1, L=10.0), "`x_hi`"),
])
def test_spec_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SubstrateSpec(**kwargs)


def _blocks(path: Path) -> tuple[meshio.Mesh, dict[str, set[tuple[int, ...]]]]:
    """meshio's mesh of ``path`` and each physical group's cells as sets of sorted node tuples."""
    m = meshio.gmsh.read(str(path))
    tags = m.cell_data_dict["gmsh:physical"]
    groups = {}
    for name, (tag, dim) in m.field_data.items():
        kind = "line" if int(dim) == 1 else "triangle"
        groups[name] = {tuple(sorted(c)) for c in m.cells_dict[kind][tags[kind] == tag]}
    return m, groups


@pytest.mark.parametrize("body", ["substrate", "punch"])
def test_one_entity_per_group_holds_gmsh_own_file(tmp_path, monkeypatch, body):
    """A graded zone is one gmsh curve per element; the file holds one entity per physical group
    (meshio reads it in one block each) and the very nodes and elements gmsh's own writing of the
    model holds (the reference: gmsh.write of the meshed model, the old path)."""
    from threepart.meshes import PunchSpec, build_punch
    from threepart.meshes import punch as punch_module, substrate as substrate_module

    zone = SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.05, L=40.0, growth=0.3, breakpoints=(-0.25, 0.25),
                         refine_at=(-0.25, 0.25), h_fine=0.01)
    if body == "punch":
        build = lambda path: build_punch(PunchSpec(zone=zone, b=0.25, R1=2.0, R2=1.0, H=1.0), path)
    else:
        build = lambda path: build_substrate(zone, path)
    grouped, groups = _blocks(build(tmp_path / "grouped.msh"))
    assert len(grouped.cells) == len(grouped.field_data)        # one block per group
    for module in (punch_module, substrate_module):
        monkeypatch.setattr(module, "write_grouped", lambda path, curves, surface: gmsh.write(str(path)))
    plain, plain_groups = _blocks(build(tmp_path / "plain.msh"))
    assert len(plain.cells) > 2 * len(plain.field_data)          # the per-element curves
    assert np.array_equal(grouped.points, plain.points)
    assert np.array_equal(grouped.cells_dict["triangle"], plain.cells_dict["triangle"])
    assert groups == plain_groups

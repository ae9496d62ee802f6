"""Manifest of a kept mesh: gmsh version, parameters, counts and a coordinate checksum.

The manifest makes a committed mesh reproducible and checkable: :func:`check_manifest`
re-reads the ``.msh`` file and compares every recorded number.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path
from typing import Any

import meshio
import numpy as np

from threepart.errors import ManifestError

from .substrate import SubstrateSpec

__all__ = ["coordinate_checksum", "describe", "write_manifest", "check_manifest", "ManifestError"]


def coordinate_checksum(points: np.ndarray, scale: float) -> str:
    """SHA-256 of the node coordinates rounded to ``1e-9 * scale`` (as int64)."""
    q = np.rint(np.asarray(points, dtype=float)[:, :2] / (1e-9 * scale)).astype("<i8")
    return hashlib.sha256(np.ascontiguousarray(q).tobytes()).hexdigest()


def describe(path: str | Path, spec: SubstrateSpec) -> dict[str, Any]:
    """Manifest entry of the mesh file ``path`` built from ``spec``."""
    import gmsh

    m = meshio.read(path)
    tags = m.cell_data_dict["gmsh:physical"]
    groups = {}
    for name, (tag, dim) in m.field_data.items():
        kind = "line" if int(dim) == 1 else "triangle"
        groups[name] = {"dim": int(dim), "cells": int(np.sum(tags[kind] == tag))}
    return {
        "file": Path(path).name,
        "gmsh_version": gmsh.__version__,
        "parameters": dataclasses.asdict(spec),
        "nodes": int(m.points.shape[0]),
        "triangles": int(m.cells_dict["triangle"].shape[0]),
        "physical_groups": groups,
        "coordinate_checksum": coordinate_checksum(m.points, spec.L),
    }


def write_manifest(entries: list[dict[str, Any]], path: str | Path, overwrite: bool = False) -> None:
    """Write manifest ``entries`` as JSON to ``path``, atomically.

    Through :func:`threepart.output.write_file`: a new file, or the manifest
    threepart wrote there earlier if unchanged; any other existing file only
    with ``overwrite`` (e.g. the committed manifest, when the meshes are
    rebuilt on purpose).
    """
    from threepart.output import write_file

    write_file(path, json.dumps({"meshes": entries}, indent=2, sort_keys=True) + "\n", arg="path",
               overwrite=overwrite, how="choose another name or pass overwrite=True to replace it")


def check_manifest(manifest: str | Path) -> list[str]:
    """Re-read every mesh listed in ``manifest`` and compare it with its entry.

    Returns
    -------
    list of str
        The files checked.

    Raises
    ------
    ManifestError
        Naming the file and the first quantity that differs.
    """
    manifest = Path(manifest)
    checked = []
    for entry in json.loads(manifest.read_text())["meshes"]:
        params: dict[str, Any] = {k: tuple(v) if isinstance(v, list) else v
                                  for k, v in entry["parameters"].items()}
        spec = SubstrateSpec(**params)
        found = describe(manifest.parent / entry["file"], spec)
        for key in ("nodes", "triangles", "physical_groups", "coordinate_checksum"):
            if found[key] != entry[key]:
                raise ManifestError(f"{entry['file']}: `{key}` is {found[key]!r}, "
                                    f"the manifest says {entry[key]!r}")
        checked.append(entry["file"])
    return checked

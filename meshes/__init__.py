"""Substrate meshes built with gmsh, with named physical groups and a manifest.

Builders
--------
SubstrateSpec        -- frozen parameters of the block mesh (zone, size h, block L, grading)
build_substrate      -- mesh a SubstrateSpec with gmsh and write an ``.msh`` file
gmsh_session         -- context manager: initialize gmsh quietly, always finalize
PHYSICAL_CURVES      -- names of the physical curve groups ("contact", "top", "base", ...)
PunchSpec            -- a punch of real shape (flat centre, exact arcs, flanks, height H)
build_punch          -- mesh a PunchSpec with gmsh, its face matching a substrate's zone

Manifest
--------
describe             -- manifest entry of a mesh file (gmsh version, counts, checksum)
write_manifest       -- write manifest entries as JSON
check_manifest       -- re-read the listed meshes and compare them with the manifest
coordinate_checksum  -- SHA-256 of the rounded node coordinates
ManifestError        -- a mesh does not match its manifest
REFERENCE_SPEC       -- parameters of the committed ``reference.msh``
"""
from __future__ import annotations

from .manifest import ManifestError, check_manifest, coordinate_checksum, describe, write_manifest
from .punch import PunchSpec, build_punch
from .substrate import PHYSICAL_CURVES, SubstrateSpec, build_substrate, gmsh_session

__all__ = ["SubstrateSpec", "build_substrate", "gmsh_session", "PHYSICAL_CURVES", "PunchSpec",
           "build_punch",
           "describe", "write_manifest", "check_manifest", "coordinate_checksum",
           "ManifestError", "REFERENCE_SPEC"]

#: The small committed reference mesh (``meshes/reference.msh``): a unit contact zone
#: with breakpoints at ``x = ±0.25``.
REFERENCE_SPEC = SubstrateSpec(x_lo=-0.6, x_hi=0.6, h=0.05, L=40.0, growth=0.3,
                               breakpoints=(-0.25, 0.25))

"""Regenerate the committed reference mesh and its manifest: ``python -m meshes``."""
from __future__ import annotations

from pathlib import Path

from . import REFERENCE_SPEC, build_substrate, describe, write_manifest

if __name__ == "__main__":
    here = Path(__file__).parent
    path = build_substrate(REFERENCE_SPEC, here / "reference.msh")
    write_manifest([describe(path, REFERENCE_SPEC)], here / "manifest.json", overwrite=True)
    print(f"wrote {path} and {here / 'manifest.json'}")

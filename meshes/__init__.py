"""meshes: filled by its own issue."""

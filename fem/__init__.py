"""fem: filled by its own issue."""

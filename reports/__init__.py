"""reports: filled by its own issue."""

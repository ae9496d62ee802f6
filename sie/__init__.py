"""sie: filled by its own issue."""

"""The problem: the punch (eq. 2), the material (eq. 4), the input checks, the catalogue."""

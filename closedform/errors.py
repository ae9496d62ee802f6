"""Named exceptions of the closed-form library.

Every bad input is a ``ValueError`` (or a subclass below) whose message names
the argument and the limit; a root finder that fails raises
:class:`NoConvergenceError`. No function returns NaN for an inadmissible case.
"""
from __future__ import annotations

__all__ = ["NoConvergenceError", "LiftOffError", "FullSlidingError", "StickZoneError",
           "SeparationError"]


class NoConvergenceError(RuntimeError):
    """A root finder did not converge; no result is returned."""


class LiftOffError(ValueError):
    """The lever arm ``s`` (or the load ``P``) puts a contact edge inside the central segment."""


class FullSlidingError(ValueError):
    """``|Q| >= f P``: the contact slides, there is no stick zone."""


class StickZoneError(ValueError):
    """The stick zone would end inside the central segment, where the closed form does not hold."""


class SeparationError(ValueError):
    """A concave centre would separate (tensile pressure): the contact is not simply connected."""

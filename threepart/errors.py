"""The one error family of threepart; every solver raises from here.

Every error threepart raises derives from :class:`ThreepartError`, so that
``except ThreepartError`` catches any refusal of threepart's, and keeps the
built-in base it always had, so that ``except ValueError`` still catches bad
input: ``class LiftOffError(ThreepartError, ValueError)``.

The family (built-in base in brackets):

ThreepartError          -- the base of all: any refusal of threepart's
NoConvergenceError      -- an iteration did not converge (RuntimeError)
LiftOffError            -- ``s`` or ``P`` puts a contact edge inside the central segment (ValueError)
FullSlidingError        -- ``|Q| >= f P`` (ValueError)
StickZoneError          -- a stick zone the method cannot represent (ValueError)
  StickSeparationError  -- its corrective pressure breaks Coulomb's law
  SlipReversalError     -- a bulk stress reverses the slip at one end
    CycleSlipReversalError -- a cycle's steady state would slip against the half-cycle
  CoulombError          -- an answer's shear breaks ``|q| <= f p``
  OneSidedSlipError     -- a cycle's permanent stick zone reaches one edge only
  DisjointContactsError -- a cycle's end states' contacts do not overlap: no permanent stick zone
SeparationError         -- a concave centre would separate (ValueError)
ContactZoneError        -- the FE contact reached the end of its mesh zone (RuntimeError)
  MeshResolutionError   -- a contact end too close to a join for the FE mesh
SlopeLimitError         -- past half-plane theory's small-slope limit (ValueError)
ArcExtentError          -- a contact end past an edge arc's extent (ValueError)
ReaderError             -- a file of another code that cannot be read: names the file and why (ValueError)
OutputExistsError       -- a path holds what threepart did not write (ValueError)
CcxError                -- CalculiX ran but failed, or wrote no result (RuntimeError)
CcxMissing              -- ``ccx`` is not on the PATH (OSError)
GetfemError             -- a GetFEM script ran but failed (Newton, a crash), or wrote no result (RuntimeError)
GetfemMissing           -- no interpreter that imports ``getfem`` (OSError)
ManifestError           -- a mesh file does not match its manifest (AssertionError)

Bad input is a :class:`ValueError` (or one of the subclasses below) whose
message names the argument and the limit. A contact that leaves the paper's
framework is refused with the subclass that says why. A numerical method that
does not reach its tolerance raises :class:`NoConvergenceError`; no function
returns a number it does not trust, and none returns NaN.
"""
from __future__ import annotations

__all__ = ["ThreepartError", "NoConvergenceError", "LiftOffError", "FullSlidingError", "StickZoneError",
           "SeparationError", "ContactZoneError", "MeshResolutionError", "SlopeLimitError",
           "ArcExtentError", "StickSeparationError", "SlipReversalError", "CoulombError", "full_sliding",
           "ReaderError", "OutputExistsError", "CcxError", "CcxMissing", "ManifestError"]


class ThreepartError(Exception):
    """The base of every error threepart raises: ``except ThreepartError`` catches any refusal."""


class NoConvergenceError(ThreepartError, RuntimeError):
    """An iteration (root finder, Newton, active set) did not converge; no result is returned."""


class LiftOffError(ThreepartError, ValueError):
    """The lever arm ``s`` (or the load ``P``) puts a contact edge inside the central segment."""


class FullSlidingError(ThreepartError, ValueError):
    """``|Q| >= f P``: the contact slides as a whole, there is no stick zone."""


class StickZoneError(ThreepartError, ValueError):
    """The stick zone would end inside the central segment, where the closed form does not hold."""


class StickSeparationError(StickZoneError):
    """The single stick zone found breaks Coulomb's law: its corrective pressure ``p*`` is not in ``[0, p]``.

    The Ciavarella–Jäger superposition ``q = f (p - p*)`` obeys ``|q| <= f p``
    only where ``0 <= p* <= p``. On a concave centre the corrective contact of
    the stick zone (the punch at ``P* = P - |Q|/f`` with the tilt held) can be
    tensile, or exceed ``p``, on the centre's dip; the true stick zone is then
    not that single interval (it splits in two or rests on one flank).
    """


class SlipReversalError(StickZoneError):
    """A bulk stress reverses the slip at one end: the Ciavarella–Jäger superposition does not hold.

    Under a bulk stress ``sigma_bulk`` rising with ``Q`` the stick zone is the
    superposition's only while both its ends move inwards and every slip zone
    slips in the direction that opposes ``q`` (docs/BULK_STRESS.md). Past that,
    one end slips backwards (a reversed slip zone, or a second stick zone
    appears); the closed form refuses, and ``method="auto"`` falls back.
    """


class CoulombError(StickZoneError):
    """A partial-slip answer's shear breaks Coulomb's law: ``|q| > f p`` somewhere in the contact.

    Raised by the one check of every answer (:func:`threepart.results.answer.check_coulomb`)
    whatever the method: the stick zone found is not one that friction can
    hold (too coarse a discretisation, or too near full sliding for it). A
    ``StickZoneError``, so that ``method="auto"`` falls back from the closed form.
    """


def full_sliding(name: str, Q: float, f: float, P: float, what: str = "there is no stick zone"
                 ) -> FullSlidingError:
    """The one :class:`FullSlidingError` of every method, for ``|Q| >= f P``.

    Parameters
    ----------
    name
        The shear argument's name (``"Q"``, ``"Q_max"``).
    Q, f, P
        The shear force, the coefficient of friction and the normal load.
    what
        What is lost, e.g. ``"there is no fretting cycle"``.
    """
    return FullSlidingError(
        f"|`{name}`| = {abs(Q):.6g} >= f P = {f * P:.6g} (`f` = {f:g}, `P` = {P:.6g}): the "
        f"contact slides as a whole (full sliding), {what}")


class SeparationError(ThreepartError, ValueError):
    """A concave centre would separate: the single contact's pressure is tensile.

    The true contact then splits into two zones, or the punch rests on one
    flank alone; neither is the closed form's single contact ``[-a, c]``.
    """


class ContactZoneError(ThreepartError, RuntimeError):
    """The FE contact reached an end of the mesh's candidate zone, so the mesh cannot hold it."""


class MeshResolutionError(ContactZoneError):
    """A contact end lies too close to a join for the mesh to resolve (fewer than a few elements).

    The pressure has a kink at each join; an end within a few elements of one
    is located no better than an element, and the tilt with it. A preset mesh
    is refined automatically up to a limit; past it, or on a mesh the user
    gave, this is raised rather than a silently coarse answer returned.
    """


class SlopeLimitError(ThreepartError, ValueError):
    """The contact's surface slope ``max |v'|`` exceeds the small-slope limit of half-plane theory.

    Half-plane theory measures the gap vertically and applies the tractions to
    the undeformed surface; the limit is ``threepart.problem.validate.SLOPE_LIMIT``.
    """


class ArcExtentError(ThreepartError, ValueError):
    """A contact end runs past the geometric extent of an edge arc (``a > b + R1`` or ``c > b + R2``)."""


# --- the steady state of in-phase loading (docs/STEADY_STATE.md) --------------------------------
__all__ += ["CycleSlipReversalError", "OneSidedSlipError", "DisjointContactsError"]


class CycleSlipReversalError(SlipReversalError):
    """In the steady state of a cycle some point would slip against the half-cycle's direction.

    The steady-state superposition (docs/STEADY_STATE.md, eq. S4) holds only
    while, on each half-cycle, the stick zone shrinks from the whole contact to
    the permanent one and every point of the slip zones slips in the sense of
    ``ΔQ`` (eq. S10): a change of the normal load, of the tilt or of the bulk
    stress can reverse the slip at one end. Past that the closed form and the
    SIE refuse; ``method="auto"`` falls back, and only a marched history answers.
    """


class OneSidedSlipError(StickZoneError):
    """The permanent stick zone of a cycle would reach one edge of the smaller contact but not the other.

    Then one end slips and the other has shaken down (a tilt that changes with
    the load), or the two ends slip in opposite senses (a bulk stress that
    changes more than the shear): neither is the steady-state superposition
    (docs/STEADY_STATE.md, eq. S12), whose bounded corrective pressure needs a
    stick zone inside the contact and one sense of slip a half-cycle.
    """


class DisjointContactsError(StickZoneError):
    """The contacts of a cycle's two end states do not overlap: no point stays in contact all cycle.

    The permanent stick zone of a cycle's steady state lies inside the smaller
    of the two end states' contacts and inside both; where their intersection
    is empty there is none, and no stick zone may be returned outside a contact.
    """


# --- files: other codes' output, and threepart's own output --------------------------------------

class ReaderError(ThreepartError, ValueError):
    """A file of another code cannot be read: the message names the file and what is wrong with it."""


class OutputExistsError(ThreepartError, ValueError):
    """A path may not be written: it holds something threepart did not write, or that was changed."""


class CcxError(ThreepartError, RuntimeError):
    """``ccx`` (CalculiX) ran but failed, or wrote no result."""


class CcxMissing(ThreepartError, OSError):
    """``ccx`` (CalculiX) is not on the PATH."""


class ManifestError(ThreepartError, AssertionError):
    """A mesh file does not match its manifest."""


# --- bad input ---------------------------------------------------------------------------------
__all__ += ["InputError", "InputTypeError"]


class InputError(ThreepartError, ValueError):
    """A bad value of an argument: the message names the argument and the limit it breaks."""


class InputTypeError(ThreepartError, TypeError):
    """An argument of the wrong type: the message names the argument and the type it needs."""


# --- GetFEM, the second outside referee (threepart.getfem) ---------------------------------------
__all__ += ["GetfemError", "GetfemMissing"]


class GetfemError(ThreepartError, RuntimeError):
    """A GetFEM script ran but failed (Newton did not converge, GetFEM raised), or wrote no result."""


class GetfemMissing(ThreepartError, OSError):
    """No Python interpreter that imports ``getfem`` (``THREEPART_GETFEM_PYTHON``, ``python3``)."""

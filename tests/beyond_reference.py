"""Closed-form references for contacts past the paper's framework, built from its own formulas.

Past lift-off the paper's closed form does not apply as printed, yet two
regimes still have exact solutions that owe nothing to the SIE or the FEM:

* **An edge on the central segment.** If the left end ``ℓ`` of the contact
  lies on the centre (``-b < ℓ < b``) and the right end ``r`` on the R2
  segment, only the profile on ``[ℓ, r]`` matters. It is the profile of the
  punch ``Punch(R1, R2, b')`` with ``b' = (b - ℓ)/2`` shifted by
  ``x0 = b - b'``, at its lift-off state ``a' = b'``: over the contact the
  shifted slope differs from the original by the constant ``x0/R``, which the
  tilt takes up: ``α = α' - x0/R``. So ``P``, ``s`` and ``α`` follow from the forward formulas
  (:mod:`closedform.formulas`, checked against quadrature) of the shifted
  punch. The mirror image covers a right end on the centre.
* **The punch on one corner.** A contact wholly on the R2 segment
  (``ℓ > b``) sees a single parabola of radius R2: a Hertz contact centred at
  the lever arm ``s``, half-width ``sqrt(2 P A R2/π)`` (eq. contact_law_Hertz)
  and the tilt that levels the profile there, ``α = -g'(s)`` (eq. 2:
  ``v' = α + g'``).

The inverse problems (ends for a load and a lever arm, or a load and a tilt, as
the stick zone needs) are solved here by Newton on those forward formulas,
started from a fixed guess, never from a solver's answer.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import root

from threepart import closedform as cf
from threepart.problem.punch import Punch


def _shifted(punch: Punch, left: float) -> tuple[Punch, float]:
    """The punch whose left join sits at ``left`` on the centre, and its shift ``x0``."""
    b2 = 0.5 * (punch.b - left)
    return Punch(punch.R1, punch.R2, b2, punch.R), punch.b - b2


def forward(punch: Punch, left: float, right: float, A: float) -> tuple[float, float, float]:
    """``(P, s, α)`` of the contact ``[left, right]``, left end on the centre, right on R2."""
    if not (-punch.b < left < punch.b < right):
        raise ValueError(f"[{left}, {right}] must start on the centre and end on R2")
    sp, x0 = _shifted(punch, left)
    a, c = sp.b, right - x0
    P = float(cf.formulas.load(sp, a, c, A))
    s = float(cf.formulas.lever_arm(sp, a, c)) + x0
    alpha = float(cf.formulas.tilt(sp, a, c)) - x0 * punch.kappa0
    return P, s, alpha


def edge_on_centre(punch: Punch, P: float, A: float, *, s: float | None = None,
                   alpha: float | None = None) -> tuple[float, float]:
    """Ends ``(left, right)`` of a contact with its left end on the centre, for ``P`` and ``s`` or ``α``.

    Exactly one of ``s`` (tilt free) and ``alpha`` (tilt given: the stick
    zone's corrective problem) is given. Newton (MINPACK's hybrid method) on
    the forward formulas, started from the middle of the centre and a Hertz
    width; the ends are kept in place by ``left = -b cos φ``, ``right = b + |w|``.
    Raises ``ValueError`` if it does not converge to such a contact.
    """
    if (s is None) == (alpha is None):
        raise ValueError("give exactly one of `s` and `alpha`")
    i, target = (1, s) if s is not None else (2, alpha)
    width = math.sqrt(2 * P * A * punch.R2 / math.pi)   # Hertz width of the R2 segment: the scale
    scale = (width, width, width / punch.R2)[i]

    def ends(z: np.ndarray) -> tuple[float, float]:
        return -punch.b * math.cos(z[0]), punch.b + abs(z[1])

    def miss(z: np.ndarray) -> list[float]:
        got = forward(punch, *ends(z), A)
        return [got[0] / P - 1.0, (got[i] - target) / scale]

    sol = root(miss, [0.5 * math.pi, width], method="hybr", options={"xtol": 1e-15})
    left, right = ends(sol.x)
    if max(abs(r) for r in miss(sol.x)) > 1e-12 or not -punch.b < left < punch.b:
        raise ValueError(f"no contact with its left end on the centre: {sol.message}")
    return left, right


def on_corner(punch: Punch, P: float, s: float, A: float) -> tuple[float, float, float]:
    """``(left, right, α)`` of the punch resting on its R2 corner alone (Hertz, centred at ``s``)."""
    h = float(cf.special.hertz_half_width(P, punch.R2, A))
    if s - h <= punch.b:
        raise ValueError(f"the Hertz contact [{s - h}, {s + h}] reaches the centre")
    return s - h, s + h, -float(punch.slope(s))

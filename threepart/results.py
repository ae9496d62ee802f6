"""The one result shape shared by the closed form, the SIE and the FEM solvers.

Every solver returns a :class:`NormalResult` (and, for partial slip, a
:class:`SlipResult`) subclass, so that :mod:`threepart.reports` never
special-cases a method. It holds no solution formula.

Sign conventions (see README): ``P > 0`` is compressive, ``s`` is the lever arm
of the load, positive to the right, and equals the centroid of the pressure;
``pressure(x) >= 0`` is compressive (the paper's ``p`` is negative);
``shear(x)`` has the sign of ``Q`` and integrates to ``Q``.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from .punch import Punch

__all__ = ["NormalResult", "SlipResult", "Peak"]


@dataclass(frozen=True)
class Peak:
    """A pressure maximum ``p`` at position ``x``."""

    x: float
    p: float


@dataclass(frozen=True)
class NormalResult:
    """Solution of the normal problem on the contact ``[-a, c]``.

    Attributes
    ----------
    punch, A
        Geometry and compliance (eq. 4) that were solved for.
    a, c
        Contact extent ``[-a, c]``.
    alpha
        Tilt of the punch (eq. 2); 0 when ``tilt == "suppressed"``.
    P, s
        Compressive load and its lever arm (the pressure centroid).
    tilt
        ``"free"`` or ``"suppressed"``.
    method
        ``"closedform"``, ``"sie"`` or ``"fem"``.
    info
        Discretisation metadata (``n``, ``h``, ``dofs``, timings, ...).
    """

    punch: Punch
    A: float
    a: float
    c: float
    alpha: float
    P: float
    s: float
    tilt: str = "free"
    method: str = ""
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive contact pressure at ``x`` (0 outside ``[-a, c]``)."""
        raise NotImplementedError

    @property
    def width(self) -> float:
        """Contact width ``W = a + c``."""
        return self.a + self.c

    def peaks(self, n: int = 2001) -> tuple[Peak, Peak]:
        """Largest pressure left and right of ``x = 0``, each refined by a bounded search.

        For a single-humped distribution (Hertz, case C) both may be the same
        point or one may sit at ``x = 0``.
        """
        out = []
        for lo, hi in ((-self.a, min(0.0, self.c)), (max(0.0, -self.a), self.c)):
            x = np.linspace(lo, hi, n)
            p = self.pressure(x)
            i = int(np.argmax(p))
            left, right = x[max(i - 1, 0)], x[min(i + 1, n - 1)]
            best = Peak(float(x[i]), float(p[i]))
            if right > left:
                r = minimize_scalar(lambda t: -float(self.pressure(t)), bounds=(left, right),
                                    method="bounded", options={"xatol": 1e-12 * self.width})
                if -r.fun > best.p:
                    best = Peak(float(r.x), float(-r.fun))
            out.append(best)
        return out[0], out[1]


@dataclass(frozen=True)
class SlipResult:
    """Partial-slip solution: stick zone ``[-(d+e), d-e]`` inside the contact.

    Attributes
    ----------
    normal
        The normal solution the shear load was applied to.
    Q, f
        Shear force and coefficient of friction, ``|Q| < f P``.
    d, e
        Stick-zone half-width and eccentricity (stick zone centred at ``-e``).
    """

    normal: NormalResult
    Q: float
    f: float
    d: float
    e: float
    method: str = ""
    info: dict[str, Any] = field(default_factory=dict, compare=False)

    # the normal result's fields, so that a slip result has the shared shape too
    @property
    def a(self) -> float:
        return self.normal.a

    @property
    def c(self) -> float:
        return self.normal.c

    @property
    def alpha(self) -> float:
        return self.normal.alpha

    @property
    def P(self) -> float:
        return self.normal.P

    @property
    def s(self) -> float:
        return self.normal.s

    @property
    def stick_zone(self) -> tuple[float, float]:
        """``(-(d+e), d-e)``."""
        return -(self.d + self.e), self.d - self.e

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Compressive pressure of the normal problem."""
        return self.normal.pressure(x)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear traction ``q(x)``, with the sign of ``Q``; integrates to ``Q``."""
        raise NotImplementedError

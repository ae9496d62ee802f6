"""Partial slip by the Ciavarella–Jäger superposition, stick zone from the discretised equations.

With elastically similar bodies the shear problem (paper eq.
integral_equation_tangential) uncouples from the normal one, and the shear is

    q(x) = sign(Q) f [p(x) - p*(x)],

where ``p`` is the normal pressure on ``[-a, c]`` and the corrective ``p*`` is
the bounded solution of the *same* equation (same ``v'``, same tilt ``α``) on
the stick zone ``[-(d+e), d-e]`` (eq. integral_equation_2), with load
``P* = P - |Q|/f`` (eq. horizontal_equilibrium). The two stick-zone ends follow
from the discretised consistency and load equations exactly as the contact ends
do in :mod:`sie.normal` (:func:`sie.normal.solve_ends` with ``α`` given), so
``d = h*`` and ``e = -m*``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from threepart.validate import check_finite, check_positive
from threepart.errors import FullSlidingError
from threepart.results import NormalResult, SlipResult

from .normal import DEFAULT_N, DEFAULT_SCHEME, check_scheme, solve_ends
from .series import ChebyshevPressure

__all__ = ["SieSlipResult", "solve_partial_slip"]


@dataclass(frozen=True)
class SieSlipResult(SlipResult):
    """Partial-slip solution from :func:`solve_partial_slip`.

    Attributes
    ----------
    n, scheme
        Discretisation of the corrective pressure ``p*``.
    stick
        The corrective pressure ``p*`` on the stick zone (zero outside).
    """

    n: int = 0
    scheme: str = ""
    stick: ChebyshevPressure | None = field(default=None, repr=False, compare=False)

    def corrective(self, x: ArrayLike) -> np.ndarray:
        """Corrective pressure ``p*(x)`` (0 outside the stick zone)."""
        assert self.stick is not None
        return self.stick(x)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear ``q = sign(Q) f (p - p*)``; has the sign of ``Q`` and integrates to ``Q``."""
        return math.copysign(1.0, self.Q) * self.f * (self.normal.pressure(x) - self.corrective(x)) \
            if self.Q != 0 else np.zeros(np.shape(x))


def _check_slip(normal: NormalResult, Q: float, f: float) -> None:
    if not isinstance(normal, NormalResult):
        raise ValueError(f"`normal` = {normal!r} must be a NormalResult (from solve_normal)")
    check_positive(f=f)
    check_finite(Q=Q)
    if abs(Q) >= f * normal.P:
        raise FullSlidingError(f"`Q` = {Q:g} must satisfy |Q| < f P = {f * normal.P:g} "
                               "(at |Q| = f P the contact slides as a whole)")


def solve_partial_slip(normal: NormalResult, Q: float, f: float, *, n: int | None = None,
                       scheme: str | None = None) -> SieSlipResult:
    """Stick zone ``[-(d+e), d-e]`` and shear ``q(x)`` for shear force ``Q`` and friction ``f``.

    Parameters
    ----------
    normal
        A normal solution (any method): its punch, ``A``, ``α``, ``P`` and
        ``pressure`` are used.
    Q
        Shear force, ``|Q| < f P``; the shear has its sign.
    f
        Coefficient of friction, > 0.
    n, scheme
        Discretisation of ``p*``; by default those of ``normal`` when it is
        an SIE result, else ``n = 1024`` and ``"projected"``.

    Returns
    -------
    SieSlipResult
        ``method="sie"``; ``info`` holds ``n``, ``scheme``, ``iterations``,
        ``residual`` and ``time_s``. Its ``within_paper`` says whether the
        stick zone contains the central segment, as the paper's closed form
        requires (end of its partial-slip section); a stick zone that ends on
        the central segment is solved all the same, as is one on a contact
        past lift-off.

    Raises
    ------
    ValueError
        For invalid input (``FullSlidingError`` for ``|Q| >= f P``).
    NoConvergenceError
        If the Newton iteration fails.
    """
    _check_slip(normal, Q, f)
    n = int(normal.info.get("n", DEFAULT_N)) if n is None else n
    scheme = str(normal.info.get("scheme", DEFAULT_SCHEME)) if scheme is None else scheme
    sch = check_scheme(scheme, n)
    t0 = time.perf_counter()
    P_star = normal.P - abs(Q) / f
    punch, A = normal.punch, normal.A
    m0 = 0.5 * (normal.c - normal.a)
    h0 = 0.5 * (normal.a + normal.c) * math.sqrt(P_star / normal.P)
    m, h, _, its, res = solve_ends(punch, A, P_star, sch, alpha=normal.alpha, m0=m0, h0=h0)
    d, e = h, -m
    lo, hi = m - h, m + h
    if lo < -normal.a * (1 + 1e-12) or hi > normal.c * (1 + 1e-12):
        raise ValueError(f"`Q` = {Q:g}: stick zone [{lo:.6g}, {hi:.6g}] leaves the contact "
                         f"[{-normal.a:.6g}, {normal.c:.6g}]; is `normal` consistent with its punch?")
    stick, extra = sch.pressure(punch, A, m, h)
    info = {"n": sch.n, "scheme": sch.name, "iterations": its, "residual": res,
            "time_s": time.perf_counter() - t0, "P_star": P_star, **extra}
    return SieSlipResult(normal=normal, Q=float(Q), f=float(f), d=d, e=e, method="sie", info=info,
                         n=sch.n, scheme=sch.name, stick=stick)

"""Any profile: the three-part punch plus a worn depth, solved by the SIE's own equations (issue 39).

A :class:`WornProfile` is the punch of eq. (2) with a depth ``w(x) >= 0`` removed
from it (the gap grows by ``w``; docs/WEAR.md, section 4), tabulated at knots and
interpolated piecewise linearly (``"linear"``) or by a monotone C1 cubic
(``"pchip"``). Its slope is ``v'(x) + w'(x)``.

The SIE's schemes reduce a trial contact ``[m - h, m + h]`` to the Chebyshev
coefficients ``G_k`` of the slope (:mod:`sie.schemes`). :class:`ProfileScheme`
adds the worn slope's coefficients to the punch's exact ones, so that
:func:`sie.normal.solve_ends`, :func:`sie.slip.stick_zone` and the fretting
cycle's loading zones solve the worn profile with no second solver:

* ``"linear"``: ``w'`` is a sum of steps, whose coefficients are exact
  (``θ_j/π`` and ``(2/π) sin kθ_j / k``, ``β_j = cos θ_j`` the knot);
* ``"pchip"``: ``w'`` is C1; its coefficients are taken by the discrete cosine
  transform at :data:`SAMPLES_PER_TERM` times as many first-kind Chebyshev
  points as sine terms (Gauss–Chebyshev quadrature of the projection).

Ends
----
``ends="bounded"``: both contact ends free, the pressure bounded there (the
consistency condition fixes them, as :func:`sie.solve_normal`).
``ends="unbounded"``: the contact ``[x1, x2]`` given, the pressure square-root
singular at both ends (docs/WEAR.md, eq. W3):
``p = Σ (G_k/A) sin kθ + (C0 + C1 cos θ)/sin θ``, with ``C0`` from the load,
``C1`` from the moment (free tilt; then ``α = -G_0 - A C1``, eq. W6) or from the
tilt (suppressed; then ``s`` is returned). A worn limit's contact is its stick zone.

WornProfile          -- punch + worn depth: ``depth``, ``slope``, ``profile``; ``from_csv`` reads (x, h)
ProfileScheme        -- the scheme of a worn profile (moments and pressure on a trial contact)
solve_profile        -- normal contact on a worn profile, bounded or unbounded ends
ProfileNormalResult  -- SieNormalResult with its profile
SingularPressure     -- a bounded sine series plus ``(C0 + C1 cos θ)/sin θ``
profile_gap          -- gap outside a bounded contact of the worn profile
"""
from __future__ import annotations

import dataclasses
import math
import os
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.fft
from numpy.typing import ArrayLike
from scipy.interpolate import PchipInterpolator

from threepart.errors import InputError, InputTypeError, SeparationError
from threepart.problem.punch import Punch
from threepart.results import Diagnostics
from threepart.textfile import finite_row, read_text
from threepart.problem.validate import check_contact, check_punch

from .fretting import approach as punch_approach, stick_gap
from .normal import SieNormalResult, check_normal, solve_ends
from .schemes import Projected
from .series import ChebyshevPressure

__all__ = ["WornProfile", "ProfileScheme", "solve_profile", "ProfileNormalResult",
           "SingularPressure", "profile_gap", "profile_approach", "KINDS", "ENDS", "DEFAULT_TERMS"]

KINDS = ("linear", "pchip")
ENDS = ("bounded", "unbounded")
#: sine terms of a worn profile's pressure by default: a C1 worn slope's coefficients fall as
#: k^-2, so the truncation leaves ~1/n of the worn part's pressure next to a kink of w''
DEFAULT_TERMS = 2048
#: first-kind Chebyshev points per sine term of the "pchip" projection (aliasing ~ (4n)^-2)
SAMPLES_PER_TERM = 4
#: points of the tensile-pressure check, uniform in θ
CHECK_POINTS = 801
#: a pressure below minus this fraction of its peak is tensile (the C1 slope's truncation)
TENSILE_FLOOR = 1e-6
#: Chebyshev terms of the punch's part of a gap (sie.fretting.GAP_TERMS is 16384: a kink truncated
#: at N terms leaves ~1/(N^2 φ) of the gap at x = m + h cosh φ, 1e-6/φ at 1024, below a worn
#: profile's own truncation; 0 for Hertz, whose slope has two terms)
GAP_TERMS = 1024


@dataclass(frozen=True)
class WornProfile:
    """The punch of eq. (2) less a worn depth ``w(x)`` (the gap grows by ``w``).

    Attributes
    ----------
    punch
        The three-part punch.
    x, depth
        Knots (strictly increasing) and the worn depth there; outside the knots
        the depth stays at its end value (its slope 0).
    kind
        ``"linear"`` or ``"pchip"`` (:data:`KINDS`).
    """

    punch: Punch
    x: np.ndarray = field(repr=False)
    depth_values: np.ndarray = field(repr=False)
    kind: str = "pchip"

    def __post_init__(self) -> None:
        check_punch(self.punch)
        x = np.array(self.x, dtype=float)
        w = np.array(self.depth_values, dtype=float)
        if x.ndim != 1 or w.shape != x.shape or x.size < 2:
            raise InputError(f"`x` and `depth` must be 1-D of one length >= 2, not {x.shape} and {w.shape}")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(w))):
            raise InputError("`x` and `depth` must be finite")
        if np.any(np.diff(x) <= 0):
            raise InputError("`x` must increase strictly")
        if self.kind not in KINDS:
            raise InputError(f"`kind` = {self.kind!r} must be one of {', '.join(KINDS)}")
        x.setflags(write=False)
        w.setflags(write=False)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "depth_values", w)
        if self.kind == "pchip":
            spline = PchipInterpolator(x, w, extrapolate=False)
            object.__setattr__(self, "_d", (spline, spline.derivative(1), spline.derivative(2)))

    @classmethod
    def from_csv(cls, path: str | os.PathLike[str], punch: Punch, kind: str = "pchip") -> "WornProfile":
        """A measured profile ``(x, h)`` from a two-column text file (``#`` comments, a header allowed).

        The worn depth is ``h - v(x)`` of the punch (eq. 2, no tilt): the
        measured height over the nominal one. Read through :mod:`threepart.textfile`.
        """
        if not isinstance(punch, Punch):
            raise InputTypeError(f"`punch` must be a threepart.Punch, not {type(punch).__name__}")
        label = f"`path` = {str(path)!r}"
        rows: list[list[float]] = []
        for k, line in enumerate(read_text(path, label).splitlines(), 1):
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            cells = [c for c in text.replace(",", " ").replace(";", " ").split()]
            if not rows and any(c[0].isalpha() for c in cells):
                continue     # a header
            rows.append(finite_row(cells[:2], f"{label}, line {k}", ("x", "h")))
        if len(rows) < 2:
            raise InputError(f"{label}: a profile needs at least two (x, h) rows")
        x, h = np.array(rows).T
        return cls(punch, x, h - punch.profile(x), kind)

    def depth(self, x: ArrayLike) -> np.ndarray:
        """Worn depth ``w(x)``."""
        return self._eval(x, 0)

    def _eval(self, x: ArrayLike, order: int) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        if self.kind == "linear":
            if order == 0:
                return np.interp(x, self.x, self.depth_values)
            if order == 2:
                return np.zeros(x.shape)
            k = np.clip(np.searchsorted(self.x, x, side="right") - 1, 0, self.x.size - 2)
            slope = np.diff(self.depth_values)[k] / np.diff(self.x)[k]
            return np.where((x > self.x[0]) & (x < self.x[-1]), slope, 0.0)
        inside = (x >= self.x[0]) & (x <= self.x[-1])
        xc = np.clip(x, self.x[0], self.x[-1])
        value = self._d[order](xc)     # type: ignore[attr-defined]
        if order == 0:
            return np.asarray(value, dtype=float)
        return np.where(inside, value, 0.0)

    def slope(self, x: ArrayLike, alpha: float = 0.0) -> np.ndarray:
        """``v'(x) + w'(x)``, the tilt ``alpha`` added (eq. 2 less the wear)."""
        return self.punch.slope(x, alpha) + self._eval(x, 1)

    def profile(self, x: ArrayLike, alpha: float = 0.0, Delta: float = 0.0) -> np.ndarray:
        """``v(x) + w(x)``: the punch's profile of eq. (2) with the worn depth removed from it."""
        return self.punch.profile(x, alpha, Delta) + self.depth(x)

    def coefficients(self, m: float, h: float, kmax: int, samples: int | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Chebyshev coefficients ``G_0..G_kmax`` of ``w'(m + h s)`` and their ``m``, ``h`` gradients.

        ``"pchip"``: by Gauss–Chebyshev quadrature at ``samples`` first-kind points
        (default :data:`SAMPLES_PER_TERM` ``kmax``); a scheme passes its own, so
        that its moments and its sine terms are one projection.
        """
        k = np.arange(kmax + 1, dtype=float)
        if self.kind == "linear":
            return self._step_coefficients(m, h, k)
        N = samples if samples is not None else SAMPLES_PER_TERM * max(kmax, 16)
        theta = (np.arange(N) + 0.5) * np.pi / N
        s = np.cos(theta)
        x = m + h * s
        d1, d2 = self._eval(x, 1), self._eval(x, 2)
        if kmax <= 8:      # a few moments: the sums themselves
            C = np.cos(np.outer(k, theta)) * (2.0 / N)
            C[0] *= 0.5
            return C @ d1, C @ d2, C @ (s * d2)
        out = [scipy.fft.dct(v, type=2)[:kmax + 1] / N for v in (d1, d2, s * d2)]
        for v in out:
            v[0] *= 0.5
        return out[0], out[1], out[2]

    def _step_coefficients(self, m: float, h: float, k: np.ndarray
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Exact coefficients of a piecewise-constant ``w'``: steps ``Δ_j H(s - β_j)`` at the knots."""
        slopes = np.concatenate([[0.0], np.diff(self.depth_values) / np.diff(self.x), [0.0]])
        jumps = np.diff(slopes)
        beta = (self.x - m) / h
        G, dm, dh = np.zeros(k.size), np.zeros(k.size), np.zeros(k.size)
        G[0] += float(np.sum(jumps[beta <= -1.0]))        # steps left of the interval: constants
        sel = (beta > -1.0) & (beta < 1.0) & (jumps != 0)
        if np.any(sel):
            b, J = beta[sel], jumps[sel]
            tb = np.arccos(b)
            kk = k[:, None]
            with np.errstate(divide="ignore", invalid="ignore"):
                coef = np.where(kk == 0, tb / np.pi, 2.0 / np.pi * np.sin(kk * tb) / np.where(kk == 0, 1, kk))
            G += coef @ J
            # d coef/dβ = -(c_k/π) T_k(β)/sqrt(1 - β^2); dβ/dm = -1/h, dβ/dh = -β/h
            dcoef = -np.where(kk == 0, 1.0, 2.0) / np.pi * np.cos(kk * tb) / np.sin(tb)
            dm += dcoef @ (J * (-1.0 / h))
            dh += dcoef @ (J * (-b / h))
        return G, dm, dh


@dataclass(frozen=True)
class ProfileScheme(Projected):
    """The projected scheme of a worn profile: the punch's exact coefficients plus the worn slope's.

    ``moments`` and ``pressure`` take the punch as :class:`sie.schemes.Projected`
    does, so every SIE routine that takes a scheme solves the worn profile.
    Build it as ``ProfileScheme(n=..., profile=...)``.
    """

    name: str = "profile"
    profile: WornProfile | None = None

    def moments(self, punch: Punch, m: float, h: float) -> tuple[np.ndarray, np.ndarray]:
        """``(G_0, G_1, G_2)`` of the worn profile's slope and their ``(m, h)`` Jacobian."""
        assert self.profile is not None
        G, J = Projected(self.n).moments(self.profile.punch, m, h)
        Gw, dm, dh = self.profile.coefficients(m, h, 2, SAMPLES_PER_TERM * self.n)
        return G + Gw, J + np.column_stack([dm, dh])

    def worn_terms(self, m: float, h: float) -> np.ndarray:
        """``G_0..G_n`` of the worn slope on ``[m - h, m + h]``."""
        assert self.profile is not None
        return self.profile.coefficients(m, h, self.n, SAMPLES_PER_TERM * self.n)[0]

    def pressure(self, punch: Punch, A: float, m: float, h: float) -> tuple[ChebyshevPressure, dict]:
        """The bounded pressure on ``[m - h, m + h]``: the punch's (kinks in closed form) plus the worn sine terms."""
        assert self.profile is not None
        base, extra = Projected(self.n).pressure(self.profile.punch, A, m, h)
        Gw = self.worn_terms(m, h)
        g = np.asarray(base.g) + Gw[1:] / A
        return dataclasses.replace(base, g=g), {**extra, "worn_tail": float(abs(Gw[-1]) * self.n / A)}


@dataclass(frozen=True)
class SingularPressure(ChebyshevPressure):
    """A bounded pressure plus ``(C0 + C1 cos θ)/sin θ`` on ``[m - h, m + h]`` (eq. W3), ``inf`` at the ends.

    ``C0``, ``C1`` in pressure units; with ``w = sqrt((x - x1)(x2 - x)) = h sin θ``,
    ``lim p w = (C0 ∓ C1) h`` at the left and right end (eq. W10's ``K``).
    """

    bounded: ChebyshevPressure | None = None
    C0: float = 0.0
    C1: float = 0.0

    def __call__(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        assert self.bounded is not None
        s = (x - self.m) / self.h
        inside = (np.abs(s) < 1.0)
        sc = np.where(inside, s, 0.0)
        extra = (self.C0 + self.C1 * sc) / np.sqrt(1.0 - sc * sc)
        return np.where(inside, self.bounded(x) + extra, np.where(np.abs(s) == 1.0, np.inf, 0.0))

    @property
    def K(self) -> tuple[float, float]:
        """``lim p w`` at the left and right end (eq. W10), ``w = sqrt((x - x1)(x2 - x))``."""
        return (self.C0 - self.C1) * self.h, (self.C0 + self.C1) * self.h


@dataclass(frozen=True)
class ProfileNormalResult(SieNormalResult):
    """Normal solution on a worn profile (:func:`solve_profile`); ``punch`` is the profile's punch.

    Attributes
    ----------
    profile
        The worn profile solved.
    ends
        ``"bounded"`` or ``"unbounded"`` (:data:`ENDS`).
    """

    profile: WornProfile | None = field(default=None, repr=False, compare=False)
    ends: str = "bounded"
    tensile_floor: float = 0.0

    def check(self) -> None:
        """The answer check (:func:`threepart.results.answer.check_pressure`); a wear march's state takes its own floor.

        With ``tensile_floor > 0`` (a marched state, :mod:`sie.wear`) the pressure may
        dip below 0 by that fraction of its peak where the knots do not resolve a
        steep scar (next to the stick zone's ends as the limit's singular pressure
        forms); the least is ``info["least"]``.
        """
        if self.tensile_floor == 0.0:
            super().check()
        else:
            _check_tensile(self, f"`P` = {self.P:g} at `s` = {self.s:g}", self.tensile_floor)

    def edges(self) -> Any:
        """Edge multipliers (:meth:`threepart.results.edges.Edged.edges`) of bounded ends only.

        Square-root singular ends have no ``K_N``; their strengths are ``info["K"]`` (eq. W10).
        """
        if self.ends == "unbounded":
            raise InputError("a contact with square-root singular (unbounded) ends has no edge "
                             "multiplier K_N; its ends' strengths lim p w are info['K'] (eq. W10)")
        return super().edges()

    @property
    def scheme(self) -> ProfileScheme:
        """The scheme it was solved with (for the corrective problems of partial slip)."""
        assert self.profile is not None
        return ProfileScheme(n=self.diagnostics.n or DEFAULT_TERMS, profile=self.profile)


def _check_tensile(res: ProfileNormalResult, what: str, floor: float = TENSILE_FLOOR) -> float:
    """Refuse a pressure tensile below ``-floor`` of its peak on the contact (SeparationError); its least / peak."""
    m, h = 0.5 * (res.c - res.a), 0.5 * (res.a + res.c)
    theta = np.linspace(0.0, np.pi, CHECK_POINTS)[1:-1]
    x = m + h * np.cos(theta)
    p = res.pressure(x)
    i = int(np.argmin(p))
    if p[i] < -floor * float(np.max(p)):
        raise SeparationError(f"{what}: the pressure on [{-res.a:.6g}, {res.c:.6g}] is tensile "
                              f"({p[i]:.4g} at x = {x[i]:.6g}, peak {np.max(p):.4g}); the worn profile "
                              "does not touch over one interval")
    return float(p[i] / np.max(p))


def solve_profile(profile: WornProfile, P: float, s: float = 0.0, *, A: float, tilt: str = "free",
                  n: int = DEFAULT_TERMS, ends: str = "bounded",
                  contact: tuple[float, float] | None = None,
                  start: tuple[float, float] | None = None,
                  tensile_floor: float = TENSILE_FLOOR) -> ProfileNormalResult:
    """Normal contact of a worn profile under ``P`` at the lever arm ``s`` (paper eq. integral_equation).

    Parameters
    ----------
    profile
        The punch less its worn depth.
    P, s, A, tilt
        As :func:`sie.solve_normal`.
    n
        Sine terms of the pressure (the punch's kinks are summed in closed form).
    ends
        ``"bounded"`` (default): the contact ends follow from consistency.
        ``"unbounded"``: the contact ``contact = (x1, x2)`` is given and the
        pressure is square-root singular at both ends (eqs. W3-W6).
    contact
        The contact of ``ends="unbounded"``; not taken otherwise.
    start
        ``(m, h)`` to start the bounded ends' Newton iteration from (a previous state).
    tensile_floor
        The least pressure accepted, of the peak (default :data:`TENSILE_FLOOR`); the
        least found is ``info["least"]``.

    Returns
    -------
    ProfileNormalResult
        ``method="sie"``, ``diagnostics.scheme = "profile"``; ``info`` holds
        ``worn_tail`` (the last worn term's size, times ``n``), and for unbounded ends ``K``.

    Raises
    ------
    SeparationError
        The pressure is tensile somewhere (the worn profile touches in more than one interval),
        or an unbounded end's ``K < 0``.
    """
    if not isinstance(profile, WornProfile):
        raise InputTypeError(f"`profile` must be a WornProfile, not {type(profile).__name__}")
    if ends not in ENDS:
        raise InputError(f"`ends` = {ends!r} must be one of {', '.join(ENDS)}")
    if (ends == "unbounded") != (contact is not None):
        raise InputError("`contact` is given exactly when `ends` = 'unbounded'")
    punch = profile.punch
    P, s, A, _ = check_normal(punch, P, s, A, tilt, n, "projected")
    sch = ProfileScheme(n=n, profile=profile)
    t0 = time.perf_counter()
    if ends == "unbounded":
        assert contact is not None
        return _unbounded(profile, sch, P, s, A, tilt, contact, t0)
    target: dict[str, float] = {"s": s} if tilt == "free" else {"alpha": 0.0}
    m0, h0 = start if start is not None else (s, None)
    m, h, G, its, res = solve_ends(punch, A, P, sch, m0=m0, h0=h0, **target)
    alpha = -float(G[0]) if tilt == "free" else 0.0
    s_out = float(s) if tilt == "free" else m + math.pi * h * h * float(G[2]) / (4 * A * P)
    check_contact(punch, h - m, h + m, alpha)
    density, extra = sch.pressure(punch, A, m, h)
    out = ProfileNormalResult(
        punch=punch, A=float(A), a=h - m, c=h + m, alpha=alpha, P=float(P), s=s_out, tilt=tilt,
        method="sie", info=dict(extra), density=density, profile=profile, ends="bounded",
        tensile_floor=0.0 if tensile_floor == TENSILE_FLOOR else tensile_floor, diagnostics=Diagnostics(n=n, scheme=sch.name, iterations=its, residual=res,
                                timings={"total": time.perf_counter() - t0}))
    out.info["least"] = _check_tensile(out, f"`P` = {P:g} at `s` = {s_out:g}", tensile_floor)
    return out


def _unbounded(profile: WornProfile, sch: ProfileScheme, P: float, s: float, A: float, tilt: str,
               contact: tuple[float, float], t0: float) -> ProfileNormalResult:
    """The contact ``[x1, x2]`` given, square-root singular at both ends (eqs. W3-W6)."""
    x1, x2 = (float(v) for v in contact)
    if not (np.isfinite(x1) and np.isfinite(x2) and x1 < x2):
        raise InputError(f"`contact` = {contact!r} must be two finite ends x1 < x2")
    punch = profile.punch
    m, h = 0.5 * (x1 + x2), 0.5 * (x2 - x1)
    bounded, extra = sch.pressure(punch, A, m, h)
    G = sch.moments(punch, m, h)[0]
    C0 = P / (math.pi * h) - G[1] / (2 * A)
    if tilt == "free":
        C1 = 2.0 / math.pi * (P * (s - m) / (h * h) - math.pi * G[2] / (4 * A))
        alpha = -float(G[0]) - A * C1
        s_out = s
    else:
        C1 = -float(G[0]) / A
        alpha = 0.0
        s_out = m + h * h * (math.pi * G[2] / (4 * A) + 0.5 * math.pi * C1) / P
    K = ((C0 - C1) * h, (C0 + C1) * h)
    if min(K) < 0:
        raise SeparationError(f"`contact` = [{x1:.6g}, {x2:.6g}]: the unbounded pressure of `P` = {P:g} "
                              f"at `s` = {s_out:g} would be tensile at the {'left' if K[0] < 0 else 'right'} "
                              f"end (K = {min(K):.4g})")
    density = SingularPressure(m=m, h=h, g=np.zeros(1), bounded=bounded, C0=float(C0), C1=float(C1))
    out = ProfileNormalResult(
        punch=punch, A=float(A), a=-x1, c=x2, alpha=float(alpha), P=float(P), s=float(s_out), tilt=tilt,
        method="sie", info={**extra, "K": K}, density=density, profile=profile, ends="unbounded",
        diagnostics=Diagnostics(n=sch.n, scheme=sch.name, timings={"total": time.perf_counter() - t0}))
    _check_tensile(out, f"`contact` = [{x1:.6g}, {x2:.6g}]")
    return out


def _I(k: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """``I_k(φ) = ∫_0^φ e^{-kt} sinh t dt`` for ``k >= 1`` (rows: points, columns: k)."""
    ph = phi[:, None]
    kk = k[None, :]
    one = 0.5 * ph + 0.25 * np.expm1(-2.0 * ph)
    with np.errstate(divide="ignore", invalid="ignore"):
        high = 0.5 * (-np.expm1(-(kk - 1) * ph) / np.where(kk == 1, 1, kk - 1)
                      + np.expm1(-(kk + 1) * ph) / (kk + 1))
    return np.where(kk == 1, one, high)


def profile_gap(profile: WornProfile, alpha: float, m: float, h: float, x: ArrayLike,
                terms: int = GAP_TERMS // 2, samples: int = SAMPLES_PER_TERM * DEFAULT_TERMS) -> np.ndarray:
    """Gap outside the bounded contact ``[m - h, m + h]`` of the worn profile at tilt ``alpha``; 0 inside.

    The punch's part is :func:`sie.fretting.stick_gap`; the worn part's gap slope
    ``w'(x) - Σ_{k>=1} G^w_k ρ^k`` integrates from the end ``e`` in closed form,
    ``w(x) - w(e) - side h Σ G^w_k side^k I_k(φ)``, ``|x - m| = h cosh φ``; ``terms`` of it
    (``I_k ~ 1/k`` outside, ``G^w_k ~ k^-2``: the tail left is ~ terms^-2 of the worn part).
    """
    x = np.asarray(x, dtype=float)
    flat = np.ravel(x)
    out = np.ravel(stick_gap(profile.punch, alpha, m, h, flat, terms=GAP_TERMS)).copy()
    Gw = profile.coefficients(m, h, terms, samples)[0]
    k = np.arange(1, terms + 1, dtype=float)
    for side in (1.0, -1.0):
        end = m + side * h
        sel = side * (flat - end) > 0
        if not np.any(sel):
            continue
        u = side * (flat[sel] - end) / h
        phi = np.log1p(u + np.sqrt(u * (u + 2.0)))
        series = _I(k, phi) @ (Gw[1:] * side ** k)
        out[sel] += profile.depth(flat[sel]) - float(profile.depth(np.array([end]))[0]) - side * h * series
    return out.reshape(x.shape)


def profile_approach(profile: WornProfile, A: float, alpha: float, P: float, m: float, h: float,
                     samples: int = 4 * DEFAULT_TERMS) -> float:
    """Rigid approach of a bounded pressure of load ``P`` on ``[m - h, m + h]`` (:func:`sie.fretting.approach`).

    The worn depth's mean under the Chebyshev weight (Gauss–Chebyshev, first kind) is added to the punch's.
    """
    theta = (np.arange(samples) + 0.5) * np.pi / samples
    worn = float(np.mean(profile.depth(m + h * np.cos(theta))))
    return punch_approach(profile.punch, A, alpha, P, m, h) + worn


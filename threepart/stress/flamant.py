"""The stress field in the elastic half-plane under the contact, from any method's tractions.

Conventions
-----------
- ``x`` runs along the surface, ``z >= 0`` is the depth into the substrate (the
  half-plane the punch presses on). Tension is positive.
- ``p(x) >= 0`` is the compressive pressure the punch exerts on the substrate.
- ``q(x)`` is the shear traction that the punch exerts on the substrate, along
  ``+x``, so ``∫q dx = Q`` is the force the punch exerts on the substrate along
  ``+x``. This is what every threepart result means by ``shear(x)`` and ``Q``
  (:mod:`threepart.results`, :mod:`closedform.slip`, and the FE model of
  :mod:`fem.friction`, whose nodal forces ``t_i`` "drag the substrate" and sum to
  ``Q``): ``result.pressure`` and ``result.shear`` are passed as they are, no
  conversion is needed.
- ``sigma_bulk > 0`` is a uniform tension ``σxx`` in the substrate (it adds to
  ``σxx`` everywhere, and to nothing else).
- Plane strain, bodies elastically similar: ``σyy = ν (σxx + σzz)`` enters the
  principal stresses and the von Mises stress.

At the surface these give ``σzz = -p(x)``, ``σxz = -q(x)`` (the traction on the
surface, whose outward normal is ``-z``, is ``(q, p)``) and
``σxx = -p(x) + (2/π) PV∫ q(t)/(t - x) dt + sigma_bulk``.

Method
------
Below the surface the stresses are Flamant's line-load kernels (Johnson,
*Contact Mechanics*, 1985, eqs. 2.15 and 2.19; the distributed forms 2.23–2.25)
integrated over the tractions on ``[-a, c]``. For each point ``(x, z)`` the
tractions' value at ``x`` is subtracted and integrated against the kernels
analytically (:func:`kernel_primitives`), so the remaining integrand is bounded
at every depth; the remainder is integrated by a composite Gauss–Legendre rule
whose panels end at the contact ends, the ``kinks`` and ``x`` itself, and are
graded geometrically toward each of them after the change of variable
``t = E ± h u²`` (which removes the square-root behaviour at the ends and the
stick-zone ends). The same formula holds at ``z = 0``: the analytic part then
carries the surface values and the remainder is the principal-value integral.
Derivation and signs: ``docs/STRESS.md``.

Public names
------------
Stress              -- σxx, σzz, σxz on a grid, with principal, von Mises and Tresca stresses
stress              -- the stress at points (x, z >= 0) from p(x), q(x) and a bulk stress
hilbert             -- (1/π) PV∫ f(t)/(t - x) dt over the contact, the surface's Hilbert transform
flamant_normal      -- Flamant's kernels of a normal line load (Johnson eq. 2.15)
flamant_tangential  -- Flamant's kernels of a tangential line load (Johnson eq. 2.19)
kernel_primitives   -- the kernels' antiderivatives in s = x - t, for the singular subtraction
"""
from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Callable, Iterator

import numpy as np
from numpy.typing import ArrayLike

from ..halfplane.legendre import graded01
from ..progress import heartbeat
from .grid import GRID_DEPTH, grid_integrals, is_grid
from ..problem.checks import finite, show
from threepart.errors import InputError, InputTypeError

__all__ = ["Stress", "stress", "hilbert", "flamant_normal", "flamant_tangential",
           "kernel_primitives", "RULE", "POINTS_PER_CHUNK", "PROGRESS_S"]

Traction = Callable[[np.ndarray], Any]

#: the composite rule, per half of each interval between break points: ``L + 1`` panels
#: in ``u`` (``t = E + h u²``) with ends ``0, ratio**L, ..., ratio, 1``, each with ``n``
#: Gauss–Legendre nodes. ``L`` is chosen per point between ``min_levels`` and ``levels``
#: (:func:`_depth`): deep for shallow points and points near a contact end or kink.
#: Measured: see docs/STRESS.md; tests/test_stress.py asserts 1e-8 of p0.
RULE = {"n": 12, "ratio": 0.35, "levels": 11, "min_levels": 2}
#: points per block of the vectorised quadrature (memory: blocks of about 2e6 nodes)
_NODES_PER_BLOCK = 2_000_000
#: points per chunk of :func:`stress` and :func:`hilbert`: each chunk's grading depths, break-point
#: distances and integrals are made and dropped in turn, so that the working memory stays about
#: 100 MB beside the points and the result (5 arrays of them), whatever their number (1e7 points
#: took 1.9 GB in one piece); each point's integrals do not depend on the chunk it falls in
POINTS_PER_CHUNK = 100_000
#: seconds between two progress lines of :func:`stress` (when it is given ``progress``)
PROGRESS_S = 1.0


def _kernels(s: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The four Flamant kernels ``z s²/r⁴, z³/r⁴, z² s/r⁴, s³/r⁴`` without their ``-2/π``.

    ``r = 0`` (only at the nodes of an empty interval, weight 0) gives 0. ``s³`` is ``s·s·s``:
    numpy's ``s ** 3`` calls ``pow`` at every node, 30 times the cost, for the same value to rounding.
    """
    s2 = s * s
    r2 = s2 + z * z
    inv = 1.0 / np.where(r2 > 0, r2 * r2, np.inf)
    return z * s * s * inv, z ** 3 * inv, z * z * s * inv, s2 * s * inv


def flamant_normal(s: ArrayLike, z: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stresses ``(σxx, σzz, σxz)`` at ``(s, z)`` of a unit compressive line load at ``s = 0``.

    Johnson, *Contact Mechanics*, eq. (2.15): ``σxx = -(2/π) s² z / r⁴``,
    ``σzz = -(2/π) z³ / r⁴``, ``σxz = -(2/π) s z² / r⁴`` with ``r² = s² + z²``; in
    polar form the purely radial ``σr = -(2/π) cos θ / r``. ``s`` is the horizontal
    distance of the point from the load, ``z > 0`` its depth.
    """
    k = _kernels(np.asarray(s, float), np.asarray(z, float))
    return -2 / math.pi * k[0], -2 / math.pi * k[1], -2 / math.pi * k[2]


def flamant_tangential(s: ArrayLike, z: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stresses ``(σxx, σzz, σxz)`` at ``(s, z)`` of a unit line load along ``+x`` at ``s = 0``.

    Johnson, *Contact Mechanics*, eq. (2.19): ``σxx = -(2/π) s³ / r⁴``,
    ``σzz = -(2/π) s z² / r⁴``, ``σxz = -(2/π) s² z / r⁴``; in polar form
    ``σr = -(2/π) sin θ / r`` (compressive ahead of the load, ``s > 0``).
    """
    k = _kernels(np.asarray(s, float), np.asarray(z, float))
    return -2 / math.pi * k[3], -2 / math.pi * k[2], -2 / math.pi * k[0]


def kernel_primitives(s: ArrayLike, z: ArrayLike) -> tuple[np.ndarray, ...]:
    """Antiderivatives in ``s`` of ``z s²/r⁴, z³/r⁴, z² s/r⁴, s³/r⁴`` (``r² = s² + z²``).

    They are, in that order, ``(atan(s/z) - z s/r²)/2``, ``(atan(s/z) + z s/r²)/2``,
    ``-z²/(2 r²)`` and ``ln(r²)/2 + z²/(2 r²)``: the Flamant kernels of
    :func:`flamant_normal` and :func:`flamant_tangential` without their factor
    ``-2/π`` (``z² s/r⁴`` and ``z s²/r⁴`` serve both loads). ``atan(s/z)`` is
    ``atan2(s, z)``, so that ``z = 0`` gives the surface's ``±π/2`` jump: the
    kernel ``z s²/r⁴`` tends to ``(π/2) δ(s)``. At ``s = z = 0`` the bounded terms
    are taken as 0 and the logarithm is ``-inf``.
    """
    s, z = np.asarray(s, float), np.asarray(z, float)
    r2 = s * s + z * z
    safe = np.where(r2 > 0, r2, 1.0)
    zs = np.where(r2 > 0, z * s / safe, 0.0)
    zz = np.where(r2 > 0, z * z / safe, 0.0)
    th = np.arctan2(s, z)
    with np.errstate(divide="ignore"):
        log = 0.5 * np.log(r2)
    return 0.5 * (th - zs), 0.5 * (th + zs), -0.5 * zz, log + 0.5 * zz


@dataclass(frozen=True)
class Stress:
    """Stresses in the half-plane at points ``(x, z)``; tension positive, ``z`` the depth.

    Attributes
    ----------
    x, z
        The points, broadcast against each other.
    sxx, szz, sxz
        ``σxx``, ``σzz``, ``σxz`` at the points, of the shape of ``x`` and ``z`` broadcast.
    nu
        Poisson's ratio of the plane-strain substrate: ``σyy = ν (σxx + σzz)``.
    rule
        The quadrature rule used (:data:`RULE`).
    """

    x: np.ndarray
    z: np.ndarray
    sxx: np.ndarray
    szz: np.ndarray
    sxz: np.ndarray
    nu: float
    rule: tuple[tuple[str, float], ...] = ()

    @property
    def syy(self) -> np.ndarray:
        """Out-of-plane ``σyy = ν (σxx + σzz)`` (plane strain)."""
        return self.nu * (self.sxx + self.szz)

    @cached_property
    def _in_plane(self) -> tuple[np.ndarray, np.ndarray]:
        centre = 0.5 * (self.sxx + self.szz)
        radius = np.hypot(0.5 * (self.sxx - self.szz), self.sxz)
        return centre + radius, centre - radius

    @cached_property
    def principal(self) -> np.ndarray:
        """Principal stresses ``(s1, s2, s3)``, ``s1 >= s2 >= s3``, stacked on a first axis of 3."""
        major, minor = self._in_plane
        return np.sort(np.stack([major, minor, self.syy]), axis=0)[::-1]

    @property
    def s1(self) -> np.ndarray:
        """Largest principal stress (including ``σyy``)."""
        return self.principal[0]

    @property
    def s2(self) -> np.ndarray:
        """Intermediate principal stress."""
        return self.principal[1]

    @property
    def s3(self) -> np.ndarray:
        """Smallest principal stress."""
        return self.principal[2]

    @property
    def von_mises(self) -> np.ndarray:
        """Von Mises equivalent stress ``sqrt(((s1-s2)² + (s2-s3)² + (s3-s1)²)/2)``."""
        s1, s2, s3 = self.principal
        return np.sqrt(0.5 * ((s1 - s2) ** 2 + (s2 - s3) ** 2 + (s3 - s1) ** 2))

    @property
    def max_shear(self) -> np.ndarray:
        """Tresca's maximum shear stress ``(s1 - s3)/2``."""
        return 0.5 * (self.s1 - self.s3)

    @property
    def angle(self) -> np.ndarray:
        """Angle (rad, from ``+x`` toward ``+z``) of the larger in-plane principal stress."""
        return 0.5 * np.arctan2(2.0 * self.sxz, self.sxx - self.szz)


def _array(name: str, value: Any) -> np.ndarray:
    """``value`` as a finite float array, else ``TypeError``/``ValueError`` naming ``name``."""
    if isinstance(value, (str, bytes)) or value is None:
        raise InputTypeError(f"`{name}` = {show(value)} must be a real number or array, "
                        f"not {type(value).__name__}")
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        raise InputTypeError(f"`{name}` must be a real number or array, not {type(value).__name__}") from None
    if arr.dtype == bool or not (np.issubdtype(arr.dtype, np.floating) or np.issubdtype(arr.dtype, np.integer)):
        raise InputTypeError(f"`{name}` must be a real number or array, not an array of {arr.dtype}")
    arr = arr.astype(float)
    if not np.all(np.isfinite(arr)):
        bad = float(arr[~np.isfinite(arr)].flat[0])
        raise InputError(f"`{name}` holds {bad!r}: every value must be a finite number")
    return arr


def _traction(name: str, func: Any) -> Traction:
    if not callable(func):
        raise InputTypeError(f"`{name}` must be a callable of x (e.g. result.pressure), "
                        f"not {type(func).__name__}")
    return func


def _evaluate(name: str, func: Traction, t: np.ndarray) -> np.ndarray:
    """``func(t)`` as a finite float array of ``t``'s shape, else ``ValueError`` naming ``name``."""
    v = np.asarray(func(t), dtype=float)
    if v.shape != t.shape:
        raise InputError(f"`{name}` returned shape {v.shape} for x of shape {t.shape}: it must be "
                         "a vectorised callable of x")
    if not np.all(np.isfinite(v)):
        where = t[~np.isfinite(v)].flat[0]
        raise InputError(f"`{name}` is not finite at x = {where:.6g} inside `ends`")
    return v


def _ends_kinks(ends: Any, kinks: Any) -> tuple[float, float, np.ndarray]:
    if not isinstance(ends, (tuple, list, np.ndarray)) or len(ends) != 2:
        raise InputTypeError(f"`ends` = {show(ends)} must be the pair (-a, c)")
    lo, hi = finite("ends[0]", ends[0]), finite("ends[1]", ends[1])
    if not lo < hi:
        raise InputError(f"`ends` = ({lo:g}, {hi:g}) must satisfy ends[0] < ends[1]")
    k = _array("kinks", kinks if np.size(kinks) else np.zeros(0)).ravel()
    if k.size and (k.min() < lo or k.max() > hi):
        bad = k[(k < lo) | (k > hi)][0]
        raise InputError(f"`kinks` holds x = {bad:g}, outside `ends` [{lo:g}, {hi:g}]")
    k = np.unique(k[(k > lo) & (k < hi)])
    return lo, hi, k


def _depth(x: np.ndarray, z: np.ndarray, lo: float, hi: float, kinks: np.ndarray,
           rule: dict[str, Any]) -> np.ndarray:
    """Grading levels each point needs: ``ratio**levels <= sqrt(ζ/W)/2``, within the rule's bounds.

    ``ζ`` is the distance from the point ``x + i z`` to the nearest pole of its kernels
    seen from a break point: ``z`` itself (the point's own break point ``x``) and
    ``|x - B + i z|`` for the contact ends and kinks ``B``, and the tractions' own
    square-root or kink singularities at the distance ``|x_c - B| > 0`` of ``B`` from the
    break point ``x_c`` (``x`` clipped into the contact). After ``t = B + h u²`` the
    pole lies at ``|u| = sqrt(ζ/|h|) >= sqrt(ζ/W)``; the innermost panel must be
    shorter than half that. A surface point on a kink (``ζ = 0``) gets the deepest
    grading: there the remainder ``(w(t) - w(x))/(x - t)`` is log-singular.
    """
    W = hi - lo
    B = np.concatenate([[lo, hi], kinks])[None, :]
    dist = np.abs((x[:, None] - B) + 1j * z[:, None])
    # the tractions' own singularities at the other break points, seen from the clipped x
    apart = np.abs(np.clip(x, lo, hi)[:, None] - B)
    apart = np.where(apart > 0, apart, np.inf).min(axis=1)
    zeta = np.minimum(np.minimum(np.where(z > 0, z, np.inf), dist.min(axis=1)), apart)
    with np.errstate(divide="ignore"):
        need = np.ceil(np.log(0.5 * np.sqrt(zeta / W)) / math.log(rule["ratio"]))
    # zeta = 0: a surface point on an end or a kink, where the remainder has a weak singularity
    return np.clip(np.nan_to_num(need, posinf=rule["levels"]), rule["min_levels"],
                   rule["levels"]).astype(int)


def _integrals(x: np.ndarray, z: np.ndarray, funcs: dict[str, Traction], lo: float, hi: float,
               kinks: np.ndarray, rule: dict[str, Any]) -> dict[str, tuple[np.ndarray, ...]]:
    """For each traction ``w``: ``∫ w(t) K(x - t, z) dt`` over ``[lo, hi]`` for the four kernels.

    The kernels are ``z s²/r⁴, z³/r⁴, z² s/r⁴, s³/r⁴`` (:func:`_kernels`, whose
    primitives are :func:`kernel_primitives`). ``x`` and ``z`` are 1-d of one length. The points
    are grouped by the grading depth they need (:func:`_depth`).
    """
    levels = _depth(x, z, lo, hi, kinks, rule)
    out = {name: tuple(np.empty(x.size) for _ in range(4)) for name in funcs}
    for L in np.unique(levels):
        sel = np.flatnonzero(levels == L)
        part = _integrals_at_depth(x[sel], z[sel], funcs, lo, hi, kinks, {**rule, "levels": int(L)})
        for name in funcs:
            for k in range(4):
                out[name][k][sel] = part[name][k]
    return out


def _chunks(n: int) -> Iterator[slice]:
    """The points ``0..n-1`` in slices of :data:`POINTS_PER_CHUNK` (read when called)."""
    size = POINTS_PER_CHUNK
    for start in range(0, n, size):
        yield slice(start, min(start + size, n))


def _halves(left: np.ndarray, right: np.ndarray, U: np.ndarray,
            Wu: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each interval ``[left, right]`` halved, each half mapped by ``t = E + h u²`` from its end ``E``.

    Returns ``E`` and ``h u²`` at the nodes (so that ``x - t`` can be formed as
    ``(x - E) - h u²``, exact near ``x``) and the weights, each of shape
    ``left.shape[:-1] + (2 * intervals * U.size,)``.
    """
    mid = 0.5 * (left + right)
    E = np.concatenate([left, right], axis=-1)               # the end each half is graded toward
    h = np.concatenate([mid - left, mid - right], axis=-1)   # signed: t = E + h u^2
    shape = E.shape[:-1] + (-1,)
    En = np.broadcast_to(E[..., None], E.shape + U.shape).reshape(shape)
    hu2 = (h[..., None] * (U * U)).reshape(shape)
    wt = (2.0 * np.abs(h)[..., None] * U * Wu).reshape(shape)
    return En, hu2, wt


def _integrals_at_depth(x: np.ndarray, z: np.ndarray, funcs: dict[str, Traction], lo: float,
                        hi: float, kinks: np.ndarray,
                        rule: dict[str, Any]) -> dict[str, tuple[np.ndarray, ...]]:
    """:func:`_integrals` with one grading depth ``rule["levels"]`` for all the points.

    The intervals between the fixed break points (ends and kinks) carry one shared rule,
    whose tractions are evaluated once; the interval holding ``x`` is replaced, for each
    point, by its two parts on either side of ``x`` (clipped into the contact).
    """
    U, Wu = graded01(rule["n"], rule["ratio"], rule["levels"])
    F = np.concatenate([[lo], kinks, [hi]])
    nint = F.size - 1
    sE, s_hu2, s_wt = _halves(F[:-1], F[1:], U, Wu)
    s_t = sE + s_hu2
    s_id = np.tile(np.repeat(np.arange(nint), U.size), 2)   # the interval of each shared node
    shared = {name: _evaluate(name, func, s_t) for name, func in funcs.items()}
    out: dict[str, list[list[np.ndarray]]] = {name: [[], [], [], []] for name in funcs}
    block = max(1, _NODES_PER_BLOCK // (U.size * 4 + s_t.size))
    for start in range(0, x.size, block):
        xb, zb = x[start:start + block], z[start:start + block]
        xc = np.clip(xb, lo, hi)
        j = np.clip(np.searchsorted(F, xc, side="right") - 1, 0, nint - 1)
        own = np.column_stack([F[j], xc]), np.column_stack([xc, F[j + 1]])
        pE, p_hu2, p_wt = _halves(own[0], own[1], U, Wu)
        p_t = pE + p_hu2
        keep = s_id[None, :] != j[:, None]                      # drop the shared interval of x
        cols = keep.any(axis=0)                                 # shared nodes some point uses
        keep = keep[:, cols]
        s_own = (xb[:, None] - pE) - p_hu2
        s_sh = (xb[:, None] - sE[None, cols]) - s_hu2[None, cols]
        prim_hi = kernel_primitives(xb - lo, zb)   # s = x - t at t = lo (upper limit in s)
        prim_lo = kernel_primitives(xb - hi, zb)
        inside = (xb >= lo) & (xb <= hi)
        w0 = {}
        for name, func in funcs.items():
            w0[name] = np.zeros_like(xb)
            if inside.any():
                w0[name][inside] = _evaluate(name, func, xb[inside])
        acc = {name: [np.zeros_like(xb) for _ in range(4)] for name in funcs}
        for s, wt, values in ((s_own, p_wt, {n: _evaluate(n, f, p_t) for n, f in funcs.items()}),
                              (s_sh, s_wt[None, cols] * keep, {n: v[None, cols] for n, v in shared.items()})):
            kernels = _kernels(s, zb[:, None])
            for name in funcs:
                dw = (values[name] - w0[name][:, None]) * wt
                for k in range(4):
                    acc[name][k] += np.einsum("ij,ij->i", dw, kernels[k])
        for name in funcs:
            for k in range(4):
                with np.errstate(invalid="ignore"):
                    analytic = np.where(w0[name] != 0, w0[name] * (prim_hi[k] - prim_lo[k]), 0.0)
                out[name][k].append(acc[name][k] + analytic)
    return {name: tuple(np.concatenate(parts) for parts in lists) for name, lists in out.items()}


def _parts(xb: np.ndarray, zb: np.ndarray, funcs: dict[str, Traction], lo: float, hi: float,
           kinks: np.ndarray) -> Iterator[tuple[Any, dict[str, tuple[np.ndarray, ...]]]]:
    """``(where, integrals)`` over the flattened points, in parts of bounded memory.

    A grid's rows deeper than :data:`threepart.stress.grid.GRID_DEPTH` of the contact's
    width come one row at a time from :func:`threepart.stress.grid.grid_integrals`; every
    other point in chunks of :data:`POINTS_PER_CHUNK` from the pointwise rule.
    """

    xf, zf = xb.ravel(), zb.ravel()
    grid = is_grid(xb, zb)
    if grid is None:
        for part in _chunks(xf.size):
            yield part, _integrals(xf[part], zf[part], funcs, lo, hi, kinks, RULE)
        return
    x_row, z_col, rows = grid
    F = np.concatenate([[lo], kinks, [hi]])
    deep = z_col >= GRID_DEPTH * (hi - lo)
    for j in np.flatnonzero(deep):
        yield rows[j], grid_integrals(x_row, float(z_col[j]), funcs, F, RULE, _evaluate)
    rest = np.sort(np.concatenate([np.arange(*rows[j].indices(xf.size)) for j in np.flatnonzero(~deep)]
                                  or [np.zeros(0, dtype=int)]))
    for part in _chunks(rest.size):
        idx = rest[part]
        yield idx, _integrals(xf[idx], zf[idx], funcs, lo, hi, kinks, RULE)


@contextlib.contextmanager
def _progress(say: Callable[[str], None] | None, done: list[int], n: int) -> Iterator[None]:
    """A line every second (:func:`threepart.progress.heartbeat`) while ``stress`` works, if ``say``."""
    if say is None:
        yield
        return
    with heartbeat(say, lambda: f"stress: {done[0]:,} of {n:,} points", every=PROGRESS_S):
        yield


def _stress_iv(x: ArrayLike, z: ArrayLike, pressure: Any, shear: Any, sigma_bulk: Any, nu: Any
               ) -> tuple[np.ndarray, np.ndarray, Traction | None, Traction | None, float, float]:
    """:func:`stress`'s input checked: the broadcast points, the tractions, ``sigma_bulk`` and ``nu``."""
    xa, za = _array("x", x), _array("z", z)
    if np.any(za < 0):
        raise InputError(f"`z` = {float(za[za < 0].flat[0])!r} must be >= 0: z is the depth into the substrate")
    p_fn = None if pressure is None and shear is not None else _traction("pressure", pressure)
    q_fn = None if shear is None else _traction("shear", shear)
    bulk = finite("sigma_bulk", sigma_bulk)
    poisson = finite("nu", nu)
    if not -1.0 < poisson <= 0.5:
        raise InputError(f"`nu` = {nu!r} must lie in (-1, 0.5]")
    try:
        xb, zb = np.broadcast_arrays(xa, za)
    except ValueError:
        raise InputError(f"`x` of shape {xa.shape} and `z` of shape {za.shape} do not broadcast "
                         "against each other") from None
    return xb, zb, p_fn, q_fn, bulk, poisson


def stress(x: ArrayLike, z: ArrayLike, *, pressure: Traction | None, shear: Traction | None = None,
           ends: tuple[float, float], sigma_bulk: float = 0.0, nu: float = 0.3,
           kinks: ArrayLike = (), progress: Callable[[str], None] | None = None) -> Stress:
    """Stresses at the points ``(x, z)``, ``z >= 0``, of the surface tractions on ``ends``.

    Parameters
    ----------
    x, z
        Points (broadcast against each other): ``x`` along the surface, ``z >= 0``
        the depth. ``z = 0`` gives the surface values.
    pressure
        Vectorised callable ``p(x) >= 0`` (compressive), e.g. ``result.pressure``;
        only its values on ``ends`` are used. ``None``: the stresses of the shear
        alone (a part of a superposition, such as a fretting cycle's history
        built from its loading states, :func:`threepart.fatigue.stress_history`).
    shear
        Vectorised callable ``q(x)``, the shear the punch exerts on the substrate
        along ``+x`` (e.g. ``slip.shear``); ``None`` for a frictionless contact.
    ends
        The contact ``(-a, c)``; the tractions vanish outside it.
    sigma_bulk
        Uniform bulk stress ``σxx`` in the substrate, tension positive.
    nu
        Poisson's ratio, ``-1 < nu <= 0.5``, for ``σyy`` and the derived stresses.
    kinks
        Points inside ``ends`` where ``p`` or ``q`` is not smooth (the joins
        ``x = ±b``, the stick-zone ends); the quadrature puts panel ends there.
    progress
        Called with a line ``"stress: N of M points still running (T s)"``
        every :data:`PROGRESS_S` seconds of work, if given (the command line
        passes its stderr).

    Notes
    -----
    Points that form a grid (``x`` the same on every row, one ``z`` per row, e.g.
    ``x`` of shape ``(1, nx)`` and ``z`` of ``(nz, 1)``) share one rule per depth
    (:mod:`threepart.stress.grid`); the rest, and the grid's rows shallower than
    ``GRID_DEPTH`` of the contact's width, take each point's own rule. Both agree
    to the quadrature's accuracy. The work is done in parts of bounded memory.

    Returns
    -------
    Stress

    Raises
    ------
    TypeError
        A traction that is not callable, points or values of the wrong type.
    ValueError
        Non-finite points, ``z < 0``, ``ends`` out of order, a kink outside
        ``ends``, ``nu`` outside ``(-1, 0.5]``, a traction that is not finite on
        ``ends``, or a surface point at a contact end where the shear jumps
        (its ``σxx`` is infinite there).
    """
    xb, zb, p_fn, q_fn, bulk, poisson = _stress_iv(x, z, pressure, shear, sigma_bulk, nu)
    lo, hi, k = _ends_kinks(ends, kinks)
    funcs = {name: f for name, f in (("pressure", p_fn), ("shear", q_fn)) if f is not None}
    xf = xb.ravel()
    sxx, szz, sxz = np.zeros(xf.size), np.zeros(xf.size), np.zeros(xf.size)
    c = -2.0 / math.pi
    done = [0]
    with _progress(progress, done, xf.size):
        for part, I in _parts(xb, zb, funcs, lo, hi, k):   # each part's integrals made and dropped in turn
            if p_fn is not None:
                pxx, pzz, pxz, _ = I["pressure"]
                sxx[part], szz[part], sxz[part] = c * pxx, c * pzz, c * pxz
            if q_fn is not None:
                qxz, _, qzz, qxx = I["shear"]
                sxx[part] += c * qxx
                szz[part] += c * qzz
                sxz[part] += c * qxz
            done[0] += sxx[part].size
    sxx += bulk
    if not np.all(np.isfinite(sxx)):
        where = int(np.argmax(~np.isfinite(sxx)))
        raise InputError(f"σxx is infinite at the surface point x = {xb.ravel()[where]:.6g}, a contact "
                         "end where the shear traction jumps; evaluate at z > 0")
    shape = xb.shape
    return Stress(x=xb.copy(), z=zb.copy(), sxx=sxx.reshape(shape), szz=szz.reshape(shape),
                  sxz=sxz.reshape(shape), nu=poisson, rule=tuple(RULE.items()))


def hilbert(func: Traction, x: ArrayLike, *, ends: tuple[float, float], kinks: ArrayLike = ()) -> np.ndarray:
    """``(1/π) PV∫ f(t)/(t - x) dt`` over ``ends``, at surface points ``x``.

    The Hilbert transform that gives the surface ``σxx`` of a shear traction,
    ``(2/π) PV∫ q(t)/(t - x) dt``, and that the pressure satisfies in the
    paper's eq. (integral_equation): ``(1/π) PV∫ p(t)/(t - x) dt = -v'(x)/A``
    with ``p >= 0`` compressive (the paper's ``p`` is negative).
    Computed by the rule of :func:`stress` at ``z = 0``.
    """
    xa = _array("x", x)
    fn = _traction("func", func)
    lo, hi, k = _ends_kinks(ends, kinks)
    flat = xa.ravel()
    val = np.empty(flat.size)
    for part in _chunks(flat.size):
        val[part] = -_integrals(flat[part], np.zeros(flat[part].size), {"func": fn}, lo, hi, k,
                                RULE)["func"][3] / math.pi
    if not np.all(np.isfinite(val)):
        where = flat[int(np.argmax(~np.isfinite(val)))]
        raise InputError(f"the Hilbert transform is infinite at x = {where:.6g}, a contact end where "
                         "`func` jumps")
    return val.reshape(xa.shape)

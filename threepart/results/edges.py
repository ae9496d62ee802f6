"""Edge asymptotics: the multipliers of each contact edge and its asymptotic slip zone.

Near an edge of an incomplete contact, at a distance ``r`` inside it, the
pressure is ``p ≈ K_N √r`` and the shear of the fully stuck contact is
``q ≈ K_T/√r`` (docs/EDGES.md). Two edges that share ``K_N``, ``K_T`` and the
bulk stress share their local field, and with it the slip zone
``2 |K_T|/(f K_N)`` (eq. E5): a dovetail flank's edge can be reproduced by a
Hertzian pad test (:func:`threepart.studies.matching.match`).

The core holds no solver: a method gives its ``K_N`` through the registry
(:attr:`threepart.registry.Method.edges`); ``K_T`` follows from the loads and
the method's own contact ``[-a, c]`` (eq. E3), the same for every method.

Names
-----
Edged       -- the ``edges()`` method every normal, slip, fretting and steady-state result inherits
Edge        -- the multipliers of one edge (left ``-a`` or right ``c``), with units (threepart.problem.units)
edges       -- the two :class:`Edge` records of a normal, slip, fretting or steady-state result
K_T_stuck   -- ``(K_T_left, K_T_right)`` of the fully stuck shear under ``Q`` and ``sigma_bulk`` (E3)
K_sigma     -- the bulk stress's share of ``K_T`` at each edge (E3)
slip_zone   -- the asymptotic slip zone ``2 |K_T|/(f K_N)`` (E5), or of a cycle (E7)
exact_slip  -- a result's own slip zone at an edge, to compare the asymptote with
hertz_K_N   -- ``K_N = p0 √(2/a)`` of a Hertzian contact (E2)
SIDES       -- ``("left", "right")``
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, ClassVar

from .. import registry
from threepart.errors import InputError, InputTypeError

if TYPE_CHECKING:
    from .contact import NormalResult

__all__ = ["Edge", "Edged", "edges", "K_T_stuck", "K_sigma", "slip_zone", "exact_slip", "hertz_K_N", "SIDES",
           "EDGE_KINDS"]

#: the two edges of a contact, in the order :func:`edges` returns them
SIDES = ("left", "right")


@dataclass(frozen=True)
class Edge:
    """The asymptotic multipliers of one contact edge (docs/EDGES.md); units in :data:`threepart.problem.units.UNITS`.

    Attributes
    ----------
    side, x
        ``"left"`` (at ``x = -a``) or ``"right"`` (at ``x = c``), and that ``x``.
    K_N
        Bounded pressure's multiplier, ``p ≈ K_N √r`` at ``r`` inside the edge
        (MPa/√mm; eq. E1). For a cycle the mean of its two end states'.
    K_T
        Multiplier of the fully stuck shear, ``q ≈ K_T/√r`` (MPa·√mm; eq. E3),
        with the sign of the shear's force; for a cycle, of the change of shear
        from state 0 (or ``-Q_max``) to state 1 (or ``Q_max``). None without a shear.
    K_sigma
        The bulk stress's share of ``K_T`` (E3), None without a shear.
    sigma_bulk
        The bulk stress at the edge (MPa): the regular tension of its local
        field; for a cycle its change. None without a shear.
    slip_zone
        Asymptotic slip zone at the edge (mm; eq. E5, E7), None without a shear.
    fit_error
        Bound on the error of ``K_N`` from the method's fit (FEM), None where
        ``K_N`` is exact to rounding (closed form, SIE).
    kind, method
        The result it came from (``"normal"``, ``"slip"``, ``"fretting"``,
        ``"steady"``) and its method.
    """

    side: str
    x: float
    K_N: float
    K_T: float | None = None
    K_sigma: float | None = None
    sigma_bulk: float | None = None
    slip_zone: float | None = None
    fit_error: float | None = None
    kind: str = "normal"
    method: str = ""


def hertz_K_N(p0: float, a: float) -> float:
    """``K_N = p0 √(2/a)`` of Hertz's pressure ``p0 √(1 - x²/a²)`` (eq. E2)."""
    return p0 * math.sqrt(2.0 / a)


def K_T_stuck(Q: float, sigma_bulk: float, a: float, c: float) -> tuple[float, float]:
    """``(K_T_left, K_T_right)`` of the fully stuck shear on ``[-a, c]`` (eq. E3).

    ``q = [Q/π + (sigma_bulk/4)(m - x)]/√((x + a)(c - x))``, ``m = (c - a)/2``
    (docs/BULK_STRESS.md, B6 over the whole contact), so with ``W = a + c``
    ``K_T = (Q/π ± sigma_bulk W/8)/√W``, ``+`` at the left edge.
    """
    W = a + c
    shear = Q / math.pi
    left, right = K_sigma(sigma_bulk, a, c)
    return shear / math.sqrt(W) + left, shear / math.sqrt(W) + right


def K_sigma(sigma_bulk: float, a: float, c: float) -> tuple[float, float]:
    """The bulk stress's share of ``K_T`` at each edge: ``(+, -) sigma_bulk √W/8`` (eq. E3)."""
    share = sigma_bulk * math.sqrt(a + c) / 8.0
    return share, -share


def slip_zone(K_T: float, K_N: float, f: float, *, cycle: bool = False) -> float:
    """Asymptotic slip zone ``2 |K_T|/(f K_N)`` (eq. E5); of a cycle ``|ΔK_T|/(f K_N)`` (eq. E7).

    For a cycle ``K_T`` is the change of the stuck shear's multiplier over the
    half-cycle and ``K_N`` the mean of the two end states' (the slip zones
    carry ``2 f`` times the mean pressure's change of shear, eq. S3).
    """
    return (1.0 if cycle else 2.0) * abs(K_T) / (f * K_N)


def _normal_multipliers(normal: NormalResult) -> tuple[tuple[float, float | None], ...]:
    """``((K_N, fit_error), (K_N, fit_error))`` of a normal result, by its method's ``edges``."""
    method = registry.get(normal.method)
    if method.edges is None:
        raise InputError(f"method {normal.method!r} does not compute edge multipliers "
                         "(its registry entry has no `edges`)")
    return method.edges(normal)


def _edges_normal(result: NormalResult) -> tuple[Edge, Edge]:
    """The two records of a normal result: ``K_N`` (and the FEM's fit error) only."""
    (K_l, err_l), (K_r, err_r) = _normal_multipliers(result)
    return (Edge("left", -result.a, K_l, fit_error=err_l, method=result.method),
            Edge("right", result.c, K_r, fit_error=err_r, method=result.method))


def _with_shear(normals: tuple[NormalResult, ...], K_T: tuple[float, float],
                K_s: tuple[float, float], sigma: float, f: float, kind: str, method: str,
                cycle: bool) -> tuple[Edge, Edge]:
    """The two records of a result with a shear: ``K_N`` (mean over ``normals``) and the given ``K_T``."""
    mults = [_normal_multipliers(n) for n in normals]
    out = []
    for k, side in enumerate(SIDES):
        K_N = sum(m[k][0] for m in mults) / len(mults)
        errs = [m[k][1] for m in mults]
        err = None if all(e is None for e in errs) else max(e or 0.0 for e in errs)
        x = (-normals[0].a, normals[0].c)[k]
        out.append(Edge(side, x, K_N, K_T[k], K_s[k], sigma, slip_zone(K_T[k], K_N, f, cycle=cycle),
                        err, kind, method))
    return out[0], out[1]


class Edged:
    """What every normal, slip, fretting and steady-state result has: :meth:`edges`.

    A result class names the records :func:`edges` builds for it in :attr:`edge_kind`
    (``"normal"``, ``"slip"``, ``"fretting"`` or ``"steady"``), so that this module needs
    none of the result classes: they import it.
    """

    #: which records :func:`edges` builds (a key of :data:`EDGE_KINDS`); a subclass inherits it
    edge_kind: ClassVar[str] = ""

    def edges(self) -> tuple[Edge, Edge]:
        """Multipliers of the edges ``-a`` and ``c``: K_N, K_T, slip zone (:func:`edges`)."""
        return edges(self)


def edges(result: Any) -> tuple[Edge, Edge]:
    """The :class:`Edge` records ``(left, right)`` of a result of any method (docs/EDGES.md).

    Parameters
    ----------
    result
        A :class:`~threepart.results.NormalResult`, :class:`~threepart.results.SlipResult`
        (``K_T`` of its ``Q`` and ``sigma_bulk``, E3), :class:`~threepart.results.FrettingResult`
        (``K_T`` of the change from ``-Q_max`` to ``Q_max``, reloading) or
        :class:`~threepart.results.cycles.SteadyStateResult` (of the change from state 0 to 1).

    Raises
    ------
    TypeError
        For any other object.
    ValueError
        If the result's method computes no multipliers (its registry entry has
        no ``edges``), or as that method's ``edges`` raises (the FEM: too few
        nodes near an edge for the fit).
    """
    build = EDGE_KINDS.get(result.edge_kind) if isinstance(result, Edged) else None
    if build is None:
        raise InputTypeError(f"`result` must be a normal, slip, fretting or steady-state result, "
                             f"not {type(result).__name__}")
    return build(result)


def _edges_slip(result: Any) -> tuple[Edge, Edge]:
    """Records of a partial-slip result: ``K_T`` of its ``Q`` and ``sigma_bulk`` (E3)."""
    n = result.normal
    return _with_shear((n,), K_T_stuck(result.Q, result.sigma_bulk, n.a, n.c),
                       K_sigma(result.sigma_bulk, n.a, n.c), result.sigma_bulk, result.f,
                       "slip", result.method, cycle=False)


def _edges_fretting(result: Any) -> tuple[Edge, Edge]:
    """Records of a fretting cycle: ``K_T`` of the change from ``-Q_max`` to ``Q_max`` (E7)."""
    n, dQ, ds = result.normal, 2.0 * result.Q_max, 2.0 * result.sigma_bulk
    return _with_shear((n,), K_T_stuck(dQ, ds, n.a, n.c), K_sigma(ds, n.a, n.c), ds, result.f,
                       "fretting", result.method, cycle=True)


def _edges_steady(result: Any) -> tuple[Edge, Edge]:
    """Records of a steady state: ``K_T`` of the change of the stuck shear from state 0 to 1 (E7)."""
    n0, n1 = result.normals
    (_, _, Q0, s0), (_, _, Q1, s1) = result.states
    T0, T1 = K_T_stuck(Q0, s0, n0.a, n0.c), K_T_stuck(Q1, s1, n1.a, n1.c)
    S0, S1 = K_sigma(s0, n0.a, n0.c), K_sigma(s1, n1.a, n1.c)
    dT = (T1[0] - T0[0], T1[1] - T0[1])
    dS = (S1[0] - S0[0], S1[1] - S0[1])
    return _with_shear((n0, n1), dT, dS, s1 - s0, result.f, "steady", result.method, cycle=True)


#: the records of each kind of result (:attr:`Edged.edge_kind`)
EDGE_KINDS: dict[str, Callable[[Any], tuple[Edge, Edge]]] = {
    "normal": _edges_normal, "slip": _edges_slip, "fretting": _edges_fretting, "steady": _edges_steady}


def exact_slip(res: Any, k: int) -> float | None:
    """A result's own slip zone at edge ``k`` (0 left, 1 right): from its contact end to its stick
    zone's; None for a result without a stick zone (a normal result, a cycle that shook down)."""
    zone = getattr(res, "stick_zone", None)
    if zone is None or getattr(res, "shakedown", False) or not hasattr(res, "d"):
        return None
    normal = res.normals[0] if hasattr(res, "normals") else getattr(res, "normal", res)
    lo, hi = zone
    return float(lo + normal.a) if k == 0 else float(normal.c - hi)

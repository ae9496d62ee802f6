"""Two elastically similar bodies with Coulomb friction: partial slip and the fretting cycle.

The model (issue 11). The substrate is the block of :mod:`fem.mesh`; the punch
body is its mirror image about the interface ``y = 0``, whose top ``y = L`` is
welded to a rigid loading plate. The plate translates by ``(xi, -delta)`` and
tilts by ``alpha``; the punch's shape enters, as in the paper, only as the
initial gap ``g(x)`` of eq. (2). Both bodies have the same ``E`` and ``nu``, so
Dundurs' ``beta = 0`` and the composite compliance is ``A = 4 (1 - nu^2) / E``.

Each body is condensed onto its interface nodes, both displacement components
(:func:`fem.elasticity.condense`); the meshes match node for node. With ``fn_i``
the normal force the punch presses onto the substrate at node ``i`` (``f`` is
the coefficient of friction) and ``t_i`` the shear force it drags the substrate
with (``sum t_i = Q``), the gap and the relative tangential displacement of the
punch are::

    gap_i = g(x_i) + alpha x_i - delta + (C_nn fn)_i - (C_nt t)_i
    w_i   = xi + (C_tn fn)_i - (C_tt t)_i

where ``C_nn = G^P_yy + G^S_yy``, ``C_nt = G^P_yx + G^S_yx``, ``C_tn = G^P_xy + G^S_xy``
and ``C_tt = G^P_xx + G^S_xx`` are sums of the two bodies' flexibility blocks
(``u = G F`` for nodal forces ``F``). For mirror images ``C_nt`` and ``C_tn``
vanish: the normal and tangential problems uncouple, as the paper assumes; the
solver does not rely on it (it iterates the two to a fixed point).

The load history is ``P`` at lever arm ``s`` first (frictionless normal contact,
:func:`fem.contact.solve_contact` on ``C_nn``), then ``Q`` in steps. In each step
the interface nodes in contact either stick (``w_i`` keeps its value of the
previous step) or slip (``t_i = ±f fn_i`` with the sign of the slip increment),
found by a primal-dual active-set iteration on the complementarity function
``t_i = proj_[-f fn_i, f fn_i](t_i + c Δw_i)`` (Hüeber, Stadler & Wohlmuth 2008).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from skfem import MeshTri

from threepart.errors import FullSlidingError, NoConvergenceError
from threepart.material import similar_pair
from threepart.meshes import SubstrateSpec
from threepart.punch import Punch
from threepart.results import BRANCHES, FrettingResult, NormalResult, SlipResult
from threepart.validate import check_contact, check_states, integer, shear_load

from .contact import ContactSolution, solve_contact
from .elasticity import SurfaceCompliance, condense
from ._boundary import boundary
from ._iv import MAX_FE_STATES, STEPS, mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .ends import REFINE_ATTEMPTS, check_one_zone, contact_ends, end_size, refined
from .mesh import PRESETS, MeshPreset, Substrate, make_substrate
from .solve import FemResult, MeshArg, place_substrate

__all__ = ["Interface", "FemSlipResult", "FemFrettingResult", "Step", "mirror", "interface",
           "solve_partial_slip", "fretting_cycle"]


def mirror(sub: Substrate) -> Substrate:
    """The mirror image of ``sub`` about ``y = 0``, with the same named boundary groups.

    The triangles' orientation is restored (two vertices swapped); the groups
    are carried over by their vertex pairs, so the image's ``"contact"`` nodes
    are the original's, node for node.
    """
    if not isinstance(sub, Substrate):
        raise TypeError(f"`sub` must be a fem.Substrate, not {type(sub).__name__}")
    m = sub.mesh
    image = MeshTri(np.ascontiguousarray(m.p * np.array([[1.0], [-1.0]])),
                    np.ascontiguousarray(m.t[[0, 2, 1]]))
    nv = m.p.shape[1]

    def keys(mesh: MeshTri) -> np.ndarray:
        f = np.sort(mesh.facets, axis=0).astype(np.int64)
        return f[0] * nv + f[1]

    new_keys = keys(image)
    order = np.argsort(new_keys)
    old_keys = keys(m)
    groups = {name: np.sort(order[np.searchsorted(new_keys, old_keys[facets], sorter=order)])
              for name, facets in sub.boundaries.items()}
    return Substrate(mesh=image, boundaries=groups, path=sub.path + " (mirrored)")


@dataclass(frozen=True, eq=False)
class Interface:
    """The two bodies seen from their matched interface nodes.

    Attributes
    ----------
    x, weights
        Node positions (increasing) and lumped weights ``w_i = ∫ phi_i ds``.
    C_nn, C_nt, C_tn, C_tt
        Blocks of the interface flexibility (module docstring).
    h, dofs
        Largest element size on the interface and DOFs of both bodies.
    timings
        Seconds spent assembling and factorising both bodies.
    backend
        The sparse factorisation that condensed them (:func:`fem.choose_backend`).
    """

    x: np.ndarray
    weights: np.ndarray
    C_nn: np.ndarray
    C_nt: np.ndarray
    C_tn: np.ndarray
    C_tt: np.ndarray
    h: float
    dofs: int
    timings: dict[str, float]
    backend: str = "scipy"


@boundary
def interface(lower: Substrate, upper: Substrate | None, E: float, nu: float) -> Interface:
    """Condense both bodies onto their interface and combine their flexibilities.

    ``lower`` is the substrate (below ``y = 0``), ``upper`` the punch body above
    it; ``None`` stands for ``lower``'s mirror image (:func:`mirror`), whose
    flexibility is ``lower``'s reflected, ``G' = R G R`` with ``R = diag(1, -1)``
    on the ``(u_x, u_y)`` blocks: the same blocks, the coupling ones negated.
    That halves the cost and is what condensing the mirrored mesh gives, to
    round-off (tests/test_fem_friction.py checks it).

    Raises
    ------
    ValueError
        If the two bodies' interface nodes do not match.
    """
    if upper is not None and not isinstance(upper, Substrate):
        raise TypeError(f"`upper` must be a fem.Substrate or None, not {type(upper).__name__}")
    S = condense(lower, E, nu, ("u^1", "u^2"))
    B = S if upper is None else condense(upper, E, nu, ("u^1", "u^2"))
    if len(S.x) != len(B.x) or not np.allclose(S.x, B.x, rtol=0, atol=1e-12 * np.ptp(S.x)):
        raise ValueError("the two bodies' interface nodes do not match (use `mirror`)")
    n = len(S.x)

    def blocks(sc: SurfaceCompliance, sign: float) -> tuple[np.ndarray, ...]:
        C = sc.C
        return C[:n, :n], sign * C[:n, n:], sign * C[n:, :n], C[n:, n:]

    Sxx, Sxy, Syx, Syy = blocks(S, 1.0)
    Bxx, Bxy, Byx, Byy = blocks(B, -1.0 if upper is None else 1.0)
    timings = {k: S.timings[k] + (0.0 if upper is None else B.timings[k]) for k in S.timings}
    return Interface(x=S.x, weights=S.weights, C_nn=Byy + Syy, C_nt=Byx + Syx, C_tn=Bxy + Sxy,
                     C_tt=Bxx + Sxx, h=S.h, dofs=S.dofs + B.dofs, timings=timings,
                     backend=S.backend)


@dataclass(frozen=True, eq=False)
class Step:
    """The interface after one load step.

    Attributes
    ----------
    Q, branch
        Shear force and branch (:data:`threepart.results.BRANCHES`).
    fn, t
        Normal and shear nodal forces (``fn``: ``f`` is the coefficient of friction).
    w
        Relative tangential displacement of the punch at the nodes.
    xi
        Tangential displacement of the loading plate.
    stick
        Nodes that did not slip in this step.
    direction
        Sign of the step's load increment (+1 or -1).
    iterations
        Active-set iterations of the tangential problem.
    """

    Q: float
    branch: str
    fn: np.ndarray = field(repr=False)
    t: np.ndarray = field(repr=False)
    w: np.ndarray = field(repr=False)
    xi: float
    stick: np.ndarray = field(repr=False)
    direction: int
    iterations: int


def _tangential(itf: Interface, fn: np.ndarray, w_prev: np.ndarray, Q: float, mu: float,
                stick0: np.ndarray, max_iter: int) -> tuple[np.ndarray, float, np.ndarray, int]:
    """Shear forces, plate displacement and stick set of one load step (normal forces ``fn`` given).

    Stick nodes keep ``w_prev``; slip nodes carry ``t_i = ±mu fn_i``; ``sum t = Q``.
    """
    touch = fn > 0
    bound = mu * fn
    C = itf.C_tt
    w0 = itf.C_tn @ fn
    stick = stick0 & touch
    sign = np.zeros(len(fn))
    if not stick.any():   # start from the node that carries the most force
        stick[np.argmax(fn)] = True
    t = np.zeros(len(fn))
    cpd = 1.0 / float(np.mean(np.diag(C)))
    for it in range(1, max_iter + 1):
        slip = touch & ~stick
        S = np.flatnonzero(stick)
        t_slip = np.where(slip, sign * bound, 0.0)
        m = len(S)
        M = np.zeros((m + 1, m + 1))
        M[:m, :m] = -C[np.ix_(S, S)]
        M[:m, m] = 1.0
        M[m, :m] = 1.0
        rhs = np.empty(m + 1)
        rhs[:m] = w_prev[S] - w0[S] + C[S] @ t_slip
        rhs[m] = Q - t_slip.sum()
        sol = np.linalg.solve(M, rhs)
        t = t_slip.copy()
        t[S] = sol[:m]
        xi = float(sol[m])
        dw = xi + w0 - C @ t - w_prev
        z = t + cpd * dw
        new_stick = touch & (np.abs(z) < bound)
        new_sign = np.where(touch & ~new_stick, np.sign(z), 0.0)
        if np.array_equal(new_stick, stick) and np.array_equal(new_sign[slip], sign[slip]):
            break
        stick, sign = new_stick, new_sign
        if not stick.any():
            raise FullSlidingError(
                f"`Q` = {Q:.6g}: every node in contact slides (|Q| reached the discrete f P)")
    else:
        raise NoConvergenceError(
            f"stick/slip states did not settle within `max_iter` = {max_iter} iterations")
    over = np.abs(t) - bound
    if over.max() > 1e-9 * max(bound.max(), 1e-300):
        raise NoConvergenceError(f"shear exceeds f p by {over.max():.3g} after {it} iterations")
    return t, xi, stick, it


@dataclass(frozen=True)
class FemSlipResult(SlipResult):
    """FE partial-slip solution of the two-body model.

    Attributes (beyond :class:`~threepart.results.SlipResult`)
    ----------
    x_nodes, q_nodes
        Interface nodes and their shear ``t_i / w_i``.
    slip_nodes
        Relative slip of the punch since the shear was first applied.
    history
        One :class:`Step` per load step.
    """

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    q_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    slip_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear traction, linear between nodes, 0 outside the contact."""
        return _interp(self.normal, self.x_nodes, self.q_nodes, x)

    def slip(self, x: ArrayLike) -> np.ndarray:
        """Relative slip of the punch over the substrate since ``Q = 0`` (0 in the stick zone)."""
        return _interp(self.normal, self.x_nodes, self.slip_nodes, x)


def _interp(normal: NormalResult, xn: np.ndarray, values: np.ndarray, x: ArrayLike) -> np.ndarray:
    """Nodal ``values`` interpolated linearly over the contact ``[-a, c]``, 0 outside."""
    x = np.asarray(x, dtype=float)
    inside = (xn > -normal.a) & (xn < normal.c)
    xs = np.concatenate([[-normal.a], xn[inside], [normal.c]])
    vs = np.concatenate([[0.0], values[inside], [0.0]])
    return np.interp(x, xs, vs, left=0.0, right=0.0)


@dataclass(frozen=True)
class FemFrettingResult(FrettingResult):
    """FE fretting cycle of the two-body model, by the incremental load path.

    Attributes (beyond :class:`~threepart.results.FrettingResult`)
    ----------
    history
        One :class:`Step` per recorded state, in the order of :attr:`Q`.
    x_nodes
        Interface nodes.
    """

    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)

    def _state(self, Q: float, branch: str) -> Step:
        for st in self.history:
            if st.branch == branch and math.isclose(st.Q, Q, rel_tol=1e-12, abs_tol=1e-12 * self.Q_max):
                return st
        raise ValueError(f"`Q` = {Q!r} on `branch` = {branch!r} is not a recorded state "
                         f"(one of the {len(self.history)} of `Q` on {BRANCHES})")

    def shear(self, x: ArrayLike, Q: float, branch: str) -> np.ndarray:
        st = self._state(Q, branch)
        return _interp(self.normal, self.x_nodes, st.t / self.weights, x)

    def slip_amplitude(self, x: ArrayLike) -> np.ndarray:
        w = np.array([st.w for st in self.history if st.branch != "loading"])
        return _interp(self.normal, self.x_nodes, 0.5 * np.ptp(w, axis=0), x)


class _Model:
    """The two-body interface under ``P`` at ``s``, stepped through a shear-load path."""

    def __init__(self, punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                 lower: Substrate, L: float, guess: tuple[float, float] | None,
                 max_iter: int, mu: float) -> None:
        t0 = time.perf_counter()
        self.itf = interface(lower, None, E, nu)
        self.punch, self.P, self.s, self.tilt, self.max_iter = punch, P, s, tilt, max_iter
        self.E, self.nu, self.L, self.guess, self.mu = E, nu, L, guess, mu
        self.timings = {**self.itf.timings, "normal": 0.0, "friction": 0.0}
        self.t = np.zeros(len(self.itf.x))
        self.normal = self._normal(self.t)
        check_one_zone(self.itf.x, self.normal.active, P, s)
        self.fn = self.normal.f
        self.w0 = self.itf.C_tn @ self.fn          # relative tangential displacement before Q
        self.w = self.w0.copy()
        self.stick = self.fn > 0
        self.steps: list[Step] = []
        self.h_end = math.nan
        self.timings["condense"] = time.perf_counter() - t0

    def _normal(self, t: np.ndarray) -> ContactSolution:
        t0 = time.perf_counter()
        itf = self.itf
        g0 = self.punch.profile(itf.x) - itf.C_nt @ t
        active = None if self.guess is None else (itf.x >= self.guess[0]) & (itf.x <= self.guess[1])
        sol = solve_contact(itf.C_nn, itf.x, g0, self.P, self.s, free_tilt=self.tilt == "free",
                            max_iter=self.max_iter, active=active)
        self.timings["normal"] += time.perf_counter() - t0
        return sol

    def step(self, Q: float, branch: str, direction: int) -> Step:
        """Advance to shear ``Q``; the normal and tangential problems are iterated to a fixed point."""
        t0 = time.perf_counter()
        normal, t = self.normal, self.t
        for _ in range(20):
            t, xi, stick, its = _tangential(self.itf, normal.f, self.w, Q, self.mu, self.stick,
                                            self.max_iter)
            coupled = self._normal(t) if np.any(self.itf.C_nt) else normal
            if np.abs(coupled.f - normal.f).max() <= 1e-12 * self.P:
                break
            normal = coupled
        else:
            raise NoConvergenceError("normal and tangential problems did not reach a fixed point")
        self.normal, self.t, self.stick = normal, t, stick
        self.w = xi + self.itf.C_tn @ normal.f - self.itf.C_tt @ t
        st = Step(Q=float(Q), branch=branch, fn=normal.f, t=t, w=self.w.copy(), xi=xi,
                  stick=stick, direction=direction, iterations=its)
        self.steps.append(st)
        self.timings["friction"] += time.perf_counter() - t0
        return st

    def contact_ends(self) -> tuple[float, float]:
        """Contact ends ``(-a, c)`` of the normal solution, as :func:`fem.solve_normal` finds them."""
        sol = self.normal
        return contact_ends(self.itf.x, sol.f / self.itf.weights, sol.active,
                     (-self.punch.b, self.punch.b))

    def normal_result(self) -> FemResult:
        """The normal solution as the shared result shape (composite ``A = 4 (1 - nu^2) / E``)."""
        itf, sol = self.itf, self.normal
        p = sol.f / itf.weights
        left, right = self.contact_ends()
        s_out = float(np.sum(itf.x * sol.f) / np.sum(sol.f))
        info = {"dofs": itf.dofs, "h": itf.h, "h_end": self.h_end, "L": self.L, "n_candidates": len(itf.x),
                "iterations": sol.iterations, "delta": sol.delta, "timings": self.timings,
                "model": "two similar bodies", "backend": itf.backend}
        return FemResult(punch=self.punch, A=similar_pair(self.E, self.nu), a=-left, c=right,
                         alpha=sol.alpha, P=float(np.sum(sol.f)), s=s_out, tilt=self.tilt,
                         method="fem", info=info, h=itf.h, dofs=itf.dofs, L=self.L,
                         delta=sol.delta, timings=self.timings, x_nodes=itf.x, p_nodes=p)

    def stick_zone(self, st: Step) -> tuple[float, float]:
        """Ends of the zone that has not slipped in the step's direction, from ``p*^2 -> 0``.

        ``p* = (f fn_i - direction t_i) / w_i`` vanishes where the nodes slip and
        decays as a square root at the ends of the stick zone, like the
        pressure at the contact ends (:func:`fem.ends.contact_ends`).
        """
        pstar = (self.mu * st.fn - st.direction * st.t) / self.itf.weights
        return contact_ends(self.itf.x, pstar, st.stick, (-self.punch.b, self.punch.b))


def _model(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
           mesh: MeshPreset | Path | SubstrateSpec | Substrate, max_iter: int, mu: float, Q: float,
           say: Progress) -> _Model:
    """The two-body model on the checked ``mesh``; a preset is refined at the stick-zone ends of ``Q`` too.

    The mirrored pair is a rigid punch on a block of half the modulus, so the
    contact is located as :func:`fem.solve_normal` locates it, with ``E/2``.
    With a refined preset, a first solve on the ``"locate"`` mesh places the
    stick zone of ``Q``, whose ends then become mesh nodes with fine elements
    around them, as the contact ends are. An end within ``MIN_END_ELEMENTS``
    of a join refines the preset, or is refused, as in :func:`fem.solve_normal`.
    The normal contact is checked against the limits of half-plane theory
    (:func:`threepart.validate.check_contact`) before any shear is applied.
    """
    t0 = time.perf_counter()
    breaks = (-punch.b, punch.b)
    pre = mesh
    lower, L, guess, t_locate = place_substrate(mesh, punch, P, s, 0.5 * E, nu, tilt, max_iter, say)
    ends: tuple[float, ...] = ()
    if isinstance(pre, MeshPreset) and pre.refine > 1 and Q != 0 and guess is not None:
        t1 = time.perf_counter()
        coarse = make_substrate(PRESETS["locate"].spec(*guess, breaks))
        trial = _Model(punch, P, s, E, nu, tilt, coarse, L, guess, max_iter, mu)
        ends = trial.stick_zone(trial.step(Q, "loading", 1 if Q > 0 else -1))
        t_locate += time.perf_counter() - t1
        say(f"locate: stick zone of Q = {Q:.6g} about [{ends[0]:.6g}, {ends[1]:.6g}] "
            f"({time.perf_counter() - t1:.1f} s)")
    t_mesh = time.perf_counter() - t0 - t_locate
    for attempt in range(REFINE_ATTEMPTS + 1):
        t1 = time.perf_counter()
        if isinstance(pre, MeshPreset) and guess is not None:
            spec = pre.spec(*guess, breaks)
            if ends and pre.refine > 1:
                fine = spec.h_fine / 2.0 ** 6
                nodes = tuple(round(x / fine) * fine for x in ends)
                spec = replace(spec, breakpoints=spec.breakpoints + nodes,
                               refine_at=spec.refine_at + nodes)
            lower = make_substrate(spec)
        t2 = time.perf_counter()
        t_mesh += t2 - t1
        say(f"mesh: {lower.mesh.t.shape[1]} triangles a body ({t2 - t1:.1f} s)")
        model = _Model(punch, P, s, E, nu, tilt, lower, L, guess, max_iter, mu)
        left, right = model.contact_ends()
        say(f"condense and normal contact: {model.itf.dofs} DOFs, contact [{left:.6g}, "
            f"{right:.6g}] ({time.perf_counter() - t2:.1f} s)")
        h_end = end_size(model.itf.x, left, right)
        finer = refined(punch, left, right, h_end, pre, attempt, mesh)
        if finer is None:
            break
        say(f"refine: an end lies near a join, elements W / (n {finer.refine:g}) there")
        pre, guess = finer, (left, right)   # refine at these ends and the joins
    check_contact(punch, -left, right, model.normal.alpha)
    model.timings.update(locate=t_locate, mesh=t_mesh)
    model.h_end = h_end
    return model


def _slip_iv(punch: Any, P: Any, s: Any, Q: Any, f: Any, E: Any, nu: Any, tilt: Any, mesh: Any,
             steps: Any, max_iter: Any, progress: Any, name: str = "Q") -> tuple[Any, ...]:
    """The checked input of :func:`solve_partial_slip` (and, with ``Q_max``, :func:`fretting_cycle`,
    whose ``steps`` are its ``states``)."""
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=True)
    Q, f = shear_load(Q, f, P, name)
    steps = (check_states(steps, MAX_FE_STATES) if name == "Q_max"
             else integer("steps", steps, *STEPS))
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    return P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress_iv(progress)


@boundary
def solve_partial_slip(punch: Punch, P: float, s: float = 0.0, *, Q: float, f: float, E: float,
                       nu: float, tilt: str = "free", mesh: MeshArg = "default", steps: int = 10,
                       max_iter: int = 100, progress: ProgressArg = None) -> FemSlipResult:
    """Two similar elastic bodies pressed by ``P`` at lever arm ``s``, then sheared by ``Q`` in steps.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2), the initial gap between the bodies.
    P, s, tilt
        Normal load, its lever arm and whether the tilt is free, as in
        :func:`fem.solve_normal`.
    Q, f
        Shear force, ``|Q| < f P``, and coefficient of friction.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    mesh
        The substrate's mesh, as in :func:`fem.solve_normal`; the punch body is its mirror image.
    steps
        Equal increments of ``Q`` from 0, in ``[1, 1000]``.
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    progress
        One line per stage and per load step on stderr, as in :func:`fem.solve_normal`.

    Returns
    -------
    FemSlipResult
        ``d``, ``e`` from the stick zone of the last step; ``shear``, ``slip``,
        the per-step ``history``; ``info`` holds the discretisation and the timings
        (``locate``, ``mesh``, ``assemble``, ``factorise``, ``normal``, ``friction``).

    Raises
    ------
    TypeError, ValueError
        For invalid input, before any numerics (as :func:`fem.solve_normal`,
        with ``A = 4 (1 - nu^2) / E``); ``FullSlidingError`` for ``|Q| >= f P``.
    ArcExtentError, SlopeLimitError, NoConvergenceError, ContactZoneError, SeparationError,
    MeshResolutionError
        As :func:`fem.solve_normal`, and when the stick/slip states do not settle.
    """
    P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress = _slip_iv(
        punch, P, s, Q, f, E, nu, tilt, mesh, steps, max_iter, progress)
    say = Progress(progress)
    t0 = time.perf_counter()
    model = _model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q, say)
    direction = 1 if Q >= 0 else -1
    for k in range(1, steps + 1):
        t1 = time.perf_counter()
        st = model.step(Q * k / steps, "loading", direction)
        say(f"step {k}/{steps}, Q = {st.Q:.6g}: {int(st.stick.sum())} nodes stick "
            f"({time.perf_counter() - t1:.1f} s)")
    normal = model.normal_result()
    left, right = model.stick_zone(st)
    model.timings["total"] = time.perf_counter() - t0
    info = {**normal.info, "steps": steps, "xi": st.xi, "stick_nodes": int(st.stick.sum())}
    return FemSlipResult(normal=normal, Q=float(Q), f=float(f), d=0.5 * (right - left),
                         e=-0.5 * (right + left), method="fem", info=info, x_nodes=model.itf.x,
                         q_nodes=st.t / model.itf.weights, slip_nodes=st.w - model.w0,
                         history=tuple(model.steps))


@boundary
def fretting_cycle(punch: Punch, P: float, s: float = 0.0, *, Q_max: float, f: float, E: float,
                   nu: float, tilt: str = "free", mesh: MeshArg = "default", states: int = 21,
                   max_iter: int = 100, progress: ProgressArg = None) -> FemFrettingResult:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of the two-body model, step by step.

    Each branch is stepped through ``states`` equally spaced values of ``Q``
    (both ends included), the states the closed form and the SIE record too.
    The energy dissipated per cycle is the work of the shear forces on the
    relative slip over the unloading and reloading branches,
    ``sum_i ∮ t_i dw_i`` (trapezoidal in the steps); ``info["loop_energy"]``
    holds the area of the ``Q``–``xi`` loop, the same energy by the global balance.

    Parameters and errors as :func:`solve_partial_slip`, with ``Q_max > 0`` and
    ``states`` in ``[2, 1000]``.
    """
    P, s, Q_max, f, E, nu, tilt, pre, states, max_iter, progress = _slip_iv(
        punch, P, s, Q_max, f, E, nu, tilt, mesh, states, max_iter, progress, "Q_max")
    say = Progress(progress)
    t0 = time.perf_counter()
    model = _model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q_max, say)
    path = [("loading", np.linspace(0.0, Q_max, states), 1),
            ("unloading", np.linspace(Q_max, -Q_max, states), -1),
            ("reloading", np.linspace(-Q_max, Q_max, states), 1)]
    recorded: list[Step] = []
    first = Step(Q=0.0, branch="loading", fn=model.fn, t=model.t, w=model.w.copy(), xi=0.0,
                 stick=model.stick, direction=1, iterations=0)
    for branch, Qs, direction in path:
        for k, Q in enumerate(Qs):
            if branch == "loading" and k == 0:
                recorded.append(first)
            elif k == 0:
                recorded.append(replace_branch(recorded[-1], branch, direction))
            else:
                t1 = time.perf_counter()
                recorded.append(model.step(float(Q), branch, direction))
                say(f"{branch} {k}/{states - 1}, Q = {float(Q):.6g} "
                    f"({time.perf_counter() - t1:.1f} s)")
    normal = model.normal_result()
    cycle = [st for st in recorded if st.branch != "loading"]
    work = sum(float(np.sum(0.5 * (a.t + b.t) * (b.w - a.w))) for a, b in zip(cycle, cycle[1:]))
    loop = sum(0.5 * (a.Q + b.Q) * (b.xi - a.xi) for a, b in zip(cycle, cycle[1:]))
    # at Q = 0 and at each reversal nothing has slipped yet: the whole contact sticks
    stick = np.array([model.stick_zone(st) if st.iterations else (-normal.a, normal.c)
                      for st in recorded])
    model.timings["total"] = time.perf_counter() - t0
    info = {**normal.info, "states": states, "loop_energy": float(loop)}
    return FemFrettingResult(normal=normal, Q_max=float(Q_max), f=float(f),
                             branch=np.array([st.branch for st in recorded]),
                             Q=np.array([st.Q for st in recorded]), stick=stick,
                             delta=np.array([st.xi for st in recorded]), energy=float(work),
                             method="fem", info=info, history=tuple(recorded), x_nodes=model.itf.x,
                             weights=model.itf.weights)


def replace_branch(st: Step, branch: str, direction: int) -> Step:
    """The state ``st`` recorded again as the first of ``branch`` (a reversal point)."""
    return Step(Q=st.Q, branch=branch, fn=st.fn, t=st.t, w=st.w, xi=st.xi, stick=st.stick,
                direction=direction, iterations=0)

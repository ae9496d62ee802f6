"""Two elastically similar bodies with Coulomb friction: partial slip and the fretting cycle.

The model (issue 11). The substrate is the block of :mod:`fem.mesh`; the punch
body is its mirror image about the interface ``y = 0``, whose top ``y = L`` is
welded to a rigid loading plate. The plate translates by ``(xi, -delta)`` and
tilts by ``alpha``; the punch's shape enters, as in the paper, only as the
initial gap ``g(x)`` of eq. (2). Both bodies have the same ``E`` and ``nu``, so
Dundurs' ``beta = 0`` and the composite compliance is ``A = 4 (1 - nu^2) / E``.

Each body is condensed onto its interface nodes, both displacement components
(:mod:`fem.interface`); the meshes match node for node. With ``fn_i`` the
normal force the punch presses onto the substrate at node ``i`` (``f`` is the
coefficient of friction) and ``t_i`` the shear force it drags the substrate
with (``sum t_i = Q``), the gap and the relative tangential displacement of the
punch are::

    gap_i = g(x_i) + alpha x_i - delta + (C_nn fn)_i - (C_nt t)_i
    w_i   = xi + (C_tn fn)_i - (C_tt t)_i - lambda sigma_bulk u_b(x_i)

where ``C_nn = G^P_yy + G^S_yy``, ``C_nt = G^P_yx + G^S_yx``, ``C_tn = G^P_xy + G^S_xy``
and ``C_tt = G^P_xx + G^S_xx`` are sums of the two bodies' flexibility blocks
(``u = G F`` for nodal forces ``F``). For mirror images ``C_nt`` and ``C_tn``
vanish: the normal and tangential problems uncouple, as the paper assumes; the
solver does not rely on it (it iterates the two to a fixed point).

The bulk stress ``sigma_bulk`` (tension along ``x`` in the substrate only)
acts on the substrate's end faces; ``u_b`` is the substrate's surface
displacement under a unit end tension (:func:`fem.interface.bulk_field`), the
uniform strain ``(1 - nu^2)/E`` to round-off, so a positive ``sigma_bulk``
stretches the substrate and a stuck punch must follow it. Its vertical part is
uniform along the surface, a rigid shift that ``delta`` takes up. ``lambda``
is the load fraction: ``P`` at ``s`` first (frictionless normal contact,
:func:`fem.contact.solve_contact` on ``C_nn``), then ``Q`` and the bulk stress
together in proportion, in steps (``lambda = Q / Q_ref``, ``Q_ref`` the largest
shear of the path). Each step finds the stick and slip nodes by
:func:`fem.coulomb.tangential`.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from threepart.errors import NoConvergenceError
from threepart.material import similar_pair
from threepart.meshes import SubstrateSpec
from threepart.punch import Punch
from threepart.results import BRANCHES, NU, Diagnostics, FrettingResult, NormalResult, SlipResult
from threepart.stress import Stress
from threepart.validate import check_contact, check_states, finite, integer, shear_load

from .contact import ContactSolution, solve_contact
from .coulomb import Step, reversal, tangential
from .interface import bulk_field, interface
from ._boundary import boundary
from ._iv import MAX_FE_STATES, STEPS, mesh_arg, normal_iv
from ._progress import Progress, ProgressArg, progress_iv
from .ends import REFINE_ATTEMPTS, check_one_zone, contact_ends, end_size, refined
from .mesh import PRESETS, MeshPreset, Substrate, make_substrate
from .recovery import StressField, model_nu
from .solve import FemResult, MeshArg, place_substrate

__all__ = ["FemSlipResult", "FemFrettingResult", "solve_partial_slip", "fretting_cycle"]


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
        One :class:`~fem.coulomb.Step` per load step.
    stress_field
        The substrate's displacement at the last step, for :meth:`stress`.
    """

    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    q_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    slip_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    stress_field: StressField | None = field(default=None, compare=False, repr=False)

    def shear(self, x: ArrayLike) -> np.ndarray:
        """Shear traction, linear between nodes, 0 outside the contact."""
        return _interp(self.normal, self.x_nodes, self.q_nodes, x)

    def slip(self, x: ArrayLike) -> np.ndarray:
        """Relative slip of the punch over the substrate since ``Q = 0`` (0 in the stick zone)."""
        return _interp(self.normal, self.x_nodes, self.slip_nodes, x)

    def stress(self, x: ArrayLike, z: ArrayLike, *, nu: float | None = None) -> Stress:  # type: ignore[override]
        """Stresses in the substrate at ``(x, z)`` from the FE field, ``sigma_bulk`` included.

        Recovered by :class:`fem.recovery.StressField`; ``nu`` must be the
        model's (``None``).
        """
        if self.stress_field is None:
            return super().stress(x, z, nu=NU if nu is None else nu)
        model_nu(nu, self.stress_field.nu)
        return self.stress_field.at(x, z)


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
        One :class:`~fem.coulomb.Step` per recorded state, in the order of :attr:`Q`.
    x_nodes, weights
        Interface nodes and their lumped weights.
    """

    history: tuple[Step, ...] = field(default=(), compare=False, repr=False)
    x_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    weights: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False, repr=False)
    model: Any = field(default=None, compare=False, repr=False)

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

    def stress(self, x: ArrayLike, z: ArrayLike, Q: float, branch: str, *,  # type: ignore[override]
               nu: float | None = None) -> Stress:
        """Stresses in the substrate at ``(x, z)`` in the recorded state ``(Q, branch)``, from the FE field.

        The bulk stress is ``sigma_bulk Q / Q_max`` (in phase with ``Q``);
        ``nu`` must be the model's (``None``).
        """
        st = self._state(Q, branch)
        model_nu(nu, self.model.nu)
        return self.model.field(st, st.Q / self.Q_max).at(x, z)


class _Model:
    """The two-body interface under ``P`` at ``s``, stepped through a shear-load path."""

    def __init__(self, punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                 lower: Substrate, L: float, guess: tuple[float, float] | None,
                 max_iter: int, mu: float, sigma_bulk: float = 0.0) -> None:
        t0 = time.perf_counter()
        self.itf = interface(lower, None, E, nu)
        self.punch, self.P, self.s, self.tilt, self.max_iter = punch, P, s, tilt, max_iter
        self.E, self.nu, self.L, self.guess, self.mu = E, nu, L, guess, mu
        self.lower, self.sigma_bulk = lower, sigma_bulk
        self.timings = {**self.itf.timings, "normal": 0.0, "friction": 0.0}
        n = len(self.itf.x)
        self.t = np.zeros(n)
        self.normal = self._normal(self.t)
        check_one_zone(self.itf.x, self.normal.active, P, s)
        self.fn = self.normal.f
        self.w0 = self.itf.C_tn @ self.fn          # relative tangential displacement before Q
        self.w = self.w0.copy()
        self.stick = self.fn > 0
        self.steps: list[Step] = []
        self.h_end = math.nan
        self.u_bulk: np.ndarray | None = None
        self.ub = np.zeros(n)                      # substrate's u_x at the nodes under sigma_bulk
        if sigma_bulk != 0.0:
            t1 = time.perf_counter()
            sc = self.itf.substrate
            assert sc is not None
            self.u_bulk = bulk_field(lower, sc, E, nu)
            self.ub = sigma_bulk * self.u_bulk[sc.surface_dofs[:n]]
            self.timings["bulk"] = time.perf_counter() - t1
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

    def step(self, Q: float, branch: str, direction: int, fraction: float) -> Step:
        """Advance to shear ``Q`` and the bulk stress ``fraction sigma_bulk``.

        The normal and tangential problems are iterated to a fixed point.
        """
        t0 = time.perf_counter()
        normal, t = self.normal, self.t
        bulk = fraction * self.ub
        for _ in range(20):
            w_fixed = self.itf.C_tn @ normal.f - bulk
            t, xi, stick, its, res = tangential(self.itf, normal.f, self.w, w_fixed, Q, self.mu,
                                                self.stick, self.max_iter)
            coupled = self._normal(t) if np.any(self.itf.C_nt) else normal
            if np.abs(coupled.f - normal.f).max() <= 1e-12 * self.P:
                break
            normal = coupled
        else:
            raise NoConvergenceError("normal and tangential problems did not reach a fixed point")
        self.normal, self.t, self.stick = normal, t, stick
        self.w = xi + self.itf.C_tn @ normal.f - bulk - self.itf.C_tt @ t
        st = Step(Q=float(Q), branch=branch, fn=normal.f, t=t, w=self.w.copy(), xi=xi,
                  stick=stick, direction=direction, iterations=its, residual=res)
        self.steps.append(st)
        self.timings["friction"] += time.perf_counter() - t0
        return st

    def field(self, st: Step, fraction: float) -> StressField:
        """The substrate's displacement in the state ``st`` with the bulk stress ``fraction sigma_bulk``."""
        sc = self.itf.substrate
        assert sc is not None
        basis, u = sc.displacement(np.concatenate([st.t, -st.fn]))
        if self.u_bulk is not None:
            u = u + fraction * self.sigma_bulk * self.u_bulk
        return StressField(basis=basis, u=u, E=self.E, nu=self.nu)

    def contact_ends(self) -> tuple[float, float]:
        """Contact ends ``(-a, c)`` of the normal solution, as :func:`fem.solve_normal` finds them."""
        sol = self.normal
        return contact_ends(self.itf.x, sol.f / self.itf.weights, sol.active,
                            (-self.punch.b, self.punch.b))

    def diagnostics(self, steps: int, total: float) -> Diagnostics:
        """The typed record of the model's solve so far (active-set iterations summed over the steps)."""
        self.timings["total"] = total
        return Diagnostics(h=self.itf.h, h_end=self.h_end, dofs=self.itf.dofs, L=self.L,
                           iterations=self.normal.iterations + sum(s.iterations for s in self.steps),
                           residual=max((s.residual for s in self.steps), default=0.0),
                           steps=steps, timings=dict(self.timings))

    def normal_result(self, diagnostics: Diagnostics) -> FemResult:
        """The normal solution as the shared result shape (composite ``A = 4 (1 - nu^2) / E``)."""
        itf, sol = self.itf, self.normal
        p = sol.f / itf.weights
        left, right = self.contact_ends()
        s_out = float(np.sum(itf.x * sol.f) / np.sum(sol.f))
        info = {"n_candidates": len(itf.x), "model": "two similar bodies", "backend": itf.backend}
        frictionless = Step(Q=0.0, branch="loading", fn=sol.f, t=np.zeros(len(itf.x)),
                            w=self.w0, xi=0.0, stick=self.fn > 0, direction=1, iterations=0)
        return FemResult(punch=self.punch, A=similar_pair(self.E, self.nu), a=-left, c=right,
                         alpha=sol.alpha, P=float(np.sum(sol.f)), s=s_out, tilt=self.tilt,
                         method="fem", info=info, diagnostics=replace(diagnostics, steps=None),
                         delta=sol.delta, x_nodes=itf.x, p_nodes=p,
                         stress_field=self.field(frictionless, 0.0))

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
           sigma_bulk: float, say: Progress) -> _Model:
    """The two-body model on the checked ``mesh``; a preset is refined at the stick-zone ends of ``Q`` too.

    The mirrored pair is a rigid punch on a block of half the modulus, so the
    contact is located as :func:`fem.solve_normal` locates it, with ``E/2``.
    With a refined preset, a first solve on the ``"locate"`` mesh places the
    stick zone of ``Q`` (with ``sigma_bulk``), whose ends then become mesh
    nodes with fine elements around them, as the contact ends are. An end
    within ``MIN_END_ELEMENTS`` of a join refines the preset, or is refused, as
    in :func:`fem.solve_normal`. The normal contact is checked against the
    limits of half-plane theory (:func:`threepart.validate.check_contact`)
    before any shear is applied.
    """
    t0 = time.perf_counter()
    breaks = (-punch.b, punch.b)
    pre = mesh
    lower, L, guess, t_locate = place_substrate(mesh, punch, P, s, 0.5 * E, nu, tilt, max_iter, say)
    ends: tuple[float, ...] = ()
    if isinstance(pre, MeshPreset) and pre.refine > 1 and Q != 0 and guess is not None:
        t1 = time.perf_counter()
        coarse = make_substrate(PRESETS["locate"].spec(*guess, breaks))
        trial = _Model(punch, P, s, E, nu, tilt, coarse, L, guess, max_iter, mu, sigma_bulk)
        ends = trial.stick_zone(trial.step(Q, "loading", 1 if Q > 0 else -1, 1.0))
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
                nodes = tuple(round(x / fine) * fine for x in ends
                              if spec.x_lo < x < spec.x_hi)
                spec = replace(spec, breakpoints=spec.breakpoints + nodes,
                               refine_at=spec.refine_at + nodes)
            lower = make_substrate(spec)
        t2 = time.perf_counter()
        t_mesh += t2 - t1
        say(f"mesh: {lower.mesh.t.shape[1]} triangles a body ({t2 - t1:.1f} s)")
        model = _Model(punch, P, s, E, nu, tilt, lower, L, guess, max_iter, mu, sigma_bulk)
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
             steps: Any, max_iter: Any, progress: Any, sigma_bulk: Any, name: str = "Q"
             ) -> tuple[Any, ...]:
    """The checked input of :func:`solve_partial_slip` (and, with ``Q_max``, :func:`fretting_cycle`,
    whose ``steps`` are its ``states``)."""
    P, s, E, nu, tilt, max_iter = normal_iv(punch, P, s, E, nu, tilt, max_iter, pair=True)
    Q, f = shear_load(Q, f, P, name)
    steps = (check_states(steps, MAX_FE_STATES) if name == "Q_max"
             else integer("steps", steps, *STEPS))
    pre = mesh_arg(mesh, (MeshPreset, SubstrateSpec, Substrate))
    sigma_bulk = finite("sigma_bulk", sigma_bulk)
    return P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress_iv(progress), sigma_bulk


@boundary
def solve_partial_slip(punch: Punch, P: float, s: float = 0.0, *, Q: float, f: float, E: float,
                       nu: float, tilt: str = "free", mesh: MeshArg = "default", steps: int = 10,
                       max_iter: int = 100, progress: ProgressArg = None,
                       sigma_bulk: float = 0.0) -> FemSlipResult:
    """Two similar elastic bodies pressed by ``P`` at lever arm ``s``, then sheared by ``Q`` in steps.

    Parameters
    ----------
    punch
        Punch geometry (eq. 2), the initial gap between the bodies.
    P, s, tilt
        Normal load, its lever arm and whether the tilt is free, as in
        :func:`fem.solve_normal`.
    Q, f
        Shear force the punch exerts on the substrate along ``+x``, ``|Q| < f P``,
        and coefficient of friction.
    E, nu
        Young's modulus and Poisson's ratio of both bodies (``A = 4 (1 - nu^2) / E``).
    mesh
        The substrate's mesh, as in :func:`fem.solve_normal`; the punch body is its mirror image.
    steps
        Equal increments of ``Q`` (and ``sigma_bulk``) from 0, in ``[1, 1000]``.
    max_iter
        Cap on the active-set iterations, in ``[1, 10000]``.
    progress
        One line per stage and per load step on stderr, as in :func:`fem.solve_normal`.
    sigma_bulk
        Bulk stress ``σxx`` in the substrate (tension positive), on its end
        faces, rising with ``Q`` in proportion (any finite value: the model is
        linear). Where it reverses the slip at one end the model still answers
        (the slip direction of each node comes out of the active set).

    Returns
    -------
    FemSlipResult
        ``d``, ``e`` from the stick zone of the last step; ``shear``, ``slip``,
        ``stress``, the per-step ``history``; ``diagnostics`` holds the
        discretisation, the active-set iterations and the timings (``locate``,
        ``mesh``, ``assemble``, ``factorise``, ``bulk``, ``normal``, ``friction``, ``total``).

    Raises
    ------
    TypeError, ValueError
        For invalid input, before any numerics (as :func:`fem.solve_normal`,
        with ``A = 4 (1 - nu^2) / E``); ``FullSlidingError`` for ``|Q| >= f P``.
    ArcExtentError, SlopeLimitError, NoConvergenceError, ContactZoneError, SeparationError,
    MeshResolutionError
        As :func:`fem.solve_normal`, and when the stick/slip states do not settle.
    """
    P, s, Q, f, E, nu, tilt, pre, steps, max_iter, progress, sigma_bulk = _slip_iv(
        punch, P, s, Q, f, E, nu, tilt, mesh, steps, max_iter, progress, sigma_bulk)
    say = Progress(progress)
    t0 = time.perf_counter()
    model = _model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q, sigma_bulk, say)
    direction = 1 if Q >= 0 else -1
    for k in range(1, steps + 1):
        t1 = time.perf_counter()
        st = model.step(Q * k / steps, "loading", direction, k / steps)
        say(f"step {k}/{steps}, Q = {st.Q:.6g}: {int(st.stick.sum())} nodes stick "
            f"({time.perf_counter() - t1:.1f} s)")
    left, right = model.stick_zone(st)
    field = model.field(st, 1.0)
    diag = model.diagnostics(steps, time.perf_counter() - t0)
    normal = model.normal_result(diag)
    info = {**normal.info, "xi": st.xi, "stick_nodes": int(st.stick.sum())}
    return FemSlipResult(normal=normal, Q=float(Q), f=float(f), d=0.5 * (right - left),
                         e=-0.5 * (right + left), method="fem", sigma_bulk=sigma_bulk,
                         diagnostics=diag, info=info, x_nodes=model.itf.x,
                         q_nodes=st.t / model.itf.weights, slip_nodes=st.w - model.w0,
                         history=tuple(model.steps), stress_field=field)


@boundary
def fretting_cycle(punch: Punch, P: float, s: float = 0.0, *, Q_max: float, f: float, E: float,
                   nu: float, tilt: str = "free", mesh: MeshArg = "default", states: int = 21,
                   max_iter: int = 100, progress: ProgressArg = None,
                   sigma_bulk: float = 0.0) -> FemFrettingResult:
    """One fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of the two-body model, step by step.

    Each branch is stepped through ``states`` equally spaced values of ``Q``
    (both ends included), the states the closed form and the SIE record too;
    the bulk stress follows in phase, ``sigma_bulk Q / Q_max``. The energy
    dissipated per cycle is the work of the shear forces on the relative slip
    over the unloading and reloading branches, ``sum_i ∮ t_i dw_i``
    (trapezoidal in the steps); ``info["loop_energy"]`` holds the area of the
    ``Q``–``xi`` loop, the same energy by the global balance when
    ``sigma_bulk = 0``.

    Parameters and errors as :func:`solve_partial_slip`, with ``Q_max > 0``,
    ``states`` in ``[2, 1000]`` and ``sigma_bulk`` the bulk stress at ``Q_max``.
    """
    P, s, Q_max, f, E, nu, tilt, pre, states, max_iter, progress, sigma_bulk = _slip_iv(
        punch, P, s, Q_max, f, E, nu, tilt, mesh, states, max_iter, progress, sigma_bulk, "Q_max")
    say = Progress(progress)
    t0 = time.perf_counter()
    model = _model(punch, P, s, E, nu, tilt, pre, max_iter, f, Q_max, sigma_bulk, say)
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
                recorded.append(reversal(recorded[-1], branch, direction))
            else:
                t1 = time.perf_counter()
                recorded.append(model.step(float(Q), branch, direction, float(Q) / Q_max))
                say(f"{branch} {k}/{states - 1}, Q = {float(Q):.6g} "
                    f"({time.perf_counter() - t1:.1f} s)")
    cycle = [st for st in recorded if st.branch != "loading"]
    work = sum(float(np.sum(0.5 * (a.t + b.t) * (b.w - a.w))) for a, b in zip(cycle, cycle[1:]))
    loop = sum(0.5 * (a.Q + b.Q) * (b.xi - a.xi) for a, b in zip(cycle, cycle[1:]))
    diag = model.diagnostics(states, time.perf_counter() - t0)
    normal = model.normal_result(diag)
    # at Q = 0 and at each reversal nothing has slipped yet: the whole contact sticks
    stick = np.array([model.stick_zone(st) if st.iterations else (-normal.a, normal.c)
                      for st in recorded])
    info = {**normal.info, "loop_energy": float(loop)}
    return FemFrettingResult(normal=normal, Q_max=float(Q_max), f=float(f),
                             branch=np.array([st.branch for st in recorded]),
                             Q=np.array([st.Q for st in recorded]), stick=stick,
                             delta=np.array([st.xi for st in recorded]), energy=float(work),
                             method="fem", sigma_bulk=sigma_bulk, diagnostics=diag, info=info,
                             history=tuple(recorded), x_nodes=model.itf.x,
                             weights=model.itf.weights, model=model)

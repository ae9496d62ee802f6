"""The two-body friction model of :mod:`fem.friction`: its interface, its state and its load steps.

:class:`TwoBodyModel` holds the condensed interface (:mod:`fem.interface`), the
normal contact under ``P`` at ``s`` and the shear state, and advances it by
load steps (:meth:`TwoBodyModel.step`, the Coulomb states by
:func:`fem.coulomb.tangential`) with the bulk stress in proportion.
:func:`two_body_model` builds it on a checked mesh argument, locating the
contact and the stick zone and refining the mesh at their ends. The
formulation and the sign conventions are in :mod:`fem.friction`.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from threepart.threads import one_blas_thread

from threepart.errors import InputError, NoConvergenceError
from threepart.problem.material import similar_pair
from threepart.meshes import SubstrateSpec
from threepart.problem.punch import Punch
from threepart.results import Diagnostics
from threepart.problem.validate import check_contact

from .contact import ContactSolution, solve_contact
from .coulomb import Step, tangential
from .interface import bulk_field, interface
from ._progress import Progress
from .ends import REFINE_ATTEMPTS, check_one_zone, contact_ends, end_size, refined
from .mesh import PRESETS, MeshPreset, Substrate, make_substrate
from .recovery import StressField, lazy_field
from .solve import FemResult, place_substrate, preset_ends

__all__ = ["TwoBodyModel", "two_body_model", "with_nodes"]


class TwoBodyModel:
    """The two-body interface under ``P`` at ``s``, stepped through a shear-load path (and the bulk stress).

    ``upper`` is the punch body (default: ``lower``'s mirror image, the
    paper's model) and ``gap`` the initial gap over the interface nodes
    (default: the profile of eq. 2, ``punch.profile``). A real punch body
    (:func:`fem.solve_finite_slip`) is not ``lower``'s mirror image, so the
    coupling blocks ``C_nt``, ``C_tn`` of :func:`fem.interface.interface` do
    not vanish and :meth:`step` iterates the normal and tangential problems.
    """

    def __init__(self, punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
                 lower: Substrate, L: float, guess: tuple[float, float] | None,
                 max_iter: int, mu: float, sigma_bulk: float = 0.0, *,
                 upper: Substrate | None = None,
                 gap: Callable[[np.ndarray], np.ndarray] | None = None, one_zone: bool = True) -> None:
        t0 = time.perf_counter()
        self.itf = interface(lower, upper, E, nu)
        self.gap = punch.profile if gap is None else gap
        self.punch, self.P, self.s, self.tilt, self.max_iter = punch, P, s, tilt, max_iter
        self.E, self.nu, self.L, self.guess, self.mu = E, nu, L, guess, mu
        self.lower, self.sigma_bulk = lower, sigma_bulk
        self.timings = {**self.itf.timings, "normal": 0.0, "friction": 0.0}
        n = len(self.itf.x)
        self.t = np.zeros(n)
        self.normal = self._normal(self.t)
        if one_zone:    # a worn gap (fem.wear) may part the contact where its scar is deep
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
        g0 = self.gap(itf.x) - itf.C_nt @ t
        # warm start: the last normal solution's active set (a coupled re-solve, a next step),
        # else the located contact
        last = getattr(self, "normal", None)
        active = (last.active if last is not None else None if self.guess is None
                  else (itf.x >= self.guess[0]) & (itf.x <= self.guess[1]))
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
        # dense systems of a few hundred nodes: BLAS threads only contend for the cores (on two
        # busy cores the finite body's shear path took 16 s in np.linalg.solve, 1 thread 0.3 s)
        with one_blas_thread():
            for _ in range(20):
                w_fixed = self.itf.C_tn @ normal.f - bulk
                t, xi, stick, its, res = tangential(self.itf, normal.f, self.w, w_fixed, Q,
                                                    self.mu, self.stick, self.max_iter)
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
        """The substrate's displacement in the state ``st`` with the bulk stress ``fraction sigma_bulk``.

        Made when first asked for (:func:`fem.recovery.lazy_field`): a substrate read from the
        cache factorises its stiffness only then.
        """
        sc = self.itf.substrate
        assert sc is not None
        later = sc.displacement_later(np.concatenate([st.t, -st.fn]))
        bulk = None if self.u_bulk is None else fraction * self.sigma_bulk * self.u_bulk

        def make() -> tuple[Any, np.ndarray]:
            basis, u = later()
            return basis, u if bulk is None else u + bulk

        return lazy_field(make, self.E, self.nu)

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


def _worn(punch: Punch, depth: Callable[[np.ndarray], np.ndarray]) -> Callable[[np.ndarray], np.ndarray]:
    """The gap of the punch worn by ``depth``: ``punch.profile(x) + w(x)``, ``w`` checked finite and >= 0."""
    def gap(x: np.ndarray) -> np.ndarray:
        w = np.asarray(depth(x), dtype=float)
        if w.shape != np.shape(x) or not np.all(np.isfinite(w)) or np.any(w < 0):
            raise InputError("`depth` must return finite values >= 0 of the shape of its argument")
        return punch.profile(x) + w
    return gap


def with_nodes(spec: SubstrateSpec, ends: tuple[float, ...]) -> SubstrateSpec:
    """``spec`` with a node and fine elements at each of ``ends`` inside its zone (stick-zone ends).

    The ends are rounded to ``h_fine / 64``, so that a mesh refined around the
    same ends twice has the same nodes.
    """
    fine = spec.h_fine / 2.0 ** 6
    nodes = tuple(round(x / fine) * fine for x in ends if spec.x_lo < x < spec.x_hi)
    return replace(spec, breakpoints=spec.breakpoints + nodes, refine_at=spec.refine_at + nodes)


def two_body_model(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
           mesh: MeshPreset | Path | SubstrateSpec | Substrate, max_iter: int, mu: float, Q: float,
           sigma_bulk: float, say: Progress,
           depth: Callable[[np.ndarray], np.ndarray] | None = None) -> TwoBodyModel:
    """The two-body model on the checked ``mesh``; a preset is refined at the stick-zone ends of ``Q`` too.

    The mirrored pair is a rigid punch on a block of half the modulus, so the
    contact is located as :func:`fem.solve_normal` locates it, with ``E/2``.
    With a refined preset, a first solve on the ``"locate"`` mesh places the
    stick zone of ``Q`` (with ``sigma_bulk``), whose ends then become mesh
    nodes with fine elements around them, as the contact ends are. An end
    within ``MIN_END_ELEMENTS`` of a join refines the preset, or is refused, as
    in :func:`fem.solve_normal`. The normal contact is checked against the
    limits of half-plane theory (:func:`threepart.problem.validate.check_contact`)
    before any shear is applied. ``depth``: a worn depth ``w(x)`` (both bodies together)
    that opens the gap to ``punch.profile(x) + w(x)``; the contact is located on the punch.
    """
    t0 = time.perf_counter()
    breaks = (-punch.b, punch.b)
    pre = mesh
    gap = None if depth is None else _worn(punch, depth)
    lower: Substrate | None
    guess: tuple[float, float] | None
    if isinstance(mesh, MeshPreset) and mesh.refine > 1 and Q != 0:
        # meshed below with the stick zone's ends as nodes: the preset's plain mesh is not made
        guess, t_locate = preset_ends(punch, P, s, 0.5 * E, nu, tilt, max_iter, say)
        lower, L = None, mesh.spec(*guess, breaks).L    # the block's width, as its mesh spans it
    else:
        lower, L, guess, t_locate = place_substrate(mesh, punch, P, s, 0.5 * E, nu, tilt, max_iter,
                                                    say)
    ends: tuple[float, ...] = ()
    if isinstance(pre, MeshPreset) and pre.refine > 1 and Q != 0 and guess is not None:
        t1 = time.perf_counter()
        coarse = make_substrate(PRESETS["locate"].spec(*guess, breaks))
        trial = TwoBodyModel(punch, P, s, E, nu, tilt, coarse, L, guess, max_iter, mu, sigma_bulk, gap=gap)
        if gap is not None:         # a worn profile: its own contact, not the punch's, places the mesh
            guess = trial.contact_ends()
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
                spec = with_nodes(spec, ends)
            lower = make_substrate(spec)
        t2 = time.perf_counter()
        t_mesh += t2 - t1
        assert lower is not None
        say(f"mesh: {lower.mesh.t.shape[1]} triangles a body ({t2 - t1:.1f} s)")
        model = TwoBodyModel(punch, P, s, E, nu, tilt, lower, L, guess, max_iter, mu, sigma_bulk, gap=gap)
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

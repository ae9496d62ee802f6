"""Fretting wear by the FEM: the two-body friction model marched through cycles (issue 39; docs/WEAR.md).

threepart.wear's ``method="fem"``. The model is :mod:`fem.friction`'s: two similar
elastic bodies (the substrate and its mirror image, ``E``, ``nu``) with Coulomb
friction, condensed onto their interface once (:func:`fem.interface.interface`; the
condensation is cached per mesh and material). Each state re-solves, on that interface,

* the normal contact under ``P`` at ``s`` of the worn gap ``g(x) + w(x)`` (``w`` the
  worn depth at the interface nodes, both bodies together), and
* the shear from 0 to ``Q_max`` in one load step (the tangential active set of
  :func:`fem.coulomb.tangential`: monotonic loading at a fixed pressure needs no
  sub-steps),

so that the slip at ``Q_max`` is the FE's own, not Ciavarella–Jäger's. Masing's rule
gives the travel per cycle, ``∮|ds| = 4 |slip(Q_max)|``; the depth grows by
``k' p ∮|ds|`` per cycle at the nodes (``k' = k`` for Archard, ``k f`` for the energy
law), by the jumps of :func:`threepart.fretting_wear.jump_size` with the nodes' spacing.

``WearResult.final`` is :func:`fem.fretting_cycle` on the last worn gap (``depth=``), on its
own quick mesh.

The mesh is a uniform candidate zone (:data:`MESH`: ``n`` elements across the unworn
contact, :data:`MARGIN` of it beyond each end, where the scar outgrows the contact),
not refined at the ends: the refined elements' spacing would set the jumps' stability
bound.

march -- the FEM's wear march (registered as method "fem")
MESH  -- the march's mesh preset
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from threepart.errors import InputError, InputTypeError, NoConvergenceError
from threepart.fretting_wear import MarchState, WearResult, march_depth, register_marcher
from threepart.problem.checks import positive, poisson
from threepart.problem.material import similar_pair
from threepart.problem.punch import Punch
from threepart.results import FrettingResult

from ._progress import Progress
from .mesh import MeshPreset
from .twobody import TwoBodyModel, two_body_model

__all__ = ["march", "MESH", "MARGIN"]

#: the candidate zone reaches this fraction of the unworn contact beyond each end
MARGIN = 0.2
#: the march's mesh: uniform over the candidate zone, W/100 a P2 element (two nodes)
MESH = MeshPreset(n=100, growth=0.1, L=200.0, refine=1.0, margin=MARGIN)
#: active-set iterations of each solve
MAX_ITER = 200


def _interpolated(x: np.ndarray, values: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """The gap at any point: ``values`` at the nodes ``x``, linear between them."""
    def gap(t: np.ndarray) -> np.ndarray:
        return np.interp(t, x, values)
    return gap


def _spacing(x: np.ndarray) -> np.ndarray:
    gaps = np.diff(x)
    return np.minimum(np.concatenate([gaps[:1], gaps]), np.concatenate([gaps, gaps[-1:]]))


def march(punch: Punch, P: float, s: float, Q_max: float, f: float, *, A: float, law: str, k: float,
          cycles: int, jump: int | None = None, tilt: str = "free", E: float | None = None,
          nu: float | None = None, mesh: MeshPreset = MESH) -> WearResult:
    """Fretting wear at constant ``P``, ``s`` with ``Q`` between ``±Q_max``: threepart.wear's FEM march.

    ``E`` and ``nu`` are the bodies' (both required); ``A`` must be theirs,
    ``4 (1 - nu^2)/E``. Input is otherwise checked by :func:`threepart.fretting_wear.wear`.

    Raises
    ------
    ValueError
        ``E`` or ``nu`` missing or out of range, or ``A`` not the pair's.
    NoConvergenceError, ContactZoneError
        The first state not solved (later ones end the march, ``info["stopped"]``).
    """
    if E is None or nu is None:
        raise InputError("`E` and `nu` are required by the FEM's wear march (two similar bodies)")
    E, nu = positive("E", E), poisson(nu)
    if not isinstance(mesh, MeshPreset):
        raise InputTypeError(f"`mesh` must be a fem MeshPreset (the march's uniform zone, fem.wear.MESH), "
                             f"not {type(mesh).__name__}")
    if not math.isclose(similar_pair(E, nu), A, rel_tol=1e-9):
        raise InputError(f"`A` = {A:.10g} must be the pair's 4 (1 - nu^2)/E = {similar_pair(E, nu):.10g}")
    t0 = time.perf_counter()
    law_factor = f if law == "energy" else 1.0
    say = Progress(None)
    first = two_body_model(punch, P, s, E, nu, tilt, mesh, MAX_ITER, f, Q_max, 0.0, say)
    x, weights = first.itf.x, first.itf.weights
    g = punch.profile(x)

    def solve(depth: np.ndarray, last: TwoBodyModel | None) -> MarchState:
        model = first if last is None else TwoBodyModel(      # a state's model shears once
            punch, P, s, E, nu, tilt, first.lower, first.L, last.contact_ends(), MAX_ITER, f,
            gap=_interpolated(x, g + depth), one_zone=False)   # its normal contact starts from the last state's
        st = model.step(Q_max, "loading", 1, 1.0)
        travel = np.where(st.fn > 0, 4.0 * np.abs(st.w - model.w0), 0.0)
        p = st.fn / weights
        return MarchState(rate=p * travel, travel=travel, work=f * float(np.sum(st.fn * travel)),
                          stick=model.stick_zone(st), contact=model.contact_ends(), alpha=model.normal.alpha,
                          pressure=p, solved=model)

    rec, stopped, _ = march_depth(solve, weights, _spacing(x), k=k, law_factor=law_factor, A=A, P=P,
                                  cycles=cycles, jump=jump, failures=(NoConvergenceError, ValueError, RuntimeError))
    last_depth = _interpolated(x, np.asarray(rec["depths"][-1]))

    def final() -> FrettingResult:
        """The fretting cycle on the last worn profile, on the friction model's own mesh (:func:`fem.fretting_cycle`)."""
        from .friction import fretting_cycle
        return fretting_cycle(punch, P, s, Q_max=Q_max, f=f, E=E, nu=nu, tilt=tilt, mesh="quick", depth=last_depth)

    return WearResult(punch=punch, P=P, s=s, Q_max=Q_max, f=f, A=A, law=law, k=k, x=x, method="fem",
                      final_cycle=final, **rec,
                      info={"time": time.perf_counter() - t0, "steps": len(rec["cycles"]) - 1,
                            "jump": "auto" if jump is None else jump, "points": x.size, "E": E, "nu": nu,
                            "stopped": stopped, "requested": cycles, "tilt": tilt})


register_marcher("fem", march, material=True)

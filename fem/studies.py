"""Mesh-convergence and domain-size studies of the FE model, on the one study driver.

Both run :func:`threepart.convergence.run_study`, which returns the shared
:class:`threepart.convergence.Study` and does the arithmetic (fitted orders
against a reference, the three-level order and Roache's GCI of the three
finest levels, Richardson estimates) by one rule for every method. The
quantities followed are :data:`QUANTITIES`; ``a`` and ``c`` are measured in
units of the contact width, ``alpha`` and the peaks relative to their
reference (absolute where it is 0). No closed form is called here.
"""
from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

from threepart.convergence import Study, run_study
from threepart.problem.punch import Punch

from ._boundary import boundary
from .mesh import MeshPreset
from .solve import FemResult, solve_normal
from threepart.errors import InputError

__all__ = ["convergence_study", "domain_study", "QUANTITIES"]

#: quantities followed by the studies
QUANTITIES = ("a", "c", "alpha", "p_left", "p_right")


def _values(res: FemResult) -> dict[str, float]:
    left, right = res.peaks()
    return {"a": res.a, "c": res.c, "alpha": res.alpha, "p_left": left.p, "p_right": right.p}


def _scales(ref: Mapping[str, float]) -> dict[str, float]:
    """``a``, ``c`` in units of ``W``; ``alpha`` and the peaks relative (absolute where 0)."""
    W = ref["a"] + ref["c"]
    return {q: W if q in ("a", "c") else (abs(ref[q]) or 1.0) for q in QUANTITIES}


def _level(punch: Punch, P: float, s: float, E: float, nu: float, tilt: str,
           pre: MeshPreset) -> tuple[float, dict[str, float], dict[str, Any]]:
    """One solve: its element size ``h``, the quantities and the mesh's metadata."""
    res = solve_normal(punch, P, s, E=E, nu=nu, tilt=tilt, mesh=pre)
    dg = res.diagnostics
    assert dg.h is not None
    return dg.h, _values(res), {"n": pre.n, "L": dg.L, "dofs": dg.dofs}


@boundary
def convergence_study(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                      tilt: str = "free", ns: Sequence[float] = (30, 60, 120, 240),
                      growth: float = 0.1, L: float = 200.0,
                      reference: Callable[[], dict[str, float]] | dict[str, float] | None = None
                      ) -> Study:
    """Solve on ``len(ns) >= 4`` meshes with ``n`` elements across W, coarse to fine.

    Parameters
    ----------
    punch, P, s, E, nu, tilt
        As for :func:`fem.solve_normal`.
    ns
        Elements across the contact width, increasing, at least four.
    growth, L
        Grading and block size (in contact widths), shared by all levels.
    reference
        Optional exact values of :data:`QUANTITIES` (or a callable giving them),
        e.g. from another solver; then ``errors`` and fitted ``orders`` are filled.

    Returns
    -------
    threepart.convergence.Study
        ``param = "h"``, ``sizes`` the element sizes along the contact, ``info``
        per level ``n``, ``L`` and ``dofs``; orders and GCI by the driver's rule.
    """
    ns = [float(n) for n in ns]
    if len(ns) < 4 or any(b <= a for a, b in zip(ns, ns[1:])):
        raise InputError(f"`ns` = {ns!r} must hold at least 4 increasing element counts")
    ref = reference() if callable(reference) else reference
    return run_study(lambda n: _level(punch, P, s, E, nu, tilt,
                                      MeshPreset(n=n, growth=growth, L=L)),
                     ns, param="h", reference=ref, scales=None if ref is None else _scales(ref),
                     method="fem", scheme=f"P2, growth {growth:g}, L = {L:g} W")


@boundary
def domain_study(punch: Punch, P: float, s: float = 0.0, *, E: float, nu: float,
                 tilt: str = "free", Ls: Sequence[float] = (12.5, 25, 50, 100, 200, 400),
                 n: float = 120, growth: float = 0.1) -> Study:
    """Solve with block sizes ``L`` (in contact widths) at fixed ``n`` and grading.

    The study's size is ``1/L`` (``param = "1/L"``: it falls as the block
    grows), and its reference the largest block: ``errors`` holds each
    quantity's change from it, relative for ``alpha`` and the peaks, in units
    of the contact width for ``a`` and ``c``.
    """
    Ls = [float(v) for v in Ls]
    if len(Ls) < 2 or any(b <= a for a, b in zip(Ls, Ls[1:])):
        raise InputError(f"`Ls` = {Ls!r} must hold at least 2 increasing block sizes")
    solved = {v: _level(punch, P, s, E, nu, tilt, MeshPreset(n=n, growth=growth, L=v))
              for v in Ls}
    last = solved[Ls[-1]][1]
    return run_study(lambda v: (1.0 / v, solved[v][1], solved[v][2]), Ls, param="1/L",
                     reference=last, scales=_scales(last), method="fem",
                     scheme=f"P2, n = {n:g}, growth {growth:g}")

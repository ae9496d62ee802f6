"""The CalculiX column of the verification run: one case's convergence in ``h`` and in the penalty ``K``.

Names
-----
calculix_result  -- one CalculiX run of a case (threepart.calculix) as a PointsResult, with its reference
calculix_studies -- its convergence in h and in the penalty K against the closed form
CALCULIX_CASE, SLOPE_SCALE, CALCULIX_N, CALCULIX_K, CALCULIX_K_MESH, CALCULIX_QUANTITIES -- the study's settings
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable

from threepart.results import Diagnostics, NormalResult

from .points import PointsResult, from_points

__all__ = ["calculix_result", "calculix_studies", "CALCULIX_CASE", "SLOPE_SCALE", "CALCULIX_N",
           "CALCULIX_K", "CALCULIX_K_MESH", "CALCULIX_QUANTITIES"]

#: the case of the CalculiX column: the symmetric flat rounded punch
CALCULIX_CASE = "caseA_sym"
#: its radii times this and P over it: the same contact [-a, c] and pressure shape, slopes and
#: pressures divided by it (half-plane theory is linear in them): small slopes for the FE model
SLOPE_SCALE = 20.0
#: elements across W at the contact of the mesh study, up to the deck's default (200); the
#: penalty study is run at the middle one (the column: about 30 s of CPU, measured)
CALCULIX_N = (50, 100, 200)
#: the penalty K in units of E/h of the penalty study (at W/h = CALCULIX_N[1]); the mesh study
#: runs at the deck's default, 200 E/h
CALCULIX_K = (20.0, 80.0, 320.0)
#: the penalty of the mesh study, in E/h (the deck's default)
CALCULIX_K_MESH = 200.0
#: what the CalculiX study follows (errors normalised as in the tolerance table)
CALCULIX_QUANTITIES = ("a", "c", "P", "p_left", "p_right", "p_interior_max")


def calculix_result(case: Any, n: float, penalty_factor: float, workdir: Path,
                    scale: float = SLOPE_SCALE) -> tuple[PointsResult, NormalResult]:
    """One CalculiX run of ``case`` scaled to small slopes: ``(result, closed-form reference)``.

    The pressure is CalculiX's nodal contact forces over the nodes' shares of
    the block's quadratic faces, freed of the vertex/midside alternation
    (:func:`threepart.calculix.surface_pressure`); the ends come from the gap
    (:func:`threepart.calculix.contact_edge`), ``P`` from the points.
    """
    from dataclasses import replace as _replace

    from threepart import calculix
    from threepart.problem.material import compliance
    from threepart.methods import solve

    case = case.resolved()
    E, nu = case.block_E, case.material[1]    # the rigid-punch block of the case's A
    settings = calculix.DeckSettings(n=n, penalty_factor=penalty_factor)
    A = compliance(E, nu, E * settings.stiffening, nu)
    punch = _replace(case.punch, R1=scale * case.punch.R1, R2=scale * case.punch.R2,
                     R=scale * case.punch.R)
    P, s = case.P / scale, float(case.s or 0.0)
    ref = solve(punch, P, s, A=A, tilt=case.tilt)
    assert isinstance(ref, NormalResult)
    model = calculix.build_model(punch, ref.a, ref.c, settings)
    stem = calculix.run_ccx(calculix.write_deck(model, P=P, s=s, E=E, nu=nu, settings=settings,
                                                title=f"{case.name}, radii x {scale:g}, P / {scale:g}"),
                            workdir, f"n{n:g}_K{penalty_factor:g}")
    sp = calculix.surface_pressure(model, stem)
    res = from_points(sp.x, sp.p, ref, ends=(sp.a, sp.c), method="calculix",
                      info={"penalty": settings.K(E, ref.a + ref.c)})
    return _replace(res, diagnostics=Diagnostics(h=model.h0, dofs=2 * model.n_nodes)), ref


def calculix_studies(say: Callable[[str], None] = print) -> list[Any]:
    """The CalculiX column of the verification run: convergence in h, then in K, on one case.

    Without ``ccx`` on the PATH, one empty study whose note says so.
    """
    import tempfile

    from threepart import calculix
    from threepart.problem.catalogue import get_case
    from threepart.convergence import Study, run_study

    from ..compare import normal_figures

    if not calculix.ccx_available():
        st = Study("h", method="calculix", case=CALCULIX_CASE)
        st.notes.append("`ccx` (CalculiX) is not on the PATH: the CalculiX column was not run "
                        "(Debian: apt-get install calculix-ccx)")
        return [st]
    case = get_case(CALCULIX_CASE)
    cache: dict[tuple[float, float], tuple[PointsResult, NormalResult]] = {}
    with tempfile.TemporaryDirectory(prefix="threepart-ccx-") as tmp:
        def level(n: float, k: float, param: str) -> tuple[float, dict[str, float], dict[str, Any],
                                                          dict[str, float]]:
            if (n, k) not in cache:
                cache[n, k] = calculix_result(case, n, k, Path(tmp))
            res, ref = cache[n, k]
            fig = normal_figures(ref, res)
            err = {q: fig[q][2] for q in CALCULIX_QUANTITIES}
            raw = {q: (fig[q][1] if q != "p_interior_max" else fig[q][2]) for q in CALCULIX_QUANTITIES}
            say(f"[study]   calculix W/h = {n:g}, K = {k:g} E/h: peak error {max(err['p_left'], err['p_right']):.3g}, "
                f"a {err['a']:.3g} W, c {err['c']:.3g} W")
            h = float(res.diagnostics.h or math.nan)
            E = float(case.block_E) if case.material else math.nan
            return (h if param == "h" else h / (k * E), raw, {"dofs": res.diagnostics.dofs}, err)

        mesh = run_study(lambda n: level(n, CALCULIX_K_MESH, "h"), list(CALCULIX_N), param="h",
                         error_only=("p_interior_max",), skip=(calculix.CcxError,),
                         method="calculix", case=CALCULIX_CASE, scheme=f"K = {CALCULIX_K_MESH:g} E/h")
        penalty = run_study(lambda k: level(CALCULIX_N[1], k, "1/K"), list(CALCULIX_K), param="1/K",
                            error_only=("p_interior_max",), skip=(calculix.CcxError,),
                            method="calculix", case=CALCULIX_CASE, scheme=f"W/h = {CALCULIX_N[1]}")
    for st in (mesh, penalty):
        st.notes.append(f"{CALCULIX_CASE} with the radii x {SLOPE_SCALE:g} and P / {SLOPE_SCALE:g} "
                        "(the same contact, slopes / 20); punch 1000 x stiffer than the block (in A); "
                        "pressure = the nodal contact forces -2 CELS/COPEN over the nodes' shares of the "
                        "quadratic faces, vertex/midside alternation fitted out; a, c from the gap")
    return [mesh, penalty]

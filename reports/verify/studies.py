"""Convergence studies: SIE in the number of nodes n, FEM in the mesh size h (normal and partial slip).

Both are measured against the closed form, so they live in :mod:`reports`.
Each study returns a :class:`Study` of plain numbers: the errors per level, the
observed orders fitted as ``np.polyfit(np.log(h), np.log(err), 1)``, and, for
the FEM, Roache's grid-convergence index (GCI) of the three finest levels; the
tools are those of :mod:`threepart.convergence`.
"""
from __future__ import annotations

import math
from typing import Any, Callable, Sequence

from threepart import registry
from threepart.problem.catalogue import Case
from threepart.registry import REFERENCE
from threepart.convergence import Study, fitted_order, run_study

from .runs import Mode, solve_normal
from ..compare import normal_figures, slip_figures
from .. import solvers
from threepart.errors import InputError

__all__ = ["Study", "sie_study", "fem_study", "fem_slip_study", "fem_step_study",
           "STUDY_QUANTITIES", "SLIP_STUDY_QUANTITIES", "STEP_STATES"]

#: figures followed through a study (errors normalised as in threepart.tolerances)
STUDY_QUANTITIES = ("a", "c", "alpha", "p_left", "p_right", "p_interior_max")
#: figures followed through a partial-slip study
SLIP_STUDY_QUANTITIES = ("a", "c", "alpha", "d", "e", "q_interior_max")
#: states per branch of the fretting load-step study (the step halves from one to the next)
STEP_STATES = (6, 11, 21, 41)
#: quantities that are themselves a field error (their "value" is the error, no Richardson step)
_FIELD_ERRORS = ("p_interior_max", "q_interior_max")


def _figures(ref: Any, res: Any, quantities: Sequence[str]) -> tuple[dict[str, float], dict[str, float]]:
    """Obtained values and normalised errors of ``quantities`` (as :func:`compare`)."""
    figures = normal_figures(getattr(ref, "normal", ref), getattr(res, "normal", res))
    if "d" in quantities:
        figures.update(slip_figures(ref, res))
    raw = {q: figures[q][1] for q in quantities}
    err = {q: figures[q][2] for q in quantities}
    for q in _FIELD_ERRORS:
        if q in raw:
            raw[q] = err[q]
    return raw, err


def _say(progress: Callable[[str], None] | None, method: str, param: str,
         where: str) -> Callable[[float, Any, float], None] | None:
    """The driver's per-level callback as one progress line of the verification run."""
    if progress is None:
        return None

    def line(size: float, level: Any, seconds: float) -> None:
        at = f"{where} {level}" if where.endswith("=") else where
        progress(f"{method} {param} = {size:.4g} ({at}): {seconds:.2f} s")

    return line


def _run(method: str, case: Case, labels: Sequence[str], solver: Callable[[Case, str], Any],
         param_of: Callable[[Any, str], float],
         progress: Callable[[str], None] | None, param_label: str = "level",
         quantities: Sequence[str] = STUDY_QUANTITIES, scheme: str = "") -> Study:
    """A study of ``method`` against the closed form on the one driver (:func:`run_study`).

    The errors are normalised by the tolerance table's units (:func:`compare`'s
    figures); a level that fails is a note, not a crash. The parameter is the
    method's :attr:`threepart.registry.Method.study` (``"n"``, ``"h"``).
    """
    param = registry.get(method).study or "level"
    case = case.resolved()
    ref = solve_normal(case, REFERENCE, Mode("study", None, "quick", (), ()))
    if "d" in quantities:
        ref = solvers.slip(REFERENCE, case, ref)

    def level(lab: str) -> tuple[float, dict[str, float], dict[str, Any], dict[str, float]]:
        res = solver(case, lab)
        raw, err = _figures(ref, res, quantities)
        return param_of(res, lab), raw, {}, err

    return run_study(level, list(labels), param=param, reference=_figures(ref, ref, quantities)[0],
                     error_only=_FIELD_ERRORS, skip=(Exception,),
                     progress=_say(progress, method, param, param_label),
                     method=method, case=case.name, scheme=scheme)


def sie_study(case: Case, ns: Sequence[int], scheme: str | None = None,
              progress: Callable[[str], None] | None = None) -> Study:
    """SIE errors against the closed form for each ``n`` in ``ns``.

    ``scheme`` is passed to ``sie.solve_normal`` (``"plain"`` collocation or
    the kink-aware ``"projected"``; None: the solver's default).
    """
    options = {} if scheme is None else {"scheme": scheme}

    def solver(c: Case, lab: str) -> Any:
        return solvers.normal("sie", c, n=int(lab), **options)

    return _run("sie", case, [str(n) for n in ns], solver,
                lambda res, lab: float(res.diagnostics.n or int(lab)),
                progress, "scheme " + (scheme or "default"), scheme=scheme or "default")


def fem_study(case: Case, ns: Sequence[int],
              progress: Callable[[str], None] | None = None) -> Study:
    """FEM errors against the closed form for ``n`` elements across the contact (coarse to fine).

    The meshes are members of the default preset's self-similar family
    (:meth:`fem.MeshPreset.scaled`): every element size, the grading included,
    scales with ``1/n`` at fixed block size and end refinement.
    """
    def solver(c: Case, lab: str) -> Any:
        return solve_normal(c, "fem", Mode("study", None, _family(int(lab)), (), ()))

    return _run("fem", case, [str(n) for n in ns], solver, _h_of, progress, "W/h =")


def fem_slip_study(case: Case, ns: Sequence[int],
                   progress: Callable[[str], None] | None = None) -> Study:
    """Two-body friction FEM errors (contact, stick zone, shear) against the closed form, by ``n``.

    ``case`` is a partial-slip case; the meshes are those of :func:`fem_study`.
    """
    def solver(c: Case, lab: str) -> Any:
        return solvers.slip("fem", c, None, mesh=_family(int(lab)))

    return _run("fem", case, [str(n) for n in ns], solver, _h_of, progress, "W/h =",
                SLIP_STUDY_QUANTITIES)


def _family(n: int) -> Any:
    """The member of the default mesh's self-similar family with ``n`` elements across W."""
    from threepart.fem.mesh import PRESETS

    return PRESETS["default"].scaled(n / PRESETS["default"].n)


def _h_of(res: Any, lab: str) -> float:
    """Element size along the contact of an FE result (normal or partial slip)."""
    h = res.diagnostics.h
    if h is None:   # a slip result's element size is its normal result's
        h = getattr(res, "normal", res).diagnostics.h
    if h is None:
        raise InputError(f"the FE result of level {lab} carries no element size in its diagnostics")
    return float(h)


def fem_step_study(case: Case, reference: Any, mesh: Any = "quick",
                   states: Sequence[int] = STEP_STATES,
                   progress: Callable[[str], None] | None = None) -> Study:
    """The FE energy per fretting cycle as the load step ``ΔQ = 2 Q_max / (states - 1)`` shrinks.

    ``case`` is a fretting case and ``reference`` the closed form's cycle. The
    errors against it level off at the mesh's own error, so the order is
    also given reference-free, from the three finest steps (Celik et al.
    2008), where the energies converge from one side.
    """
    case = case.resolved()
    Q = case.shear_load[0]
    E_ref = float(reference.energy)

    def level(k: int) -> tuple[float, dict[str, float], dict[str, Any], dict[str, float]]:
        res = solvers.fretting("fem", case, None, k, mesh=mesh)
        if progress:
            progress(f"fem {k} states per branch: energy {res.energy:.8g}")
        return 2 * Q / (k - 1), {"energy": res.energy}, {}, {}

    # reference-free: the energies' own three-level order, where they converge from one side
    st = run_study(level, list(states), param="dQ", method="fem", case=case.name)
    st.reference = {"energy": E_ref}
    st.errors = {"energy": [abs(e / E_ref - 1) for e in st.values["energy"]]}
    if math.isfinite(st.orders["energy"]):
        fit = fitted_order(st.h, st.errors["energy"])[0]
        st.notes.append(f"energy: order {st.orders['energy']:.2f} from the three finest steps "
                        "(reference-free); against the closed form the error includes the mesh's "
                        f"and fits order {fit:.2f}")
    else:
        st.notes.append("energy: the energies do not converge monotonically in the load step; "
                        "no order is given")
    return st

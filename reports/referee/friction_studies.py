"""The friction referee columns of the verification run: CalculiX and GetFEM against the closed form.

Each outside code that carries Coulomb friction is one row of :data:`REFEREES`
(its name, whether it is installed, its partial-slip and fretting runs, and how to
install it); a new code is one row. Every column solves the same problems, two
similar elastic bodies scaled to small slopes as the CalculiX normal column
(:data:`~.studies.SLOPE_SCALE`):

- Hertz's partial slip at ``Q = 0.4 f P`` against Mindlin's ``c/a = sqrt(1 - Q/fP)``
  (the closed form), at each code's own levels of elements across the contact width W
  (:attr:`Referee.levels`; GetFEM's P2 run at 128 takes ten minutes here):
  the stick zone ``d``, ``e``, the shear, ``∫q = Q`` (:func:`slip_from_points`,
  judged by the verification run's own comparison);
- with ``fretting=True`` (``threepart verify --full``), the same punch's fretting cycle
  ``0 -> Q_max -> -Q_max -> Q_max`` at the finest level: its energy per cycle against
  the closed form's (Masing).

Names
-----
Referee          -- one outside code: its runs and how to tell it is there
REFEREES         -- the table of outside codes with friction, by name
register_referee -- add one
friction_problem -- the scaled Hertz pair the columns solve, with its closed-form references
friction_studies -- every installed code's column (a Study in h each, and the fretting energy)
FRICTION_QUANTITIES, FRICTION_RATIO, FRICTION_F, FRICTION_METHOD -- the columns' settings
"""
from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from threepart.tolerances import tolerance

from .friction import slip_from_points
from .studies import SLOPE_SCALE

__all__ = ["Referee", "REFEREES", "register_referee", "friction_problem", "friction_studies",
           "FRICTION_METHOD", "FRICTION_QUANTITIES", "FRICTION_RATIO", "FRICTION_F"]

#: the suffix of a friction column's method name in its Study (``"calculix-friction"``)
FRICTION_METHOD = "-friction"
#: what the columns follow, as the comparison names them (errors in the tolerance table's units)
FRICTION_QUANTITIES = ("d", "e", "q_interior_max", "q_integral")
#: the shear of the partial slip and the fretting amplitude, of f P; and the coefficient of friction
FRICTION_RATIO = 0.4
FRICTION_F = 0.5


@dataclass(frozen=True)
class Referee:
    """One outside code with Coulomb friction.

    ``partial_slip(punch, P, s, Q, f, E, nu, *, n, tilt, workdir)`` returns an object with
    the surface points ``x, p, q`` and ``info`` (``h``); ``fretting(punch, P, s, Q_max, f,
    E, nu, *, n, tilt, workdir)`` one whose ``energy`` is the energy per cycle (or
    ``info["energy"]``); ``available()`` says whether the code is installed,
    ``missing`` how to install it, ``errors`` what a failed run raises, ``levels`` the
    elements across W of its mesh study, coarse to fine.
    """

    name: str
    available: Callable[[], bool]
    partial_slip: Callable[..., Any]
    fretting: Callable[..., Any]
    missing: str
    errors: tuple[type[BaseException], ...]
    levels: tuple[float, ...]


#: the outside codes with friction, by name (:func:`register_referee`)
REFEREES: dict[str, Referee] = {}


def register_referee(referee: Referee) -> None:
    """Add an outside code to :data:`REFEREES` (by name)."""
    REFEREES[referee.name] = referee


def _calculix() -> Referee:
    from threepart import calculix
    from threepart.calculix import friction
    from threepart.errors import CcxError

    def fretting(*args: Any, **kwargs: Any) -> Any:
        states = friction.fretting_cycle(*args, **kwargs)
        return states[-1]

    return Referee("calculix", calculix.ccx_available, friction.partial_slip, fretting,
                   "`ccx` (CalculiX) is not on the PATH (Debian: apt-get install calculix-ccx)",
                   (CcxError,), (50.0, 100.0))


def _getfem() -> Referee:
    from threepart import getfem
    from threepart.errors import GetfemError

    return Referee("getfem", getfem.getfem_available, getfem.partial_slip, getfem.fretting_cycle,
                   "no Python interpreter imports getfem (Debian: apt-get install python3-getfem; "
                   "or set THREEPART_GETFEM_PYTHON)", (GetfemError,), (32.0, 64.0))


def _builtin() -> None:
    for make in (_calculix, _getfem):
        ref = make()
        REFEREES.setdefault(ref.name, ref)


def friction_problem() -> dict[str, Any]:
    """The scaled Hertz pair of the columns and its closed-form references (partial slip, fretting).

    Two steel bodies (``E`` = 210 GPa, ``nu`` = 0.3, ``A = 4 (1 - nu^2)/E``), radius
    ``10 SLOPE_SCALE`` mm, ``P = 400 / SLOPE_SCALE`` N/mm: Hertz's a = 0.21 mm with the
    slopes divided by :data:`SLOPE_SCALE`; ``Q = FRICTION_RATIO f P``.
    """
    from threepart.material import E_STEEL, NU, similar_pair
    from threepart.methods import fretting, solve
    from threepart.punch import Punch

    R, P = 10.0 * SLOPE_SCALE, 400.0 / SLOPE_SCALE
    punch = Punch(R1=R, R2=R, b=0.0)
    A = similar_pair(E_STEEL, NU)
    Q = FRICTION_RATIO * FRICTION_F * P
    slip = solve(punch, P, 0.0, A=A, Q=Q, f=FRICTION_F, method="closedform")
    cycle = fretting(punch, P, 0.0, A=A, Q_max=Q, f=FRICTION_F, method="closedform")
    return {"punch": punch, "P": P, "s": 0.0, "Q": Q, "f": FRICTION_F, "E": E_STEEL, "nu": NU,
            "A": A, "slip": slip, "cycle": cycle,
            "title": f"Hertz pair, R = {R:g} mm, P = {P:g} N/mm, Q = {FRICTION_RATIO:g} f P"}


def friction_studies(say: Callable[[str], None] = print, codes: tuple[str, ...] | None = None, *,
                     fretting: bool = False, levels: tuple[float, ...] | None = None) -> list[Any]:
    """Every installed outside code's friction column: a Study in h of the partial slip each, and
    with ``fretting`` the energy per cycle at its finest level in its notes.

    ``codes`` picks rows of :data:`REFEREES` (default: all), ``levels`` overrides their levels.

    A code that is not installed gives one empty study whose note says so.
    """
    from threepart.convergence import Study, run_study

    from ..compare import compare

    _builtin()
    problem = friction_problem()
    ref, cycle = problem["slip"], problem["cycle"]
    W = ref.a + ref.c
    out = []
    for name in codes if codes is not None else tuple(REFEREES):
        code = REFEREES[name]
        case = f"{problem['title']} ({name})"
        if not code.available():
            st = Study("h", method=name + FRICTION_METHOD, case=case)
            st.notes.append(f"{code.missing}: the {name} friction column was not run")
            out.append(st)
            continue
        with tempfile.TemporaryDirectory(prefix=f"threepart-{name}-friction-") as tmp:
            def level(n: float) -> tuple[float, dict[str, float], dict[str, Any], dict[str, float]]:
                workdir = Path(tmp) / f"slip_n{n:g}"
                workdir.mkdir()
                run = code.partial_slip(problem["punch"], problem["P"], 0.0, problem["Q"], problem["f"],
                                        problem["E"], problem["nu"], n=n, tilt="suppressed", workdir=workdir)
                res = slip_from_points(run.x, run.p, run.q, ref, method=name)
                checks = {c.quantity: c for c in compare(ref, res, "referee", stresses=False)}
                err = {q: checks[q].error for q in FRICTION_QUANTITIES}
                raw = {"d": res.d, "e": res.e, "q_interior_max": err["q_interior_max"],
                       "q_integral": checks["q_integral"].obtained}
                h = float(run.info.get("h", W / n))
                say(f"[study]   {name} W/h = {n:g}: stick zone d {err['d']:.3g} of d, e {err['e']:.3g}, "
                    f"shear {err['q_interior_max']:.3g} of its peak, ∫q {err['q_integral']:.3g}")
                return h, raw, {"seconds": run.info.get("time")}, err

            st = run_study(level, list(levels or code.levels), param="h", error_only=("q_interior_max",),
                           skip=code.errors, require_monotone=False, method=name + FRICTION_METHOD, case=case,
                           scheme="two similar elastic bodies, Coulomb friction")
            if fretting:
                st.notes.append(_energy_note(code, problem, cycle, (levels or code.levels)[-1],
                                             Path(tmp), say))
        out.append(st)
    return out


def _energy_note(code: Referee, problem: dict[str, Any], cycle: Any, n: float, tmp: Path,
                 say: Callable[[str], None]) -> str:
    """The fretting energy per cycle of ``code`` at ``n`` elements across W against the closed form's, as a note."""
    limit = tolerance("referee", "energy").limit
    workdir = tmp / f"fretting_n{n:g}"
    workdir.mkdir()
    try:
        run = code.fretting(problem["punch"], problem["P"], 0.0, problem["Q"], problem["f"],
                            problem["E"], problem["nu"], n=n, tilt="suppressed", workdir=workdir)
    except code.errors as exc:
        return f"the fretting cycle at W/h = {n:g} failed: {exc}"
    energy = float(getattr(run, "energy", None) or run.info["energy"])
    error = abs(energy - cycle.energy) / cycle.energy
    verdict = "within" if error <= limit else "OUTSIDE"
    say(f"[study]   {code.name} fretting energy per cycle at W/h = {n:g}: {energy:.6g} against "
        f"{cycle.energy:.6g} (error {error:.3g})")
    return (f"fretting cycle 0 -> Q -> -Q -> Q at W/h = {n:g}: energy per cycle {energy:.6g} N·mm/mm "
            f"against the closed form's {cycle.energy:.6g}, error {error:.3g}, {verdict} the limit "
            f"{limit:g}" + ("" if math.isfinite(error) else " (not finite)"))

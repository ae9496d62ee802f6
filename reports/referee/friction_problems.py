"""The problems of the friction referee columns: one table, a problem one row.

Every problem is two similar steel bodies scaled to small slopes as the CalculiX normal
column (radii times :data:`~.studies.SLOPE_SCALE`, loads and stresses over it), with its
closed-form reference built only when a column runs it.

Names
-----
FrictionProblem   -- one row: its name, builder, kind, the mode it runs in, its codes, what it needs
FRICTION_PROBLEMS -- the table, in report order
pair_problem      -- one problem's dict: two similar bodies at Q = FRICTION_RATIO f P, its references
hertz             -- the Hertz pair at Q = 0.4 f P against Mindlin (c/a = sqrt(1 - Q/fP))
slip_q04          -- slip_Q0.4 (the three-part punch, tilt free) against the closed form
slip_q04_bulk     -- the same with a bulk tension (needs ``partial_slip(..., sigma_bulk=)``)
fretting_q04      -- fretting_Q0.4: its energy per cycle and its stick zone at Q_max
flight            -- a flight cycle of slip_Q0.4's punch: the steady state's energy (needs ``load_history``)
FRICTION_RATIO, FRICTION_F, SIGMA_BULK -- the columns' loads
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from .studies import SLOPE_SCALE

__all__ = ["FrictionProblem", "FRICTION_PROBLEMS", "pair_problem", "hertz", "slip_q04", "slip_q04_bulk", "fretting_q04",
           "flight", "FRICTION_RATIO", "FRICTION_F", "SIGMA_BULK"]

#: the shear of the partial slip and the fretting amplitude, of f P; and the coefficient of friction
FRICTION_RATIO = 0.4
FRICTION_F = 0.5
#: the bulk tension of slip_Q0.4's bulk-stress problem at the scaled loads (MPa): about a tenth
#: of its mean pressure (the catalogue's fan-blade case: 300 MPa at its own loads)
SIGMA_BULK = 30.0


@dataclass(frozen=True)
class FrictionProblem:
    """One problem of the friction columns.

    ``build()`` returns the problem's dict: ``punch, P, s, Q, f, E, nu, A, tilt,
    sigma_bulk``, the closed form's partial slip at ``Q`` (``slip``), for a cycle its
    fretting cycle (``cycle``), for a flight cycle its ``states`` and steady state
    (``steady``), and a ``title``. ``kind`` is ``"slip"``, ``"fretting"`` or
    ``"flight"``; ``mode`` the verification mode it first runs in (``"default"`` or
    ``"full"``); ``codes`` the referees that run it (empty: all); ``needs`` the keyword
    of ``partial_slip`` (``"sigma_bulk"``) or the referee's call (``"load_history"``)
    it needs, which a code without it marks "not yet".
    """

    name: str
    build: Callable[[], dict[str, Any]]
    kind: str
    mode: str
    codes: tuple[str, ...] = ()
    needs: str = ""


def pair_problem(punch: Any, P: float, s: float, *, tilt: str, title: str, sigma_bulk: float = 0.0,
                 fretting: bool = False, E: float | None = None, nu: float | None = None,
                 method: str = "closedform") -> dict[str, Any]:
    """A problem of two similar bodies (default: steel) at ``Q = FRICTION_RATIO f P`` with its
    partial slip by ``method`` (the closed form; ``"auto"``: the SIE where it refuses) and, with
    ``fretting``, its fretting cycle: the dict a column runs (:class:`FrictionProblem`)."""
    from threepart.problem.material import E_STEEL, NU, similar_pair
    from threepart.methods import fretting as cycle
    from threepart.methods import solve

    E, nu = (E_STEEL if E is None else E), (NU if nu is None else nu)
    A = similar_pair(E, nu)
    Q = FRICTION_RATIO * FRICTION_F * P
    slip = solve(punch, P, s, A=A, Q=Q, f=FRICTION_F, method=method, tilt=tilt,
                 **({"sigma_bulk": sigma_bulk} if sigma_bulk else {}))
    out = {"punch": punch, "P": P, "s": s, "Q": Q, "f": FRICTION_F, "E": E, "nu": nu, "A": A,
           "tilt": tilt, "sigma_bulk": sigma_bulk, "slip": slip, "title": title}
    if fretting:
        out["cycle"] = cycle(punch, P, s, A=A, Q_max=Q, f=FRICTION_F, method=method, tilt=tilt)
    return out


def hertz() -> dict[str, Any]:
    """The Hertz pair: radius ``10 SLOPE_SCALE`` mm, ``P = 400 / SLOPE_SCALE`` N/mm (a = 0.21 mm
    unscaled), ``Q = FRICTION_RATIO f P``, the tilt suppressed (symmetric), with its fretting cycle."""
    from threepart.problem.punch import Punch

    R, P = 10.0 * SLOPE_SCALE, 400.0 / SLOPE_SCALE
    return pair_problem(Punch(R1=R, R2=R, b=0.0), P, 0.0, tilt="suppressed", fretting=True,
                 title=f"Hertz pair, R = {R:g} mm, P = {P:g} N/mm, Q = {FRICTION_RATIO:g} f P")


def _scaled(name: str) -> tuple[Any, float, float]:
    """The catalogue case ``name``'s punch with its radii times SLOPE_SCALE, ``P`` over it, ``s``."""
    from dataclasses import replace

    from threepart.problem.catalogue import get_case

    case = get_case(name).resolved()
    p = case.punch
    return (replace(p, R1=SLOPE_SCALE * p.R1, R2=SLOPE_SCALE * p.R2, R=SLOPE_SCALE * p.R),
            case.P / SLOPE_SCALE, float(case.s or 0.0))


def slip_q04() -> dict[str, Any]:
    """``slip_Q0.4`` x SLOPE_SCALE of two similar steel bodies, tilt free."""
    punch, P, s = _scaled("slip_Q0.4")
    return pair_problem(punch, P, s, tilt="free", title=f"slip_Q0.4 x {SLOPE_SCALE:g}, P = {P:g} N/mm, s = {s:g} mm")


def slip_q04_bulk() -> dict[str, Any]:
    """``slip_Q0.4`` x SLOPE_SCALE with the bulk tension :data:`SIGMA_BULK` rising with ``Q``."""
    punch, P, s = _scaled("slip_Q0.4")
    return pair_problem(punch, P, s, tilt="free", sigma_bulk=SIGMA_BULK,
                 title=f"slip_Q0.4 x {SLOPE_SCALE:g} with a bulk tension of {SIGMA_BULK:g} MPa")


def fretting_q04() -> dict[str, Any]:
    """``fretting_Q0.4`` x SLOPE_SCALE: 0 -> Q_max -> -Q_max -> Q_max, Q_max = FRICTION_RATIO f P."""
    punch, P, s = _scaled("fretting_Q0.4")
    return pair_problem(punch, P, s, tilt="free", fretting=True,
                 title=f"fretting_Q0.4 x {SLOPE_SCALE:g}, Q_max = {FRICTION_RATIO:g} f P")


def flight() -> dict[str, Any]:
    """A flight cycle of ``slip_Q0.4`` x SLOPE_SCALE's punch (two similar steel bodies, tilt free), whose
    slip zones the codes' meshes resolve: between ``(0.9 P, s, -0.3 f P, -30 MPa)`` and ``(P, s,
    0.4 f P, 40 MPa)``, in phase; the closed form's steady state (docs/STEADY_STATE.md) is the reference.
    (``fan_blade_flight_cycle`` x 20 slips over 0.8 % and 0.2 % of W, under one element at W/h = 100.)"""
    from threepart.problem.material import E_STEEL, NU, similar_pair
    from threepart.methods import solve, steady_state

    punch, P, s = _scaled("slip_Q0.4")
    f = FRICTION_F
    states = ((0.9 * P, s, -0.3 * f * P, -30.0), (P, s, FRICTION_RATIO * f * P, 40.0))
    A = similar_pair(E_STEEL, NU)
    steady = steady_state(punch, states, f, A=A, method="auto")
    normal = solve(punch, states[0][0], states[0][1], A=A, method="auto")
    return {"punch": punch, "states": states, "f": f, "E": E_STEEL, "nu": NU, "A": A, "tilt": "free",
            "steady": steady, "W": normal.a + normal.c,
            "title": f"a flight cycle of slip_Q0.4 x {SLOPE_SCALE:g} (steady state)"}


#: the problems of the columns, in report order (a new problem is one row)
FRICTION_PROBLEMS: tuple[FrictionProblem, ...] = (
    FrictionProblem("hertz", hertz, "slip", "default"),
    FrictionProblem("slip_Q0.4", slip_q04, "slip", "default"),
    FrictionProblem("slip_Q0.4_bulk", slip_q04_bulk, "slip", "full", needs="sigma_bulk"),
    FrictionProblem("fretting_Q0.4", fretting_q04, "fretting", "full"),
    FrictionProblem("flight", flight, "flight", "full", needs="load_history"),
)

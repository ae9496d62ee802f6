"""CalculiX with Coulomb friction: partial slip and the fretting cycle of two similar bodies (issue 38).

The punch is an elastic body of the block's material (Dundurs ``beta = 0``), so the normal
and the tangential problems uncouple as in the closed form (a rigid or a stiffened punch
couples them: ``beta`` about 0.29 at ``nu = 0.3``). The deck loads ``P`` at ``x = s`` in a
first ``*STEP``, then the shear force ``Q`` on the punch's top in further steps, each ramped
in equal increments: partial slip ``0 -> Q``, or the fretting cycle ``0 -> Q -> -Q -> Q``.

Names
-----
SLOPE_FACTOR     -- the default stick slope ``lambda`` in units of ``E / h``
PENALTY_FACTOR   -- the default normal penalty ``K`` in units of ``E / h`` (two similar bodies)
friction_deck    -- the deck of a model under ``P`` at ``s`` and a history of ``Q`` (``*FRICTION``),
                    with the block's bulk stress, or a load history of states ``(P, s, Q, sigma_bulk)``
side_weights     -- the block's sides' nodal forces per unit bulk stress
FrictionResult   -- one state's ``x``, ``p``, ``q``, the stick zone, ``∫p``, ``∫q`` and the run's info
partial_slip     -- mesh, write, run and read one partial-slip problem (``P``, ``s``, ``Q``, ``f``)
fretting_cycle   -- the same for the cycle ``0 -> Q -> -Q -> Q``: every state, the energy per cycle
read_frd_states  -- every recorded increment of an ``.frd`` (step, time, blocks)
contact_traction -- ``(x, p, q)`` along the block's face from one increment (surface to surface)
stick_ends       -- the stick zone's ends from ``1 - |q| / (f p)`` at the nodes
control_history  -- the punch's control nodes' displacements at each increment (``.dat``)
cycle_energy     -- the energy per cycle, ``-∮ u·dF`` of the punch's loads (Simpson's rule)
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from ..problem.checks import finite, positive
from .deck import (CONVENTIONS, DeckSettings, deck_head, lid_nodes, boundary_text, elements_text,
                   material_text, nodes_text, nset_text, surface_text)
from threepart.errors import InputError
from threepart.results.fields import stick_ends
from threepart.textfile import finite_row

if TYPE_CHECKING:   # pragma: no cover
    from ..problem.punch import Punch
    from .mesh import Model

__all__ = ["SLOPE_FACTOR", "PENALTY_FACTOR", "friction_deck", "side_weights", "FrictionResult", "partial_slip",
           "fretting_cycle", "read_frd_states", "contact_traction", "stick_ends", "control_history",
           "cycle_energy"]

#: the stick slope lambda (shear stress per tangential slip) in units of E/h: as stiff as the
#: normal penalty (at 2 E/h the normal step of slip_Q0.4 did not converge at W/h = 50; a softer
#: slope lets the stick zone creep q/lambda and moves its ends, docs/CALCULIX.md)
SLOPE_FACTOR = 20.0
#: the normal penalty K in units of E/h for two similar bodies (the validity map's referee's
#: setting: 200 E/h did not settle in one increment on this pair, docs/CALCULIX.md)
PENALTY_FACTOR = 20.0

FRICTION_CONVENTIONS = """\
** Friction (threepart's friction deck, issue 38): Coulomb, *FRICTION mu = f and the stick
**   slope lambda (shear stress per unit tangential slip, MPa/mm) below. A stick node carries
**   q = lambda * slip: too soft a slope lets the stick zone creep by q/lambda, which shrinks
**   the shear's peak at the stick zone's ends and moves them; check that a stiffer lambda
**   changes nothing you use.
** Two similar bodies: the punch (PUNCH) is elastic with the block's E and nu (Dundurs beta =
**   0), so the normal load does not cause shear, nor the shear pressure; a rigid or stiffened
**   punch couples them (beta about 0.29 at nu = 0.3) and Cattaneo-Mindlin does not hold.
** Steps: 1 the normal load P at x = s; then Q, the horizontal force on the punch's top (every
**   top node's u_x tied to the left corner's, which nothing else holds: the contact's stick
**   fixes the punch in x), ramped in equal increments per step to each target below. With
**   free tilt the corners' vertical forces are shifted so that P and Q act at (s, 0): the
**   moment of Q about the surface (Q times the top's height) is balanced; with the tilt
**   suppressed the guided lid reacts it. The punch exerts the shear on the block along +x
**   for Q > 0.
** States: the steps' targets (P, s, Q, sigma_bulk) are listed above; within a step the corners'
**   forces, Q and the sides' forces move linearly from the last target to the next.
** Contact: SURFACE TO SURFACE penalty (PRESSURE-OVERCLOSURE=LINEAR, stiffness K below): on
**   these quadratic faces ccx's node-to-surface friction cycled between two stick/slip states
**   and did not converge; surface to surface converged in 7 to 10 iterations an increment.
** Output: *CONTACT FILE CDIS, CSTR (CPRESS, CSHEAR1, CSHEAR2), CELS at every increment, at the
**   block's (slave) nodes: p = CPRESS, q = -CSHEAR1 (ccx's first tangent of the block's face
**   points along -x), the shear the punch exerts on the block along +x (threepart.readers.read
**   returns x, p, q from this .frd).
"""

BULK_CONVENTIONS = """\
** Bulk stress: a tension sigma_bulk (MPa) along x in the block (the substrate) only, as the
**   sides' consistent nodal forces (NSIDES: -sigma on the left side, +sigma on the right, per
**   unit length of side), rising with Q in proportion (the closed form's load path: P first,
**   then Q and sigma_bulk together); the block's base on rollers (y held), one base node held
**   in x, so that the bulk strain is free. The punch carries none.
"""

# --------------------------------------------------------------------------- the deck
#: one state of a friction deck's shear steps: ``(P, s, Q, sigma_bulk)``
State = tuple[float, float, float, float]


def friction_deck(model: Model, *, P: float | None = None, s: float | None = None, E: float, nu: float,
                  f: float, Q: Sequence[float] = (), increments: int = 8,
                  settings: DeckSettings | None = None, slope: float | None = None,
                  descent: float | None = None, title: str = "", sigma_bulk: float = 0.0,
                  history: Any = None) -> str:
    """The CalculiX deck of ``model`` under ``P`` at ``x = s``, then the shear force history ``Q``.

    Parameters
    ----------
    model
        A whole model (:func:`threepart.calculix.build_model`), meshed with ``pair=True``.
    P, s
        The normal load (per unit thickness) and its line of action, held from step 1 on
        (with ``history``: leave them out, or give its first state's).
    E, nu
        The modulus and Poisson's ratio of both bodies (two similar bodies).
    f
        The coefficient of friction (``*FRICTION``'s ``mu``).
    Q
        The targets of the shear force, one ``*STEP`` each after the normal step:
        ``[Q]`` partial slip, ``[Q, -Q, Q]`` the fretting cycle; each ``|Q| < f P``.
    increments
        Equal increments per shear step (ccx may cut one that does not converge).
    settings
        Mesh and normal penalty (default: ``pair=True``, ``K = PENALTY_FACTOR E/h``).
    slope
        The stick slope ``lambda`` (MPa/mm); default ``SLOPE_FACTOR E / h``.
    descent
        Instead of the force ``P``, the punch's top is lowered by ``descent`` in step 1 and
        held there (``P`` is then the base's reaction, an outcome; with
        ``settings.tilt = "suppressed"`` only). A face that first touches at one point
        (Hertz) does not start under a force in ccx: no contact element closes in its first
        iterations and the punch, held by contact alone, is free.
    sigma_bulk
        The block's bulk stress ``sigma_xx`` (tension positive) at the first target ``Q[0]``,
        rising with ``Q`` in proportion (``sigma_bulk Q_k / Q[0]`` at target ``k``), as the
        closed form's (docs/BULK_STRESS.md): a traction on the block's two sides only, its base
        on rollers with one node held in ``x`` (so that it strains freely).
    history
        A load history instead of ``P``, ``s``, ``Q``, ``sigma_bulk``: states ``(P, s, Q,
        sigma_bulk)`` (:func:`threepart.halfplane.load_history.check_history`: a sequence, a CSV path or a
        ``History``). Step 1 loads the first state's ``P`` at its ``s``; then one step per
        state, the four moving linearly together (the corners' forces, so ``P`` and ``P s``;
        ``s`` is then linear where ``P`` is constant). A flight cycle is ``[state0, state1,
        state0, state1]``.
    """
    settings = settings or DeckSettings(pair=True, penalty_factor=PENALTY_FACTOR)
    P0, s0, E, nu, f, states, lam, descent = _checked(
        model, P=P, s=s, E=E, nu=nu, f=f, Q=Q, increments=increments, settings=settings,
        slope=slope, descent=descent, sigma_bulk=sigma_bulk, history=history)
    W = model.a + model.c
    h, K = settings.size(W), settings.K(E, W)
    tl, _ = model.control_nodes()
    T = float(model.xy[tl - 1, 1])             # the top's height above the contact
    base, top = model.nsets["block_base"], model.nsets["punch_top"]
    bulk = any(st[3] != 0.0 for st in states)
    p_est = 2 * P0 / (math.pi * W)
    head = deck_head(model, P=P0, s=s0, E=E, K=K, settings=settings, title=title)
    head = head.replace(CONVENTIONS, "") + _friction_head(f, lam, lam * h / E, states, increments)
    parts = [head, *_model_text(model, E=E, nu=nu, K=K, sigma_inf=1e-6 * p_est, f=f, lam=lam)]
    sides = side_weights(model) if bulk else {}
    if bulk:
        parts.append(nset_text("NSIDES", np.array(sorted(sides))))
    rows, _ = lid_nodes(model, P=P0, s=s0, tilt=settings.tilt, half=False)
    rows += [f"2\n{int(n)}, 1, 1., {tl}, 1, -1." for n in top if int(n) != tl]
    parts.append("*EQUATION\n" + "\n".join(rows) + "\n")
    if bulk:        # rollers: the base strains with the bulk stress; one node holds it in x
        mid = int(base[np.argmin(np.abs(model.xy[base - 1, 0] - 0.5 * (model.c - model.a)))])
        parts.append(boundary_text([("NBASE", 2), (str(mid), 1)]))
    else:
        parts.append(boundary_text([("NBASE", 1), ("NBASE", 2)]))
    parts.append(_step(model, (P0, s0, 0.0, 0.0), T=T, tilt=settings.tilt, n=1, first=True,
                       descent=descent, sides=sides))
    for st in states:
        parts.append(_step(model, st, T=T, tilt=settings.tilt, n=increments, first=False,
                           descent=descent, sides=sides))
    return "".join(parts)


def _model_text(model: Model, *, E: float, nu: float, K: float, sigma_inf: float, f: float,
                lam: float) -> list[str]:
    """The deck's model data: nodes, the two bodies, the sets, materials and the contact pair."""
    tl, tr = model.control_nodes()
    return ["*HEADING\nthreepart: a three-part punch on an elastic block with friction\n",
            nodes_text(model.xy),
            elements_text(model.elements["block"], model.numbers["block"], "BLOCK"),
            elements_text(model.elements["punch"], model.numbers["punch"], "PUNCH"),
            nset_text("NSURF", model.nsets["block_surface"]),
            nset_text("NPROFILE", model.nsets["punch_profile"]),
            nset_text("NBASE", model.nsets["block_base"]), nset_text("NTOP", model.nsets["punch_top"]),
            nset_text("NCTRL", np.array([tl, tr])),
            nset_text("NOUT", np.union1d(model.nsets["block_surface"], model.nsets["punch_profile"])),
            material_text("BLOCK_MAT", E, nu, "BLOCK"), material_text("PUNCH_MAT", E, nu, "PUNCH"),
            surface_text("SSLAVE", faces=model.slave), surface_text("SMASTER", faces=model.master),
            f"*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSSLAVE, SMASTER\n"
            f"*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
            f"{K:.6g}, {sigma_inf:.6g}\n*FRICTION\n{f:.15g}, {lam:.6g}\n"]


def _friction_head(f: float, lam: float, lam_h: float, states: list[State], increments: int) -> str:
    """The friction deck's header after :func:`deck_head`'s first lines: the friction, each step's
    state (the reader's loads, :func:`threepart.calculix.cycle.step_loads`), the conventions."""
    bulk = any(st[3] != 0.0 for st in states)
    return (f"** friction: f = {f:.6g}, stick slope lambda = {lam:.6g} ({lam_h:.3g} E/h); "
            f"{len(states)} shear steps ({increments} increments each); |Q|/fP up to "
            f"{max(abs(st[2]) / st[0] for st in states) / f:.3g}\n"
            + "".join(f"** state {k + 1} (step {k + 2}): P = {st[0]:.10g}, s = {st[1]:.10g}, "
                      f"Q = {st[2]:.10g}, sigma_bulk = {st[3]:.10g}\n" for k, st in enumerate(states))
            + FRICTION_CONVENTIONS + (BULK_CONVENTIONS if bulk else "") + CONVENTIONS.split("** Contact:")[0])


def side_weights(model: Model) -> dict[int, float]:
    """The block's side nodes' consistent forces along ``x`` per unit bulk stress (MPa -> N/mm).

    A tension ``sigma`` on the sides is the traction ``-sigma`` (left side) and ``+sigma``
    (right side) along ``x``; on each quadratic edge of length ``L`` it is ``L/6, 2L/3, L/6``
    at its corner, middle and corner nodes. Their sum is zero; each side's ``±`` the depth.
    """
    from .mesh import face_elements

    out: dict[int, float] = {}
    for name, sign in (("block_left", -1.0), ("block_right", 1.0)):
        nodes = model.nsets.get(name)
        if nodes is None:
            raise InputError(f"the model has no `{name}` node set: mesh it with build_model (a bulk "
                             "stress acts on the block's sides)")
        for num, face in face_elements(model.elements["block"], model.numbers["block"], nodes, model.xy, math.inf):
            kind, conn = model.elements["block"][int(num) - int(model.numbers["block"][0])]
            nc = 4 if kind == "CPE8" else 3
            k = int(face[1:]) - 1
            i, j, m = int(conn[k]), int(conn[(k + 1) % nc]), int(conn[nc + k])
            L = float(np.hypot(*(model.xy[j - 1] - model.xy[i - 1])))
            for node, w in ((i, L / 6), (j, L / 6), (m, 2 * L / 3)):
                out[node] = out.get(node, 0.0) + sign * w
    return out


def _checked(model: Model, *, P: float | None, s: float | None, E: float, nu: float, f: float,
             Q: Sequence[float], increments: int, settings: DeckSettings, slope: float | None,
             descent: float | None, sigma_bulk: float, history: Any
             ) -> tuple[float, float, float, float, float, list[State], float, float | None]:
    """:func:`friction_deck`'s input, checked: ``(P, s, E, nu, f, states, lambda, descent)``."""
    E, nu = positive("E", E, (1e-6, 1e15)), finite("nu", nu)
    f = positive("f", f, (1e-6, 10.0))
    if not settings.pair:
        raise InputError("`settings.pair` must be True: friction is modelled on two similar bodies "
                         "(a stiffened punch couples the normal and the tangential problems)")
    if not isinstance(increments, int) or not 1 <= increments <= 1000:
        raise InputError(f"`increments` = {increments!r} must be an integer from 1 to 1000")
    states = _states(P=P, s=s, f=f, Q=Q, sigma_bulk=sigma_bulk, history=history)
    P0, s0 = states[0][0], states[0][1]       # the normal step's load: the first state's
    W = model.a + model.c
    lam = (positive("slope", slope, (1e-9, 1e20)) if slope is not None
           else SLOPE_FACTOR * E / settings.size(W))
    tl, tr = model.control_nodes()
    xL, xR, T = model.xy[tl - 1, 0], model.xy[tr - 1, 0], float(model.xy[tl - 1, 1])
    for Pk, sk, q, _ in [(P0, s0, 0.0, 0.0), *states] if settings.tilt == "free" else []:
        if not xL < sk - T * q / Pk < xR:
            raise InputError(f"`Q` = {q:g} moves the top's load to x = {sk - T * q / Pk:g}, off the "
                             f"punch's top [{xL:g}, {xR:g}]: lower Q or widen the block")
    if descent is not None:
        descent = positive("descent", descent, (1e-12, 0.1 * W))
        if settings.tilt != "suppressed":
            raise InputError("`descent` needs `settings.tilt` = 'suppressed' (the lid held level)")
        if history is not None or any(st[3] != 0.0 for st in states):
            raise InputError("`descent` holds one normal load: not with `history` or `sigma_bulk`")
    return P0, s0, E, nu, f, states, lam, descent


def _states(*, P: float | None, s: float | None, f: float, Q: Sequence[float], sigma_bulk: float,
            history: Any) -> list[State]:
    """The shear steps' states ``(P, s, Q, sigma_bulk)``, checked (each ``|Q| < f P``)."""
    if history is not None:
        from threepart.halfplane.load_history import check_history

        if len(Q) or sigma_bulk:
            raise InputError("`history` gives the states: leave `Q` and `sigma_bulk` out")
        hist = check_history(history)
        states = [hist.state(k) for k in range(len(hist))]
        if P is not None and (P != states[0][0] or (s is not None and s != states[0][1])):
            raise InputError(f"`P`, `s` = {P:g}, {s} must be the history's first state's "
                             f"({states[0][0]:g}, {states[0][1]:g}), or left out")
    else:
        if P is None or s is None:
            raise InputError("`P` and `s` are needed without a `history`")
        P, s = positive("P", P, (1e-12, 1e15)), finite("s", s)
        sb = finite("sigma_bulk", sigma_bulk)
        Qs = [finite("Q", q) for q in Q]
        if not Qs or (sb and Qs[0] == 0.0):
            raise InputError(f"`Q` = {Qs} must hold at least one target (the first nonzero with "
                             "`sigma_bulk`)")
        states = [(P, s, q, sb * q / Qs[0] if sb else 0.0) for q in Qs]
    bad = [st for st in states if not abs(st[2]) < f * st[0]]
    if bad:
        raise InputError(f"`Q` = {bad[0][2]:g} at P = {bad[0][0]:g}: each target needs |Q| < f P = "
                         f"{f * bad[0][0]:.6g}")
    return states


def _step(model: Model, state: State, *, T: float, tilt: str, n: int, first: bool,
          descent: float | None = None, sides: dict[int, float] | None = None) -> str:
    """One static step to ``state = (P, s, Q, sigma_bulk)`` in ``n`` equal increments (the normal
    step: ``first``); ``descent``: the top held lowered by it instead of loaded by ``P``;
    ``sides``: the block's side nodes' forces per unit bulk stress (:func:`side_weights`)."""
    P, s, Q, sigma = state
    # free tilt: the corners' forces balance Q's moment about the surface; tilt suppressed: the
    # guided lid reacts it (and P acts at the left corner, s an outcome)
    _, loads = lid_nodes(model, P=P, s=s - T * Q / P if tilt == "free" else s, tilt=tilt, half=False)
    tl, _ = model.control_nodes()
    dt = 1.0 / n
    held = "" if descent is None else f"{tl}, 2, 2, {-descent:.15g}\n"
    if descent is not None:
        loads = ""
    loads += "".join(f"{node}, 1, {sigma * w:.15g}\n" for node, w in (sides or {}).items())
    # the descent, once set, holds in the later steps (CalculiX keeps a step's boundary conditions)
    release = f"*BOUNDARY\n{held}" if first and held else ""
    side_print = "*NODE PRINT, NSET=NSIDES\nU\n" if sides else ""
    return ("*STEP, INC=1000\n*CONTROLS, PARAMETERS=TIME INCREMENTATION\n40, 60, 9, 200, 10, 4, 12, 40\n"
            f"*STATIC\n{dt:.15g}, 1., {dt / 256:.15g}, {dt:.15g}\n{release}*CLOAD\n{loads}"
            f"{tl}, 1, {Q:.15g}\n"
            "*NODE FILE, NSET=NOUT\nU\n*CONTACT FILE\nCDIS, CSTR, CELS\n"
            "*NODE PRINT, NSET=NBASE, TOTALS=ONLY\nRF\n*NODE PRINT, NSET=NCTRL\nU\n"
            f"{side_print}*END STEP\n")


# --------------------------------------------------------------------------- reading a run
def read_frd_states(stem: Path) -> list[tuple[int, float, dict[str, dict[int, np.ndarray]]]]:
    """Every recorded increment of ``stem.frd``: ``(step, total time, {block: {node: values}})``.

    :func:`threepart.calculix.read_frd` keeps the last increment only; a load
    history needs each. The step and the time are read from the ``1PSTEP`` and
    ``100CL`` records that open each increment's blocks.
    """
    from threepart.textfile import read_text

    from .files import file_label, frd_row, run_file

    path = run_file(stem, ".frd")
    label = file_label(path, None)
    states: list[tuple[int, float, dict[str, dict[int, np.ndarray]]]] = []
    step, t = 0, math.nan
    current: dict[int, np.ndarray] | None = None
    block = ""
    for i, line in enumerate(read_text(path, label).splitlines(), start=1):
        if line.startswith("    1PSTEP"):
            step = int(line.split()[3]) if len(line.split()) > 3 else step
        elif line.startswith("  100CL"):
            t = finite_row([line[12:24]], f"{label}, line {i} (the increment's time)")[0]
            if not states or states[-1][1] != t or states[-1][0] != step:
                states.append((step, t, {}))
        elif line.startswith(" -4") and states:
            current, block = {}, line.split()[1]
            states[-1][2][block] = current
        elif line.startswith(" -1") and current is not None:
            n, values = frd_row(line, i, label, block)
            current[n] = np.array(values)
        elif line.startswith(" -3"):
            current = None
    return states


def contact_traction(state: dict[str, dict[int, np.ndarray]], xy: dict[int, np.ndarray]
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(x, p, q)`` along the block's face from one increment of a surface-to-surface run.

    ``state`` holds the increment's CONTACT block (COPEN, CSLIP1, CSLIP2, CPRESS,
    CSHEAR1, CSHEAR2 at the slave nodes); ``xy`` the nodes' undeformed coordinates.
    ``x`` is the slave nodes' undeformed position (sorted: the material point, as the
    half-plane theory's ``x``; the deformed one moves with the block's surface, by
    ``2.5e-3 W`` along ``+x`` on ``slip_Q0.4`` at ``Q = 0.4 fP``, which read as the stick
    zone's "offset", docs/CALCULIX.md), ``p`` CPRESS
    (compressive positive) and ``q = -CSHEAR1``: on the block's upward face
    CalculiX's first tangent points along ``-x`` (measured: ``-∫CSHEAR1 dx = Q``
    for ``Q > 0`` along ``+x`` on the punch), so ``q`` is the shear the punch
    exerts on the block along ``+x``, the project's convention. A node whose
    contact output is all zero (never paired) is left out.
    """
    x, v = contact_rows(state, xy)
    return x, v[:, 3], -v[:, 4]


def contact_rows(state: dict[str, dict[int, np.ndarray]], xy: dict[int, np.ndarray]
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The slave nodes' undeformed ``x`` (sorted) and their CONTACT rows (COPEN, CSLIP1, CSLIP2,
    CPRESS, CSHEAR1, CSHEAR2), CPRESS and CSHEAR turned into the traction's global components per
    unit undeformed length; nodes whose output is all zero (never paired) left out.

    ccx's contact stresses are per unit deformed length and along the deformed face (its contact
    is solved on the deformed faces): CPRESS along the face's normal, CSHEAR1 along its tangent,
    which turns by the surface's slope ``du_y/dx`` (up to 5e-3 on ``slip_Q0.4`` x 20). With
    the deformed face's tangent ``(dx + du_x, du_y)`` per undeformed ``dx`` (from DISP, when the
    increment holds it) the traction per unit undeformed length along ``x`` and ``-y`` is
    ``q = q_t (1 + du_x/dx) + p_n du_y/dx`` and ``p = p_n (1 + du_x/dx) - q_t du_y/dx``: the
    half-plane theory's ``σ_xy`` and ``-σ_yy`` at the material point, so that ``∫q dx = Q`` and
    ``∫p dx = P`` (read along the face, ``∫q`` was 1.17e-3 off ``Q``, the pressure's share
    ``∫p du_y/dx dx``; turned, 7e-5; without the stretch ``∫p`` read 7.7e-4 off ``P``, with it
    1.6e-5; docs/CALCULIX.md). The stick zone moves by less than 5e-4 of W.
    """
    contact, disp = state["CONTACT"], state.get("DISP", {})
    nodes = [k for k, v in contact.items() if k in xy and np.any(v != 0.0)]
    if len(nodes) < 8:
        raise InputError(f"{len(nodes)} slave nodes carry contact output; at least 8 are needed")
    x = np.array([xy[k][0] for k in nodes])
    v = np.array([contact[k] for k in nodes])
    order = np.argsort(x)
    x, v = x[order], v[order]
    u = np.array([disp[k][:2] if k in disp else (0.0, 0.0) for k in np.asarray(nodes)[order]])
    if np.all(np.diff(x) > 0):
        dx, dy = np.gradient(x + u[:, 0], x), np.gradient(u[:, 1], x)   # the deformed tangent per dx
        p_n, q_t = v[:, 3].copy(), -v[:, 4]
        v[:, 3] = p_n * dx - q_t * dy
        v[:, 4] = -(q_t * dx + p_n * dy)
        v[:, 5] *= np.hypot(dx, dy)
    return x, v


def control_history(stem: Path) -> tuple[np.ndarray, np.ndarray]:
    """The times and the displacements ``(u_x, u_y)`` of the two control nodes (``NCTRL``) at each
    increment, from ``stem.dat``: ``(t, u)`` with ``u[i] = (ux_L, uy_L, ux_R, uy_R)``."""
    times, rows = [], []
    lines = Path(f"{stem}.dat").read_text().splitlines()
    for i, ln in enumerate(lines):
        if ln.strip().startswith("displacements") and "NCTRL" in ln:
            times.append(float(ln.split()[-1]))
            a, b = (lines[i + 2 + j].split() for j in (0, 1))
            rows.append([float(a[1]), float(a[2]), float(b[1]), float(b[2])])
    return np.array(times), np.array(rows)


@dataclass(frozen=True)
class FrictionResult:
    """One state of a CalculiX friction run: the traction along the block's face and its reading.

    Attributes
    ----------
    x, p, q
        The block's slave nodes (undeformed ``x``, sorted), CPRESS and the shear the punch
        exerts on the block along ``+x`` (:func:`contact_traction`).
    Q, P
        The loads the deck applied at this state (``P``: the base's reaction with a descent).
    stick
        The stick zone's ends (:func:`stick_ends`).
    P_int, Q_int
        ``∫p dx`` and ``∫q dx`` of the nodes (trapezoidal).
    info
        ``h``, ``nodes``, ``time`` (ccx's wall and CPU seconds), ``increments`` per step, the
        run's directory ``stem``, and for a cycle ``energy`` (``∮ F·du`` of the punch's top).
    """

    x: np.ndarray
    p: np.ndarray
    q: np.ndarray
    Q: float
    P: float
    stick: tuple[float, float]
    P_int: float
    Q_int: float
    info: dict[str, Any] = field(default_factory=dict)


def step_increments(stem: Path) -> dict[int, int]:
    """The converged increments of each step (``stem.sta``)."""
    out: dict[int, int] = {}
    sta = Path(f"{stem}.sta")
    for r in (ln.split() for ln in sta.read_text().splitlines()[2:]) if sta.is_file() else []:
        if len(r) >= 3 and not r[2].endswith("U"):
            out[int(r[0])] = out.get(int(r[0]), 0) + 1
    return out


def run_steps(punch: Punch, P: float, s: float, Qs: list[float], f: float, E: float, nu: float, *,
         n: float, increments: int, slope: float | None, tilt: str, workdir: Path, name: str,
         **deck: Any) -> tuple[Model, Path, dict[str, Any]]:
    """Mesh the pair for the closed form's normal contact, write the friction deck (``deck``: its
    ``sigma_bulk`` or ``history``), run ccx."""
    import resource

    from ..problem.material import compliance
    from ..methods import solve
    from .mesh import build_model
    from ..cache import restored
    from .run import run_ccx

    normal = solve(punch, P, s, A=compliance(E, nu, E, nu), tilt=tilt)
    settings = DeckSettings(n=n, pair=True, penalty_factor=PENALTY_FACTOR, tilt=tilt)
    model = build_model(punch, normal.a, normal.c, settings)
    text = friction_deck(model, P=None if deck.get("history") is not None else P,
                         s=None if deck.get("history") is not None else s, E=E, nu=nu, f=f, Q=Qs,
                         increments=increments, settings=settings, slope=slope, title=name, **deck)
    t0, c0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    stem = run_ccx(text, workdir, name, timeout=7200.0)
    info = {"h": model.h0, "nodes": model.n_nodes, "stem": stem,
            "wall": time.perf_counter() - t0, "cached": restored(workdir),
            "cpu": resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - c0,
            "increments": step_increments(stem)}
    return model, stem, info


def traction_state(state: dict[str, dict[int, np.ndarray]], xy: dict[int, np.ndarray], *,
           P: float, Q: float, f: float, info: dict[str, Any]) -> FrictionResult:
    """One recorded state as a :class:`FrictionResult`."""
    x, p, q = contact_traction(state, xy)
    return FrictionResult(x, p, q, Q, P, stick_ends(x, p, q, f), float(np.trapezoid(p, x)),
                          float(np.trapezoid(q, x)), info)


def partial_slip(punch: Punch, P: float, s: float, Q: float, f: float, E: float, nu: float, *,
                 n: float = 100.0, increments: int = 4, slope: float | None = None,
                 tilt: str = "free", workdir: Path, name: str = "slip", sigma_bulk: float = 0.0
                 ) -> FrictionResult:
    """Partial slip by CalculiX: ``P`` at ``s``, then ``Q`` in ``increments`` steps; the last state.

    ``sigma_bulk``: the block's bulk stress at ``Q``, rising with ``Q`` in proportion (the
    closed form's load path, docs/BULK_STRESS.md; :func:`friction_deck`).

    Two similar bodies (``E``, ``nu``), meshed for the closed form's normal contact at
    ``W / n``; surface-to-surface penalty contact with ``*FRICTION`` (``f``, the stick
    slope ``slope``, default :data:`SLOPE_FACTOR` ``E/h``). A Hertz punch (``b = 0``) is
    symmetric: give ``tilt="suppressed"`` (``s = 0``), which holds the lid level and lets it
    react ``Q``'s moment. Raises ``CcxMissing`` without ``ccx``, ``CcxError`` if it fails.
    """
    from .read import read_frd_nodes

    model, stem, info = run_steps(punch, P, s, [Q], f, E, nu, n=n, increments=increments, slope=slope,
                             tilt=tilt, workdir=workdir, name=name, sigma_bulk=sigma_bulk)
    xy = read_frd_nodes(stem)
    states = read_frd_states(stem)
    return traction_state(states[-1][2], xy, P=P, Q=Q, f=f, info=dict(info, sigma_bulk=sigma_bulk))


def fretting_cycle(punch: Punch, P: float, s: float, Q_max: float, f: float, E: float, nu: float, *,
                   n: float = 100.0, increments: int = 8, slope: float | None = None,
                   tilt: str = "free", workdir: Path, name: str = "fretting"
                   ) -> list[FrictionResult]:
    """The fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` by CalculiX: every recorded state.

    As :func:`partial_slip`, with three shear steps of ``increments`` each. Each state's
    ``info["energy"]`` is the energy dissipated per cycle (:func:`cycle_energy`).
    """
    from .read import read_frd_nodes

    Qs = [Q_max, -Q_max, Q_max]
    model, stem, info = run_steps(punch, P, s, Qs, f, E, nu, n=n, increments=increments, slope=slope,
                             tilt=tilt, workdir=workdir, name=name)
    t, u = control_history(stem)
    tl, tr = model.control_nodes()
    xL, xR = model.xy[tl - 1, 0], model.xy[tr - 1, 0]
    T = float(model.xy[tl - 1, 1])

    def loads(tt: np.ndarray) -> np.ndarray:
        """The control nodes' forces ``(Fx_L, Fy_L, Fx_R, Fy_R)`` at the total times ``tt``."""
        Qt = np.interp(tt, [0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 0.0, *Qs])
        Pt = P * np.minimum(tt, 1.0)
        FR = (Pt * s - T * Qt - Pt * xL) / (xR - xL) if tilt == "free" else np.zeros_like(tt)
        return np.c_[Qt, -(Pt - FR), np.zeros_like(tt), -FR]

    energy = cycle_energy(t, u, loads)
    info = dict(info, energy=energy)
    xy = read_frd_nodes(stem)
    return [traction_state(blk, xy, P=P, Q=float(np.interp(tt, [0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 0.0, *Qs])),
                   f=f, info=dict(info, time=tt, step=step))
            for step, tt, blk in read_frd_states(stem)]


def cycle_energy(t: np.ndarray, u: np.ndarray, loads: Any, span: tuple[int, int] = (2, 4)) -> float:
    """The energy dissipated per cycle: the work ``∮ F·du`` of the loads on the punch's control
    nodes over the closed loop of the steps between the total times ``span`` (default steps 3
    and 4, ``Q_max -> -Q_max -> Q_max``, total times 2 to 4; each step one unit of time).

    Over a closed loop the elastic work cancels, and ``∮ F·du = -∮ u·dF``; the loads ``F =
    loads(t)`` are linear in ``t`` within a step, so each step is ``-F' · ∫u dt``, by Simpson's
    rule over its equal increments (the trapezoidal rule where ccx cut one, or their count is
    odd). On ``fretting_Q0.4`` at W/h = 50 with 8 increments a step, Simpson's rule read the
    closed form's energy to +0.25 %, the trapezoidal rule on ``∮ F·du`` to -1.4 %.
    """
    from scipy.integrate import simpson

    total = 0.0
    for a in map(float, range(span[0], span[1])):
        m = (t >= a - 1e-9) & (t <= a + 1 + 1e-9)
        tt, uu = t[m], u[m]
        dF = (loads(np.array([a + 1.0])) - loads(np.array([a])))[0]
        even = len(tt) % 2 == 1 and np.allclose(np.diff(tt), np.diff(tt)[0])
        integral = (simpson(uu, x=tt, axis=0) if even
                    else np.sum(0.5 * (uu[1:] + uu[:-1]) * np.diff(tt)[:, None], axis=0))
        total -= float(np.dot(dF, integral))
    return total

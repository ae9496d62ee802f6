"""A load cycle from another code's file judged: the friction energy per cycle and the slip amplitude.

A file that records every state of a run (a GetFEM sidecar ``job.getfem.json``, a
CalculiX friction ``.frd``: :mod:`threepart.readers` returns them in
``info["states"]``, each with its loads ``P, Q`` (``s``, ``sigma_bulk`` where
recorded) and its nodal ``x, p, q, slip``) is judged over its last complete cycle
(:func:`threepart.getfem.last_cycle`) against the closed form's cycle: a fretting
cycle ``0 -> Q_max -> -Q_max -> Q_max`` (:func:`threepart.fretting`, Masing) or the
periodic steady state of a flight cycle between two states
(:func:`threepart.steady_state`):

- the cycle reaches both of the reference's turning states (a stage missing fails);
- the friction energy per cycle, ``Σ_k ∫ (q_k + q_k+1)/2 (slip_k+1 - slip_k) dx`` over
  the cycle's states (:func:`threepart.getfem.friction_work`), against the reference's;
- the largest slip amplitude, half the range of a node's slip over the cycle, at the
  nodes in contact, against the reference's amplitude at the same nodes.

It names the cycle's pitfalls with their numbers: a flipped shear or slip sign, and a
step too coarse to resolve the reversal (the states per half-cycle, and the energy's
step error estimated from every second state).

Names
-----
CycleReference  -- the reference's cycle: its turning states, energy and slip amplitude
fretting_reference -- the closed form's fretting cycle as a CycleReference
flight_reference   -- the steady state of a flight cycle as a CycleReference
judge_cycle     -- the checks and pitfalls of recorded states, as a JSON-safe document
cycle_document  -- that document as the report's sections
main_cycle      -- read, judge and report (``threepart compare`` of a cycle); 0 when all holds, else 1
CYCLE_QUANTITIES, STEP, SAME_LOAD -- the checks and the limits of the pitfalls
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

from threepart.errors import InputError
from threepart.results.fields import STICK_LOAD
from threepart.output import atomic_dir, json_safe, strict_json
from threepart.tolerances import tolerance

from ..verify.sections import Bullets, Document, Item, Section, Status, Table, Verdict, fmt, words
from .pitfalls import PITFALLS, Pitfall

__all__ = ["CycleReference", "fretting_reference", "flight_reference", "judge_cycle", "cycle_document",
           "main_cycle", "CYCLE_QUANTITIES", "STEP", "SAME_LOAD"]

#: what a cycle is judged by, as the tolerance table's "referee" rows name them
CYCLE_QUANTITIES = ("energy", "slip_amplitude")
#: the energy's step error (of the energy) past which the steps are named too coarse
STEP = tolerance(PITFALLS, "cycle_step").limit
#: a recorded state is one of the reference's turning states when its loads agree to this (of each load's scale)
SAME_LOAD = tolerance(PITFALLS, "cycle_state").limit
#: the tolerance table's group of the checks
COMPARISON = "referee"
#: the states whose |Q| passes this fraction of the cycle's largest judge the shear's sign (near Q = 0
#: the integral is rounding); the sign is flipped when more than half of them oppose Q
LOADED, MAJORITY = 0.1, 0.5


@dataclass(frozen=True)
class CycleReference:
    """The reference's cycle.

    Attributes
    ----------
    kind
        ``"fretting"`` or ``"flight"``.
    ends
        The cycle's two turning states ``(P, s, Q, sigma_bulk)``.
    energy
        The friction work per cycle and unit length (N mm/mm).
    amplitude
        The slip amplitude at ``x`` (a callable), 0 outside the larger contact.
    largest
        ``(value, x)``: the largest slip amplitude and where it lies.
    """

    kind: str
    ends: tuple[tuple[float, float, float, float], tuple[float, float, float, float]]
    energy: float
    amplitude: Callable[[np.ndarray], np.ndarray]
    largest: tuple[float, float]
    method: str = ""
    note: str = ""
    result: Any = field(default=None, compare=False)


def fretting_reference(punch: Any, P: float, s: float, *, A: float, Q_max: float, f: float,
                       tilt: str = "free", sigma_bulk: float = 0.0) -> CycleReference:
    """The fretting cycle ``0 -> Q_max -> -Q_max -> Q_max`` of :func:`threepart.fretting` (``auto``)."""
    from threepart.methods import fretting

    res = fretting(punch, P, s, A=A, Q_max=Q_max, f=f, tilt=tilt, sigma_bulk=sigma_bulk)
    n = res.normal
    x = np.linspace(-n.a, n.c, 4001)[1:-1]
    amp = np.asarray(res.slip_amplitude(x), dtype=float)
    i = int(np.argmax(amp))
    ends = ((float(P), float(s), float(Q_max), float(sigma_bulk)),
            (float(P), float(s), -float(Q_max), -float(sigma_bulk)))
    return CycleReference("fretting", ends, float(res.energy), res.slip_amplitude, (float(amp[i]), float(x[i])),
                          res.method, str(res.info.get("auto", "")), res)


def flight_reference(punch: Any, state0: Sequence[float], state1: Sequence[float], *, A: float,
                     f: float) -> CycleReference:
    """The periodic steady state of the in-phase cycle ``state0 <-> state1`` (:func:`threepart.steady_state`, ``auto``)."""
    from threepart.methods import steady_state

    res = steady_state(punch, (tuple(state0), tuple(state1)), f, A=A)
    ends = tuple(tuple(float(v) for v in st) for st in res.states)
    return CycleReference("flight", ends, float(res.energy), res.slip_amplitude,  # type: ignore[arg-type]
                          res.largest_slip_amplitude(), res.method, str(res.info.get("auto", "")), res)


def _loads(st: Any) -> np.ndarray:
    """A state's ``(P, s, Q, sigma_bulk)``, NaN where the code records none."""
    values = (getattr(st, k, None) for k in ("P", "s", "Q", "sigma_bulk"))
    return np.array([math.nan if v is None else float(v) for v in values])


def _reached(states: Sequence[Any], ref: CycleReference) -> np.ndarray:
    """``(K, 2)``: whether each state has the loads of each of the reference's turning states (to
    :data:`SAME_LOAD` of each load's scale; a load the code does not record is not judged)."""
    loads = np.array([_loads(st) for st in states])
    ends = np.array(ref.ends)
    scale = np.maximum(np.nanmax(np.abs(np.vstack([loads, ends])), axis=0), 1e-300)
    diff = np.abs(loads[:, None, :] - ends[None, :, :]) / scale
    return np.all(np.where(np.isnan(diff), 0.0, diff) <= SAME_LOAD, axis=2)


def _check(quantity: str, reference: float, obtained: float, reason: str) -> dict[str, Any]:
    limit = tolerance(COMPARISON, quantity).limit
    error = (obtained - reference) / reference if reference else math.inf
    return {"quantity": quantity, "reference": reference, "obtained": obtained, "error": error,
            "limit": limit, "passed": bool(abs(error) <= limit), "reason": reason}


def _in_contact(states: Sequence[Any], x: np.ndarray) -> np.ndarray:
    """The nodes loaded above :data:`threepart.results.fields.STICK_LOAD` of the peak at some state of the cycle."""
    p = np.array([np.interp(x, np.asarray(st.x, float), np.asarray(st.p, float), left=0.0, right=0.0)
                  for st in states])
    return np.any(p > STICK_LOAD * float(np.max(p)), axis=0)


def _sign_pitfalls(states: Sequence[Any], energy: float) -> list[Pitfall]:
    """``shear-sign``: ``∫q dx`` against ``Q`` at most states; ``slip-sign``: a negative friction work."""
    Q = np.array([float(st.Q) for st in states])
    integral = np.array([float(np.trapezoid(st.q, st.x)) for st in states])
    loaded = np.abs(Q) > LOADED * float(np.max(np.abs(Q)))
    opposed = float(np.mean(integral[loaded] * Q[loaded] < 0)) if loaded.any() else 0.0
    if opposed > MAJORITY:
        return [Pitfall("shear-sign", opposed, MAJORITY,
                        f"∫q dx has the sign opposite to Q at {opposed:.0%} of the cycle's loaded states: the "
                        "shear's sign is flipped; threepart's q is the shear the punch exerts on the substrate "
                        "along +x (∫q dx = Q): a code's contact shear on the slave (lower) surface often has "
                        "the other sign")]
    if energy < 0:
        return [Pitfall("slip-sign", energy, 0.0,
                        f"the friction work over the cycle is {energy:.6g} N mm/mm, negative while ∫q dx = Q: the "
                        "slip's sign is flipped; threepart's slip is the punch's tangential displacement "
                        "relative to the substrate (GetFEM's u2_x - u1_x)")]
    return []


def _step_pitfall(states: Sequence[Any], turn: int, energy: float) -> tuple[Pitfall | None, dict[str, Any]]:
    """The steps: states per half-cycle and the energy's step error, ``|E - E_2|/3`` (``E_2`` from every
    second state: the trapezoid rule in the state index converges as the step squared)."""
    from threepart.getfem import friction_work

    steps = len(states) - 1
    figures: dict[str, Any] = {"states_per_half_cycle": steps / 2, "step_error": None}
    if steps % 2 or turn % 2 or steps < 4:
        return None, figures
    coarse = friction_work(states, 2)
    error = abs(energy - coarse) / 3.0 / abs(energy) if energy else math.inf
    figures["step_error"] = error
    if error <= STEP:
        return None, figures
    return Pitfall("step", error, STEP,
                   f"{steps // 2} states per half-cycle leave a step error of about {error:.3g} of the energy "
                   f"(every second state gives {coarse:.6g} against {energy:.6g} N mm/mm): the steps are too "
                   "coarse to resolve the reversal, where the whole contact sticks and the slip zones grow "
                   "back from its ends; halve them"), figures


def judge_cycle(states: Sequence[Any], ref: CycleReference, *, source: str = "") -> dict[str, Any]:
    """The checks and the pitfalls of a run's recorded ``states`` against ``ref``, as a JSON-safe document.

    ``checks``: ``cycle`` (a complete last cycle reaching both turning states), then
    ``energy`` and ``slip_amplitude`` (:data:`CYCLE_QUANTITIES`, the tolerance table's
    ``"referee"`` rows); ``pitfalls``: ``shear-sign``, ``slip-sign``, ``step``.
    """
    from threepart.getfem import friction_work, last_cycle, slip_amplitude

    bounds = last_cycle(states)
    reference = {"method": ref.method, "kind": ref.kind, "ends": [list(e) for e in ref.ends],
                 "energy": ref.energy, "largest_slip_amplitude": list(ref.largest), "note": ref.note}
    obtained: dict[str, Any] = {"states": len(states), "points": int(np.size(states[0].x)) if states else 0}
    checks: list[dict[str, Any]] = []
    pitfalls: list[Pitfall] = []
    names = ("state0", "state1") if ref.kind == "flight" else ("Q = Q_max", "Q = -Q_max")
    start, end = bounds if bounds is not None else (0, -1)
    cycle = list(states[start:end + 1])
    reached = _reached(cycle, ref) if cycle else np.zeros((0, 2), bool)
    missing = [k for k in (0, 1) if not reached[:, k].any()]
    why = ("the file's states close no cycle (no state before the last one has its loads)" if not cycle else
           "the last cycle (states {}..{}) misses {}".format(start + 1, end + 1, " and ".join(
               f"{names[k]} {tuple(round(v, 6) for v in ref.ends[k])}" for k in missing)) if missing else
           f"the last cycle, states {start + 1}..{end + 1} (counted from 1), reaches both turning states")
    checks.append({"quantity": "cycle", "reference": 2.0, "obtained": float(2 - len(missing)),
                   "error": float(len(missing)), "limit": 0.0, "passed": not missing, "reason": why})
    if cycle and not missing:
        energy = friction_work(cycle)
        x, amp = slip_amplitude(cycle)
        touch = _in_contact(cycle, x)
        ref_amp = np.asarray(ref.amplitude(x), dtype=float)
        got, want = float(np.max(amp[touch], initial=0.0)), float(np.max(ref_amp[touch], initial=0.0))
        checks.append(_check("energy", ref.energy, energy,
                             "Σ ∫ (q_k + q_k+1)/2 (slip_k+1 - slip_k) dx over the last cycle's states against "
                             f"the {ref.method} {ref.kind} cycle's energy"))
        checks.append(_check("slip_amplitude", want, got,
                             "the largest half-range of a node's slip over the cycle, at the nodes in contact, "
                             f"against the reference's amplitude at the same nodes (its largest anywhere: "
                             f"{ref.largest[0]:.6g} mm at x = {ref.largest[1]:.6g} mm)"))
        other = 1 if reached[0, 0] else 0          # the turning state the cycle does not start at
        turn = int(np.flatnonzero(reached[:, other])[0])
        step, figures = _step_pitfall(cycle, turn, energy)
        pitfalls += _sign_pitfalls(cycle, energy) + ([step] if step else [])
        obtained.update(cycle=[start, end], energy=energy, slip_amplitude=got, **figures)
    return json_safe({
        "tool": "threepart compare (cycle)", "source": source, "reference": reference, "obtained": obtained,
        "passed": all(c["passed"] for c in checks) and not pitfalls,
        "checks": checks, "pitfalls": [q.as_dict() for q in pitfalls]})


def cycle_document(doc: dict[str, Any]) -> Document:
    """The document of :func:`judge_cycle` as the report's two sections: the checks, the pitfalls."""
    ok = bool(doc["passed"])
    rows = tuple((c["quantity"], fmt(c["reference"]), fmt(c["obtained"]), fmt(c["error"]), fmt(c["limit"]),
                  Verdict(Status.of(bool(c["passed"]))), words(c["reason"])) for c in doc["checks"])
    table = Table(("quantity", "reference", "obtained", "error", "limit", "verdict", "reason"), rows)
    items = tuple(Item(words(f"{q['name']}: {q['message']}")) for q in doc["pitfalls"]) or \
        (Item(("none of the known pitfalls was found",)),)
    ref, got = doc["reference"], doc["obtained"]
    per_half = got.get("states_per_half_cycle")
    intro = (words(f"`{doc['source']}` ({got['states']} states, {got['points']} points) over its last cycle "
                   f"against the {ref['method']} {ref['kind']} cycle" + (f" ({ref['note']})" if ref["note"] else "")
                   + (f"; {per_half:g} states per half-cycle" if per_half else "") + "; limits from the "
                   f"tolerance table's `{COMPARISON}` rows."),)
    return Document("threepart compare", "PASSED" if ok else "FAILED", Status.of(ok), (
        Section("Checks", "checks", intro, (table,), status=Status.of(all(c["passed"] for c in doc["checks"]))),
        Section("Pitfalls", "pitfalls", (Bullets(items),), status=Status.of(not doc["pitfalls"]))))


def main_cycle(path: str | Path, ref: CycleReference, *, out: str | Path, say: Callable[[str], None] = print,
               **options: Any) -> int:
    """Read the file's states (``info["states"]``), judge its last cycle, write the report into ``out``;
    0 when every check holds and no pitfall shows, else 1."""
    from threepart import readers

    from ..verify.render import render_html, render_markdown

    record = readers.read(path, arg="--pressure", **options)
    states = record.info.get("states")
    if not states:
        raise InputError(f"`--pressure` {path}: the file records no states (info['states']), which a cycle "
                         "is judged by: give a GetFEM sidecar (job.getfem.json) or a CalculiX friction .frd")
    if any(getattr(st, "P", None) is None or getattr(st, "Q", None) is None for st in states):
        raise InputError(f"`--pressure` {path}: its states carry no loads P and Q, which find the cycle "
                         "(CalculiX: threepart's friction deck .inp beside the .frd gives them)")
    doc = judge_cycle(list(states), ref, source=str(path))
    with atomic_dir(out, command="compare") as tmp:
        d = cycle_document(doc)
        (tmp / "report.json").write_text(strict_json(doc, indent=1), encoding="utf-8")
        (tmp / "report.md").write_text(render_markdown(d), encoding="utf-8")
        (tmp / "report.html").write_text(render_html(d, tmp), encoding="utf-8")
    failed = [c for c in doc["checks"] if not c["passed"]]
    say(f"{'PASSED' if doc['passed'] else 'FAILED'}: {len(doc['checks']) - len(failed)}/{len(doc['checks'])} "
        f"checks of the cycle within tolerance, {len(doc['pitfalls'])} pitfalls -> {Path(out) / 'report.html'}")
    for c in doc["checks"]:
        if c["quantity"] == "cycle" or not c["passed"]:
            say(f"  {'failed' if not c['passed'] else 'cycle'}: {c['quantity']}: " + (
                c["reason"] if c["quantity"] == "cycle" else f"error {c['error']:.3g} > {c['limit']:.3g}"))
    for c in doc["checks"]:
        if c["passed"] and c["quantity"] != "cycle":
            say(f"  {c['quantity']}: {c['obtained']:.6g} against {c['reference']:.6g}, error {c['error']:.3g}")
    for q in doc["pitfalls"]:
        say(f"  pitfall {q['name']}: {q['message']}")
    return 0 if doc["passed"] else 1

"""The one case catalogue: ``threepart/problem/cases.json`` read into :class:`Case` records.

Every test, benchmark and the verification run take their cases from here; a
case's ``suites`` says who uses it (``"verify"``, ``"fem"``, ``"sie"``, see the
file's ``"about"``). Inputs only, no solution: a case exposes its numbers, and
the solvers are called elsewhere (:mod:`threepart.reports.verify.runs`).

A case given as a fraction of its lift-off lever arm is resolved
(:meth:`Case.resolved`) with the lift-off range of the method
:data:`threepart.registry.REFERENCE`, asked for through :mod:`threepart.registry` (this
module imports no solver); a case that the SIE or the FEM reads alone stores
that lever arm, so they never load the closed form.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from .material import BODIES, block_modulus, material_compliance, modulus
from .punch import Punch
from ..registry import BEYOND_REFERENCE, REFERENCE, lift_off
from .checks import finite, positive, show
from threepart.errors import InputError

__all__ = ["Case", "Wear", "CASES_FILE", "SUITES", "load_cases", "get_case", "slip_loads"]

CASES_FILE = Path(__file__).with_name("cases.json")
#: who reads a case: the verification run, the FEM tests and benchmark, the SIE tests and benchmark
SUITES = ("verify", "fem", "sie", "wear")


@dataclass(frozen=True)
class Wear:
    """A wear case's march (issue 39, :func:`threepart.wear`): its ``law``, coefficient ``k``, ``cycles``
    and where ``k`` comes from (``source``)."""

    law: str
    k: float
    cycles: int
    source: str = ""


@dataclass(frozen=True)
class Case:
    """One case of the catalogue: punch, material or compliance, loads and (for partial slip) Q and f.

    Exactly one of ``material`` (``(E, nu)``, E in MPa) and ``compliance``
    (``A`` itself, for a nondimensional case) is given. A material is that of
    both bodies, two similar elastic bodies, ``A = 4 (1 - nu^2)/E`` (the one
    convention, :func:`threepart.problem.material.material_compliance`), unless
    ``bodies`` says ``"rigid punch"``: a rigid punch on an elastic half-plane of
    that material, ``A = 2 (1 - nu^2)/E``. ``s`` is the lever arm; when ``s_lift_off_fraction`` is set
    instead, :meth:`resolved` computes ``s`` from the lift-off range, using the
    stored lift-off lever arm ``s_max`` when there is one (a fraction above 1
    is past lift-off). ``closedform_refuses`` names the error the closed form
    must raise for a case past its framework (``"LiftOffError"``,
    ``"StickZoneError"``); such a case is judged against the SIE. With
    ``cycle`` the shear load is the amplitude ``Q_max`` of a fretting cycle
    ``0 -> Q_max -> -Q_max -> Q_max``. ``sigma_bulk`` is a bulk stress ``σxx``
    in the substrate (tension positive), applied with the shear load in
    proportion (in phase over a cycle). With ``states``, two states
    ``(P, s, Q, sigma_bulk)`` between which the four move linearly and in
    phase, the case is the periodic steady state of that cycle (a flight
    cycle, docs/STEADY_STATE.md); ``P``, ``s``, ``Q_over_fP`` and
    ``sigma_bulk`` are then its running loads, for the record.
    """

    name: str
    description: str
    punch: Punch
    P: float
    material: tuple[float, float] | None = None
    compliance: float | None = None
    s: float | None = 0.0
    tilt: str = "free"
    s_lift_off_fraction: float | None = None
    s_max: float | None = None
    f: float | None = None
    Q_over_fP: float | None = None
    suites: tuple[str, ...] = ()
    closedform_refuses: str | None = None
    cycle: bool = False
    sigma_bulk: float = 0.0
    states: tuple[tuple[float, float, float, float], tuple[float, float, float, float]] | None = None
    bodies: str = BODIES[0]
    wear: Wear | None = None

    @property
    def beyond(self) -> bool:
        """Whether the case lies past the paper's framework (the closed form must refuse it)."""
        return self.closedform_refuses is not None

    @property
    def reference(self) -> str:
        """The method the others are compared with: the closed form, or the SIE past it."""
        return BEYOND_REFERENCE if self.beyond else REFERENCE

    def __post_init__(self) -> None:
        if (self.material is None) == (self.compliance is None):
            raise InputError(f"case {self.name!r} needs exactly one of `material` (E, nu) and `A`")
        if self.bodies not in BODIES:
            raise InputError(f"case {self.name!r}: `bodies` = {self.bodies!r} must be one of {BODIES}")
        if self.compliance is not None and self.bodies != BODIES[0]:
            raise InputError(f"case {self.name!r} gives `A` itself: `bodies` applies to a material (E, nu)")

    @property
    def E(self) -> float:
        """Young's modulus of both bodies (of the half-plane under a ``"rigid punch"``); ``ValueError``
        for a nondimensional case."""
        return self._material()[0]

    @property
    def nu(self) -> float:
        """Poisson's ratio of both bodies (of the half-plane under a ``"rigid punch"``); ``ValueError``
        for a nondimensional case."""
        return self._material()[1]

    def _material(self) -> tuple[float, float]:
        if self.material is None:
            raise InputError(f"case {self.name!r} is nondimensional: it gives `A`, not a material (E, nu)")
        return self.material

    @property
    def A(self) -> float:
        """Compliance of eq. (4): the given ``A``, or that of the material and its ``bodies``: two
        similar bodies, ``4 (1 - nu^2)/E``, or a rigid punch, ``2 (1 - nu^2)/E``."""
        if self.compliance is not None:
            return self.compliance
        return material_compliance(*self._material(), bodies=self.bodies)

    @property
    def block_E(self) -> float:
        """The modulus of the FE normal model's block under its rigid punch that has this case's ``A``
        (:func:`threepart.problem.material.block_modulus`): ``E`` for a ``"rigid punch"`` case, ``E/2`` for two
        similar bodies of ``E``, the same ``nu``. ``ValueError`` for a nondimensional case."""
        return block_modulus(self._material()[0], self.bodies)

    @property
    def kind(self) -> str:
        """``"wear"`` with a ``wear`` march (a fretting cycle worn), ``"steady"`` with two ``states``,
        ``"fretting"`` for a cycle, ``"slip"`` when a shear load is applied, else ``"normal"``."""
        if self.wear is not None:
            return "wear"
        if self.states is not None:
            return "steady"
        if self.Q_over_fP is None:
            return "normal"
        return "fretting" if self.cycle else "slip"

    @property
    def Q(self) -> float | None:
        """Shear force ``Q = (Q/fP) f P``."""
        if self.Q_over_fP is None or self.f is None:
            return None
        return self.Q_over_fP * self.f * self.P

    @property
    def load_4PA_over_b(self) -> float:
        """The paper's dimensionless load ``4PA/b`` (inf for b = 0)."""
        return 4 * self.P * self.A / self.punch.b if self.punch.b > 0 else math.inf

    @property
    def shear_load(self) -> tuple[float, float]:
        """``(Q, f)`` of a partial-slip case; ``ValueError`` for a normal case."""
        if self.Q is None or self.f is None:
            raise InputError(f"case {self.name!r} has no shear load (`Q_over_fP` and `f`)")
        return self.Q, self.f

    @property
    def s_load(self) -> float:
        """The lever arm passed to a solver: ``s``, or 0 when the tilt is suppressed (``s*`` is returned)."""
        return 0.0 if self.tilt == "suppressed" else float(self.s or 0.0)

    def normal_key(self) -> tuple[Any, ...]:
        """Cases with equal keys share one normal problem (partial slip reuses it)."""
        return (self.punch, self.material, self.bodies, self.compliance, self.P, self.s, self.tilt)

    def resolved(self) -> Case:
        """This case with ``s`` a number (from the lift-off fraction if one is given)."""
        frac = self.s_lift_off_fraction
        if frac is None:
            return self
        if frac >= 0 and self.s_max is not None:
            return replace(self, s=frac * self.s_max)
        # the paper's closed form: its framework (both contact ends on the edge arcs) is what the
        # fraction measures
        s_min, s_max = lift_off(REFERENCE, self.punch, self.P, self.A)
        s = frac * (s_max if frac >= 0 else -s_min)
        return replace(self, s=float(s))

    def as_dict(self) -> dict[str, Any]:
        """Plain dict of the case (JSON-ready; ``R = inf`` and ``4PA/b = inf`` as None)."""
        p = self.punch
        E, nu = self.material if self.material is not None else (None, None)
        return {"name": self.name, "description": self.description, "kind": self.kind,
                "punch": {"R1": p.R1, "R2": p.R2, "b": p.b, "R": None if math.isinf(p.R) else p.R,
                          "case": p.case},
                "E": E, "nu": nu, "bodies": None if self.material is None else self.bodies,
                "A": self.A, "P": self.P, "s": self.s, "tilt": self.tilt,
                "s_lift_off_fraction": self.s_lift_off_fraction, "load_4PA_over_b":
                    None if math.isinf(self.load_4PA_over_b) else self.load_4PA_over_b,
                "f": self.f, "Q_over_fP": self.Q_over_fP, "Q": self.Q,
                "closedform_refuses": self.closedform_refuses, "sigma_bulk": self.sigma_bulk,
                **({} if self.states is None else {"states": [list(st) for st in self.states]})}


def _read(path: str | Path | None) -> dict[str, Any]:
    """The catalogue file as a dict; ``ValueError`` naming ``path`` if it cannot be read or is not one."""
    where = f"`path` = {str(path or CASES_FILE)!r}"
    try:
        data = json.loads(Path(path or CASES_FILE).read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(f"{where} cannot be read: {exc.strerror or exc}") from None
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"{where} is not a JSON case catalogue: {exc}") from None
    if not isinstance(data, dict) or not isinstance(data.get("cases"), list):
        raise InputError(f"{where} has no field 'cases' (a list of cases)")
    return data


def _checked_case(c: Any, default_material: Any, path: str | Path | None, i: int) -> Case:
    """:func:`_case` with every missing or bad field named, with the file and the case."""
    name = c.get("name", f"#{i}") if isinstance(c, dict) else f"#{i}"
    where = f"`path` = {str(path or CASES_FILE)!r}, case {name!r}"
    try:
        case = _case(c, default_material)
        positive("P", case.P)
        finite("s", case.s if case.s is not None else 0.0)
        for key, value in (("f", case.f), ("Q_over_fP", case.Q_over_fP), ("A", case.compliance),
                           ("s_lift_off_fraction", case.s_lift_off_fraction)):
            if value is not None:
                finite(key, value)
        finite("sigma_bulk", case.sigma_bulk)
        if case.wear is not None and (case.f is None or case.Q_over_fP is None):
            raise InputError(f"has no field {'f' if case.f is None else 'Q_over_fP'!r} (a wear case is a "
                             "fretting cycle of amplitude Q_over_fP f P)")
        if case.states is not None and case.f is None:
            raise InputError("`states` (a cycle) needs the coefficient of friction `f`")
        if case.material is not None:
            modulus(case.material[0])
            finite("nu", case.material[1])
    except KeyError as exc:
        raise InputError(f"{where} has no field {exc.args[0]!r}") from None
    except (TypeError, ValueError, AttributeError) as exc:
        raise InputError(f"{where}: {exc}") from None
    return case


def _case(c: dict[str, Any], default_material: dict[str, float]) -> Case:
    pd = dict(c["punch"])
    R = pd.pop("R", None)
    punch = Punch(R=math.inf if R is None else float(R), **pd)
    mat = c.get("material", None if "A" in c else default_material)
    material = None if mat is None else (float(mat["E"]), float(mat["nu"]))
    compliance = float(c["A"]) if "A" in c else None
    return Case(name=c["name"], description=c.get("description", ""), punch=punch, P=float(c["P"]),
                material=material, compliance=compliance,
                s=c.get("s", None if "s_lift_off_fraction" in c else 0.0), tilt=c.get("tilt", "free"),
                s_lift_off_fraction=c.get("s_lift_off_fraction"), s_max=c.get("s_max"),
                f=c.get("f"), Q_over_fP=c.get("Q_over_fP"), suites=tuple(c["suites"]),
                closedform_refuses=c.get("closedform_refuses"), cycle=bool(c.get("cycle", False)),
                sigma_bulk=float(c.get("sigma_bulk", 0.0)), states=_states(c.get("states")),
                bodies=c.get("bodies", BODIES[0]), wear=_wear(c.get("wear")))


def _wear(spec: Any) -> Wear | None:
    """A case's ``wear``: None, or its law, ``k > 0``, whole ``cycles >= 1`` and source."""
    if spec is None:
        return None
    if not isinstance(spec, dict):
        raise InputError(f"`wear` must be an object {{law, k, cycles, source}}, not {show(spec)}")
    law, k, cycles = spec["law"], positive("k", spec["k"]), spec["cycles"]
    if not isinstance(law, str):
        raise InputError(f"`law` must be a string, not {show(law)}")
    if isinstance(cycles, bool) or not isinstance(cycles, int) or cycles < 1:
        raise InputError(f"`cycles` = {show(cycles)} must be a whole number >= 1")
    return Wear(law, float(k), cycles, str(spec.get("source", "")))


def _states(states: Any) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float]] | None:
    """A case's ``states``: None, or two states ``(P, s, Q, sigma_bulk)`` of finite numbers, ``P > 0``."""
    if states is None:
        return None
    if not isinstance(states, list) or len(states) != 2:
        raise InputError(f"`states` must be a list of 2 states [P, s, Q, sigma_bulk], not {show(states)}")
    out = []
    for k, st in enumerate(states):
        if not isinstance(st, list) or len(st) != 4:
            raise InputError(f"`states[{k}]` must be a list [P, s, Q, sigma_bulk] of 4 numbers, not {show(st)}")
        P, s, Q, sigma = (finite(f"states[{k}][{i}]", v) for i, v in enumerate(st))
        positive(f"states[{k}][0] (P)", P)
        out.append((float(P), float(s), float(Q), float(sigma)))
    return out[0], out[1]


def load_cases(suite: str | None = "verify", path: str | Path | None = None) -> list[Case]:
    """The cases of ``suite`` (default: the verification run's; None: every case), in file order.

    ``path`` reads another catalogue file of the same layout (default :data:`CASES_FILE`).
    """
    if suite is not None and suite not in SUITES:
        raise InputError(f"`suite` = {suite!r} is not one of {SUITES}")
    data = _read(path)
    cases = [_checked_case(c, data.get("material"), path, i) for i, c in enumerate(data["cases"])]
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        raise InputError(f"case names in {path or CASES_FILE} are not unique: {names}")
    unknown = {s for c in cases for s in c.suites} - set(SUITES)
    if unknown:
        raise InputError(f"unknown suites {sorted(unknown)} in {path or CASES_FILE}")
    return [c for c in cases if suite is None or suite in c.suites]


def get_case(name: str, path: str | Path | None = None) -> Case:
    """The catalogue case called ``name``, whatever its suites.

    Raises
    ------
    ValueError
        If there is no such case; the message lists the catalogue's names.
    """
    cases = load_cases(None, path)
    for c in cases:
        if c.name == name:
            return c
    raise InputError(f"`name` = {show(name)} is not a case of {path or CASES_FILE.name} "
                     f"(its cases: {', '.join(c.name for c in cases)})")


def slip_loads(suite: str = "sie", path: str | Path | None = None) -> tuple[tuple[float, float], ...]:
    """The ``(Q/fP, f)`` pairs applied to every case of ``suite`` in its partial-slip comparison."""
    loads = _read(path)["slip_loads"].get(suite, [])
    return tuple((float(q), float(f)) for q, f in loads)

"""The text of a GetFEM script (``job.py``): two similar elastic bodies with Coulomb friction.

Names
-----
JobSettings  -- the mesh (elements across W), the block, the augmentation, Newton's limits, the steps
legs         -- the load path: partial slip (0 -> Q), a fretting cycle (0 -> Q -> -Q -> Q) or a load history
gap_text     -- the profile v(x) of eq. 2 in GetFEM's weak-form language
write_script -- the whole script: its header (what it models), its ``PARAMS`` and :data:`BODY`
header       -- the header alone
params_of    -- the ``PARAMS`` dictionary of a script's text (for checks)
BODY         -- the script's body (:mod:`._body`)
"""
from __future__ import annotations

import ast
from dataclasses import asdict, dataclass
from typing import Any

from ..problem.checks import check_tilt, finite, integer, poisson, positive
from ..halfplane.load_history import History, check_history
from ..problem.punch import Punch
from ..problem.validate import shear_load
from threepart.errors import InputError, InputTypeError

from ._body import BODY

__all__ = ["JobSettings", "legs", "gap_text", "write_script", "header", "params_of", "BODY"]

#: the admissible mesh in elements across the contact width W = a + c (W/h): 8 resolve the
#: stick zone at all; 512 (h = a/256 on Hertz) is past what two cores solve in minutes
W_OVER_H = (8.0, 512.0)


@dataclass(frozen=True)
class JobSettings:
    """How the GetFEM model is built and loaded.

    Attributes
    ----------
    n
        Elements across the contact width ``W = a + c`` at the contact (``h = W/n``):
        128 is the trial's ``h = a/64`` on Hertz.
    margin
        The uniform zone reaches ``margin W`` past each contact end; the contact
        multiplier lives there only.
    half_width, depth
        Each body's half-width and depth in units of ``W`` (a block ``2 half_width`` wide).
    growth
        The grid's growth factor away from the zone and below the surface layer.
    layer
        The depth of the uniform surface layer, in units of ``W``.
    r_factor
        Augmentation ``r = r_factor E / W`` (the trial's ``E/a`` is 2; ``E/h`` made Newton cycle).
    steps
        Shear steps from 0 to ``Q`` (a cycle's reversal ``Q -> -Q`` takes twice as many).
    max_iter, max_res
        Newton's iteration limit and its residual target, as a fraction of ``P``.
    min_step
        The smallest fraction of a planned step Newton may halve to before the run fails.
    lambda_degree
        Degree of the contact traction's elements (1: P1, the default; 2: P2, as accurate).
    """

    n: float = 128.0
    margin: float = 0.125
    half_width: float = 10.0
    depth: float = 10.0
    growth: float = 1.15
    layer: float = 0.125
    r_factor: float = 2.0
    steps: int = 8
    max_iter: int = 40
    max_res: float = 1e-9
    min_step: float = 1.0 / 64.0
    lambda_degree: int = 1

    def __post_init__(self) -> None:
        for name in ("margin", "half_width", "depth", "layer", "r_factor", "max_res", "min_step"):
            object.__setattr__(self, name, positive(name, getattr(self, name)))
        n = positive("n", self.n)
        if not W_OVER_H[0] <= n <= W_OVER_H[1]:
            raise InputError(f"`n` = {n:g} elements across W must lie in [{W_OVER_H[0]:g}, {W_OVER_H[1]:g}]")
        object.__setattr__(self, "n", n)
        if not 1.0 < self.growth <= 2.0:
            raise InputError(f"`growth` = {self.growth!r} must lie in (1, 2]")
        object.__setattr__(self, "steps", integer("steps", self.steps, 1, 1000))
        object.__setattr__(self, "max_iter", integer("max_iter", self.max_iter, 1, 1000))
        object.__setattr__(self, "lambda_degree", integer("lambda_degree", self.lambda_degree, 1, 2))


def legs(Q: float | None = None, Q_max: float | None = None, steps: int = 8, *, P: float = 1.0,
         s: float = 0.0, sigma_bulk: float = 0.0, history: History | None = None) -> list[dict[str, Any]]:
    """The load path after the normal load ``P`` at ``s``: each leg ``{"branch", "P", "s", "Q",
    "sigma_bulk" (its end), "steps"}``, the four moving linearly together along it.

    ``Q`` (partial slip): one leg to ``(P, s, Q, sigma_bulk)``, the bulk stress rising with
    the shear in proportion (docs/BULK_STRESS.md). ``Q_max`` (a fretting cycle
    ``0 -> Q_max -> -Q_max -> Q_max``): the bulk stress in phase, ``sigma_bulk`` at ``Q_max``,
    each reversal in ``2 steps``. ``history``: one leg to each of its states in turn, from the
    first state's normal load (``P``, ``s`` are then its first state's), ``steps`` each.
    """
    if sum(v is not None for v in (Q, Q_max, history)) != 1:
        raise InputError("give `Q` (partial slip), `Q_max` (a fretting cycle) or `history`, one of them")
    if history is not None:
        return [{"branch": f"state {k}", "P": P_k, "s": s_k, "Q": Q_k, "sigma_bulk": sb_k, "steps": steps}
                for k, (P_k, s_k, Q_k, sb_k) in enumerate(history.state(k) for k in range(len(history)))]
    end = {"P": float(P), "s": float(s)}
    if Q is not None:
        return [{"branch": "loading", **end, "Q": float(Q), "sigma_bulk": float(sigma_bulk), "steps": steps}]
    assert Q_max is not None
    sb = float(sigma_bulk)
    return [{"branch": "loading", **end, "Q": float(Q_max), "sigma_bulk": sb, "steps": steps},
            {"branch": "unloading", **end, "Q": -float(Q_max), "sigma_bulk": -sb, "steps": 2 * steps},
            {"branch": "reloading", **end, "Q": float(Q_max), "sigma_bulk": sb, "steps": 2 * steps}]


def gap_text(punch: Punch) -> str:
    """The profile ``v(x)`` of eq. 2 (at ``Delta = alpha = 0``) in GetFEM's weak-form language.

    ``kappa0 x^2/2 + kappa1 (-b - x)_+^2/2 + kappa2 (x - b)_+^2/2``: the centre's
    curvature everywhere and each flank's curvature jump past its join, which is
    eq. 2's ``(x^2 ± 2 b k_i x + b^2 k_i)/(2 R_i)`` outside ``[-b, b]``.
    """
    b = repr(float(punch.b))
    return (f"({punch.kappa0!r}*sqr(X(1))/2 + {punch.kappa1!r}*sqr(pos_part(-{b}-X(1)))/2"
            f" + {punch.kappa2!r}*sqr(pos_part(X(1)-{b}))/2)")


def header(title: str, punch: Punch, P: float, s: float, tilt: str, E: float, nu: float, f: float,
           path: list[dict[str, Any]], settings: JobSettings, a: float, c: float, name: str = "job") -> str:
    """The script's header: what it models, its units and conventions, what it writes."""
    W = a + c
    bulk = any(leg["sigma_bulk"] for leg in path)
    if any(leg["branch"].startswith("state") for leg in path):      # a load history: every state in turn
        shear = "the states (P, s, Q, sigma_bulk) in turn, the four moving linearly together:\n" + "\n".join(
            f"    {leg['branch']}: P = {leg['P']:.6g}, s = {leg['s']:.6g}, Q = {leg['Q']:.6g}, "
            f"sigma_bulk = {leg['sigma_bulk']:.6g} ({leg['steps']} steps)" for leg in path)
    else:
        shear = "the shear Q" + (" and the bulk stress sigma_bulk together, in proportion" if bulk else "") + \
            " (force control on the cap): " + " -> ".join(
                ["0"] + [f"{leg['Q']:.6g}" + (f" (sigma_bulk {leg['sigma_bulk']:.6g} MPa)" if bulk else "")
                         + f" ({leg['steps']} steps)" for leg in path])
    base = ("The substrate's base moves with the uniform\n  strain of the bulk stress (not restraining it) and "
            "its sides carry sigma_bulk: a tension\n  along x in the substrate only, the half-plane theory's "
            "(docs/BULK_STRESS.md)." if bulk else "The substrate's base is clamped.")
    return f'''"""threepart GetFEM job: {title}

What it models
  Two similar elastic bodies (E = {E:g} MPa, nu = {nu:g}, plane strain, P2 triangles): the
  substrate y <= 0 and the punch body y >= 0, its mirror image, each {2 * settings.half_width:g} W wide
  and {settings.depth:g} W deep (W = a + c = {W:.6g} mm, the half-plane theory's contact width),
  h = W/{settings.n:g} = {W / settings.n:.4g} mm over [{-a - settings.margin * W:.6g}, {c + settings.margin * W:.6g}] mm,
  growing by {settings.growth:g} away from it. {base} The punch body's
  top is a rigid cap (U_x, U_y, rotation) carrying the loads.
  The gap is the half-plane theory's: the punch profile v(x) of eq. 2 ({punch!r})
  measured along the fixed normal [0; 1] between the two surfaces y = 0.
  Coulomb friction f = {f:g} by the weak-form term Coulomb_friction_coupled_projection with a
  P{settings.lambda_degree} multiplier on the substrate's surface, augmentation r = {settings.r_factor:g} E/W.
  Loads: the normal load P = {P:.6g} N/mm at x = s = {s:g} mm (tilt {tilt}) first, then
  {shear}.
  Each step is solved by GetFEM's Newton (line search 'simplest') from the last converged
  state; a step Newton fails is halved, down to {settings.min_step:g} of it.

Conventions
  Units mm, N/mm (per unit thickness), MPa. x along the surface, y up. contact_pressure is
  compressive positive; contact_shear is the shear the punch exerts on the substrate along
  +x (its integral is Q); slip is the punch's tangential displacement relative to the
  substrate since the normal load (u2_x - u1_x).

What it writes (in the folder it runs in)
  {name}_NNN.vtu   the substrate's surface nodes over the contact zone at each recorded state
                     (one per load step)
  {name}.vtu       the last state
  {name}.getfem.json  the loads, cap displacement, resultants and fields of every state,
                     and what each Newton step needed

Run it in its folder with the interpreter that imports getfem (GetFEM 5.4): python3 {name}.py
"""
'''


def write_script(punch: Punch, P: float | None = None, s: float = 0.0, *, a: float, c: float, E: float,
                 nu: float, f: float, Q: float | None = None, Q_max: float | None = None,
                 sigma_bulk: float = 0.0, history: Any = None, tilt: str = "free",
                 settings: JobSettings | None = None, title: str = "", name: str = "job") -> str:
    """The GetFEM script of partial slip (``Q``), a fretting cycle (``Q_max``) or a load history of ``punch``.

    Parameters
    ----------
    punch
        The punch profile (eq. 2); its gap is the half-plane theory's ``v(x)``.
    P, s
        The normal load (> 0) and its lever arm (eqs. vertical, rotational); a history's are its
        first state's (``P`` None, or that state's).
    a, c
        The expected contact ends (the closed form's; a history's: the union over its states):
        they place the fine zone.
    E, nu
        The bodies' modulus and Poisson's ratio (plane strain).
    f, Q, Q_max
        The coefficient of friction and the shear (``|Q| < f P``), or a cycle's amplitude.
    sigma_bulk
        The substrate's bulk stress (tension positive) at ``Q`` (``Q_max``), rising with the shear
        in proportion after the normal load (docs/BULK_STRESS.md).
    history
        Instead of ``Q``/``Q_max``: the states ``(P, s, Q, sigma_bulk)`` in turn, each reached in
        ``settings.steps`` steps from the first state's normal load
        (:func:`threepart.halfplane.load_history.check_history`: states, a CSV path or a History).
    tilt
        ``"free"`` (the moment ``P s`` applied) or ``"suppressed"`` (the cap's rotation held).
    settings
        The mesh, the augmentation and the steps (:class:`JobSettings`).
    name
        The stem of the files the script writes.

    Raises
    ------
    ValueError
        A load, material or contact out of range, or full sliding (``FullSlidingError``).
    """
    if not isinstance(punch, Punch):
        raise InputTypeError(f"`punch` = {punch!r} must be a threepart.Punch")
    settings = JobSettings() if settings is None else settings
    hist = None if history is None else check_history(history)
    if hist is not None:
        if Q is not None or Q_max is not None or sigma_bulk:
            raise InputError("give `history` alone, or `Q`/`Q_max` with `sigma_bulk`, not both")
        if P is not None and P != hist.P[0]:
            raise InputError(f"`P` = {P!r} is not the history's first normal load {hist.P[0]!r}: give P=None")
        P, s = float(hist.P[0]), float(hist.s[0])
        for k in range(len(hist)):
            shear_load(hist.Q[k], f, float(hist.P[k]), f"history[{k}].Q")
    if P is None:
        raise InputError("give `P`, the normal load (> 0), or a `history`")
    P, E, a, c = (positive(k, v) for k, v in (("P", P), ("E", E), ("a", a), ("c", c)))
    s, nu, tilt = finite("s", s), poisson(nu), check_tilt(tilt)
    sigma_bulk = finite("sigma_bulk", sigma_bulk)
    if hist is None:
        shear = Q_max if Q is None else Q
        if shear is None:
            raise InputError("give `Q` (partial slip), `Q_max` (a fretting cycle) or a `history`")
        shear_load(shear, f, P, "Q" if Q is not None else "Q_max")
    if not name.isidentifier():
        raise InputError(f"`name` = {name!r} must be a plain file stem (letters, digits, _)")
    W = a + c
    path = legs(Q, Q_max, settings.steps, P=P, s=s, sigma_bulk=sigma_bulk, history=hist)
    params = {"name": name, "E": E, "nu": nu, "f": float(f), "P": P, "s": s, "tilt": tilt,
              "h": W / settings.n, "W": W, "zone": [-a - settings.margin * W, c + settings.margin * W],
              "half_width": settings.half_width * W, "depth": settings.depth * W,
              "growth": settings.growth, "layer": settings.layer * W, "r": settings.r_factor * E / W,
              "ktheta": 0.0 if tilt == "free" else 1e6 * E * W * W, "gap": gap_text(punch),
              "delta0": max(float(punch.profile(-a)), float(punch.profile(c))),
              "legs": path, "max_iter": settings.max_iter, "max_res": settings.max_res,
              "min_step": settings.min_step, "lsolver": "mumps",
              "lambda_degree": settings.lambda_degree, "settings": asdict(settings)}
    text = header(title or f"{punch!r}, P = {P:g}, s = {s:g}", punch, P, s, tilt, E, nu, float(f),
                  path, settings, a, c, name)
    return text + f"HEADER = __doc__\nPARAMS = {params!r}\n" + BODY


def params_of(script: str) -> dict[str, Any]:
    """The ``PARAMS`` dictionary of a script :func:`write_script` wrote (a literal, read without running it)."""
    for node in ast.parse(script).body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", "") for t in node.targets] == ["PARAMS"]:
            value = ast.literal_eval(node.value)
            assert isinstance(value, dict)
            return value
    raise InputError("the script has no `PARAMS = {...}` line")


"""The text of a GetFEM script (``job.py``): two similar elastic bodies with Coulomb friction.

Names
-----
JobSettings  -- the mesh (elements across W), the block, the augmentation, Newton's limits, the steps
legs         -- the shear path of a partial-slip run (0 -> Q) or of a fretting cycle (0 -> Q -> -Q -> Q)
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

from ..checks import check_tilt, finite, integer, poisson, positive
from ..punch import Punch
from ..validate import shear_load
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


def legs(Q: float | None = None, Q_max: float | None = None, steps: int = 8) -> list[dict[str, Any]]:
    """The shear path: ``Q`` alone (partial slip), or ``Q_max`` (a fretting cycle ``0 -> Q_max -> -Q_max -> Q_max``).

    Each leg is ``{"branch", "Q" (its end), "steps"}``; the cycle's reversals take ``2 steps``.
    """
    if (Q is None) == (Q_max is None):
        raise InputError("give `Q` (partial slip) or `Q_max` (a fretting cycle), not both nor neither")
    if Q is not None:
        return [{"branch": "loading", "Q": float(Q), "steps": steps}]
    assert Q_max is not None
    return [{"branch": "loading", "Q": float(Q_max), "steps": steps},
            {"branch": "unloading", "Q": -float(Q_max), "steps": 2 * steps},
            {"branch": "reloading", "Q": float(Q_max), "steps": 2 * steps}]


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
    shear = " -> ".join(["0"] + [f"{leg['Q']:.6g} ({leg['steps']} steps)" for leg in path])
    return f'''"""threepart GetFEM job: {title}

What it models
  Two similar elastic bodies (E = {E:g} MPa, nu = {nu:g}, plane strain, P2 triangles): the
  substrate y <= 0 and the punch body y >= 0, its mirror image, each {2 * settings.half_width:g} W wide
  and {settings.depth:g} W deep (W = a + c = {W:.6g} mm, the half-plane theory's contact width),
  h = W/{settings.n:g} = {W / settings.n:.4g} mm over [{-a - settings.margin * W:.6g}, {c + settings.margin * W:.6g}] mm,
  growing by {settings.growth:g} away from it. The substrate's base is clamped; the punch body's
  top is a rigid cap (U_x, U_y, rotation) carrying the loads.
  The gap is the half-plane theory's: the punch profile v(x) of eq. 2 ({punch!r})
  measured along the fixed normal [0; 1] between the two surfaces y = 0.
  Coulomb friction f = {f:g} by the weak-form term Coulomb_friction_coupled_projection with a
  P{settings.lambda_degree} multiplier on the substrate's surface, augmentation r = {settings.r_factor:g} E/W.
  Loads: the normal load P = {P:.6g} N/mm at x = s = {s:g} mm (tilt {tilt}) first, then the
  shear Q (force control on the cap): {shear}.
  Each step is solved by GetFEM's Newton (line search 'simplest') from the last converged
  state; a step Newton fails is halved, down to {settings.min_step:g} of it.

Conventions
  Units mm, N/mm (per unit thickness), MPa. x along the surface, y up. contact_pressure is
  compressive positive; contact_shear is the shear the punch exerts on the substrate along
  +x (its integral is Q); slip is the punch's tangential displacement relative to the
  substrate since the normal load (u2_x - u1_x).

What it writes (in the folder it runs in)
  {name}_NNN.vtu   the substrate's surface nodes over the contact zone at each recorded state
                     (one per shear step)
  {name}.vtu       the last state
  {name}.getfem.json  the loads, cap displacement, resultants and fields of every state,
                     and what each Newton step needed

Run it in its folder with the interpreter that imports getfem (GetFEM 5.4): python3 {name}.py
"""
'''


def write_script(punch: Punch, P: float, s: float = 0.0, *, a: float, c: float, E: float, nu: float,
                 f: float, Q: float | None = None, Q_max: float | None = None, tilt: str = "free",
                 settings: JobSettings | None = None, title: str = "", name: str = "job") -> str:
    """The GetFEM script of partial slip (``Q``) or a fretting cycle (``Q_max``) of ``punch``.

    Parameters
    ----------
    punch
        The punch profile (eq. 2); its gap is the half-plane theory's ``v(x)``.
    P, s
        The normal load (> 0) and its lever arm (eqs. vertical, rotational).
    a, c
        The expected contact ends (the closed form's): they place the fine zone.
    E, nu
        The bodies' modulus and Poisson's ratio (plane strain).
    f, Q, Q_max
        The coefficient of friction and the shear (``|Q| < f P``), or a cycle's amplitude.
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
    P, E, a, c = (positive(k, v) for k, v in (("P", P), ("E", E), ("a", a), ("c", c)))
    s, nu, tilt = finite("s", s), poisson(nu), check_tilt(tilt)
    shear = Q_max if Q is None else Q
    if shear is None:
        raise InputError("give `Q` (partial slip) or `Q_max` (a fretting cycle)")
    shear_load(shear, f, P, "Q" if Q is not None else "Q_max")
    if not name.isidentifier():
        raise InputError(f"`name` = {name!r} must be a plain file stem (letters, digits, _)")
    W = a + c
    path = legs(Q, Q_max, settings.steps)
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


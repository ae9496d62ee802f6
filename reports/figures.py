"""``threepart figures``: the paper's result figures, closed form with SIE markers.

Section *Results* (normal pressure) and the partial-slip section (shear
traction at Q/(fP) = 0.4) of the paper, for case A (flat centre) at the
dimensionless load ``4PA/b = 1`` with E = 210 GPa and nu = 0.3:

* set (a): the lever arm ``s/R1`` varied with ``R2/R1 = 1``;
* set (b): ``R2/R1`` varied with ``s/R1 = 0.25``.

The pressure is normalised by ``P/(2b)`` and the shear by ``f P/(2b)``, both
against ``x/b``. With ``4PA/b`` fixed the normalised curves depend only on
``b/R1``, ``R2/R1`` and ``s/R1``, not on A itself. The paper does not give
``b/R1``; ``s/R1 = 0.25`` must lie inside the lift-off range, which needs
``R1`` of the order of ``b``, so :data:`GEOMETRY` uses ``R1 = b = 1 mm`` (see
:func:`check_admissible`, which the tests run).

:func:`figure_data` returns the numbers of every curve (the figures'
"key figures", kept as regression baselines); :func:`main` draws them.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from threepart.problem.material import E_STEEL, NU as NU_DEFAULT
from threepart.problem.punch import Punch
from threepart.results import NormalResult, SlipResult

__all__ = ["main", "figure_data", "curves", "check_admissible", "Curve", "GEOMETRY", "SETS",
           "Q_OVER_FP", "F", "E", "NU"]

E, NU = E_STEEL, NU_DEFAULT       # MPa, as in the paper
F = 0.5                           # friction coefficient; the normalised shear does not depend on it
Q_OVER_FP = 0.4                   # the paper's partial-slip figure
LOAD_4PA_OVER_B = 1.0             # the paper's dimensionless load
#: b and R1 in mm (the paper gives neither; R1 = b keeps s/R1 = 0.25 inside the lift-off range)
GEOMETRY = {"b": 1.0, "R1": 1.0}
#: the two sets of curves: (label, s/R1, R2/R1)
SETS: dict[str, list[tuple[float, float]]] = {
    "a": [(s, 1.0) for s in (0.0, 0.05, 0.10, 0.15, 0.20, 0.25)],
    "b": [(0.25, r) for r in (1.0, 0.9, 0.8, 0.7, 0.6, 0.5)],
}
N_MARKERS = 25


def _A() -> float:
    """Rigid punch on the steel half-plane, 2(1 - nu^2)/E (only 4PA/b matters)."""
    return 2.0 * (1.0 - NU**2) / E


@dataclass(frozen=True)
class Curve:
    """One curve of a figure: its parameters and the solutions of both methods."""

    s_over_R1: float
    R2_over_R1: float
    punch: Punch
    P: float
    s: float
    cf: NormalResult
    sie: NormalResult | None
    cf_slip: SlipResult
    sie_slip: SlipResult | None


def _case(s_over_R1: float, R2_over_R1: float) -> tuple[Punch, float, float]:
    b, R1 = GEOMETRY["b"], GEOMETRY["R1"]
    punch = Punch(R1=R1, R2=R2_over_R1 * R1, b=b)
    P = LOAD_4PA_OVER_B * b / (4 * _A())
    return punch, P, s_over_R1 * R1


def check_admissible() -> list[str]:
    """Messages for every curve outside the closed form's range (empty: all admissible)."""
    from threepart import closedform

    problems = []
    for name, items in SETS.items():
        for sr, rr in items:
            punch, P, s = _case(sr, rr)
            lim = closedform.lift_off(punch, P, _A())
            if not lim.s_min < s < lim.s_max:
                problems.append(f"set {name}: s/R1 = {sr} outside ({lim.s_min / punch.R1:.4f}, "
                                f"{lim.s_max / punch.R1:.4f}) for R2/R1 = {rr}")
    return problems


def curves(which: str, sie: bool = True, n: int | None = None) -> list[Curve]:
    """Solve every curve of set ``which`` (``"a"`` or ``"b"``) with the closed form and the SIE."""
    from threepart import registry

    cf_method, sie_method = registry.get("closedform"), registry.get("sie")
    options = {} if n is None else {"n": n}
    out = []
    for sr, rr in SETS[which]:
        punch, P, s = _case(sr, rr)
        Q = Q_OVER_FP * F * P
        cf = cf_method.normal(punch, P, s, A=_A())
        cf_slip = cf_method.slip(punch, P, s, A=_A(), Q=Q, f=F, normal=cf)  # type: ignore[misc]
        sn = ss = None
        if sie:
            sn = sie_method.normal(punch, P, s, A=_A(), **options)
            ss = sie_method.slip(punch, P, s, A=_A(), Q=Q, f=F, normal=sn,  # type: ignore[misc]
                                 **options)
        out.append(Curve(sr, rr, punch, P, s, cf, sn, cf_slip, ss))
    return out


def figure_data(which: str, sie: bool = True) -> dict[str, list[float]]:
    """Key figures of set ``which``, one entry per curve (normalised, dimensionless).

    Keys: ``a/b``, ``c/b``, ``alpha_R1_over_b``, ``p_left``, ``p_right`` (peaks over
    P/(2b)), ``d/b``, ``e/b`` and, with ``sie``, ``sie_p_dev`` and ``sie_q_dev``,
    the largest SIE deviation from the closed form over the contact, in the
    figures' units.
    """
    b = GEOMETRY["b"]
    data: dict[str, list[float]] = {k: [] for k in ("s/R1", "R2/R1", "a/b", "c/b", "alpha_R1_over_b",
                                                    "p_left", "p_right", "d/b", "e/b")}
    if sie:
        data.update({"sie_p_dev": [], "sie_q_dev": []})
    for cv in curves(which, sie=sie):
        p0 = cv.P / (2 * b)
        left, right = cv.cf.peaks()
        data["s/R1"].append(cv.s_over_R1)
        data["R2/R1"].append(cv.R2_over_R1)
        data["a/b"].append(cv.cf.a / b)
        data["c/b"].append(cv.cf.c / b)
        data["alpha_R1_over_b"].append(cv.cf.alpha * cv.punch.R1 / b)
        data["p_left"].append(left.p / p0)
        data["p_right"].append(right.p / p0)
        data["d/b"].append(cv.cf_slip.d / b)
        data["e/b"].append(cv.cf_slip.e / b)
        if cv.sie is not None and cv.sie_slip is not None:
            # inside the contact: at its very ends one method's pressure is 0 and the other's a
            # rounding above it, which a one-ulp change of c turns into a 1e-7 "deviation"
            x = np.linspace(-cv.cf.a, cv.cf.c, 803)[1:-1]
            data["sie_p_dev"].append(float(np.max(np.abs(cv.sie.pressure(x) - cv.cf.pressure(x)))) / p0)
            data["sie_q_dev"].append(float(np.max(np.abs(cv.sie_slip.shear(x) - cv.cf_slip.shear(x))))
                                     / (F * p0))
    return data


def _draw(cs: list[Curve], which: str, field: str, path: Path) -> None:
    from .verify.plots import new_figure, save

    b = GEOMETRY["b"]
    fig, axes = new_figure(size=(7.0, 4.6))
    ax = axes[0, 0]
    colors = [f"C{i}" for i in range(len(cs))]
    for cv, col in zip(cs, colors):
        p0 = cv.P / (2 * b)
        x = np.linspace(-cv.cf.a, cv.cf.c, 1201)
        xm = np.linspace(-cv.cf.a, cv.cf.c, N_MARKERS + 2)[1:-1]
        if field == "pressure":
            y = cv.cf.pressure(x) / p0
            ym = None if cv.sie is None else cv.sie.pressure(xm) / p0
        else:
            y = cv.cf_slip.shear(x) / (F * p0)
            ym = None if cv.sie_slip is None else cv.sie_slip.shear(xm) / (F * p0)
        label = f"s/R1 = {cv.s_over_R1:g}" if which == "a" else f"R2/R1 = {cv.R2_over_R1:g}"
        ax.plot(x / b, y, color=col, lw=1.4, label=label)
        if ym is not None:
            ax.plot(xm / b, ym, ls="none", marker="o", ms=3.5, mfc="none", color=col)
    ax.plot([], [], ls="none", marker="o", mfc="none", color="0.3", label="SIE (markers)")
    for xb in (-1, 1):
        ax.axvline(xb, color="0.75", lw=0.8, ls=":")
    ax.set_xlabel("x / b")
    if field == "pressure":
        ax.set_ylabel("p / (P / 2b)")
        ttl = "normal pressure"
    else:
        ax.set_ylabel("q / (f P / 2b)")
        ttl = f"shear traction in partial slip, Q/(fP) = {Q_OVER_FP:g}"
    sub = "R2/R1 = 1, s/R1 varied" if which == "a" else "s/R1 = 0.25, R2/R1 varied"
    ax.set_title(f"({which}) {ttl}\n4PA/b = {LOAD_4PA_OVER_B:g}, E = 210 GPa, ν = 0.3, "
                 f"R1 = b; {sub}", fontsize=10)
    ax.set_ylim(bottom=0)
    ax.grid(True, color="0.92")
    ax.legend(fontsize=8, loc="upper center", ncol=2)
    save(fig, path, dpi=130)


def main(out: str | Path = "figures", force: bool = False, sie: bool = True) -> int:
    """Draw the four figures (pressure and shear, sets a and b) and their numbers into ``out``.

    Writes ``pressure_a.png``, ``pressure_b.png``, ``shear_a.png``,
    ``shear_b.png`` and ``figures.json`` atomically through
    :func:`threepart.output.atomic_dir`: ``out`` must be missing or empty, or
    figures that threepart wrote earlier and that are unchanged (replaced;
    ``force`` changes nothing); a directory holding anything else is refused
    with ``OutputExistsError`` before any work.
    Returns 0, or 1 if a curve is not admissible.
    """
    from threepart.output import atomic_dir, check_out, strict_json

    check_out(out, force, command="figures")
    problems = check_admissible()
    for p in problems:
        print(f"threepart figures: {p}")
    if problems:
        return 1
    out = Path(out)
    with atomic_dir(out, force, command="figures") as tmp:
        numbers: dict[str, Any] = {"about": __doc__.split("\n\n")[1], "geometry_mm": GEOMETRY,
                                   "E_MPa": E, "nu": NU, "4PA/b": LOAD_4PA_OVER_B,
                                   "Q/fP": Q_OVER_FP, "f": F, "sets": {}}
        for which in SETS:
            cs = curves(which, sie=sie)
            _draw(cs, which, "pressure", tmp / f"pressure_{which}.png")
            _draw(cs, which, "shear", tmp / f"shear_{which}.png")
            print(f"threepart figures: set ({which}) drawn: {len(cs)} curves")
            numbers["sets"][which] = figure_data(which, sie=sie)
        (tmp / "figures.json").write_text(strict_json(numbers, indent=1), encoding="utf-8")
    print(f"threepart figures: wrote {out}/pressure_[ab].png, shear_[ab].png, figures.json")
    return 0

"""The small-slope error of half-plane theory, measured with finite-deformation FE (CalculiX).

Half-plane theory (the paper's eqs. 1-4, and every solver in threepart) takes
the contact on the undeformed, flat surface and the strains as small. Both
fail as the surface slope ``max |v'(x)|`` over the contact grows. This
benchmark presses a stiff punch of threepart's profile (eq. 2) onto a large
elastic block in CalculiX, once geometrically linear and once with ``NLGEOM``
(finite deformation), on the same mesh with the same penalty, and reports, as
a function of the slope,

- the relative change of the peak pressure and of the contact half-width
  from the linear run to the finite-deformation run (the small-slope error);
- the linear run against threepart's closed form (the FE model's own error,
  which must stay well below the effect measured).

The model is independent of threepart's FEM (``fem/``): its own gmsh mesh,
CalculiX's CPE8 elements and node-to-surface penalty contact. Only the closed
form (``threepart.closedform.solve_normal``) is used, as the reference for the
linear run and to size the mesh and choose the loads.

The deck is built by the small functions of :mod:`threepart.calculix` (the one
home of threepart's CalculiX decks and readers) -- mesh to ``*NODE``/``*ELEMENT``
text, node sets, surfaces, material, contact, constraints, step -- and the runs
are read by :mod:`threepart.calculix.read`; this script keeps only the study.

Usage::

    python benchmarks/small_slope_calculix.py                 # Hertz, the default slopes
    python benchmarks/small_slope_calculix.py --slopes 0.02 0.1 --n-fine 200   # mesh check

It needs ``ccx`` (Debian: ``apt-get install calculix-ccx``) and exits with
status 2 and one line when ``ccx`` is missing. It is not part of the test run.
The method, the deck settings and the measured table: ``docs/SMALL_SLOPE.md``.
"""
from __future__ import annotations

import argparse
import math
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from threepart.results.fields import peak
from threepart.calculix import Material, Mesh, run_ccx
from threepart.calculix import build_half_mesh as build_mesh
from threepart.calculix import half_deck as write_deck
from threepart.calculix.read import (centre_pressure, contact_edge, element_vertices, read_descent,
                                     read_frd, read_reaction, surface_gap)
from threepart.closedform import solve_normal
from threepart.problem.punch import Punch

__all__ = ["ContactProfile", "peak_pressure", "profile", "neo_hooke", "Row", "load_for_slope", "run_case", "fit_law", "slope_at",
           "table", "main"]

# --------------------------------------------------------------------------- analysis
@dataclass(frozen=True)
class ContactProfile:
    """The contact after one CalculiX run.

    ``x`` are the block's surface nodes (deformed positions), ``p`` the
    normal stress ``-sigma_yy`` there and ``gap`` their distance up to the
    deformed punch; ``P`` the whole
    load (twice the half model's base reaction); ``peak`` the pressure at
    ``x = 0`` and ``a`` the contact's half-width.
    """

    x: np.ndarray
    p: np.ndarray
    gap: np.ndarray
    P: float
    peak: float
    a: float


def peak_pressure(x: np.ndarray, p: np.ndarray, a: float) -> float:
    """The largest pressure: ``p(0)`` by :func:`centre_pressure` when it is the largest, else the
    maximum of a parabola fitted over ``|x - x_max| < 0.1 a`` about the largest nodal value.

    A flat rounded punch (``b > 0``, case A) peaks off the centre; the fit
    smooths the nodal stresses' scatter there as the centre fit does for Hertz.
    """
    inside = np.abs(x) < a
    k = int(np.argmax(np.where(inside, p, -np.inf)))
    if abs(x[k]) < 0.3 * a:
        return centre_pressure(x, p, a)
    return peak(x, p, half_width=0.1 * a, degree=2, smooth=1, passes=1)[1]


def profile(mesh: Mesh, stem: Path) -> ContactProfile:
    """Read one run: the surface pressure, the gap to the punch, the load, peak and half-width.

    Positions are deformed (``X + u``) in both runs: CalculiX pairs the
    contact on the current surfaces even in a geometrically linear step.
    The pressure is the block's ``-sigma_yy`` at its surface nodes (Cauchy
    stress with ``NLGEOM``; at ``x = 0`` the surface normal stays vertical by
    symmetry, so it is the contact pressure there). The node-to-surface
    penalty on quadratic faces leaves the vertex nodes about 5 % above the
    midside nodes, so the peak is the mean of two fits, one over each kind.
    """
    frd = read_frd(stem)
    nb, npu = mesh.nsets["block_fine"], mesh.nsets["punch_fine"]
    xb, gap = surface_gap(mesh.xy, frd["DISP"], nb, npu, spline=False)
    p = -np.array([frd["STRESS"][n][1] for n in nb])
    vertex = element_vertices(mesh.elements["block"], nb, len(mesh.xy))
    order = np.argsort(xb)
    x, p, gap, vertex = xb[order], p[order], gap[order], vertex[order]
    a = contact_edge(x, gap)
    peak = 0.5 * (peak_pressure(x[vertex], p[vertex], a) + peak_pressure(x[~vertex], p[~vertex], a))
    P = 2 * float(read_reaction(stem)[1])
    return ContactProfile(x, p, gap, P, peak, a)


# --------------------------------------------------------------------------- the study
@dataclass(frozen=True)
class Row:
    """One load: the closed form, the linear run and the finite-deformation run.

    The linear run carries the load ``P``; the finite-deformation run is
    driven by the linear run's descent (displacement control converges in one
    increment, force control does not), so it carries a slightly different
    load ``nl.P``. Its peak and half-width are brought back to ``P`` with the
    closed form's local exponents ``s_p = dln p(0)/dln P`` and
    ``s_a = dln a/dln P`` (1/2 and 1/2 for Hertz).
    """

    slope: float
    P: float
    load: float                 # 4PA/b (case A) or P (Hertz)
    a_cf: float
    p_cf: float
    s_p: float
    s_a: float
    lin: ContactProfile
    nl: ContactProfile
    seconds: float
    nodes: int

    @property
    def nl_peak(self) -> float:
        """The finite-deformation peak at the load ``P``."""
        return self.nl.peak * (self.P / self.nl.P) ** self.s_p

    @property
    def nl_a(self) -> float:
        """The finite-deformation half-width at the load ``P``."""
        return self.nl.a * (self.P / self.nl.P) ** self.s_a

    @property
    def d_peak(self) -> float:
        """Small-slope error of the peak: NLGEOM over linear, minus 1, at the load ``P``."""
        return self.nl_peak / self.lin.peak - 1

    @property
    def d_a(self) -> float:
        """Small-slope error of the half-width: NLGEOM over linear, minus 1, at the load ``P``."""
        return self.nl_a / self.lin.a - 1

    @property
    def lin_peak(self) -> float:
        """The linear run's peak against the closed form (its own error)."""
        return self.lin.peak / self.p_cf - 1

    @property
    def lin_a(self) -> float:
        """The linear run's half-width against the closed form."""
        return self.lin.a / self.a_cf - 1

    @property
    def nl_peak_cf(self) -> float:
        """The finite-deformation peak against the closed form: half-plane theory's whole error."""
        return self.nl_peak / self.p_cf - 1

    @property
    def nl_a_cf(self) -> float:
        """The finite-deformation half-width against the closed form."""
        return self.nl_a / self.a_cf - 1


def load_for_slope(punch: Punch, slope: float, A: float) -> float:
    """Load ``P`` whose symmetric contact reaches the edge slope ``slope``.

    On the arcs ``|v'(a)| = (a - b)/R2`` (eq. 2), so ``a = b + slope R2``,
    and ``P`` is eq. (equilibrium_condition_1) at ``a = c``.
    """
    from threepart.closedform import formulas

    a = punch.b + slope * punch.R2
    return float(formulas.load(punch, a, a, A))


def _closed_form(punch: Punch, P: float, A: float) -> tuple[float, float]:
    """Closed-form half-width and peak pressure at ``P`` (at ``x = 0`` for Hertz)."""
    cf = solve_normal(punch, P, 0.0, A=A)
    x = np.linspace(-cf.a, cf.c, 20001)
    return cf.a, float(np.max(cf.pressure(x)))


def neo_hooke(deck: str, mat: Material) -> str:
    """``deck`` with the block's ``*ELASTIC`` law replaced by a compressible neo-Hookean one.

    Same small-strain ``E`` and ``nu`` (``C10 = mu/2``, ``D1 = 2/K``), another
    large-strain response: the NLGEOM run's St Venant-Kirchhoff law softens in
    compression, the neo-Hookean one stiffens. The change of the measured
    small-slope error between the two is the share of the material law.
    """
    mu, K = mat.E / (2 * (1 + mat.nu)), mat.E / (3 * (1 - 2 * mat.nu))
    old = f"*MATERIAL, NAME=BLOCK_MAT\n*ELASTIC\n{mat.E:.15g}, {mat.nu:.15g}\n"
    if old not in deck:
        raise RuntimeError("the deck has no block *ELASTIC card to replace")
    return deck.replace(old, f"*MATERIAL, NAME=BLOCK_MAT\n*HYPERELASTIC, NEO HOOKE\n"
                             f"{mu / 2:.15g}, {2 / K:.15g}\n")


def run_case(punch: Punch, slope: float, mat: Material, workdir: Path, *, n_fine: int = 300,
             penalty: float = 20.0, increments: int | None = None, law: str = "svk") -> Row:
    """Both runs at the load of edge slope ``slope``; ``h0 = a/n_fine``, ``K = penalty E/h0``.

    ``law``: the block's material in the NLGEOM run, ``"svk"`` (CalculiX's
    ``*ELASTIC`` at finite strain: St Venant-Kirchhoff) or ``"neo-hooke"``
    (:func:`neo_hooke`); the linear run is ``*ELASTIC`` either way.

    The NLGEOM step takes ``increments`` fixed increments, by default
    ``max(5, 40 slope)``: the surface slides along the punch by about a
    mesh cell per increment at most, which keeps its Newton iteration
    converging.
    """
    if increments is None:
        increments = max(5, round(40 * slope))
    P = load_for_slope(punch, slope, mat.A)
    a_cf, p_cf = _closed_form(punch, P, mat.A)
    (a_m, p_m), (a_p, p_p) = (_closed_form(punch, P * f, mat.A) for f in (1 - 1e-4, 1 + 1e-4))
    d = math.log((1 + 1e-4) / (1 - 1e-4))
    s_p, s_a = math.log(p_p / p_m) / d, math.log(a_p / a_m) / d
    h0 = a_cf / n_fine
    t0 = time.perf_counter()
    mesh = build_mesh(punch, a_cf, h0=h0, x_fine=1.3 * a_cf)
    K, sigma_inf = penalty * mat.E / h0, 1e-6 * p_cf
    stem = run_ccx(write_deck(mesh, mat, nlgeom=False, F=P / 2, K=K, sigma_inf=sigma_inf),
                   workdir, f"s{slope:g}_lin")
    lin = profile(mesh, stem)
    deck = write_deck(mesh, mat, nlgeom=True, delta=read_descent(stem), increments=increments,
                      K=K, sigma_inf=sigma_inf)
    stem = run_ccx(neo_hooke(deck, mat) if law == "neo-hooke" else deck, workdir,
                   f"s{slope:g}_nl_{law}")
    nl = profile(mesh, stem)
    load = 4 * P * mat.A / punch.b if punch.b > 0 else P
    return Row(slope, P, load, a_cf, p_cf, s_p, s_a, lin, nl, time.perf_counter() - t0, len(mesh.xy))


def fit_law(slopes: np.ndarray, errors: np.ndarray) -> tuple[float, float]:
    """``|error| = k slope^m`` fitted on logs (``np.polyfit``); returns ``(k, m)``."""
    m, logk = np.polyfit(np.log(slopes), np.log(np.abs(errors)), 1)
    return float(np.exp(logk)), float(m)


def slope_at(k: float, m: float, error: float) -> float:
    """The slope at which the fitted law ``k slope^m`` reaches ``error``."""
    return float((error / k) ** (1 / m))


def table(rows: list[Row]) -> str:
    """The results as a Markdown table (relative changes in per cent)."""
    head = ("| slope a/R or (a-b)/R2 | P (N/mm) | 4PA/b | peak NLGEOM/lin - 1 | a NLGEOM/lin - 1 "
            "| peak NLGEOM/closed form - 1 | a NLGEOM/closed form - 1 | peak lin/closed form - 1 "
            "| a lin/closed form - 1 | P_nl/P | nodes | s |\n" + "|---" * 12 + "|\n")
    out = []
    for r in rows:
        pct = [f"{100 * v:+.2f} %" for v in (r.d_peak, r.d_a, r.nl_peak_cf, r.nl_a_cf, r.lin_peak, r.lin_a)]
        load = f"{r.load:.4g}" if r.load != r.P else "-"
        out.append(f"| {r.slope:g} | {r.P:.5g} | {load} | " + " | ".join(pct)
                   + f" | {r.nl.P / r.P:.4f} | {r.nodes} | {r.seconds:.0f} |")
    return head + "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slopes", type=float, nargs="+", default=[0.02, 0.05, 0.1, 0.2, 0.3],
                        help="edge slopes |v'(a)| to run")
    parser.add_argument("--n-fine", type=int, default=100, help="elements per half-width a at the contact")
    parser.add_argument("--penalty", type=float, default=20.0, help="penalty stiffness K in E/h0")
    parser.add_argument("--increments", type=int, default=None,
                        help="increments of the NLGEOM step (default max(5, 40 slope))")
    parser.add_argument("--keep", type=Path, default=None, help="keep the decks and results here")
    parser.add_argument("--law", choices=("svk", "neo-hooke"), default="svk",
                        help="the block's law in the NLGEOM run (St Venant-Kirchhoff or neo-Hookean)")
    parser.add_argument("--case", choices=("hertz", "caseA_sym"), default="hertz",
                        help="the punch: Hertz (R = 10 mm) or the catalogue's caseA_sym "
                             "(b = 1 mm, R1 = R2 = 10 mm; slope (a - b)/R2 = 0.101 is 4PA/b = 1)")
    args = parser.parse_args(argv)
    if shutil.which("ccx") is None:
        print("small_slope_calculix: `ccx` (CalculiX) is not on the PATH; "
              "install it with `apt-get install calculix-ccx`", file=sys.stderr)
        return 2
    if args.case == "hertz":
        punch = Punch(10.0, 10.0, 0.0)    # Hertz: the peak is at x = 0
    else:
        from threepart.problem.catalogue import get_case
        punch = get_case(args.case).punch   # its peaks lie off the centre (peak_pressure)
    mat = Material()
    rows = []
    with tempfile.TemporaryDirectory(prefix="small_slope_") as tmp:
        workdir = args.keep or Path(tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        for slope in args.slopes:
            try:
                row = run_case(punch, slope, mat, workdir, n_fine=args.n_fine,
                               penalty=args.penalty, increments=args.increments, law=args.law)
            except RuntimeError as exc:          # one load that does not converge ends no study
                print(f"slope {slope:g}: {exc}", file=sys.stderr, flush=True)
                continue
            rows.append(row)
            print(f"slope {slope:g}: peak {100 * row.d_peak:+.3f} %, a {100 * row.d_a:+.3f} % "
                  f"({row.seconds:.0f} s)", file=sys.stderr, flush=True)
    print(f"{args.case}, NLGEOM law {args.law}, b = {punch.b:g} mm, R = {punch.R1:g} mm, n_fine = {args.n_fine}, K = {args.penalty:g} E/h0, "
          f"NLGEOM increments {args.increments or 'max(5, 40 slope)'}\n")
    print(table(rows))
    if len(rows) >= 2:
        s = np.array([r.slope for r in rows])
        for name, err in (("peak", [r.d_peak for r in rows]), ("a", [r.d_a for r in rows]),
                          ("peak vs closed form", [r.nl_peak_cf for r in rows])):
            k, m = fit_law(s, np.array(err))
            print(f"|{name}| ~ {k:.3g} slope^{m:.2f}: 1 % at slope {slope_at(k, m, 0.01):.3g}, "
                  f"5 % at slope {slope_at(k, m, 0.05):.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

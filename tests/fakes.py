"""Small fake solvers with a Hertz-like pressure, for testing :mod:`reports` on its own.

The fake contact is an ellipse of half-width ``h = sqrt(2 P A R1 / pi)``
centred on the lever arm ``s`` (so the centroid is ``s``); partial slip is the
Ciavarella–Jäger solution of that ellipse. The pressure is defined by the
``centre``/``half`` fields, so that ``dataclasses.replace`` of ``a``, ``c``,
``alpha``, ... perturbs only that figure. The other fields move one compared
figure each by a known normalised size (see ``tests/test_compare.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import quad

from threepart import registry
from threepart.registry import Method
from threepart.results import Diagnostics, NormalResult, Peak, SlipResult


@dataclass(frozen=True)
class FakeNormal(NormalResult):
    checks_answer = False      # a fake to test the judge with: its faults are measured, not refused
    centre: float = 0.0
    half: float = 1.0
    bump: float = 0.0          # relative pressure bump at the centre (perturbs the field only)
    peak_shift: float = 0.0    # relative shift of the reported right peak only
    left_shift: float = 0.0    # relative shift of the reported left peak only
    x_shifts: tuple[float, float] = (0.0, 0.0)   # reported peak positions moved by this fraction of W
    edge_bump: float = 0.0     # a narrow bump near the right end, of this L2 norm relative to p's

    def pressure(self, x):
        x = np.asarray(x, dtype=float)
        t = (x - self.centre) / self.half
        p0 = 2 * self.P / (math.pi * self.half)
        p = p0 * np.sqrt(np.clip(1 - t**2, 0, None))
        if self.bump:
            p = p + self.bump * p0 * np.exp(-((t / 0.05) ** 2))
        if self.edge_bump:
            # ||p||^2 = p0^2 h 4/3 and ||g||^2 = h w sqrt(pi/2) for g = exp(-((t - t0)/w)^2):
            # the bump's L2 norm is edge_bump ||p||; it lies inside the 5 % edge band (t > 0.9)
            amp = self.edge_bump * p0 * math.sqrt((4 / 3) / (EDGE_W * math.sqrt(math.pi / 2)))
            p = p + amp * np.exp(-(((t - EDGE_T) / EDGE_W) ** 2))
        return p

    def peaks(self, n: int = 2001):
        p0 = 2 * self.P / (math.pi * self.half)
        W = 2 * self.half
        return (Peak(self.centre + self.x_shifts[0] * W, p0 * (1 + self.left_shift)),
                Peak(self.centre + self.x_shifts[1] * W, p0 * (1 + self.peak_shift)))


#: where (t = (x - centre)/half) and how wide the narrow bumps of the fakes are: t = 0.95 lies in
#: the 5 % band at the right end that the interior errors leave out, and 5 widths from its edge
EDGE_T, EDGE_W = 0.95, 0.01
#: half-width of the hump at the centre that keeps ∫q dx of a perturbed shear: inside the fakes'
#: stick zone (|t| < d/h = 0.77), so that it never lifts |q| above f p
WIDE = 0.5
#: the pair of opposite shear bumps at t = ∓BUMP_T (on the 4001-point grid, in the stick zone)
BUMP_T = 0.3


def _bump(t, t0, w=EDGE_W):
    """A Gaussian of height 1: integral ``w sqrt(pi)``, squared integral ``w sqrt(pi/2)`` (in t)."""
    return np.exp(-(((t - t0) / w) ** 2))


def _hump(t, w):
    """``(1 - (t/w)^2)^2`` on ``|t| < w``: integral ``16 w / 15``, squared integral ``256 w / 315``."""
    return np.clip(1 - (t / w) ** 2, 0, None) ** 2


@dataclass(frozen=True)
class FakeSlip(SlipResult):
    checks_answer = False      # bound_bump breaks Coulomb's law on purpose, for the judge to measure
    d0: float = 1.0   # stick zone of the shear field (replace(d=...) perturbs the figure only)
    e0: float = 0.0
    bumps: float = 0.0        # opposite bumps at t = ∓BUMP_T of this fraction of max|q| (∫ unchanged)
    edge_dip: float = 0.0     # a dip near the right end of this L2 norm relative to q's (∫ unchanged)
    bound_bump: float = 0.0   # |q| above f p near the right end by this fraction of f p_max

    def shear(self, x):
        x = np.asarray(x, dtype=float)
        n = self.normal
        q = self.f * n.pressure(x)
        t = (x + self.e0) / self.d0
        p0 = 2 * n.P / (math.pi * n.half)
        q = q - self.f * p0 * (self.d0 / n.half) * np.sqrt(np.clip(1 - t**2, 0, None))
        t = (x - n.centre) / n.half
        if self.bumps:
            # max|q| = f p0 sqrt(1 - (d/h)^2), at the stick-zone ends (Ciavarella–Jäger)
            q_max = self.f * p0 * math.sqrt(1 - (self.d0 / n.half) ** 2)
            q = q + self.bumps * q_max * (_bump(t, -BUMP_T) - _bump(t, BUMP_T))
        if self.edge_dip:
            # a dip in the slip zone (|q| falls below f p), balanced by a wide rise of the same
            # integral at the centre; its L2 norm (the two hardly overlap) is edge_dip ||q||
            norm = _l2(replace(self, bumps=0.0, edge_dip=0.0, bound_bump=0.0))
            rise = EDGE_W * math.sqrt(math.pi) / (WIDE * 16 / 15)   # equal integrals
            amp = self.edge_dip * norm / math.sqrt(n.half * (EDGE_W * math.sqrt(math.pi / 2)
                                                             + rise**2 * WIDE * 256 / 315))
            q = q - amp * _bump(t, EDGE_T) + amp * rise * _hump(t, WIDE)
        if self.bound_bump:
            # balanced by a wide dip of the same integral at the centre (in the stick zone)
            amp = self.bound_bump * self.f * p0
            q = q + amp * _bump(t, EDGE_T) - amp * EDGE_W * math.sqrt(math.pi) / (WIDE * 16 / 15) * _hump(t, WIDE)
        return q



@lru_cache
def _l2(slip: FakeSlip) -> float:
    """``||q||_2`` over the contact by adaptive quadrature split at the stick-zone ends."""
    n = slip.normal
    return math.sqrt(quad(lambda u: float(slip.shear(u)) ** 2, -n.a, n.c, points=slip.stick_zone,
                          limit=200)[0])


def _normal(punch, P, s=0.0, *, A, tilt="free", method="fake", **kw):
    half = math.sqrt(2 * P * A * punch.R1 / math.pi)
    if tilt == "suppressed":
        s = 0.0
    return FakeNormal(punch=punch, A=A, a=half - s, c=half + s, alpha=0.0, P=P, s=s, tilt=tilt,
                      method=method, info=dict(kw), centre=s, half=half)


def _slip(normal, Q, f, method="fake", **kw):
    d = normal.half * math.sqrt(1 - Q / (f * normal.P))
    return FakeSlip(normal=normal, Q=Q, f=f, d=d, e=-normal.centre, method=method, info=dict(kw),
                    d0=d, e0=-normal.centre)


def _lift_off(punch, P, A):
    """The fake lift-off lever arms ``(s_min, s_max)``: half the fake contact's half-width."""
    half = math.sqrt(2 * P * A * punch.R1 / math.pi)
    return -0.5 * half, 0.5 * half


def fake_solver(method: str) -> Method:
    """A :class:`threepart.registry.Method` named ``method`` with the fake results."""
    if method == "fem":
        def fem_normal(punch, P, s, *, A, tilt="free", nu=None, mesh="quick"):
            h = {"quick": 0.04, "default": 0.01, "fine": 0.005}[mesh] if isinstance(mesh, str) else 2.0 / mesh.n
            r = _normal(punch, P, s, A=A, tilt=tilt, method="fem")
            # a small O(h^2) error so that the convergence study has something to fit
            return FakeNormal(**{**{k: getattr(r, k) for k in r.__dataclass_fields__},
                                 "a": r.a * (1 + 0.01 * h**2), "diagnostics": Diagnostics(h=h)})

        def fem_slip(punch, P, s, *, A, tilt="free", nu=None, Q, f, normal=None, mesh="quick"):
            fe = fem_normal(punch, P, s, A=A, tilt=tilt, mesh=mesh)
            return replace(_slip(fe, Q, f, method="fem", mesh=mesh), diagnostics=fe.diagnostics)

        return _as_real(Method("fem", fem_normal, fem_slip, options=("mesh",), default_nu=0.3,
                               comparison=_judged_as("fem")))

    def normal(punch, P, s, *, A, tilt="free", nu=None, n=64, scheme=None):
        return _normal(punch, P, s, A=A, tilt=tilt, method=method, n=n)

    def slip(punch, P, s, *, A, tilt="free", nu=None, Q, f, normal=None, n=64):
        return _slip(normal, Q, f, method=method, n=n)

    return _as_real(Method(method, normal, slip, options=("n", "scheme"), lift_off=_lift_off,
                           comparison=_judged_as(method)))


def _as_real(fake: Method) -> Method:
    """``fake`` with the real method's presentation and role (label, plot style, study parameter,
    framework only), which the report reads from the registry."""
    real = registry.get(fake.name)
    return replace(fake, label=real.label, style=real.style, field_color=real.field_color,
                   study=real.study, framework_only=real.framework_only)


def _judged_as(method: str):
    """The tolerance group of the real ``method``: a fake is judged as what it stands in for."""
    return registry.get(method).comparison


def install_fakes(monkeypatch, **replacements: Method) -> None:
    """Register a fake for every built-in method (or the given replacement), undone after the test."""
    for method in registry.BUILTIN:
        monkeypatch.setitem(registry._REGISTRY, method, replacements.get(method, fake_solver(method)))


#: the eight bytes every PNG file begins with
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def sketch(*args, path, **kw) -> Path:
    """A plot function's stand-in: the file at ``path`` holds a PNG's signature, nothing is drawn."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_bytes(PNG_SIGNATURE)
    return Path(path)


def unrendered(monkeypatch) -> None:
    """The verification report's plots built but not rendered, undone after the test.

    :func:`reports.verify.plots.save` (matplotlib's ``savefig`` and the palette PNG, 0.9 s a
    plot, most of a report's writing) becomes :func:`sketch`: every plot is still drawn up,
    written, listed and embedded in the page. For the tests that judge a report's verdicts, not
    its pictures; tests/test_report.py and the schema test of tests/test_compare.py render them.
    """
    from threepart.reports.verify import plots

    monkeypatch.setattr(plots, "save", lambda fig, path, dpi=None: sketch(path=path))


@dataclass(frozen=True)
class Stored:
    """``base`` whose stress field is computed once per set of points, then kept.

    The comparator (:func:`reports.compare.stress_figures`) evaluates the reference's
    stresses at points that depend on the reference alone; a test comparing one reference
    with several results computes them once. Every other attribute is ``base``'s.
    """

    base: Any
    fields: dict = field(default_factory=dict)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.base, name)

    def stress(self, x: Any, z: Any, **kw: Any) -> Any:
        x, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(z, float))
        key = (x.shape, x.tobytes(), z.tobytes(), tuple(sorted(kw.items())))
        if key not in self.fields:
            self.fields[key] = self.base.stress(x, z, **kw)
        return self.fields[key]

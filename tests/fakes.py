"""Small fake solvers with a Hertz-like pressure, for testing :mod:`reports` on its own.

The fake contact is an ellipse of half-width ``h = sqrt(2 P A R1 / pi)``
centred on the lever arm ``s`` (so the centroid is ``s``); partial slip is the
Ciavarella–Jäger solution of that ellipse. The pressure is defined by the
``centre``/``half`` fields, so that ``dataclasses.replace`` of ``a``, ``c``,
``alpha``, ... perturbs only that figure.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace

import numpy as np

from threepart import registry
from threepart.registry import Method
from threepart.results import Diagnostics, NormalResult, Peak, SlipResult


@dataclass(frozen=True)
class FakeNormal(NormalResult):
    centre: float = 0.0
    half: float = 1.0
    bump: float = 0.0          # relative pressure bump at the centre (perturbs the field only)
    peak_shift: float = 0.0    # relative shift of the reported right peak only

    def pressure(self, x):
        x = np.asarray(x, dtype=float)
        t = (x - self.centre) / self.half
        p0 = 2 * self.P / (math.pi * self.half)
        p = p0 * np.sqrt(np.clip(1 - t**2, 0, None))
        if self.bump:
            p = p + self.bump * p0 * np.exp(-((t / 0.05) ** 2))
        return p

    def peaks(self, n: int = 2001):
        p0 = 2 * self.P / (math.pi * self.half)
        return Peak(self.centre, p0), Peak(self.centre, p0 * (1 + self.peak_shift))


@dataclass(frozen=True)
class FakeSlip(SlipResult):
    d0: float = 1.0   # stick zone of the shear field (replace(d=...) perturbs the figure only)
    e0: float = 0.0

    def shear(self, x):
        x = np.asarray(x, dtype=float)
        n = self.normal
        q = self.f * n.pressure(x)
        t = (x + self.e0) / self.d0
        p0 = 2 * n.P / (math.pi * n.half)
        return q - self.f * p0 * (self.d0 / n.half) * np.sqrt(np.clip(1 - t**2, 0, None))


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
    half = math.sqrt(2 * P * A * punch.R1 / math.pi)
    return SimpleNamespace(s_min=-0.5 * half, s_max=0.5 * half)


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

        return Method("fem", fem_normal, fem_slip, options=("mesh",), default_nu=0.3)

    def normal(punch, P, s, *, A, tilt="free", nu=None, n=64, scheme=None):
        return _normal(punch, P, s, A=A, tilt=tilt, method=method, n=n)

    def slip(punch, P, s, *, A, tilt="free", nu=None, Q, f, normal=None, n=64):
        return _slip(normal, Q, f, method=method, n=n)

    return Method(method, normal, slip, options=("n", "scheme"))


def install_fakes(monkeypatch, **replacements: Method) -> None:
    """Register a fake for every built-in method (or the given replacement), undone after the test."""
    for method in registry.BUILTIN:
        monkeypatch.setitem(registry._REGISTRY, method, replacements.get(method, fake_solver(method)))

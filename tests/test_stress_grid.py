"""The grid path of ``stress`` (one rule per depth, issue 33) against the pointwise path and McEwen.

The pointwise rule grades each point's own panels; a grid's deeper rows share one
rule per depth (:mod:`threepart.stress.grid`). Both must give the same stresses
to the quadrature's accuracy, for the pressure alone and with a partial-slip
shear (kinks at the joins and the stick-zone ends), for grids laid out along
either axis; and a sliding Hertz grid must match McEwen's closed form.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import threepart.stress.flamant as st
from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.stress import stress
from threepart.stress.grid import GRID_DEPTH, is_grid

from .stress_reference import mcewen

#: a tenth of the accuracy threepart.stress promises (1e-8 of p0, docs/STRESS.md); measured 1.1e-11
GRID_VS_POINTS = 1e-9
#: the promise itself, against McEwen's closed form (as tests/test_stress.py)
TARGET = 1e-8


def _case(slip: bool):
    case = get_case("caseA_moment")
    n = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
    kw = {"pressure": n.pressure, "ends": (-n.a, n.c), "kinks": (-case.punch.b, case.punch.b)}
    if slip:
        sl = cf.solve_partial_slip(n, 0.2 * case.P, 0.5)
        lo, hi = sl.stick_zone
        kw.update(shear=sl.shear, kinks=(-case.punch.b, case.punch.b, lo, hi))
    W = n.a + n.c
    p0 = float(np.max(n.pressure(np.linspace(-n.a, n.c, 4001))))
    return kw, np.linspace(-n.a - W / 4, n.c + W / 4, 37), np.linspace(0.0, W, 23), p0


def _worst(a, b) -> float:
    return max(float(np.max(np.abs(getattr(a, k) - getattr(b, k)))) for k in ("sxx", "szz", "sxz"))


@pytest.mark.parametrize("slip", [False, True])
@pytest.mark.parametrize("rows_along", ["z", "x"])
def test_grid_path_equals_point_path(slip, rows_along):
    kw, x, z, p0 = _case(slip)
    X, Z = (x[None, :], z[:, None]) if rows_along == "z" else (x[:, None], z[None, :])
    xb, zb = np.broadcast_arrays(X, Z)
    assert is_grid(xb, zb) is not None
    grid = stress(X, Z, **kw)
    points = stress(xb.ravel(), zb.ravel(), **kw)   # a flat list of points: never a grid
    assert grid.sxx.shape == xb.shape
    flat = type(points)(x=points.x.reshape(xb.shape), z=points.z.reshape(xb.shape),
                        sxx=points.sxx.reshape(xb.shape), szz=points.szz.reshape(xb.shape),
                        sxz=points.sxz.reshape(xb.shape), nu=points.nu, rule=points.rule)
    assert _worst(grid, flat) <= GRID_VS_POINTS * p0
    np.testing.assert_array_equal(grid.x, xb)
    np.testing.assert_array_equal(grid.z, zb)


def test_sliding_hertz_grid_is_mcewen():
    """Rows from z = GRID_DEPTH W (the grid path's shallowest) to 5 a, x across and beyond the contact."""
    p = lambda t: np.sqrt(np.clip(1.0 - np.asarray(t) ** 2, 0.0, None))   # noqa: E731
    q = lambda t: 0.3 * p(t)   # noqa: E731
    x = np.linspace(-2.0, 2.0, 41)[None, :]
    z = np.geomspace(2 * GRID_DEPTH, 5.0, 15)[:, None]
    S = stress(x, z, pressure=p, shear=q, ends=(-1.0, 1.0))
    ref = mcewen(x, z, a=1.0, p0=1.0, q0=0.3)
    assert max(float(np.max(np.abs(u - v))) for u, v in zip((S.sxx, S.szz, S.sxz), ref)) <= TARGET


def test_not_a_grid():
    x = np.array([[0.0, 1.0], [0.5, 1.0]])
    z = np.array([[1.0, 1.0], [2.0, 2.0]])
    assert is_grid(x, z) is None
    assert is_grid(np.zeros(3), np.ones(3)) is None


def test_progress_lines_name_the_points_and_change_nothing(monkeypatch):
    kw, x, z, _ = _case(False)
    lines: list[str] = []
    monkeypatch.setattr(st, "PROGRESS_S", 1e-3)   # a line every millisecond, whatever this machine does
    with_lines = stress(x[None, :], z[:, None], progress=lines.append, **kw)
    without = stress(x[None, :], z[:, None], **kw)
    np.testing.assert_array_equal(with_lines.sxx, without.sxx)
    assert all(re.fullmatch(r"stress: [\d,]+ of 851 points still running \(\d+ s\)", m) for m in lines)

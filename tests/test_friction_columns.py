"""The friction referee columns of the verification run, driven by a stand-in code.

The stand-in returns the closed form's own partial slip sampled at nodes W/n apart (an independent
reference of the column's plumbing: its errors must fall with n as linear interpolation does),
and a code that is not installed gives one empty study whose note says how to install it.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from threepart.reports.referee import friction_studies as fs
from threepart.tolerances import tolerance


def _sampled(punch, P, s, Q, f, E, nu, *, n, tilt, workdir):
    assert workdir.is_dir()           # a code writes its deck there (CalculiX's run_ccx does not make it)
    ref = fs.friction_problem()["slip"]
    W = ref.a + ref.c
    x = np.arange(-1.2 * ref.a, 1.2 * ref.c, W / n)
    return SimpleNamespace(x=x, p=ref.pressure(x), q=ref.shear(x), info={"h": W / n})


@pytest.fixture
def stand_in(monkeypatch):
    table = {}
    monkeypatch.setattr(fs, "REFEREES", table)
    monkeypatch.setattr(fs, "_builtin", lambda: None)
    fs.register_referee(fs.Referee("sampled", lambda: True, _sampled, None, "", (), (100.0, 400.0)))
    fs.register_referee(fs.Referee("absent", lambda: False, None, None, "apt-get install absent", (),
                                   (1.0,)))
    return table


def test_a_column_per_code_and_its_errors_fall_with_h(stand_in):
    studies = fs.friction_studies(say=lambda m: None)
    by = {st.method: st for st in studies}
    assert set(by) == {"sampled" + fs.FRICTION_METHOD, "absent" + fs.FRICTION_METHOD}
    st = by["sampled" + fs.FRICTION_METHOD]
    d = st.errors["d"]
    assert d[-1] < d[0] and d[-1] <= tolerance("referee", "d").limit
    integral = st.errors["q_integral"]
    assert integral[-1] < integral[0] and integral[-1] <= tolerance("referee", "q_integral").limit


def test_a_code_not_installed_is_named_in_its_column(stand_in):
    st = [s for s in fs.friction_studies(say=lambda m: None) if s.method.startswith("absent")][0]
    assert not st.values and "apt-get install absent" in st.notes[0]


def test_the_columns_problem_is_mindlins():
    pr = fs.friction_problem()
    slip = pr["slip"]
    assert slip.d / slip.a == pytest.approx(np.sqrt(1 - fs.FRICTION_RATIO), rel=tolerance("wear-limit", "round_off").limit)

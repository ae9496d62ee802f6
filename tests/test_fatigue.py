"""Fretting-fatigue parameters (:mod:`threepart.fatigue`) and the ``threepart fatigue`` command.

Every check has a reference of its own: the analytic von Mises range, SWT and
Findley values of uniaxial and pure-shear histories; a brute-force scan of
10⁵ plane angles; the textbook Hertz (Cattaneo–Mindlin) shear traction, slip
amplitude and surface stress, written here from Johnson's *Contact Mechanics*
§7.1 and the Hilbert transform of ``sqrt(a² - t²)``; and a Cauchy principal
value by QUADPACK (``scipy.integrate.quad(weight="cauchy")``).
"""
from __future__ import annotations

import dataclasses
from typing import Any
import json
import math

import meshio
import numpy as np
import pytest
from scipy.integrate import quad

import threepart.fatigue as fat
from threepart import Punch
from threepart import closedform as cf
from threepart.cli import main
from threepart import registry
from threepart.registry import Method, register
from threepart.stress import Stress
from threepart.tolerances import tolerance

NU, E, K = 0.3, 2.0e5, 0.3
#: the analytic references hold to rounding: 1e-12 of the value
ROUNDING = 1e-12
#: surface stresses of the closed-form cycle come from threepart.stress's quadrature,
#: held to 1e-8 of p0 by tests/test_stress.py; 1e-7 p0 leaves it a factor 10
STRESS_QUADRATURE = 1e-7
#: a parameter of two equal states is zero: only the rounding of their difference remains
ZERO_RANGE = 1e-15
#: the 1° coarse scan alone (no zoom) falls below the brute-force maximum by more than this, of the
#: largest value: the zoom is needed, and the comparison with the scan can fail
COARSE_MISS = 1e-6
#: q, δ and q δ of the closed-form cycle against the textbook Cattaneo–Mindlin forms: rounding,
#: amplified by the cycle's superposition of states and the slip's logarithm
CYCLE_ROUNDING = 1e-10
#: a hot spot's value against the textbook's largest FFDP: σxx's quadrature (STRESS_QUADRATURE of
#: p0) relative to the σxx at the hot spot
HOT_SPOT = 1e-6
#: the textbook surface σxx against QUADPACK's Cauchy principal value of the textbook q
#: (epsabs 1e-13 p0; q has square-root kinks at ±d)
CAUCHY_PV = 1e-9
#: the printed hot spot is the CSV's largest value to 6 significant digits (``:.6g``)
PRINTED = 1e-5


def _history(sxx, szz, sxz, nu=NU):
    """A synthetic history at one point, one Stress record per state."""
    x, z = np.array([0.0]), np.array([1.0])
    return [Stress(x=x, z=z, sxx=np.array([a]), szz=np.array([b]), sxz=np.array([c]), nu=nu)
            for a, b, c in zip(sxx, szz, sxz)]


def _same_plane(theta, *expected):
    """Whether ``theta`` is one of the ``expected`` plane angles (mod π)."""
    return any(abs(math.remainder(theta - e, math.pi)) < 1e-6 for e in expected)


# ---------------------------------------------------------------------------------------
# synthetic histories with analytic parameters
# ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("mean", [0.0, 0.5])
def test_uniaxial_history_has_the_analytic_parameters(mean):
    """σxx = S (mean + amplitude sin): R = -1 (mean 0) and R = 0 (mean 0.5, amplitude 0.5)."""
    S = 100.0
    amp = 1.0 - mean
    t = np.linspace(0.0, 2 * math.pi, 41)
    h = _history(S * (mean + amp * np.sin(t)), 0 * t, 0 * t)
    lo, hi = S * (mean - amp), S * (mean + amp)
    rng = hi - lo
    # von Mises of the difference, plane strain: Δσyy = ν Δσxx
    vm = fat.von_mises_range(h).hot
    assert vm.value == pytest.approx(rng * math.sqrt(1 - NU + NU * NU), rel=ROUNDING)
    # SWT: σn,max = hi cos²θ, Δεn = (1+ν)/E rng |cos²θ - ν|, largest at θ = 0
    swt = fat.swt(h, E=E).hot
    assert swt.value == pytest.approx(hi * rng * (1 - NU * NU) / (2 * E), rel=ROUNDING)
    assert _same_plane(swt.theta, 0.0)
    # Findley: τa = rng |sin 2θ|/4, σn,max = hi cos²θ = hi (1 + cos 2θ)/2
    #   max_φ rng/4 |sin φ| + k hi/2 cos φ  =  sqrt((rng/4)² + (k hi/2)²), at tan φ = (rng/4)/(k hi/2)
    fin = fat.findley(h, k=K).hot
    u, v = rng / 4, K * hi / 2
    assert fin.value == pytest.approx(math.hypot(u, v) + K * hi / 2, rel=ROUNDING)
    phi = math.atan2(u, v)
    assert _same_plane(fin.theta, phi / 2, -phi / 2)


def test_pure_shear_history_has_the_analytic_parameters():
    T = 80.0
    t = np.linspace(0.0, 2 * math.pi, 41)
    h = _history(0 * t, 0 * t, T * np.sin(t))
    assert fat.von_mises_range(h).hot.value == pytest.approx(2 * math.sqrt(3) * T, rel=ROUNDING)
    # σn = ±T sin φ, trace 0: SWT = T (1+ν)/E 2T sin²φ / 2, largest on the 45° planes
    swt = fat.swt(h, E=E).hot
    assert swt.value == pytest.approx(T * T * (1 + NU) / E, rel=ROUNDING)
    assert _same_plane(swt.theta, math.pi / 4, 3 * math.pi / 4)
    # τ = ±T cos φ: Findley = T (|cos φ| + k |sin φ|), largest T sqrt(1 + k²) at tan φ = k
    fin = fat.findley(h, k=K).hot
    assert fin.value == pytest.approx(T * math.hypot(1, K), rel=ROUNDING)
    w = math.atan(K) / 2   # φ = ±atan k and π ± atan k
    assert _same_plane(fin.theta, w, -w, math.pi / 2 + w, math.pi / 2 - w)


def test_a_constant_stress_has_no_range():
    """Two equal states: every range is zero, SWT zero, Findley k σn,max of the largest normal stress."""
    h = _history([50.0, 50.0], [-20.0, -20.0], [10.0, 10.0])
    assert fat.von_mises_range(h).hot.value == 0.0
    assert fat.swt(h, E=E).hot.value == pytest.approx(0.0, abs=ZERO_RANGE)
    s1 = 15.0 + math.hypot(35.0, 10.0)   # the major principal stress
    assert fat.findley(h, k=K).hot.value == pytest.approx(K * s1, rel=ROUNDING)


# ---------------------------------------------------------------------------------------
# the critical plane against a brute-force scan
# ---------------------------------------------------------------------------------------
BRUTE_ANGLES = 100_000


def _brute(h, kind):
    """max over 1e5 plane angles θ in [0, π), written from the definitions (docs/FATIGUE.md)."""
    best = np.full(h.x.size, -np.inf)
    for th in np.array_split(np.linspace(0, math.pi, BRUTE_ANGLES, endpoint=False), 400):
        c, s = np.cos(th)[:, None, None], np.sin(th)[:, None, None]
        sxx, szz, sxz = h.sxx[None], h.szz[None], h.sxz[None]
        sn = sxx * c * c + szz * s * s + 2 * sxz * s * c          # n·σ·n, n = (cos θ, sin θ)
        tau = (szz - sxx) * s * c + sxz * (c * c - s * s)         # t·σ·n, t = (-sin θ, cos θ)
        if kind == "swt":
            eps = ((1 - NU * NU) * (sxx * c * c + szz * s * s) - NU * (1 + NU) * (sxx * s * s + szz * c * c)
                   + 2 * (1 + NU) * sxz * s * c) / E            # εxx c² + εzz s² + 2 εxz s c
            val = sn.max(1) * (eps.max(1) - eps.min(1)) / 2
        else:
            val = (tau.max(1) - tau.min(1)) / 2 + K * sn.max(1)
        best = np.maximum(best, val.max(0))
    return best


@pytest.fixture(scope="module")
def random_history():
    rng = np.random.default_rng(20261123)
    m, n = 10, 30
    x, z = rng.uniform(size=n), rng.uniform(size=n)
    return fat.History.from_stresses([Stress(x=x, z=z, sxx=rng.normal(size=n), szz=rng.normal(size=n),
                                             sxz=rng.normal(size=n), nu=NU) for _ in range(m)])


@pytest.mark.parametrize("kind", ["swt", "findley"])
def test_critical_plane_matches_a_brute_force_scan(random_history, kind, monkeypatch):
    """Ours never falls below the 1e5-angle scan, nor exceeds it by more than its step allows.

    The scan's step in φ = 2θ is 2π/1e5 = 6.3e-5; a maximum at a kink of the max over
    states, slope |dF/dφ| <= 2 max|F|, is missed by at most |F'| step/2 = 6.3e-5 max|F|.
    Without the zoom (ZOOM_LEVELS = 0, the 1° coarse scan alone) the lower bound fails.
    """
    h = random_history
    call = (lambda g: fat.swt(g, E=E)) if kind == "swt" else (lambda g: fat.findley(g, k=K))
    ref = _brute(h, kind)
    scale = float(np.max(np.abs(ref)))
    ours = call(h)
    assert np.all(ours.value >= ref - ROUNDING * scale), np.min(ours.value - ref) / scale
    assert np.all(ours.value <= ref + 2 * math.pi / BRUTE_ANGLES * scale), np.max(ours.value - ref) / scale
    # the angle returned is where the value is reached: the brute force formula there
    at = fat.History(h.x, h.z, h.sxx, h.szz, h.sxz, h.nu, h.Q, h.branch)
    th = ours.theta
    c, s = np.cos(th), np.sin(th)
    sn = h.sxx * c * c + h.szz * s * s + 2 * h.sxz * s * c
    tau = (h.szz - h.sxx) * s * c + h.sxz * (c * c - s * s)
    if kind == "swt":
        eps = (1 + NU) / E * (sn - NU * (at.sxx + at.szz))
        there = sn.max(0) * (eps.max(0) - eps.min(0)) / 2
    else:
        there = (tau.max(0) - tau.min(0)) / 2 + K * sn.max(0)
    assert np.allclose(there, ours.value, rtol=0, atol=ROUNDING * scale)
    monkeypatch.setattr(fat.functions, "ZOOM_LEVELS", 0)
    coarse = call(h)
    assert np.min(coarse.value - ref) < -COARSE_MISS * scale   # the coarse scan alone misses: the test can fail


# ---------------------------------------------------------------------------------------
# Ruiz on a Hertz (Cattaneo–Mindlin) fretting cycle, against the textbook closed forms
# ---------------------------------------------------------------------------------------
R, P, A, F, Q_MAX = 10.0, 100.0, 1.7e-4, 0.5, 20.0


def _root(u):
    return np.sqrt(np.clip(u, 0.0, None))


def hertz(x):
    """Textbook Hertz / Cattaneo–Mindlin figures at the surface points ``x``, at Q_max (Q > 0).

    ``a² = 2 A P R/π``, ``p0 = 2P/(π a)``, ``d = a sqrt(1 - Q/(fP))``;
    ``q = (f p0/a) [sqrt(a² - x²) - sqrt(d² - x²)]`` (Johnson eq. 7.8, with the
    sign of Q: the punch drags the substrate along +x);
    the slip amplitude (the slip at Q_max on loading) from
    ``ds/dx = A (1/π) PV∫ q/(t - x) dt = -(f p0/a) sgn(x) sqrt(x² - d²)`` in the slip zones:
    ``δ = (A f p0/(2a)) [|x| sqrt(x² - d²) - d² ln((|x| + sqrt(x² - d²))/d)]``;
    the surface σxx at Q_max, ``-p + (2/π) PV∫ q/(t - x) dt``, from
    ``(1/π) PV∫ sqrt(a² - t²)/(t - x) dt = -x`` inside: ``-p - 2 (f p0/a) sgn(x) sqrt(x² - d²)``.
    """
    a = math.sqrt(2 * A * P * R / math.pi)
    p0 = 2 * P / (math.pi * a)
    d = a * math.sqrt(1 - Q_MAX / (F * P))
    ax = np.abs(x)
    inside = ax < a
    p = p0 * _root(1 - x * x / (a * a))
    q = F * p0 / a * (_root(a * a - x * x) - _root(d * d - x * x))
    L = _root(x * x - d * d)
    slip = inside & (ax > d)
    delta = np.where(slip, A * F * p0 / (2 * a) * (ax * L - d * d * np.log(np.where(slip, (ax + L) / d, 1.0))), 0.0)
    sxx = -p - 2 * F * p0 / a * np.sign(x) * L * inside
    return dict(a=a, p0=p0, d=d, p=p, q=q, delta=delta, sxx_Qmax=sxx)


@pytest.fixture(scope="module")
def hertz_cycle():
    normal = cf.solve_normal(Punch(R1=R, R2=R, b=0.0), P, 0.0, A=A)
    return cf.fretting_cycle(normal, Q_MAX, F, states=5)


@pytest.fixture(scope="module")
def surface(hertz_cycle):
    a = hertz(0.0)["a"]
    x = np.linspace(-0.995 * a, 0.995 * a, 41)   # inside the contact, ends excluded
    return x, fat.stress_history(hertz_cycle, x, np.zeros_like(x))


def test_ruiz_on_hertz_matches_cattaneo_mindlin(hertz_cycle, surface):
    x, h = surface
    ref = hertz(x)
    r = fat.ruiz(hertz_cycle, h)
    p0 = ref["p0"]
    assert np.max(np.abs(r.q - ref["q"])) <= CYCLE_ROUNDING * F * p0
    assert np.max(np.abs(r.delta - ref["delta"])) <= CYCLE_ROUNDING * np.max(ref["delta"])
    # over the whole cycle the largest σxx is the tension of ±Q_max, mirrored: -p + 2(f p0/a) sqrt(x² - d²)
    sxx_max = np.maximum(-ref["p"] + 2 * F * p0 / ref["a"] * _root(x * x - ref["d"] ** 2), 0.0)
    assert np.max(np.abs(r.sxx_max - sxx_max)) <= STRESS_QUADRATURE * p0
    scale = p0 * F * p0 * np.max(ref["delta"])
    assert np.max(np.abs(r.ffdp.value - sxx_max * ref["q"] * ref["delta"])) <= STRESS_QUADRATURE * scale
    assert np.max(np.abs(r.fdp.value - ref["q"] * ref["delta"])) <= CYCLE_ROUNDING * F * p0 * np.max(ref["delta"])
    # the hot spot lies in a slip zone, near an edge, where all three factors are non-zero
    hot = r.ffdp.hot
    assert ref["d"] < abs(hot.x) < ref["a"] and hot.z == 0.0
    assert hot.value == pytest.approx(float(np.max(sxx_max * ref["q"] * ref["delta"])), rel=HOT_SPOT)


def test_the_surface_tension_peaks_at_the_trailing_edge_x_minus_a(hertz_cycle, surface):
    """Q > 0 drags the substrate along +x: on loading, the surface tension peaks at x = -a.

    The reference σxx = -p + (2/π) PV∫ q(t)/(t - x) dt is integrated here by QUADPACK's
    Cauchy rule over the textbook q; a flipped sign of Q (or of q) moves every peak
    below to x > 0.
    """
    x, h = surface
    ref = hertz(x)
    a, p0 = ref["a"], ref["p0"]
    q = lambda t: float(hertz(np.array([t]))["q"][0])   # noqa: E731
    for xi in (-0.9 * a, -0.5 * a, 0.3 * a, 0.95 * a):
        pv = quad(q, -a, a, weight="cauchy", wvar=xi, epsabs=1e-13 * p0, limit=200)[0]
        assert float(hertz(np.array([xi]))["sxx_Qmax"][0]) == pytest.approx(
            -float(hertz(np.array([xi]))["p"][0]) + 2 / math.pi * pv, abs=CAUCHY_PV * p0)
    loading = np.flatnonzero(hertz_cycle.branch == "loading")
    sub = fat.stress_history(hertz_cycle, x, np.zeros_like(x), states=loading)
    at_qmax = sub.sxx[int(np.argmax(sub.Q))]
    assert np.max(np.abs(at_qmax - ref["sxx_Qmax"])) <= STRESS_QUADRATURE * p0
    assert x[int(np.argmax(at_qmax))] < -ref["d"]                      # the trailing edge
    r = fat.ruiz(hertz_cycle, sub)
    assert -a < r.ffdp.hot.x < -ref["d"] and r.ffdp.value[x > 0].max() == 0.0
    # the σxx-driven parameters of the loading branch peak at the trailing edge too
    # (not the von Mises range: the difference of two loading states is their shear parts
    # alone, whose magnitude is mirror-symmetric for Hertz)
    assert fat.swt(sub, E=E).hot.x < -ref["d"]


def test_bad_input_is_refused_by_name(hertz_cycle, surface):
    x, h = surface
    with pytest.raises(ValueError, match=r"`E` = -1 must be > 0"):
        fat.swt(h, E=-1)
    with pytest.raises(ValueError, match=r"`k` = -0.1 must lie in \[0, 10\]"):
        fat.findley(h, k=-0.1)
    with pytest.raises(ValueError, match=r"`z` = -1.0 must be >= 0"):
        fat.stress_history(hertz_cycle, [0.0], [-1.0])
    with pytest.raises(ValueError, match=r"`states` selects 1 distinct state"):
        fat.stress_history(hertz_cycle, [0.0], [0.1], states=[3, 3])
    with pytest.raises(ValueError, match=r"`states\[0\]` = 99 must lie in"):
        fat.stress_history(hertz_cycle, [0.0], [0.1], states=[99, 1])
    with pytest.raises(TypeError, match=r"`cycle` must be a FrettingResult"):
        fat.stress_history(hertz_cycle.normal, [0.0], [0.1])
    with pytest.raises(ValueError, match=r"`nu` = 0.7 must lie in"):
        fat.stress_history(hertz_cycle, [0.0], [0.1], nu=0.7)
    with pytest.raises(ValueError, match="no surface point"):
        fat.ruiz(hertz_cycle, fat.History.from_stresses(_history([1.0, 2.0], [0, 0], [0, 0])))


# ---------------------------------------------------------------------------------------
# the command line
# ---------------------------------------------------------------------------------------
CLI_E, CLI_NU = 210_000.0, 0.3
ARGS = ["fatigue", "--R1", "10", "--R2", "10", "--b", "0", "--E", str(CLI_E), "--nu", str(CLI_NU),
        "--P", "100", "--Q-max", "20", "--f", "0.5", "--nx", "11", "--nz", "4", "--states", "3", "--ns", "21"]


def _err(capsys):
    cap = capsys.readouterr()
    assert cap.err.count("\n") == 1 and cap.err.startswith("threepart fatigue: error: "), cap.err
    assert "Traceback" not in cap.err
    return cap.err


def _cli_hertz(x):
    """:func:`hertz` for the command line's material: A = 4 (1 - ν²)/E."""
    global A
    saved, A = A, 4 * (1 - CLI_NU ** 2) / CLI_E
    try:
        return hertz(x)
    finally:
        A = saved


def test_cli_writes_csv_vtu_png_and_prints_the_hot_spots(capsys, tmp_path):
    csv, vtu, png = tmp_path / "f.csv", tmp_path / "f.vtu", tmp_path / "f.png"
    assert main([*ARGS, "--csv", str(csv), "--vtu", str(vtu), "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert text.startswith("method: closedform")
    for label, unit in [("von Mises range", "MPa"), ("SWT (critical plane)", "MPa"),
                        ("Findley (critical plane)", "MPa"), ("Ruiz FFDP", "MPa^2 mm"),
                        ("Ruiz FDP", "MPa mm")]:
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(label))
        assert f" {unit}  at x = " in line and "z = " in line
    rows = csv.read_text().splitlines()
    head = rows[0].split(",")
    assert head[:3] == ["x [mm]", "z [mm]", "von_mises_range [MPa]"] and len(rows) == 1 + 11 * 4
    table = [r.split(",") for r in rows[1:]]
    x = np.array([float(r[0]) for r in table])
    z = np.array([float(r[1]) for r in table])
    ffdp = [(xi, float(r[-1])) for xi, zi, r in zip(x, z, table) if zi == 0.0]
    assert len(ffdp) == 11 and all(r[-1] == "" for zi, r in zip(z, table) if zi > 0)
    # Ruiz's FFDP on the surface row against the textbook Hertz cycle (the CLI's A = 4(1-ν²)/E)
    xs = np.array([v[0] for v in ffdp])
    ref = _cli_hertz(xs)
    sxx_max = np.maximum(-ref["p"] + 2 * F * ref["p0"] / ref["a"] * _root(xs * xs - ref["d"] ** 2), 0.0)
    want = sxx_max * ref["q"] * ref["delta"]
    got = np.array([v[1] for v in ffdp])
    assert np.max(np.abs(got - want)) <= STRESS_QUADRATURE * np.max(want) and np.max(want) > 0
    # the VTU holds the same grid and fields
    mesh = meshio.read(vtu)
    assert mesh.points.shape == (44, 3) and np.allclose(mesh.points[:, 1], -z)
    vm_col = np.array([float(r[2]) for r in table])
    assert np.array_equal(mesh.point_data["von_mises_range"], vm_col)
    assert mesh.cells_dict["quad"].shape == (10 * 3, 4)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the printed hot spot is the largest value in the CSV
    vm_line = next(ln for ln in text.splitlines() if ln.strip().startswith("von Mises range"))
    assert float(vm_line.split()[3]) == pytest.approx(vm_col.max(), rel=PRINTED)


@pytest.mark.parametrize("extra,match", [
    (["--nu", "0.7"], r"`nu` = 0.7 must lie in \(-1, 0.5\)"),
    (["--E", "-5"], r"`--E` = -5.0 must be > 0"),
    (["--k", "-1"], r"`k` = -1.0 must lie in \[0, 10\]"),
    (["--nx", "1"], r"`--nx` = 1 must lie in \[2, "),
    (["--depth", "0"], r"`--depth` = 0.0 must be > 0"),
    (["--ns", "1"], r"`--ns` = 1 must lie in \[2, "),
    (["--Q-max", "60"], r"\|`Q_max`\| = 60 >= f P = 50"),
    (["--sigma-bulk", "nan"], r"`--sigma-bulk` = nan"),
])
def test_cli_refuses_bad_input_in_one_line(capsys, extra, match):
    import re

    assert main([*ARGS, *extra]) == 2
    assert re.search(match, _err(capsys))


def test_cli_never_overwrites_a_foreign_file(capsys, tmp_path):
    mine = tmp_path / "notes.csv"
    mine.write_text("my own notes\n")
    assert main([*ARGS, "--csv", str(mine)]) == 2
    assert "--csv" in _err(capsys) and mine.read_text() == "my own notes\n"
    vtu = tmp_path / "mine.vtu"
    vtu.write_text("<xml/>")
    assert main([*ARGS, "--vtu", str(vtu), "--plot", str(tmp_path / "new.png")]) == 2
    assert "--vtu" in _err(capsys) and vtu.read_text() == "<xml/>"
    assert not (tmp_path / "new.png").exists()   # refused before anything was computed or written


def _toy_fretting(bulk: bool):
    """A method whose cycle is the closed form's, taking ``sigma_bulk`` (or not)."""
    def fretting(punch, P, s, *, A, tilt="free", nu=None, Q_max, f, states=None, normal=None,
                 **kw):
        if kw and not bulk:
            raise TypeError(f"fretting() got an unexpected keyword argument {next(iter(kw))!r}")
        base = cf.solve_normal(punch, P, s, A=A, tilt=tilt)
        return _bulked(cf.fretting_cycle(base, Q_max, f, states=states), kw.get("sigma_bulk", 0.0))
    return fretting


def _bulked(cycle: Any, S: float) -> Any:
    """``cycle`` whose substrate carries ``S Q/Q_max`` on top of σxx, its tractions unchanged.

    (The closed form's own ``sigma_bulk`` also moves the stick zones; this toy only adds
    the bulk term to σxx, so that the expected FFDP is the cycle's own plus ``S q δ``.)
    """
    class Bulked(type(cycle)):
        def stress(self, x, z, Q, branch, *, nu=0.3):
            st = super().stress(x, z, Q, branch, nu=nu)
            return dataclasses.replace(st, sxx=st.sxx + S * Q / self.Q_max)

    return Bulked(**{f.name: getattr(cycle, f.name) for f in dataclasses.fields(cycle)})


def test_cli_passes_sigma_bulk_to_the_method_or_refuses_in_one_line(capsys, monkeypatch):
    """``--sigma-bulk`` reaches a method that takes it; one that does not is named, exit 2.

    The bulk tension adds S Q/Q_max to σxx (in phase with Q), so at the trailing
    edge, where σxx peaks at +Q_max, the tensile factor of Ruiz's FFDP grows by S
    there and the hot spot moves to x < 0 (the cycle alone is mirror-symmetric).
    """
    monkeypatch.setattr(registry, "_REGISTRY", dict(registry._REGISTRY))   # for this test only
    register(Method("bulk_toy", cf.solve_normal, fretting=_toy_fretting(True)))
    register(Method("nobulk_toy", cf.solve_normal, fretting=_toy_fretting(False), bulk_stress=False))
    S = 300.0
    assert main([*ARGS, "--method", "bulk_toy", "--sigma-bulk", str(S), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    hot = out["hot_spots"]["ruiz_ffdp"]
    ref = _cli_hertz(np.array([hot["x"]]))
    assert -ref["a"] < hot["x"] < -ref["d"]
    want = (ref["sxx_Qmax"] + S) * ref["q"] * ref["delta"]
    assert hot["value"] == pytest.approx(float(want[0]), rel=HOT_SPOT)
    assert main([*ARGS, "--method", "nobulk_toy", "--sigma-bulk", str(S)]) == 2
    assert "`--sigma-bulk` = 300: method 'nobulk_toy' does not take a bulk stress" in _err(capsys)


def test_any_method_s_cycle_gives_the_same_parameters_sie_against_closed_form():
    """The module asks nothing of a method but the shared interface: the SIE's Hertz cycle gives
    the closed form's four parameters, to the table's SIE shear tolerance, and the same hot
    spots (mirror-image ties broken alike, HOT_SPOT_TIE)."""
    from threepart.tolerances import tolerance

    limit = tolerance("sie", "q_states").limit
    out = {}
    for name in ("closedform", "sie"):
        cycle = registry.get(name).fretting(Punch(R1=R, R2=R, b=0.0), P, 0.0, A=A, Q_max=Q_MAX, f=F,
                                            states=3)
        a = cycle.normal.a
        x, z = np.linspace(-1.25 * a, 1.25 * a, 7)[None, :], np.linspace(0.0, 2 * a, 3)[:, None]
        line = -a + 2 * a * (np.arange(21) + 0.5) / 21
        out[name] = fat.fatigue(cycle, x, z, E=E, nu=NU, surface=np.union1d(x, line))
    ref, sie = out["closedform"], out["sie"]
    for got, want in [(sie.von_mises_range, ref.von_mises_range), (sie.swt, ref.swt),
                      (sie.findley, ref.findley), (sie.ruiz.fdp, ref.ruiz.fdp),
                      (sie.ruiz.ffdp, ref.ruiz.ffdp)]:
        scale = float(np.max(np.abs(want.value)))
        assert np.max(np.abs(got.value - want.value)) <= limit * scale, got.name
        assert (got.hot.x, got.hot.z) == (want.hot.x, want.hot.z), got.name


def test_the_report_uses_the_case_s_own_modulus_not_the_similar_pair_of_its_compliance():
    """The catalogue's A of a case with a material is a rigid punch's, 2(1 - ν²)/E: reading it as a
    similar pair's, 4(1 - ν²)/A, doubled the E behind every SWT value of the report."""
    from threepart import rigid_punch
    from threepart.reports.verify.stress import fatigue_hot_spots

    E, nu = 115e3, 0.32                                   # the fan-blade flank's Ti-6Al-4V
    normal = cf.solve_normal(Punch(10.0, 5.0, 1.0), 400.0, 0.1, A=rigid_punch(E=E, nu=nu))
    cycle = cf.fretting_cycle(normal, 80.0, 0.5, states=9)
    got = fatigue_hot_spots({"closedform": cycle}, (E, nu), "closedform")
    assert (got["E"], got["nu"]) == (E, nu)


# --- the flight cycle at the command line (issue 31): --state0 and --state1 ---------------------
FLIGHT_BASE = ["fatigue", "--R1", "10", "--R2", "5", "--b", "1", "--E", str(CLI_E), "--nu", str(CLI_NU),
               "--f", "0.5", "--nx", "11", "--nz", "4", "--ns", "21", "--json"]


def test_a_flight_cycle_at_constant_load_is_the_fretting_cycle_at_the_command_line(capsys):
    """At P and s constant the steady cycle between -Q_max and Q_max is the fretting cycle's (eq. S14):
    the hot spots of ``--state0/--state1`` are those of ``--P --Q-max`` on the same grid."""
    assert main([*FLIGHT_BASE, "--state0", "400,0.1,-80,0", "--state1", "400,0.1,80,0"]) == 0
    flight = json.loads(capsys.readouterr().out)
    assert main([*FLIGHT_BASE, "--P", "400", "--s", "0.1", "--Q-max", "80", "--states", "2"]) == 0
    fretting = json.loads(capsys.readouterr().out)
    assert flight["shakedown"] is False and flight["energy"] > 0
    # the flight cycle's two load states and the count of distinct stress states are two keys
    assert flight["states"] == [[400, 0.1, -80, 0], [400, 0.1, 80, 0]] and flight["stress_states"] == 2
    for name, spot in fretting["hot_spots"].items():
        got = flight["hot_spots"][name]
        assert (got["x"], got["z"]) == (spot["x"], spot["z"]), name
        assert abs(got["value"] - spot["value"]) <= tolerance("flight", "fatigue").limit * abs(spot["value"]), name


@pytest.mark.parametrize("extra, match", [
    (["--state0", "400,0.1,-80,0"], r"a flight cycle needs both ends: `--state1` is missing"),
    (["--state0", "400,0.1,-80,0", "--state1", "400,0.1,80,0", "--P", "400"],
     r"give a fretting cycle .* or a flight cycle's ends .*, not both"),
    (["--P", "400"], r"give `--Q-max` \(a fretting cycle\), or `--state0` and `--state1`"),
    (["--state0", "400,0.1", "--state1", "400,0.1,80,0"], r"must be 4 numbers P,s,Q,sigma_bulk"),
])
def test_a_flight_cycle_s_bad_input_is_one_line(capsys, extra, match):
    import re

    assert main([*FLIGHT_BASE, *extra]) == 2
    assert re.search(match, _err(capsys))

"""The half-plane stress field (threepart.stress) against references that owe nothing to it.

References: Flamant's point loads in polar form (Johnson eqs. 2.15, 2.19), the Hertz
axis formulas (Johnson eq. 4.47 in the line-contact form), McEwen's closed form of a
sliding Hertz line contact (Johnson eqs. 7.17–7.18), the surface tractions themselves,
scipy's QUADPACK Cauchy-weight principal value, global equilibrium, and the paper's
eq. (integral_equation) for the catalogue's case A.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from threepart import closedform as cf
from threepart.problem.catalogue import get_case
from threepart.stress import Stress, flamant_normal, flamant_tangential, hilbert, stress

from .stress_reference import mcewen as _mcewen

#: the accuracy the module promises, as a fraction of p0 = max p, at every depth
TARGET = 1e-8
#: Flamant's kernels against their polar form: rounding of a few operations
KERNEL = 1e-13
#: Hertz on the axis z > 0 against its closed form (McEwen), of p0: the quadrature's own error
AXIS = 1e-9
#: equilibrium of a line at depth z (Hertz, Gauss rule to L = 2000): truncation ~1e-11 P (docstring)
EQUILIBRIUM = 1e-9
#: as EQUILIBRIUM under caseA_moment's partial slip: the load's centroid adds up to 1e-7 Q (docstring)
TRUNCATED = 2e-7

A_H, P0, F = 1.0, 1.0, 0.3     # Hertz half-width, peak pressure, friction coefficient (McEwen)


def p_hertz(t):
    return P0 * np.sqrt(np.clip(1.0 - (np.asarray(t) / A_H) ** 2, 0.0, None))


def q_hertz(t):
    return F * p_hertz(t)


def mcewen(x, z):
    """McEwen's stresses for this file's Hertz contact (half-width A_H, peak P0, q = F p)."""
    return _mcewen(x, z, a=A_H, p0=P0, q0=F * P0)


def worst(S: Stress, ref) -> float:
    return max(float(np.max(np.abs(u - v))) for u, v in zip((S.sxx, S.szz, S.sxz), ref))


# --- Flamant ----------------------------------------------------------------------------------

@pytest.mark.parametrize("load", ["normal", "tangential"])
def test_narrow_strip_is_flamant_point_load(load):
    """A strip of width eps carrying P (or Q) is Flamant's point load at r >> eps, to O((eps/r)^2)."""
    eps, P = 1e-3, 2.0
    uniform = lambda t: np.full(np.shape(t), P / eps)        # noqa: E731
    zero = lambda t: np.zeros(np.shape(t))                   # noqa: E731
    theta = np.linspace(-1.4, 1.4, 15)                      # from the depth axis, toward +x
    r = 0.05
    x, z = r * np.sin(theta), r * np.cos(theta)
    kw = {"pressure": uniform} if load == "normal" else {"pressure": zero, "shear": uniform}
    S = stress(x, z, ends=(-eps / 2, eps / 2), **kw)
    trig = np.cos(theta) if load == "normal" else np.sin(theta)
    sr = -2 * P / math.pi * trig / r                        # radial, the only stress (Johnson 2.15, 2.19)
    # Cartesian components of a purely radial stress, radial direction (sin θ, cos θ)
    ref = (sr * np.sin(theta) ** 2, sr * np.cos(theta) ** 2, sr * np.sin(theta) * np.cos(theta))
    scale = 2 * P / (math.pi * r)
    assert worst(S, ref) <= 3 * (eps / r) ** 2 * scale, worst(S, ref) / scale


def test_flamant_kernels_are_radial():
    """The Cartesian kernels against the polar σr = -(2/π) cos θ/r (normal) and -(2/π) sin θ/r
    (tangential along +x), σθ = τrθ = 0, rotated with the radial direction (sin θ, cos θ)."""
    theta = np.linspace(-1.5, 1.5, 31)
    r = np.array([[0.01], [1.0], [50.0]])
    s, z = r * np.sin(theta), r * np.cos(theta)
    for kernel, trig in ((flamant_normal, np.cos(theta)), (flamant_tangential, np.sin(theta))):
        sr = -2 / math.pi * trig / r
        ref = (sr * np.sin(theta) ** 2, sr * np.cos(theta) ** 2, sr * np.sin(theta) * np.cos(theta))
        for got, want in zip(kernel(s, z), ref):
            assert np.allclose(got, want, rtol=KERNEL, atol=KERNEL * np.abs(sr).max())


# --- Hertz and McEwen -------------------------------------------------------------------------

def test_hertz_axis():
    """σzz(0, z) = -p0 a/√(a²+z²), σxx(0, z) = -(p0/a)[(a²+2z²)/√(a²+z²) - 2z], σxz = 0 (Johnson 4.47)."""
    z = np.logspace(-6, 1, 36) * A_H
    S = stress(0.0, z, pressure=p_hertz, ends=(-A_H, A_H))
    root = np.sqrt(A_H ** 2 + z ** 2)
    ref = (-(P0 / A_H) * ((A_H ** 2 + 2 * z ** 2) / root - 2 * z), -P0 * A_H / root, 0 * z)
    assert worst(S, ref) <= AXIS * P0


def test_mcewen_everywhere():
    """Sliding Hertz contact, q = f p along +x: McEwen's closed form to 1e-8 p0, shallow points and
    beyond the edges included."""
    x = np.concatenate([np.linspace(-2.5, 2.5, 41) + 1e-3, [-1, 1, -1 - 1e-6, 1 + 1e-6, -1 + 1e-7, 0.999999]])
    z = np.array([1e-7, 1e-6, 1e-4, 1e-2, 0.1, 0.3, 1.0, 3.0, 10.0])
    S = stress(x[:, None], z[None, :], pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H), nu=0.3)
    assert S.sxx.shape == (x.size, z.size)
    assert worst(S, mcewen(x[:, None], z[None, :])) <= TARGET * P0


def test_mcewen_random_points():
    """2000 seeded random points: 20 % on the surface, depths 1e-9 to 10 a, and 10 % within
    1e-10 to 0.1 a of a contact end, where the grading must go deepest."""
    rng = np.random.default_rng(2)
    N = 2000
    x = rng.uniform(-3, 3, N) * A_H
    z = np.where(rng.random(N) < 0.2, 0.0, 10 ** rng.uniform(-9, 1, N)) * A_H
    x[:200] = rng.choice([-1, 1], 200) * A_H * (1 + rng.choice([-1, 1], 200) * 10 ** rng.uniform(-10, -1, 200))
    S = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    assert worst(S, mcewen(x, z)) <= TARGET * P0


def test_mcewen_at_the_surface():
    """z = 0: McEwen's surface values, in and outside the contact (σxx = -p - 2 q0 x/a inside)."""
    x = np.array([-3.0, -1.2, -0.9, -0.3, 0.0, 0.5, 0.99, 1.0001, 2.0])
    S = stress(x, 0.0, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    assert worst(S, mcewen(x, 0 * x)) <= TARGET * P0


# --- the surface ------------------------------------------------------------------------------

def surface_reference(x, p, q, lo, hi, breaks):
    """σxx, σzz, σxz at the surface from the tractions and QUADPACK's Cauchy principal value."""
    inside = lo < x < hi
    pv = 0.0
    if q is not None:
        f = lambda t: float(q(np.array(t)))                  # noqa: E731
        if inside:
            pts = sorted({lo, *[b for b in breaks if lo < b < hi], hi})
            for u, v in zip(pts[:-1], pts[1:]):
                if u < x < v:
                    pv += quad(f, u, v, weight="cauchy", wvar=x, epsabs=1e-11, epsrel=1e-11, limit=200)[0]
                else:
                    pv += quad(lambda t: f(t) / (t - x), u, v, epsabs=1e-11, epsrel=1e-11, limit=200)[0]
        else:
            pv = quad(lambda t: f(t) / (t - x), lo, hi, points=list(breaks), epsabs=1e-11,
                      epsrel=1e-11, limit=200)[0]
    pz = float(p(np.array(x))) if inside else 0.0
    qz = float(q(np.array(x))) if (inside and q is not None) else 0.0
    return -pz + 2 / math.pi * pv, -pz, -qz


@pytest.mark.parametrize("x", [-1.7, -0.8, 0.1, 0.6, 1.3])
def test_subsurface_tends_to_surface(x):
    """z -> 0+ of the subsurface stress is the surface formula: σzz = -p, σxz = -q,
    σxx = -p + (2/π) PV∫ q/(t - x) (QUADPACK), inside and outside the contact."""
    ref = surface_reference(x, p_hertz, q_hertz, -A_H, A_H, ())
    for z in (1e-10, 1e-9):
        S = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
        got = (float(S.sxx), float(S.szz), float(S.sxz))
        assert max(abs(u - v) for u, v in zip(got, ref)) <= TARGET * P0 + 10 * z * P0


# --- equilibrium ------------------------------------------------------------------------------

def line_rule(z: float, L: float, X: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on the line [-L, L] at depth z: panels of width 0.05
    on |x| <= X (the stress varies on the scale z), and x = z tan θ beyond (smooth there)."""
    g, w = np.polynomial.legendre.leggauss(20)
    edges = np.linspace(-X, X, int(round(2 * X / 0.05)) + 1)
    xs = (0.5 * np.diff(edges)[:, None] * g + 0.5 * (edges[1:] + edges[:-1])[:, None]).ravel()
    ws = (0.5 * np.diff(edges)[:, None] * w).ravel()
    th = np.linspace(math.atan(X / z), math.atan(L / z), 9)
    tt = (0.5 * np.diff(th)[:, None] * g + 0.5 * (th[1:] + th[:-1])[:, None]).ravel()
    wt = (0.5 * np.diff(th)[:, None] * w).ravel() * z / np.cos(tt) ** 2
    return np.concatenate([-z * np.tan(tt)[::-1], xs, z * np.tan(tt)]), np.concatenate([wt[::-1], ws, wt])


@pytest.mark.parametrize("z", [0.05, 0.7])
def test_equilibrium_at_depth(z):
    """∫σzz dx = -P and ∫σxz dx = -Q across a line at depth z, truncated at |x| <= L.

    The truncation is integrated analytically for a point load (Johnson 2.15, 2.19):
    ∫_{-L}^{L} σzz = -(2P/π)[atan(L/z) + zL/(L²+z²)], ∫_{-L}^{L} σxz = -(2Q/π)[atan(L/z) - zL/(L²+z²)],
    while σxz of the normal load and σzz of the shear are odd in x (zero). Outside [-L, L] the
    symmetric distributed loads differ from point loads by their second moments (a²/8 of the
    load) times the kernels' second derivatives: in all 2·(2/π)(Q a²/8)·2z/L³ ≈ 1e-11 P for σxz
    and O(a² z³/L⁵) for σzz at L = 2000, z <= 0.7 (at L = 200 the σxz check fails by 1.3e-8).
    """
    P, Q = math.pi / 2 * P0 * A_H, math.pi / 2 * F * P0 * A_H
    L = 2000.0
    x, wx = line_rule(z, L, 3.0)
    S = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    at, frac = math.atan(L / z), z * L / (L * L + z * z)
    assert abs(np.sum(S.szz * wx) + P * 2 / math.pi * (at + frac)) <= EQUILIBRIUM * P
    assert abs(np.sum(S.sxz * wx) + Q * 2 / math.pi * (at - frac)) <= EQUILIBRIUM * P


# --- signs ------------------------------------------------------------------------------------

def test_shear_and_bulk_signs():
    """q along +x: the trailing edge (x = -a) is tensile at the surface, the leading edge
    compressive; sigma_bulk adds to σxx exactly and to nothing else. Flipping either sign fails."""
    x = np.array([-A_H, A_H])
    S = stress(x, 0.0, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    assert S.sxx[0] == pytest.approx(2 * F * P0, abs=TARGET * P0) and S.sxx[1] == pytest.approx(-2 * F * P0, abs=TARGET * P0)
    xs, zs = np.meshgrid(np.linspace(-2, 2, 7), [0.0, 0.3, 2.0])
    base = stress(xs, zs, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    bulk = stress(xs, zs, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H), sigma_bulk=0.25)
    assert np.array_equal(bulk.sxx, base.sxx + 0.25)
    assert np.array_equal(bulk.szz, base.szz) and np.array_equal(bulk.sxz, base.sxz)


def test_derived_stresses():
    """Principal stresses, von Mises and Tresca against their definitions on a hand-made state."""
    S = Stress(x=np.zeros(2), z=np.ones(2), sxx=np.array([-3.0, 1.0]), szz=np.array([-1.0, 1.0]),
               sxz=np.array([math.sqrt(3.0), 0.0]), nu=0.25)
    # first point: in-plane centre -2, radius 2 -> 0 and -4; σyy = 0.25 (-4) = -1
    assert np.allclose(S.principal[:, 0], [0.0, -1.0, -4.0])
    assert S.von_mises[0] == pytest.approx(math.sqrt(0.5 * (1 + 9 + 16)))
    assert S.max_shear[0] == pytest.approx(2.0)
    assert S.angle[0] == pytest.approx(0.5 * math.atan2(2 * math.sqrt(3.0), -2.0))
    # second point: hydrostatic in-plane, σyy = 0.5
    assert np.allclose(S.principal[:, 1], [1.0, 1.0, 0.5])


# --- a threepart punch: caseA_moment ----------------------------------------------------------

@pytest.fixture(scope="module")
def case_a():
    case = get_case("caseA_moment")
    normal = cf.solve_normal(case.punch, case.P, case.s, A=case.A)
    slip = cf.solve_partial_slip(normal, 0.4 * 0.5 * case.P, 0.5)
    return case, normal, slip


def test_case_a_pressure_satisfies_the_integral_equation(case_a):
    """eq. (integral_equation): v'(x)/A = (1/π) PV∫ p(t)/(t - x) dt with the paper's p < 0; with
    threepart's p >= 0, (1/π) PV∫ p/(t - x) = -v'(x)/A, v'(x) = alpha + g'(x) of eq. (2)."""
    case, n, _ = case_a
    b = case.punch.b
    x = np.array([-1.7, -1.2, -b, -0.4, 0.0, 0.3, b, 1.5, 1.78])
    H = hilbert(n.pressure, x, ends=(-n.a, n.c), kinks=(-b, b))
    ref = -case.punch.slope(x, n.alpha) / case.A
    p0 = float(np.max(n.pressure(np.linspace(-n.a, n.c, 4001))))
    assert np.max(np.abs(H - ref)) <= TARGET * p0


def test_case_a_surface_stress_against_quadpack(case_a):
    """Partial slip of caseA_moment at Q = 0.4 f P (f = 0.5): the surface σxx from the Hilbert
    transform of q, and σzz = -p, σxz = -q, against QUADPACK's Cauchy principal value, to 1e-8 p0."""
    case, n, slip = case_a
    b = case.punch.b
    lo, hi = slip.stick_zone
    kinks = (-b, b, lo, hi)
    p0 = float(np.max(n.pressure(np.linspace(-n.a, n.c, 4001))))
    for x in (-1.9, -1.5, -0.7, 0.05, 0.9, 1.6, 2.1):
        S = stress(x, 0.0, pressure=n.pressure, shear=slip.shear, ends=(-n.a, n.c), kinks=kinks)
        ref = surface_reference(x, n.pressure, slip.shear, -n.a, n.c, kinks)
        got = (float(S.sxx), float(S.szz), float(S.sxz))
        assert max(abs(u - v) for u, v in zip(got, ref)) <= TARGET * p0, (x, got, ref)


def test_case_a_subsurface_converges(case_a):
    """No closed form below case A: the stress at shallow and deep points, on and next to the
    ends, joins and stick-zone ends, agrees with a rule of twice the nodes per panel graded
    to the full depth everywhere, to 1e-8 p0 (a self-consistency bound: the independent
    references above fix the rule's accuracy; this one checks the grading depth chosen per
    point where p and q have kinks)."""
    import threepart.stress.flamant as st

    case, n, slip = case_a
    b = case.punch.b
    lo, hi = slip.stick_zone
    x = np.array([-n.a - 1e-6, -n.a + 1e-6, -b, -b + 1e-5, 0.0, lo, hi + 1e-4, b, n.c, 2.0])
    z = np.array([1e-6, 1e-3, 0.1, 1.0, 4.0])[None, :]
    kw = dict(pressure=n.pressure, shear=slip.shear, ends=(-n.a, n.c), kinks=(-b, b, lo, hi))
    S = stress(x[:, None], z, **kw)
    saved = dict(st.RULE)
    try:
        st.RULE.update(n=24, ratio=0.5, levels=30, min_levels=30)
        fine = stress(x[:, None], z, **kw)
    finally:
        st.RULE.update(saved)
    p0 = float(np.max(n.pressure(np.linspace(-n.a, n.c, 4001))))
    assert worst(S, (fine.sxx, fine.szz, fine.sxz)) <= TARGET * p0


# --- input checks -----------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs, error, match", [
    ({"z": -0.1}, ValueError, "`z` = -0.1 must be >= 0"),
    ({"x": np.nan}, ValueError, "`x` holds nan"),
    ({"z": "deep"}, TypeError, "`z`"),
    ({"pressure": 3.0}, TypeError, "`pressure` must be a callable"),
    ({"shear": "q"}, TypeError, "`shear` must be a callable"),
    ({"ends": (1.0, -1.0)}, ValueError, "ends\\[0\\] < ends\\[1\\]"),
    ({"ends": 1.0}, TypeError, "`ends`"),
    ({"kinks": (2.0,)}, ValueError, "`kinks` holds x = 2"),
    ({"nu": 0.7}, ValueError, "`nu` = 0.7 must lie in"),
    ({"x": np.zeros(3), "z": np.ones(2)}, ValueError, "`x` of shape \\(3,\\) and `z` of shape \\(2,\\)"),
    ({"nu": True}, TypeError, "`nu`"),
    ({"sigma_bulk": math.inf}, ValueError, "`sigma_bulk`"),
    ({"pressure": lambda t: np.full(np.shape(t), np.nan)}, ValueError, "`pressure` is not finite"),
    ({"pressure": lambda t: 1.0}, ValueError, "`pressure` returned shape"),
])
def test_bad_input(kwargs, error, match):
    args = {"x": 0.0, "z": 0.1, "pressure": p_hertz, "ends": (-1.0, 1.0), **kwargs}
    with pytest.raises(error, match=match):
        stress(args.pop("x"), args.pop("z"), **args)


def test_surface_point_at_a_traction_jump_is_refused():
    """A uniform shear jumps at the contact end: σxx is infinite there, refused, not inf or NaN."""
    one = lambda t: np.ones(np.shape(t))                     # noqa: E731
    with pytest.raises(ValueError, match="infinite at the surface point x = 1"):
        stress(1.0, 0.0, pressure=one, shear=one, ends=(-1.0, 1.0))


def test_case_a_slip_result_carries_q_and_Q_as_this_module_means_them(case_a):
    """A threepart SlipResult's shear(x) and Q go in unconverted: ∫σxz dx = -Q (and ∫σzz = -P)
    at depth 0.5 under partial slip of caseA_moment. Truncation at L = 2000 as in
    test_equilibrium_at_depth; the load's centroid (|s| <= W) adds at most (2/π) Q W z/L² ≈ 1e-7 Q."""
    case, n, slip = case_a
    b = case.punch.b
    z, L = 0.5, 2000.0
    x, wx = line_rule(z, L, 4.0)
    S = stress(x, z, pressure=n.pressure, shear=slip.shear, ends=(-n.a, n.c),
               kinks=(-b, b, *slip.stick_zone))
    at, frac = math.atan(L / z), z * L / (L * L + z * z)
    assert abs(np.sum(S.sxz * wx) + slip.Q * 2 / math.pi * (at - frac)) <= TRUNCATED * abs(slip.Q)
    assert abs(np.sum(S.szz * wx) + n.P * 2 / math.pi * (at + frac)) <= TRUNCATED * n.P


# --- many points: chunks ------------------------------------------------------------------------

#: chunked against whole: the same quadrature per point, summed over other node subsets (blocks
#: of other points keep other shared nodes, with zero weight for this one): rounding, of p0
CHUNKED = 1e-13
#: arrays of one double per point that stress() may hold beside its result: the inputs as floats
#: (x and z), and as much again (measured: 1.5 per point; in one piece, 591)
PER_POINT_ARRAYS = 4


def _random_points(n, seed):
    """``n`` seeded points: a fifth on the surface, depths 1e-9 to 10 a, a tenth near a contact end."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(-3, 3, n) * A_H
    z = np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-9, 1, n)) * A_H
    k = n // 10
    x[:k] = rng.choice([-1, 1], k) * A_H * (1 + rng.choice([-1, 1], k) * 10 ** rng.uniform(-10, -1, k))
    return x, z


def test_points_in_chunks_give_the_same_stresses(monkeypatch):
    """2000 points in chunks of 7 (the last one short) and in one piece: the same to rounding, and
    each within the module's accuracy of McEwen's closed form; hilbert alike."""
    from threepart.stress import flamant as stress_mod

    x, z = _random_points(2000, 3)
    whole = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    h_whole = hilbert(p_hertz, x, ends=(-A_H, A_H))
    monkeypatch.setattr(stress_mod, "POINTS_PER_CHUNK", 7)
    chunked = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
    h_chunked = hilbert(p_hertz, x, ends=(-A_H, A_H))
    assert worst(chunked, (whole.sxx, whole.szz, whole.sxz)) <= CHUNKED * P0
    assert float(np.max(np.abs(h_chunked - h_whole))) <= CHUNKED * P0
    assert worst(chunked, mcewen(x, z)) <= TARGET * P0


def test_the_working_memory_does_not_grow_with_the_points(monkeypatch):
    """tracemalloc's peak (numpy's buffers included) less the result: 16 chunks of points need no
    more than 4 of the same chunks (the points repeated), bar a few arrays of one double per point.
    In one piece the quadrature's nodes (hundreds per point) grew with the points."""
    import tracemalloc

    from threepart.stress import flamant as stress_mod

    chunk = 500
    monkeypatch.setattr(stress_mod, "POINTS_PER_CHUNK", chunk)
    x4, z4 = _random_points(4 * chunk, 4)

    def working(copies):
        x, z = np.tile(x4, copies), np.tile(z4, copies)
        tracemalloc.start()
        try:
            S = stress(x, z, pressure=p_hertz, shear=q_hertz, ends=(-A_H, A_H))
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        return peak - 5 * S.sxx.nbytes                          # x, z, sxx, szz, sxz of the result

    small, large = working(1), working(4)
    assert large - small <= PER_POINT_ARRAYS * 8 * (12 * chunk), (small, large)

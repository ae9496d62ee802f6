"""McEwen's closed-form stresses of a Hertz line contact in full sliding: the reference of the stress field.

Independent of :mod:`threepart.stress`: Johnson, *Contact Mechanics* (1985),
eqs. (7.17)-(7.18). Used by tests/test_stress.py and benchmarks/bench_stress.py.
"""
from __future__ import annotations

import numpy as np

def mcewen(x, z, a=1.0, p0=1.0, q0=0.3):
    """McEwen's stresses of a Hertz line contact sliding with q = f p along +x (Johnson eq. 7.18).

    ``m, n`` of eq. (7.17), with m >= 0 and n of the sign of x, computed free of cancellation
    (``m n = x z``).
    """
    x, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(z, float))
    A = a * a - x * x + z * z
    R = np.sqrt(A * A + 4 * x * x * z * z)
    big = np.sqrt(0.5 * (R + np.abs(A)))
    small = np.divide(np.abs(x) * z, big, out=np.zeros_like(big), where=big > 0)
    m = np.where(A >= 0, big, small)
    n = np.sign(x) * np.where(A >= 0, small, big)
    mn = m * m + n * n
    sxx = -(p0 / a) * (m * (1 + (z * z + n * n) / mn) - 2 * z) \
        + (q0 / a) * (n * (2 - (z * z - m * m) / mn) - 2 * x)
    szz = -(p0 / a) * m * (1 - (z * z + n * n) / mn) - (q0 / a) * n * (m * m - z * z) / mn
    sxz = -(p0 / a) * n * (m * m - z * z) / mn - (q0 / a) * (m * (1 + (z * z + n * n) / mn) - 2 * z)
    return sxx, szz, sxz


def hertz_partial_slip(x, z, a, p0, f, c, x0, sigma_bulk=0.0):
    """Hills & Nowell's stresses of a Hertz line contact in partial slip under a bulk stress.

    The shear the pad exerts on the substrate along +x is Mindlin's sliding
    traction less a corrective of the stick zone ``[x0 - c, x0 + c]``
    (Hills & Nowell, *Mechanics of Fretting Fatigue*, 1994, ch. 5; Nowell &
    Hills 1987, offset ``x0 = a sigma_bulk/(4 f p0)`` when ``Q > 0``)::

        q(t) = f p0 sqrt(1 - t^2/a^2) - f p0 (c/a) sqrt(1 - (t - x0)^2/c^2),

    so by linearity the field is McEwen's (:func:`mcewen`) of the sliding part,
    less McEwen's shear-only field of the corrective (half-width ``c``, peak
    ``f p0 c/a``, shifted by ``x0``), plus ``sigma_bulk`` in ``σxx``. ``f < 0``
    gives a shear along -x.
    """
    x, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(z, float))
    s1 = mcewen(x, z, a, p0, f * p0)
    s2 = mcewen(x - x0, z, c, 0.0, f * p0 * c / a)
    sxx, szz, sxz = (u - v for u, v in zip(s1, s2))
    return sxx + sigma_bulk, szz, sxz


def _hilbert_semicircle(x, a):
    """``(1/π) PV ∫_{-a}^{a} sqrt(a^2 - t^2)/(t - x) dt = -x + sign(x) sqrt(x^2 - a^2)`` (0 inside)."""
    x = np.asarray(x, float)
    out = np.sqrt(np.maximum(x * x - a * a, 0.0))
    return -x + np.sign(x) * out


def hertz_partial_slip_surface_sxx(x, a, p0, f, c, x0, sigma_bulk=0.0):
    """Surface ``σxx`` of :func:`hertz_partial_slip` in closed form (Hills & Nowell).

    ``σxx(x, 0) = -p(x) + (2/π) PV ∫ q(t)/(t - x) dt + sigma_bulk`` with the
    Hilbert transform of a semi-ellipse, :func:`_hilbert_semicircle`; in the
    stick zone it is ``-p - 2 f p0 x0/a + sigma_bulk``.
    """
    x = np.asarray(x, float)
    p = p0 * np.sqrt(np.maximum(1.0 - (x / a) ** 2, 0.0))
    hq = f * p0 / a * (_hilbert_semicircle(x, a) - _hilbert_semicircle(x - x0, c))
    return -p + 2.0 * hq + sigma_bulk

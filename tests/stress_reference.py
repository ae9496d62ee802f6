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

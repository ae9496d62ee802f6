"""Damped Newton iteration for the two contact-end unknowns, and a bracketing root finder."""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from threepart.errors import NoConvergenceError

__all__ = ["newton", "bracket_root", "STEP_FLOOR"]

#: A Newton step below this fraction of ``h`` is at the rounding floor: where the line
#: search cannot lower the residual any further (a sharp edge arc makes the residual's
#: rounding level ~1e-9, far above ``tol``), the iterate is accepted if the full step
#: would move the ends by less than this (they are then known to ~1e-10 of the width).
STEP_FLOOR = 1e-10
#: ... or if the residual (dimensionless: relative load error, tilt error over the load's
#: slope scale) is below this, where the rounding of the moments' sums leaves it
RESIDUAL_FLOOR = 1e-8


Residual = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def newton(fun: Residual, z0: np.ndarray, *, what: str, tol: float = 1e-14,
           maxiter: int = 60) -> tuple[np.ndarray, int, float]:
    """Solve ``fun(z) = 0`` for ``z = (m, h)`` with ``h > 0``, by Newton's method with backtracking.

    Parameters
    ----------
    fun
        Returns the dimensionless residual (length 2) and its Jacobian (2 x 2).
    z0
        Starting point.
    what
        Name of the problem, for the error message.
    tol
        Converged when the residual norm is below ``tol`` or the step is
        below ``tol * h``.

    Returns
    -------
    z, iterations, residual norm

    Raises
    ------
    NoConvergenceError
        When the iteration stalls, leaves ``h > 0`` for good, or runs out of
        iterations, or when a residual is not finite.
    """
    z = np.asarray(z0, dtype=float)
    r, J = fun(z)
    norm = float(np.linalg.norm(r))
    for it in range(1, maxiter + 1):
        if not np.isfinite(norm):
            raise NoConvergenceError(f"{what}: residual is not finite at (m, h) = {tuple(z)}")
        try:
            dz = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError as exc:
            raise NoConvergenceError(f"{what}: singular Jacobian at (m, h) = {tuple(z)}") from exc
        lam = 1.0
        while True:
            zn = z + lam * dz
            if zn[1] > 0:
                rn, Jn = fun(zn)
                nn = float(np.linalg.norm(rn))
                if nn <= (1.0 - 1e-4 * lam) * norm or nn <= tol:
                    break
            lam *= 0.5
            if lam < 1e-10:
                # at rounding level: accept (the residual, or the full step, is at its floor)
                if (norm <= max(1e3 * tol, RESIDUAL_FLOOR)
                        or float(np.linalg.norm(dz)) <= STEP_FLOOR * z[1]):
                    return z, it, norm
                raise NoConvergenceError(
                    f"{what}: line search failed at (m, h) = {tuple(z)}, residual {norm:.3g}")
        step = float(np.linalg.norm(zn - z))
        z, r, J, norm = zn, rn, Jn, nn
        if norm <= tol or step <= tol * z[1]:
            return z, it, norm
    raise NoConvergenceError(f"{what}: no convergence in {maxiter} Newton iterations "
                             f"(residual {norm:.3g} at (m, h) = {tuple(z)})")


def bracket_root(f: Callable[[float], float], x0: float, *, what: str,
                 grow: float = 2.0, maxsteps: int = 200) -> float:
    """Root of an increasing ``f`` on ``x > 0``: bracket from ``x0`` by factors ``grow``, then Brent.

    Raises
    ------
    NoConvergenceError
        When no sign change is found within ``maxsteps`` factors.
    """
    def f_checked(x: float) -> float:
        fx = f(x)
        if not np.isfinite(fx):
            raise NoConvergenceError(f"{what}: function is not finite at {x:.6g}")
        return fx

    hi = x0
    fhi = f_checked(hi)
    steps = 0
    while fhi <= 0:
        hi *= grow
        fhi = f_checked(hi)
        steps += 1
        if steps > maxsteps:
            raise NoConvergenceError(f"{what}: no upper bracket found up to {hi:.3g}")
    lo = hi / grow
    flo = f_checked(lo)
    steps = 0
    while flo > 0:
        hi, lo = lo, lo / grow
        flo = f_checked(lo)
        steps += 1
        if steps > maxsteps:
            raise NoConvergenceError(f"{what}: no lower bracket found down to {lo:.3g}")
    return float(brentq(f_checked, lo, hi, xtol=1e-16 * hi, rtol=1e-15, maxiter=200))

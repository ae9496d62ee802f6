"""The FE package's boundary: no foreign exception leaves a public FE call.

scikit-fem, SciPy, NumPy, meshio and gmsh raise their own exceptions
(``LinAlgError`` of a singular system, ``ZeroDivisionError``, ``OverflowError``,
``FloatingPointError``, ``ArpackError``, SuperLU's ``RuntimeError`` "Factor is
exactly singular", meshio's ``ReadError``; gmsh's bare ``Exception`` is caught
where gmsh runs, :func:`fem.mesh.gmsh_failure`). At a public entry point they become :class:`NoConvergenceError`
with a one-line message: by then the input has been checked, so what failed is
the numerical method. The package's own errors (``ValueError`` and its
subclasses, ``TypeError``, :class:`NoConvergenceError`, :class:`ContactZoneError`)
pass unchanged.
"""
from __future__ import annotations

import functools
import tempfile
from typing import Any, Callable, TypeVar

import numpy as np

from threepart.errors import ContactZoneError, NoConvergenceError

__all__ = ["boundary", "FOREIGN"]

F = TypeVar("F", bound=Callable[..., Any])

#: foreign numerical failures that become NoConvergenceError at the boundary
#: (``LinAlgError`` is a ``ValueError`` to NumPy, but not bad input: it is caught first)
FOREIGN: tuple[type[BaseException], ...] = (np.linalg.LinAlgError, ArithmeticError)


def _foreign() -> tuple[type[BaseException], ...]:
    import meshio
    from scipy.sparse.linalg import ArpackError

    return (*FOREIGN, meshio.ReadError, ArpackError, RuntimeError)


#: everything the boundary turns into NoConvergenceError (after the package's own errors)
FOREIGN_ALL: tuple[type[BaseException], ...] = _foreign()


def boundary(func: F) -> F:
    """Wrap a public FE call: foreign numerical errors become :class:`NoConvergenceError`."""
    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except (NoConvergenceError, ContactZoneError):
            raise   # the package's own (RuntimeError subclasses, like SuperLU's "singular")
        except FOREIGN_ALL as e:
            why = " ".join(str(e).split()[:30]) or type(e).__name__
            why = why.replace(tempfile.gettempdir(), "<tmp>")
            raise NoConvergenceError(f"{func.__name__}: the FE computation failed "
                                     f"({type(e).__name__}: {why})") from None
    return wrapper  # type: ignore[return-value]

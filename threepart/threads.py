"""One BLAS thread around a dense solve, without rescanning the loaded libraries each time.

``threadpoolctl.threadpool_limits`` finds the process's BLAS and OpenMP libraries on every
call (it reads the loaded shared objects: ~18 ms, measured on this machine; a wear march
solves a contact thousands of times). A :class:`threadpoolctl.ThreadpoolController` does
that once; it is rebuilt when modules have been imported since (a newly imported extension,
CHOLMOD's say, may bring its own BLAS).

one_blas_thread -- the context manager every dense solve of the package enters
"""
from __future__ import annotations

import sys
from contextlib import AbstractContextManager
from typing import Any

__all__ = ["one_blas_thread"]

_CONTROLLER: list[Any] = [None, -1]     # the controller and len(sys.modules) when it was built


def one_blas_thread() -> AbstractContextManager[Any]:
    """``threadpool_limits(limits=1, user_api="blas")`` on a controller built once per set of imports."""
    from threadpoolctl import ThreadpoolController

    if _CONTROLLER[0] is None or _CONTROLLER[1] != len(sys.modules):
        _CONTROLLER[0] = ThreadpoolController()
        _CONTROLLER[1] = len(sys.modules)
    return _CONTROLLER[0].limit(limits=1, user_api="blas")

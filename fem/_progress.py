"""One line per stage on stderr while a long FE solve runs.

The lines look like the verification run's (``reports/verify/report.py``): the seconds
since the call began, then the stage, e.g.::

       1.2s  fem: locate: contact [-1.02, 1.05] (trial and locate meshes)
      14.8s  fem: step 3/10, Q = 24

``progress`` is ``None`` (default: on only when stderr is a terminal, so that
tests and pipes stay quiet), ``True``, ``False``, or a callable that takes each
line's message (e.g. a report's own ``say``).
"""
from __future__ import annotations

import sys
import time
from typing import Any, Callable, Union
from threepart.errors import InputTypeError

__all__ = ["Progress", "ProgressArg", "progress_iv"]

ProgressArg = Union[bool, None, Callable[[str], None]]


def progress_iv(progress: Any) -> ProgressArg:
    """``progress`` if it is ``None``, a bool or a callable, else ``TypeError``."""
    if progress is None or isinstance(progress, bool) or callable(progress):
        return progress
    raise InputTypeError(f"`progress` must be None, True, False or a callable, "
                    f"not {type(progress).__name__}")


class Progress:
    """Print ``fem: <stage>`` lines, timed from construction, or nothing."""

    def __init__(self, progress: ProgressArg = None) -> None:
        self.t0 = time.perf_counter()
        if callable(progress):
            self._out: Callable[[str], None] | None = progress
        elif progress or (progress is None and _stderr_is_tty()):
            self._out = self._print
        else:
            self._out = None

    def _print(self, msg: str) -> None:
        print(f"{time.perf_counter() - self.t0:7.1f}s  fem: {msg}", file=sys.stderr, flush=True)

    def __call__(self, msg: str) -> None:
        """Report one stage (nothing when quiet)."""
        if self._out is not None:
            self._out(msg)


def _stderr_is_tty() -> bool:
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):   # replaced or closed stream
        return False

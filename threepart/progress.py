"""Progress of long stages: a line every few seconds while a block runs.

Used by the verification run (``reports``), the command line and any long computation of the core.
"""
from __future__ import annotations

import threading
import time
from contextlib import contextmanager
from typing import Callable, Iterator

__all__ = ["heartbeat", "HEARTBEAT_S"]

#: seconds between two "still running" lines of a long stage
HEARTBEAT_S = 15.0


@contextmanager
def heartbeat(say: Callable[[str], None], stage: Callable[[], str],
               every: float | None = None) -> Iterator[None]:
    """Say ``"<stage> still running (N s)"`` every ``every`` seconds until the block ends.

    A stage such as the FE fretting cycle (over a minute on the default mesh)
    reports nothing of its own until it is done; these lines, in the run's
    one-line-per-stage style, show that it is still working.
    """
    stop = threading.Event()
    t0 = time.perf_counter()
    period = HEARTBEAT_S if every is None else every

    def beat() -> None:
        while not stop.wait(period):
            say(f"{stage()} still running ({time.perf_counter() - t0:.0f} s)")

    thread = threading.Thread(target=beat, name="threepart-progress", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join()

"""The engine of a validity-map sweep: dask.distributed, a local cluster or an existing scheduler.

Names
-----
open_engine -- context manager: a client on a new local cluster or on a scheduler, closed on exit
sweep       -- submit every task, log each result as it arrives, hand it on (and submit its follow-ups), report progress
Task        -- a task of a sweep: its key, the function a worker runs, its arguments, and what it is
"""
from __future__ import annotations

import asyncio
import gc
import logging
import os
import threading
import time
import uuid
from asyncio import CancelledError
from contextlib import ExitStack, contextmanager, nullcontext
from typing import Any, Callable, Iterator, Sequence

import dask
from dask.distributed import Client, LocalCluster, as_completed

from .log import control_record, one_line, point_record
from .schema import pct

__all__ = ["open_engine", "sweep", "Task"]

Say = Callable[[str], None]
#: a task of a sweep: its key, the function a worker runs, its arguments, and what it is (see
#: :func:`sweep`)
Task = tuple[str, Callable[..., Any], tuple[Any, ...], Any]


@contextmanager
def _quiet_workers() -> Iterator[None]:
    """Start worker processes that leave Ctrl-C to this one and log only errors.

    A terminal's Ctrl-C reaches every process of the group. The workers
    spawned here inherit an ignored SIGINT (an ignored signal survives
    ``exec``; Python and asyncio then install no handler of their own), so
    only this process is interrupted and closes the cluster; their
    ``distributed`` loggers (configured from the environment at import) say
    nothing below ERROR, such as the cancelled tasks of that close.
    """
    import signal

    saved_env = os.environ.get(_WORKER_LOG_ENV)
    os.environ[_WORKER_LOG_ENV] = "error"
    saved = signal.signal(signal.SIGINT, signal.SIG_IGN) if _main_thread() else None
    try:
        yield
    finally:
        if saved is not None:
            signal.signal(signal.SIGINT, saved)
        if saved_env is None:
            os.environ.pop(_WORKER_LOG_ENV, None)
        else:
            os.environ[_WORKER_LOG_ENV] = saved_env


#: seconds between two looks at the cluster's workers while a sweep waits
WORKER_CHECK_S = 5.0
#: seconds without any worker after which a sweep gives up: its pending tasks are cancelled and
#: the map stops with an error naming the cause (a rerun resumes), instead of waiting forever
NO_WORKERS_S = 120.0

#: the dask setting (as an environment variable) of the worker processes' log level
_WORKER_LOG_ENV = "DASK_LOGGING__DISTRIBUTED"
#: the map's own workers keep glibc's default heap trimming. distributed's nanny starts its
#: workers with ``MALLOC_TRIM_THRESHOLD_=65536`` (to hand freed memory back at once), which
#: also fixes glibc's mmap threshold: every dense compliance and every temporary of a few
#: hundred kB is then mapped afresh and faulted in page by page. Measured on one map point
#: (issue 41): 462,000 page faults and 1.7 s of system time against 105,000 and 0.9 s, 27 %
#: more CPU; the quick map spent a third of its CPU (340 of 1,023 s) in the kernel. ``None``
#: unsets the variable (distributed's own rule); one set in this process's environment stays.
_WORKER_MALLOC = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}


def _main_thread() -> bool:
    import threading

    return threading.current_thread() is threading.main_thread()


@contextmanager
def _silenced(loggers: Sequence[str] = ("distributed", "dask", "tornado", "asyncio")) -> Iterator[None]:
    """Raise the level of ``loggers`` above CRITICAL for the block (the cluster's close on Ctrl-C)."""
    import logging

    saved = {name: logging.getLogger(name).level for name in loggers}
    for name in loggers:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for name, level in saved.items():
            logging.getLogger(name).setLevel(level)


class _ExpectedAtClose:
    """A logging filter that drops the nanny's warning that it killed a worker at the cluster's close.

    Closing the map's own cluster stops its workers; a worker still busy (a
    loaded machine, a study's thread) after the nanny's grace is killed, which
    is what the close asks for, not a fault. Every other record passes:
    errors, and a worker restarted mid-run ("Restarting worker").
    """

    def filter(self, record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith(_KILLED_AT_CLOSE)


#: the start of the warning ``distributed.nanny`` logs when it kills a worker slow to stop
_KILLED_AT_CLOSE = "Worker process still alive after"


@contextmanager
def _own_cluster_logs() -> Iterator[None]:
    """For the life of the map's own cluster: no nanny warning about killing its workers at close."""
    nanny, expected = logging.getLogger("distributed.nanny"), _ExpectedAtClose()
    nanny.addFilter(expected)
    try:
        yield
    finally:
        nanny.removeFilter(expected)


@contextmanager
def open_engine(scheduler: str | None, workers: int, timeout: float) -> Iterator[tuple[Any, dict[str, Any]]]:
    """A dask client on a new local cluster of ``workers`` or on ``scheduler``; closed on exit.

    The local cluster, if one is made, is closed too. ``workers`` is its
    number of worker processes (unused with ``scheduler``); ``timeout`` is how
    long an existing scheduler has to answer (seconds).

    On an interrupt the close is silent: the one line that says so is the
    command line's.
    """
    cluster = None
    stack = ExitStack()
    if scheduler is None:
        stack.enter_context(_own_cluster_logs())
        try:
            with _quiet_workers(), dask.config.set(_WORKER_MALLOC):
                # the dashboard on a free port: another cluster on this machine may hold 8787, and
                # distributed's warning about it would break the one-line stderr of an interrupt
                cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                       processes=True, dashboard_address=":0")
        except BaseException:
            stack.close()
            raise
        try:
            client = Client(cluster)
        except BaseException:
            with stack, _silenced():
                cluster.close()
            raise
    else:
        client = connect(scheduler, timeout)
    interrupted = False
    try:
        engine = {"kind": "dask.distributed", "scheduler": client.scheduler.address,
                  "workers": len(client.nthreads()), "dask_version": dask.__version__}
        yield client, engine
    except BaseException:
        interrupted = True
        raise
    finally:
        with stack, _silenced() if interrupted else nullcontext():
            client.close()
            if cluster is not None:
                _stop_workers(cluster)
                cluster.close()


#: seconds the map's own workers get to stop at its close before their nanny kills them; a worker
#: busy in a task (a solve is not interruptible) is killed after 0.8 of it. distributed's own 5 s
#: held the end of an interrupted map 4 s on such a worker (issue 41, measured on a Ctrl-C)
CLOSE_GRACE_S = 1.0


def _stop_workers(cluster: Any) -> None:
    """Stop the worker processes of the map's own ``cluster`` with :data:`CLOSE_GRACE_S` of grace.

    Each nanny's close (distributed's ``Nanny.close``) asks its worker to close, kills it
    when the grace is over, and closes the nanny; the cluster's close then finds them
    closed. Whatever goes wrong here is left to that close, which stops them with
    distributed's own grace.
    """
    from distributed import Nanny

    nannies = [w for w in cluster.workers.values() if isinstance(w, Nanny)]

    async def close_all() -> None:
        await asyncio.gather(*(n.close(timeout=CLOSE_GRACE_S, reason="threepart-map-close")
                               for n in nannies))

    try:
        cluster.sync(close_all)
    except Exception:            # noqa: BLE001 - the close below stops them all the same
        pass


def connect(scheduler: str, timeout: float) -> Any:
    """A client of the scheduler at ``scheduler``, or a one-line ``OSError``."""
    try:
        return Client(scheduler, timeout=timeout)
    except (OSError, ValueError, TypeError) as exc:
        reason = one_line(exc)
    # the half-made client sits in reference cycles; collected later, on whatever thread, its
    # __del__ can deadlock the start of the next client in this process (it takes the loop
    # runners' lock): collect it now, outside the handler, where nothing refers to it any more
    gc.collect()
    raise OSError(f"cannot reach the dask scheduler `--scheduler` = {scheduler!r}: {reason}")


def sweep(client: Any, tasks: list[Task], log: Callable[[dict[str, Any]], None], mode: str, done0: int,
          total: int, say: Say, arrived: Callable[[dict[str, Any]], list[Task]]) -> None:
    """Submit every task, log each result as it arrives, hand it to ``arrived``, and report progress.

    A task is ``(key, fn, args, what)``: ``what`` is the grid point (its line is
    :func:`~reports.map.log.point_record`), ``None`` (the control), or a callable
    ``what(result, exc, mode)`` that makes the line of a study task
    (:func:`~reports.map.log.task_record`). ``arrived(record)`` keeps a logged
    record and returns the tasks it makes possible (the next step of a
    bisection); they are submitted at once and counted into ``total``.
    """
    futures = {}

    def submit(batch: list[Task]) -> list[Any]:
        new = []
        for key, fn, args, point in batch:
            fut = client.submit(fn, *args, pure=False, key=f"threepart-map-{key}-{uuid.uuid4().hex[:8]}")
            futures[fut] = (key, point)
            new.append(fut)
        return new

    pending = as_completed(submit(tasks))
    n = 0
    t0 = time.perf_counter()
    stop, lost = threading.Event(), list[str]()
    watch = threading.Thread(target=_watch_workers, args=(client, futures, stop, lost),
                             name="threepart-map-workers", daemon=True)
    watch.start()
    try:
        for fut in pending:
            if lost:
                raise RuntimeError(lost[0])
            key, point = futures[fut]
            exc: BaseException | None = None
            try:
                result = fut.result()
            except (Exception, CancelledError) as e:   # a failed point is recorded, never a crash
                result, exc = None, e
            error = None if exc is None else one_line(exc)
            if callable(point):   # a study task: it makes its own line
                rec = point(result, exc, mode)
            else:
                rec = (control_record(result, error, mode) if point is None
                       else point_record(point, result, error, mode))
            log(rec)
            n += 1
            more = arrived(rec)
            for new in submit(more):
                pending.add(new)
            total += len(more)
            done = done0 + n
            elapsed = time.perf_counter() - t0
            eta = elapsed / n * (total - done)
            status = "FAILED " + rec["error"] if rec["error"] else (
                rec.get("note") or "done" if callable(point) else
                f"peak error {pct(rec.get('peak_rel_error'))}" if point is not None
                else f"control error {rec['control_rel_error']:.2e}")
            say(f"[{done:>{len(str(total))}}/{total}] {key}  {status}  "
                f"elapsed {elapsed:.1f} s, ETA {eta:.0f} s")
    finally:   # on an interrupt or an error: nothing left running for this run
        stop.set()
        watch.join()
        try:
            client.cancel([f for f in futures if not f.done()])
        except Exception:   # the scheduler is gone already: nothing to cancel
            pass


def _watch_workers(client: Any, futures: dict[Any, Any], stop: threading.Event, lost: list[str]) -> None:
    """Until ``stop``: every :data:`WORKER_CHECK_S`, count the cluster's workers; after
    :data:`NO_WORKERS_S` without one, say why in ``lost`` and cancel the pending ``futures``
    (their results then arrive as cancelled, and :func:`sweep` raises ``lost``'s reason)."""
    since: float | None = None
    while not stop.wait(WORKER_CHECK_S):
        try:
            workers = len(client.scheduler_info().get("workers", {}))
        except Exception:   # the scheduler is unreachable: the sweep's own calls will say so
            continue
        since = None if workers else (since if since is not None else time.monotonic())
        if since is not None and time.monotonic() - since >= NO_WORKERS_S:
            lost.append(f"the dask cluster has had no worker for {NO_WORKERS_S:.0f} s, so the map's "
                        "pending tasks cannot run; start workers (or a new cluster) and rerun: the "
                        "map resumes where it stopped")
            try:
                client.cancel([f for f in list(futures) if not f.done()])
            except Exception:
                pass
            return

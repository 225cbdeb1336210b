"""Running a sweep's points on a process pool: Ctrl-C, and collecting the results.

A sweep's default executor is a `process_pool` whose workers leave Ctrl-C to this
process, which stops them (`stop_process_pool`) without the hang of a shutdown
interrupted while it joins its threads; `_collect` gathers the points as they finish,
with a progress bar, warns of each cache file that failed its checks, and says how
many points were done when interrupted.
"""

from __future__ import annotations

import concurrent.futures as cf
import os
import signal
import sys
import warnings

from .._processes import end_with_parent
from .cache import CacheWarning

__all__ = ["process_pool", "stop_process_pool", "workers_of", "Tally"]


def _worker_start():
    """A pool worker's initializer: Ctrl-C (SIGINT to the terminal's process group) is
    the sweep's to handle (a worker that raised KeyboardInterrupt itself would leave
    the pool waiting on it), and the worker ends when the sweep's process dies
    (``kill -9``: issue 36 item 13), which cannot stop it then."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    end_with_parent()


def process_pool(workers: int | None) -> cf.ProcessPoolExecutor:
    """A process pool for sweeps whose workers leave Ctrl-C to this process, which
    stops them (`stop_process_pool`), and end when it dies.

    Parameters
    ----------
    workers : int or None
        The number of worker processes (None: the number of CPUs).

    Returns
    -------
    concurrent.futures.ProcessPoolExecutor

    See Also
    --------
    beltmdsm.sweep : its default executor is one of these.

    Examples
    --------
    >>> pool = process_pool(1)
    >>> pool.submit(sum, [1, 2, 3]).result()
    6
    >>> stop_process_pool(pool)
    """
    return cf.ProcessPoolExecutor(max_workers=workers, initializer=_worker_start)


def stop_process_pool(executor: cf.ProcessPoolExecutor, futures=()) -> None:
    """Stop a process pool now (Ctrl-C): the queued points cancelled, the running
    ones ended (their workers terminated), nothing waited for but the workers' exit.

    A second Ctrl-C meanwhile is ignored, so that it cannot leave the pool half shut
    (the permanent hang of a shutdown interrupted while it joins its threads).

    Parameters
    ----------
    executor : concurrent.futures.ProcessPoolExecutor
        The pool (`process_pool`).
    futures : iterable of concurrent.futures.Future
        Its futures, cancelled first.

    See Also
    --------
    process_pool : the pool it stops.

    Examples
    --------
    >>> pool = process_pool(1)
    >>> stop_process_pool(pool)
    >>> pool.submit(sum, [1])
    Traceback (most recent call last):
    ...
    RuntimeError: cannot schedule new futures after shutdown
    """
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        for fut in futures:
            fut.cancel()
        workers = list((getattr(executor, "_processes", None) or {}).values())
        executor.shutdown(wait=False, cancel_futures=True)
        for worker in workers:
            worker.terminate()
        for worker in workers:
            worker.join(timeout=5)
        # the pool's manager thread closes its wake-up pipe as it ends; joined here, not
        # at exit, where CPython 3.11's `_python_exit` may write to that pipe as it
        # closes ("Exception ignored ... Bad file descriptor" after the one line)
        manager = getattr(executor, "_executor_manager_thread", None)
        if manager is not None:
            manager.join(timeout=5)
    finally:
        signal.signal(signal.SIGINT, previous)


def workers_of(executor) -> int:
    """How many tasks ``executor`` runs at once: 1 for ``"serial"``; a process or
    thread pool's workers; a dask ``Client.get_executor()``'s threads; else (None, a
    pool of the call's own) the CPUs.

    Parameters
    ----------
    executor : concurrent.futures.Executor, "serial" or None

    Returns
    -------
    int

    See Also
    --------
    beltmdsm.basin.basin_stability.chunk_size : the starts per task it sizes.

    Examples
    --------
    >>> import concurrent.futures as cf
    >>> with cf.ThreadPoolExecutor(3) as pool:
    ...     workers_of(pool), workers_of("serial")
    (3, 1)
    """
    if executor == "serial":
        return 1
    client = getattr(executor, "_client", None)  # distributed's ClientExecutor
    if client is not None:
        return max(1, sum(client.nthreads().values()))
    return max(1, getattr(executor, "_max_workers", None) or os.cpu_count() or 1)


def _collect(results, n, desc, progress, cache_dir=None):
    """``(rows, n_cached, problems)`` from ``(index, (row, cached, problem))`` results,
    with a progress bar; each problem is warned about once, by the file's name.

    Interrupted (Ctrl-C), it raises KeyboardInterrupt saying how many points it had
    received (each finished point is in the cache, written by the process that
    computed it: a worker may have written one more than it had sent).
    """
    from tqdm import tqdm

    rows, n_cached, problems = [None] * n, 0, []
    bar = tqdm(total=n, desc=desc, disable=not progress, file=sys.stderr)
    done = 0
    try:
        for i, (row, cached, problem) in _interruptible(results):
            done += 1
            rows[i] = row
            n_cached += bool(cached)
            if problem is not None:
                problems.append(problem)
                # stacklevel 4: the caller of sweep (sweep -> _collect -> warn)
                warnings.warn(str(problem), CacheWarning, stacklevel=3)
            bar.update()
    except KeyboardInterrupt:
        kept = (
            f"; every point finished is kept in the cache ({cache_dir})"
            if cache_dir is not None
            else " (no cache: nothing kept)"
        )
        raise KeyboardInterrupt(f"{desc}: stopped after {done} of {n} points{kept}") from None
    finally:
        bar.close()
    return rows, n_cached, problems


def _interruptible(results):
    """``results``, with the SystemError that numba raises where Ctrl-C lands inside a
    compiled function ("returned a result with an exception set") read as the
    KeyboardInterrupt it wraps."""
    try:
        yield from results
    except SystemError as err:
        if isinstance(err.__context__, KeyboardInterrupt) or isinstance(
            err.__cause__, KeyboardInterrupt
        ):
            raise KeyboardInterrupt from None
        raise


class Tally:
    """The progress of a study's tasks (``n`` of them, ``unit`` each) on stderr, shown
    on a terminal once it has taken 2 s, and what an interrupt keeps.

    Used as a context manager: Ctrl-C inside it raises KeyboardInterrupt saying how
    many were finished and where they are kept (each task's result is in the cache,
    written by the process that computed it), one line for the command line.

    Examples
    --------
    >>> with Tally(3, "starts", "basins", cache_dir=None) as tally:
    ...     tally.update(3)
    >>> tally.done
    3
    """

    def __init__(self, n: int, unit: str, desc: str, cache_dir=None) -> None:
        from tqdm import tqdm

        self.unit, self.desc, self.cache_dir, self.done = unit, desc, cache_dir, 0
        # disable=None: shown on a terminal only, not in a pipe or a captured stream
        self.bar = tqdm(
            total=n, desc=desc, unit=unit[:-1], delay=2, leave=False, disable=None, file=sys.stderr
        )

    def update(self, k: int = 1) -> None:
        self.done += k
        self.bar.update(k)

    def grow(self, k: int) -> None:
        """``k`` more tasks (another round over those left)."""
        self.bar.total += k
        self.bar.refresh()

    def __enter__(self) -> Tally:
        return self

    def __exit__(self, kind, err, tb) -> None:
        self.bar.close()
        if kind is not None and issubclass(kind, KeyboardInterrupt) and not str(err):
            kept = (
                f"; every {self.unit[:-1]} finished is kept in the cache ({self.cache_dir})"
                if self.cache_dir is not None
                else " (no cache: nothing kept)"
            )
            raise KeyboardInterrupt(
                f"{self.desc}: stopped after {self.done} of {self.bar.total} {self.unit}{kept}"
            ) from None

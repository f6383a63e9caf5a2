"""The executor: independent jobs on all cores (sensitivity cases, FMU runs)."""

from concurrent.futures import ProcessPoolExecutor, as_completed
import os

from threadpoolctl import threadpool_limits

__all__ = ["parallel_map"]


def parallel_map(function, jobs, workers=None, ordered=True):
    """Yield ``function(job)`` for every job, computed in worker processes.

    Parameters
    ----------
    function : callable
        A module-level function (it is pickled).
    jobs : sequence
    workers : int, optional
        Processes (default: all cores); 1 runs in this process.
    ordered : bool
        Yield in the order of ``jobs`` (else as each finishes).

    Each worker uses one BLAS thread: the kernels work on many tiny
    matrices, where threaded BLAS only contends (measured 5x slower).
    """
    workers = workers or os.cpu_count() or 1
    if workers == 1:
        with threadpool_limits(limits=1):
            yield from map(function, jobs)
        return
    with ProcessPoolExecutor(max_workers=workers, initializer=threadpool_limits,
                             initargs=(1,)) as pool:
        if ordered:
            yield from pool.map(function, jobs)
            return
        futures = [pool.submit(function, job) for job in jobs]
        try:
            for future in as_completed(futures):
                yield future.result()
        finally:
            for future in futures:
                future.cancel()

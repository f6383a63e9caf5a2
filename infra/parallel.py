"""The executor: independent jobs on Dask distributed (sensitivity cases,
envelope samples, fit rounds, FMU runs).

:func:`parallel_map` runs ``function(job)`` for every job:

* in this process when one worker is asked for (or one job is given);
* else on a Dask cluster: the one of the enclosing :func:`cluster`
  context (a ``LocalCluster`` started on first use, or an existing
  cluster at ``scheduler``), or a ``LocalCluster`` of its own, closed
  when the jobs are done.

Local workers are processes with one thread and one BLAS thread each:
the kernels work on many tiny matrices, where threaded BLAS only
contends (measured 5x slower). A failed job never stops the others and
is never lost: it is reported with its inputs (:class:`TaskFailure`),
either in place of its result or, after all the other jobs, in one
:class:`TaskFailures` error: an input error (exit 2) when every job
failed on its input (:class:`~infra.errors.JudderError`, or memory),
else a bug (exit 1, the jobs named). Ctrl-C and SIGTERM close the cluster and its
worker processes. Dask logs nothing below CRITICAL and serves no
dashboard.
"""

from concurrent.futures import CancelledError
from contextlib import contextmanager
from dataclasses import dataclass
import functools
import logging
import math
import os
import shutil
import signal
import sys
import tempfile
import threading

from threadpoolctl import threadpool_limits

from .contract import warn
from .errors import JudderError
from .lifecycle import die_with_parent
from .provenance import current, recorded

__all__ = ["parallel_map", "cluster", "TaskFailure", "TaskFailures",
           "TaskInputErrors"]

#: Seconds to wait for an existing scheduler to answer.
CONNECT_TIMEOUT = 10
#: Seconds an existing scheduler has to answer a first hello
#: (:func:`_probe`), before any work.
PROBE_TIMEOUT = 5
#: Largest first message of a scheduler (its hello is a few hundred
#: bytes); a longer one is not Dask.
_HELLO_BYTES = 1 << 20
#: Batches per worker process of one :func:`parallel_map`: Dask's cost of
#: a task (about 2 ms here, paid in the process that also runs the
#: scheduler, on the same 2 cores) is paid per batch of jobs, while
#: enough batches remain for the load to balance.
BATCHES_PER_WORKER = 8
#: Failures spelled out in a :class:`TaskFailures` message.
_LISTED = 5
#: Characters of a job's description kept in a failure report.
_DESCRIPTION = 200
#: Loggers silenced while a cluster runs (worker processes get the level
#: through ``silence_logs``).
_LOGGERS = ("distributed", "tornado", "asyncio", "bokeh")


@dataclass(frozen=True)
class TaskFailure:
    """A job that raised instead of returning.

    Attributes
    ----------
    index : int
        Position of the job in ``jobs``.
    inputs : str
        The job, described (``describe(job)``).
    message : str
        ``'ExceptionType: text'`` of what it raised (the text alone for
        an input error).
    input_error : bool
        It failed on its input (:class:`~infra.errors.JudderError`, or
        memory), not by a bug.
    """

    index: int
    inputs: str
    message: str
    input_error: bool = False

    def __str__(self):
        return f"job {self.index} ({self.inputs}): {self.message}"


class TaskFailures(Exception):
    """Some jobs of a :func:`parallel_map` failed, one at least by a bug;
    ``failures`` lists them (the others completed). Not an input error:
    a command line reports it as an internal error (exit 1) naming the
    jobs."""

    def __init__(self, failures, total):
        self.failures = tuple(failures)
        self.total = total
        listed = "; ".join(str(f) for f in self.failures[:_LISTED])
        more = len(self.failures) - _LISTED
        super().__init__(
            f"{len(self.failures)} of {total} jobs failed: {listed}"
            + (f"; and {more} more" if more > 0 else ""))


class TaskInputErrors(TaskFailures, JudderError):
    """Some jobs of a :func:`parallel_map` failed, every one on its input
    (exit 2, the reasons named)."""


def _failures(failed, total):
    """The error of the failed jobs: input errors, or bugs."""
    kind = TaskInputErrors if all(f.input_error for f in failed) \
        else TaskFailures
    return kind(failed, total)


def _input_error(exc):
    return isinstance(exc, (JudderError, MemoryError))


def _describe(job):
    text = repr(job)
    return text if len(text) <= _DESCRIPTION else \
        text[:_DESCRIPTION - 3] + "..."


def _message(exc):
    """What a job raised: the text of an input error, else
    ``'ExceptionType: text'``."""
    if isinstance(exc, JudderError):
        return str(exc)
    return f"{type(exc).__name__}: {exc}"


_LIMITED = False


def _call(function, job):
    """Run one job on a worker, BLAS limited to one thread (also on
    workers of a cluster started elsewhere)."""
    global _LIMITED
    if not _LIMITED:
        threadpool_limits(limits=1)
        _LIMITED = True
    return function(job)


def _call_batch(function, jobs):
    """Run a batch of jobs on a worker: ``(True, result, None)`` per job,
    or ``(False, message, input_error)`` for one that raised (the others
    go on; see :func:`_message`)."""
    results = []
    for job in jobs:
        try:
            results.append((True, _call(function, job), None))
        except Exception as exc:   # reported, the others go on
            results.append((False, _message(exc), _input_error(exc)))
    return results


def _terminate(signum, frame):
    raise SystemExit(128 + signum)


def _check_address(address):
    """Refuse a malformed scheduler address before a Dask client is made
    of it (a client half made of one hangs for 20 s at exit)."""
    from distributed.comm.addressing import parse_address, parse_host_port
    try:
        scheme, location = parse_address(address)
        if scheme in ("tcp", "tls"):
            parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise JudderError(f"`scheduler` {address}: not a scheduler address "
                          f"({exc}); allowed: HOST:PORT or "
                          "tcp://HOST:PORT") from None


def _first_bytes(address, host, port):
    """Over a plain socket: a refused connection fails at once (not after
    Dask's retries), a silent peer after :data:`PROBE_TIMEOUT` s, and a
    first message longer than a Dask hello (its first 8 bytes are the
    length) before Dask would allocate that length."""
    import socket
    import struct

    def refuse(reason):
        raise JudderError(f"`scheduler` {address}: {reason}; allowed: the "
                          "address of a running Dask scheduler")
    try:
        with socket.create_connection((host, port),
                                      timeout=PROBE_TIMEOUT) as sock:
            head = b""
            while len(head) < 8:
                chunk = sock.recv(8 - len(head))
                if not chunk:
                    refuse("it closed the connection without a Dask hello")
                head += chunk
    except TimeoutError:
        refuse(f"no Dask answer within {PROBE_TIMEOUT} s")
    except OSError as exc:
        refuse(f"cannot connect ({exc.strerror or exc})")
    if struct.unpack("<Q", head)[0] > _HELLO_BYTES:
        refuse("it does not speak the Dask protocol")


def _probe(address):
    """Refuse, in :data:`PROBE_TIMEOUT` seconds, a scheduler address where
    nothing listens, where something accepts and stays silent, or where
    what answers does not speak Dask or is not a scheduler (a Dask client
    made on one waits 20 s, or for ever, then fails with a traceback).
    """
    import asyncio
    from distributed.comm import connect
    from distributed.comm.addressing import parse_address, parse_host_port
    scheme, location = parse_address(address)
    if scheme == "tcp":
        _first_bytes(address, *parse_host_port(location))

    async def identity():
        comm = await connect(address, timeout=PROBE_TIMEOUT)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    try:
        reply = asyncio.run(asyncio.wait_for(identity(), PROBE_TIMEOUT))
    except (TimeoutError, asyncio.TimeoutError):
        reason = f"no Dask answer within {PROBE_TIMEOUT} s"
    except Exception as exc:   # noqa: BLE001 - whatever garbage it sent
        reason = (f"it does not speak the Dask protocol "
                  f"({type(exc).__name__})")
    else:
        if isinstance(reply, dict) and reply.get("type") == "Scheduler":
            return
        reason = "it answers, but is not a Dask scheduler"
    raise JudderError(f"`scheduler` {address}: {reason}; allowed: the "
                      "address of a running Dask scheduler")


class _Cluster:
    """A Dask client, started on first use; see :func:`cluster`."""

    def __init__(self, workers=None, scheduler=None):
        if workers is not None and (int(workers) != workers or workers < 1):
            raise JudderError(f"`workers` {workers} is not allowed; "
                              "allowed: a whole number >= 1")
        if workers is not None and scheduler is not None:
            raise JudderError(f"`workers` {workers} is not allowed with "
                              f"`scheduler` {scheduler}: the cluster's own "
                              "workers run the jobs")
        self.workers = workers
        self.scheduler = scheduler
        self._client = None
        self._cluster = None
        self._scratch = None
        self._levels = {}
        self._sigterm = None
        self._children = set()

    def serial(self, workers, jobs, job_bytes=0):
        """True if ``jobs`` jobs with ``workers`` asked for run here."""
        if self.scheduler is not None:
            return False
        if self._client is not None:     # started: its workers are there
            return min(workers or self.workers or jobs, jobs) <= 1
        return worker_count(workers or self.workers, jobs, job_bytes)[0] <= 1

    def client(self, workers, jobs, job_bytes=0):
        """The Dask client; a local cluster is started with the workers
        :func:`worker_count` allows for these jobs (the reason said on
        stderr when fewer than asked)."""
        if self._client is None:
            count, reason = (None, "") if self.scheduler is not None else \
                worker_count(workers or self.workers, jobs, job_bytes)
            if reason:
                warn(reason)
            self._start(count)
        return self._client

    def _start(self, workers):
        for name in _LOGGERS:
            logger = logging.getLogger(name)
            self._levels[name] = logger.level
            logger.setLevel(logging.CRITICAL)
        main = threading.current_thread() is threading.main_thread()
        if main and signal.getsignal(signal.SIGTERM) is signal.SIG_DFL:
            # let SIGTERM unwind (closing the workers) instead of killing
            # this process alone
            self._sigterm = signal.signal(signal.SIGTERM, _terminate)
        if not main:
            self._connect(workers)
            return
        # a signal while Dask starts would leave half-made objects whose
        # clean-up blocks: hold it until the cluster can be closed
        pending = []
        held = {signal.SIGTERM: signal.signal(
            signal.SIGTERM, lambda signum, _: pending.append(signum))}
        # SIGINT ignored meanwhile: the worker processes inherit that
        # (Python then leaves it ignored), so that a terminal's Ctrl-C,
        # sent to the whole process group, reaches only this process,
        # which closes them; a Ctrl-C in these seconds is lost (the next
        # one stops the command). SIGTERM stays theirs: their parent's
        # death sends it (infra.lifecycle).
        held[signal.SIGINT] = signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            self._connect(workers)
        finally:
            for signum, handler in held.items():
                signal.signal(signum, handler)
        for signum in pending[:1]:
            handler = held[signum]
            if callable(handler):
                handler(signum, None)

    def _connect(self, workers):
        from distributed import Client, LocalCluster
        if self.scheduler is not None:
            _check_address(self.scheduler)
            try:
                self._client = Client(self.scheduler,
                                      timeout=CONNECT_TIMEOUT,
                                      set_as_default=False)
            except (OSError, TimeoutError, ValueError) as exc:
                self.close()
                raise JudderError(f"`scheduler` {self.scheduler}: cannot "
                                  f"connect ({exc})") from None
            return
        import psutil
        self._children = {p.pid for p in psutil.Process().children(
            recursive=True)}
        _remove_orphan_scratch()
        self._scratch = tempfile.mkdtemp(prefix=f"{_SCRATCH}{os.getpid()}-")
        with _main_script_hidden():
            self._cluster = LocalCluster(
                n_workers=workers,
                threads_per_worker=1, processes=True, host="127.0.0.1",
                dashboard_address=None, silence_logs=logging.CRITICAL,
                # no dashboard; its HTTP server (health checks) on any
                # free port
                scheduler_kwargs={"dashboard_address": "127.0.0.1:0",
                                  # its locks too, removed on closing
                                  # (not $TMPDIR/dask-scratch-space)
                                  "local_directory": self._scratch},
                local_directory=self._scratch,
                env={"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
                     "MKL_NUM_THREADS": "1"})
        self._client = Client(self._cluster, set_as_default=False)
        # every worker dies with this process, also when it is killed
        # (SIGKILL leaves no chance to close the cluster)
        self._client.run(die_with_parent)

    def close(self):
        """Close the client and a local cluster; kill any worker process
        that outlived it (a close interrupted, or during start-up)."""
        try:
            if self._client is not None:
                self._client.close()
            if self._cluster is not None:
                self._cluster.close()
        except Exception:           # noqa: BLE001 - the processes go below
            pass
        finally:
            if self._cluster is not None:
                from distributed.deploy.spec import SpecCluster
                # closed (or reaped below): nothing left for its atexit hook
                SpecCluster._instances.discard(self._cluster)
                _reap(self._children)
            self._client = self._cluster = None
            if self._scratch is not None:
                shutil.rmtree(self._scratch, ignore_errors=True)
                self._scratch = None
            if self._sigterm is not None:
                signal.signal(signal.SIGTERM, self._sigterm)
                self._sigterm = None
            for name, level in self._levels.items():
                logging.getLogger(name).setLevel(level)
            self._levels = {}


#: Resident memory of one local worker process with the kernels imported,
#: bytes: 137 MB measured after a chart of the example runs (64 MB
#: bare).
WORKER_BYTES = 150 * 2**20


def worker_count(asked, jobs, job_bytes=0):
    """Local worker processes for ``jobs`` jobs, and why fewer than asked.

    At most one per job, per core (the jobs are CPU-bound: more processes
    than cores only contend; 48 on 2 cores took 441 s where 2 took 14 s)
    and as many as 80 % of the memory available holds
    (:data:`WORKER_BYTES` + ``job_bytes`` each).

    Returns
    -------
    count : int
        >= 1 (1: run the jobs in this process).
    reason : str
        A warning naming what bounds the count, where ``asked`` was
        given and is cut, or memory bounds it; else ''.
    """
    from .memory import available_memory
    cores = os.cpu_count() or 1
    wanted = asked or cores
    free = available_memory()
    memory = int(0.8 * free // (WORKER_BYTES + job_bytes))
    count = max(1, min(wanted, jobs, cores, memory))
    if count == wanted or (asked is None and memory >= min(jobs, cores)):
        return count, ""
    bounds = [f"{jobs} job{'s' * (jobs != 1)}" if jobs == count else "",
              f"{cores} cores" if cores == count else "",
              f"memory for {max(memory, 0)} ({free / 2**30:.3g} GiB "
              f"available, {(WORKER_BYTES + job_bytes) / 2**20:.0f} MB "
              "each)" if memory <= count else ""]
    return count, (f"`workers` {wanted} reduced to {count}: "
                   + ", ".join(b for b in bounds if b))


#: Prefix of a local cluster's scratch folder in the temporary folder,
#: followed by the pid of the process that made it.
_SCRATCH = "judder-dask-"


def _remove_orphan_scratch():
    """Remove the scratch folders of local clusters whose process is gone
    (a SIGKILL leaves no chance to remove its own)."""
    import glob
    for folder in glob.glob(os.path.join(tempfile.gettempdir(),
                                         f"{_SCRATCH}*")):
        pid = os.path.basename(folder)[len(_SCRATCH):].split("-")[0]
        if pid.isdigit() and not os.path.exists(f"/proc/{pid}"):
            shutil.rmtree(folder, ignore_errors=True)


def _reap(before):
    """Kill the child processes started since ``before`` (pids), but
    multiprocessing's resource tracker (it outlives every pool, and
    complains when killed)."""
    import psutil

    def tracker(process):
        try:
            return "resource_tracker" in " ".join(process.cmdline())
        except psutil.Error:
            return False
    left = [p for p in psutil.Process().children(recursive=True)
            if p.pid not in before and not tracker(p)]
    for process in left:
        try:
            process.kill()
        except psutil.NoSuchProcess:
            pass
    psutil.wait_procs(left, timeout=5)


_ACTIVE = []


@contextmanager
def _main_script_hidden():
    """Start worker processes without importing the calling script again.

    A worker process is spawned: it imports the ``__main__`` of its parent
    from its file (as ``__mp_main__``) before it runs. A plain script that
    calls the API without an ``if __name__ == "__main__":`` guard would
    then run its calls again in every worker, start a cluster of its own
    there and fail ("Nanny failed to start"). The jobs sent to the workers
    are functions of the project's modules, never of ``__main__``, so the
    script's file is hidden while the workers start. A ``__main__`` run as
    a module (``python -m judder``, pytest) is imported by its name and
    left alone.
    """
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if main is None or path is None or \
            getattr(main, "__spec__", None) is not None:
        yield
        return
    del main.__file__
    try:
        yield
    finally:
        main.__file__ = path


@contextmanager
def cluster(workers=None, scheduler=None):
    """Share one Dask cluster among the :func:`parallel_map` calls inside.

    Parameters
    ----------
    workers : int, optional
        Local worker processes (default: all cores); 1 runs every job in
        this process.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``) whose
        workers run the jobs instead.

    Nothing is started until a :func:`parallel_map` inside needs it; the
    cluster is closed on leaving, also on Ctrl-C or SIGTERM. Inside
    another ``cluster()`` (without ``scheduler``) the outer one is shared.

    Raises
    ------
    JudderError
        ``workers`` not a whole number >= 1, ``workers`` together with
        ``scheduler``, or the scheduler does not answer as a Dask
        scheduler within :data:`PROBE_TIMEOUT` seconds.
    """
    if _ACTIVE and scheduler is None:
        # inside another one (a command's, around an API call): share it
        yield _ACTIVE[-1]
        return
    state = _Cluster(workers, scheduler)
    if scheduler is not None:    # a dead scheduler is refused before work
        _check_address(scheduler)
        _probe(scheduler)
    _ACTIVE.append(state)
    try:
        yield state
    finally:
        _ACTIVE.remove(state)
        state.close()


def parallel_map(function, jobs, workers=None, ordered=True, describe=None,
                 failures="raise", job_bytes=0):
    """Yield ``function(job)`` for every job (see the module docstring).

    Parameters
    ----------
    function : callable
        A module-level function (it is pickled).
    jobs : sequence
    workers : int, optional
        Processes (default: those of the enclosing :func:`cluster`, else
        all cores); 1 runs in this process.
    ordered : bool
        Yield in the order of ``jobs`` (else as each finishes).
    describe : callable, optional
        ``describe(job)``: the inputs a failure report names (default a
        shortened ``repr``).
    failures : {'raise', 'yield'}
        A failed job: ``'raise'`` goes on with the others and raises one
        :class:`TaskFailures` after the last; ``'yield'`` yields a
        :class:`TaskFailure` in place of its result.
    job_bytes : int
        Memory one job takes in its worker beyond :data:`WORKER_BYTES`
        (bounds the local workers, :func:`worker_count`).

    Raises
    ------
    TaskFailures
        With ``failures='raise'``, if any job failed.
    """
    if failures not in ("raise", "yield"):
        raise ValueError(f"failures={failures!r}; allowed: 'raise', 'yield'")
    jobs = list(jobs)
    describe = describe or _describe
    failed = []

    def outcome(index, message, input_error=False):
        failure = TaskFailure(index, describe(jobs[index]), message,
                              input_error)
        failed.append(failure)
        return failure

    state = _ACTIVE[-1] if _ACTIVE else _Cluster(workers)
    try:
        if state.serial(workers, len(jobs), job_bytes):
            results = _serial(function, jobs, outcome)
        else:
            # a worker process writes files with the command's
            # provenance, as this process would
            results = _distributed(
                state.client(workers, len(jobs), job_bytes),
                functools.partial(_with_provenance, current(), function),
                jobs, ordered, outcome)
        for item in results:
            if not isinstance(item, TaskFailure) or failures == "yield":
                yield item
    finally:
        if not _ACTIVE or state is not _ACTIVE[-1]:
            state.close()
    if failed and failures == "raise":
        raise _failures(failed, len(jobs))


def _with_provenance(provenance, function, job):
    with recorded(provenance):
        return function(job)


def _serial(function, jobs, outcome):
    with threadpool_limits(limits=1):
        for index, job in enumerate(jobs):
            try:
                result = function(job)
            except Exception as exc:   # reported, the others go on
                yield outcome(index, _message(exc), _input_error(exc))
            else:
                yield result


def _distributed(client, function, jobs, ordered, outcome):
    from distributed import as_completed
    workers = max(1, len(client.scheduler_info().get("workers", ())))
    size = max(1, math.ceil(len(jobs) / (workers * BATCHES_PER_WORKER)))
    batches = [range(start, min(start + size, len(jobs)))
               for start in range(0, len(jobs), size)]
    futures = client.map(_call_batch, [function] * len(batches),
                         [[jobs[i] for i in batch] for batch in batches],
                         pure=False)
    position = {future.key: batch for future, batch in zip(futures, batches)}
    waiting, head = {}, 0
    try:
        for future in as_completed(futures, loop=client.loop):
            batch = position[future.key]
            try:
                results = future.result()
            except (Exception, CancelledError) as exc:   # the worker died
                results = [(False, _message(exc), False)] * len(batch)
            future.release()
            for index, (done, value, input_error) in zip(batch, results):
                item = value if done else outcome(index, value, input_error)
                if not ordered:
                    yield item
                    continue
                waiting[index] = item
                while head in waiting:
                    yield waiting.pop(head)
                    head += 1
    finally:
        if client.status == "running":
            client.cancel([f for f in futures if not f.done()])

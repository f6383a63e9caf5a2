"""Worker processes that die with their parent and clean up on the way.

:func:`die_with_parent` is called at the start of a job in a worker
process (it is idempotent and cheap): on Linux the kernel sends the
worker SIGTERM when its parent dies, even by SIGKILL
(``prctl(PR_SET_PDEATHSIG)``), and SIGTERM raises ``SystemExit`` so that
``finally`` blocks run (a ``.part`` file is removed, see
:func:`infra.files.atomic_write`), then ends the process
:data:`GRACE_S` later (a pool worker would otherwise catch the exception
and wait for more work).

:class:`FolderLock` is an exclusive ``fcntl`` lock on a file in a folder,
for read-modify-write of a file shared by several processes.
"""

import ctypes
import fcntl
import multiprocessing
import os
import signal
import threading

__all__ = ["die_with_parent", "FolderLock"]

_PR_SET_PDEATHSIG = 1
_armed = set()


#: Seconds a worker has, after SIGTERM, to unwind (remove its ``.part``
#: file) before it exits for good.
GRACE_S = 1.0


def _exit_on_sigterm(signum, frame):
    # an executor's worker catches what its job raises and waits for the
    # next job: so exit for good once the job has unwound
    timer = threading.Timer(GRACE_S, os._exit, (128 + signum,))
    timer.daemon = True
    timer.start()
    raise SystemExit(128 + signum)


def die_with_parent():
    """Make this process receive SIGTERM when its parent dies, and turn
    SIGTERM into ``SystemExit``. Does nothing in the main process."""
    pid = os.getpid()
    if pid in _armed or multiprocessing.parent_process() is None:
        return
    _armed.add(pid)
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):   # not Linux: no parent-death signal
        pass
    try:
        signal.signal(signal.SIGTERM, _exit_on_sigterm)
    except ValueError:                  # not the main thread
        pass


class FolderLock:
    """Exclusive lock of ``folder`` (on the file ``folder/NAME``), held
    in a ``with`` block; blocks until other holders release it."""

    def __init__(self, folder, name=".index.lock"):
        self._path = os.path.join(os.fspath(folder), name)
        self._fd = None

    def __enter__(self):
        self._fd = os.open(self._path, os.O_RDWR | os.O_CREAT, 0o666)
        fcntl.flock(self._fd, fcntl.LOCK_EX)
        return self

    def __exit__(self, *exc):
        fcntl.flock(self._fd, fcntl.LOCK_UN)
        os.close(self._fd)
        self._fd = None
        return False

"""A job run in a child Python process, so that what crashes, aborts or
hangs in compiled code (a third-party FMU's binary, rumoca) cannot take
the tool down: the job pickled on the child's stdin and the answer on
its stdout, a line on its stderr before each step, in its own session,
dying with its parent, killed after a time limit.

Used by :mod:`sources.fmu_host` (FMU calls) and
:mod:`fmu.rumoca_child` (the Modelica front end); each writes its child's
side (``python -m ...``) and reads the reply.
"""

import ctypes
import os
import pickle
import signal
import subprocess
import sys
from pathlib import Path

__all__ = ["run_child", "die_with_parent", "write_stage", "signal_name"]


def run_child(arguments, job, limit, stage_prefix):
    """Run ``python ARGUMENTS`` with ``job`` pickled on its stdin.

    Parameters
    ----------
    arguments : sequence of str
        After the interpreter, e.g. ``("-m", "sources.fmu_host")``.
    job : object
        Pickled to the child's stdin.
    limit : float
        Seconds before the child is killed.
    stage_prefix : str
        Prefix of the child's stderr lines that name its steps
        (:func:`write_stage`).

    Returns
    -------
    reply, stages, status, stderr
        The unpickled stdout (None unless the child exited with 0), the
        steps it reached, its exit status (None if killed after
        ``limit``; negative: the signal) and its stderr.
    """
    root = str(Path(__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        filter(None, [root, os.environ.get("PYTHONPATH")]))}
    proc = subprocess.Popen(
        [sys.executable, *arguments],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, env=env, start_new_session=True)
    try:
        out, err = proc.communicate(pickle.dumps(job), timeout=limit)
        status = proc.returncode
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        status = None
    finally:
        if proc.poll() is None:        # Ctrl-C, SIGTERM in the parent
            proc.kill()
            proc.wait()
    err = err.decode("utf-8", "replace")
    stages = [line[len(stage_prefix):] for line in err.splitlines()
              if line.startswith(stage_prefix)]
    reply = pickle.loads(out) if status == 0 and out else None
    return reply, stages, status, err


def write_stage(stage_prefix, text):
    """In the child: name the step it starts, for the parent's message."""
    sys.stderr.write(f"{stage_prefix}{text}\n")
    sys.stderr.flush()


def die_with_parent():
    """In the child: be killed when the parent dies (Linux)."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)   # PR_SET_PDEATHSIG
    except (OSError, AttributeError):           # not Linux
        pass


def signal_name(status):
    """``SIGSEGV`` for an exit status of -11."""
    try:
        return signal.Signals(-status).name
    except ValueError:
        return f"signal {-status}"

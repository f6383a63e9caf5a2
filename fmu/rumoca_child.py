"""rumoca in a child process, so that its crashes, its aborts and its
appetite for memory and time cannot take the tool down.

rumoca is a compiled (Rust) extension: a deeply nested expression
overflows its stack (SIGSEGV), an allocation it cannot get aborts the
process (``memory allocation of 7200000000 bytes failed``, SIGABRT), and
neither can be caught in Python. :func:`flatten_isolated` therefore runs
it as the project runs a third-party FMU's binary
(:mod:`infra.children`, which :mod:`sources.fmu_host` uses too): a
child Python process (``python -m fmu.rumoca_child``), the job
pickled on its stdin and the answer on its stdout, a line on its stderr
before each step, in its own session, dying with its parent, killed
after a time limit. In addition the child

* runs rumoca in a thread with a large stack (:data:`STACK_BYTES`), so
  that long expressions (a sum of 5,000 terms) flatten instead of
  overflowing the 8 MiB of a main thread;
* limits its own address space (``RLIMIT_AS``) to the memory available
  (:func:`memory_limit`), so that an allocation beyond it fails in the
  child, not by swapping the machine or waking the kernel's OOM killer.

The parent turns each way the child can end into one
:class:`~fmu.frontend.FrontEndError` naming the file and what happened.
"""

import os
import pickle
import re
import resource
import sys
import threading
from pathlib import Path

from infra.children import (die_with_parent, run_child, signal_name,
                             write_stage)
from infra.environment import positive_setting
from infra.memory import available_memory

from .errors import FrontEndError

__all__ = ["flatten_isolated", "memory_limit", "time_limit",
           "STACK_BYTES", "TIME_LIMIT_S"]

#: Stack of the thread that runs rumoca (virtual memory: only what is
#: used is committed). 1 GiB holds a sum of 50,000 terms (which rumoca
#: then takes 250 s to flatten, against 3.5 s for 5,000) and parentheses
#: nested 200,000 deep.
STACK_BYTES = 1 << 30
#: Seconds rumoca may take for one model before the child is stopped
#: (MSL models take 10-25 s); ``JUDDER_FLATTEN_TIMEOUT`` sets another.
TIME_LIMIT_S = 900.0
#: Arguments of the Python child (the tests put a child that crashes).
_CHILD = ("-m", "fmu.rumoca_child")
#: Prefix of the child's lines that name the step it is in.
_STAGE = "judder-rumoca: "
#: Address space of the child beyond what it may allocate: the Python
#: interpreter, numpy, rumoca's code, the thread's reserved stack.
_BASE_BYTES = (1 << 30) + STACK_BYTES


def time_limit():
    """``JUDDER_FLATTEN_TIMEOUT`` (seconds) or :data:`TIME_LIMIT_S`."""
    return positive_setting("JUDDER_FLATTEN_TIMEOUT", TIME_LIMIT_S,
                            "seconds", FrontEndError)


def memory_limit():
    """Bytes the compiler may allocate: nine tenths of what this process
    may still use (:func:`infra.memory.available_memory`: the memory
    available now, the cgroup's and ``ulimit -v``'s room), at least 256
    MiB."""
    return max(1 << 28, int(0.9 * available_memory()))


def _stage(text):
    """In the child: name the step it starts (:data:`_STAGE`)."""
    write_stage(_STAGE, text)


def flatten_isolated(path, model_name, roots):
    """rumoca's flat model (a dict) of ``model_name``, flattened in a
    child process.

    Raises
    ------
    FrontEndError
        rumoca's diagnostics (file, line, what is wrong); or that rumoca
        crashed, ran out of the memory allowed or of time, naming the
        file, the step and the limit.
    """
    limit, memory = time_limit(), memory_limit()
    job = {"path": str(path), "model": model_name,
           "roots": [str(r) for r in roots], "memory": memory}
    reply, stages, status, err = run_child(_CHILD, job, limit, _STAGE)
    where = stages[-1] if stages else "starting"
    if status is None:
        raise FrontEndError(
            f"{path}: rumoca did not finish {model_name} within {limit:g} s "
            f"(it was {where}); allowed: a model that flattens in that time "
            "(JUDDER_FLATTEN_TIMEOUT=SECONDS allows more)")
    kind, value = reply if reply is not None else ("", "")
    wanted = re.search(r"memory allocation of (\d+) bytes failed", err)
    if wanted or (status != 0 and "MemoryError" in err) or \
            (kind == "failed" and value.startswith("MemoryError")):
        asked = f" (it asked for {int(wanted.group(1)) / 1e9:.3g} GB at " \
            "once)" if wanted else ""
        raise FrontEndError(
            f"{path}: {model_name} needs more memory than the "
            f"{memory / 1e9:.3g} GB available to the compiler while "
            f"{where}{asked}; allowed: a model that fits (look for large "
            "arrays: every element is a variable of its own)")
    if status < 0:
        raise FrontEndError(
            f"{path}: rumoca crashed ({signal_name(status)}) on "
            f"{model_name} while {where}; judder ran it in a child process: "
            "nothing else is affected, but this model cannot be compiled "
            f"as written (a deeply nested expression beyond the "
            f"{STACK_BYTES >> 20} MiB stack given to rumoca is one cause: "
            "split it into several equations)")
    if reply is None:
        raise RuntimeError(f"rumoca's child process ended with status "
                           f"{status} while {where} without a result: "
                           f"{err.strip()[-2000:]}")
    if kind == "error":
        raise FrontEndError(value)
    if kind == "failed":   # a panic of rumoca's Rust code, say
        raise FrontEndError(
            f"{path}: rumoca failed on {model_name} while {where} "
            f"({value.strip()[:500]}); judder ran it in a child process: "
            "nothing else is affected, but rumoca cannot compile this "
            "model as written")
    return value


def _flatten(job):
    """``('ok', flat dict)`` or ``('error', message)``, in this process."""
    import rumoca
    path, model_name, roots = job["path"], job["model"], job["roots"]
    try:
        _stage("checking the source")
        diagnostics = rumoca.validate(path, model=model_name)
    except Exception as exc:       # rumoca raises its own error classes
        return ("error", f"{path}: {exc}"
                f"{_library_errors(rumoca, roots, path)}")
    errors = [d for d in diagnostics
              if str(getattr(d, "severity", "error")).lower().endswith(
                  "error")]
    if errors:
        return ("error", "\n".join(str(d) for d in errors))
    session = model = None
    try:
        _stage("loading the libraries")
        session = rumoca.Session(roots=roots)
        _stage("flattening")
        model = session.load(path, model=model_name)
        _stage("reading the flat model")
        return ("ok", model.to_dict())
    except Exception as exc:       # rumoca raises its own error classes
        return ("error", f"{path}: {exc}"
                f"{_library_errors(rumoca, roots, path)}")
    finally:
        del session, model


def _library_errors(rumoca, roots, path):
    """Syntax errors anywhere in the model's own library (rumoca only says
    'failed'); the other libraries of the path (the MSL: 2,400 files) are
    not searched."""
    found = []
    path = Path(path).resolve()
    for root in roots:
        if not path.is_relative_to(Path(root).resolve()):
            continue
        for source in sorted(Path(root).rglob("*.mo")):
            try:
                source.read_bytes().decode("utf-8")
            except UnicodeDecodeError as exc:
                found.append(f"{source}: not UTF-8 text (byte "
                             f"0x{exc.object[exc.start]:02x} at offset "
                             f"{exc.start}); save the file as UTF-8")
                continue
            found += [str(d) for d in rumoca.validate(str(source))
                      if "error" in str(d).lower()]
    return ("\n" + "\n".join(found)) if found else ""


def _child():
    die_with_parent()
    # rumoca also loads the folders of MODELICAPATH by itself: the
    # parent gives every library folder in "roots" (MODELICAPATH's
    # among them, fmu.classes), some as rewritten copies (fmu.rewrite),
    # and the MSL read twice, once rewritten, is "Duplicate class
    # 'Modelica.Blocks.Continuous.Integrator' ... with non-identical
    # definition"
    os.environ.pop("MODELICAPATH", None)
    job = pickle.load(sys.stdin.buffer)
    memory = job["memory"] + _BASE_BYTES
    _, hard = resource.getrlimit(resource.RLIMIT_AS)
    if hard == resource.RLIM_INFINITY or memory < hard:
        resource.setrlimit(resource.RLIMIT_AS, (memory, hard))
    threading.stack_size(STACK_BYTES)
    reply = []

    def work():
        try:
            reply.append(_flatten(job))
        except BaseException as exc:   # rumoca's panics are BaseException
            reply.append(("failed", f"{type(exc).__name__}: {exc}"))
    worker = threading.Thread(target=work)
    worker.start()
    worker.join()
    sys.stdout.buffer.write(pickle.dumps(reply[0]))
    sys.stdout.flush()


if __name__ == "__main__":
    _child()

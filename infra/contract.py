"""The error contract of every command line of the project, in one place.

:func:`run_guarded` runs a command and turns what escapes it into an exit
status and one line on stderr:

* :class:`~infra.errors.JudderError` (bad input, or a request that cannot
  be answered): ``PROG: error: MESSAGE``, exit 2;
* an ``OSError`` on a file (disk full, read-only folder, file too large):
  the file and the reason, exit 2;
* ``MemoryError``: exit 2, saying the request does not fit in memory;
* Ctrl-C (SIGINT) and SIGTERM: exit 130 (143), no partial output;
* a broken pipe (``judder params --json | head -1``): quietly, exit 0
  (the reader has what it wanted);
* anything else is a bug: ``PROG: internal error`` with the exception and
  how to report it, exit 1 (the traceback only with ``JUDDER_DEBUG=1``).
"""

import contextlib
import os
import re
import signal
import sys
import traceback

from infra.errors import (EXIT_ERROR, EXIT_INTERRUPTED, EXIT_OK,
                          JudderError)

__all__ = ["run_guarded", "EXIT_INTERNAL", "EXIT_TERMINATED",
           "join_negative_values", "Terminated"]

#: A bug in the tool: the message says how to report it.
EXIT_INTERNAL = 1
#: Stopped by SIGTERM (128 + 15); no partial output was written.
EXIT_TERMINATED = 128 + signal.SIGTERM

_REPORT = ("this is a bug in judder, not in your input; please report it "
           "with the command line and this message (JUDDER_DEBUG=1 shows "
           "the traceback)")

#: A value that starts with '-' but is a number or a grid, not an option.
_NEGATIVE_VALUE = re.compile(r"-(\d|\.\d|inf|nan)", re.IGNORECASE)


class Terminated(BaseException):
    """Raised in the main thread on SIGTERM, so that ``finally`` blocks
    and context managers clean up as on Ctrl-C."""


def join_negative_values(argv):
    """``--opt -0.002:0.002:9`` as ``--opt=-0.002:0.002:9``.

    argparse takes a value starting with '-' for an option unless it is a
    plain negative number; a grid or list of negative numbers would be
    refused. Joined with '=', argparse reads it as the option's value.
    """
    out = []
    for item in argv:
        if (out and out[-1].startswith("--") and "=" not in out[-1]
                and _NEGATIVE_VALUE.match(item)):
            out[-1] = f"{out[-1]}={item}"
        else:
            out.append(item)
    return out


def _on_sigterm(signum, frame):
    raise Terminated()


@contextlib.contextmanager
def _sigterm_raises():
    """SIGTERM raises :class:`Terminated` while the command runs."""
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    except ValueError:          # not the main thread: leave it alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def run_guarded(prog, command):
    """Run ``command()`` under the error contract; returns the exit status."""
    try:
        with _sigterm_raises():
            command()
        sys.stdout.flush()
    except JudderError as exc:
        _say(f"{prog}: error: {exc}")
        return EXIT_ERROR
    except KeyboardInterrupt:
        _say(f"{prog}: interrupted; no partial output was written")
        return EXIT_INTERRUPTED
    except Terminated:
        _say(f"{prog}: terminated; no partial output was written")
        return EXIT_TERMINATED
    except BrokenPipeError:
        _quiet_stdout()
        return EXIT_OK
    except MemoryError:
        _say(f"{prog}: error: the request does not fit in this machine's "
             "memory; allowed: a smaller grid or fewer points")
        return EXIT_ERROR
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        _say(f"{prog}: error: cannot use{where}: "
             f"{exc.strerror or exc}")
        return EXIT_ERROR
    except Exception as exc:
        if os.environ.get("JUDDER_DEBUG"):
            traceback.print_exc()
        _say(f"{prog}: internal error: {type(exc).__name__}: "
             f"{_one_line(exc)}; {_REPORT}")
        return EXIT_INTERNAL
    return EXIT_OK


def _one_line(exc):
    return " ".join(str(exc).split())[:300]


def _say(text):
    try:
        print(" ".join(text.split("\n")), file=sys.stderr)
    except (BrokenPipeError, OSError):
        pass


def _quiet_stdout():
    """After a broken pipe: point stdout at /dev/null so that the flush
    at exit does not raise again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass

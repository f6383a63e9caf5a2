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

__all__ = ["run_guarded", "signals_held", "warn", "EXIT_INTERNAL",
           "EXIT_TERMINATED", "join_negative_values", "Terminated"]

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


class _Signals:
    """The handlers of SIGINT and SIGTERM while a command runs.

    The first signal raises (``KeyboardInterrupt``, :class:`Terminated`)
    in the main thread, so that ``finally`` blocks remove ``.part`` files
    and close worker processes; a second one while that clean-up runs
    ends the process at once with the same exit status (a clean-up that
    blocks cannot hold the user; it says a ``.part`` file may remain:
    the next campaign into the folder removes it). After the command,
    while the report is printed and the interpreter exits, a signal ends
    the process at once with the usual line. A SIGINT that the
    parent ignores (a job started with ``&`` or ``nohup``) stays ignored.
    """

    def __init__(self, prog, words=None):
        self.prog = prog
        self.words = words
        self.unwinding = False
        self.done = False
        self.held = None
        self.previous = {}

    def install(self):
        for signum in (signal.SIGINT, signal.SIGTERM):
            try:
                current = signal.getsignal(signum)
                if signum == signal.SIGINT and current is signal.SIG_IGN:
                    continue
                self.previous[signum] = signal.signal(signum, self._handle)
            except ValueError:      # not the main thread: leave it alone
                return

    def restore(self):
        for signum, handler in self.previous.items():
            signal.signal(signum, handler)
        self.previous = {}

    def _handle(self, signum, frame):
        if self.done:
            _say(_stopped(self.prog, signum))
            os._exit(_stop_status(signum))
        if self.unwinding:
            _say(f"{self.prog}: stopped again while cleaning up; a "
                 "temporary .NAME.*.part file may remain")
            os._exit(_stop_status(signum))
        if self.held is not None:
            self.held.append(signum)
            return
        self.raise_for(signum)

    def raise_for(self, signum):
        self.unwinding = True
        if signum == signal.SIGINT:
            raise KeyboardInterrupt()
        raise Terminated()


_ACTIVE = []


@contextlib.contextmanager
def signals_held():
    """Hold SIGINT and SIGTERM in the block, act on the first at its end.

    For imports of compiled libraries (numpy turns an exception raised
    inside its import into an ``ImportError`` that reads like a broken
    installation): the block runs to its end, then the signal raises as
    usual. Outside :func:`run_guarded` it does nothing.
    """
    signals = _ACTIVE[-1] if _ACTIVE else None
    if signals is None or signals.held is not None:
        yield
        return
    signals.held = []
    try:
        yield
    finally:
        pending, signals.held = signals.held, None
    if pending:
        signals.raise_for(pending[0])


def _stop_status(signum):
    return EXIT_INTERRUPTED if signum == signal.SIGINT else EXIT_TERMINATED


def _stopped(prog, signum):
    word = "interrupted" if signum == signal.SIGINT else "terminated"
    return f"{prog}: {word}; no partial output was written"


def run_guarded(prog, command, whole_process=False, words=None):
    """Run ``command()`` under the error contract; returns the exit status.

    SIGINT and SIGTERM are handled from the first line of ``command`` on:
    a command line calls this before its heavy imports (inside
    ``command``), so that a signal at any moment gives one line and
    exit 130 or 143.

    Parameters
    ----------
    prog : str
        The name the messages start with.
    command : callable
        Called without arguments.
    whole_process : bool
        The command is the whole process (a command line run from a
        shell): the handlers stay until it exits, so that a signal while
        the interpreter shuts down still gives one line. Otherwise (a
        call inside a test) the previous handlers are restored.
    words : callable, optional
        Puts a library's message in the words of the command line (the
        arguments it names as the options carrying them); applied to
        the warnings said while ``command`` runs.
    """
    signals = _Signals(prog, words)
    signals.install()
    _ACTIVE.append(signals)
    try:
        return _guarded(prog, command)
    finally:
        _ACTIVE.remove(signals)
        # from here on a signal ends the process at once (nothing is
        # left to unwind)
        signals.done = True
        if not whole_process:
            signals.restore()


def _guarded(prog, command):
    try:
        command()
        sys.stdout.flush()
    except JudderError as exc:
        _say(f"{prog}: error: {exc}")
        return EXIT_ERROR
    except KeyboardInterrupt:
        _say(_stopped(prog, signal.SIGINT))
        return EXIT_INTERRUPTED
    except Terminated:
        _say(_stopped(prog, signal.SIGTERM))
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


def warn(text):
    """A warning line on stderr (the command goes on), in the words of
    the command running (:func:`run_guarded`'s ``words``)."""
    words = _ACTIVE[-1].words if _ACTIVE else None
    _say(f"judder: warning: {text if words is None else words(text)}")


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

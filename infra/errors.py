"""Exceptions for bad input, and the exit codes every command line uses.

A :class:`JudderError` carries a message that names the input, its value
and what is allowed; a command line prints it as ``PROG: error: MESSAGE``
and exits with :data:`EXIT_ERROR`. Anything else escaping is a bug.
"""

__all__ = ["JudderError", "ParameterError", "EXIT_OK", "EXIT_ERROR",
           "EXIT_INTERRUPTED"]

#: The command did what was asked.
EXIT_OK = 0
#: Bad input, or a computation that cannot answer it; the message says why
#: (argparse uses the same code for malformed options).
EXIT_ERROR = 2
#: Interrupted (Ctrl-C, 128 + SIGINT); no partial output was written.
EXIT_INTERRUPTED = 130


class JudderError(ValueError):
    """Bad input to the tool; the message says what is wrong and what is allowed."""


class ParameterError(JudderError):
    """A model parameter or option is unknown, missing or out of range."""

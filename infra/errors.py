"""Exceptions for bad input, the options a command line says for the
library's arguments, and the exit codes every command line uses.

A :class:`JudderError` carries a message that names the input, its value
and what is allowed; a command line prints it as ``PROG: error: MESSAGE``
and exits with :data:`EXIT_ERROR`. Anything else escaping is a bug.

A library module names an argument of its own in backticks, as SciPy
does (`` `scatter` ``); a command line puts its option in its
place (:func:`in_options`), so a Python caller reads the argument it
passed and a command-line user the option they typed.
"""

import re

__all__ = ["JudderError", "ParameterError", "in_options", "EXIT_OK",
           "EXIT_ERROR", "EXIT_INTERRUPTED"]

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


def in_options(message, options):
    """``message`` with each argument named in backticks that ``options``
    maps (argument name -> option) replaced by its option.

    Examples
    --------
    >>> in_options("`scatter` 0 is not allowed; see `seed`",
    ...            {"scatter": "--scatter"})
    '--scatter 0 is not allowed; see `seed`'
    """
    return re.sub(r"`(\w+)`", lambda m: options.get(m.group(1), m.group(0)),
                  message)

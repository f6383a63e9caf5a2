"""Exceptions for bad input, the one check of a number a user gives, and
the exit codes every command line uses.

A :class:`JudderError` carries a message that names the input, its value
and what is allowed; a command line prints it as ``PROG: error: MESSAGE``
and exits with :data:`EXIT_ERROR`. Anything else escaping is a bug.

A library module names an argument of its own in backticks, as SciPy
does (`` `scatter` ``); a command line puts its option in its
place (:func:`in_options`), so a Python caller reads the argument it
passed and a command-line user the option they typed.
"""

import math
import re

__all__ = ["JudderError", "ParameterError", "check_number", "in_options",
           "EXIT_OK", "EXIT_ERROR", "EXIT_INTERRUPTED"]

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


def check_number(name, value, unit, low=0.0, strict=True):
    """``value`` if it is finite and above ``low`` (``strict``) or not
    below it; else a :class:`JudderError` naming ``name``, the value and
    what is allowed. ``None`` passes (an option not given).

    Parameters
    ----------
    name : str
        The option (``--pf``) or argument (``p_f``) it came in.
    value : float or None
    unit : str
        Its unit as the user gave it (``bar``, ``Hz``, ``1/s``).
    low : float
        The bound; ``-inf``: any finite number.
    strict : bool
        ``value > low`` rather than ``value >= low``.
    """
    if value is None:
        return value
    value = float(value)
    if math.isfinite(value) and (value > low if strict else value >= low):
        return value
    given = f"{name} {value:g}" if name.startswith("-") else \
        f"{name} = {value:g}"
    allowed = ("a finite number" if low == -math.inf else
               f"a finite value {'>' if strict else '>='} {low:g} {unit}")
    raise JudderError(f"{given} {unit} is not allowed; allowed: {allowed}")


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

"""Settings a user gives through the environment (time limits of long
or hanging work), read with one rule: a finite number > 0."""

import math
import os

from .errors import JudderError

__all__ = ["positive_setting"]


def positive_setting(name, default, unit, error=JudderError):
    """The number in the environment variable ``name``, or ``default``.

    Raises ``error`` naming the variable, its text and what is allowed
    (``unit`` > 0) when it is not a finite number > 0.
    """
    text = os.environ.get(name)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (value > 0 and math.isfinite(value)):
        # a text that is no number is quoted, so an empty or odd one shows
        shown = text if not math.isnan(value) else repr(text)
        raise error(f"{name}={shown} is not allowed; allowed: {unit} > 0")
    return value

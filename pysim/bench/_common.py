"""What the format readers share: names of a time channel, messages that
list names, metadata as plain Python, ``name [unit]`` headers."""

import re

import numpy as np

from infra.errors import JudderError

from .units import unit_factor

__all__ = ["TIME_NAMES", "one_line", "listing", "plain", "split_header",
           "column_factor", "on_one_clock", "is_time_name", "time_unit"]

#: Names of a time channel, column or variable (lower case).
TIME_NAMES = ("time", "t", "zeit", "timestamp")
def is_time_name(name, time=None):
    """Whether a column, channel or variable ``name`` (its name without a
    ``[unit]``) is the file's time: the one ``time`` names (the ``time``
    role's :class:`~pysim.bench.acquisition.ChannelSpec`), else one
    of :data:`TIME_NAMES`."""
    name = split_header(name)[0]
    if time is not None:
        return name == time.name
    return name.lower() in TIME_NAMES


def time_unit(time, unit):
    """The unit of a time column: the ``time`` role's, else the file's
    ``unit``."""
    return time.unit if time is not None and time.unit else unit


#: Channel names listed in a message, at most.
LISTED = 40


def one_line(exc, limit=200):
    """An exception's message on one line, at most ``limit`` characters."""
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text if len(text) <= limit else text[:limit - 3] + "..."


def listing(names):
    """Names for a message: the first :data:`LISTED`, and how many more."""
    if not names:
        return "(none)"
    shown = ", ".join(repr(n) for n in names[:LISTED])
    more = len(names) - LISTED
    return shown + (f" and {more} more" if more > 0 else "")


def plain(value):
    """A metadata value as plain Python (numpy scalars and arrays, dicts)."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.datetime64):
        return str(value)
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    return value


def split_header(cell):
    """``name [unit]`` -> (name, unit); a plain name has unit None."""
    match = re.fullmatch(r"\s*(.*?)\s*\[([^\[\]]*)\]\s*", cell)
    if match:
        return match.group(1), match.group(2).strip() or None
    return cell.strip(), None


def column_factor(path, column, kind):
    """Factor of the unit of a (name, unit) column; 1 when it has none."""
    name, unit = column
    if unit is None:
        return 1.0
    try:
        return unit_factor(unit, kind)
    except JudderError as exc:
        raise JudderError(f"{path}: column {name!r}: {exc}") from None


def on_one_clock(path, raws, starts, where):
    """Channels of separately started clocks laid on one time base.

    Parameters
    ----------
    path : path
        The file, for messages.
    raws : dict
        Name -> (time s from the channel's own clock start, values, unit).
    starts : dict
        Name -> the absolute instant of that clock start
        (``numpy.datetime64``), or None where the file records none.
    where : str
        Where the format records a start, for the message.

    Returns
    -------
    dict
        ``raws`` with each time from the earliest start among them (the
        same where no channel records a start: the file's channels are
        then taken to share one clock, as a single-clock recording has
        them).

    Raises
    ------
    JudderError
        Some channels record a start and others do not: naming both, as
        they cannot be aligned.
    """
    known = {n: t for n, t in starts.items() if t is not None and n in raws}
    if not known:
        return raws
    unknown = [n for n in raws if n not in known]
    if unknown:
        raise JudderError(
            f"{path}: channels {listing(sorted(known))} record when their "
            f"clock started ({where}) and {listing(unknown)} do not, so "
            "they cannot be laid on one time base; allowed: channels that "
            "all record their start, or none")
    first = min(known.values())
    return {n: (time + (known[n] - first) / np.timedelta64(1, "s"),
                values, unit)
            for n, (time, values, unit) in raws.items()}

"""What the studies' numbers may be: the rule of each argument (unit,
allowed range, plausibility), checked where a value enters, whether an
option's text (:meth:`Rule.parse`) or a Python caller's value
(:meth:`Rule.check`).

A plain number is in the argument's unit (frequencies Hz, amplitudes
bar, times s, speeds rpm, parameters SI); a number may carry a unit instead
(``1.2kHz``, ``300mbar``, ``50ms``), read by
:func:`infra.quantities.parse_quantity`. A plain number far outside what
its unit makes plausible is refused with the likely slip (``30000`` bar:
Pa given for bar; ``p_m=10``: bar given for Pa).

Grids (``START:STOP:N``), lists and dither waveforms are parsed here too.
Nothing here knows a command line: the options' parsers
(:mod:`judder.commands._values`) apply these rules.
"""


import math

import numpy as np

from infra.errors import JudderError
from infra.quantities import has_unit, parse_quantity
from infra.units import PA_PER_BAR

#: Dither frequencies allowed, Hz: below, the period needs more
#: sub-intervals than any engine takes; above, no hydraulic valve
#: dithers and the multipliers round to 1.
FREQ_RANGE_HZ = (1e-3, 1e5)


#: A plain --pf above this (bar) is taken for a slip of unit (Pa for bar).
MAX_PLAIN_PF_BAR = 100.0


#: A plain p_m below this (Pa, i.e. 1 bar) is taken for bar given as Pa.
MIN_PLAIN_P_M_PA = 1e5


#: Most worker processes (a request for more is a typo).
MAX_WORKERS = 256


#: Longest simulated time of one run, s.
MAX_DURATION_S = 3600.0


def option_value(text, option, unit, low=-math.inf, high=math.inf,
                 low_open=False, amplitude=True):
    """A number of an option, in ``unit`` (plain, or with a unit).

    Raises
    ------
    JudderError
        Naming the option, the value and the allowed range.
    """
    value = parse_quantity(text, unit, option)
    if _outside(value, low, high, low_open).any():
        raise JudderError(f"{option} {text} is not allowed; allowed: "
                          f"{_allowed(unit, low, high, low_open)}")
    if amplitude and unit == "bar" and not has_unit(text):
        check_amplitudes([value], option, f": write {text}Pa, or give the "
                                          "unit")
    return value


def check_amplitudes(values_bar, option, fix=""):
    """Refuse a dither amplitude above :data:`MAX_PLAIN_PF_BAR`: Pa given
    where bar is meant (an option, a list, a grid or a table column);
    ``fix`` says how to write it."""
    for value in values_bar:
        if value is not None and value > MAX_PLAIN_PF_BAR:
            raise JudderError(
                f"{option} {value:g} bar is not plausible for a dither "
                f"amplitude (a plain number is in bar); did you give Pa? "
                f"{value:g} Pa = {value / PA_PER_BAR:g} bar{fix} (allowed: "
                f"at most {MAX_PLAIN_PF_BAR:g} bar)")


def _outside(values, low, high, low_open):
    """Where ``values`` are not finite or not in the range, as a boolean
    array."""
    values = np.atleast_1d(np.asarray(values, dtype=float))
    below = values <= low if low_open else values < low
    return ~np.isfinite(values) | below | (values > high)


def _allowed(unit, low, high, low_open, hint=True):
    parts = []
    if low > -math.inf:
        parts.append(f"{'>' if low_open else '>='} {low:g}")
    if high < math.inf:
        parts.append(f"<= {high:g}")
    unit_text = "" if unit == "1" else f" {unit}"     # a plain ratio
    return (" and ".join(parts) or "a finite number") + unit_text + (
        " (a plain number; or with a unit, e.g. 1.2kHz)"
        if hint and unit == "Hz" else "")


class Rule:
    """What one number may be: its unit (of a plain number), its allowed
    range and whether it is a dither amplitude; :meth:`parse` reads an
    option's text (:func:`option_value`), :meth:`check` a Python caller's
    value, by the same rule.

    Parameters
    ----------
    unit : str
        The unit of a plain number (Hz, bar, s, rpm, 1/s).
    low, high : float
        The allowed range; ``low_open`` excludes ``low`` itself.
    amplitude : bool
        A plain number in bar is a dither amplitude: one above
        :data:`MAX_PLAIN_PF_BAR` is taken for Pa (False for a margin).
    """

    def __init__(self, unit, low=-math.inf, high=math.inf,
                 low_open=False, amplitude=True):
        self.unit = unit
        self.low, self.high, self.low_open = low, high, low_open
        self.amplitude = amplitude

    def parse(self, text, name):
        """The number ``text`` gives (plain in ``unit``, or with a unit),
        if allowed; else a :class:`JudderError` naming ``name``."""
        return option_value(text, name, self.unit, self.low, self.high,
                            self.low_open, self.amplitude)

    def check(self, value, name):
        """``value`` (a number or an array, in ``unit``) if every element
        is finite and allowed, else a :class:`JudderError` naming
        ``name``: the same rule at the API as on the command line."""
        values = np.atleast_1d(np.asarray(value, dtype=float))
        bad = _outside(values, self.low, self.high, self.low_open)
        if bad.any():
            allowed = _allowed(self.unit, self.low, self.high, self.low_open,
                               hint=False)
            unit = "" if self.unit == "1" else f" {self.unit}"
            raise JudderError(f"{name} = {values[bad][0]:g}{unit} is not "
                              f"allowed; allowed: {allowed}")
        return value



#: The rule of each argument of the studies that an option carries: a
#: Python caller's value is checked by the same rule as the option's
#: (:func:`studies._common.checked_values`; the options:
#: :mod:`judder.commands._values`).
RULES = {"freq_hz": Rule("Hz", *FREQ_RANGE_HZ),
         "p_f_bar": Rule("bar", 0.0),
         "p_max_bar": Rule("bar", 0.0, low_open=True),
         "duration": Rule("s", 0.0, MAX_DURATION_S, low_open=True),
         "min_growth": Rule("1/s", 0.0),
         "threshold_spread": Rule("1/s", 0.0),
         "judder_limit_rpm": Rule("rpm", 0.0, low_open=True),
         "margin_bar": Rule("bar", 0.0, amplitude=False),
         "margin_hz": Rule("Hz", 0.0),
         "valve_max_bar": Rule("bar", 0.0, low_open=True)}

#: The bench's known scatter of the onsets, by error model: a share of
#: the amplitude, or bar.
SCATTER = {"relative": Rule("1", 0.0, 1.0, low_open=True),
           "absolute": Rule("bar", 0.0, low_open=True, amplitude=False)}


#: Most values of one grid axis (a typo like N = 100000000000 would
#: otherwise allocate hundreds of GiB).
MAX_GRID_VALUES = 100_000


def parse_grid(text, option, unit, allow_negative=False):
    """Parse ``START:STOP:N`` (or a single value) into a linspace.

    START and STOP are plain numbers in ``unit`` or carry a unit
    (``0:300mbar:10``); see :func:`option_value`.

    Raises
    ------
    JudderError
        Naming ``option`` and saying what is allowed.
    """
    parts = text.split(":")
    lowest = "" if allow_negative else "0 <= "
    allowed = (f"allowed: START:STOP:N with {lowest}START <= STOP in {unit} "
               f"and N a whole number from 1 to {MAX_GRID_VALUES} (1 only "
               f"when START = STOP), or one value (e.g. {option} 10:220:300)")
    low, high = (-math.inf, math.inf) if allow_negative else (0.0, math.inf)
    if unit == "Hz":
        low, high = FREQ_RANGE_HZ
    try:
        if len(parts) == 1:
            start = stop = option_value(parts[0], option, unit, low, high)
            count = 1
        elif len(parts) == 3:
            start = option_value(parts[0], option, unit, low, high)
            stop = option_value(parts[1], option, unit, low, high)
            count = int(parts[2])
        else:
            raise ValueError
    except JudderError:
        raise
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a grid; {allowed}") \
            from None
    if start > stop or count < 1 or count > MAX_GRID_VALUES \
            or (count == 1 and start != stop):
        raise JudderError(f"{option} {text!r} is not allowed; {allowed}")
    return np.linspace(start, stop, count)


def parse_list(text, option, convert=float):
    """Comma-separated values of ``option``."""
    items = [item.strip() for item in text.split(",")]
    if len(items) > 1 and not all(items):
        raise JudderError(f"{option} {text!r} has an empty item; allowed: "
                          "values separated by single commas")
    items = [item for item in items if item]
    try:
        values = [convert(item) for item in items]
    except JudderError:          # a value out of range, or its unit
        raise
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a comma-separated list "
                          "of numbers") from None
    if not values:
        raise JudderError(f"{option} is empty")
    return values


def refuse_decimal(decimal, files, instead):
    """Refuse a decimal separator where no CSV is read: `decimal` is for
    the CSV ``files`` (in words), and not allowed ``instead`` (the inputs
    given, in words)."""
    if decimal:
        raise JudderError(f"`decimal` is for {files}; allowed: no "
                          f"`decimal` {instead}")

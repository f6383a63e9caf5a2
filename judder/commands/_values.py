"""Values of the command-line options: numbers with or without a unit,
checked against what is allowed and plausible before any work.

A plain number is in the option's unit (frequencies Hz, amplitudes bar,
times s, speeds rpm, parameters SI); a number may carry a unit instead
(``--freq 1.2kHz``, ``--pf 300mbar``, ``--duration 50ms``), read by
:func:`infra.quantities.parse_quantity`. A plain number far outside what
its unit makes plausible is refused with the likely slip
(``--pf 30000``: Pa given for bar; ``--set p_m=10``: bar given for Pa).

Grids (``START:STOP:N``), lists and dither waveforms are parsed here too.
The argparse ``type=`` parsers (:class:`Quantity`, :class:`Grid`,
:class:`Listed`, ...) parse each option once, with its unit; the API
functions check a Python caller's arguments with the same rule objects
(:data:`RULES`, :meth:`Quantity.check`). Nothing here knows a command.
"""

import argparse
import math

import numpy as np

from infra.contract import warn
from infra.errors import JudderError
from infra.quantities import has_unit, parse_quantity
from infra.units import PA_PER_BAR

from ..inputs import read_input

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


class Quantity:
    """An argparse ``type=``: one number of an option, in ``unit`` (plain)
    or with a unit of its own (:func:`option_value`), within the allowed
    range.

    Parameters
    ----------
    option : str
        The option, named in the error message.
    unit : str
        The unit of a plain number (Hz, bar, s, rpm, 1/s).
    low, high : float
        The allowed range; ``low_open`` excludes ``low`` itself.
    amplitude : bool
        A plain number in bar is a dither amplitude: one above
        :data:`MAX_PLAIN_PF_BAR` is taken for Pa (False for a margin).
    """

    def __init__(self, option, unit, low=-math.inf, high=math.inf,
                 low_open=False, amplitude=True):
        self.option, self.unit = option, unit
        self.low, self.high, self.low_open = low, high, low_open
        self.amplitude = amplitude

    def __call__(self, text):
        try:
            return option_value(text, self.option, self.unit, self.low,
                                self.high, self.low_open, self.amplitude)
        except JudderError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None

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


class QuantityList(Quantity):
    """An argparse ``type=``: comma-separated numbers, each a
    :class:`Quantity`."""

    def __call__(self, text):
        return [super(QuantityList, self).__call__(item.strip())
                for item in text.split(",")]


class WholeNumber:
    """An argparse ``type=``: a whole number of an option from ``low`` to
    ``high``."""

    def __init__(self, option, low, high):
        self.option, self.low, self.high = option, low, high

    def __call__(self, text):
        try:
            value = int(text)
        except ValueError:
            value = None
        if value is None or not self.low <= value <= self.high:
            allowed = (f"from {self.low} to {self.high}"
                       if self.high < 2 ** 62 else f">= {self.low}")
            raise argparse.ArgumentTypeError(
                f"{self.option} {text} is not allowed; allowed: a whole "
                f"number {allowed}")
        return value


class Grid:
    """An argparse ``type=``: a grid of an option, ``START:STOP:N`` or a
    list (:func:`parse_grid`), as an array in ``unit``."""

    def __init__(self, option, unit, allow_negative=False):
        self.option, self.unit = option, unit
        self.allow_negative = allow_negative

    def __call__(self, text):
        try:
            return parse_grid(text, self.option, self.unit,
                              self.allow_negative)
        except JudderError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None


class Listed:
    """An argparse ``type=``: comma-separated values of an option
    (:func:`parse_list`), each made by ``convert``."""

    def __init__(self, option, convert=float):
        self.option, self.convert = option, convert

    def __call__(self, text):
        try:
            return parse_list(text, self.option, self.convert)
        except JudderError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None


class Settings:
    """An argparse ``type=``: dither settings of an option, a
    ``START:STOP:N`` grid or a comma-separated list, each value plain (in
    ``unit``) or with a unit, in its documented range."""

    def __init__(self, option, unit):
        self.option, self.unit = option, unit

    def __call__(self, text):
        if ":" in text:
            return list(Grid(self.option, self.unit)(text))
        low, high = FREQ_RANGE_HZ if self.unit == "Hz" else (0.0, math.inf)
        return Listed(self.option, Quantity(self.option, self.unit, low,
                                            high))(text)


class Interval:
    """An argparse ``type=``: ``LOW:HIGH`` of an option, each a
    :class:`Quantity` (``90Hz:120Hz``), with LOW < HIGH."""

    def __init__(self, option, unit, low=-math.inf, high=math.inf):
        self.option, self.unit = option, unit
        self.value = Quantity(option, unit, low, high)

    def __call__(self, text):
        ends = text.split(":")
        if len(ends) != 2:
            raise argparse.ArgumentTypeError(
                f"{self.option} {text!r} is not LOW:HIGH in {self.unit} "
                "(e.g. 60:200, 90Hz:120Hz)")
        low, high = (self.value(end.strip()) for end in ends)
        if not low < high:
            raise argparse.ArgumentTypeError(
                f"{self.option} {text} is not allowed; allowed: LOW < HIGH")
        return low, high


class NameList(Listed):
    """An argparse ``type=``: comma-separated names of an option, or
    ``none`` for an empty list."""

    def __init__(self, option):
        super().__init__(option, str)

    def __call__(self, text):
        return [] if text.strip().lower() == "none" else \
            super().__call__(text)


class OrNone(Quantity):
    """An argparse ``type=``: the word ``none``, or a :class:`Quantity`."""

    def __call__(self, text):
        return "none" if text.strip().lower() == "none" else \
            super().__call__(text)


#: The options every command reads alike, as argparse ``type=``.
FREQ = Quantity("--freq", "Hz", *FREQ_RANGE_HZ)
PF = Quantity("--pf", "bar", 0.0)
PF_MAX = Quantity("--pf-max", "bar", 0.0, low_open=True)
DURATION = Quantity("--duration", "s", 0.0, MAX_DURATION_S, low_open=True)
MIN_GROWTH = Quantity("--min-growth", "1/s", 0.0)
THRESHOLD_SPREAD = Quantity("--threshold-spread", "1/s", 0.0)
#: The bench's known scatter of the onsets, by error model: a share of
#: the amplitude, or bar.
SCATTER = {"relative": Quantity("--scatter", "1", 0.0, 1.0, low_open=True),
           "absolute": Quantity("--scatter", "bar", 0.0, low_open=True,
                                amplitude=False)}
LIMIT = Quantity("--limit", "rpm", 0.0, low_open=True)
WORKERS = WholeNumber("--workers", 1, MAX_WORKERS)
SEED = WholeNumber("--seed", 0, 2 ** 63 - 1)

#: The margins of the safe dither windows (advise, compare) and the
#: valve's largest amplitude (compare --valve-max, as advise --pf-max).
MARGIN_BAR = Quantity("--margin-bar", "bar", 0.0, amplitude=False)
MARGIN_HZ = Quantity("--margin-hz", "Hz", 0.0)
VALVE_MAX = Quantity("--valve-max", "bar", 0.0, low_open=True)

#: The rule of each argument of the API functions that an option above
#: carries: a Python caller's value is checked by the same rule as the
#: option's (:func:`judder.commands._common.checked_values`).
RULES = {"freq_hz": FREQ, "p_f_bar": PF, "p_max_bar": PF_MAX,
         "min_growth": MIN_GROWTH, "threshold_spread": THRESHOLD_SPREAD,
         "judder_limit_rpm": LIMIT, "margin_bar": MARGIN_BAR,
         "margin_hz": MARGIN_HZ, "valve_max_bar": VALVE_MAX}


def check_pressures(p_f_max_pa, params, option="--pf"):
    """Warn when the dither amplitude reaches the mean pressure: the
    clutch pressure ``p_m + p_f cos`` would go below zero, which a clutch
    cannot do and the linear model does not know."""
    p_m = params["p_m"] if "p_m" in params.specs else None
    if p_m is not None and np.isfinite(p_f_max_pa) and p_f_max_pa >= p_m:
        warn(f"{option}: p_f = {p_f_max_pa / PA_PER_BAR:g} bar reaches the "
             f"mean pressure p_m = {p_m / PA_PER_BAR:g} bar; the clutch "
             "pressure p_m + p_f cos(2 pi f t) would go below zero, which "
             "the linear model does not represent (check the units: --pf "
             "is in bar, p_m in Pa unless a unit is given)")


def check_plain_pressure(assignment):
    """Refuse ``--set p_m=10``: a plain number is in Pa, and a mean clutch
    pressure below 1 bar is bar given as Pa; with a unit it is taken as
    it is (``p_m=10bar``, ``p_m=50000Pa``)."""
    name, _, value = assignment.partition("=")
    if name.strip() != "p_m" or has_unit(value.strip()):
        return
    number = float(value)
    if 0 <= number < MIN_PLAIN_P_M_PA:
        raise JudderError(
            f"--set {assignment.strip()}: p_m = {number:g} Pa (a plain "
            f"number is in Pa, SI) is not plausible for a clutch pressure "
            f"(below 1 bar); " + _bar_hint(
                number, f"Give p_m={value.strip()}bar",
                f", or p_m={value.strip()}Pa to keep it"))


def check_file_pressure(params, path):
    """Refuse ``p_m = 10`` in a parameter file: the file is in SI (Pa),
    and a mean clutch pressure below 1 bar is bar written as Pa."""
    if "p_m" not in params.specs:
        return
    p_m = params["p_m"]
    if 0 <= p_m < MIN_PLAIN_P_M_PA:
        raise JudderError(
            f"--param-file {path}: p_m = {p_m:g} Pa (the file is in SI) is "
            "not plausible for a clutch pressure (below 1 bar); "
            + _bar_hint(p_m, f"Write p_m = {p_m * PA_PER_BAR:g}"))


#: Highest mean clutch pressure a number meant in bar is taken for, bar
#: (a pressure channel's plausible range): beyond, no unit makes it a
#: clutch pressure.
MAX_PLAUSIBLE_BAR = 1000.0


def _bar_hint(number, fix, keep=""):
    """What to do with a mean pressure below 1 bar given as Pa: read it
    as bar (``fix`` says how) where that is plausible, else the range
    allowed; ``keep`` says how to keep it."""
    if 0 < number <= MAX_PLAUSIBLE_BAR:
        return (f"did you mean {number:g} bar = {number * PA_PER_BAR:g} "
                f"Pa? {fix}{keep}")
    return (f"allowed: {MIN_PLAIN_P_M_PA:g} to "
            f"{MAX_PLAUSIBLE_BAR * PA_PER_BAR:g} Pa (1 to "
            f"{MAX_PLAUSIBLE_BAR:g} bar){keep}")


#: Most values of one grid axis (a typo like N = 100000000000 would
#: otherwise allocate hundreds of GiB).
MAX_GRID_VALUES = 100_000


#: Forms of --dither-wave, for its help and its error message.
WAVEFORMS = ("cosine", "square[:TAU_MS]", "fourier:A1,A2,...[/B1,B2,...]",
             "period:FILE.csv")


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


def parse_waveform(text):
    """The dither waveform of ``--dither-wave`` (None: the cosine).

    ``square:TAU_MS`` is a square wave through a first-order valve lag of
    time constant TAU_MS (ms, default 0); ``fourier:A/B`` the cosine and
    sine coefficients of the harmonics 1, 2, ...; ``period:FILE.csv`` one
    measured period of pressure, equally spaced, the last column of each
    numeric row (a header line is skipped).
    """
    from stability.waveforms import FilteredSquare, FourierSeries, from_samples
    kind, _, rest = (text or "cosine").partition(":")
    option = f"--dither-wave {text!r}"
    if kind == "cosine" and not rest:
        return None
    if kind == "square":
        tau = parse_list(rest, "--dither-wave square:")[0] if rest else 0.0
        Quantity("--dither-wave square:", "ms", 0.0).check(
            tau, "--dither-wave square: TAU_MS")
        return FilteredSquare(tau * 1e-3)
    if kind == "fourier" and rest:
        cos, _, sin = rest.partition("/")
        return FourierSeries(
            cos=tuple(parse_list(cos, option)) if cos.strip() else (),
            sin=tuple(parse_list(sin, option)) if sin.strip() else ())
    if kind == "period" and rest:
        rows = [line.split(",")[-1].strip()
                for line in read_input(rest, "--dither-wave period:")
                .splitlines() if line.strip()]
        if rows and not _is_float(rows[0]):
            rows = rows[1:]
        samples = parse_list(",".join(rows), option)
        bad = [i for i, v in enumerate(samples) if not math.isfinite(v)]
        if bad:
            raise JudderError(f"--dither-wave period:{rest}: sample "
                              f"{bad[0] + 1} of {len(samples)} is "
                              f"{samples[bad[0]]:g}; allowed: finite "
                              "pressures, at least 4")
        try:
            return from_samples(samples)
        except JudderError as exc:
            raise JudderError(f"--dither-wave period:{rest}: {exc}") \
                from None
    raise JudderError(f"{option} is not allowed; allowed: "
                      + ", ".join(WAVEFORMS))


def _is_float(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


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

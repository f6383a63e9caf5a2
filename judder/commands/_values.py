"""The options' parsers: argparse ``type=`` objects that read an
option's text once, with its unit, by the rule of :mod:`studies.rules`
(a refusal names the option), and the options every command reads alike.
"""

import argparse
import math

import numpy as np

from infra.contract import warn
from infra.errors import JudderError
from infra.quantities import has_unit, parse_quantity
from infra.units import PA_PER_BAR
from studies.rules import (FREQ_RANGE_HZ, MAX_WORKERS, MIN_PLAIN_P_M_PA, RULES,
                           Rule, parse_grid, parse_list)
from studies.rules import SCATTER as SCATTER_RULES


class Quantity:
    """An argparse ``type=``: one number of ``option``, in ``unit``
    (plain) or with a unit of its own, by :class:`studies.rules.Rule`
    (its arguments after ``unit``); or by the ``rule`` given."""

    def __init__(self, option, unit=None, *limits, rule=None, **options):
        self.option = option
        self.rule = rule if rule is not None else Rule(unit, *limits,
                                                       **options)
        self.unit = self.rule.unit

    def __call__(self, text):
        try:
            return self.rule.parse(text, self.option)
        except JudderError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None


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
FREQ = Quantity("--freq", rule=RULES["freq_hz"])
PF = Quantity("--pf", rule=RULES["p_f_bar"])
PF_MAX = Quantity("--pf-max", rule=RULES["p_max_bar"])
DURATION = Quantity("--duration", rule=RULES["duration"])
MIN_GROWTH = Quantity("--min-growth", rule=RULES["min_growth"])
THRESHOLD_SPREAD = Quantity("--threshold-spread",
                            rule=RULES["threshold_spread"])
SCATTER = {model: Quantity("--scatter", rule=rule)
           for model, rule in SCATTER_RULES.items()}
LIMIT = Quantity("--limit", rule=RULES["judder_limit_rpm"])
WORKERS = WholeNumber("--workers", 1, MAX_WORKERS)
SEED = WholeNumber("--seed", 0, 2 ** 63 - 1)

#: The margins of the safe dither windows (advise, compare) and the
#: valve's largest amplitude (compare --valve-max, as advise --pf-max).
MARGIN_BAR = Quantity("--margin-bar", rule=RULES["margin_bar"])
MARGIN_HZ = Quantity("--margin-hz", rule=RULES["margin_hz"])
VALVE_MAX = Quantity("--valve-max", rule=RULES["valve_max_bar"])


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


#: Forms of --dither-wave, for its help and its error message.
WAVEFORMS = ("cosine", "square[:TAU_MS]", "fourier:A1,A2,...[/B1,B2,...]",
             "period:FILE.csv")


def parse_waveform(text, decimal=None):
    """The dither waveform of ``--dither-wave`` (None: the cosine).

    ``square:TAU_MS`` is a square wave through a first-order valve lag of
    time constant TAU_MS (ms, default 0); ``fourier:A/B`` the cosine and
    sine coefficients of the harmonics 1, 2, ...; ``period:FILE.csv`` one
    measured period of pressure, equally spaced, the last column of each
    numeric row (a header line is skipped), read with the project's CSV
    rules (:func:`studies.inputs.read_period`; ``decimal``, its decimal
    separator where its cells cannot tell it, from ``--decimal``).
    """
    from stability.waveforms import FilteredSquare, FourierSeries, from_samples
    kind, _, rest = (text or "cosine").partition(":")
    option = f"--dither-wave {text!r}"
    if decimal is not None and not (kind == "period" and rest):
        raise JudderError(f"--decimal {decimal} is for the file of "
                          "--dither-wave period:FILE.csv; allowed: no "
                          f"--decimal with {option}")
    if kind == "cosine" and not rest:
        return None
    if kind == "square":
        tau = parse_list(rest, "--dither-wave square:")[0] if rest else 0.0
        Rule("ms", 0.0).check(
            tau, "--dither-wave square: TAU_MS")
        return FilteredSquare(tau * 1e-3)
    if kind == "fourier" and rest:
        cos, _, sin = rest.partition("/")
        return FourierSeries(
            cos=tuple(parse_list(cos, option)) if cos.strip() else (),
            sin=tuple(parse_list(sin, option)) if sin.strip() else ())
    if kind == "period" and rest:
        from studies.inputs import read_period
        samples = read_period(rest, "--dither-wave period:", decimal)
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


#: How --bounds is written, in every command that takes it.
BOUNDS_FORM = ("NAME=LOW:HIGH, each end a value (SI, or with a unit: "
               "J4=0.09:0.12) or a factor of the nominal value written "
               "with x (J4=0.8x:1.25x)")


def parse_bounds(items, params, names, names_option, plain_factors=False):
    """The ``--bounds NAME=LOW:HIGH`` texts ``items`` as ``{name: (low,
    high)}`` in SI, each name one of ``names`` (the parameters of
    ``names_option``; None: any of ``params``) given once, each end a value or a factor of the
    nominal value (``0.8x``) allowed for the parameter, LOW < HIGH.

    ``plain_factors``: a plain number is read as a factor, the meaning
    ``advise --bounds`` had (kept for one release, with a warning).

    Raises
    ------
    JudderError
        Naming the item, what is wrong and :data:`BOUNDS_FORM`.
    """
    bounds, warned = {}, False
    for item in items:
        name, _, span = item.partition("=")
        name, parts = name.strip(), span.split(":")
        allowed = list(params.specs) if names is None else names
        if name not in allowed or len(parts) != 2:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              f"{BOUNDS_FORM}, NAME "
                              + ("a parameter" if names is None else
                                 f"one of {names_option}")
                              + f" ({', '.join(allowed)})")
        if name in bounds:
            raise JudderError(f"--bounds {name} is given twice; allowed: "
                              "one range per parameter")
        spec, nominal = params.specs[name], params[name]
        ends = []
        for part in (p.strip() for p in parts):
            factor = part[:-1] if part.endswith("x") else None
            if factor is None and plain_factors and _is_float(part):
                factor = part
                if not warned:
                    warn(f"--bounds {item}: a plain number is read as a "
                         "factor of the nominal value for this release; "
                         f"write {name}={parts[0].strip()}x:"
                         f"{parts[1].strip()}x")
                    warned = True
            if factor is None:
                ends.append(spec.check(parse_quantity(
                    part, spec.unit, f"--bounds {name}")))
            elif _is_float(factor) and float(factor) > 0:
                ends.append(spec.check(float(factor) * nominal))
            else:
                raise JudderError(f"--bounds {item!r}: factor {part!r} is "
                                  "not allowed; allowed: a number > 0 "
                                  "followed by x")
        if not ends[0] < ends[1]:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              f"LOW < HIGH, each {spec.allowed()} "
                              f"[{spec.unit}]")
        bounds[name] = tuple(ends)
    return bounds

"""Units of bench channels: speeds, pressures, times and encoder angles.

Each spelling a bench writes is a unit of the project's one table,
:data:`infra.units.UNITS`, which gives its SI factor. One reading differs
from the table's, deliberately: a speed channel in ``Hz`` (or ``rps``)
counts revolutions, a tachometer's Hz (1 Hz = 2 pi rad/s, the table's
``rev/s``), where the table, Modelica and the command line read Hz as 1/s,
a frequency.

The spellings are converted with these small explicit tables
(:data:`SPEED_UNITS`, :data:`PRESSURE_UNITS`), not with pint (0.25, which
installs): pint reads ``Hz`` and ``1/min`` as 1/s and 1/60 s, i.e. 1 Hz =
1 rad/s, where a rotational speed in Hz or 1/min counts revolutions (1 Hz
= 2 pi rad/s), it does not know ``rev``, and it accepts anything of
dimension 1/time (``kHz``, ``1/h``, even ``U/min`` as enzyme units); every
speed unit would need a correcting table anyway, for the price of three
more packages and 0.4 s to build its registry. The tables accept exactly
the units a bench writes and list them when one is not.

Examples
--------
>>> round(unit_factor("rpm", "speed"), 9)
0.104719755
>>> unit_factor("bar", "pressure")
100000.0
>>> round(angle_factor("counts/1024"), 9)
0.006135923
"""

from dataclasses import dataclass
import re

from infra.errors import JudderError
from infra.units import UNITS

__all__ = ["unit_factor", "angle_factor", "is_angle_unit", "allowed_units",
           "parse_scale", "LinearScale", "SPEED_UNITS", "PRESSURE_UNITS",
           "TIME_UNITS", "ANGLE_UNITS"]


def _factors(spellings):
    """Spelling -> SI factor of the unit of :data:`infra.units.UNITS` it
    stands for."""
    return {spelling: UNITS[unit].factor
            for spelling, unit in spellings.items()}


#: rad/s per unit of speed; Hz and 1/min count revolutions (rev/s, rpm).
SPEED_UNITS = _factors({
    "rpm": "rpm", "rev/min": "rpm", "1/min": "rpm", "min^-1": "rpm",
    "min-1": "rpm", "r/min": "rpm", "U/min": "rpm",
    "rad/s": "rad/s", "rad/sec": "rad/s", "rad s^-1": "rad/s",
    "Hz": "rev/s", "rev/s": "rev/s", "rps": "rev/s"})
#: rad per unit of a shaft angle (an encoder's), read as a speed channel.
ANGLE_UNITS = _factors({"rad": "rad", "deg": "deg", "°": "deg",
                        "rev": "rev"})
#: Pa per unit of pressure.
PRESSURE_UNITS = _factors({unit: unit for unit in (
    "Pa", "hPa", "kPa", "MPa", "bar", "mbar", "psi")})
#: s per unit of a time column or track.
TIME_UNITS = _factors({"s": "s", "sec": "s", "ms": "ms", "us": "us",
                       "µs": "us", "min": "min"})
_UNITS = {"speed": SPEED_UNITS, "pressure": PRESSURE_UNITS,
          "time": TIME_UNITS, "angle": ANGLE_UNITS}
#: Units whose case carries a prefix (milli/mega): matched exactly only.
_CASE_SENSITIVE = {"mpa", "mbar"}


def _normalise_unit(unit):
    """A unit string with unicode minus and superscripts spelt in ASCII."""
    text = str(unit).strip().replace("⁻¹", "^-1").replace("−", "-")
    return re.sub(r"\s*/\s*", "/", text)


def allowed_units(kind):
    """The units of ``kind`` a channel may be in, for a message."""
    text = ", ".join(_UNITS[kind])
    if kind == "speed":
        text += "; or an encoder's angle: " + ", ".join(ANGLE_UNITS) \
            + ", counts/N (N a revolution)"
    return text


def unit_factor(unit, kind):
    """SI units per ``unit`` of a quantity of ``kind``.

    Parameters
    ----------
    unit : str
    kind : {'speed', 'pressure', 'time'}

    Returns
    -------
    float
        rad/s, Pa or s per ``unit``.

    Raises
    ------
    JudderError
        The unit is unknown, or of another kind.
    """
    text = _normalise_unit(unit)
    for table_kind, table in _UNITS.items():
        factor = _lookup(table, text)
        if factor is None:
            continue
        if table_kind != kind:
            raise JudderError(f"unit {unit!r} is a {table_kind} unit, not a "
                              f"{kind} unit; allowed: "
                              f"{allowed_units(kind)}")
        return factor
    if text.lower() in _RAW_SIGNAL_UNITS:
        # a transmitter's current or voltage: only its scale tells the
        # quantity
        raise JudderError(
            f"unit {unit!r} is a sensor's raw signal, not a {kind} unit; "
            "give the sensor's linear scale LOW..HIGH UNIT=LOW..HIGH UNIT "
            f"after the channel's name, such as `channels` "
            f"ROLE=NAME:4..20{text}=0..25bar (4-20 {text} recorded for 0-25 "
            f"bar); allowed for a {kind}: {allowed_units(kind)}")
    raise JudderError(f"unit {unit!r} is unknown; allowed for a {kind}: "
                      f"{allowed_units(kind)}")


#: Units of a sensor's raw signal (a transmitter's current loop, a
#: voltage), in lower case: a channel in them needs its linear scale.
_RAW_SIGNAL_UNITS = {"a", "ma", "ua", "µa", "v", "mv"}


def _lookup(table, text):
    """Factor of ``text`` in ``table``: exact, or ignoring the case where
    the case carries no prefix."""
    if text in table:
        return table[text]
    if text.lower() in _CASE_SENSITIVE:
        return None
    by_lower = {key.lower(): value for key, value in table.items()}
    return by_lower.get(text.lower())


#: An encoder's counts as an angle unit: ``counts/N`` (N counts a
#: revolution; also count, pulses, increments).
_COUNT_UNIT = re.compile(r"(?:counts?|pulses?|increments?)\s*/\s*(\d+)",
                         re.IGNORECASE)


def angle_factor(unit):
    """rad per ``unit`` of an angle channel: rad, deg, rev, or an
    encoder's ``counts/N``; None where ``unit`` is not one."""
    text = _normalise_unit(unit)
    factor = _lookup(ANGLE_UNITS, text)
    if factor is not None:
        return factor
    counts = _COUNT_UNIT.fullmatch(text)
    if counts and int(counts.group(1)) > 0:
        return UNITS["rev"].factor / int(counts.group(1))
    return None


def is_angle_unit(unit):
    """True if ``unit`` is an angle (an encoder's), not a speed."""
    return angle_factor(unit) is not None


_NUMBER = r"[+-]?(?:\d+(?:\.\d+)?|\.\d+)(?:[eE][+-]?\d+)?"
#: ``LOW..HIGH UNIT=LOW..HIGH UNIT``.
_SCALE = re.compile(rf"\s*({_NUMBER})\s*\.\.\s*({_NUMBER})\s*([^=\s]+)\s*="
                    rf"\s*({_NUMBER})\s*\.\.\s*({_NUMBER})\s*(\S+)\s*")


@dataclass(frozen=True)
class LinearScale:
    """A sensor's linear scale: ``raw`` from ``raw_low`` to ``raw_high`` (in
    ``raw_unit``, what the DAQ recorded: mA, V) is ``low`` to ``high`` in
    ``unit`` (the quantity's)."""

    raw_low: float
    raw_high: float
    raw_unit: str
    low: float
    high: float
    unit: str

    def __call__(self, raw):
        """The quantity, in :attr:`unit`, of raw readings."""
        return self.low + (raw - self.raw_low) * (
            (self.high - self.low) / (self.raw_high - self.raw_low))


def parse_scale(text):
    """A linear sensor scale ``LOW..HIGH UNIT=LOW..HIGH UNIT``, or None
    where ``text`` is no scale (a plain unit).

    Examples
    --------
    >>> scale = parse_scale("4..20mA=0..25bar")
    >>> scale.raw_unit, scale.unit, scale(12.0)
    ('mA', 'bar', 12.5)
    >>> parse_scale("bar") is None
    True
    """
    if "=" not in str(text):
        return None
    match = _SCALE.fullmatch(str(text))
    if match is None:
        raise JudderError(f"scale {text!r} is not allowed; allowed: "
                          "LOW..HIGH UNIT=LOW..HIGH UNIT, such as "
                          "4..20mA=0..25bar (a transmitter's 4-20 mA for "
                          "0-25 bar)")
    raw_low, raw_high, raw_unit, low, high, unit = match.groups()
    if float(raw_low) == float(raw_high):
        raise JudderError(f"scale {text!r}: the raw range {raw_low}.."
                          f"{raw_high} {raw_unit} is empty; allowed: two "
                          "different raw values")
    return LinearScale(float(raw_low), float(raw_high), raw_unit,
                       float(low), float(high), unit)

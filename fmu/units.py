"""Modelica unit strings as exponents of the SI base units (FMI BaseUnit).

A unit string is a product of factors joined by ``.``, with at most one
``/`` (``N.m.s/rad``, ``kg.m2``, ``rad/s2``); a factor is a unit symbol
with an optional integer exponent.
"""

import re

__all__ = ["base_exponents", "BASE_UNITS", "DISPLAY_UNITS"]

#: FMI BaseUnit attribute names.
BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")

_SYMBOLS = {
    "1": {}, "kg": {"kg": 1}, "g": {"kg": 1}, "m": {"m": 1}, "s": {"s": 1},
    "A": {"A": 1}, "K": {"K": 1}, "mol": {"mol": 1}, "cd": {"cd": 1},
    "rad": {"rad": 1}, "N": {"kg": 1, "m": 1, "s": -2},
    "Pa": {"kg": 1, "m": -1, "s": -2}, "J": {"kg": 1, "m": 2, "s": -2},
    "W": {"kg": 1, "m": 2, "s": -3}, "Hz": {"s": -1},
}
_SCALE = {"g": 1e-3}

#: Display units an FMU declares: name -> (unit, factor, offset), with
#: display value = factor * value + offset (FMI <DisplayUnit>).
DISPLAY_UNITS = {
    "bar": ("Pa", 1e-5, 0.0), "deg": ("rad", 180 / 3.141592653589793, 0.0),
    "rpm": ("rad/s", 30 / 3.141592653589793, 0.0),
    "mm": ("m", 1e3, 0.0), "degC": ("K", 1.0, -273.15),
}


def _factor(text, unit):
    found = re.fullmatch(r"([A-Za-z]+|1)(-?\d+)?", text)
    if not found or found.group(1) not in _SYMBOLS:
        raise ValueError(f"unit {unit!r}: unknown factor {text!r}")
    power = int(found.group(2) or 1)
    return found.group(1), power


def base_exponents(unit):
    """``({base: exponent}, factor)`` of a unit string.

    Examples
    --------
    >>> base_exponents("N.m.s/rad")
    ({'kg': 1, 'm': 2, 's': -1, 'rad': -1}, 1.0)
    """
    numerator, _, denominator = unit.partition("/")
    exponents, scale = {}, 1.0
    for sign, part in ((1, numerator), (-1, denominator)):
        if not part:
            continue
        for text in part.split("."):
            symbol, power = _factor(text, unit)
            for base, exponent in _SYMBOLS[symbol].items():
                exponents[base] = exponents.get(base, 0) + sign * power * exponent
            scale *= _SCALE.get(symbol, 1.0) ** (sign * power)
    ordered = {b: exponents[b] for b in BASE_UNITS if exponents.get(b)}
    return ordered, scale

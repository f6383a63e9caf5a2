"""Modelica unit strings as exponents of the SI base units (FMI BaseUnit).

A unit string is a product of factors joined by ``.``, with at most one
``/`` (``N.m.s/rad``, ``kg.m2``, ``rad/s2``); a factor is a unit symbol
with an optional integer exponent. The symbols, their dimensions and
factors, and the display units an FMU declares are those of the project's
one table of units, :data:`infra.units.UNITS`.
"""

import re

from infra.units import BASE_UNITS, UNITS

__all__ = ["base_exponents", "DISPLAY_UNITS"]

#: Unit symbols a factor of a Modelica unit string may be (of
#: :data:`infra.units.UNITS`): the SI base and derived units Modelica
#: models write, and the gram.
_SYMBOLS = ("1", "kg", "g", "m", "s", "A", "K", "mol", "cd", "rad", "N",
            "Pa", "J", "W", "Hz")

#: Display units an FMU declares (of :data:`infra.units.UNITS`), and the
#: Modelica unit each displays.
_DISPLAYED = {"bar": "Pa", "deg": "rad", "rpm": "rad/s", "mm": "m",
              "degC": "K"}
#: Display units an FMU declares: name -> (unit, factor, offset), with
#: display value = factor * value + offset (FMI <DisplayUnit>).
DISPLAY_UNITS = {
    name: (unit, 1.0 / UNITS[name].factor,
           -UNITS[name].offset / UNITS[name].factor if UNITS[name].offset
           else 0.0)
    for name, unit in _DISPLAYED.items()}


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
            for base, exponent in UNITS[symbol].dimension.items():
                exponents[base] = exponents.get(base, 0) + sign * power * exponent
            scale *= UNITS[symbol].factor ** (sign * power)
    ordered = {b: exponents[b] for b in BASE_UNITS if exponents.get(b)}
    return ordered, scale

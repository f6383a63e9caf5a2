"""Numbers the user types, with or without a unit (``10bar``, ``1.2kHz``,
``1000rpm``), as floats in the unit the caller works in.

A plain number keeps the caller's unit. A number with a unit is converted
by pint (imported only then) into the caller's unit, a unit of the
project's table (:data:`infra.units.UNITS`) or one pint reads. Angles are
kept apart from frequencies: pint treats the radian as dimensionless, so
it would turn ``1Hz`` into 1 rad/s; here, as in the table, where the
radian is a base unit, a frequency (Hz) and an angular speed (rad/s, rpm)
do not convert into each other, and the message says which to give.

Examples
--------
>>> parse_quantity("10bar", "Pa", "--set p_m")
1000000.0
>>> parse_quantity("1.2kHz", "Hz", "--freq")
1200.0
>>> round(parse_quantity("1000rpm", "rad/s", "--set w_motor"), 6)
104.719755
>>> parse_quantity("300mbar", "bar", "--pf")
0.3
>>> parse_quantity("2.5", "bar", "--pf")
2.5
>>> parse_quantity("10Nms/rad", "N m s/rad", "--set c12")
10.0
"""

import functools
import math
import re

from .errors import JudderError
from .units import UNITS

__all__ = ["parse_quantity", "has_unit"]

_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")
_WITH_UNIT = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
                        r"\s*([^\d\s.+-].*?)\s*")


#: The table's units with spaces, written without them (``Nms/rad``,
#: ``Nm/rad``, ``kgm^2``, ``Nm``): pint would read ``Nms`` as a
#: "number_meter"; these are the table's units.
_COMPACT = {name.replace(" ", ""): name for name in UNITS if " " in name}


def has_unit(text):
    """True if ``text`` is not a plain number (it may carry a unit)."""
    return isinstance(text, str) and _NUMBER.fullmatch(text) is None \
        and text.strip().lower() not in ("nan", "inf", "-inf", "+inf",
                                         "infinity", "-infinity")


@functools.lru_cache(maxsize=1)
def _registry():
    import pint
    return pint.UnitRegistry()


def _dimensionality_error():
    import pint
    return pint.errors.DimensionalityError


def _angle_power(quantity):
    """Power of the radian in ``quantity``'s root units (rpm: 1, Hz: 0)."""
    return dict(quantity.to_root_units().unit_items()).get("radian", 0)


def _pint_spelling(unit):
    """A unit of :data:`infra.units.UNITS` as pint reads it (``N m s/rad``:
    ``N*m*s/rad``, ``kg m^2``: ``kg*m**2``, ``1``: ``dimensionless``);
    any other unit as it is."""
    if unit == "1":
        return "dimensionless"
    if unit in UNITS:
        return unit.replace(" ", "*").replace("^", "**")
    return unit


def _reference_angle_power(unit, reference):
    """Power of the radian in ``unit``: the table's, else pint's."""
    if unit in UNITS:
        return UNITS[unit].dimension.get("rad", 0)
    return _angle_power(reference)


def parse_quantity(text, unit, what):
    """``text`` as a float in ``unit``.

    Parameters
    ----------
    text : str or float
        A number, or a number with a unit (``10bar``, ``1.2 kHz``).
    unit : str
        The unit of the result, and of a plain number.
    what : str
        The option or parameter, for messages.

    Raises
    ------
    JudderError
        On text that is not a number, an unknown unit, or a unit of
        another dimension; the message names ``what``, the text and the
        unit expected.
    """
    if not isinstance(text, str):
        return float(text)
    if not has_unit(text):
        try:
            return float(text)
        except ValueError:
            pass
    target = _pint_spelling(unit)
    allowed = ("allowed: a plain number, or a percentage (e.g. 3%)"
               if unit == "1" else
               f"allowed: a number in {unit}, or a number with a unit of "
               f"the same kind (e.g. {_example(unit)})")
    match = _WITH_UNIT.fullmatch(text)
    if match is None:
        raise JudderError(f"{what} {text!r} is not a number or a number "
                          f"with a unit; {allowed}")
    registry = _registry()
    try:
        # only the unit goes to pint's parser (it evaluates expressions)
        written = _COMPACT.get(match.group(2), match.group(2))
        quantity = registry.Quantity(float(match.group(1)),
                                     registry.parse_units(
                                         _pint_spelling(written)))
        reference = registry.Quantity(1.0, registry.parse_units(target))
    except Exception:   # pint's parser raises many kinds on bad text
        raise JudderError(f"{what} {text!r}: unknown unit "
                          f"{match.group(2)!r}; {allowed}") from None
    if _angle_power(quantity) != _reference_angle_power(unit,
                                                        reference):
        raise JudderError(
            f"{what} {text!r}: a frequency (Hz) and an angular speed "
            f"(rad/s, rpm) do not convert into each other here; {allowed}")
    try:
        value = float(quantity.to(target).magnitude)
    except _dimensionality_error():
        raise JudderError(f"{what} {text!r} is not "
                          + ("a pure number" if unit == "1" else
                             f"in a unit of {unit}") + f"; {allowed}") from None
    if not math.isfinite(value):
        raise JudderError(f"{what} {text!r} is not finite; {allowed}")
    return value


def _example(unit):
    return {"Pa": "10bar", "bar": "300mbar", "Hz": "1.2kHz",
            "rad/s": "1000rpm", "s": "50ms"}.get(unit, f"1 {unit}")


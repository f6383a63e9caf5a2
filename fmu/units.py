"""Modelica unit strings as exponents of the SI base units (FMI BaseUnit).

A unit string follows the grammar of the Modelica specification
(section 19.1, "Unit Expressions")::

    unit_expression  : unit_numerator [ "/" unit_denominator ]
    unit_numerator   : "1" | unit_factors | "(" unit_expression ")"
    unit_denominator : unit_factor | "(" unit_expression ")"
    unit_factors     : unit_factor [ "." unit_factors ]
    unit_factor      : unit_operand [ [ "+" | "-" ] integer ]
    unit_operand     : unit_symbol | unit_prefix unit_symbol

(``N.m.s/rad``, ``kg.m2``, ``rad/s2``, ``W/(m2.K)``); as before, a
denominator of several factors without parentheses (``J/kg.K``) divides
by all of them. An operand is looked up in the project's one table of
units, :data:`infra.units.UNITS` (its factors are those of the display
units), then read by pint (already a dependency: the command line
converts with it), which knows the SI prefixes and derived units (``V``,
``kOhm``, ``mH``) and the units accepted beside them (``min``, ``bar``,
``l``); ``Ohm``, ``var`` and ``rev``, spelt as Modelica writes them, are
added to its registry. A unit of one operand with an offset (``degC``,
``degF``) keeps its offset; inside a compound unit (``degC/s``) it is a
difference and has none.

A unit neither reads (a misspelling, a unit of one's own) raises
:class:`UnknownUnit`: the FMU keeps it as written, without a BaseUnit
(:mod:`fmu.description`), and the build warns.
"""

from dataclasses import dataclass, field
from functools import lru_cache
import re

from infra.units import BASE_UNITS, UNITS

__all__ = ["BaseUnit", "UnknownUnit", "UnitWarning", "base_unit",
           "base_exponents", "DISPLAY_UNITS"]

#: Unit symbols of :data:`infra.units.UNITS` an operand is looked up in
#: first: the SI base and derived units Modelica models write, the gram
#: and the display units.
_SYMBOLS = ("1", "kg", "g", "m", "s", "A", "K", "mol", "cd", "rad", "N",
            "Pa", "J", "W", "Hz", "bar", "deg", "rpm", "mm", "degC")

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

#: pint's base units -> FMI's (the radian is a base unit of FMI; pint
#: keeps it as its own root unit). pint counts a becquerel as
#: ``count/s``; Modelica and FMI as 1/s.
_PINT_BASE = {"kilogram": "kg", "meter": "m", "second": "s", "ampere": "A",
              "kelvin": "K", "mole": "mol", "candela": "cd", "radian": "rad",
              "count": None}
#: Modelica's spellings pint lacks (Modelica specification, 19.1; MSL
#: ``Modelica.Units``): added to its registry, so prefixes apply.
_PINT_DEFINITIONS = ("Ohm = ohm", "var = volt * ampere", "rev = turn",
                     "degRk = degree_Rankine")


class UnknownUnit(ValueError):
    """A unit string that is not in Modelica's grammar or names a unit
    the table and pint do not know."""


class UnitWarning(UserWarning):
    """A unit kept as written in the FMU, without its base units."""


@dataclass(frozen=True)
class BaseUnit:
    """A unit in FMI's base units: SI value = ``factor * value + offset``.

    Attributes
    ----------
    exponents : dict
        Base unit (:data:`infra.units.BASE_UNITS`) -> exponent, in their
        order, without zeros.
    factor : float
    offset : float
        Nonzero for a unit of one operand with an offset (``degC``:
        273.15 K).
    """

    exponents: dict = field(default_factory=dict)
    factor: float = 1.0
    offset: float = 0.0


@lru_cache(maxsize=1)
def _registry():
    import pint   # imported only when a unit is outside the table
    registry = pint.UnitRegistry()
    for definition in _PINT_DEFINITIONS:
        registry.define(definition)
    return registry


@lru_cache(maxsize=None)
def _operand(symbol):
    """``(dimension, factor, offset)`` of one unit operand, prefix and
    all (``kOhm``)."""
    if symbol in _SYMBOLS:
        unit = UNITS[symbol]
        return dict(unit.dimension), unit.factor, unit.offset
    registry = _registry()
    try:
        unit = registry.parse_units(symbol)
        at = [registry.Quantity(float(v), unit).to_base_units()
              for v in (0, 1, 2)]
        # the factor of a difference (pint reads an offset unit in a
        # compound as its difference): 5/9 for degF without the rounding
        # of (1 degF - 0 degF) in kelvin
        rate = registry.Quantity(1.0, registry.parse_units(
            f"{symbol}/second")).to_base_units()
    except Exception:   # pint's UndefinedUnitError, a symbol it misreads
        return None
    offset, factor = at[0].magnitude, rate.magnitude
    if abs(at[1].magnitude - offset - factor) > 1e-9 * abs(factor) or \
            abs(at[2].magnitude - offset - 2 * factor) > 1e-9 * abs(factor) \
            or not factor:
        return None   # not affine: a logarithmic unit (dB, Np)
    dimension = {}
    for name, power in dict(at[1].units._units).items():
        if name not in _PINT_BASE:
            return None   # bit, and what FMI has no base unit for
        if _PINT_BASE[name] and power:
            if power != int(power):
                return None
            dimension[_PINT_BASE[name]] = int(power)
    return dimension, factor, offset


_TOKEN = re.compile(r"\s*(?:([A-Za-z_]+)([+-]?\d+)?|(\d+)|([./()]))")


class _Parser:
    """Recursive descent over Modelica's unit grammar (module docstring)."""

    def __init__(self, unit):
        self.unit = unit
        self.tokens, position = [], 0
        while position < len(unit.rstrip()):
            found = _TOKEN.match(unit, position)
            if not found or found.end() == position:
                self.fail(f"unexpected {unit[position:]!r}")
            self.tokens.append(found.groups())
            position = found.end()
        self.at = 0
        self.compound = False   # more than one operand, or a power

    def fail(self, why):
        raise UnknownUnit(f"unit {self.unit!r}: {why}")

    def peek(self, symbol):
        return self.at < len(self.tokens) and \
            self.tokens[self.at][3] == symbol

    def take(self, symbol):
        if not self.peek(symbol):
            self.fail(f"{symbol!r} expected")
        self.at += 1

    def expression(self):
        dimension, factor, offset = self.numerator()
        if self.peek("/"):
            self.take("/")
            self.compound = True
            below, scale, _ = self.numerator()   # J/kg.K: by all of them
            for base, power in below.items():
                dimension[base] = dimension.get(base, 0) - power
            factor /= scale
        return dimension, factor, offset

    def numerator(self):
        if self.peek("("):
            self.take("(")
            value = self.expression()
            self.take(")")
            return value
        if self.at < len(self.tokens) and self.tokens[self.at][2]:
            if self.tokens[self.at][2] != "1":
                self.fail(f"number {self.tokens[self.at][2]} (only 1 is "
                          "allowed)")
            self.at += 1
            return {}, 1.0, 0.0
        dimension, factor, offset = self.factor()
        while self.peek("."):
            self.take(".")
            self.compound = True
            more, scale, _ = self.factor()
            for base, power in more.items():
                dimension[base] = dimension.get(base, 0) + power
            factor *= scale
        return dimension, factor, offset

    def factor(self):
        if self.at >= len(self.tokens) or not self.tokens[self.at][0]:
            self.fail("a unit symbol expected")
        symbol, power, _, _ = self.tokens[self.at]
        self.at += 1
        read = _operand(symbol)
        if read is None:
            self.fail(f"unknown symbol {symbol!r}")
        dimension, factor, offset = read
        power = int(power) if power else 1
        self.compound |= power != 1
        return ({k: v * power for k, v in dimension.items()},
                factor ** power, offset)


@lru_cache(maxsize=None)
def base_unit(unit):
    """The :class:`BaseUnit` of a Modelica unit string.

    Raises
    ------
    UnknownUnit
        Not in Modelica's grammar, or an operand neither
        :data:`infra.units.UNITS` nor pint knows.

    Examples
    --------
    >>> base_unit("kOhm")
    BaseUnit(exponents={'kg': 1, 'm': 2, 's': -3, 'A': -2}, factor=1000.0, offset=0.0)
    >>> base_unit("degC").offset
    273.15
    """
    parser = _Parser(unit)
    dimension, factor, offset = parser.expression()
    if parser.at != len(parser.tokens):
        parser.fail("unexpected text after the unit")
    ordered = {b: dimension[b] for b in BASE_UNITS if dimension.get(b)}
    return BaseUnit(ordered, factor, 0.0 if parser.compound else offset)


def base_exponents(unit):
    """``({base: exponent}, factor)`` of a unit string.

    Examples
    --------
    >>> base_exponents("N.m.s/rad")
    ({'kg': 1, 'm': 2, 's': -1, 'rad': -1}, 1.0)
    """
    found = base_unit(unit)
    return dict(found.exponents), found.factor

"""The project's one table of units: each with its SI factor and dimension.

SI inside, bar and rpm where engineers read them. :data:`UNITS` maps a
unit's name to a :class:`Unit`: SI value = ``factor * value + offset``,
dimension as exponents of :data:`BASE_UNITS`, FMI's base units, where the
radian is a base unit of its own. The other vocabularies draw on it:

* :mod:`fmu.units` reads Modelica unit strings with the symbols of the
  table and declares the FMU's display units from it;
* :mod:`infra.quantities` parses the numbers users type: pint converts,
  the table names the tool's units and the dimension of each;
* :mod:`pysim.bench.units` accepts the spellings benches write, each
  one a unit of the table.

Two readings of ``Hz`` are deliberate. Here, as in Modelica and FMI, Hz is
1/s, a frequency: an angular speed (rad/s, rpm) has the radian in its
dimension, so the command line does not convert a frequency into an
angular speed (pint, reading the radian as 1, would make 1 Hz 1 rad/s).
A bench's speed channel in Hz counts revolutions (a tachometer's Hz,
1 Hz = 2 pi rad/s): :mod:`pysim.bench.units` reads it as ``rev/s``.

Examples
--------
>>> 0.3 * PA_PER_BAR
30000.0
>>> round(1000 * RAD_S_PER_RPM, 6)
104.719755
>>> UNITS["rpm"].dimension
{'rad': 1, 's': -1}
"""

from dataclasses import dataclass, field
import math

__all__ = ["Unit", "UNITS", "BASE_UNITS", "PA_PER_BAR", "RPM_PER_RAD_S",
           "RAD_S_PER_RPM"]

#: The base units a dimension is counted in (FMI BaseUnit attributes).
BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")


@dataclass(frozen=True)
class Unit:
    """A unit: SI value = ``factor * value + offset``.

    Attributes
    ----------
    factor : float
        SI units per unit.
    dimension : dict
        Base unit (:data:`BASE_UNITS`) -> exponent, in their order,
        without zeros.
    offset : float
        SI value of the unit's zero (degC: 273.15 K), else 0.
    """

    factor: float
    dimension: dict = field(default_factory=dict)
    offset: float = 0.0


_SPEED = {"rad": 1, "s": -1}
_PRESSURE = {"kg": 1, "m": -1, "s": -2}
_TORQUE = {"kg": 1, "m": 2, "s": -2}

#: Unit name -> :class:`Unit`: the SI units and those the tool, its FMUs
#: and the benches it reads write (psi: lbf/in^2 from the exact pound and
#: inch).
UNITS = {
    "1": Unit(1.0),
    "kg": Unit(1.0, {"kg": 1}), "g": Unit(1e-3, {"kg": 1}),
    "m": Unit(1.0, {"m": 1}), "mm": Unit(1e-3, {"m": 1}),
    "m^2": Unit(1.0, {"m": 2}),
    "s": Unit(1.0, {"s": 1}), "ms": Unit(1e-3, {"s": 1}),
    "us": Unit(1e-6, {"s": 1}), "min": Unit(60.0, {"s": 1}),
    "A": Unit(1.0, {"A": 1}), "K": Unit(1.0, {"K": 1}),
    "degC": Unit(1.0, {"K": 1}, offset=273.15),
    "mol": Unit(1.0, {"mol": 1}), "cd": Unit(1.0, {"cd": 1}),
    "rad": Unit(1.0, {"rad": 1}), "deg": Unit(math.pi / 180.0, {"rad": 1}),
    "rev": Unit(2.0 * math.pi, {"rad": 1}),
    "Hz": Unit(1.0, {"s": -1}),
    "rad/s": Unit(1.0, _SPEED), "rpm": Unit(2.0 * math.pi / 60.0, _SPEED),
    "rev/s": Unit(2.0 * math.pi, _SPEED),
    "N": Unit(1.0, {"kg": 1, "m": 1, "s": -2}), "N m": Unit(1.0, _TORQUE),
    "N m/rad": Unit(1.0, {"kg": 1, "m": 2, "s": -2, "rad": -1}),
    "N m s/rad": Unit(1.0, {"kg": 1, "m": 2, "s": -1, "rad": -1}),
    "kg m^2": Unit(1.0, {"kg": 1, "m": 2}),
    "J": Unit(1.0, _TORQUE), "W": Unit(1.0, {"kg": 1, "m": 2, "s": -3}),
    "Pa": Unit(1.0, _PRESSURE), "hPa": Unit(1e2, _PRESSURE),
    "kPa": Unit(1e3, _PRESSURE), "MPa": Unit(1e6, _PRESSURE),
    "bar": Unit(1e5, _PRESSURE), "mbar": Unit(1e5 / 1000, _PRESSURE),
    "psi": Unit(0.45359237 * 9.80665 / 0.0254 ** 2, _PRESSURE),
}

#: Pascal per bar.
PA_PER_BAR = UNITS["bar"].factor
#: rad/s per revolution per minute.
RAD_S_PER_RPM = UNITS["rpm"].factor
#: Revolutions per minute per rad/s.
RPM_PER_RAD_S = 1.0 / RAD_S_PER_RPM

"""One vocabulary of units (infra.units.UNITS): the command-line parser,
the FMUs' display units and the bench tables all read their factors from
it, and keep their deliberate difference on Hz."""

import math

import pytest

from fmu.units import DISPLAY_UNITS, base_exponents
from infra.errors import JudderError
from infra.quantities import parse_quantity
from infra.units import BASE_UNITS, UNITS
from pysim.bench.units import SPEED_UNITS, unit_factor

# SI per unit, written independently of the table (closed forms)
REFERENCE = [("bar", 1e5), ("mbar", 100.0), ("kPa", 1e3),
             ("psi", 6894.757293168361), ("rpm", 2 * math.pi / 60),
             ("rev/s", 2 * math.pi), ("deg", math.pi / 180),
             ("ms", 1e-3), ("min", 60.0), ("g", 1e-3), ("mm", 1e-3)]


@pytest.mark.parametrize("unit, factor", REFERENCE)
def test_table_factors(unit, factor):
    assert UNITS[unit].factor == pytest.approx(factor, rel=1e-15)


def test_dimensions_count_base_units_only():
    for name, unit in UNITS.items():
        assert set(unit.dimension) <= set(BASE_UNITS), name
        assert all(unit.dimension.values()), name


def _si(dimension):
    """The table's coherent SI unit of ``dimension`` (factor 1)."""
    return next(name for name, unit in UNITS.items()
                if unit.dimension == dimension and unit.factor == 1.0
                and not unit.offset)


@pytest.mark.parametrize("name", sorted(set(UNITS) - {"rev", "rev/s",
                                                      "degC"}))
def test_pint_converts_as_the_table_where_it_knows_the_unit(name):
    # the command-line parser converts with pint: it agrees with the table
    # on every unit of the table that pint reads (pint lacks rev, rev/s)
    text = "2" if name == "1" else f"2{name}"
    value = parse_quantity(text, _si(UNITS[name].dimension), "--x")
    assert value == pytest.approx(2 * UNITS[name].factor, rel=1e-12)


def test_fmu_display_factors_are_the_inverse_of_the_table():
    for name, (unit, factor, offset) in DISPLAY_UNITS.items():
        assert factor * UNITS[name].factor == pytest.approx(1.0, rel=1e-15)
        assert offset == pytest.approx(-UNITS[name].offset)
        assert base_exponents(unit)[0] == UNITS[name].dimension


def test_hz_is_a_frequency_on_the_command_line_but_revolutions_on_a_bench():
    # infra and Modelica: 1 Hz = 1/s, refused as an angular speed
    assert UNITS["Hz"].dimension == {"s": -1}
    with pytest.raises(JudderError, match="do not convert into each other"):
        parse_quantity("1Hz", "rad/s", "--set w_motor")
    # a bench's speed channel in Hz counts revolutions (rev/s)
    assert unit_factor("Hz", "speed") == UNITS["rev/s"].factor
    assert SPEED_UNITS["Hz"] == pytest.approx(2 * math.pi, rel=1e-15)


@pytest.mark.parametrize("text, unit, value", [
    ("10Nms/rad", "N m s/rad", 10.0), ("10 N m s/rad", "N m s/rad", 10.0),
    ("3856Nm/rad", "N m/rad", 3856.0), ("0.122kgm^2", "kg m^2", 0.122),
    ("150Nm", "N m", 150.0)])
def test_the_tables_units_may_be_written_without_spaces(text, unit, value):
    # pint alone reads "Nms" as a "number_meter": --set c12=10Nms/rad was
    # refused as "not in a unit of N m s/rad"
    assert parse_quantity(text, unit, "--set") == pytest.approx(value,
                                                                rel=1e-12)


def test_a_compact_unit_of_another_kind_is_still_refused():
    with pytest.raises(JudderError, match="c12"):
        parse_quantity("10Nm/rad", "N m s/rad", "--set c12")

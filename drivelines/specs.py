"""Parameter specifications: unit, allowed range and meaning of each name."""

from dataclasses import dataclass
import math
import numbers

from infra.errors import JudderError, ParameterError
from infra.quantities import parse_quantity

__all__ = ["allowed_names", "ParameterSpec", "positive", "nonnegative", "CLUTCH_SPECS",
           "MEAN_PRESSURE_DAMPING", "split_assignment", "parse_overrides", "MIN_MAGNITUDE",
           "MAX_MAGNITUDE"]

#: Smallest and largest magnitude of a parameter value in SI units: the
#: drivelines' values lie within 1e-4..1e7, and beyond these bounds the
#: eigenvalue problems lose the small modes or overflow.
MIN_MAGNITUDE, MAX_MAGNITUDE = 1e-9, 1e12

#: Name of the model option that scales the mean pressure in the damping term.
MEAN_PRESSURE_DAMPING = "mean_pressure_damping"


def split_assignment(text):
    """``(name, value text)`` of a ``NAME=VALUE`` string given to ``--set``.

    Raises
    ------
    ParameterError
        When ``text`` is not of that form.
    """
    name, sep, value = text.partition("=")
    name, value = name.strip(), value.strip()
    if not sep or not name or not value:
        raise ParameterError(f"`assignments` {text!r} is not of the form "
                             "NAME=VALUE (for example c12=10)")
    return name, value


def parse_overrides(assignments, specs, model):
    """``{name: value}`` (SI) of ``NAME=VALUE`` strings given to ``--set``.

    A plain VALUE is in the parameter's SI unit; it may carry a unit
    instead (``p_m=10bar``), see :func:`infra.quantities.parse_quantity`.

    Parameters
    ----------
    assignments : iterable of str
    specs : mapping of str to ParameterSpec
        The parameters of ``model`` that may be set.
    model : str
        The model's name, for messages.

    Raises
    ------
    ParameterError
        On a malformed assignment, an unknown name or a bad value.
    """
    changes = {}
    for text in assignments:
        name, value = split_assignment(text)
        if name not in specs:
            raise ParameterError(
                f"`assignments` {text!r}: unknown parameter, {name!r} is not a "
                f"tunable parameter of the {model} model; allowed names: "
                f"{allowed_names(specs)}")
        spec = specs[name]
        try:
            number = parse_quantity(value, spec.unit,
                                    f"`assignments` {name}: parameter {name} =")
        except JudderError as exc:
            raise ParameterError(str(exc)) from None
        changes[name] = spec.check(number)
    return changes



def allowed_names(names):
    """Parameter names for a message's "allowed", or what to do where a
    model has none."""
    return ", ".join(names) or ("none: the model has no tunable parameter "
                                "(a Modelica class declares one with "
                                "'parameter Real NAME = VALUE;')")

@dataclass(frozen=True)
class ParameterSpec:
    """Unit, bounds and meaning of one parameter.

    ``lower``/``upper`` are inclusive unless ``lower_open`` is set (then the
    value must be strictly greater than ``lower``).
    """

    name: str
    unit: str
    description: str
    lower: float = -math.inf
    upper: float = math.inf
    lower_open: bool = False
    integer: bool = False

    def allowed(self):
        """Describe the allowed range in words, for error messages."""
        parts = []
        if self.lower > -math.inf:
            parts.append(f"{'>' if self.lower_open else '>='} {self.lower:g}")
        if self.upper < math.inf:
            parts.append(f"<= {self.upper:g}")
        text = " and ".join(parts) if parts else "any finite number"
        return ("an integer " + text) if self.integer else text

    def check(self, value):
        """Return ``value`` as a float, or raise :class:`ParameterError`.

        A bool is refused (TOML ``J1 = true`` is not a number), and so is
        a magnitude above ``MAX_MAGNITUDE``, or below ``MIN_MAGNITUDE`` for
        a positive parameter: no driveline has it, and the numerics
        overflow or lose the small modes.
        """
        if isinstance(value, bool):
            raise ParameterError(
                f"parameter {self.name} = {value!r} is not a number; "
                f"allowed: {self.allowed()} [{self.unit}]")
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ParameterError(
                f"parameter {self.name} = {value!r} is not a number; "
                f"allowed: {self.allowed()} [{self.unit}]") from None
        ok = math.isfinite(number)
        ok = ok and (number > self.lower if self.lower_open
                     else number >= self.lower)
        ok = ok and number <= self.upper
        ok = ok and (not self.integer or number == int(number))
        smallest = MIN_MAGNITUDE if self.lower_open and self.lower == 0 \
            else 0.0
        if ok and number != 0 and not (
                smallest <= abs(number) <= MAX_MAGNITUDE):
            raise ParameterError(
                f"parameter {self.name} = {_shown(value)} is not allowed; allowed:"
                f" {self.allowed()} [{self.unit}], of magnitude "
                + (f"{smallest:g} to " if smallest else "at most ")
                + f"{MAX_MAGNITUDE:g}")
        if not ok:
            raise ParameterError(
                f"parameter {self.name} = {_shown(value)} is not allowed; "
                f"allowed: {self.allowed()} [{self.unit}] ({self.description})")
        return number


def positive(name, unit, description, **kw):
    """Spec of a parameter that must be > 0."""
    return ParameterSpec(name, unit, description, lower=0.0, lower_open=True,
                         **kw)


def nonnegative(name, unit, description):
    """Spec of a parameter that must be >= 0."""
    return ParameterSpec(name, unit, description, lower=0.0)


#: The wet clutch and its actuation, Eq. (3)-(5); every driveline has them.
CLUTCH_SPECS = (
    nonnegative("mu0", "1", "clutch friction coefficient at zero slip (Eq. 5)"),
    ParameterSpec("mu_g", "s/rad",
                  "gradient of the friction coefficient with slip speed (Eq. 5);"
                  " negative values model a falling friction curve"),
    positive("N_c", "1", "number of pairs of clutch plates (Eq. 3)",
             integer=True),
    positive("R_m", "m", "mean radius of the friction surfaces (Eq. 3)"),
    positive("S", "m^2", "area the actuation pressure acts on (Eq. 3)"),
    nonnegative("p_m", "Pa", "mean actuation pressure (Eq. 4)"),
    ParameterSpec(MEAN_PRESSURE_DAMPING, "1",
                  "share of the mean pressure p_m that enters the slip-speed "
                  "damping mu_g N_c R_m S p(t): 1 is Eq. (2)-(4) taken "
                  "literally, 0 keeps only the dither part (paper's maps)",
                  lower=0.0, upper=1.0),
)


def _shown(value):
    """A value as the user would write it (``1e+300``, not
    ``np.float64(1e+300)``)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return f"{float(value):g}"
    return repr(value)

"""Parameter sets of the 3-DOF and 4-DOF driveline models.

Every value is held in SI units (kg m^2, N m/rad, N m s/rad, m, m^2, Pa,
s/rad). A parameter set is a :class:`Parameters` object: the model name and
an immutable mapping of canonical names to floats. Named presets reproduce
the paper's Appendix A and the fitted set of its section 4.2; sets can be
overridden by name, saved to and loaded from TOML.

Calibration of ``N_c``, ``R_m`` and ``S``
-----------------------------------------
The paper keeps the number of plate pairs, the mean radius and the piston
area confidential. They enter Eq. (3) only as the product
``N_c * R_m * S``. The defaults (8 pairs, 75 mm, 0.01 m^2) give
``N_c R_m S = 6e-3 m^3``, chosen from two statements of the paper:

* the EVEN clutch then transmits ``mu0 N_c R_m S p_m = 540 N m`` at the
  bench pressure of about 10 bar (section 2.2), below the 680 N m the bench
  motor delivers, as an engaging clutch that does not stall the motor must;
* with this product the tongue tips lie between 0.03 and 0.19 bar (Fig.
  14), inside the bench's dither range, and with the clutch damper at
  16.8 % damping (c12 = 10) the combination tongues 5 and 6 lie above the
  0.7 bar the paper states (at 1.45 bar).
"""

from dataclasses import dataclass, field
import math
import tomllib
from types import MappingProxyType

from .errors import ParameterError

__all__ = ["ParameterSpec", "Parameters", "MODELS", "PRESETS", "SPECS",
           "get_preset", "default_preset", "load_toml", "dumps_toml",
           "MEAN_PRESSURE_DAMPING"]

#: Name of the model option that scales the mean pressure in the damping term.
MEAN_PRESSURE_DAMPING = "mean_pressure_damping"


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
        """Return ``value`` as a float, or raise :class:`ParameterError`."""
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
        if not ok:
            raise ParameterError(
                f"parameter {self.name} = {value!r} is not allowed; "
                f"allowed: {self.allowed()} [{self.unit}] ({self.description})")
        return number


def _positive(name, unit, description, **kw):
    return ParameterSpec(name, unit, description, lower=0.0, lower_open=True,
                         **kw)


def _nonnegative(name, unit, description):
    return ParameterSpec(name, unit, description, lower=0.0)


_CLUTCH_SPECS = (
    _nonnegative("mu0", "1", "clutch friction coefficient at zero slip (Eq. 5)"),
    ParameterSpec("mu_g", "s/rad",
                  "gradient of the friction coefficient with slip speed (Eq. 5);"
                  " negative values model a falling friction curve"),
    _positive("N_c", "1", "number of pairs of clutch plates (Eq. 3)",
              integer=True),
    _positive("R_m", "m", "mean radius of the friction surfaces (Eq. 3)"),
    _positive("S", "m^2", "area the actuation pressure acts on (Eq. 3)"),
    _nonnegative("p_m", "Pa", "mean actuation pressure (Eq. 4)"),
    ParameterSpec(MEAN_PRESSURE_DAMPING, "1",
                  "share of the mean pressure p_m that enters the slip-speed "
                  "damping mu_g N_c R_m S p(t): 1 is Eq. (2)-(4) taken "
                  "literally, 0 keeps only the dither part (paper's maps)",
                  lower=0.0, upper=1.0),
)

#: Parameter specifications of each model, in display order.
SPECS = MappingProxyType({
    "4dof": MappingProxyType({s.name: s for s in (
        _positive("J1", "kg m^2", "inertia of the engine-side body"),
        _positive("J2", "kg m^2", "inertia of the clutch damper"),
        _positive("J3", "kg m^2", "inertia of the gearbox-side body"),
        _positive("J4", "kg m^2",
                  "inertia between clutch damper and clutch discs"),
        _positive("k12", "N m/rad", "torsional stiffness of the clutch damper"),
        _positive("k24", "N m/rad",
                  "equivalent stiffness between damper and clutch pack"),
        _nonnegative("c12", "N m s/rad", "damping of the clutch damper"),
        _nonnegative("c24", "N m s/rad", "internal damping between 2 and 4"),
        _nonnegative("c1", "N m s/rad", "external damping of body 1"),
        _nonnegative("c2", "N m s/rad", "external damping of body 2"),
        _nonnegative("c3", "N m s/rad", "external damping of body 3"),
        _nonnegative("c4", "N m s/rad", "external damping of body 4"),
    ) + _CLUTCH_SPECS}),
    "3dof": MappingProxyType({s.name: s for s in (
        _positive("J1", "kg m^2", "inertia of the engine-side body"),
        _positive("J24", "kg m^2",
                  "inertia of the clutch damper and everything up to the "
                  "clutch pack"),
        _positive("J3", "kg m^2", "inertia of the gearbox-side body"),
        _positive("k", "N m/rad", "torsional stiffness of the clutch damper"),
        _nonnegative("c", "N m s/rad", "damping of the clutch damper"),
        _nonnegative("c1", "N m s/rad", "external damping of body 1"),
        _nonnegative("c24", "N m s/rad", "external damping of body 2-4"),
        _nonnegative("c3", "N m s/rad", "external damping of body 3"),
    ) + _CLUTCH_SPECS}),
})

#: Model names.
MODELS = tuple(SPECS)


@dataclass(frozen=True)
class Parameters:
    """A validated, immutable parameter set of one model.

    Parameters
    ----------
    model : {'4dof', '3dof'}
        Which driveline the values describe.
    values : mapping
        Every parameter of ``SPECS[model]``, SI units.

    Raises
    ------
    ParameterError
        On an unknown model, a missing or unknown name, or a value outside
        its allowed range; the message names the parameter and the range.

    Examples
    --------
    >>> p = get_preset("paper-4dof").replace(c12=10.0)
    >>> p["c12"]
    10.0
    """

    model: str
    values: MappingProxyType = field(repr=False)

    def __post_init__(self):
        if self.model not in SPECS:
            raise ParameterError(
                f"model = {self.model!r} is unknown; allowed: "
                f"{', '.join(MODELS)}")
        specs = SPECS[self.model]
        unknown = sorted(set(self.values) - set(specs))
        if unknown:
            raise ParameterError(
                f"unknown parameter {unknown[0]!r} for the {self.model} model;"
                f" allowed names: {', '.join(specs)}")
        missing = [name for name in specs if name not in self.values]
        if missing:
            raise ParameterError(
                f"parameter {missing[0]} is missing for the {self.model} model")
        checked = {name: spec.check(self.values[name])
                   for name, spec in specs.items()}
        object.__setattr__(self, "values", MappingProxyType(checked))

    def __getitem__(self, name):
        return self.values[name]

    def __reduce__(self):
        # MappingProxyType does not pickle; worker processes need copies
        return (Parameters, (self.model, dict(self.values)))

    def replace(self, **changes):
        """Return a copy with some values changed (validated)."""
        return Parameters(self.model, {**self.values, **changes})

    def with_overrides(self, assignments):
        """Apply ``NAME=VALUE`` strings, as given to ``--set``.

        Raises
        ------
        ParameterError
            On a malformed assignment, an unknown name or a bad value.
        """
        changes = {}
        for text in assignments:
            name, sep, value = text.partition("=")
            name, value = name.strip(), value.strip()
            if not sep or not name or not value:
                raise ParameterError(
                    f"--set {text!r} is not of the form NAME=VALUE "
                    f"(for example --set c12=10)")
            if name not in SPECS[self.model]:
                raise ParameterError(
                    f"--set {text!r}: unknown parameter {name!r} for the "
                    f"{self.model} model; allowed names: "
                    f"{', '.join(SPECS[self.model])}")
            changes[name] = SPECS[self.model][name].check(value)
        return self.replace(**changes)

    @property
    def clutch_factor(self):
        """``N_c R_m S`` in m^3, the product of Eq. (3)."""
        return self["N_c"] * self["R_m"] * self["S"]

    def as_dict(self):
        """Plain ``dict`` of the values (SI units)."""
        return dict(self.values)


def _appendix_4dof():
    return {"J1": 1.12, "J2": 0.231, "J3": 4.07, "J4": 0.122,
            "k12": 3856.0, "k24": 32885.0, "c12": 0.5, "c24": 0.1,
            "c1": 0.1, "c2": 0.1, "c3": 0.1, "c4": 0.1,
            **_clutch_defaults()}


def _clutch_defaults():
    # N_c R_m S = 6e-3 m^3, see the module docstring for the calibration.
    return {"mu0": 0.09, "mu_g": 0.017, "N_c": 8.0, "R_m": 0.075, "S": 0.01,
            "p_m": 1.0e6, MEAN_PRESSURE_DAMPING: 0.0}


_PRESET_VALUES = {
    # Appendix A, 3 DOFs model; external damping as c_i of the 4-DOF table.
    "paper-3dof": ("3dof", {"J1": 1.12, "J24": 0.353, "J3": 4.07,
                            "k": 3451.0, "c": 0.5, "c1": 0.1, "c24": 0.1,
                            "c3": 0.1, **_clutch_defaults()}),
    # Appendix A, 4 DOFs model.
    "paper-4dof": ("4dof", _appendix_4dof()),
    # Section 4.2, solid line of Fig. 16: c12 = 10, mu_g = 0.022, k24 + 6 %.
    "paper-4dof-fitted": ("4dof", {**_appendix_4dof(), "c12": 10.0,
                                   "mu_g": 0.022, "k24": 32885.0 * 1.06}),
}

#: Preset descriptions, by name.
PRESETS = MappingProxyType({
    "paper-3dof": "3-DOF model, Appendix A of the paper",
    "paper-4dof": "4-DOF model, Appendix A of the paper",
    "paper-4dof-fitted": "4-DOF model fitted to the bench (section 4.2): "
                         "c12 = 10, mu_g = 0.022, k24 + 6 %",
})


def get_preset(name):
    """Return the named preset as :class:`Parameters`.

    Raises
    ------
    ParameterError
        If ``name`` is not a preset; the message lists the presets.
    """
    if name not in _PRESET_VALUES:
        raise ParameterError(f"preset = {name!r} is unknown; allowed: "
                             f"{', '.join(_PRESET_VALUES)}")
    model, values = _PRESET_VALUES[name]
    return Parameters(model, values)


def default_preset(model):
    """Name of the paper's preset for ``model`` ('4dof' or '3dof')."""
    if model not in SPECS:
        raise ParameterError(f"model = {model!r} is unknown; allowed: "
                             f"{', '.join(MODELS)}")
    return f"paper-{model}"


def load_toml(text, source="TOML"):
    """Parse a parameter file written by :func:`dumps_toml`.

    The file holds ``model = "4dof"`` and a ``[parameters]`` table; names
    not given there take the value of the paper's preset for that model.

    Raises
    ------
    ParameterError
        On TOML syntax errors or bad content, naming ``source``.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{source}: not valid TOML: {exc}") from None
    unknown = sorted(set(data) - {"model", "parameters"})
    if unknown:
        raise ParameterError(f"{source}: unknown key {unknown[0]!r}; allowed: "
                             "model and a [parameters] table")
    model = data.get("model")
    if model not in SPECS:
        raise ParameterError(f"{source}: model = {model!r} is not allowed; "
                             f"allowed: {', '.join(MODELS)}")
    table = data.get("parameters", {})
    if not isinstance(table, dict):
        raise ParameterError(f"{source}: [parameters] must be a table")
    try:
        return get_preset(default_preset(model)).replace(**table)
    except ParameterError as exc:
        raise ParameterError(f"{source}: {exc}") from None


def dumps_toml(params):
    """Serialise ``params`` to TOML text, with units as comments."""
    lines = [f'model = "{params.model}"', "", "[parameters]"]
    for name, spec in SPECS[params.model].items():
        lines.append(f"{name} = {params[name]!r}  # [{spec.unit}] "
                     f"{spec.description}")
    return "\n".join(lines) + "\n"

"""Validated parameter sets of the registered drivelines, presets, TOML.

Every value is held in SI units (kg m^2, N m/rad, N m s/rad, m, m^2, Pa,
s/rad). A parameter set is a :class:`Parameters` object: the model name and
an immutable mapping of canonical names to floats, checked against the
model's specifications (:mod:`drivelines.registry`). Named presets
reproduce the paper's Appendix A and the fitted set of its section 4.2;
sets can be overridden by name, saved to and loaded from TOML.
"""

from dataclasses import dataclass, field
import tomllib
from types import MappingProxyType
from typing import ClassVar

from infra.errors import ParameterError

from drivelines.registry import MODELS, get_model
from .kinds import SourceKind
from drivelines.specs import MEAN_PRESSURE_DAMPING, parse_overrides

__all__ = ["Parameters", "get_preset", "default_preset", "load_toml",
           "dumps_toml", "MEAN_PRESSURE_DAMPING"]


@dataclass(frozen=True)
class Parameters:
    """A validated, immutable parameter set of one model.

    Parameters
    ----------
    model : str
        Which driveline the values describe: a name of
        :data:`drivelines.registry.MODELS`.
    values : mapping
        Every parameter of the model's specifications, SI units.

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
    #: The clutch's friction characteristic
    #: (:class:`drivelines.friction.FrictionTable`), or None: the bench's
    #: bounded curve (see :meth:`with_friction`).
    friction: object = None
    #: A registry chain (:mod:`drivelines.registry`).
    source_kind: ClassVar[SourceKind] = SourceKind.CHAIN

    def __post_init__(self):
        specs = get_model(self.model).specs
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
        return (Parameters, (self.model, dict(self.values), self.friction))

    def replace(self, **changes):
        """Return a copy with some values changed (validated)."""
        return Parameters(self.model, {**self.values, **changes},
                          self.friction)

    def with_friction(self, table, slip):
        """A copy whose clutch has the friction characteristic ``table``
        (:class:`drivelines.friction.FrictionTable`): ``mu0`` and
        ``mu_g`` become its value and slope at ``slip`` (rad/s, the
        operating slip the linearisation of the chain is taken at), and
        every view that follows the slip (the bench's linearisation at
        its own slip, the orbit, the bench FMU) reads the table."""
        mu, slope = table.at(slip)
        return Parameters(self.model, {**self.values, "mu0": mu,
                                       "mu_g": slope}, table)

    def with_overrides(self, assignments):
        """Apply ``NAME=VALUE`` strings, as given to ``--set``.

        A plain VALUE is in the parameter's SI unit; it may carry a unit
        instead (``p_m=10bar``), see :func:`infra.quantities.parse_quantity`.

        Raises
        ------
        ParameterError
            On a malformed assignment, an unknown name or a bad value.
        """
        return self.replace(**parse_overrides(assignments, self.specs,
                                              self.model))

    @property
    def specs(self):
        """Specifications of the model's parameters, in display order."""
        return get_model(self.model).specs

    @property
    def driveline(self):
        """The :class:`~drivelines.registry.DrivelineModel` described."""
        return get_model(self.model)

    @property
    def clutch_factor(self):
        """``N_c R_m S`` in m^3, the product of Eq. (3)."""
        return self["N_c"] * self["R_m"] * self["S"]

    def as_dict(self):
        """Plain ``dict`` of the values (SI units)."""
        return dict(self.values)


def get_preset(name):
    """Return the named preset as :class:`Parameters`.

    Raises
    ------
    ParameterError
        If ``name`` is not a preset; the message lists the presets.
    """
    for model in MODELS.values():
        if name in model.presets:
            return Parameters(model.name, model.presets[name].values)
    names = [preset for m in MODELS.values() for preset in m.presets]
    raise ParameterError(f"preset = {name!r} is unknown; allowed: "
                         f"{', '.join(names)}")


def default_preset(model):
    """Name of the paper's preset for ``model``, e.g. '4dof'."""
    return get_model(model).default_preset


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
    if model not in MODELS:
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
    """Serialise ``params`` to TOML text, with units, meanings and
    allowed ranges as comments."""
    lines = [f'model = "{params.model}"', "", "[parameters]"]
    if params.friction is not None:
        # the table is data of its own file: say where mu0 and mu_g
        # come from, so that the file is not read as the curve's
        lines[1:1] = ["", f"# mu0 and mu_g: the value and slope of the "
                      f"{params.friction.words()} at the operating slip; "
                      "the table is not in this file: give it again for "
                      "the bench, the orbit and the runs to read it"]
    for name, spec in params.specs.items():
        lines.append(f"{name} = {params[name]!r}  # [{spec.unit}] "
                     f"{spec.description} (allowed: {spec.allowed()})")
    return "\n".join(lines) + "\n"

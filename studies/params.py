"""``judder params``: show, or save as TOML, a parameter set."""

from dataclasses import dataclass

from infra.files import write_text
from sources import dumps_toml

from ._common import resolve


def params(parameters=None, changes=None):
    """``judder params``: a parameter set with units and meanings.

    Returns
    -------
    ParamsResult
        ``save(path)`` writes it as TOML.
    """
    return ParamsResult(resolve(parameters, changes))


@dataclass(frozen=True)
class ParamsResult:
    """``judder params``: a parameter set with units and meanings."""

    params: object

    def as_dict(self):
        specs = self.params.specs
        return {"model": self.params.model,
                "parameters": {name: {"value": self.params[name],
                                      "unit": spec.unit,
                                      "allowed": spec.allowed(),
                                      "description": spec.description}
                               for name, spec in specs.items()},
                "friction": None if getattr(self.params, "friction", None)
                is None else self.params.friction.words()}

    def save(self, path, overwrite=False):
        """Write the set as TOML (refuses to replace a file by default)."""
        write_text(path, dumps_toml(self.params), overwrite=overwrite)

"""The driveline registry: the names of every model the tool knows.

:mod:`drivelines.registry` describes each driveline of the paper's kind
(its bodies and couplings by parameter name, the clutch, its Modelica
class and FMU, the signals a run reports, the names of its presets);
:mod:`drivelines.specs` holds the rules of a parameter (unit, allowed
range). The values of a model, and the models a user brings (a Modelica
class, an FMU), are model sources: :mod:`sources`. Packages above ask
the registry instead of branching on a model's name.
"""

from .registry import (DEFAULT_MODEL, MODELS, PRESETS, SPECS, Body,
                       Coupling, DrivelineModel, get_model)

__all__ = ["DEFAULT_MODEL", "MODELS", "PRESETS", "SPECS", "Body",
           "Coupling", "DrivelineModel", "get_model"]

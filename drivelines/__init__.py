"""The driveline registry: every model the tool knows, in one place.

:mod:`drivelines.registry` describes each driveline (its bodies and
couplings by parameter name, the clutch, its Modelica class and FMU, the
signals a run reports, its presets); :mod:`drivelines.parameters` holds
validated parameter sets of those models, their presets and TOML files.
Packages above (``stability``, ``pysim``, the ``judder`` application) ask
the registry instead of branching on a model's name.
"""

from .parameters import (Parameters, default_preset, dumps_toml,
                         get_preset, load_toml)
from .registry import (DEFAULT_MODEL, MODELS, PRESETS, SPECS, Body,
                       Coupling, DrivelineModel, get_model)
from .sources import SourceKind

__all__ = ["Parameters", "default_preset", "dumps_toml", "get_preset",
           "load_toml", "DEFAULT_MODEL", "MODELS", "PRESETS", "SPECS",
           "Body", "Coupling", "DrivelineModel", "get_model", "SourceKind"]

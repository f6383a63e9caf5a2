"""Model sources: where a driveline's equations and values come from.

Every parameter set names its :class:`~sources.kinds.SourceKind`, and
each kind has one module:

- :mod:`sources.presets`: a chain of the registry (:mod:`drivelines`)
  with its values, the paper's presets and TOML files (``CHAIN``);
- :mod:`sources.modelica`: a Modelica class, compiled by :mod:`fmu` and
  linearised from its equations (``MODELICA``);
- :mod:`sources.fmus`: a third-party FMU, linearised from its Jacobian
  (``FMU``), whose calls run in a child process (:mod:`sources.fmu_host`).

The kernels (:mod:`stability`), the time-domain runs (:mod:`pysim`)
and the studies (:mod:`studies`) take a parameter set of any kind and
ask it what it offers; whether a dither keeps a hybrid class in the mode
it is linearised in is each source's check (:mod:`sources.dither_modes`).
"""

from .kinds import SourceKind
from .presets import (Parameters, default_preset, dumps_toml, get_preset,
                      load_toml)

__all__ = ["SourceKind", "Parameters", "default_preset", "dumps_toml",
           "get_preset", "load_toml"]

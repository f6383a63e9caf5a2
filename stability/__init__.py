"""Floquet stability of a wet-clutch driveline under hydraulic dither.

Implements the 3-DOF and 4-DOF models of Tentarelli et al., "Parametric
excitation as a cause of clutch judder" (equation numbers in the docstrings
refer to that paper): parameter presets, the matrices of Eq. (1)-(9),
natural frequencies (Eq. 15-16), monodromy matrices and Floquet multipliers
(Eq. 10-13) and stability maps (Fig. 12, Fig. 14).

Importing this package does not import matplotlib; plots live in
:mod:`stability.plotting`.
"""

from .errors import JudderError, ParameterError
from .floquet import KINDS, FloquetResult, classify, floquet
from .maps import StabilityMap, stability_map
from .modal import (clutch_damper_damping_factor, closed_form_frequencies,
                    damped_modes, natural_frequencies)
from .model import Driveline, PeriodicSystem, build_driveline
from .monodromy import METHODS
from .parameters import PRESETS, SPECS, Parameters, get_preset

__all__ = ["JudderError", "ParameterError", "KINDS", "FloquetResult",
           "classify", "floquet", "StabilityMap", "stability_map",
           "clutch_damper_damping_factor", "closed_form_frequencies",
           "damped_modes", "natural_frequencies", "Driveline",
           "PeriodicSystem", "build_driveline", "METHODS", "PRESETS", "SPECS",
           "Parameters", "get_preset"]

"""Floquet stability of a wet-clutch driveline under hydraulic dither.

Implements the stability analysis of Tentarelli et al., "Parametric
excitation as a cause of clutch judder" (equation numbers in the
docstrings refer to that paper) for every driveline of
:mod:`drivelines`: the matrices of Eq. (1)-(9), natural frequencies (Eq.
14-16), monodromy matrices and Floquet multipliers (Eq. 10-13), stability
maps (Fig. 12, Fig. 14), tongue boundaries, sensitivity (Fig. 17-18), the
friction-gradient threshold (Fig. 19) and fitting to a measured boundary
(Fig. 16a). Kernels only: nothing here reads files or prints.

Importing this package does not import matplotlib; plots live in
:mod:`stability.plotting`.
"""

from .floquet import FloquetResult, floquet
from .kinds import KINDS, Kind, classify
from .maps import StabilityMap, stability_map
from .modal import (clutch_damper_damping_factor, closed_form_frequencies,
                    damped_modes, natural_frequencies)
from .linear import LinearDriveline
from .model import AugmentedSystem, Driveline, ModulatedSystem, PeriodicSystem
from .monodromy import DEFAULT_METHOD, METHODS
from .source import ModelSource, build_driveline

__all__ = ["FloquetResult", "floquet", "KINDS", "Kind", "classify",
           "StabilityMap", "stability_map", "clutch_damper_damping_factor",
           "closed_form_frequencies", "damped_modes", "natural_frequencies",
           "Driveline", "PeriodicSystem", "ModulatedSystem", "AugmentedSystem",
           "LinearDriveline", "ModelSource", "build_driveline",
           "DEFAULT_METHOD", "METHODS"]

"""Floquet stability of a wet-clutch driveline under hydraulic dither.

Implements the stability analysis of Tentarelli et al., "Parametric
excitation as a cause of clutch judder" (equation numbers in the
docstrings refer to that paper) for every driveline of
:mod:`drivelines`: the matrices of Eq. (1)-(9), natural frequencies (Eq.
14-16), monodromy matrices and Floquet multipliers (Eq. 10-13), stability
maps (Fig. 12, Fig. 14), tongue boundaries, sensitivity (Fig. 17-18), the
friction-gradient threshold (Fig. 19) and fitting to a measured boundary
(Fig. 16a). Kernels only: nothing here reads files or prints.

Where things are:

* top level, the Floquet core: :mod:`~stability.model` and
  :mod:`~stability.linear` (the periodic systems), :mod:`~stability.waveforms`,
  :mod:`~stability.modal`, :mod:`~stability.monodromy` (the engines),
  :mod:`~stability.multipliers`, :mod:`~stability.hill`, :mod:`~stability.kinds`,
  :mod:`~stability.maps`, :mod:`~stability.tongues`,
  :mod:`~stability.sensitivity`, :mod:`~stability.threshold`,
  :mod:`~stability.friction`;
* :mod:`stability.fit`: fitting to a measured boundary (a facade over
  private steps);
* :mod:`stability.decisions`: judder relevance, margins of a setting,
  design advice;
* :mod:`stability.uncertainty`: parameter ranges and the envelope over
  them;
* :mod:`stability.plots`: one module per kind of result; plots draw what
  a result holds and compute nothing.

Importing this package does not import matplotlib; only
:mod:`stability.plots` does.
"""

from .multipliers import FloquetResult, floquet
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

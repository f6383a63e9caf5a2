"""The broadest unstable region over uncertain parameters (section 4.2):
the parameter ranges and distributions and the points that sample them
(:mod:`~stability.uncertainty.ranges`), and the envelope of the tongue
boundaries over those samples (:mod:`~stability.uncertainty.envelope`).
"""

from .envelope import Envelope, build_envelope, sample_boundary
from .ranges import Correlated, Normal, Ranges, Uniform, design_points

__all__ = ["Uniform", "Normal", "Correlated", "Ranges", "design_points",
           "Envelope", "build_envelope", "sample_boundary"]

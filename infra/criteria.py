"""When a growing oscillation counts as judder: the criteria shared by the
Floquet analysis (:mod:`stability.decisions.relevance`) and the
time-domain verdict of a run (:mod:`pysim.run_analysis`), defined once
below both so the maps, ``judder check`` and the bench charts agree.
"""

__all__ = ["ENGAGEMENT_DURATION_S", "DEFAULT_MIN_GROWTH_PER_S"]

#: Typical duration of the slipping phase of one engagement, s.
ENGAGEMENT_DURATION_S = 1.0

#: Smallest growth rate counted as judder, 1/s: one e-fold over
#: :data:`ENGAGEMENT_DURATION_S`.
DEFAULT_MIN_GROWTH_PER_S = 1.0 / ENGAGEMENT_DURATION_S

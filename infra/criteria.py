"""When a growing oscillation counts as judder: the criteria shared by the
Floquet analysis (:mod:`stability.decisions.relevance`) and the
time-domain verdict of a run (:mod:`pysim.bench.verdict`), defined once
below both so the maps, ``judder check`` and the bench charts agree.
"""

import numpy as np

__all__ = ["ENGAGEMENT_DURATION_S", "DEFAULT_MIN_GROWTH_PER_S",
           "DEFAULT_JUDDER_LIMIT_RPM", "MECHANISMS", "mechanism_code"]

#: Typical duration of the slipping phase of one engagement, s.
ENGAGEMENT_DURATION_S = 1.0

#: Smallest growth rate counted as judder, 1/s: one e-fold over
#: :data:`ENGAGEMENT_DURATION_S`.
DEFAULT_MIN_GROWTH_PER_S = 1.0 / ENGAGEMENT_DURATION_S

#: NVH limit of an engagement, rpm: an oscillation of the upstream speed
#: at the dither-related frequencies larger than this is judder, whatever
#: its mechanism. 30 rpm at 100 Hz is an angular acceleration of about
#: 2000 rad/s^2 of the clutch plates (an inertia torque of about 250 N m
#: on the 4-DOF model's J4, half the clutch's mean torque), and 3 % of
#: the 1000 rpm of the paper's bench: a vibration a driver feels and a
#: bench engineer reads as judder in a peak-amplitude chart (Fig. 10).
DEFAULT_JUDDER_LIMIT_RPM = 30.0

#: Why a setting judders, as codes of the predicted chart
#: (:mod:`stability.orbit_chart`): none (no judder), forced (the dither's
#: forced oscillation above the limit), parametric (an instability), both.
MECHANISMS = ("none", "forced", "parametric", "both")


def mechanism_code(forced, parametric):
    """Index into :data:`MECHANISMS` of an oscillation forced above the
    limit (``forced``) and/or of an instability (``parametric``), bools
    or arrays of bools: 1 + 2 = 3 is both."""
    return np.asarray(forced, dtype=int) + 2 * np.asarray(parametric,
                                                          dtype=int)

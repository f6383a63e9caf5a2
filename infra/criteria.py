"""When a growing oscillation counts as judder: the criteria and the
verdict words shared by the Floquet analysis
(:mod:`stability.decisions.relevance`) and the time-domain verdict of a
run (:mod:`pysim.bench.verdict`), defined once below both so the maps,
``judder check`` and the bench charts agree, and say so in the same
words.
"""

import numpy as np

__all__ = ["ENGAGEMENT_DURATION_S", "DEFAULT_MIN_GROWTH_PER_S",
           "DEFAULT_JUDDER_LIMIT_RPM", "CHART_THRESHOLD_SPREAD_PER_S",
           "JUDDER", "SLOW_GROWTH", "STABLE", "NO_JUDDER", "VERDICTS",
           "RUN_VERDICTS", "CANNOT_TELL", "run_verdict", "MECHANISMS",
           "mechanism_code"]

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

#: How far the growth rate a chart's verdict calls judder from may lie
#: from its threshold, 1/s: on the tongue-4 round trip (docs/roundtrip.md)
#: runs of 3 s whose Floquet exponent lay within this of the threshold
#: were called either way. ``judder fit --chart`` widens its intervals by
#: the values this spread gives (:func:`stability.fit.fit_boundary`,
#: ``threshold_spread``).
CHART_THRESHOLD_SPREAD_PER_S = 0.25

#: The verdict words, written the same in every output (text, JSON,
#: figures, the report). A dither setting's, from its Floquet multipliers
#: (:func:`stability.decisions.relevance.verdict`), most severe first:
#: ``JUDDER`` (an instability growing at the minimum growth rate or
#: faster), ``SLOW GROWTH`` (an instability slower than that), ``STABLE``.
JUDDER, SLOW_GROWTH, STABLE = "JUDDER", "SLOW GROWTH", "STABLE"
VERDICTS = (JUDDER, SLOW_GROWTH, STABLE)

#: A run's verdict (a bench's, a simulated engagement's, a periodic
#: orbit's): ``JUDDER`` where an instability grows at the minimum growth
#: rate or faster or the dither-related oscillation exceeds the NVH limit
#: (as ``judder fit --limit`` compares); else ``NO JUDDER``: a run cannot
#: tell a setting's SLOW GROWTH from STABLE; ``CANNOT TELL`` where the run
#: was read but what it was run at is not known (a bench run whose dither
#: frequency, estimated from an aliasing pressure, may be any of its
#: aliases): such a run is no verdict and is counted as none. In running
#: text the words are lower case (``NO_JUDDER.lower()``).
NO_JUDDER = "NO JUDDER"
CANNOT_TELL = "CANNOT TELL"
RUN_VERDICTS = (JUDDER, NO_JUDDER, CANNOT_TELL)


def run_verdict(judder, told=True):
    """A run's verdict word (:data:`RUN_VERDICTS`) from whether it
    judders; None where it was not read (None); ``CANNOT TELL`` where it
    was read but its reading cannot be told (``told`` False).

    Examples
    --------
    >>> run_verdict(True), run_verdict(False), run_verdict(None)
    ('JUDDER', 'NO JUDDER', None)
    >>> run_verdict(False, told=False)
    'CANNOT TELL'
    """
    if judder is None:
        return None
    if not told:
        return CANNOT_TELL
    return JUDDER if judder else NO_JUDDER


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

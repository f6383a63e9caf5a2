r"""The model side of a boundary fit (section 4.2): the fitting problem,
the model's tongue boundaries at trial parameters, and the residuals.

Residuals
---------
The measured amplitude is the *lowest* at which judder was seen, so:

* a point with judder: model boundary of its matched kind minus the
  measured amplitude; and, as a second residual, how far the boundary of
  any *other* kind lies below the measured amplitude (zero if none does:
  the model must not predict judder of another kind below the measured
  onset);
* a censored point: how far the *lowest* model boundary (any kind) lies
  below ``p_max`` (zero where the model is stable up to ``p_max`` too).

Both one-sided residuals are zero with zero slope wherever the model
agrees with the data, so near a good fit the sum of squares stays smooth.
The degrees of freedom count the points with judder and the one-sided
residuals that are not zero.

With ``error_model='absolute'`` every residual is in bar (equal scatter
at every amplitude). With ``'relative'`` each residual is divided by its
measured amplitude (at least 2 % of ``p_max``; censored points by
``p_max``), which suits a scatter proportional to the amplitude (a noise
of a few per cent). Dividing by the measured amplitude puts the fitted
boundary 2 sigma^2 low (0.2 % with 3 % noise, about a seventh of mu_g's
95 % half-width on the boundaries of ``benchmarks/fit_coverage.py``).
Differences of logarithms would remove that, and were tried: they
compress the residual of a point matched to a kind with no boundary
below the search limit (3 bar against 0.57 bar: 1.7 instead of 4.3), and
on 60 noisy boundaries three fits then stopped at k24 = 41 000-42 000
N m/rad for a truth near 29 000 (reported as problems, but wrong).
"""

import numpy as np

from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
from infra.units import PA_PER_BAR

from ..friction import forced_onset
from ..source import build_driveline
from ..monodromy import DEFAULT_METHOD
from ..tongues import tongue_boundaries
from ._common import evaluated

__all__ = ["model_boundary", "fit_curves", "CURVE_POINTS"]


#: Frequencies of the start and fitted curves stored for the plot.
CURVE_POINTS = 100


def model_boundary(params, freq_hz, p_max, method=DEFAULT_METHOD, *,
                   min_growth=DEFAULT_MIN_GROWTH_PER_S, added=(),
                   forced_limit=None):
    """Lowest amplitude of judder growing at ``min_growth`` (1/s) or
    faster at each frequency, Pa: the model boundary
    :func:`stability.fit.fit_boundary` compares with.

    NaN where there is none up to ``p_max``; ``method`` is the monodromy
    engine (:data:`stability.monodromy.METHODS`). ``min_growth`` defaults
    to ``judder check``'s judder-relevant rate, as ``fit_boundary``'s
    does; 0 gives the stability boundary
    (:func:`stability.tongues.tongue_boundaries`). ``added`` are ``(name,
    value)`` pairs added to ``params`` for the model evaluated (see
    :func:`stability.fit._common.evaluated`). With ``forced_limit``
    (rad/s), the lower of that and the amplitude at which the forced
    oscillation of the upstream speed reaches it
    (:func:`stability.friction.forced_onset`), as a bench's verdict has
    it.
    """
    driveline = build_driveline(evaluated(params, added))
    boundary = tongue_boundaries(driveline, freq_hz, p_max, method,
                                 min_growth=min_growth,
                                 check=False).stability_boundary
    if forced_limit is None:
        return boundary
    forced = forced_onset(driveline, freq_hz, forced_limit)
    return np.fmin(boundary, np.where(forced <= p_max, forced, np.nan))


def fit_curves(result, points=CURVE_POINTS, method=DEFAULT_METHOD):
    """Lowest model boundary with the start and the fitted values.

    Parameters
    ----------
    result : FitResult
    points : int
        Frequencies over the measured range.
    method : str
        Monodromy engine.

    Returns
    -------
    freq_hz, start_bar, fitted_bar : ndarray, shape (points,)
        Hz, and the two boundaries in bar (NaN: stable up to ``p_max``),
        as drawn in Fig. 16a (dotted: first attempt, solid: fitted).
    """
    p_max = result.p_max_bar * PA_PER_BAR
    freq = np.linspace(result.freq_hz.min(), result.freq_hz.max(), points)
    curves = [model_boundary(p, freq, p_max, method,
                             min_growth=result.min_growth,
                             added=result.added,
                             forced_limit=result.forced_limit) / PA_PER_BAR
              for p in (result.start_params, result.params)]
    return freq, curves[0], curves[1]



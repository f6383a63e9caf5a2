r"""Which instabilities matter for judder: growth against the engagement.

A Floquet multiplier outside the unit circle is an instability, but it only
becomes judder if it grows enough while the clutch slips. The response
grows as :math:`e^{\sigma t}` with the growth rate
:math:`\sigma = \ln|\lambda| / T` (Eq. 12-13, ``growth_rate_per_s`` of
every result). A slipping phase of a wet-clutch engagement lasts about
:data:`infra.criteria.ENGAGEMENT_DURATION_S` (the bench engagements of
section 2.2 run for 1-2 s); a mode that grows by less than one e-fold
over it stays at the size of whatever started it. So an instability is *judder-relevant* when

.. math:: \sigma > \sigma_{min}, \qquad
          \sigma_{min} = 1 / t_{engagement} = 1\ \text{1/s}

by default (:data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`). This is
the same 1/s the time-domain verdict of :mod:`pysim.bench.verdict` uses
(defined once, in :mod:`infra.criteria`), so the maps, the
tongue boundaries, ``judder check`` and ``judder envelope`` agree with the
bench charts. The slow slip-speed mode of a stiffly damped clutch damper
(about 0.02 1/s at 60 Hz, 1.2 bar with ``c12 = 10``) is unstable but not
judder-relevant: it needs 50 s for one e-fold.

``min_growth = 0`` gives back plain stability (``|lambda| > 1``).

The verdict of a dither setting is one of three words, written the same
in every output (``judder check``'s text and JSON, the figures, the
report), :data:`infra.criteria.VERDICTS`:

* ``JUDDER``: a multiplier outside the unit circle whose growth rate
  exceeds ``min_growth`` (inside a stability tongue and judder-relevant);
* ``SLOW GROWTH``: a multiplier outside the unit circle (inside a
  stability tongue) growing slower than that: less than one e-fold over
  an engagement, no judder;
* ``STABLE``: every non-rigid-body multiplier inside the unit circle.

The words themselves are :mod:`infra.criteria`'s, shared with the
verdict of a run.
"""

import numpy as np

from infra.criteria import (DEFAULT_MIN_GROWTH_PER_S, JUDDER, SLOW_GROWTH,
                            STABLE)
from infra.errors import JudderError

__all__ = ["is_judder_relevant", "verdict"]


def is_judder_relevant(growth_rate_per_s, min_growth=DEFAULT_MIN_GROWTH_PER_S):
    """True where an instability grows fast enough to be judder.

    Parameters
    ----------
    growth_rate_per_s : array_like of float
        Growth rates ``ln|lambda| / T`` (1/s) of leading multipliers, or
        real parts of characteristic exponents (any shape).
    min_growth : float
        Smallest judder-relevant rate, 1/s (finite, >= 0); 0 counts every
        instability.

    Returns
    -------
    ndarray of bool, same shape
        ``growth_rate_per_s > min_growth`` (NaN gives False).

    Raises
    ------
    JudderError
        If ``min_growth`` is negative or not finite.

    Examples
    --------
    >>> is_judder_relevant([0.02, 0.9, 1.5, 25.0]).tolist()
    [False, False, True, True]
    >>> is_judder_relevant([0.02, -0.1], min_growth=0.0).tolist()
    [True, False]
    """
    if not np.isfinite(min_growth) or min_growth < 0:
        raise JudderError(f"min_growth = {min_growth!r} 1/s is not allowed; "
                          "allowed: a finite rate >= 0")
    rate = np.asarray(growth_rate_per_s, dtype=float)
    with np.errstate(invalid="ignore"):
        return rate > min_growth


def verdict(unstable, growth_rate_per_s, min_growth=DEFAULT_MIN_GROWTH_PER_S):
    """The verdict word of one setting.

    Parameters
    ----------
    unstable : bool
        The leading (non-rigid-body) multiplier lies outside the unit
        circle: the setting is inside a stability tongue.
    growth_rate_per_s : float
        Its growth rate ``ln|lambda| / T``, 1/s.
    min_growth : float
        Smallest judder-relevant rate, 1/s (:func:`is_judder_relevant`).

    Returns
    -------
    str
        One of :data:`infra.criteria.VERDICTS`.

    Examples
    --------
    >>> verdict(True, 25.0), verdict(True, 0.56), verdict(False, -0.3)
    ('JUDDER', 'SLOW GROWTH', 'STABLE')
    """
    if not unstable:
        return STABLE
    return JUDDER if is_judder_relevant(growth_rate_per_s, min_growth) \
        else SLOW_GROWTH

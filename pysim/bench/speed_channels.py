"""What the samples of a speed channel mean, and the angle they carry.

A bench records a shaft's rotation in one of three ways:

* ``passage``: a magnetic pick-up on a toothed wheel gives, at each tooth
  passage ``t_k``, the mean speed since the previous one (section 2.2:
  41 teeth, 684 samples/s at 1000 rpm); ``speed_k (t_k - t_{k-1})`` is one
  tooth pitch, so the angle follows exactly by summation;
* ``sampled``: the DAQ samples (or resamples) a speed at its own times,
  usually uniformly, sometimes with gaps where samples were lost;
* ``angle``: an encoder angle (rad, deg, rev, or counts of N a
  revolution) at the DAQ's times; one that restarts every revolution is
  unwrapped, a counter that overflows elsewhere is not read.

The judder analysis (:mod:`pysim.bench.verdict`) rebuilds the angle from
mean speeds over the sample intervals, the pick-up's convention.
:func:`interval_means` turns each kind into it: a passage channel as it
is, a sampled speed through the exact integral of its cubic spline (which
also bridges gaps), an angle through its differences.
:func:`detect_speed_kind` tells a pick-up from a sampled speed by its time
stamps: a pick-up's intervals vary inversely with the speed, their
product with it is the tooth pitch.
"""

import numpy as np
from scipy.interpolate import CubicSpline

__all__ = ["SPEED_KINDS", "detect_speed_kind", "interval_means"]

#: The kinds of speed channel, and what each one's samples are.
SPEED_KINDS = {"passage": "mean speed since the previous sample (a "
                          "toothed-wheel pick-up)",
               "sampled": "the speed at the sample times (a DAQ's rate, "
                          "uniform or with gaps)",
               "angle": "the shaft angle at the sample times (an encoder)"}
#: Relative spread of the sample intervals below which they are uniform.
UNIFORM_SPREAD = 1e-6
#: Correlation of the intervals with the inverse speed above which the
#: samples are a pick-up's tooth passages.
PASSAGE_CORRELATION = 0.5


def _spread(values):
    mean = np.mean(values)
    return float(np.std(values) / abs(mean)) if mean else np.inf


def detect_speed_kind(time, speed):
    """``'passage'`` or ``'sampled'``, from the time stamps of a speed.

    Uniform intervals (to :data:`UNIFORM_SPREAD`) are a DAQ's sampling.
    Otherwise a pick-up's intervals follow the inverse of its speed (each
    is one tooth pitch over the mean speed across it), while a DAQ's, made
    irregular by rounded time stamps or lost samples, do not: the channel
    is a pick-up's when the intervals correlate with the inverse speed
    (correlation above :data:`PASSAGE_CORRELATION`).

    Parameters
    ----------
    time : ndarray, shape (n,)
        s, increasing.
    speed : ndarray, shape (n,)
        rad/s.

    Returns
    -------
    str
        A key of :data:`SPEED_KINDS` (never ``'angle'``: that is told by
        the channel's unit).

    Examples
    --------
    >>> t = np.arange(0.0, 1.0, 1e-3)
    >>> detect_speed_kind(t, 100 + np.sin(50 * t))
    'sampled'
    """
    if len(time) < 4:
        return "passage"
    interval = np.diff(time)
    inverse = 1.0 / np.maximum(np.abs(speed[1:]), 1e-12)
    # intervals over lost samples (several pitches, or a DAQ's gap) aside
    single = np.abs(interval / np.median(interval) - 1.0) < 0.5
    interval, inverse = interval[single], inverse[single]
    if len(interval) < 4 or _spread(interval) < UNIFORM_SPREAD \
            or np.std(inverse) == 0:
        return "sampled"
    correlation = np.corrcoef(interval, inverse)[0, 1]
    return "passage" if correlation > PASSAGE_CORRELATION else "sampled"


def _whole_pitches(time, speed):
    """A pick-up's mean speeds with lost passages restored.

    Each interval spans a whole number of tooth pitches: one normally,
    more where passages were lost (a dropped sample, a NaN the reader
    removed), while the speed recorded at its end is that of its last
    pitch only. The pitch is the median product of interval and speed; an
    interval of ``k`` pitches gets the mean speed ``k pitch / interval``,
    so that the rebuilt angle is exact at every passage (read as it is,
    it is off by the relative change of speed across the lost teeth:
    per cent of a pitch each time with a 20 rpm oscillation).
    """
    interval = np.diff(time)
    product = interval * speed[1:]
    pitch = np.median(np.abs(product))
    if not pitch > 0:
        return speed
    teeth = np.maximum(np.rint(np.abs(product) / pitch), 1.0)
    if np.all(teeth == 1.0):
        return speed
    out = speed.astype(float).copy()
    out[1:] = np.where(teeth > 1, np.sign(speed[1:]) * teeth * pitch
                       / interval, speed[1:])
    return out


def interval_means(time, values, kind):
    """Mean speed over each sample interval, the pick-up's convention.

    Parameters
    ----------
    time : ndarray, shape (n,)
        s, increasing.
    values : ndarray, shape (n,)
        rad/s for ``passage`` and ``sampled``, rad for ``angle``.
    kind : str
        A key of :data:`SPEED_KINDS`.

    Returns
    -------
    time, speed : ndarray
        The end of each interval (s) and the mean speed over it (rad/s);
        a ``passage`` channel as it is but where passages were lost (an
        interval of several pitches), the others one sample shorter.
    """
    if len(time) < 2:
        return time, values
    if kind == "passage":
        return time, _whole_pitches(time, values)
    if kind == "sampled":
        angle = CubicSpline(time, values).antiderivative()(time)
    elif kind == "angle":
        angle = np.unwrap(values)
    else:
        raise ValueError(f"speed kind {kind!r} is unknown; allowed: "
                         f"{', '.join(SPEED_KINDS)}")
    return time[1:], np.diff(angle) / np.diff(time)

"""Signal analysis of runs and bench acquisitions: spectrum, growth rate.

Kernels only: arrays in, result objects out.
"""

from dataclasses import dataclass

import numpy as np
import scipy.signal

from infra.spectrum import hann_spectrum

__all__ = ["Spectrum", "amplitude_spectrum", "GrowthFit",
           "stroboscopic_growth", "free_response_growth", "dither_envelope",
           "per_period"]


@dataclass(frozen=True)
class Spectrum:
    """Single-sided amplitude spectrum.

    Attributes
    ----------
    freq_hz : ndarray
    amplitude : ndarray
        Amplitude of a sine at each frequency, in the signal's unit
        (Hann window, amplitude-corrected).
    peak_freq_hz, peak_amplitude : float
        Largest line above ``f_min``.
    """

    freq_hz: np.ndarray
    amplitude: np.ndarray
    peak_freq_hz: float
    peak_amplitude: float


def amplitude_spectrum(time, signal, f_min=2.0):
    """Amplitude spectrum of a uniformly sampled signal (Fig. 8;
    :func:`infra.spectrum.hann_spectrum`).

    The linear trend (the engagement itself) is removed first; the peak is
    searched above ``f_min`` Hz.
    """
    time = np.asarray(time, dtype=float)
    y = scipy.signal.detrend(np.asarray(signal, dtype=float))
    freq, amplitude = hann_spectrum(y, np.median(np.diff(time)))
    band = freq >= f_min
    i = np.flatnonzero(band)[np.argmax(amplitude[band])]
    return Spectrum(freq_hz=freq, amplitude=amplitude,
                    peak_freq_hz=float(freq[i]),
                    peak_amplitude=float(amplitude[i]))


@dataclass(frozen=True)
class GrowthFit:
    """Exponential growth rate of the part of a response that is not
    periodic with the dither.

    Attributes
    ----------
    rate : float
        Fitted rate, 1/s (comparable with the Floquet exponent
        ``ln|lambda| / T``).
    stderr : float
        Standard error of the slope, 1/s.
    periods : int
        Dither periods in the fit.
    envelope_time, envelope : ndarray
        The sampled envelope ``|x(t_k + T) - x(t_k)|`` and its times.
    """

    rate: float
    stderr: float
    periods: int
    envelope_time: np.ndarray
    envelope: np.ndarray


def _strobe(time, signals, period):
    """Samples of the stacked signals at t_k = k T, and t_k."""
    time = np.asarray(time, dtype=float)
    dt = np.median(np.diff(time))
    per = int(round(period / dt))
    if per < 1 or abs(per * dt - period) > 1e-6 * period:
        raise ValueError("the sampling must divide the dither period")
    x = np.vstack([np.asarray(s, dtype=float) for s in signals])
    return time[::per], x[:, ::per]


def _log_slope(t, envelope, start):
    """Least-squares slope of ln(envelope) against t for t >= start."""
    keep = (t >= start) & (envelope > 0)
    t, d = t[keep], envelope[keep]
    slope, intercept = np.polyfit(t, np.log(d), 1)
    residual = np.log(d) - (slope * t + intercept)
    stderr = np.sqrt(np.sum(residual ** 2) / max(len(t) - 2, 1)
                     / np.sum((t - t.mean()) ** 2))
    return GrowthFit(rate=float(slope), stderr=float(stderr),
                     periods=int(len(t)), envelope_time=t, envelope=d)


def stroboscopic_growth(time, signals, period, skip=0.3):
    r"""Growth rate of one run, from samples taken once per dither period.

    The response of the linear periodic system is a periodic forced part
    plus the free part :math:`X(T)^k z_0`. Sampled at :math:`t_k = kT`
    the forced part is constant, so successive differences
    :math:`d_k = x(t_{k+1}) - x(t_k)` contain only the free part and grow as
    :math:`|\lambda|^k`: the slope of :math:`\ln\|d_k\|` against
    :math:`t_k` (least squares, after dropping the first ``skip`` share of
    the run where the other modes have not died out) is
    :math:`\ln|\lambda|/T`. A multiplier close to +1 is weighted by
    :math:`|\lambda - 1|` and hard to see; when two runs can be made, use
    :func:`free_response_growth`.

    Parameters
    ----------
    time : ndarray, shape (n,)
        Uniform samples with a whole number of samples per ``period``.
    signals : sequence of ndarray, shape (n,)
        Signals combined into ``x`` (e.g. the measured speeds).
    period : float
        Dither period, s.
    skip : float
        Share of the run left out at the start.
    """
    t, samples = _strobe(time, signals, period)
    d = np.linalg.norm(np.diff(samples, axis=1), axis=0)
    return _log_slope(t[:-1], d, skip * t[-1])


def free_response_growth(time, free_signals, period, rank_tolerance=1e-9):
    r"""Leading growth rate of a free response by a Prony (Hankel DMD) fit.

    ``free_signals`` are differences of two runs of a linear model that
    differ only in their initial state: the forced response cancels and the
    samples :math:`\Delta x_k = \Delta x(kT)` obey
    :math:`\Delta x_{k+1} = X(T) \Delta x_k`. Stacking two successive
    samples (so that fewer signals than states still see every mode), the
    least-squares one-step map of the sample sequence, truncated to its
    numerical rank, has the Floquet multipliers of the excited modes as
    eigenvalues. All modes are fitted at once, so a slow mode cannot bias
    the rate of a faster-growing one.

    Returns
    -------
    GrowthFit
        ``rate`` is :math:`\ln|\mu_{max}|/T`; ``stderr`` is the relative
        residual of the one-step fit (a check of linearity);
        ``envelope`` is the norm of the free response at the samples.
    """
    t, samples = _strobe(time, free_signals, period)
    stacked = np.vstack([samples[:, :-2], samples[:, 1:-1]])
    following = np.vstack([samples[:, 1:-1], samples[:, 2:]])
    u, sigma, vt = np.linalg.svd(stacked, full_matrices=False)
    rank = int(np.sum(sigma > rank_tolerance * sigma[0]))
    u, sigma, vt = u[:, :rank], sigma[:rank], vt[:rank]
    step = u.T @ following @ vt.T / sigma
    multipliers = np.linalg.eigvals(step)
    fitted = u @ step @ (u.T @ stacked)
    residual = np.linalg.norm(following - fitted) / np.linalg.norm(following)
    return GrowthFit(rate=float(np.log(np.abs(multipliers).max()) / period),
                     stderr=float(residual), periods=int(samples.shape[1]),
                     envelope_time=t,
                     envelope=np.linalg.norm(samples, axis=0))


def dither_envelope(time, signal, freq_hz, start, window=0.4):
    """Envelope of the oscillation at the dither frequency and its growth.

    The signal is band-passed to +-10 % around ``freq_hz`` (4th-order
    Butterworth, forward and backward) and its Hilbert envelope taken; the
    growth rate is the least-squares slope of the log envelope over
    ``[start, start + window]``.

    Returns
    -------
    envelope : ndarray, shape (n,)
        In the signal's unit.
    rate : float
        1/s; positive when the oscillation grows (judder setting in).
    """
    time = np.asarray(time, dtype=float)
    fs = 1.0 / np.median(np.diff(time))
    band = np.array([0.9, 1.1]) * freq_hz
    if band[1] >= fs / 2:
        raise ValueError("sampling too slow for the dither frequency")
    sos = scipy.signal.butter(4, band, btype="bandpass", fs=fs, output="sos")
    filtered = scipy.signal.sosfiltfilt(sos, np.asarray(signal, dtype=float))
    envelope = np.abs(scipy.signal.hilbert(filtered))
    keep = (time >= start) & (time <= start + window) & (envelope > 0)
    rate = np.polyfit(time[keep], np.log(envelope[keep]), 1)[0]
    return envelope, float(rate)


def per_period(time, values, period):
    """Per period: centre time, minimum, maximum and mean of ``values``.

    Parameters
    ----------
    time : ndarray, shape (n,)
        s, increasing.
    values : ndarray, shape (n,)
    period : float
        s (a dither period).

    Returns
    -------
    centre, low, high, mean : ndarray, shape (m,)
        One entry per period that holds samples: the mean of its time
        stamps (s), and the minimum, maximum and mean of its values. The
        last period, where the run ends, is left out when it holds fewer
        than half the samples of the others: its mean would be that of a
        part of the swing (a run ending at a whole number of periods has
        one sample there, at the dither's crest or trough).
    """
    # (a sample on a period's start belongs to it, whatever the rounding)
    index = np.floor((time - time[0]) / period + 1e-9).astype(int)
    count = index[-1] + 1
    edges = np.searchsorted(index, np.arange(count + 1))
    keep = np.diff(edges) > 0
    starts = edges[:-1][keep]
    sizes = np.diff(np.append(starts, len(values)))
    if len(sizes) > 1 and sizes[-1] < 0.5 * np.median(sizes[:-1]):
        time, values, starts = (time[:starts[-1]], values[:starts[-1]],
                                starts[:-1])
    low = np.minimum.reduceat(values, starts)
    high = np.maximum.reduceat(values, starts)
    mean = np.add.reduceat(values, starts) / np.diff(
        np.append(starts, len(values)))
    centre = np.add.reduceat(time, starts) / np.diff(
        np.append(starts, len(values)))
    return centre, low, high, mean

r"""What one engagement run shows: is there judder, of which kind, how fast.

The input is what a bench records (section 2.2): the speed upstream of the
clutch from a pick-up (sampled at tooth passages, not uniformly), and
optionally the speed downstream and the actuation pressure, each on its
own time base. :func:`analyse_run` does, in order:

1. **Engagement window**: where the pressure is on (after its ramp, above
   :data:`PRESSURE_ON` of its high level) and the clutch slips (slip above
   :data:`SLIP_SHARE` of its largest value; without a downstream speed,
   the pressure alone), both smoothed over :data:`SMOOTHING_S`.
2. **Dither setting** when it is not given: the pressure's spectral peak
   in the window, refined to the frequency of the least-squares sinusoid
   fitted to the pressure samples as taken (:func:`estimate_dither`); the
   amplitude is that sinusoid's. Frequency, amplitude and phase come with
   their standard uncertainties, and with warnings where the sampling
   cannot support them (:mod:`pysim.bench.dither`). Where one value of
   the setting is given and the other estimated, the run is read at the
   value given, and a given amplitude the pressure's estimate contradicts
   is warned of (:func:`pysim.bench.dither.disagreement`).
3. **Components** of the upstream speed, resampled uniformly over the
   whole run and high-passed above 5 Hz (the engagement itself is
   slower), by complex demodulation,
   :math:`e(t) = 2|\mathrm{LP}[y(t) e^{-2\pi i f_c t}]|`: at the dither
   frequency ``f``, at ``f/2`` and at the largest other spectral peak
   below ``f/2`` (where every combination response has a frequency).
   Their largest envelopes are the amplitudes a chart contours (Fig. 10).

The verdict
-----------
Judder is what the bench sees (Fig. 7b, Fig. 10): an oscillation of the
upstream speed at the dither-related frequencies that is large or
growing. A run has judder when, in the engagement window,

- the oscillation at ``f``, ``f/2`` or the other peak (each component's
  largest envelope if it stays after it, else its level over the
  window's last third: a transient that dies away does not count)
  exceeds ``judder_limit_rpm`` (:data:`infra.criteria.
  DEFAULT_JUDDER_LIMIT_RPM`, 30 rpm), or
- an instability grows at ``min_growth`` or faster (default
  :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`, 1/s).

Its **mechanism** is a second statement. *Forced*: the part of the
oscillation at ``f`` that the dither forces (periodic with it) exceeds
the limit; near a natural frequency (tongues 1 and 2 lie on f1 and f2)
the dither drives the mode directly, and the amplitude grows with p_f
without a threshold. *Parametric*: an instability grows (the part that is
not periodic with the dither grows, at ``f``, ``f/2`` or a combination
frequency; the Floquet exponent), or a component at ``f/2`` or at another
frequency, which the dither cannot force, exceeds the limit. *Both*
where both hold (a single-period judder growing out of a forced
resonance above the limit). ``kind`` names the parametric kind, or
``'forced'``.

What separates the two is periodicity: the forced response repeats every
dither period ``T``, the free response does not. So growth is read on
the **non-periodic part** (as :func:`pysim.bench.signals.stroboscopic_growth`
does for simulations),

.. math:: d(t) = y(t + L) - y(t), \qquad
          r(t) = \sqrt{\overline{d^2}}\ \text{(mean over two periods)},

with the lag ``L = T`` for ``f/2`` and the other peaks, where ``d`` is
about twice the component; the forced response cancels, the engagement
transient and the beating of a forced resonance decay. A single-period
judder grows by only ``exp(g T) - 1`` per period (1.5 % at 1.5 1/s and
100 Hz, below a pick-up's noise), so at ``f`` the lag is
:data:`LONG_LAG_S` (a whole number of periods), the band
:data:`SINGLE_PERIOD_BAND_HZ`, and the rate is fitted to the speed's own
phasor as a forced part plus a growing one (:func:`single_period_growth`).
The band around ``f`` is also read with ``L = T`` and the wide band,
where a combination response near ``f`` grows. In each envelope (and in
``r``) the growth rate is read from the lowest value before the maximum
up to where the envelope last rises through :data:`READ_SHARE` of the
maximum, or over its first e-fold (:func:`growth_phase`): the rise
before the nonlinear limit (the friction curve's flattening) bends it.
It is the rate of an exponential over a floor fitted to the log of that
rise, with its standard uncertainty (:func:`rise_rate`): a pick-up's
noise or an integer export's rounding (speeds to 1 or 0.1 rpm) lies
under the start of the rise, and a straight line through the log read
the example run06 at 3.47 1/s recorded and 4.71 1/s rounded, where the
floor's fit reads 4.93 +- 0.26 and 4.71 +- 0.17 1/s (its exponent on
the bench's linearisation: 5.0 1/s). A growth counts when its linear
rise lasts :data:`MIN_GROWTH_PERIODS` periods, grows at ``min_growth``
or more over at least one e-fold to the maximum (two if the rise is
shorter than :data:`MIN_PHASE_S`: noise makes short rises), reaches
:data:`NOISE_FLOOR_RPM` of the speed or more, and stays after its maximum
(a beat of decaying free modes rising from a null dies away again; a
single-period judder that saturates is periodic again, and the speed's
own component stays), while the speed's own component there reaches
``min_amplitude`` (default :data:`MIN_AMPLITUDE_RPM`), and its rate is
at least :data:`GROWTH_SIGNIFICANCE` standard uncertainties above zero
(a rise read over a tenth of a second at 2 rpm is noise). The largest
growing component gives the growth rate; its kind is that of its
frequency (``f``: single-period, ``f/2``: double-period), or read from
the spectrum of ``d`` within its band: within :data:`_KIND_BAND` of a
multiple of ``f`` single-period, of an odd multiple of ``f/2``
double-period, elsewhere combination.

A strong instability saturates (the friction curve limits it) within a
tenth of a second, before the window's first filter settling time has
passed, and what follows creeps. Such a run is parametric judder when,
over the last third of the window, ``r`` keeps at least
:data:`SATURATED_SHARE` of its mean over the first third (it has not died
away) and of the component at ``f``, and is above the limit: a stable
run's free part has died out by then, or, beating against a lightly
damped mode near ``f``, is only ``2 sin(pi f_n/f)`` times a free
amplitude smaller than the forced one (0.19 for 103 Hz against 100 Hz),
and a lightly damped free mode that rings for seconds at a few rpm
is below the limit. The kind of a saturated judder, read from the
spectrum of ``d``, is unreliable: the motion is no longer near-linear.

Measured on emulated campaigns (``judder campaign``, the bench with its
bounded friction curve) against the Floquet exponent of the bench's
linearisation: over tongues 5, 2 and 6 at 1000 and 1500 rpm and four oil
temperatures (1736 runs), exponent > 1.25 1/s, 49 of 49 judder; exponent
< 0, 1 of 1397. Over tongue 4 (500 runs, 200-212 Hz x 0.05-1.0 bar):
exponent > 1.25 1/s, 155 of 156; below 0.75 1/s, 0 of 335
(docs/time-domain.md, docs/roundtrip.md). On tongues 1 and 2 the dither
forces a resonance that saturates the friction curve, and the verdicts
follow that nonlinear motion, not the exponent.
"""

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.signal
from scipy.interpolate import CubicSpline
from scipy.optimize import least_squares, minimize_scalar

from infra.criteria import (DEFAULT_JUDDER_LIMIT_RPM,
                            DEFAULT_MIN_GROWTH_PER_S, run_verdict)
from infra.errors import JudderError
from infra.spectrum import hann_amplitude, hann_spectrum
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .dither import disagreement, fit_sinusoid

__all__ = ["Component", "RunAnalysis", "analyse_run", "estimate_dither",
           "dither_estimate_dict", "SETTING", "engagement_window",
           "component_envelope", "component_phasor",
           "single_period_growth", "nonperiodic_part",
           "growth_phase", "rise_rate", "LINEAR_SHARE", "READ_SHARE",
           "MIN_AMPLITUDE_RPM",
           "MIN_GROWTH_PERIODS", "MIN_PHASE_S", "NOISE_FLOOR_RPM",
           "SATURATED_SHARE", "SLIP_SHARE", "GROWTH_SIGNIFICANCE",
           "REFERENCE_S", "PRESSURE_ON",
           "LONG_LAG_S", "SINGLE_PERIOD_BAND_HZ",
           "SMOOTHING_S"]

#: Share of its maximum a judder keeps after it (a beat of decaying modes
#: falls below it), and of its largest envelope a component keeps to be
#: sustained.
LINEAR_SHARE = 0.5
#: Share of its maximum up to which a growing component's rate is read
#: (:func:`growth_phase`): below it the rise is still near-linear, above
#: it the friction curve's limit bends it (a curve of +-0.04 around mu0
#: bends a judder from about a third of its saturated amplitude; below
#: 0.4 a pick-up's noise on the shorter rise costs more than the bend).
READ_SHARE = 0.4
#: Smallest judder component of the speed, rpm.
MIN_AMPLITUDE_RPM = 2.0
#: Smallest growing non-periodic part, rpm: above the noise of a pick-up.
NOISE_FLOOR_RPM = 1.0
#: Last share of the window whose spectrum names the other components.
LATE_SHARE = 2.0 / 3.0
#: Non-periodic part, relative to the component at ``f``, that marks a
#: saturated instability.
SATURATED_SHARE = 0.5
#: Lag of the non-periodic part read at the dither frequency, s (a whole
#: number of periods): long enough that a slow single-period judder shows
#: above a pick-up's noise, short against the window.
LONG_LAG_S = 0.1
#: Demodulation band of a single-period judder at f, Hz: it has the
#: dither's frequency exactly, while a combination response and the free
#: modes near f lie at f1 or more (18.9 Hz) and a few Hz away.
SINGLE_PERIOD_BAND_HZ = 5.0
#: Shortest growth phase called judder, s (and in dither periods below).
MIN_PHASE_S = 0.25
#: Shortest growth phase called judder, in dither periods.
MIN_GROWTH_PERIODS = 5
#: The clutch slips while the slip is above this share of its value as the
#: engagement begins (median over :data:`REFERENCE_S` from the pressure on).
SLIP_SHARE = 0.1
#: Time over which the slip as the engagement begins is taken, s.
REFERENCE_S = 0.1
#: The pressure is on above this share of its high level.
PRESSURE_ON = 0.9
#: Moving average applied to pressure and slip to find the window, s.
SMOOTHING_S = 0.05
#: Demodulation bandwidth: this share of the component frequency, at most
#: :data:`_MAX_BANDWIDTH_HZ`.
_BANDWIDTH_SHARE = 0.3
_MAX_BANDWIDTH_HZ = 20.0
#: Frequencies below this are the engagement itself, not judder, Hz.
_LOWEST_HZ = 5.0
#: A peak within this share of a multiple of f/2 counts as at it.
_KIND_BAND = 0.03
#: Kinds of judder by component (names of :data:`stability.kinds.KINDS`).
_KIND_OF = {"dither": "single-period", "half": "double-period",
            "other": "combination"}


@dataclass(frozen=True)
class Component:
    """One frequency component of the upstream speed in the window.

    Attributes
    ----------
    name : {'dither', 'half', 'other'}
        At ``f``, at ``f/2``, or the largest other peak.
    kind : str
        The judder it would be: single-period, double-period, combination.
    freq_hz : float
    amplitude_rpm : float
        Largest envelope in the window, rpm.
    sustained_rpm : float
        What the component keeps in the window, rpm: its largest
        envelope if it stays after it, else its median over the window's
        last third (a transient dies away).
    """

    name: str
    kind: str
    freq_hz: float
    amplitude_rpm: float
    sustained_rpm: float


@dataclass(frozen=True)
class RunAnalysis:
    """The reading of one engagement run.

    Attributes
    ----------
    window_s : (float, float)
        Engagement window, s.
    freq_hz, p_f_bar : float
        Dither setting used (given, or estimated from the pressure).
    estimated : bool
        True if the dither setting was estimated from the pressure.
    components : tuple of Component
    judder : bool
        The verdict (module docstring): the dither-related oscillation
        exceeds ``judder_limit_rpm`` or an instability grows at
        ``min_growth`` or faster.
    kind : str
        Kind of the parametric judder ('single-period', 'double-period',
        'combination'), 'forced' for a forced one alone, 'stable'
        without judder.
    growth_per_s : float or None
        Growth rate of the non-periodic part in its growth phase, 1/s
        (None when there is no growth phase of :data:`MIN_GROWTH_PERIODS`
        periods).
    growth_phase_s : (float, float) or None
    growth_std_per_s : float or None
        Standard uncertainty of ``growth_per_s``, 1/s
        (:func:`rise_rate`; NaN where it cannot be told).
    nonperiodic_rpm : float
        Largest non-periodic part ``r``, rpm.
    amplitude_rpm : float
        Largest envelope of the component at the dither frequency, or of
        the judder component if that is larger, rpm: what the chart
        contours (Fig. 10).
    oscillation_rpm : float
        The dither-related oscillation the verdict compares with the
        limit, rpm: the largest of the forced part at ``f`` (or the
        single-period judder there) and the sustained components at
        ``f/2`` and another frequency.
    forced_rpm : float
        The part of the oscillation at ``f`` the dither forces, rpm
        (without the single-period judder grown out of it).
    mechanism : {'parametric', 'forced', 'both'} or None
        Why the run judders (None without judder).
    judder_limit_rpm : float
        The NVH limit the oscillation was compared with, rpm.
    dither : pysim.bench.dither.SinusoidFit or None
        The sinusoid fitted to the pressure where the dither setting was
        estimated (amplitude in Pa, with standard uncertainties and the
        sampling's warnings, and a given value it contradicts), else None.
    given : tuple of str
        The values of the dither setting that were given, of
        ``('freq_hz', 'p_f_bar')``; the others were estimated.
    """

    window_s: tuple
    freq_hz: float
    p_f_bar: float
    estimated: bool
    components: tuple
    judder: bool
    kind: str
    growth_per_s: object
    growth_phase_s: object
    nonperiodic_rpm: float
    amplitude_rpm: float
    oscillation_rpm: float
    forced_rpm: float
    mechanism: object
    judder_limit_rpm: float
    dither: object = None
    given: tuple = ("freq_hz", "p_f_bar")
    growth_std_per_s: object = None

    @property
    def verdict(self):
        """The run's verdict word (:data:`infra.criteria.RUN_VERDICTS`):
        ``CANNOT TELL`` where :attr:`cannot_tell` says why."""
        return run_verdict(self.judder, told=self.cannot_tell is None)

    @property
    def cannot_tell(self):
        """Why the run's reading is no verdict, in words naming what to
        give; None where it is one.

        A dither frequency estimated from a pressure that cannot tell it
        from its aliases (:attr:`frequency_aliased`) leaves the speed read
        at frequencies the run may not have had: its components at ``f``
        and ``f/2``, its growth and its kind are those of a guess (a run
        growing to 39 rpm at 210 Hz read at its 17 Hz alias came out
        stable)."""
        if not self.frequency_aliased:
            return None
        others = ", ".join(f"{f:.4g}" for f in self.dither.aliases)
        return (f"the dither frequency, estimated from the pressure at "
                f"{self.freq_hz:.4g} Hz, cannot be told from its aliases"
                + (f" ({others} Hz)" if others else "")
                + " and no dither frequency was given; give it (a freq_hz "
                "column in the index, or the file's dither_frequency_hz "
                "metadata)")

    @property
    def frequency_aliased(self):
        """The dither frequency was estimated from the pressure, and the
        sampling cannot tell it from its aliases
        (:attr:`pysim.bench.dither.SinusoidFit.aliased`): the run may
        belong at another frequency."""
        return (SETTING[0] not in self.given and self.dither is not None
                and self.dither.aliased)

    def as_dict(self):
        """JSON fields (Hz, bar, rpm, 1/s); where the run cannot be told
        (:attr:`cannot_tell`, its words), ``judder``, ``kind`` and
        ``mechanism`` are None: no verdict."""
        told = self.cannot_tell is None
        return {"window_s": list(self.window_s), "freq_hz": self.freq_hz,
                "p_f_bar": self.p_f_bar,
                "dither_estimated": self.estimated,
                "judder": self.judder if told else None,
                "verdict": self.verdict, "cannot_tell": self.cannot_tell,
                "kind": self.kind if told else None,
                "growth_per_s": self.growth_per_s,
                "growth_std_per_s": self.growth_std_per_s,
                "growth_phase_s": None if self.growth_phase_s is None
                else list(self.growth_phase_s),
                "nonperiodic_rpm": self.nonperiodic_rpm,
                "amplitude_rpm": self.amplitude_rpm,
                "oscillation_rpm": self.oscillation_rpm,
                "forced_rpm": self.forced_rpm,
                "mechanism": self.mechanism if told else None,
                "judder_limit_rpm": self.judder_limit_rpm,
                "components": [c.__dict__ for c in self.components],
                "dither_estimate": dither_estimate_dict(self.dither,
                                                        self.given)}


#: The values of a dither setting, given or estimated.
SETTING = ("freq_hz", "p_f_bar")


def dither_estimate_dict(fit, given=()):
    """JSON fields of an estimated dither (Hz, bar, rad, s), None for
    none: which values of the setting were ``given`` and which
    ``estimated`` (of :data:`SETTING`), the pressure's values with their
    standard uncertainties (``*_std_*``; the frequency's NaN where it was
    given), the time the phase refers to, the sampling and its warnings,
    the aliases that fit as well (Hz) and ``frequency_aliased``: the
    frequency was estimated and may be an alias, so the run is on no
    boundary (:meth:`pysim.bench.charts.Chart.set_points`)."""
    if fit is None:
        return None
    return {"given": [name for name in SETTING if name in given],
            "estimated": [name for name in SETTING if name not in given],
            "freq_hz": fit.freq_hz, "freq_std_hz": fit.freq_std_hz,
            "p_f_bar": fit.amplitude / PA_PER_BAR,
            "p_f_std_bar": fit.amplitude_std / PA_PER_BAR,
            "phase_rad": fit.phase_rad, "phase_std_rad": fit.phase_std_rad,
            "phase_time_s": fit.reference_s,
            "samples_per_period": fit.samples_per_period,
            "periods": fit.periods, "warnings": list(fit.warnings),
            "aliases_hz": list(fit.aliases),
            "frequency_aliased": SETTING[0] not in given and fit.aliased}


def _uniform(time, values, rate=None):
    """A channel resampled linearly onto a uniform grid at its median
    rate."""
    time = np.asarray(time, dtype=float)
    rate = rate or 1.0 / np.median(np.diff(time))
    grid = np.arange(time[0], time[-1], 1.0 / rate)
    return grid, np.interp(grid, time, values)


def _angle(time, speed):
    """The angle a speed channel implies, as a cubic spline (rad).

    A pick-up gives at each tooth passage ``t_k`` the mean speed since the
    last one, so ``speed_k (t_k - t_{k-1})`` is exactly one tooth pitch and
    the summed angle is exact at the passages; between them the spline is
    accurate to fourth order. For uniformly sampled speeds this is a
    half-sample delay, the same every period.
    """
    time = np.asarray(time, dtype=float)
    angle = np.concatenate([[0.0], np.cumsum(speed[1:] * np.diff(time))])
    return CubicSpline(time, angle)


def _moving_average(values, samples):
    # at most the signal's length: np.convolve's 'same' would otherwise
    # return the kernel's length
    samples = min(max(int(samples), 1), len(values))
    return np.convolve(values, np.ones(samples) / samples, mode="same")


def _runs_of(mask):
    edges = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def engagement_window(speed, pressure=None, downstream=None):
    """The longest interval with the pressure on and the clutch slipping.

    Parameters
    ----------
    speed : (ndarray, ndarray)
        Time (s) and upstream speed (rad/s).
    pressure, downstream : (ndarray, ndarray), optional
        Time and actuation pressure (Pa); time and downstream speed
        (rad/s).

    Returns
    -------
    (float, float)
        Start and end of the window, s.

    Raises
    ------
    JudderError
        If no part of the run has the pressure on and the clutch slipping.
    """
    t, w = _uniform(*speed)
    width = SMOOTHING_S / (t[1] - t[0])
    on = np.ones(len(t), dtype=bool)
    if pressure is not None:
        p = _moving_average(np.interp(t, *pressure), width)
        on &= p > PRESSURE_ON * np.percentile(p, 95)
    if downstream is not None:
        slip = np.abs(_moving_average(w - np.interp(t, *downstream), width))
        # the slip as the engagement begins, not its largest value: a
        # judder that runs away (the upstream speed swinging by many
        # times the slip) would otherwise leave only its last part
        pressed = np.flatnonzero(on)
        first = pressed[t[pressed] <= t[pressed[0]] + REFERENCE_S] \
            if len(pressed) else np.arange(len(t))
        reference = np.nanmedian(slip[first]) if np.isfinite(
            slip[first]).any() else np.nanmax(slip)
        on &= slip > SLIP_SHARE * reference
    runs = _runs_of(on)
    if not runs:
        raise JudderError("no engagement window: the pressure is never on "
                          "while the clutch slips")
    start, stop = max(runs, key=lambda r: t[r[1] - 1] - t[r[0]])
    return float(t[start]), float(t[stop - 1])


def estimate_dither(time, pressure, window, freq_hz=None):
    """Dither frequency, amplitude and phase, with their standard
    uncertainties, from the pressure channel.

    The least-squares sinusoid (over a line, the engagement's trend) is
    fitted to the pressure samples in ``window`` as they were taken
    (:func:`pysim.bench.dither.fit_sinusoid`). Resampling them first
    would not do: a pressure sampled at a pick-up's tooth passages has
    about 3.3 samples per dither period, and linear interpolation between
    them loses 7 to 36 % of the amplitude (issue 31). The frequency,
    unless given, is the spectral peak above 5 Hz of the pressure
    resampled uniformly (only to find the peak), refined within one bin
    to the frequency whose sinusoid fits best (then fitted with the
    others, with its uncertainty).

    Parameters
    ----------
    time, pressure : ndarray
        The pressure channel, s and Pa.
    window : (float, float)
        The engagement window, s.
    freq_hz : float, optional
        The dither frequency when it is known: the amplitude is fitted at
        it.

    Returns
    -------
    pysim.bench.dither.SinusoidFit
        Amplitude in Pa; ``warnings`` where the sampling cannot support
        the estimate.

    Raises
    ------
    JudderError
        If the window holds fewer than 16 pressure samples.
    """
    keep = (time >= window[0]) & (time <= window[1])
    if np.count_nonzero(keep) < 16:
        raise JudderError("too few pressure samples in the engagement "
                          "window to estimate the dither")
    time, pressure = time[keep], pressure[keep]
    if freq_hz is not None:
        return fit_sinusoid(time, pressure, freq_hz)
    t, p = _uniform(time, pressure)
    p = scipy.signal.detrend(p)
    freq, spectrum = hann_spectrum(p, t[1] - t[0])
    band = freq >= _LOWEST_HZ
    peak = freq[band][np.argmax(spectrum[band])]
    return fit_sinusoid(time, pressure, peak,
                        bracket_hz=(peak - freq[1], peak + freq[1]))


def _given_frequency_contradicted(pressure, window, freq_hz):
    """Words where the pressure's own frequency (:func:`estimate_dither`
    with the frequency free) contradicts the one given
    (:func:`pysim.bench.dither.disagreement`); None where they agree,
    or where the sampling cannot tell the frequency from its aliases (the
    estimate's own warnings)."""
    own = estimate_dither(np.asarray(pressure[0], dtype=float),
                          np.asarray(pressure[1], dtype=float), window)
    if own.warnings:
        return None
    return disagreement("frequency", freq_hz, own.freq_hz, own.freq_std_hz,
                        "Hz")


def _bandwidth(freq_hz):
    return np.minimum(_BANDWIDTH_SHARE * freq_hz, _MAX_BANDWIDTH_HZ)


def component_phasor(time, values, freq_hz, bandwidth_hz=None):
    """Complex amplitude of the component at ``freq_hz`` over time, by
    complex demodulation: ``2 LP[y e^{-2 pi i f t}]`` (a Butterworth low
    pass of :func:`_bandwidth`, forwards and backwards).

    Parameters
    ----------
    time, values : ndarray
        Uniform samples.
    freq_hz : float
    bandwidth_hz : float, optional
        Of the low pass (default :func:`_bandwidth`).

    Returns
    -------
    ndarray, complex
        In the unit of ``values``.
    """
    fs = 1.0 / (time[1] - time[0])
    sos = scipy.signal.butter(4, bandwidth_hz or _bandwidth(freq_hz), fs=fs,
                              output="sos")
    base = values * np.exp(-2j * np.pi * freq_hz * time)
    return 2 * (scipy.signal.sosfiltfilt(sos, base.real)
                + 1j * scipy.signal.sosfiltfilt(sos, base.imag))


def component_envelope(time, values, freq_hz, bandwidth_hz=None):
    """Envelope ``|component_phasor|`` of the component at ``freq_hz``."""
    return np.abs(component_phasor(time, values, freq_hz, bandwidth_hz))


def single_period_growth(time, phasor):
    """Growth rate of a single-period judder over a forced response.

    A single-period Floquet response has the dither's frequency exactly
    (a real multiplier), so the speed's phasor at ``f`` is
    ``z(t) = P + A e^{g t}``: the forced response ``P`` and the growing
    judder. ``g`` minimises the least-squares residual of that model
    (``P``, ``A`` complex, linear for each ``g``); a forced response still
    building up fits a negative ``g``.

    Returns
    -------
    rate : float
        ``g``, 1/s.
    judder : ndarray, complex
        ``A e^{g t}`` at ``time``.
    """
    tau = time - time[0]

    def fitted(rate):
        basis = np.column_stack([np.ones_like(tau), np.exp(rate * tau)])
        coef, *_ = np.linalg.lstsq(basis.astype(complex), phasor,
                                   rcond=None)
        return coef, float(np.sum(np.abs(basis @ coef - phasor) ** 2))
    span = max(tau[-1], 1e-9)
    rates = np.linspace(-20.0 / span, 20.0 / span, 161)
    errors = [fitted(r)[1] for r in rates]
    best = int(np.argmin(errors))
    found = minimize_scalar(lambda r: fitted(r)[1], bracket=(
        rates[max(best - 1, 0)], rates[best],
        rates[min(best + 1, len(rates) - 1)])) if 0 < best < len(rates) - 1 \
        else None
    rate = float(found.x) if found is not None and found.success \
        else float(rates[best])
    coef, _ = fitted(rate)
    return rate, coef[1] * np.exp(rate * tau)


def nonperiodic_part(angle, time, period):
    """The non-periodic part, from the angle: ``theta(t + T) - theta(t)``.

    Its derivative is ``d(t) = w(t + T) - w(t)``, but the angle is known to
    fourth order between pick-up samples and its derivative only to third:
    a 100 Hz oscillation gets about seven samples a period, at phases that
    drift against the dither, and the error of a differentiated spline
    (several % of the oscillation) would itself look non-periodic. The
    mean speed times ``T`` is removed by a 5 Hz high-pass.

    Parameters
    ----------
    angle : callable
        Angle (rad) at any time, e.g. :func:`_angle`.
    time : ndarray
        Uniform times, s.
    period : float
        Dither period ``T``, s.

    Returns
    -------
    t, difference : ndarray
        Times where ``t + T`` is still inside ``time``, and
        ``theta(t + T) - theta(t)`` high-passed, rad. A component of it at
        ``f_c`` is ``2 pi f_c`` times that component of ``d``.
    """
    t = time[time + period <= time[-1]]
    fs = 1.0 / (time[1] - time[0])
    difference = scipy.signal.sosfiltfilt(scipy.signal.butter(
        2, _LOWEST_HZ, btype="highpass", fs=fs, output="sos"),
        angle(t + period) - angle(t))
    return t, difference


def _speed_rms(difference, freq_hz, fs):
    """RMS over two periods of the non-periodic part, in rpm, taking it
    to be at ``freq_hz``."""
    return (2 * np.pi * freq_hz * RPM_PER_RAD_S
            * np.sqrt(_moving_average(difference ** 2, 2 * fs / freq_hz)))


def growth_phase(time, rms):
    """Growth phase of the non-periodic part and its rate.

    The rate is read while the component grows as the linearisation
    says: from the lowest value before the maximum up to where it last
    rises through :data:`READ_SHARE` of the maximum, before the
    nonlinear limit bends the rise (the friction curve's slope falls as
    the slip swings wider), when that part spans at least one e-fold;
    else over its first e-fold (a judder that saturates gradually bends
    before it), or up to the maximum where it never grows by one.

    The rate is that of an exponential over a floor fitted to the rise
    (:func:`rise_rate`): the noise a pick-up, an integer export's
    rounding or a decaying transient leaves under the judder bends the
    log of the envelope at the start of the rise, and a straight line
    through it read a run growing at 4.9 1/s at 3.47 1/s (4.7 1/s once
    its speeds were rounded to 0.1 rpm: issue 44).

    Returns
    -------
    (start, stop) : (float, float)
        The part of the rise the rate is read over, s.
    rate : float
        Growth rate over it, 1/s (:func:`rise_rate`).
    peak : float
        Time of the maximum, s.
    rate_std : float
        Standard uncertainty of ``rate``, 1/s.

    Returns None when the maximum comes first.
    """
    top = int(np.argmax(rms))
    low = int(np.argmin(rms[:top + 1]))
    if top - low < 4 or rms[low] <= 0:
        return None
    # where it last rises through the share (noise makes early spikes)
    below = np.flatnonzero(rms[low:top + 1] < READ_SHARE * rms[top])
    end = low + int(below[-1]) + 1 if below.size else top
    if end - low < 4 or rms[end] < np.e * rms[low]:
        # less than an e-fold to the share: read the first e-fold (a
        # saturating growth bends early), or up to the maximum
        efold = np.flatnonzero(rms[low:top + 1] >= np.e * rms[low])
        end = low + int(efold[0]) if efold.size else top
        if end - low < 4:
            end = top
    rate, rate_std = rise_rate(time[low:end + 1], rms[low:end + 1])
    return (float(time[low]), float(time[end])), rate, float(time[top]), \
        rate_std


#: The floor under a rise is at most this many e-folds below its end:
#: the exponential carries at least its last e-fold (a floor as high as
#: the end would leave a rate fitted to the last few samples alone).
_FLOOR_EFOLDS_BELOW_END = 1.0


def rise_rate(time, envelope):
    r"""Growth rate of a rising envelope over the floor under it, with
    its standard uncertainty.

    The envelope is taken as a growth over a floor that adds in power
    (noise, the rounding of an integer export, a transient's remains),

    .. math:: \ln r(t) = \tfrac12 \ln\left(c^2 + a^2 e^{2 g (t -
              t_1)}\right),

    fitted in the log by least squares (``g``, ``ln a``, ``ln c``; the
    floor at least :data:`_FLOOR_EFOLDS_BELOW_END` e-fold below the end).
    A floor can only flatten the start of the rise, so ``g`` is at least
    the straight line's log-slope, which it is where there is no floor.

    The uncertainty is the Gauss-Newton one, ``s^2 (J^T J)^{-1}``, times
    the residuals' integrated autocorrelation time in samples (the
    envelope is a smoothed signal: its samples are not independent), so
    it counts the rise's independent stretches, not its samples.

    Parameters
    ----------
    time, envelope : ndarray
        The rise, s and any unit (> 0).

    Returns
    -------
    rate, rate_std : float
        1/s.
    """
    time = np.asarray(time, dtype=float)
    y = np.log(np.asarray(envelope, dtype=float))
    tau = time - time[-1]
    line = np.polyfit(tau, y, 1)
    slope = float(line[0])

    def residual(p):
        g, log_a, log_c = p
        return 0.5 * np.logaddexp(2 * log_c, 2 * (log_a + g * tau)) - y
    span = max(float(-tau[0]), 1e-12)
    top_c = y[-1] - _FLOOR_EFOLDS_BELOW_END
    lower = [slope, y[-1] - 10.0, y.min() - 30.0]
    upper = [max(10 * abs(slope) + 10 / span, slope + 1e-6), y[-1] + 10.0,
             top_c]
    start = np.clip([slope, y[-1], min(y.min(), top_c) - 1e-3], lower,
                    upper)
    try:
        fit = least_squares(residual, start, bounds=(lower, upper),
                            x_scale=[1 / span, 1.0, 1.0])
        rate, res, jac = float(fit.x[0]), fit.fun, fit.jac
    except (ValueError, np.linalg.LinAlgError):
        rate, res = slope, np.polyval(line, tau) - y
        jac = np.column_stack([tau, np.ones_like(tau)])
    dof = len(y) - jac.shape[1]
    if dof <= 0:
        return rate, float("nan")
    variance = float(res @ res) / dof * _correlation_time(res)
    try:
        cov = variance * np.linalg.pinv(jac.T @ jac)
    except np.linalg.LinAlgError:
        return rate, float("nan")
    return rate, float(np.sqrt(max(cov[0, 0], 0.0)))


def _correlation_time(residual):
    """Integrated autocorrelation time of a residual, in samples:
    ``1 + 2 sum rho_k`` up to the first negative ``rho_k`` (at least 1)."""
    r = residual - residual.mean()
    power = float(r @ r)
    if power <= 0:
        return 1.0
    rho = np.correlate(r, r, mode="full")[len(r) - 1:] / power
    negative = np.flatnonzero(rho < 0)
    stop = int(negative[0]) if negative.size else len(rho)
    return max(1.0, 1.0 + 2.0 * float(rho[1:stop].sum()))


def _other_peak(freq, spectrum, dither_hz, resolution):
    """Largest peak between 5 Hz and f/2, farther than 1.5 demodulation
    bandwidths (and three frequency bins) from 0 and f/2.

    A combination multiplier ``e^{i theta}`` puts the response at
    ``theta/(2 pi T) + k f`` for every ``k``, so one of its frequencies
    always lies below ``f/2`` (tongue 6 at f1 + f2: f1; tongue 5 at
    f2 - f1: f1 too).
    """
    half = dither_hz / 2
    distance = np.minimum(freq, half - freq)
    away = (freq >= _LOWEST_HZ) & (freq < half) & (distance > np.maximum(
        3 * resolution, 1.5 * _bandwidth(freq)))
    if not np.any(away):
        return None
    return float(freq[away][np.argmax(spectrum[away])])


def _difference_spectrum(difference, fs):
    """Spectrum of the non-periodic part in speed terms (the angle
    difference's spectrum times the frequency)."""
    freq, spectrum = hann_spectrum(difference, 1.0 / fs)
    return freq, spectrum * freq


def _dominant(freq, spectrum, dither_hz, centre=None):
    """Which of f, f/2 and the other frequencies holds the largest peak of
    a spectrum (within the demodulation band of ``centre`` if given):
    within :data:`_KIND_BAND` of a multiple of ``f`` is 'dither', of an
    odd multiple of ``f/2`` 'half', elsewhere (above 5 Hz) 'other'."""
    band = freq >= _LOWEST_HZ
    if centre is not None:
        band &= np.abs(freq - centre) <= max(_bandwidth(centre), 2 * freq[1])
    peak = freq[band][np.argmax(spectrum[band])]
    half = dither_hz / 2
    multiple = int(np.round(peak / half))
    if multiple == 0 or abs(peak - multiple * half) > max(
            _KIND_BAND * peak, 3 * freq[1]):
        return "other"
    return "dither" if multiple % 2 == 0 else "half"


def _growing_components(time, difference, freq_hz, min_growth,
                        envelope_of, phasor_of, min_amplitude_rpm,
                        long_difference):
    """Components of the non-periodic part that grow as judder does.

    The difference ``y(t + T) - y(t)`` is demodulated at ``f/2`` and the
    two largest other peaks of its spectrum over the last
    :data:`LATE_SHARE` of the window, so that a growing component is not
    hidden by a larger decaying one (the engagement transient). At ``f``
    the difference over :data:`LONG_LAG_S` (a whole number of periods,
    ``long_difference``: times, difference, lag) is demodulated instead:
    a single-period judder grows by ``exp(g T) - 1`` per period (1.5 % at
    1.5 1/s and 100 Hz), below a pick-up's noise, and by ``exp(g L) - 1``
    over the lag ``L`` (16 % over 0.1 s), while the forced response still
    cancels.

    ``envelope_of(fc)`` and ``phasor_of(fc)`` are the envelope and
    phasor of the speed itself at ``fc`` (rpm, at ``time``); the largest
    envelope must reach ``min_amplitude_rpm``. A single-period growth
    found in the long difference is measured on the speed's phasor
    (:func:`single_period_growth`), which a pick-up's noise disturbs far
    less than a difference.

    The band around ``f`` is also read as the others are (the
    difference over one period, the wide band): a combination response
    near ``f`` (at ``f2`` for tongue 6) grows there.

    Returns
    -------
    list of (rate, (start, stop), largest speed envelope in rpm,
    frequency, kind name or None, the rate's standard uncertainty)
    """
    fs = 1.0 / (time[1] - time[0])
    late = time >= time[-1] - LATE_SHARE * (time[-1] - time[0])
    freq, spectrum = _difference_spectrum(difference[late], fs)
    # (frequency, how it is read, the kind it names: None from the
    # spectrum of the non-periodic part)
    targets = [(freq_hz, "single", "dither"), (freq_hz, "near", None),
               (freq_hz / 2, "period", "half")]
    for _ in range(2):
        other = _other_peak(freq, spectrum, freq_hz, freq[1])
        if other is None:
            break
        targets.append((other, "period", None))
        spectrum = np.where(np.abs(freq - other) <= _bandwidth(other), 0.0,
                            spectrum)
    found = []
    for fc, reading, hint in targets:
        t, d, lag = (long_difference if reading == "single"
                     else (time, difference, 1.0 / freq_hz))
        guard = 1.0 / float(_bandwidth(fc))
        read = (t >= t[0] + guard) & (t <= t[-1] - guard)
        if fc >= 0.45 * fs or np.count_nonzero(read) < 8:
            continue
        band = SINGLE_PERIOD_BAND_HZ if reading == "single" else None
        envelope = (component_envelope(t, d, fc, band)[read]
                    * 2 * np.pi * fc * RPM_PER_RAD_S)
        speed = envelope_of(fc)[:len(t)][read]
        if reading == "single":
            phase = _single_period_phase(t[read], envelope, freq_hz,
                                         min_growth, speed,
                                         phasor_of(fc)[:len(t)][read])
        else:
            phase = _judder_phase(t[read], envelope, freq_hz, min_growth,
                                  component_hz=fc, speed_envelope=speed,
                                  lag=lag)
        if phase is not None and speed.max() >= min_amplitude_rpm:
            rate, span, rate_std = phase
            found.append((rate, span, float(speed.max()), fc, hint,
                          rate_std))
    return found


def _difference_gain(rate, component_hz, lag):
    """How much larger the non-periodic part ``y(t + L) - y(t)`` of a
    component at ``component_hz`` growing at ``rate`` is than the
    component itself: ``|exp((rate + 2 pi i f_c) L) - 1|``. A single-period
    component (``f_c = f``, ``L = T``) gives ``exp(rate T) - 1`` (0.015 at
    1.5 1/s and 100 Hz), a double-period one about 2."""
    return abs(np.exp((rate + 2j * np.pi * component_hz) * lag) - 1.0)


def _single_period_phase(time, envelope, freq_hz, min_growth, speed,
                         phasor):
    """``(rate, (start, stop), rate_std)`` of a single-period judder, or
    None (``rate_std``: :func:`_phasor_rate_std`).

    Where the long difference's envelope rises (:func:`growth_phase`),
    the rate is fitted to the speed's phasor from the window's start to
    the end of that rise (:func:`single_period_growth`); it counts as
    judder as :func:`_judder_phase` says, the e-folds and the floor being
    those of the fitted judder itself.
    """
    phase = growth_phase(time, envelope)
    if phase is None:
        return None
    (_, stop), _, peak, _ = phase
    rise = time <= stop
    if np.count_nonzero(rise) < 8:
        return None
    rate, judder = single_period_growth(time[rise], phasor[rise])
    size = np.abs(judder)
    if not np.all(np.isfinite(size)) or size[0] <= 0:
        return None
    start = float(time[0])
    efolds = np.log(size[-1] / size[0])
    after = time >= peak
    grown = np.median(speed[after])
    stays = grown >= LINEAR_SHARE * speed[after].max() and \
        grown >= np.e * size[0]
    if stop - start >= MIN_GROWTH_PERIODS / freq_hz \
            and (stop - start >= MIN_PHASE_S or efolds >= 2.0) \
            and size[-1] >= NOISE_FLOOR_RPM and rate >= min_growth \
            and efolds >= 1.0 and stays:
        rate_std = _phasor_rate_std(time[rise], phasor[rise], rate)
        if _significant(rate, rate_std):
            return rate, (start, float(stop)), rate_std
    return None


#: A growth counts only where its rate is this many standard
#: uncertainties above zero: a rate read to 18 +- 11 1/s over the last
#: 0.1 s of a window, at 2 rpm (a run 0.08 bar below the tongue of its
#: campaign, issue 44), is none the reading can tell from noise.
GROWTH_SIGNIFICANCE = 2.0


def _significant(rate, rate_std):
    """Whether a growth rate is told from none: ``rate`` at least
    :data:`GROWTH_SIGNIFICANCE` standard uncertainties above zero (an
    uncertainty that cannot be told, NaN, does not refuse it)."""
    return not rate_std > rate / GROWTH_SIGNIFICANCE


def _phasor_rate_std(time, phasor, rate):
    """Standard uncertainty of the rate :func:`single_period_growth`
    fitted (1/s): from the curvature of its sum of squares at the
    minimum, ``2 s^2 / E''(g)``, with ``s^2`` the residual variance per
    real value times the residuals' correlation time in samples
    (:func:`_correlation_time`; the phasor is low-passed)."""
    tau = time - time[0]

    def error(g):
        basis = np.column_stack([np.ones_like(tau), np.exp(g * tau)])
        coef, *_ = np.linalg.lstsq(basis.astype(complex), phasor,
                                   rcond=None)
        return basis @ coef - phasor
    res = error(rate)
    dof = 2 * len(tau) - 5
    if dof <= 0:
        return float("nan")
    total = float(np.sum(np.abs(res) ** 2))
    step = max(1e-3 * abs(rate), 1e-3 / max(tau[-1], 1e-9))
    curvature = (float(np.sum(np.abs(error(rate + step)) ** 2))
                 - 2 * total + float(np.sum(np.abs(error(rate - step)) ** 2))
                 ) / step ** 2
    if curvature <= 0:
        return float("nan")
    variance = total / dof * _correlation_time(res.real)
    return float(np.sqrt(2 * variance / curvature))


def _judder_phase(time, envelope, freq_hz, min_growth, component_hz=None,
                  speed_envelope=None, lag=None):
    """``(rate, (start, stop), rate_std)`` of a growth phase that counts
    as judder (the rate and its uncertainty of :func:`growth_phase`):
    its linear part (:func:`growth_phase`) :data:`MIN_GROWTH_PERIODS`
    periods long, at least ``min_growth`` over at least one e-fold to the
    maximum (and two, or a linear part of :data:`MIN_PHASE_S`: noise makes
    short rises), up to at least :data:`NOISE_FLOOR_RPM` of the speed
    (pick-up noise), and staying, after its maximum, above
    :data:`LINEAR_SHARE` of it in the median (a beat of decaying modes
    dies away); else None.

    ``envelope`` is that of the non-periodic part at ``component_hz``
    over the lag ``lag`` (default ``T``; ``component_hz`` None: of the
    whole non-periodic part, taken as it is); its speed equivalent is
    ``envelope`` over :func:`_difference_gain`, so that a
    single-period judder, whose non-periodic part is only ``exp(rate T) -
    1`` times its amplitude, is held to the same floor as the others.
    ``speed_envelope``, the speed's own component at the same times, tells
    a judder that saturated (periodic again, its non-periodic part gone,
    the speed's component grown and staying) from a beat that died."""
    phase = growth_phase(time, envelope)
    if phase is None:
        return None
    (start, stop), rate, peak, rate_std = phase
    gain = (1.0 if component_hz is None else max(_difference_gain(
        rate, component_hz, lag or 1.0 / freq_hz), 1e-12))
    # e-folds at that rate up to the maximum (a rise that bent after half
    # its maximum still counts them); the linear part must be long
    efolds = rate * (peak - start)
    # judder stays once grown (it saturates); a beat of decaying free
    # modes rises from a null and dies away again
    after = time >= peak
    stays = np.median(envelope[after]) >= LINEAR_SHARE * envelope.max()
    if not stays and speed_envelope is not None:
        # a single-period judder that saturates becomes periodic with the
        # dither, so its non-periodic part falls back: the speed's own
        # component stays, having grown by an e-fold from the phase start
        first = speed_envelope[np.searchsorted(time, start)]
        grown = np.median(speed_envelope[after])
        stays = grown >= np.e * first and \
            grown >= LINEAR_SHARE * speed_envelope[after].max()
    if stop - start >= MIN_GROWTH_PERIODS / freq_hz \
            and (stop - start >= MIN_PHASE_S or efolds >= 2.0) \
            and envelope.max() / gain >= NOISE_FLOOR_RPM \
            and rate >= min_growth and efolds >= 1.0 and stays \
            and _significant(rate, rate_std):
        return rate, (start, stop), rate_std
    return None


def _check_length(time):
    """Refuse a run shorter than the settling of the 5 Hz high-pass at
    both ends of its window (no judder can be read in it): a few samples,
    or a time column in another unit than its header says."""
    least = 1.0 / _LOWEST_HZ
    lasts = float(time[-1] - time[0]) if len(time) else 0.0
    if len(time) < 2 or lasts < least:
        raise JudderError(
            f"the run lasts {lasts:.3g} s ({len(time)} samples of the "
            f"upstream speed); allowed: an engagement of at least "
            f"{least:g} s (check the time column's unit)")


def analyse_run(speed, pressure=None, downstream=None, freq_hz=None,
                p_f_bar=None, min_growth=DEFAULT_MIN_GROWTH_PER_S,
                min_amplitude_rpm=MIN_AMPLITUDE_RPM,
                judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM):
    """Read one engagement run: window, dither, components, verdict.

    Parameters
    ----------
    speed : (ndarray, ndarray)
        Time (s) and upstream speed (rad/s), any sampling.
    pressure : (ndarray, ndarray), optional
        Time (s) and actuation pressure (Pa); needed when the dither
        setting is not given.
    downstream : (ndarray, ndarray), optional
        Time (s) and downstream speed (rad/s).
    freq_hz, p_f_bar : float, optional
        Dither setting; estimated from the pressure where None.
    min_growth : float
        1/s; see the module docstring.
    min_amplitude_rpm : float
        Smallest growing component counted as an instability, rpm.
    judder_limit_rpm : float
        NVH limit of the dither-related oscillation, rpm.

    Returns
    -------
    RunAnalysis
    """
    t_speed, w = (np.asarray(a, dtype=float) for a in speed)
    _check_length(t_speed)
    window = engagement_window((t_speed, w), pressure, downstream)
    dither = None
    given = tuple(name for name, value in zip(SETTING, (freq_hz, p_f_bar))
                  if value is not None)
    if freq_hz is None or p_f_bar is None:
        if pressure is None:
            missing = [column for column, value in
                       (("freq_hz", freq_hz), ("p_f_bar", p_f_bar))
                       if value is None]
            raise JudderError(
                "the dither setting is not given and there is no pressure "
                "channel to estimate it from; give "
                + " and ".join(missing) + " (columns of the index, or the "
                "file's dither_frequency_hz and dither_amplitude_bar "
                "metadata) or the pressure channel (`channels` "
                "pressure=NAME)")
        dither = estimate_dither(np.asarray(pressure[0], dtype=float),
                                 np.asarray(pressure[1], dtype=float),
                                 window, freq_hz)
        if p_f_bar is None:
            p_f_bar = dither.amplitude / PA_PER_BAR
            contradicted = None if freq_hz is None else \
                _given_frequency_contradicted(pressure, window, freq_hz)
        else:
            contradicted = disagreement(
                "amplitude", p_f_bar, dither.amplitude / PA_PER_BAR,
                dither.amplitude_std / PA_PER_BAR, "bar")
        freq_hz = dither.freq_hz if freq_hz is None else freq_hz
        if contradicted:
            dither = dataclasses.replace(
                dither, warnings=dither.warnings + (contradicted,))
    angle = _angle(t_speed, w)
    t = np.arange(t_speed[0], t_speed[-1], np.median(np.diff(t_speed)))
    y = angle(t, 1) * RPM_PER_RAD_S
    fs = 1.0 / (t[1] - t[0])
    if freq_hz >= 0.45 * fs:
        raise JudderError(f"the speed is sampled at {fs:.0f} samples/s, too "
                          f"slow for judder at {freq_hz:g} Hz")
    y = scipy.signal.sosfiltfilt(scipy.signal.butter(
        2, _LOWEST_HZ, btype="highpass", fs=fs, output="sos"), y)
    period = 1.0 / freq_hz
    # settling of the demodulation and of the 5 Hz high-pass
    guard = max(1.0 / float(_bandwidth(freq_hz / 2)), 0.5 / _LOWEST_HZ)
    inside = (t >= window[0] + guard) & (t <= window[1] - guard)
    if np.count_nonzero(inside) < 32 or \
            window[1] - window[0] - 2 * guard < MIN_GROWTH_PERIODS * period:
        raise JudderError(f"the engagement window {window[0]:.3g}-"
                          f"{window[1]:.3g} s is too short to read judder at "
                          f"{freq_hz:g} Hz")
    freq, spectrum = hann_spectrum(y[inside], 1.0 / fs)
    targets = {"dither": freq_hz, "half": freq_hz / 2,
               "other": _other_peak(freq, spectrum, freq_hz, freq[1])}
    envelopes = {fc: component_envelope(t, y, fc) for fc in targets.values()
                 if fc is not None and fc < 0.45 * fs}
    components = tuple(
        Component(name=name, kind=_KIND_OF[name], freq_hz=float(fc),
                  amplitude_rpm=float(envelopes[fc][inside].max()),
                  sustained_rpm=_sustained(t[inside], envelopes[fc][inside]))
        for name, fc in targets.items() if fc in envelopes)
    t_all, difference = nonperiodic_part(angle, t, period)
    read = inside[:len(t_all)]
    t_r, difference = t_all[read], difference[read]
    rms = _speed_rms(difference, freq_hz, fs)

    def envelope_of(fc):
        """The speed's envelope at ``fc`` over the window (rpm)."""
        return (envelopes[fc] if fc in envelopes
                else component_envelope(t, y, fc))[inside]

    def phasor_of(fc):
        """The speed's phasor at ``fc`` over the window (rpm), in the
        narrow band of a single-period judder."""
        return component_phasor(t, y, fc, SINGLE_PERIOD_BAND_HZ)[inside]
    lag = max(1, round(LONG_LAG_S * freq_hz)) * period
    t_long, long_difference = nonperiodic_part(angle, t, lag)
    inside_long = inside[:len(t_long)]
    growing = _growing_components(
        t_r, difference, freq_hz, min_growth, envelope_of, phasor_of,
        min_amplitude_rpm, (t_long[inside_long],
                            long_difference[inside_long], lag))
    whole = _judder_phase(t_r, rms, freq_hz, min_growth)
    if not growing and whole is not None and \
            max(c.amplitude_rpm for c in components) >= min_amplitude_rpm:
        growing = [(whole[0], whole[1], float(rms.max()), None, None,
                    whole[2])]
    growth = phase = during = centre = hint = growth_std = None
    if growing:
        growth, phase, _, centre, hint, growth_std = max(
            growing, key=lambda g: g[2])
        during = (t_r >= phase[0]) & (t_r <= phase[1])
    else:
        by_kind = {c.kind: c for c in components}
        third = (t_r[-1] - t_r[0]) / 3
        last = t_r >= t_r[-1] - third
        late = float(rms[last].mean())
        early = float(rms[t_r <= t_r[0] + third].mean())
        # saturated: it has not died away, it is not the beat of a forced
        # resonance, and it is above the limit (a lightly damped free
        # mode rings for seconds at a few rpm; an instability that
        # stays below the limit must show its growth to count)
        if late >= SATURATED_SHARE * early and late >= max(
                SATURATED_SHARE * by_kind["single-period"].amplitude_rpm,
                min_amplitude_rpm, judder_limit_rpm):
            during = last
    # a component at f or f/2 is of its own kind; elsewhere the spectrum
    # of the non-periodic part tells
    unstable = ("stable" if during is None else _KIND_OF[hint or _dominant(
        *_difference_spectrum(difference[during], fs), freq_hz, centre)])
    forced_rpm = _forced_level(t[inside], y[inside], freq_hz, unstable,
                               phase, envelope_of(freq_hz))
    mechanism, kind = _mechanism(components, unstable, forced_rpm,
                                 judder_limit_rpm)
    # the oscillation the verdict compared with the limit: at f the
    # narrow-band forced part (a combination response or a free mode
    # near f lies in the wide band), or the single-period judder grown
    at_f = next(c.sustained_rpm for c in components if c.name == "dither")
    oscillation = max([at_f if unstable == "single-period" else forced_rpm]
                      + [c.sustained_rpm for c in components
                         if c.name != "dither"])
    if growth is None and oscillation <= judder_limit_rpm:
        # judder exactly when the oscillation exceeds the limit or a
        # growth is read: a saturated instability below the limit is not
        mechanism, kind = None, "stable"
    lead = max((c for c in components
                if c.kind in (kind, "single-period")),
               key=lambda c: c.amplitude_rpm)
    return RunAnalysis(window_s=window, freq_hz=float(freq_hz),
                       p_f_bar=float(p_f_bar), estimated=dither is not None,
                       components=components, judder=mechanism is not None,
                       kind=kind, growth_per_s=growth,
                       growth_std_per_s=growth_std, growth_phase_s=phase,
                       nonperiodic_rpm=float(rms.max()),
                       amplitude_rpm=lead.amplitude_rpm,
                       oscillation_rpm=oscillation, forced_rpm=forced_rpm,
                       mechanism=mechanism,
                       judder_limit_rpm=float(judder_limit_rpm),
                       dither=dither, given=given)


def _sustained(time, envelope):
    """What a component keeps in the window, rpm: its largest envelope if
    it stays after it (median above :data:`LINEAR_SHARE` of it: a forced
    response, a judder grown and saturated), else its median over the
    last third of the window (a transient that dies away is not judder)."""
    top = int(np.argmax(envelope))
    if np.median(envelope[top:]) >= LINEAR_SHARE * envelope[top]:
        return float(envelope[top])
    return float(np.median(envelope[time >= time[-1] - (time[-1] - time[0])
                                    / 3]))


def _forced_level(time, speed, freq_hz, unstable, phase, dither_envelope):
    """The oscillation at ``f`` that the dither forces, rpm.

    Where no single-period instability grows, the Fourier amplitude of
    the speed at exactly ``f`` over the window's last third (a Hann
    window: its band of about ``4/T`` keeps out a combination response
    at ``f2`` near ``f``); where one does, the envelope at ``f`` as the
    growth begins (the rest is the judder grown out of it); a
    single-period instability saturated before the window leaves no
    forced level to read (0).
    """
    if unstable != "single-period":
        late = time >= time[-1] - (time[-1] - time[0]) / 3
        return float(hann_amplitude(time[late], speed[late], freq_hz)[0])
    if phase is None:
        return 0.0
    return float(dither_envelope[np.searchsorted(time, phase[0])])


def _mechanism(components, unstable, forced_rpm, limit_rpm):
    """``(mechanism, kind)`` of a run (module docstring, "The verdict").

    Parametric: an instability grows (``unstable`` names its kind), or a
    component at ``f/2`` or at another frequency exceeds ``limit_rpm``
    (a sub-harmonic or combination oscillation the dither cannot force);
    forced: the oscillation at ``f`` the dither forces exceeds
    ``limit_rpm``. ``mechanism`` is None without judder; ``kind`` is the
    parametric kind, ``'forced'``, or ``'stable'``.
    """
    if unstable == "stable":
        beyond = [c for c in components if c.name != "dither"
                  and c.sustained_rpm > limit_rpm]
        if beyond:
            unstable = max(beyond, key=lambda c: c.sustained_rpm).kind
    forced = forced_rpm > limit_rpm
    if unstable != "stable":
        return ("both" if forced else "parametric"), unstable
    return ("forced", "forced") if forced else (None, "stable")

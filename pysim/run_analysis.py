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
   in the window, refined to the frequency that maximises the windowed
   Fourier sum (:func:`estimate_dither`); the amplitude is that sum's.
3. **Components** of the upstream speed, resampled uniformly over the
   whole run and high-passed above 5 Hz (the engagement itself is
   slower), by complex demodulation,
   :math:`e(t) = 2|\mathrm{LP}[y(t) e^{-2\pi i f_c t}]|`: at the dither
   frequency ``f``, at ``f/2`` and at the largest other spectral peak
   below ``f/2`` (where every combination response has a frequency).
   Their largest envelopes are the amplitudes a chart contours (Fig. 10).

The verdict
-----------
Near a resonance the dither forces a large response at ``f`` (at 100 Hz,
0.3 bar the 103 Hz mode, damped 0.2 %, swings by hundreds of rpm), the
same frequency as single-period judder, so neither the amplitude nor the
frequency tells them apart. What does is periodicity: the forced response
repeats every dither period ``T``, the free response does not. So the
verdict reads the **non-periodic part** (as :func:`pysim.signals.
stroboscopic_growth` does for simulations),

.. math:: d(t) = y(t + T) - y(t), \qquad
          r(t) = \sqrt{\overline{d^2}}\ \text{(mean over two periods)}:

the forced response cancels, the engagement transient and the beating of
a forced resonance decay, and a parametric instability grows as its
Floquet multiplier says (a single-period one scaled by ``lambda - 1``, a
double-period one by 2). ``d`` is demodulated at ``f``, ``f/2`` and its
two largest other peaks, so that a small growing component is not hidden
by a larger decaying one. In each envelope (and in ``r``) the growth rate
is the least-squares log-slope from the lowest value before the maximum
up to where the envelope last rises through :data:`LINEAR_SHARE` of the
maximum (:func:`growth_phase`): the rise before the nonlinear limit (the
friction curve's flattening) bends it. A run has judder when some
component's linear rise lasts :data:`MIN_GROWTH_PERIODS` periods, grows at
``min_growth`` or more (default
:data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`, 1/s) over at least
one e-fold to the maximum (two if the rise is shorter than
:data:`MIN_PHASE_S`: noise makes short rises), reaches
:data:`NOISE_FLOOR_RPM` or more, and stays after its maximum (median
above :data:`LINEAR_SHARE` of it: a beat of decaying free modes rising
from a null dies away again), while the speed's own component there
reaches ``min_amplitude`` (default :data:`MIN_AMPLITUDE_RPM`). The
largest growing component gives the growth rate, and the peak of the
spectrum of ``d`` within its band over its growth phase the kind: within
:data:`_KIND_BAND` of a multiple of ``f`` single-period, of an odd
multiple of ``f/2`` double-period, elsewhere combination (a combination
response at ``f2 = 103 Hz`` lies within the band of ``f = 119.4 Hz``).

A strong instability saturates (the friction curve limits it) within a
tenth of a second, before the window's first filter settling
time has passed, and what follows creeps. Such a run also has judder when,
over the last third of the window, ``r`` keeps at least
:data:`SATURATED_SHARE` of its mean over the first third (it has not died
away) and of the component at ``f``: a stable run's free part has died out
by then, or, beating against a lightly damped mode near ``f``, is only
``2 sin(pi f_n/f)`` times a free amplitude smaller than the forced one
(0.19 for 103 Hz against 100 Hz). The kind of a saturated judder, read
from the spectrum of ``d``, is unreliable: the motion is no longer
near-linear.

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

from dataclasses import dataclass

import numpy as np
import scipy.signal
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar

from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
from infra.errors import JudderError
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

__all__ = ["Component", "RunAnalysis", "analyse_run", "estimate_dither",
           "engagement_window", "component_envelope", "nonperiodic_part",
           "growth_phase", "LINEAR_SHARE", "MIN_AMPLITUDE_RPM",
           "MIN_GROWTH_PERIODS", "MIN_PHASE_S", "NOISE_FLOOR_RPM",
           "SATURATED_SHARE", "SLIP_SHARE", "REFERENCE_S", "PRESSURE_ON",
           "SMOOTHING_S"]

#: Share of its maximum up to which a growing component's rate is read
#: (:func:`growth_phase`): the linear part of the rise.
LINEAR_SHARE = 0.5
#: Smallest judder component of the speed, rpm.
MIN_AMPLITUDE_RPM = 2.0
#: Smallest growing non-periodic part, rpm: above the noise of a pick-up.
NOISE_FLOOR_RPM = 1.0
#: Last share of the window whose spectrum names the other components.
LATE_SHARE = 2.0 / 3.0
#: Non-periodic part, relative to the component at ``f``, that marks a
#: saturated instability.
SATURATED_SHARE = 0.5
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
    """

    name: str
    kind: str
    freq_hz: float
    amplitude_rpm: float


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
        The verdict (module docstring).
    kind : str
        Kind of judder ('stable' without).
    growth_per_s : float or None
        Growth rate of the non-periodic part in its growth phase, 1/s
        (None when there is no growth phase of :data:`MIN_GROWTH_PERIODS`
        periods).
    growth_phase_s : (float, float) or None
    nonperiodic_rpm : float
        Largest non-periodic part ``r``, rpm.
    amplitude_rpm : float
        Largest envelope of the component at the dither frequency, or of
        the judder component if that is larger, rpm: what the chart
        contours (Fig. 10).
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

    def as_dict(self):
        """JSON fields (Hz, bar, rpm, 1/s)."""
        return {"window_s": list(self.window_s), "freq_hz": self.freq_hz,
                "p_f_bar": self.p_f_bar,
                "dither_estimated": self.estimated, "judder": self.judder,
                "kind": self.kind, "growth_per_s": self.growth_per_s,
                "growth_phase_s": None if self.growth_phase_s is None
                else list(self.growth_phase_s),
                "nonperiodic_rpm": self.nonperiodic_rpm,
                "amplitude_rpm": self.amplitude_rpm,
                "components": [c.__dict__ for c in self.components]}


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
    samples = max(int(samples), 1)
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


def _fourier_amplitude(time, values, freq):
    """Amplitude of a sine at ``freq`` (Hann-windowed Fourier sum)."""
    window = np.hanning(len(values))
    phasor = np.exp(-2j * np.pi * freq * time)
    return 2 * abs(np.sum(window * values * phasor)) / window.sum()


def estimate_dither(time, pressure, window):
    """Dither frequency (Hz) and amplitude (Pa) from the pressure channel.

    The detrended pressure in ``window`` is resampled uniformly; the
    frequency is its spectral peak above 5 Hz, refined to the maximum of
    the windowed Fourier sum within one bin; the amplitude is that sum.

    Raises
    ------
    JudderError
        If the window holds fewer than 16 pressure samples.
    """
    keep = (time >= window[0]) & (time <= window[1])
    if np.count_nonzero(keep) < 16:
        raise JudderError("too few pressure samples in the engagement "
                          "window to estimate the dither")
    t, p = _uniform(time[keep], pressure[keep])
    p = scipy.signal.detrend(p)
    freq = np.fft.rfftfreq(len(p), t[1] - t[0])
    spectrum = np.abs(np.fft.rfft(p * np.hanning(len(p))))
    band = freq >= _LOWEST_HZ
    peak = freq[band][np.argmax(spectrum[band])]
    step = freq[1]
    best = minimize_scalar(lambda f: -_fourier_amplitude(t, p, f),
                           bounds=(peak - step, peak + step),
                           method="bounded",
                           options={"xatol": 1e-6 * peak})
    return float(best.x), float(-best.fun)


def _bandwidth(freq_hz):
    return np.minimum(_BANDWIDTH_SHARE * freq_hz, _MAX_BANDWIDTH_HZ)


def component_envelope(time, values, freq_hz):
    """Envelope of the component at ``freq_hz`` by complex demodulation.

    Parameters
    ----------
    time, values : ndarray
        Uniform samples.
    freq_hz : float

    Returns
    -------
    ndarray
        ``2 |LP[y e^{-2 pi i f t}]|``, in the unit of ``values``.
    """
    fs = 1.0 / (time[1] - time[0])
    sos = scipy.signal.butter(4, _bandwidth(freq_hz), fs=fs, output="sos")
    base = values * np.exp(-2j * np.pi * freq_hz * time)
    low = (scipy.signal.sosfiltfilt(sos, base.real)
           + 1j * scipy.signal.sosfiltfilt(sos, base.imag))
    return 2 * np.abs(low)


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
    rises through :data:`LINEAR_SHARE` of the maximum, before the
    nonlinear limit bends the rise (the friction curve's slope falls as
    the slip swings wider), when that part spans at least one e-fold;
    else up to the maximum.

    Returns
    -------
    (start, stop) : (float, float)
        The part of the rise the rate is read over, s.
    rate : float
        Least-squares log-slope over it, 1/s.
    peak : float
        Time of the maximum, s.

    Returns None when the maximum comes first.
    """
    top = int(np.argmax(rms))
    low = int(np.argmin(rms[:top + 1]))
    if top - low < 4 or rms[low] <= 0:
        return None
    # where it last rises through the share (noise makes early spikes)
    below = np.flatnonzero(rms[low:top + 1] < LINEAR_SHARE * rms[top])
    end = low + int(below[-1]) + 1 if below.size else top
    if end - low < 4 or rms[end] < np.e * rms[low]:
        end = top
    rate = float(np.polyfit(time[low:end + 1], np.log(rms[low:end + 1]),
                            1)[0])
    return (float(time[low]), float(time[end])), rate, float(time[top])


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


def _spectrum(values, fs):
    freq = np.fft.rfftfreq(len(values), 1.0 / fs)
    return freq, np.abs(np.fft.rfft(values * np.hanning(len(values))))


def _difference_spectrum(difference, fs):
    """Spectrum of the non-periodic part in speed terms (the angle
    difference's spectrum times the frequency)."""
    freq, spectrum = _spectrum(difference, fs)
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
                        amplitude_of, min_amplitude_rpm):
    """Components of the non-periodic part that grow as judder does.

    The difference ``y(t + T) - y(t)`` is demodulated at ``f``, ``f/2``
    and the two largest other peaks of its spectrum over the last
    :data:`LATE_SHARE` of the window, so that a growing component is not
    hidden by a larger decaying one (the engagement transient).

    ``amplitude_of(fc)`` is the envelope of the speed itself at ``fc``,
    which must reach ``min_amplitude_rpm`` (the difference of a
    single-period judder is only ``lambda - 1`` times it).

    Returns
    -------
    list of (rate, (start, stop), largest envelope in rpm, frequency)
    """
    fs = 1.0 / (time[1] - time[0])
    late = time >= time[-1] - LATE_SHARE * (time[-1] - time[0])
    freq, spectrum = _difference_spectrum(difference[late], fs)
    targets = [freq_hz, freq_hz / 2]
    for _ in range(2):
        other = _other_peak(freq, spectrum, freq_hz, freq[1])
        if other is None:
            break
        targets.append(other)
        spectrum = np.where(np.abs(freq - other) <= _bandwidth(other), 0.0,
                            spectrum)
    found = []
    for fc in targets:
        guard = 1.0 / float(_bandwidth(fc))
        read = (time >= time[0] + guard) & (time <= time[-1] - guard)
        if fc >= 0.45 * fs or np.count_nonzero(read) < 8:
            continue
        envelope = (component_envelope(time, difference, fc)[read]
                    * 2 * np.pi * fc * RPM_PER_RAD_S)
        phase = _judder_phase(time[read], envelope, freq_hz, min_growth)
        if phase is not None and amplitude_of(fc) >= min_amplitude_rpm:
            found.append((*phase, float(envelope.max()), fc))
    return found


def _judder_phase(time, envelope, freq_hz, min_growth):
    """``(rate, (start, stop))`` of a growth phase that counts as judder:
    its linear part (:func:`growth_phase`) :data:`MIN_GROWTH_PERIODS`
    periods long, at least ``min_growth`` over at least one e-fold to the
    maximum (and two, or a linear part of :data:`MIN_PHASE_S`: noise makes
    short rises), up to at least :data:`NOISE_FLOOR_RPM` (pick-up noise),
    and staying, after its maximum, above :data:`LINEAR_SHARE` of it in
    the median (a beat of decaying modes dies away); else None."""
    phase = growth_phase(time, envelope)
    if phase is None:
        return None
    (start, stop), rate, peak = phase
    # e-folds at that rate up to the maximum (a rise that bent after half
    # its maximum still counts them); the linear part must be long
    efolds = rate * (peak - start)
    # judder stays once grown (it saturates); a beat of decaying free
    # modes rises from a null and dies away again
    stays = np.median(envelope[time >= peak]) >= LINEAR_SHARE * envelope.max()
    if stop - start >= MIN_GROWTH_PERIODS / freq_hz \
            and (stop - start >= MIN_PHASE_S or efolds >= 2.0) \
            and envelope.max() >= NOISE_FLOOR_RPM \
            and rate >= min_growth and efolds >= 1.0 and stays:
        return rate, (start, stop)
    return None


def analyse_run(speed, pressure=None, downstream=None, freq_hz=None,
                p_f_bar=None, min_growth=DEFAULT_MIN_GROWTH_PER_S,
                min_amplitude_rpm=MIN_AMPLITUDE_RPM):
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

    Returns
    -------
    RunAnalysis
    """
    t_speed, w = (np.asarray(a, dtype=float) for a in speed)
    window = engagement_window((t_speed, w), pressure, downstream)
    estimated = False
    if freq_hz is None or p_f_bar is None:
        if pressure is None:
            raise JudderError("the dither setting is not given and there is "
                              "no pressure channel to estimate it from")
        f_est, p_est = estimate_dither(np.asarray(pressure[0], dtype=float),
                                       np.asarray(pressure[1], dtype=float),
                                       window)
        estimated = True
        freq_hz = f_est if freq_hz is None else freq_hz
        p_f_bar = p_est / PA_PER_BAR if p_f_bar is None else p_f_bar
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
    freq, spectrum = _spectrum(y[inside], fs)
    targets = {"dither": freq_hz, "half": freq_hz / 2,
               "other": _other_peak(freq, spectrum, freq_hz, freq[1])}
    components = tuple(
        Component(name=name, kind=_KIND_OF[name], freq_hz=float(fc),
                  amplitude_rpm=float(component_envelope(t, y, fc)[
                      inside].max()))
        for name, fc in targets.items()
        if fc is not None and fc < 0.45 * fs)
    t_all, difference = nonperiodic_part(angle, t, period)
    read = inside[:len(t_all)]
    t_r, difference = t_all[read], difference[read]
    rms = _speed_rms(difference, freq_hz, fs)
    def amplitude_of(fc):
        return float(component_envelope(t, y, fc)[inside].max())
    growing = _growing_components(t_r, difference, freq_hz, min_growth,
                                  amplitude_of, min_amplitude_rpm)
    whole = _judder_phase(t_r, rms, freq_hz, min_growth)
    if not growing and whole is not None and \
            max(c.amplitude_rpm for c in components) >= min_amplitude_rpm:
        growing = [(*whole, float(rms.max()), None)]
    growth = phase = during = centre = None
    if growing:
        growth, phase, _, centre = max(growing, key=lambda g: g[2])
        during = (t_r >= phase[0]) & (t_r <= phase[1])
    else:
        by_kind = {c.kind: c for c in components}
        third = (t_r[-1] - t_r[0]) / 3
        last = t_r >= t_r[-1] - third
        late = float(rms[last].mean())
        early = float(rms[t_r <= t_r[0] + third].mean())
        if late >= SATURATED_SHARE * early and late >= max(
                SATURATED_SHARE * by_kind["single-period"].amplitude_rpm,
                min_amplitude_rpm):
            during = last
    kind = ("stable" if during is None else _KIND_OF[_dominant(
        *_difference_spectrum(difference[during], fs), freq_hz, centre)])
    lead = max((c for c in components
                if c.kind in (kind, "single-period")),
               key=lambda c: c.amplitude_rpm)
    return RunAnalysis(window_s=window, freq_hz=float(freq_hz),
                       p_f_bar=float(p_f_bar), estimated=estimated,
                       components=components, judder=kind != "stable",
                       kind=kind, growth_per_s=growth, growth_phase_s=phase,
                       nonperiodic_rpm=float(rms.max()),
                       amplitude_rpm=lead.amplitude_rpm)

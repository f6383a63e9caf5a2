r"""The dither in a pressure channel: a least-squares sinusoid on the samples
as taken, with its standard uncertainties.

The actuation pressure of Eq. (4), :math:`p(t) = p_m + p_f \cos(\omega_p
t)`, is recorded over an engagement whose mean pressure moves, and often at
a pick-up's tooth passages (irregular, about 3.3 samples per period at
214 Hz). The model fitted to the samples :math:`(t_k, p_k)` as taken is

.. math:: p_k = a + b \tau_k + c \cos(2\pi f \tau_k) + d \sin(2\pi f \tau_k)
          + e_k, \qquad \tau_k = t_k - t_{ref},

a line (the engagement's trend) under the dither, with ``t_ref`` the
middle of the samples (so that the phase is uncorrelated with the
frequency). Its amplitude is :math:`A = \sqrt{c^2 + d^2}` and its phase
:math:`\varphi = \operatorname{atan2}(-d, c)` of :math:`A \cos(2\pi f
\tau + \varphi)`. With the frequency refined, :math:`(a, b, c, d, f)` is
one nonlinear least-squares problem; its covariance is the Gauss-Newton
one at the minimum, :math:`s^2 (J^T J)^{-1}` with the residual variance
:math:`s^2 = \mathrm{RSS}/(n - m)` (``m`` fitted values), and the
uncertainties of ``A`` and :math:`\varphi` follow from it to first order
(for white noise of variance :math:`\sigma^2` and many periods,
:math:`u(A) \approx \sigma \sqrt{2/n}`).

Sampling that cannot support the estimate is named in :attr:`SinusoidFit.
warnings`: aliases within the plausible dither frequencies
(:data:`DITHER_RANGE_HZ`, reaching up to :data:`ALIAS_REACH` times the
frequency found where that is higher, :func:`plausible_range`) that fit
as well as the frequency found,
``|f + k f_s|`` for the samples' mean rate ``f_s`` (all of them fit as
well where the samples are uniform and ``f_s`` is below twice the range's
top; irregular samples may tell some apart), and any other frequency of
that range that fits as well (irregular samples alias about no one
rate: a scan of the range, :func:`_scanned`), fewer than
:data:`MIN_SAMPLES_PER_PERIOD` samples per period at a frequency given,
fewer than :data:`MIN_PERIODS` periods, or an amplitude uncertain by more
than :data:`MAX_RELATIVE_UNCERTAINTY`. A value given for the dither that
the pressure's estimate contradicts is named by :func:`disagreement`.

Kernels only: arrays in, result objects out.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

__all__ = ["SinusoidFit", "fit_sinusoid", "disagreement",
           "MIN_SAMPLES_PER_PERIOD", "MIN_PERIODS", "MAX_RELATIVE_UNCERTAINTY",
           "ALIAS_SHARE", "DITHER_RANGE_HZ", "ALIAS_REACH",
           "plausible_range", "DISAGREEMENT_STDS", "DISAGREEMENT_SHARE"]

#: Fewer samples per dither period than this cannot tell the frequency
#: from its alias (the Nyquist limit of a uniform sampling).
MIN_SAMPLES_PER_PERIOD = 2.0
#: Fewer whole periods in the window than this leave the frequency and
#: the amplitude poorly determined.
MIN_PERIODS = 10.0
#: A relative standard uncertainty of the amplitude above this is warned
#: of (a chart point read to worse than 10 %).
MAX_RELATIVE_UNCERTAINTY = 0.10
#: An alias that explains more than this share of what the sinusoid found
#: explains (of the sum of squares about the line alone) fits as well:
#: the two cannot be told apart (nearly uniform samples explain an alias
#: all but exactly; a trend that is no line, or a dither that is no pure
#: sinusoid, makes a likelihood ratio of the two meaningless).
ALIAS_SHARE = 0.5
#: The dither frequencies a bench may run, Hz: from the verdict's 5 Hz
#: high-pass (below it is the engagement itself) to 250 Hz, above the
#: paper's valve range (60-200 Hz) and tongue 4 at twice f2 (about 206
#: Hz), as far as the report's stability map reaches. An alias of the
#: frequency found within it is a frequency the bench may have run.
DITHER_RANGE_HZ = (5.0, 250.0)
#: The plausible frequencies reach at least this many times the frequency
#: found (:func:`plausible_range`): with :data:`DITHER_RANGE_HZ` alone a
#: 471.4 Hz dither at 1000 samples/s (its alias 528.6 Hz) or at 700
#: samples/s (found at its alias 228.6 Hz) had no alias named. Uniform
#: samples at ``f_s`` put the first alias above ``f`` at ``f_s - f``,
#: within ``3 f`` exactly when there are fewer than 4 samples per period:
#: a sampling set for the pick-up or a CAN bus, not for the dither (a DAQ
#: set for it takes more, behind an anti-alias filter, and an alias ten
#: times the dither is none a valve runs).
ALIAS_REACH = 3.0
#: A value given for the dither contradicts the pressure's estimate when
#: they differ by more than this many standard uncertainties of the
#: estimate ...
DISAGREEMENT_STDS = 3.0
#: ... and by more than this share of the value given (a sinusoid over a
#: line reads a pressure that is no pure sinusoid a few % off: not a
#: wrong setting).
DISAGREEMENT_SHARE = 0.05


@dataclass(frozen=True)
class SinusoidFit:
    """A least-squares sinusoid over a line, with standard uncertainties.

    Attributes
    ----------
    freq_hz, freq_std_hz : float
        Frequency and its standard uncertainty, Hz (NaN when the frequency
        was given: it was not estimated).
    amplitude, amplitude_std : float
        Amplitude ``A`` and its standard uncertainty, in the unit of the
        values.
    phase_rad, phase_std_rad : float
        Phase of ``A cos(2 pi f (t - reference_s) + phase)``, rad in
        (-pi, pi], and its standard uncertainty.
    reference_s : float
        Time the phase refers to (the middle of the samples), s.
    residual_std : float
        Residual standard deviation ``s``, in the unit of the values.
    samples_per_period, periods : float
        Samples per period at ``freq_hz`` (their mean rate over it) and
        periods in the samples' span.
    warnings : tuple of str
        Why the sampling cannot support the estimate, in words (empty when
        it can); they speak of "the samples" and leave the channel to be
        named by the caller.
    aliases : tuple of float
        The aliases that fit the samples as well as ``freq_hz``, Hz (empty
        where the frequency was given: it was not sought).
    """

    freq_hz: float
    freq_std_hz: float
    amplitude: float
    amplitude_std: float
    phase_rad: float
    phase_std_rad: float
    reference_s: float
    residual_std: float
    samples_per_period: float
    periods: float
    warnings: tuple
    aliases: tuple = ()

    @property
    def aliased(self):
        """The frequency cannot be told from its aliases: some fit as
        well, or there are fewer than :data:`MIN_SAMPLES_PER_PERIOD`
        samples per period."""
        return bool(self.aliases) or \
            self.samples_per_period < MIN_SAMPLES_PER_PERIOD

    @property
    def relative_amplitude_std(self):
        """``amplitude_std / amplitude`` (inf for a zero amplitude)."""
        return (self.amplitude_std / self.amplitude if self.amplitude > 0
                else float("inf"))


def _basis(tau, freq_hz):
    """Columns ``1, tau, cos(2 pi f tau), sin(2 pi f tau)``."""
    phase = 2 * np.pi * freq_hz * tau
    return np.column_stack([np.ones_like(tau), tau, np.cos(phase),
                            np.sin(phase)])


def _linear(tau, values, freq_hz):
    """Coefficients ``(a, b, c, d)`` at a fixed frequency and the sum of
    squared residuals."""
    basis = _basis(tau, freq_hz)
    coef, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return coef, basis, float(np.sum((basis @ coef - values) ** 2))


def _covariance(jacobian, variance):
    """``variance (J^T J)^-1``, with the columns scaled to unit norm first
    (a frequency column is many orders larger than a constant one)."""
    scale = np.linalg.norm(jacobian, axis=0)
    scale[scale == 0] = 1.0
    _, sigma, vt = np.linalg.svd(jacobian / scale, full_matrices=False)
    inverse = (vt.T / sigma ** 2) @ vt
    return variance * inverse / np.outer(scale, scale)


def plausible_range(freq_hz, dither_range_hz=DITHER_RANGE_HZ):
    """The dither frequencies an alias of ``freq_hz`` (Hz, the frequency
    found) may be, Hz: ``dither_range_hz`` reaching up to
    :data:`ALIAS_REACH` times ``freq_hz`` where that is higher.

    Example
    -------
    >>> plausible_range(80.0), plausible_range(471.4)
    ((5.0, 250.0), (5.0, 1414.2))
    """
    low, high = dither_range_hz
    return low, max(high, round(ALIAS_REACH * freq_hz, 6))


def fit_sinusoid(time, values, freq_hz, bracket_hz=None,
                 dither_range_hz=DITHER_RANGE_HZ):
    r"""Least-squares sinusoid over a line, fitted to samples as taken.

    Parameters
    ----------
    time : ndarray, shape (n,)
        Sample times, s, increasing, any spacing (n > 5).
    values : ndarray, shape (n,)
        Samples (e.g. a pressure, Pa).
    freq_hz : float
        The frequency, Hz: fitted at it when ``bracket_hz`` is None, else
        the start of the search.
    bracket_hz : (float, float), optional
        Refine the frequency within this interval (the minimum of the sum
        of squares over it); the frequency is then a fitted value with its
        uncertainty.
    dither_range_hz : (float, float)
        The frequencies the dither may have, Hz: aliases of the frequency
        found within them, reaching up to :data:`ALIAS_REACH` times it
        (:func:`plausible_range`), are tried (:data:`DITHER_RANGE_HZ`).

    Returns
    -------
    SinusoidFit

    Example
    -------
    >>> t = np.sort(np.random.default_rng(0).uniform(0, 1, 700))
    >>> fit = fit_sinusoid(t, 3 + 2 * np.cos(2 * np.pi * 214 * t), 214.0)
    >>> round(fit.amplitude, 9), fit.warnings
    (2.0, ())
    """
    time = np.asarray(time, dtype=float)
    values = np.asarray(values, dtype=float)
    reference = 0.5 * (time[0] + time[-1])
    tau = time - reference
    if bracket_hz is not None:
        freq_hz = minimize_scalar(
            lambda f: _linear(tau, values, f)[2], bounds=bracket_hz,
            method="bounded", options={"xatol": 1e-6 * freq_hz}).x
    coef, jacobian, rss = _linear(tau, values, freq_hz)
    _, _, c, d = coef
    if bracket_hz is not None:
        phase = 2 * np.pi * freq_hz * tau
        derivative = 2 * np.pi * tau * (d * np.cos(phase) - c * np.sin(phase))
        jacobian = np.column_stack([jacobian, derivative])
    fitted = jacobian.shape[1]
    variance = rss / max(len(time) - fitted, 1)
    covariance = _covariance(jacobian, variance)
    amplitude = float(np.hypot(c, d))
    # first-order propagation to A = |c + i d| and phi = atan2(-d, c)
    # (a zero amplitude, no dither at all, has no phase: its direction is
    # taken along c)
    scale = amplitude if amplitude > 0 else 1.0
    grad_amplitude = np.array([c, d]) / scale if amplitude > 0 else \
        np.array([1.0, 0.0])
    grad_phase = np.array([d, -c]) / scale ** 2
    cd = covariance[2:4, 2:4]
    span = float(time[-1] - time[0])
    periods = span * freq_hz
    fit = SinusoidFit(
        freq_hz=float(freq_hz),
        freq_std_hz=(float(np.sqrt(covariance[4, 4])) if fitted == 5
                     else float("nan")),
        amplitude=amplitude,
        amplitude_std=float(np.sqrt(grad_amplitude @ cd @ grad_amplitude)),
        phase_rad=float(np.arctan2(-d, c)),
        phase_std_rad=float(np.sqrt(grad_phase @ cd @ grad_phase)),
        reference_s=float(reference), residual_std=float(np.sqrt(variance)),
        samples_per_period=(len(time) - 1) / periods, periods=periods,
        warnings=())
    dither_range_hz = plausible_range(fit.freq_hz, dither_range_hz)
    aliases = (_aliases(tau, values, fit, rss, dither_range_hz)
               if bracket_hz is not None else None)
    return SinusoidFit(**{**fit.__dict__, "aliases": tuple(aliases or ()),
                          "warnings": _warnings(
                              fit, aliases, _candidates(fit, dither_range_hz),
                              dither_range_hz)})


def _candidates(fit, dither_range_hz):
    """The aliases of the frequency fitted about the samples' mean rate
    ``f_s`` within ``dither_range_hz``: ``|f + k f_s|`` for every whole
    ``k`` but 0 (``f + k f_s`` and ``k f_s - f``), ascending."""
    rate = fit.samples_per_period * fit.freq_hz
    low, high = dither_range_hz
    reach = int(np.ceil((high + fit.freq_hz) / rate))
    found = {float(abs(fit.freq_hz + k * rate))
             for k in range(-reach, reach + 1) if k}
    return sorted(f for f in found if low <= f <= high
                  and abs(f - fit.freq_hz) > 1e-9 * fit.freq_hz)


def _aliases(tau, values, fit, rss, dither_range_hz):
    """The aliases of :func:`_candidates` that fit as well as the
    frequency found (:data:`ALIAS_SHARE`), each where it fits best.

    The mean rate of irregular samples is known only to about one
    frequency bin ``1/span``, so each alias is the best fit within two
    bins of its nominal frequency, on a grid of a quarter bin; one
    within three bins of the frequency found is that frequency.
    """
    span = tau[-1] - tau[0]
    line = np.column_stack([np.ones_like(tau), tau])
    about_line = float(np.sum((values - line @ np.linalg.lstsq(
        line, values, rcond=None)[0]) ** 2))
    found = []
    for nominal in _candidates(fit, dither_range_hz):
        if abs(nominal - fit.freq_hz) < 3.0 / span:
            continue
        grid = nominal + np.arange(-8, 9) / (4 * span)
        grid = grid[grid > 0]
        sums = [_linear(tau, values, f)[2] for f in grid]
        best = int(np.argmin(sums))
        if about_line - sums[best] > ALIAS_SHARE * (about_line - rss):
            found.append(float(grid[best]))
    # irregular samples alias about no one rate (a pressure kept at 350
    # samples/s off a pick-up's passages had its 210 Hz dither found at
    # 130.7 Hz, 4.7 Hz from the nominal alias of its mean rate): every
    # frequency of the plausible range that fits as well is one
    for other in _scanned(tau, values, dither_range_hz, span,
                          ALIAS_SHARE * (about_line - rss)):
        if abs(other - fit.freq_hz) >= 3.0 / span and all(
                abs(other - known) >= 2.0 / span for known in found):
            found.append(other)
    return sorted(found)


#: Frequencies a scan for aliases computes at once (bounds its memory).
_SCAN_CHUNK = 512


def _scanned(tau, values, dither_range_hz, span, least):
    """The frequencies of ``dither_range_hz``, on a grid of a third of a
    frequency bin ``1/span``, whose sinusoid over the line explains more
    than ``least`` of the samples' sum of squares about the line, at each
    local maximum of what it explains, Hz.

    With ``Q`` an orthonormal basis of the line, the cosine and sine
    less their parts along the line have the Gram entries ``sum cos^2 -
    |Q^T cos|^2`` (``sum sin^2 = n - sum cos^2``), ``sum cos sin - (Q^T
    cos).(Q^T sin)``, and the products ``cos . r``, ``sin . r`` with the
    samples' residual ``r`` about the line (orthogonal to it)."""
    q, _ = np.linalg.qr(np.column_stack([np.ones_like(tau), tau]))
    rest = values - q @ (q.T @ values)
    grid = np.arange(max(dither_range_hz[0], 1.0 / (3 * span)),
                     dither_range_hz[1], 1.0 / (3 * span))
    half = 0.5 * len(tau)
    explained = np.empty(len(grid))
    for start in range(0, len(grid), _SCAN_CHUNK):
        phase = 2 * np.pi * np.outer(grid[start:start + _SCAN_CHUNK], tau)
        cos, sin = np.cos(phase), np.sin(phase)
        cq, sq = cos @ q, sin @ q
        cc = np.einsum("ij,ij->i", cos, cos) - np.sum(cq ** 2, axis=1)
        dd = 2 * half - cc - np.sum(cq ** 2, axis=1) - np.sum(sq ** 2,
                                                               axis=1)
        cd = np.einsum("ij,ij->i", cos, sin) - np.sum(cq * sq, axis=1)
        a, b = cos @ rest, sin @ rest
        det = cc * dd - cd ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            explained[start:start + _SCAN_CHUNK] = np.where(
                det > 1e-12 * half ** 2,
                (dd * a ** 2 - 2 * cd * a * b + cc * b ** 2) / det, 0.0)
    peak = np.flatnonzero((explained[1:-1] >= explained[:-2])
                          & (explained[1:-1] >= explained[2:])
                          & (explained[1:-1] > least)) + 1
    return [float(grid[i]) for i in peak]


def _listing(freqs):
    """``62.59, 73.41 and 209.4 Hz``."""
    texts = [f"{f:.4g}" for f in freqs]
    return (", ".join(texts[:-1]) + " and " if len(texts) > 1 else "") \
        + texts[-1] + " Hz"


def _warnings(fit, aliases, candidates, dither_range_hz):
    """What the sampling cannot support, in words: ``aliases`` those of
    ``candidates`` (:func:`_candidates`) that fit as well as the frequency
    found (None where the frequency was given)."""
    warnings = []
    rate = fit.samples_per_period * fit.freq_hz
    if aliases:
        warnings.append(
            f"the sinusoids at {_listing(aliases)} fit the samples as well "
            f"as the one found at {fit.freq_hz:.4g} Hz: at the samples' "
            f"mean rate of {rate:.4g} samples/s they are its aliases (|f + k x "
            f"{rate:.4g} Hz|) within the plausible dither frequencies "
            f"{dither_range_hz[0]:g}-{dither_range_hz[1]:.4g} Hz, and the "
            "frequency cannot be told from its aliases; give the dither "
            "frequency (a freq_hz column in the index)")
    elif fit.samples_per_period < MIN_SAMPLES_PER_PERIOD:
        warnings.append(
            f"{fit.samples_per_period:.2g} samples per period at "
            f"{fit.freq_hz:.4g} Hz, fewer than "
            f"{MIN_SAMPLES_PER_PERIOD:g}: the frequency cannot be told from "
            + (f"its aliases at {_listing(candidates)}" if candidates else
               "its aliases")
            + ", and the amplitude read may be that of another component")
    if fit.periods < MIN_PERIODS:
        warnings.append(
            f"{fit.periods:.3g} periods at {fit.freq_hz:.4g} Hz in the "
            f"window, fewer than {MIN_PERIODS:g}: too few to read the "
            "frequency and the amplitude")
    if fit.amplitude == 0:
        warnings.append(f"no oscillation at {fit.freq_hz:.4g} Hz in the "
                        "samples (amplitude 0)")
    elif fit.relative_amplitude_std > MAX_RELATIVE_UNCERTAINTY:
        warnings.append(
            f"the amplitude is uncertain by {fit.relative_amplitude_std:.0%}"
            f" (standard uncertainty), more than "
            f"{MAX_RELATIVE_UNCERTAINTY:.0%}: the dither is not read well "
            "from these samples")
    return tuple(warnings)


def disagreement(quantity, given, estimate, std, unit):
    """Words when a value given for the dither and the pressure's estimate
    of it differ by more than :data:`DISAGREEMENT_STDS` standard
    uncertainties of the estimate and by more than
    :data:`DISAGREEMENT_SHARE` of the value given; else None.

    Parameters
    ----------
    quantity : str
        What the value is, in words (``'amplitude'``).
    given, estimate, std : float
        The value given, the estimate and its standard uncertainty, in
        ``unit``.
    unit : str

    Example
    -------
    >>> words = disagreement("amplitude", 0.6, 0.517, 0.0029, "bar")
    >>> words[words.index("differ"):words.index(":")]
    'differ by 14% (28.6 standard uncertainties)'
    >>> disagreement("amplitude", 0.6, 0.59, 0.0029, "bar") is None
    True
    """
    difference = abs(given - estimate)
    stds = difference / std if std > 0 else float("inf")
    if not (difference > DISAGREEMENT_SHARE * abs(given)
            and stds > DISAGREEMENT_STDS):
        return None
    how_many = f"{stds:.3g}" if stds < 1000 else "more than 1000"
    return (f"the {quantity} given, {given:.4g} {unit}, and the "
            f"pressure's, {estimate:.3g} ± {std:.2g} {unit} (standard "
            f"uncertainty), differ by {difference / abs(given):.0%} "
            f"({how_many} standard uncertainties): the run is read at the "
            f"{quantity} given; check that value, and the pressure channel "
            "and its unit")

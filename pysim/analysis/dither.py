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
warnings`: fewer than :data:`MIN_SAMPLES_PER_PERIOD` samples per period
(the frequency cannot be told from its alias), an alias that fits as well
as the frequency found, fewer than :data:`MIN_PERIODS` periods, or an
amplitude uncertain by more than :data:`MAX_RELATIVE_UNCERTAINTY`.

Kernels only: arrays in, result objects out.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

__all__ = ["SinusoidFit", "fit_sinusoid", "MIN_SAMPLES_PER_PERIOD", "MIN_PERIODS",
           "MAX_RELATIVE_UNCERTAINTY", "ALIAS_SHARE"]

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


@dataclass(frozen=True)
class SinusoidFit:
    """A least-squares sinusoid over a line, with standard uncertainties.

    Attributes
    ----------
    freq_hz, freq_std_hz : float
        Frequency and its standard uncertainty, Hz (0 when the frequency
        was given).
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


def fit_sinusoid(time, values, freq_hz, bracket_hz=None):
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
        freq_std_hz=float(np.sqrt(covariance[4, 4])) if fitted == 5 else 0.0,
        amplitude=amplitude,
        amplitude_std=float(np.sqrt(grad_amplitude @ cd @ grad_amplitude)),
        phase_rad=float(np.arctan2(-d, c)),
        phase_std_rad=float(np.sqrt(grad_phase @ cd @ grad_phase)),
        reference_s=float(reference), residual_std=float(np.sqrt(variance)),
        samples_per_period=(len(time) - 1) / periods, periods=periods,
        warnings=())
    alias = _alias(tau, values, fit, rss) if bracket_hz is not None \
        else None
    return SinusoidFit(**{**fit.__dict__,
                          "warnings": _warnings(fit, alias)})


def _alias(tau, values, fit, rss):
    """The alias of the frequency found about the samples' mean rate, if
    it fits as well (:data:`ALIAS_SHARE`), else None.

    The mean rate of irregular samples is known only to about one
    frequency bin ``1/span``, so the alias is the best fit within two
    bins of ``rate - f``, on a grid of a quarter bin.
    """
    span = tau[-1] - tau[0]
    rate = fit.samples_per_period * fit.freq_hz
    nominal = abs(rate - fit.freq_hz)
    if abs(nominal - fit.freq_hz) < 3.0 / span:
        return None
    candidates = nominal + np.arange(-8, 9) / (4 * span)
    sums = [_linear(tau, values, f)[2] for f in candidates[candidates > 0]]
    best = int(np.argmin(sums))
    line = np.column_stack([np.ones_like(tau), tau])
    about_line = float(np.sum((values - line @ np.linalg.lstsq(
        line, values, rcond=None)[0]) ** 2))
    if about_line - sums[best] > ALIAS_SHARE * (about_line - rss):
        return float(candidates[candidates > 0][best])
    return None


def _warnings(fit, alias):
    """What the sampling cannot support, in words."""
    warnings = []
    if fit.samples_per_period < MIN_SAMPLES_PER_PERIOD:
        warnings.append(
            f"{fit.samples_per_period:.2g} samples per period at "
            f"{fit.freq_hz:.4g} Hz, fewer than "
            f"{MIN_SAMPLES_PER_PERIOD:g}: the frequency cannot be told from "
            f"its alias at {abs(fit.samples_per_period - 1) * fit.freq_hz:.4g}"
            " Hz, and the amplitude read may be that of another component")
    elif alias is not None:
        warnings.append(
            f"the sinusoid at {alias:.4g} Hz (the alias of {fit.freq_hz:.4g} "
            f"Hz at {fit.samples_per_period:.2g} samples per period) fits "
            "the samples as well: the frequency cannot be told from its "
            "alias")
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

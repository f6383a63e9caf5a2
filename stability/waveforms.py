r"""Dither waveforms beyond the paper's cosine (section 2.1).

The paper's Eq. (4) writes the dither as :math:`p_f\cos(\omega t)`; the
solenoid is in fact driven by a square wave that the valve filters. A
waveform here is the periodic shape :math:`c(\omega t)` of the dither per
unit amplitude, so the system is

.. math:: \dot z = \bigl(A_0 + p_f\, c(\omega t)\, U V^T\bigr) z.

Each waveform gives its values along a period (for the Dyson engine, which
integrates them exactly between the instants where the shape has a kink,
``breakpoints`` per period) and its complex Fourier coefficients
:math:`c_n` (for Hill's method, where the harmonic :math:`c_n` couples
:math:`w_k` and :math:`w_{k-n}`):

* :class:`Cosine`: ``cos(theta)``, Eq. (4), the default;
* :class:`FilteredSquare`: a square wave of amplitude 1 through the
  first-order lag ``tau`` of the valve (``tau = 0``: the square wave);
* :class:`FourierSeries`: ``sum_n a_n cos(n theta) + b_n sin(n theta)``;
* :func:`from_samples`: one measured period of pressure (bench data),
  as the trigonometric interpolant of its samples.

A system carries its waveform (``waveform`` attribute, None for the
cosine); :func:`with_waveform` sets it and :class:`Dithered` sets it on
every system a driveline gives, so maps, tongues and sensitivity studies
run unchanged.
"""

from dataclasses import dataclass, replace

import numpy as np

from infra.errors import JudderError

__all__ = ["Cosine", "FilteredSquare", "FourierSeries", "from_samples",
           "with_waveform", "waveform_of", "Dithered"]


class Cosine:
    """``c(theta) = cos(theta)``: the paper's Eq. (4)."""

    breakpoints = 1
    name = "cosine"

    def values(self, theta, freq_hz):
        """Shape at the phases ``theta`` (rad)."""
        return np.cos(theta)

    def coefficients(self, n_max, freq_hz):
        """``c_n`` for ``n = 0 .. n_max`` (``c_-n`` is the conjugate)."""
        c = np.zeros(n_max + 1, dtype=complex)
        c[1] = 0.5
        return c


@dataclass(frozen=True)
class FilteredSquare:
    r"""Square wave of amplitude 1 through a first-order lag.

    The valve's command is +1 for :math:`|\theta| < \pi/2` and -1 in the
    other half period (in phase with the cosine); the pressure follows it
    through :math:`\tau \dot y = u - y`. The periodic steady state is, over
    each half period :math:`H = T/2` from its switching instant,

    .. math:: y = \pm\bigl(1 - (1 + Y) e^{-s/\tau}\bigr), \qquad
              Y = \tanh\frac{H}{2\tau},

    and its Fourier coefficients are those of the square wave,
    :math:`\frac{2}{\pi n}(-1)^{(n-1)/2}` for odd ``n``, divided by
    :math:`1 + i n \omega \tau`: the harmonic ``3 f`` has a third of the
    fundamental's amplitude before the lag.

    Attributes
    ----------
    tau : float
        Time constant of the valve, s (>= 0).
    """

    tau: float = 0.0
    breakpoints = 4
    name = "square"
    #: Harmonics Hill's method keeps: the coefficients decay as 1/n^2
    #: (1/n without the lag); 48 put the boundary multipliers within
    #: 1e-12 of the unit circle (12: 1e-10).
    hill_harmonics = 48

    def __post_init__(self):
        if not np.isfinite(self.tau) or self.tau < 0:
            raise JudderError(f"tau = {self.tau!r} s is not allowed; "
                              "allowed: a valve time constant >= 0 s")

    def values(self, theta, freq_hz):
        theta = np.mod(np.asarray(theta, dtype=float) + np.pi / 2, 2 * np.pi)
        sign = np.where(theta < np.pi, 1.0, -1.0)
        if self.tau == 0:
            return sign
        s = np.mod(theta, np.pi) / (2 * np.pi * freq_hz)
        half = 0.5 / freq_hz
        level = np.tanh(half / (2 * self.tau))
        return sign * (1 - (1 + level) * np.exp(-s / self.tau))

    def coefficients(self, n_max, freq_hz):
        n = np.arange(n_max + 1)
        c = np.zeros(n_max + 1, dtype=complex)
        odd = n % 2 == 1
        c[odd] = 2 / (np.pi * n[odd]) * (-1.0) ** ((n[odd] - 1) // 2)
        return c / (1 + 1j * n * 2 * np.pi * freq_hz * self.tau)


@dataclass(frozen=True)
class FourierSeries:
    """``c(theta) = sum_n a_n cos(n theta) + b_n sin(n theta)``, n = 1..N.

    Attributes
    ----------
    cos, sin : tuple of float
        ``a_1 .. a_N`` and ``b_1 .. b_N`` (the shorter is padded with 0).
    """

    cos: tuple = (1.0,)
    sin: tuple = ()
    breakpoints = 1
    name = "fourier"

    @property
    def hill_harmonics(self):
        """Harmonics Hill's method keeps: 12 beyond the series' own."""
        return 12 + max(len(self.cos), len(self.sin))

    def __post_init__(self):
        a = np.asarray(self.cos, dtype=float)
        b = np.asarray(self.sin, dtype=float)
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))) or \
                max(a.size, b.size) == 0:
            raise JudderError("a Fourier series needs finite coefficients; "
                              f"got cos = {self.cos!r}, sin = {self.sin!r}")

    def _ab(self):
        size = max(len(self.cos), len(self.sin))
        a, b = np.zeros(size), np.zeros(size)
        a[:len(self.cos)], b[:len(self.sin)] = self.cos, self.sin
        return a, b

    def values(self, theta, freq_hz):
        a, b = self._ab()
        n = np.arange(1, len(a) + 1)
        theta = np.asarray(theta, dtype=float)[..., None]
        return (a * np.cos(n * theta) + b * np.sin(n * theta)).sum(axis=-1)

    def coefficients(self, n_max, freq_hz):
        a, b = self._ab()
        c = np.zeros(n_max + 1, dtype=complex)
        count = min(len(a), n_max)
        c[1:count + 1] = (a[:count] - 1j * b[:count]) / 2
        return c


def from_samples(samples, amplitude=None):
    """The waveform of one measured period of pressure.

    Parameters
    ----------
    samples : array_like, shape (N,)
        Pressure at ``N`` equally spaced instants of one dither period
        (from the start of the period), any unit.
    amplitude : float, optional
        The unit amplitude: the waveform is ``(p - mean) / amplitude``, so
        ``p_f`` of a map is the dither amplitude in that unit. Default
        the amplitude of the fundamental, so that ``p_f`` is comparable
        with the paper's cosine amplitude.

    Returns
    -------
    FourierSeries
        The trigonometric interpolant of the samples (mean removed: it
        belongs to ``p_m``), with its phase kept.
    """
    p = np.asarray(samples, dtype=float)
    if p.ndim != 1 or p.size < 4 or not np.all(np.isfinite(p)):
        finite = int(np.sum(np.isfinite(p))) if p.ndim == 1 else 0
        raise JudderError("a measured period needs at least 4 finite "
                          f"samples; got {p.size}, {finite} of them finite")
    spectrum = np.fft.rfft(p) / p.size
    top = (p.size - 1) // 2          # harmonics below the Nyquist one
    c = spectrum[1:top + 1]
    scale = 2 * abs(c[0]) if amplitude is None else float(amplitude)
    if not np.isfinite(scale) or scale <= 0:
        if amplitude is None:
            raise JudderError("the measured period has no fundamental (its "
                              "first harmonic is 0, e.g. a constant); "
                              "allowed: a period with a fundamental")
        raise JudderError(f"amplitude = {scale:g} is not allowed; allowed: "
                          "> 0 (and a period with a fundamental)")
    return FourierSeries(cos=tuple(2 * c.real / scale),
                         sin=tuple(-2 * c.imag / scale))


def waveform_of(system):
    """The waveform of a system (:class:`Cosine` when it has none)."""
    return getattr(system, "waveform", None) or Cosine()


def with_waveform(system, waveform):
    """A copy of ``system`` (any of stability.model's) dithered by
    ``waveform``."""
    return replace(system, waveform=waveform)


@dataclass(frozen=True)
class Dithered:
    """A model source whose dither has another waveform.

    Implements :class:`stability.source.ModelSource` over ``driveline``
    (any model source): every system it gives (reduced, full, augmented)
    carries ``waveform``, so every form, engine and study takes it.

    Attributes
    ----------
    driveline : stability.source.ModelSource
    waveform : object
        One of this module's waveforms.

    Examples
    --------
    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> d = Dithered(build_driveline(get_preset("paper-4dof")),
    ...              FilteredSquare(0.0))
    >>> d.full_system().waveform.name
    'square'
    """

    driveline: object
    waveform: object

    @property
    def name(self):
        """The name of ``driveline``."""
        return self.driveline.name

    @property
    def kind(self):
        """The :class:`~sources.kinds.SourceKind` of ``driveline``."""
        return self.driveline.kind

    def periodic_system(self):
        """The reduced system of ``driveline`` with ``waveform``."""
        return with_waveform(self.driveline.periodic_system(), self.waveform)

    def full_system(self):
        """The full system of ``driveline`` with ``waveform``."""
        return with_waveform(self.driveline.full_system(), self.waveform)

    def augmented_system(self):
        """The augmented system of ``driveline``, its full system with
        ``waveform``."""
        augmented = self.driveline.augmented_system()
        return replace(augmented,
                       state=with_waveform(augmented.state, self.waveform))

    def undamped_omega2(self):
        """``w^2`` of ``driveline``'s undamped modes, (rad/s)^2."""
        return self.driveline.undamped_omega2()

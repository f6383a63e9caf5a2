"""Stability maps over dither frequency and amplitude (Fig. 12, Fig. 14)."""

from dataclasses import dataclass

import numpy as np

from .multipliers import leading_multipliers
from .kinds import KINDS, classify
from .modal import natural_frequencies
from .monodromy import DEFAULT_METHOD, get_method

__all__ = ["StabilityMap", "stability_map"]


@dataclass(frozen=True)
class StabilityMap:
    """Leading Floquet multiplier on a frequency x amplitude grid.

    Attributes
    ----------
    freq_hz : ndarray, shape (nf,)
        Dither frequencies, Hz.
    p_f : ndarray, shape (np,)
        Dither amplitudes, Pa.
    leading : ndarray of complex, shape (nf, np)
        Leading non-trivial multiplier (rigid-body angles removed).
    kind : ndarray of int8, shape (nf, np)
        :class:`~stability.kinds.Kind` code of each point.
    natural_frequencies_hz : ndarray
        Undamped natural frequencies of the driveline, Hz (Eq. 15).
    method : str
        Monodromy engine used.
    """

    freq_hz: np.ndarray
    p_f: np.ndarray
    leading: np.ndarray
    kind: np.ndarray
    natural_frequencies_hz: np.ndarray
    method: str

    @property
    def leading_abs(self):
        """``|leading|``, shape (nf, np)."""
        return np.abs(self.leading)

    @property
    def growth_rate(self):
        """``ln|leading| / T``, 1/s, shape (nf, np); > 0 is unstable."""
        return np.log(self.leading_abs) * self.freq_hz[:, None]

    def counts(self):
        """Number of grid points of each kind, as ``{name: count}``."""
        return {name: int(np.count_nonzero(self.kind == code))
                for code, name in enumerate(KINDS)}

    def resonances(self):
        """Frequencies the tongues grow from, numbered as in Fig. 14:
        ``[(number, label, hz, kind code)]``
        (:func:`stability.tongues.resonances`)."""
        from .tongues import resonances
        return resonances(self.natural_frequencies_hz)

    def plot(self, ax=None, **kwargs):
        """Draw the map; see :func:`stability.plots.plot_map`."""
        from .plots import plot_map
        return plot_map(self, ax=ax, **kwargs)


def stability_map(driveline, freq_hz, p_f, method=DEFAULT_METHOD,
                  callback=None):
    """Floquet stability map of Eq. (6) on a grid.

    Parameters
    ----------
    driveline : stability.source.ModelSource
    freq_hz : array_like, shape (nf,)
        Dither frequencies, Hz (> 0).
    p_f : array_like, shape (np,)
        Dither amplitudes, Pa (>= 0).
    method : str
        Monodromy engine, a key of :data:`stability.monodromy.METHODS`.
    callback : callable, optional
        Called as ``callback(done, total)`` after each frequency, for
        progress display. Interrupt (``KeyboardInterrupt``) at any time:
        nothing is written by this function.

    Returns
    -------
    StabilityMap

    Examples
    --------
    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> m = stability_map(build_driveline(get_preset("paper-4dof")),
    ...                   [37.9, 60.0, 102.9], [0.0, 0.5e5])
    >>> [[str(KINDS[k]) for k in row] for row in m.kind]
    [['stable', 'double-period'], ['stable', 'stable'], ['stable', 'single-period']]
    """
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
    engine = get_method(method)
    system = driveline.periodic_system()
    p_max = np.abs(p_f).max()
    leading = np.empty((len(freq_hz), len(p_f)), dtype=complex)
    for index, freq in enumerate(freq_hz):
        _, leading[index] = leading_multipliers(
            engine(system, freq, p_max).monodromy(p_f))
        if callback is not None:
            callback(index + 1, len(freq_hz))
    return StabilityMap(freq_hz=freq_hz, p_f=p_f, leading=leading,
                        kind=classify(leading),
                        natural_frequencies_hz=natural_frequencies(driveline),
                        method=method)

"""The envelope in the manner of Fig. 16: probability of instability
shaded over (frequency, amplitude), the broadest region's edge, the
nominal boundary.

Functions take an ``ax`` (a new figure is made when it is None), return the
artists they drew and never call ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.units import PA_PER_BAR

__all__ = ["plot_envelope", "envelope_figure"]


def plot_envelope(envelope, ax=None):
    """Probability shading, broadest edge (solid), 50 % line (dashed) and
    nominal boundary (dotted), p_f in bar.

    Parameters
    ----------
    envelope : stability.envelope.Envelope
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    list of matplotlib artists
        The shading first (for a colour bar).
    """
    if ax is None:
        _, ax = plt.subplots()
    e = envelope
    f, bar = e.freq_hz, e.p_f / PA_PER_BAR
    artists = []
    probability = e.probability
    if np.isfinite(probability).any():
        shown = np.ma.masked_equal(probability.T, 0.0)
        artists.append(ax.pcolormesh(f, bar, shown, cmap="Reds",
                                     vmin=0, vmax=1, shading="nearest"))
        artists += ax.plot(f, e.quantile_boundary(0.5) / PA_PER_BAR,
                           color="0.35", linestyle="--", linewidth=1.0,
                           label="50 % of the samples unstable")
    artists += ax.plot(f, e.broadest / PA_PER_BAR, color="k", linewidth=1.6,
                       label="broadest region (samples, refined)")
    artists += ax.plot(f, e.nominal_boundary / PA_PER_BAR, color="k",
                       linestyle=":", linewidth=1.4, label="nominal")
    ax.set_xlim(f.min(), f.max())
    ax.set_ylim(0, e.p_max / PA_PER_BAR)
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    ax.legend(loc="upper right", fontsize=7)
    return artists


def envelope_figure(envelope, title=None):
    """A figure of :func:`plot_envelope` with a colour bar."""
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    artists = plot_envelope(envelope, ax=ax)
    if envelope.probability.size and np.isfinite(envelope.probability).any():
        fig.colorbar(artists[0], ax=ax, label="probability of instability")
    growth = (f", growth > {envelope.min_growth:g} 1/s"
              if envelope.min_growth else "")
    ax.set_title(title or f"unstable region over {len(envelope.names)} "
                          f"uncertain parameters{growth}")
    return fig

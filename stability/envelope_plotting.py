"""The envelope in the manner of Fig. 16: probability of instability
shaded over (frequency, amplitude), the broadest region's edge, the
nominal boundary.

Functions take an ``ax`` (a new figure is made when it is None), return the
artists they drew and never call ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patheffects import withStroke

from infra.units import PA_PER_BAR

__all__ = ["plot_envelope", "envelope_figure", "PROBABILITY_LEVELS"]

#: Bands of the probability of instability the shading draws.
PROBABILITY_LEVELS = (0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0)


def plot_envelope(envelope, ax=None):
    """Probability shading in bands (:data:`PROBABILITY_LEVELS`),
    broadest edge (black, solid), 50 % line (black dashed on white) and
    nominal boundary (blue, dotted), p_f in bar; the legend below.

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
    if np.isfinite(probability).any() and min(probability.shape) > 1:
        # bands of probability (not grid cells), from 1 % unstable up
        artists.append(ax.contourf(f, bar, probability.T,
                                   levels=PROBABILITY_LEVELS,
                                   cmap="Oranges", extend="neither"))
        # dashed black on a white halo: readable over every band
        artists += ax.plot(f, e.quantile_boundary(0.5) / PA_PER_BAR,
                           color="k", linestyle=(0, (5, 2.5)), linewidth=1.4,
                           path_effects=[withStroke(linewidth=3.2,
                                                    foreground="w")],
                           label="50 % of the samples unstable")
    artists += ax.plot(f, e.broadest / PA_PER_BAR, color="k", linewidth=1.8,
                       label="broadest region (samples, refined)")
    artists += ax.plot(f, e.nominal_boundary / PA_PER_BAR, color="#1f4e99",
                       linestyle=(0, (1, 1.2)), linewidth=1.8,
                       label="nominal parameters")
    ax.set_xlim(f.min(), f.max())
    ax.set_ylim(0, e.p_max / PA_PER_BAR)
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncols=3,
              fontsize=7, frameon=False, borderaxespad=0.0)
    return artists


def envelope_figure(envelope, title=None):
    """A figure of :func:`plot_envelope` with a colour bar; ``title`` (the
    model) follows the description of the envelope."""
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    artists = plot_envelope(envelope, ax=ax)
    from matplotlib.contour import ContourSet
    if isinstance(artists[0], ContourSet):
        fig.colorbar(artists[0], ax=ax, label="probability of instability",
                     ticks=PROBABILITY_LEVELS)
    growth = (f", growth > {envelope.min_growth:g} 1/s"
              if envelope.min_growth else "")
    ax.set_title(f"unstable region over {len(envelope.names)} uncertain "
                 f"parameters{growth}" + (f"\n{title}" if title else ""),
                 fontsize=10)
    return fig

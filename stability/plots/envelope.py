"""The unstable region over uncertain parameters: probability bands, the
broadest edge and the nominal boundary (section 4.2)."""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.contour import ContourSet
from matplotlib.patheffects import withStroke

from infra.plotstyle import DARK_BLUE, dither_axes
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
    envelope : stability.uncertainty.Envelope
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
    artists += ax.plot(f, e.nominal_boundary / PA_PER_BAR, color=DARK_BLUE,
                       linestyle=(0, (1, 1.2)), linewidth=1.8,
                       label="nominal parameters")
    ax.set_xlim(f.min(), f.max())
    ax.set_ylim(0, e.p_max / PA_PER_BAR)
    dither_axes(ax, "dither frequency [Hz]")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncols=3,
              fontsize=7, frameon=False, borderaxespad=0.0)
    return artists


def envelope_figure(envelope, title=None):
    """A figure of :func:`plot_envelope` with a colour bar; ``title`` (the
    model) follows the description of the envelope."""
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    artists = plot_envelope(envelope, ax=ax)
    if isinstance(artists[0], ContourSet):
        fig.colorbar(artists[0], ax=ax, label="probability of instability",
                     ticks=PROBABILITY_LEVELS)
    growth = (f", growth > {envelope.min_growth:g} 1/s"
              if envelope.min_growth else "")
    ax.set_title(f"unstable region over {len(envelope.names)} uncertain "
                 f"parameters{growth}" + (f"\n{title}" if title else ""),
                 fontsize=10)
    return fig

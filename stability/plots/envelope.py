"""The unstable region over uncertain parameters: probability bands, the
broadest edge and the nominal boundary (section 4.2)."""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.contour import ContourSet
from matplotlib.patheffects import withStroke

from infra.plotstyle import DARK_BLUE, dither_axes
from infra.units import PA_PER_BAR

__all__ = ["plot_envelope", "envelope_figure", "closed_edge",
           "PROBABILITY_LEVELS"]


#: Bands of the probability of instability the shading draws.
PROBABILITY_LEVELS = (0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0)


#: Points (frequency, amplitude) of the grid the bands are drawn on.
FINE_POINTS = (1000, 400)


def closed_edge(freq_hz, edge, top):
    """The outline of the region above ``edge`` (NaN: none up to ``top``):
    each stretch of finite values joined at both ends to ``top`` at the
    neighbouring frequency (where the edge has risen above it), the
    stretches apart by NaN; so the outline closes on the axes' top, not
    in mid-air.

    Returns
    -------
    freq, p : ndarray
        The outline's points.
    """
    freq_hz, edge = np.asarray(freq_hz, float), np.asarray(edge, float)
    finite = np.isfinite(edge)
    points = []
    starts = np.flatnonzero(finite & ~np.r_[False, finite[:-1]])
    ends = np.flatnonzero(finite & ~np.r_[finite[1:], False])
    for first, last in zip(starts, ends):
        left, right = max(first - 1, 0), min(last + 1, len(edge) - 1)
        points += ([(freq_hz[left], top)]
                   + list(zip(freq_hz[first:last + 1], edge[first:last + 1]))
                   + [(freq_hz[right], top), (np.nan, np.nan)])
    if not points:
        return np.array([]), np.array([])
    freq, p = np.array(points[:-1]).T
    return freq, p


def plot_envelope(envelope, ax=None):
    """Probability shading in bands (:data:`PROBABILITY_LEVELS`),
    broadest edge (black, solid), 50 % line (black dashed on white) and
    nominal boundary (blue, dotted), p_f in bar, each closed on the top
    of the axes (:func:`closed_edge`); the legend below. The shading and
    the 50 % line come from each sample's boundary, linear between the
    study's frequencies, on a fine grid
    (:meth:`~stability.uncertainty.Envelope.probability_at`), so they lie
    within the broadest region, as that region holds every sample's.

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
    top = e.p_max / PA_PER_BAR
    artists = []
    # the bands from each sample's boundary, linear between the study's
    # frequencies, on a fine grid: their edges follow the samples'
    # boundaries, not the staircase of the probability grid (issue 46)
    fine = np.linspace(f.min(), f.max(), FINE_POINTS[0])
    fine_bar = np.linspace(0.0, top, FINE_POINTS[1])
    probability = e.probability_at(fine, fine_bar * PA_PER_BAR)
    if np.isfinite(probability).any() and len(f) > 1:
        # from 1 % unstable up; a point no sample finds unstable is left
        # out, not interpolated to
        artists.append(ax.contourf(fine, fine_bar,
                                   np.where(probability > 0,
                                            probability, np.nan).T,
                                   levels=PROBABILITY_LEVELS,
                                   cmap="Oranges", extend="neither"))
        # dashed black on a white halo: readable over every band
        artists += ax.plot(*closed_edge(fine, e.quantile_at(fine, 0.5)
                                        / PA_PER_BAR, top),
                           color="k", linestyle=(0, (5, 2.5)), linewidth=1.4,
                           path_effects=[withStroke(linewidth=3.2,
                                                    foreground="w")],
                           label="50 % of the samples "
                                 + ("with judder" if e.min_growth
                                    else "unstable"))
    artists += ax.plot(*closed_edge(f, e.broadest / PA_PER_BAR, top),
                       color="k", linewidth=1.8,
                       label="broadest region (samples, refined)")
    artists += ax.plot(*closed_edge(f, e.nominal_boundary / PA_PER_BAR, top),
                       color=DARK_BLUE, linestyle=(0, (1, 1.2)),
                       linewidth=1.8, label="nominal parameters")
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
    # one word in the title, the colour bar and the legend: judder where
    # only growth above min_growth counts, instability where every does
    growth = envelope.min_growth
    judder = f"judder (growth > {growth:g} 1/s)" if growth else "instability"
    if isinstance(artists[0], ContourSet):
        fig.colorbar(artists[0], ax=ax, label=f"probability of {judder}",
                     ticks=PROBABILITY_LEVELS)
    region = (f"judder region (growth > {growth:g} 1/s)" if growth
              else "unstable region")
    ax.set_title(f"{region} over {len(envelope.names)} uncertain "
                 "parameters" + (f"\n{title}" if title else ""),
                 fontsize=10)
    return fig

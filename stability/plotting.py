"""Plots of stability maps in the manner of Fig. 12 and Fig. 14.

Functions take an ``ax`` (a new figure is made when it is None), return the
artists they drew and never call ``plt.show()``.
"""

import itertools

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from .floquet import KINDS

__all__ = ["KIND_COLORS", "plot_map", "plot_growth_rate", "map_figure",
           "resonance_lines"]

#: Colour of each kind of :data:`~stability.floquet.KINDS`.
KIND_COLORS = ("#ffffff", "#d62728", "#1f77b4", "#2ca02c")

PA_PER_BAR = 1e5


def resonance_lines(natural_frequencies_hz):
    """Frequencies where tongues start, by kind, as ``(label, hz, kind)``.

    Single-period at ``f_i``, double-period at ``2 f_i``, combination at
    ``f_j - f_i`` and ``f_i + f_j`` (section 4.2).
    """
    f = np.sort(np.asarray(natural_frequencies_hz))
    lines = [(f"f{i + 1}", fi, 1) for i, fi in enumerate(f)]
    lines += [(f"2f{i + 1}", 2 * fi, 2) for i, fi in enumerate(f)]
    for (i, fi), (j, fj) in itertools.combinations(enumerate(f), 2):
        lines += [(f"f{j + 1}-f{i + 1}", fj - fi, 3),
                  (f"f{i + 1}+f{j + 1}", fi + fj, 3)]
    return lines


def _edges(centres):
    centres = np.asarray(centres, dtype=float)
    if len(centres) == 1:
        return centres + np.array([-0.5, 0.5])
    mid = (centres[1:] + centres[:-1]) / 2
    return np.concatenate([[2 * centres[0] - mid[0]], mid,
                           [2 * centres[-1] - mid[-1]]])


def plot_map(stability_map, ax=None, mark_resonances=True):
    """Regions of each kind of instability over frequency (Hz) and p_f (bar).

    Parameters
    ----------
    stability_map : stability.maps.StabilityMap
    ax : matplotlib.axes.Axes, optional
    mark_resonances : bool
        Draw dashed lines at the natural frequencies and their
        double-period and combination partners inside the frequency range.

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    m = stability_map
    bar = m.p_f / PA_PER_BAR
    artists = [ax.pcolormesh(_edges(m.freq_hz), _edges(bar), m.kind.T,
                             cmap=ListedColormap(KIND_COLORS), vmin=-0.5,
                             vmax=len(KINDS) - 0.5, shading="flat")]
    if len(m.freq_hz) > 1 and len(bar) > 1:
        artists.append(ax.contour(m.freq_hz, bar, m.leading_abs.T,
                                  levels=[1.0], colors="k", linewidths=0.8))
    if mark_resonances:
        low, high = m.freq_hz.min(), m.freq_hz.max()
        for label, hz, kind in resonance_lines(m.natural_frequencies_hz):
            if low <= hz <= high:
                artists.append(ax.axvline(hz, color=KIND_COLORS[kind],
                                          linestyle="--", linewidth=0.8))
                artists.append(ax.annotate(
                    label, (hz, 1.0), xycoords=("data", "axes fraction"),
                    rotation=90, ha="right", va="top", fontsize=7))
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    handles = [Patch(facecolor=c, edgecolor="k", label=k)
               for k, c in zip(KINDS, KIND_COLORS)]
    artists.append(ax.legend(handles=handles, loc="upper left", fontsize=7))
    return artists


def plot_growth_rate(stability_map, ax=None):
    """Growth rate ``ln|lambda|/T`` (1/s) of the leading multiplier.

    Stable points are drawn white; returns the artists drawn.
    """
    if ax is None:
        _, ax = plt.subplots()
    m = stability_map
    rate = np.where(m.kind > 0, m.growth_rate, np.nan)
    mesh = ax.pcolormesh(_edges(m.freq_hz), _edges(m.p_f / PA_PER_BAR),
                         rate.T, cmap="magma_r", shading="flat")
    bar = ax.figure.colorbar(mesh, ax=ax, label="growth rate [1/s]")
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    return [mesh, bar]


def map_figure(stability_map, title=None):
    """Figure with the kinds (left) and the growth rate (right)."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5),
                                      layout="constrained")
    plot_map(stability_map, ax=left)
    plot_growth_rate(stability_map, ax=right)
    left.set_title("kind of instability (leading Floquet multiplier)")
    right.set_title("growth rate of the leading multiplier")
    if title:
        fig.suptitle(title)
    return fig

"""Plots of periodic orbits: amplitude against a parameter with stable
and unstable branches (as NLvib draws them), and the predicted judder
chart (:class:`stability.orbit_chart.OrbitChart`)."""

import matplotlib.pyplot as plt
import numpy as np

from infra.criteria import JUDDER, MECHANISMS
from infra.plotstyle import (FORCED_LINE, KIND_LINESTYLES, VERMILLION,
                             dither_axes, log_levels)
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

__all__ = ["plot_orbit_curve", "orbit_curve_figure", "plot_orbit_chart",
           "orbit_chart_figure"]

#: Marker and colour of a judder point by mechanism (as the experimental
#: chart draws its runs).
_MECHANISM_STYLE = {"forced": ("s", "#ff7f0e"), "parametric": ("^", "#d62728"),
                    "both": ("D", "#9467bd")}


def plot_orbit_curve(x, amplitude, stable, ax=None, label=None,
                     color="black"):
    """One branch of an amplitude curve: solid where the orbit is stable,
    dashed where it is not.

    Parameters
    ----------
    x : ndarray, shape (k,)
        Parameter along the branch (p_f in bar, or f in Hz).
    amplitude : ndarray, shape (k,)
        Amplitude, rpm (NaN: no orbit).
    stable : ndarray of bool, shape (k,)

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    x, amplitude = np.asarray(x), np.asarray(amplitude)
    stable = np.asarray(stable, dtype=bool)
    bounds = [0, *(np.flatnonzero(np.diff(stable.astype(int))) + 1),
              len(x)]
    artists, labelled = [], set()
    for start, stop in zip(bounds[:-1], bounds[1:]):
        # each part runs on to the next point, so the branch has no gaps
        stop = min(stop + 1, len(x))
        if np.all(np.isnan(amplitude[start:stop])):
            continue
        word = "stable" if stable[start] else "unstable"
        part = np.isfinite(amplitude[start:stop])
        # a part with no two neighbouring points is no line: a marker
        # (filled stable, open unstable), so what the legend lists shows
        alone = not (part[1:] & part[:-1]).any()
        style = {"linestyle": "none", "marker": "o", "markersize": 5,
                 "markerfacecolor": color if stable[start] else "w"} \
            if alone else {"linestyle": "-" if stable[start] else "--"}
        artists += ax.plot(x[start:stop], amplitude[start:stop], **style,
                           color=color,
                           label=None if (word, alone) in labelled else
                           (f"{label}, {word}" if label else word))
        labelled.add((word, alone))
    return artists


def orbit_curve_figure(curves, limit_rpm, xlabel, title=None, folds=()):
    """Amplitude curves of periodic orbits (``curves``: list of ``(x,
    amplitude rpm, stable, label, colour)``), the NVH limit and the folds
    (``(x, amplitude)`` points)."""
    fig, ax = plt.subplots(figsize=(7.0, 4.6), layout="constrained")
    for x, amplitude, stable, label, color in curves:
        plot_orbit_curve(x, amplitude, stable, ax=ax, label=label,
                         color=color)
    ax.axhline(limit_rpm, color="#d62728", lw=1, ls=":",
               label=f"NVH limit {limit_rpm:g} rpm")
    if folds:
        ax.plot(*zip(*folds), "o", mfc="none", color="black", ms=7,
                label="fold (jump)")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("upstream speed oscillation [rpm]")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    if title:
        ax.set_title(title, fontsize=10)
    return fig


#: The predicted boundary (where the periodic orbit reaches the NVH limit
#: or grows): thick vermillion, apart from the Floquet lines; an onset at
#: one frequency alone (no neighbour to join) is a dot.
_PREDICTED = {"color": VERMILLION, "linewidth": 2.4, "marker": "o",
              "markersize": 4}

#: Smallest marker side (pt) at which the judder points of the grid stay
#: apart; on a finer grid they are shaded as a region instead.
_SMALLEST_MARKER_PT = 3.5

#: The Floquet boundaries over the chart: sky blue (Okabe-Ito), visible on
#: the light and the dark greys, each kind in its line style.
_FLOQUET_COLOR = "#56b4e9"


def _marker_size(ax, chart):
    """Marker area (pt^2) that keeps neighbouring grid points apart: 55 %
    of the smaller spacing of the grid on the axes."""
    fig = ax.figure
    box = ax.get_position()
    width = box.width * fig.get_figwidth() * 72
    height = box.height * fig.get_figheight() * 72
    f, bar = chart.freq_hz, chart.p_f / PA_PER_BAR
    spacing = []
    if len(f) > 1:
        spacing.append(width * np.min(np.diff(f)) / np.ptp(f))
    if len(bar) > 1:
        spacing.append(height * np.min(np.diff(bar)) / np.ptp(bar))
    side = 0.55 * min(spacing) if spacing else 6.0
    return float(min(side, 7.0) ** 2)


def plot_orbit_chart(chart, ax=None, levels=None):
    """The predicted chart: the settled oscillation (rpm, grey contour),
    the judder points by mechanism (markers sized to stay apart on the
    grid) and the predicted boundary (thick vermillion).

    Returns
    -------
    list of matplotlib artists
    """
    from matplotlib.colors import LogNorm
    if ax is None:
        _, ax = plt.subplots()
    bar = chart.p_f / PA_PER_BAR
    rpm = np.clip(np.nan_to_num(chart.settled_amplitude) * RPM_PER_RAD_S,
                  1e-2, None)
    if levels is None:
        levels, _ = log_levels(max(rpm.min(), 0.1), max(rpm.max(), 1.0))
    artists = [ax.contourf(chart.freq_hz, bar, np.clip(rpm.T, levels[0],
                                                        levels[-1]),
                           levels=levels, norm=LogNorm(levels[0],
                                                       levels[-1]),
                           cmap="Greys", alpha=0.8)]
    limit = chart.limit * RPM_PER_RAD_S
    if rpm.min() < limit < rpm.max():
        artists.append(ax.contour(
            chart.freq_hz, bar, rpm.T, levels=[limit],
            colors=FORCED_LINE["color"], linewidths=FORCED_LINE["linewidth"],
            linestyles=[FORCED_LINE["linestyle"]]))
    f, p = np.meshgrid(chart.freq_hz, bar, indexing="ij")
    size = _marker_size(ax, chart)
    onsets = chart.onsets() / PA_PER_BAR
    found = [(name, (chart.judder & (chart.mechanism == code)).sum())
             for code, name in enumerate(MECHANISMS)
             if name in _MECHANISM_STYLE]
    found = [(name, count) for name, count in found if count]
    if found and size < _SMALLEST_MARKER_PT ** 2 and min(f.shape) > 1:
        # markers this close merge into bars: judder shaded from the
        # predicted boundary up, in the colour of its commonest mechanism
        colour = _MECHANISM_STYLE[max(found, key=lambda x: x[1])[0]][1]
        artists.append(ax.fill_between(
            chart.freq_hz, np.where(np.isfinite(onsets), onsets, bar[-1]),
            bar[-1], where=np.isfinite(onsets), color=colour, alpha=0.5,
            linewidth=0, zorder=3,
            label="judder: " + ", ".join(name for name, _ in found)))
        found = []
    for name, _ in found:
        marker, colour = _MECHANISM_STYLE[name]
        these = chart.judder & (chart.mechanism == MECHANISMS.index(name))
        artists.append(ax.scatter(f[these], p[these], marker=marker,
                                  s=size, color=colour, zorder=3,
                                  edgecolors="k", linewidths=0.4,
                                  label=f"{JUDDER.lower()}, {name}"))
    finite = np.isfinite(onsets)
    joined = np.zeros_like(finite)
    joined[1:] |= finite[1:] & finite[:-1]
    joined[:-1] |= finite[1:] & finite[:-1]
    artists += ax.plot(chart.freq_hz, onsets, **_PREDICTED, zorder=4,
                       markevery=list(np.flatnonzero(finite & ~joined)),
                       label="predicted boundary (periodic orbit)")
    dither_axes(ax)
    return artists


def orbit_chart_figure(chart, title=None, boundaries=None):
    """The predicted chart with its colour bar, and the Floquet tongue
    boundaries of the same bench (``boundaries``, a
    :class:`stability.tongues.TongueBoundaries`) over it: sky blue, one
    line style per kind, each kind drawn in the legend."""
    from matplotlib.lines import Line2D

    from ..kinds import KINDS
    from .boundaries import plot_boundaries
    fig, ax = plt.subplots(figsize=(8.0, 5.2), layout="constrained")
    rpm = np.clip(np.nan_to_num(chart.settled_amplitude) * RPM_PER_RAD_S,
                  1e-2, None)
    levels, ticks = log_levels(max(rpm.min(), 0.1), max(rpm.max(), 1.0))
    artists = plot_orbit_chart(chart, ax=ax, levels=levels)
    bar = fig.colorbar(artists[0], ax=ax, ticks=ticks,
                       label="settled upstream speed oscillation [rpm]")
    bar.ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
    bar.ax.minorticks_off()
    floquet = []
    if boundaries is not None:
        limits = ax.get_xlim(), ax.get_ylim()
        plot_boundaries(boundaries, ax=ax, numbers=False,
                        style={"color": _FLOQUET_COLOR, "linewidth": 1.4})
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
        for column, kind in enumerate((1, 2, 3)):
            if np.isfinite(boundaries.amplitude[:, column]).any():
                floquet.append(Line2D(
                    [], [], color=_FLOQUET_COLOR, linewidth=1.4,
                    linestyle=KIND_LINESTYLES[kind],
                    label=rf"Floquet $|\lambda| = 1$, {KINDS[kind]}"))
    handles, labels = ax.get_legend_handles_labels()
    handles += floquet + [Line2D([], [], **FORCED_LINE)]
    labels += [h.get_label() for h in floquet] + [
        f"NVH limit, {chart.limit * RPM_PER_RAD_S:.3g} rpm"]
    # below the axes, off the data
    ax.legend(handles, labels, fontsize=8, loc="upper center",
              bbox_to_anchor=(0.5, -0.13), ncols=2, borderaxespad=0.0)
    if title:
        ax.set_title(title, fontsize=10)
    return fig

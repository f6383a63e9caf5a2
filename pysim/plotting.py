"""Plots of runs (Fig. 7), spectra (Fig. 8) and experimental stability
charts (Fig. 10, 11).

Functions take ``ax``/``axes`` where they draw one panel and return the
artists; figure builders return the figure. Nothing calls ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import BLUE, VERMILLION, dither_axes
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .signals import amplitude_spectrum

__all__ = ["plot_run", "plot_spectrum", "plot_spectra_overlay", "run_figure",
           "plot_chart", "chart_figure"]


#: Line styles of the speeds, so they differ without colour.
SPEED_STYLES = {"w_upstream": ("-", BLUE, "upstream of the clutch"),
                "w_downstream": ("--", VERMILLION, "downstream of the clutch")}


def _dither_text(run):
    p_f = run.p_f / PA_PER_BAR
    return ("no dither" if p_f == 0 else
            f"f = {run.freq_hz:g} Hz, $p_f$ = {p_f:g} bar")


def plot_run(run, ax=None, title=None, legend=True, verdict=None):
    """Speeds upstream and downstream (rpm) and pressure (bar) vs time
    (Fig. 1, Fig. 7); the legend goes below the axes, off the traces;
    ``verdict``, a line of text (the judder verdict and growth), under
    the title."""
    if ax is None:
        _, ax = plt.subplots()
    right = ax.twinx()
    traces = [(ax, run[name] * RPM_PER_RAD_S, style, color, label)
              for name, (style, color, label) in SPEED_STYLES.items()]
    traces.append((right, run["actuation_pressure"] / PA_PER_BAR, "-", "0.45",
                   "actuation pressure (right axis)"))
    period = 1.0 / run.freq_hz if run.p_f > 0 else None
    banded = period is not None and (run.time[-1] - run.time[0]) \
        > BANDED_PERIODS * period
    artists = []
    for axis, values, style, color, label in traces:
        if banded:
            # unresolved at this scale: the band the dither swings over,
            # and its mean per period
            t, low, high, mean = _per_period(run.time, values, period)
            axis.fill_between(t, low, high, color=color, alpha=0.3, lw=0)
            artists.append(axis.plot(t, mean, ls=style, color=color, lw=1.0,
                                     label=label)[0])
        else:
            artists.append(axis.plot(run.time, values, ls=style,
                                     color=color, lw=0.8, label=label)[0])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [rpm]")
    right.set_ylabel("actuation pressure [bar]")
    if legend:
        from matplotlib.patches import Patch
        notes = [Patch(facecolor="0.6", alpha=0.3,
                       label="shaded: swing per dither period, line: mean")
                 ] if banded else []
        ax.legend(handles=artists + notes, loc="upper center", fontsize=7,
                  bbox_to_anchor=(0.5, -0.2), ncols=2, borderaxespad=0.0)
    ax.set_title((f"{title}: " if title else "") + _dither_text(run)
                 + (f"\n{verdict}" if verdict else ""), fontsize=9)
    return artists


#: More dither periods than this in a time history and each trace is drawn
#: as its swing per period (a band) and its mean: the oscillation itself
#: would fill the axes solid.
BANDED_PERIODS = 150


def _per_period(time, values, period):
    """Per dither period: centre time, minimum, maximum and mean of
    ``values``."""
    index = np.floor((time - time[0]) / period).astype(int)
    count = index[-1] + 1
    edges = np.searchsorted(index, np.arange(count + 1))
    keep = np.diff(edges) > 0
    starts = edges[:-1][keep]
    low = np.minimum.reduceat(values, starts)
    high = np.maximum.reduceat(values, starts)
    mean = np.add.reduceat(values, starts) / np.diff(
        np.append(starts, len(values)))
    centre = np.add.reduceat(time, starts) / np.diff(
        np.append(starts, len(values)))
    return centre, low, high, mean


def _spectra(run, start):
    keep = run.time >= start
    speed = amplitude_spectrum(run.time[keep],
                               run["w_upstream"][keep] * RPM_PER_RAD_S)
    pressure = amplitude_spectrum(run.time[keep],
                                  run["actuation_pressure"][keep] / PA_PER_BAR)
    return speed, pressure


def plot_spectrum(run, ax=None, start=0.0, f_max=None):
    """Amplitude spectra (Fig. 8): the upstream speed in rpm on the left
    axis, the pressure in bar on its own right axis, both linear; the
    dither frequency marked only when the run has dither.

    Parameters
    ----------
    f_max : float, optional
        Upper end of the frequency axis, Hz (default 3 f): give every
        panel of a figure the same one.

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    speed, pressure = _spectra(run, start)
    artists = [ax.plot(speed.freq_hz, speed.amplitude, color=BLUE,
                       lw=0.9, label="upstream speed [rpm] (left axis)")[0]]
    right = ax.twinx()
    artists.append(right.plot(pressure.freq_hz, pressure.amplitude,
                              color="0.45", ls="--", lw=0.8,
                              label="pressure [bar] (right axis)")[0])
    if run.p_f > 0:
        artists.append(ax.axvline(run.freq_hz, color="k", ls=":", lw=0.8,
                                  label=f"dither frequency {run.freq_hz:g} "
                                        "Hz"))
    f_max = f_max or min(speed.freq_hz[-1], 3 * run.freq_hz)
    ax.set_xlim(0, f_max)
    band = speed.freq_hz <= f_max
    ax.set_ylim(0, 1.08 * max(speed.amplitude[band].max(), 1e-9))
    right.set_ylim(0, 1.08 * max(pressure.amplitude[band].max(), 1e-9))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("speed amplitude [rpm]")
    right.set_ylabel("pressure amplitude [bar]")
    ax.legend(handles=artists, loc="upper center", fontsize=7,
              bbox_to_anchor=(0.5, -0.2), ncols=3, borderaxespad=0.0)
    return artists


def plot_spectra_overlay(runs, ax=None, start=0.0, f_max=None):
    """Speed spectra of several engagements on one axis (Fig. 8). Each
    run's dither frequency is marked in its colour and style: a
    single-period judder peaks there, a double-period one at half of it,
    a combination one at natural frequencies of the driveline."""
    if ax is None:
        _, ax = plt.subplots()
    colours = plt.get_cmap("cividis")(np.linspace(0.0, 0.75, len(runs)))
    styles = ("-", "--", "-.", ":")
    artists = []
    top = 0.0
    for index, (label, run) in enumerate(runs):
        speed, _ = _spectra(run, start)
        band = speed.freq_hz <= (f_max or speed.freq_hz[-1])
        top = max(top, speed.amplitude[band].max())
        artists.append(ax.plot(speed.freq_hz, speed.amplitude,
                               color=colours[index],
                               ls=styles[index % len(styles)], lw=1.0,
                               label=_dither_text(run).replace("$", "")
                               .replace("p_f", "p_f"))[0])
        if run.p_f > 0:
            ax.axvline(run.freq_hz, color=colours[index], lw=0.6,
                       ls=styles[index % len(styles)], alpha=0.6)
            ax.annotate(f"dither {run.freq_hz:g} Hz", (run.freq_hz, 1.0),
                        xycoords=("data", "axes fraction"), xytext=(3, -3),
                        textcoords="offset points", ha="left", va="top",
                        fontsize=7, color=colours[index])
    ax.set_xlim(0, f_max)
    # a log scale: a run 100 times quieter than another stays visible
    ax.set_yscale("log")
    ax.set_ylim(max(top, 1e-9) * 1e-4, 2.0 * max(top, 1e-9))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("upstream speed amplitude [rpm] (log)")
    ax.set_title("speed spectra overlaid", fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
              borderaxespad=0.0)
    return artists


def run_figure(runs, start=0.0, title=None, verdicts=None):
    """Time histories (top) and spectra (middle), one column per run,
    every spectrum over the same frequencies; with more than one run with
    dither, their speed spectra overlaid (bottom). ``verdicts``: one line
    of text per run, printed over its time histories."""
    dithered = [(label, run) for label, run in runs if run.p_f > 0]
    f_max = 2.5 * max([run.freq_hz for _, run in runs])
    f_max = min(f_max, min(0.5 / np.median(np.diff(run.time))
                           for _, run in runs))
    overlay = len(dithered) > 1
    rows = 3 if overlay else 2
    fig = plt.figure(figsize=(6.5 * len(runs), 3.6 * rows + 0.6),
                     layout="constrained")
    grid = fig.add_gridspec(rows, len(runs))
    for column, (label, run) in enumerate(runs):
        plot_run(run, ax=fig.add_subplot(grid[0, column]), title=label,
                 verdict=None if verdicts is None else verdicts[column])
        plot_spectrum(run, ax=fig.add_subplot(grid[1, column]), start=start,
                      f_max=f_max)
    if overlay:
        plot_spectra_overlay(dithered, ax=fig.add_subplot(grid[2, :]),
                             start=start, f_max=f_max)
    if title:
        fig.suptitle(title, fontsize=11)
    return fig


#: How a group column reads in a panel title.
_GROUP_TITLES = {"oil_temperature": "oil {} degC",
                 "engine_rpm": "{} rpm"}


def _group_title(columns, group):
    parts = []
    for column, value in zip(columns, group):
        try:
            value = f"{float(value):g}"
        except ValueError:
            pass
        parts.append(_GROUP_TITLES.get(column, column + " {}").format(value))
    return ", ".join(parts) or "all runs"


def _amplitude_levels(low, high):
    """Log-spaced contour levels of the amplitude, rpm, and round ticks."""
    low, high = max(low, 1e-3), max(high, 1.0001 * max(low, 1e-3))
    levels = np.geomspace(low, high * 1.0001, 12)
    decades = np.arange(np.floor(np.log10(low)), np.ceil(np.log10(high)) + 1)
    ticks = [m * 10 ** d for d in decades for m in (1, 3)
             if low <= m * 10 ** d <= high]
    return levels, ticks or [low, high]


def plot_chart(chart, group, ax=None, levels=None):
    """One panel of an experimental chart (Fig. 10): amplitude contour,
    runs and the experimental boundary, over Hz and bar.

    Parameters
    ----------
    chart : pysim.charts.Chart
    group : tuple of str
        A key of ``chart.groups()``.
    levels : ndarray, optional
        Contour levels of the amplitude (rpm), shared by the panels of a
        figure (:func:`chart_figure` draws their one colour bar); without
        them the panel's own, with its colour bar.

    Returns
    -------
    list of matplotlib artists
    """
    from matplotlib.colors import LogNorm
    if ax is None:
        _, ax = plt.subplots()
    runs = chart.groups()[group]
    f = np.array([r.analysis.freq_hz for r in runs])
    p = np.array([r.analysis.p_f_bar for r in runs])
    amplitude = np.array([max(r.analysis.amplitude_rpm, 1e-3) for r in runs])
    judder = np.array([r.analysis.judder for r in runs])
    artists = []
    own = levels is None
    if own:
        levels, ticks = _amplitude_levels(amplitude.min(), amplitude.max())
    if len(np.unique(f)) >= 3 and len(np.unique(p)) >= 3:
        contour = ax.tricontourf(f, p, np.clip(amplitude, levels[0],
                                               levels[-1]),
                                 levels=levels, norm=LogNorm(levels[0],
                                                             levels[-1]),
                                 cmap="Greys", alpha=0.8)
        if own:
            bar = ax.figure.colorbar(contour, ax=ax, ticks=ticks,
                                     label="amplitude of the judder "
                                           "component [rpm]")
            bar.ax.set_yticklabels([f"{t:g}" for t in ticks])
        artists.append(contour)
    artists.append(ax.scatter(f[judder], p[judder], marker="^",
                              color="#d62728", zorder=3, clip_on=False,
                              label="judder"))
    artists.append(ax.scatter(f[~judder], p[~judder], marker="o",
                              facecolors="none", edgecolors="black",
                              zorder=3, clip_on=False, label="no judder"))
    boundary = chart.boundary(group)
    # the boundary is drawn only between neighbouring frequencies that
    # both have judder: a censored frequency between them breaks it
    lowest = np.array([np.nan if pb is None else pb for _, pb, _ in boundary])
    if np.isfinite(lowest).any():
        artists += ax.plot([fb for fb, _, _ in boundary], lowest,
                           color="#1f77b4", lw=1.5, marker="_", ms=10,
                           label="experimental boundary")
    censored = [(fb, top) for fb, pb, top in boundary if pb is None]
    if censored:
        artists.append(ax.scatter(*zip(*censored), marker="^",
                                  facecolors="none", edgecolors="#1f77b4",
                                  s=60, zorder=4, clip_on=False,
                                  label="no judder up to here"))
    _pad_limits(ax, f, p)
    dither_axes(ax, "dither frequency [Hz]")
    ax.set_title(_group_title(chart.group_by, group), fontsize=10)
    return artists


def _pad_limits(ax, freq_hz, p_f_bar, share=0.05):
    """Axis limits a share of the span beyond the runs, so no marker sits
    on the frame or under the title (a contour fill stops at the runs)."""
    for values, setter in ((freq_hz, ax.set_xlim), (p_f_bar, ax.set_ylim)):
        low, high = float(np.min(values)), float(np.max(values))
        pad = share * (high - low) if high > low else 0.05 * max(abs(high),
                                                                 1.0)
        setter(low - pad, high + pad)


def chart_figure(chart, title=None):
    """All panels of a chart, one per group (Fig. 11), up to four a row,
    on one amplitude scale with one colour bar; returns the figure and
    ``{group: ax}``."""
    groups = list(chart.groups())
    columns = min(max(len(groups), 1), 4)
    rows = -(-max(len(groups), 1) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5.2 * columns + 1.2,
                                                     4.2 * rows + 0.8),
                             layout="constrained", squeeze=False,
                             sharex=True, sharey=True)
    amplitudes = [r.analysis.amplitude_rpm for r in chart.read] or [1.0]
    levels, ticks = _amplitude_levels(min(amplitudes), max(amplitudes))
    panels = {}
    for group, ax in zip(groups, axes.flat):
        plot_chart(chart, group, ax=ax, levels=levels)
        panels[group] = ax
    for ax in list(axes.flat)[len(groups):]:
        ax.set_visible(False)
    if chart.read:               # shared axes: the limits of every run
        _pad_limits(next(iter(panels.values())),
                    [r.analysis.freq_hz for r in chart.read],
                    [r.analysis.p_f_bar for r in chart.read])
    for ax in panels.values():
        ax.label_outer()         # axis labels on the outer panels only
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import BoundaryNorm
    scale = ScalarMappable(norm=BoundaryNorm(levels, 256), cmap="Greys")
    bar = fig.colorbar(scale, ax=axes, ticks=ticks, shrink=0.9,
                       label="amplitude of the judder component [rpm]")
    bar.ax.set_yscale("log")
    bar.ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
    bar.ax.minorticks_off()
    if groups:
        handles = {}
        for ax in panels.values():
            for handle, label in zip(*ax.get_legend_handles_labels()):
                handles.setdefault(label, handle)
        fig.legend(handles.values(), handles.keys(), loc="outside lower "
                   "center", ncols=5, fontsize=8)
    if title:
        fig.suptitle(title)
    return fig, panels

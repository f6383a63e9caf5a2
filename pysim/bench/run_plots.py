"""Plots of runs: time histories (Fig. 7) and spectra (Fig. 8).

Functions take ``ax`` where they draw one panel and return the artists;
:func:`run_figure` returns the figure. They draw what they are given:
spectra come computed (:func:`pysim.bench.engagement.display_spectra`), a
long run's time history is banded per dither period for display
(:func:`pysim.bench.signals.per_period`); nothing calls ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import BLUE, VERMILLION, figure_title
from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .signals import per_period

__all__ = ["plot_run", "plot_spectrum", "plot_spectra_overlay", "plot_path",
           "run_figure"]


#: Line styles of the speeds, so they differ without colour.
SPEED_STYLES = {"w_upstream": ("-", BLUE, "upstream of the clutch"),
                "w_downstream": ("--", VERMILLION, "downstream of the clutch")}


def _dither_text(run):
    p_f = run.p_f / PA_PER_BAR
    return ("no dither" if p_f == 0 else
            f"f = {run.freq_hz:g} Hz, $p_f$ = {p_f:g} bar")


def plot_run(run, ax=None, title=None, legend=True, verdict=None,
             lock_up=None):
    """Speeds upstream and downstream (rpm) and pressure (bar) vs time
    (Fig. 1, Fig. 7); the legend goes below the axes, off the traces;
    ``verdict``, a line of text (the judder verdict and growth), under
    the title; ``lock_up``, s: the time the clutch locks up, a vertical
    line."""
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
    artists, bands = [], []
    for axis, values, style, color, label in traces:
        if banded:
            # unresolved at this scale: the band the dither swings over,
            # and its mean per period
            t, low, high, mean = per_period(run.time, values, period)
            bands.append(axis.fill_between(t, low, high, color=color,
                                           alpha=0.3, lw=0))
            artists.append(axis.plot(t, mean, ls=style, color=color, lw=1.0,
                                     label=label)[0])
        else:
            artists.append(axis.plot(run.time, values, ls=style,
                                     color=color, lw=0.8, label=label)[0])
    if lock_up is not None:
        artists.append(ax.axvline(lock_up, ls=":", color="0.2", lw=1.0,
                                  label=f"lock-up, {lock_up:.3g} s"))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [rpm]")
    right.set_ylabel("actuation pressure [bar]")
    if legend:
        # the first band stands for all: what a shade and a line mean
        notes = bands[:1]
        for band in notes:
            band.set_label("shaded: swing per dither period, line: mean")
        ax.legend(handles=artists + notes, loc="upper center", fontsize=7,
                  bbox_to_anchor=(0.5, -0.2), ncols=2, borderaxespad=0.0)
    # a run without dither has its label alone ("without dither"), not
    # the label and the setting's "no dither" again
    heading = (title if title and run.p_f == 0 else
               (f"{title}: " if title else "") + _dither_text(run))
    ax.set_title(heading + (f"\n{verdict}" if verdict else ""), fontsize=9)
    return artists


#: More dither periods than this in a time history and each trace is drawn
#: as its swing per period (a band) and its mean: the oscillation itself
#: would fill the axes solid.
BANDED_PERIODS = 150


def plot_spectrum(run, spectra, ax=None, f_max=None):
    """Amplitude spectra (Fig. 8): the upstream speed in rpm on the left
    axis, the pressure in bar on its own right axis, both linear; the
    dither frequency and the pressure only when the run has dither
    (without, the pressure's spectrum is numerical noise, 1e-9 bar).

    Parameters
    ----------
    run : pysim.simulation.runs.RunResult
    spectra : tuple
        ``(speed, pressure)`` spectra of the run, as
        :func:`pysim.bench.engagement.display_spectra` gives them.
    f_max : float, optional
        Upper end of the frequency axis, Hz (default 3 f): give every
        panel of a figure the same one.

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    speed, pressure = spectra
    artists = [ax.plot(speed.freq_hz, speed.amplitude, color=BLUE,
                       lw=0.9, label="upstream speed [rpm] (left axis)")[0]]
    f_max = f_max or min(speed.freq_hz[-1], 3 * run.freq_hz)
    band = speed.freq_hz <= f_max
    if run.p_f > 0:
        right = ax.twinx()
        artists.append(right.plot(pressure.freq_hz, pressure.amplitude,
                                  color="0.45", ls="--", lw=0.8,
                                  label="pressure [bar] (right axis)")[0])
        artists.append(ax.axvline(run.freq_hz, color="k", ls=":", lw=0.8,
                                  label=f"dither frequency {run.freq_hz:g} "
                                        "Hz"))
        right.set_ylim(0, 1.08 * max(pressure.amplitude[band].max(), 1e-9))
        right.set_ylabel("pressure amplitude [bar]")
    ax.set_xlim(0, f_max)
    ax.set_ylim(0, 1.08 * max(speed.amplitude[band].max(), 1e-9))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("speed amplitude [rpm]")
    ax.legend(handles=artists, loc="upper center", fontsize=7,
              bbox_to_anchor=(0.5, -0.2), ncols=3, borderaxespad=0.0)
    return artists


def plot_spectra_overlay(runs, speed_spectra, ax=None, f_max=None):
    """Speed spectra of several engagements on one axis (Fig. 8). Each
    run's dither frequency is marked in its colour and style: a
    single-period judder peaks there, a double-period one at half of it,
    a combination one at natural frequencies of the driveline.

    ``runs`` are ``(label, run)`` pairs, ``speed_spectra`` their speed
    spectra (:func:`pysim.bench.engagement.display_spectra`)."""
    if ax is None:
        _, ax = plt.subplots()
    colours = plt.get_cmap("cividis")(np.linspace(0.0, 0.75, len(runs)))
    styles = ("-", "--", "-.", ":")
    artists = []
    top = 0.0
    for index, ((label, run), speed) in enumerate(zip(runs,
                                                     speed_spectra)):
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


#: Padding around each panel of :func:`run_figure`, in: the pressure's
#: right-axis label ended within 0.04 in of the figure's edge (4/72 in,
#: the constrained layout's default) and met the next column's.
RIGHT_AXIS_PAD_IN = 0.15


def plot_path(path, ax=None, min_growth=None):
    """The run's path through the stability map against time: the
    Floquet exponent of its linearisation at its mean slip (1/s, left;
    shaded where it exceeds ``min_growth``) and that slip (rpm, right).

    ``path`` is ``(time s, exponent 1/s, mean slip rad/s)``
    (:mod:`stability.engagement_path`)."""
    if ax is None:
        _, ax = plt.subplots()
    time, growth, slip = (np.asarray(a) for a in path)
    artists = [ax.plot(time, growth, color=BLUE, lw=1.2,
                       label="Floquet exponent at the mean slip")[0]]
    if min_growth is not None:
        artists.append(ax.axhline(min_growth, ls="--", color="0.3", lw=0.8,
                                  label=f"judder growth, {min_growth:g} 1/s"))
        if (growth > min_growth).any():    # a legend entry only if drawn
            artists.append(ax.fill_between(
                time, min_growth, growth, where=growth > min_growth,
                color=BLUE, alpha=0.25, lw=0, label="inside a tongue"))
    artists.append(ax.axhline(0.0, color="0.6", lw=0.6,
                              label="no growth, |$\\lambda$| = 1"))
    right = ax.twinx()
    artists.append(right.plot(time, slip * RPM_PER_RAD_S, ls=":",
                              color=VERMILLION, lw=1.2,
                              label="mean slip (right axis)")[0])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("growth rate [1/s]")
    right.set_ylabel("mean slip [rpm]")
    ax.set_title("path through the stability map (quasi-static)",
                 fontsize=9)
    ax.legend(handles=artists, loc="upper center", fontsize=7,
              bbox_to_anchor=(0.5, -0.2), ncols=2, borderaxespad=0.0)
    return artists


def run_figure(runs, spectra, title=None, verdicts=None, lock_ups=None,
               paths=None, min_growth=None):
    """Time histories (top) and spectra (middle), one column per run,
    every spectrum over the same frequencies; with more than one run with
    dither, their speed spectra overlaid (bottom); with ``paths`` (per
    run ``(time, exponent, mean slip)`` or None), each run's path through
    the map under its spectrum (:func:`plot_path`).

    ``runs`` are ``(label, run)`` pairs, ``spectra`` their ``(speed,
    pressure)`` spectra (:func:`pysim.bench.engagement.display_spectra`),
    ``verdicts`` one line of text per run, printed over its time
    histories, ``lock_ups`` per run the time its clutch locks up (s, or
    None)."""
    dithered = [(label, run) for label, run in runs if run.p_f > 0]
    dithered_speeds = [speed for (_, run), (speed, _) in zip(runs, spectra)
                       if run.p_f > 0]
    f_max = 2.5 * max([run.freq_hz for _, run in runs])
    f_max = min(f_max, min(0.5 / np.median(np.diff(run.time))
                           for _, run in runs))
    overlay = len(dithered) > 1
    with_paths = paths is not None and any(p is not None for p in paths)
    rows = 2 + overlay + with_paths
    fig = plt.figure(figsize=(6.5 * len(runs), 3.6 * rows + 0.6),
                     layout="constrained")
    # room around each panel's decorations: the right axis of pressure
    # has its label at the figure's (or the next column's) edge otherwise
    fig.get_layout_engine().set(w_pad=RIGHT_AXIS_PAD_IN, wspace=0.04)
    grid = fig.add_gridspec(rows, len(runs))
    for column, (label, run) in enumerate(runs):
        plot_run(run, ax=fig.add_subplot(grid[0, column]), title=label,
                 verdict=None if verdicts is None else verdicts[column],
                 lock_up=None if lock_ups is None else lock_ups[column])
        plot_spectrum(run, spectra[column],
                      ax=fig.add_subplot(grid[1, column]), f_max=f_max)
        if with_paths and paths[column] is not None:
            plot_path(paths[column], ax=fig.add_subplot(grid[2, column]),
                      min_growth=min_growth)
    if overlay:
        plot_spectra_overlay(dithered, dithered_speeds,
                             ax=fig.add_subplot(grid[rows - 1, :]),
                             f_max=f_max)
    if title:
        figure_title(fig, title)
    return fig

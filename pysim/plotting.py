"""Plots of runs (Fig. 7), spectra (Fig. 8), cross-checks and experimental
stability charts (Fig. 10, 11).

Functions take ``ax``/``axes`` where they draw one panel and return the
artists; figure builders return the figure. Nothing calls ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.units import PA_PER_BAR, RPM_PER_RAD_S

from .signals import amplitude_spectrum

__all__ = ["plot_run", "plot_spectrum", "run_figure", "crosscheck_figure",
           "plot_chart", "chart_figure"]


def plot_run(run, ax=None, title=None):
    """Speeds upstream and downstream (rpm) and pressure (bar) vs time."""
    if ax is None:
        _, ax = plt.subplots()
    artists = [ax.plot(run.time, run["w_upstream"] * RPM_PER_RAD_S,
                       label="upstream of the clutch", lw=0.8)[0],
               ax.plot(run.time, run["w_downstream"] * RPM_PER_RAD_S,
                       label="downstream of the clutch", lw=0.8)[0]]
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [rpm]")
    right = ax.twinx()
    artists.append(right.plot(run.time, run["actuation_pressure"] / PA_PER_BAR,
                              color="0.6", lw=0.5, label="pressure")[0])
    right.set_ylabel("actuation pressure [bar]")
    ax.legend(loc="upper right", fontsize=7)
    ax.set_title(title or f"f = {run.freq_hz:g} Hz, p_f = "
                          f"{run.p_f / PA_PER_BAR:g} bar", fontsize=9)
    return artists


def plot_spectrum(run, ax=None, start=0.0):
    """Amplitude spectra of the upstream speed and the pressure (Fig. 8)."""
    if ax is None:
        _, ax = plt.subplots()
    keep = run.time >= start
    speed = amplitude_spectrum(run.time[keep],
                               run["w_upstream"][keep] * RPM_PER_RAD_S)
    pressure = amplitude_spectrum(run.time[keep],
                                  run["actuation_pressure"][keep] / PA_PER_BAR)
    artists = [ax.semilogy(speed.freq_hz, speed.amplitude,
                           label="upstream speed [rpm]", lw=0.8)[0],
               ax.semilogy(pressure.freq_hz, pressure.amplitude,
                           label="pressure [bar]", lw=0.8)[0],
               ax.axvline(run.freq_hz, color="k", ls=":", lw=0.8,
                          label="dither frequency")]
    ax.set_xlim(0, min(speed.freq_hz[-1], 3 * run.freq_hz))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("amplitude")
    ax.legend(fontsize=7)
    return artists


def run_figure(runs, start=0.0, title=None):
    """Time histories (top) and spectra (bottom), one column per run."""
    fig, axes = plt.subplots(2, len(runs), figsize=(6.5 * len(runs), 7),
                             layout="constrained", squeeze=False)
    for column, (label, run) in enumerate(runs):
        plot_run(run, ax=axes[0, column], title=label)
        plot_spectrum(run, ax=axes[1, column], start=start)
    if title:
        fig.suptitle(title)
    return fig


def crosscheck_figure(check, title=None):
    """Fitted against Floquet growth rates, and verdicts on the grid."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5),
                                      layout="constrained")
    floquet = np.array([p.floquet_rate for p in check.points])
    fitted = np.array([p.fitted_rate for p in check.points])
    agree = np.array([p.agree for p in check.points])
    left.plot(floquet[agree], fitted[agree], "o", ms=4, label="verdicts agree")
    left.plot(floquet[~agree], fitted[~agree], "rx", ms=6,
              label="verdicts disagree")
    span = [min(floquet.min(), fitted.min()), max(floquet.max(), fitted.max())]
    left.plot(span, span, "k-", lw=0.6, label="equal")
    left.set_xlabel("Floquet exponent ln|lambda|/T [1/s]")
    left.set_ylabel("growth rate fitted to the FMU run [1/s]")
    left.legend(fontsize=8)
    f = np.array([p.freq_hz for p in check.points])
    p = np.array([p.p_f for p in check.points]) / PA_PER_BAR
    unstable = np.array([q.floquet_unstable for q in check.points])
    right.scatter(f[unstable & agree], p[unstable & agree], c="C3", s=18,
                  label="unstable, both")
    right.scatter(f[~unstable & agree], p[~unstable & agree], c="C2", s=18,
                  label="stable, both")
    right.scatter(f[~agree], p[~agree], marker="x", c="k", s=30,
                  label="disagree")
    right.set_xlabel("dither frequency [Hz]")
    right.set_ylabel("dither amplitude $p_f$ [bar]")
    right.legend(fontsize=8)
    fig.suptitle(title or f"cross-check: {100 * check.agreement:.1f} % of the "
                          "verdicts agree")
    return fig


def plot_chart(chart, group, ax=None):
    """One panel of an experimental chart (Fig. 10): amplitude contour,
    runs and the experimental boundary, over Hz and bar.

    Parameters
    ----------
    chart : pysim.charts.Chart
    group : tuple of str
        A key of ``chart.groups()``.

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
    if len(np.unique(f)) >= 3 and len(np.unique(p)) >= 3:
        contour = ax.tricontourf(f, p, amplitude, levels=np.geomspace(
            amplitude.min(), amplitude.max() * 1.0001, 12), norm=LogNorm(),
            cmap="Greys", alpha=0.8)
        ticks = np.geomspace(amplitude.min(), amplitude.max(), 5)
        bar = ax.figure.colorbar(contour, ax=ax, ticks=ticks,
                                 label="amplitude of the judder component "
                                       "[rpm]")
        bar.ax.set_yticklabels([f"{t:.3g}" for t in ticks])
        artists.append(contour)
    artists.append(ax.scatter(f[judder], p[judder], marker="^",
                              color="#d62728", zorder=3, label="judder"))
    artists.append(ax.scatter(f[~judder], p[~judder], marker="o",
                              facecolors="none", edgecolors="black",
                              zorder=3, label="no judder"))
    boundary = chart.boundary(group)
    # the boundary is drawn only between neighbouring frequencies that
    # both have judder: a censored frequency between them breaks it
    lowest = np.array([np.nan if pb is None else pb for _, pb, _ in boundary])
    line = ax.plot([fb for fb, _, _ in boundary], lowest, color="#1f77b4",
                   lw=1.5, marker="_", ms=10, label="experimental boundary")
    artists += line
    censored = [(fb, top) for fb, pb, top in boundary if pb is None]
    if censored:
        artists.append(ax.scatter(*zip(*censored), marker="^",
                                  facecolors="none", edgecolors="#1f77b4",
                                  s=60, zorder=4,
                                  label="no judder up to here"))
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude p_f [bar]")
    label = ", ".join(f"{c} {v}" for c, v in zip(chart.group_by, group))
    ax.set_title(label or "all runs", fontsize=10)
    return artists


def chart_figure(chart, title=None):
    """All panels of a chart, one per group (Fig. 11); returns the figure
    and ``{group: ax}``."""
    groups = list(chart.groups())
    fig, axes = plt.subplots(1, max(len(groups), 1),
                             figsize=(6.5 * max(len(groups), 1), 4.8),
                             layout="constrained", squeeze=False)
    panels = {}
    for group, ax in zip(groups, axes[0]):
        plot_chart(chart, group, ax=ax)
        panels[group] = ax
    if groups:
        fig.legend(*axes[0][0].get_legend_handles_labels(), loc="outside "
                   "lower center", ncols=5, fontsize=8)
    if title:
        fig.suptitle(title)
    return fig, panels


"""Plots of experimental stability charts (Fig. 10, 11).

:func:`plot_chart` draws one group's panel on ``ax`` and returns the
artists; :func:`chart_figure` returns the figure. They draw what the
:class:`~pysim.bench.charts.Chart` holds; nothing calls
``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.criteria import JUDDER, NO_JUDDER
from infra.plotstyle import dither_axes, log_levels

__all__ = ["plot_chart", "plot_runs", "chart_figure", "runs_figure",
           "AMPLITUDE_LABEL", "ALIASED_LABEL"]


#: How a group column reads in a panel title.
_GROUP_TITLES = {"oil_temperature": "oil {} degC",
                 "engine_rpm": "{} rpm"}


#: Marker and colour of a judder run by its mechanism
#: (:attr:`pysim.bench.verdict.RunAnalysis.mechanism`).
_MECHANISM_MARKERS = {"parametric": ("^", "#d62728"),
                      "forced": ("s", "#ff7f0e"),
                      "both": ("D", "#9467bd")}


def _group_title(columns, group):
    parts = []
    for column, value in zip(columns, group):
        try:
            value = f"{float(value):g}"
        except ValueError:
            pass
        parts.append(_GROUP_TITLES.get(column, column + " {}").format(value))
    return ", ".join(parts) or "all runs"


def plot_chart(chart, group, ax=None, levels=None):
    """One panel of an experimental chart (Fig. 10): amplitude contour,
    runs and the experimental boundary, over Hz and bar.

    Parameters
    ----------
    chart : pysim.bench.charts.Chart
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
    if ax is None:
        _, ax = plt.subplots()
    runs = chart.groups()[group]
    arrays = {"freq_hz": [r.analysis.freq_hz for r in runs],
              "p_f_bar": [r.analysis.p_f_bar for r in runs],
              "amplitude_rpm": [r.analysis.amplitude_rpm for r in runs],
              "judder": [r.analysis.judder
                         and r.analysis.cannot_tell is None for r in runs],
              "mechanism": [r.analysis.mechanism or "" for r in runs],
              "dither_aliased": [r.analysis.frequency_aliased
                                 for r in runs]}
    artists = plot_runs(ax, arrays, chart.boundary(group), levels)
    ax.set_title(_group_title(chart.group_by, group), fontsize=10)
    return artists


#: The colour bar's words: what the contour shows, the largest envelope
#: of the speed's oscillation at the dither frequency or the judder
#: component's (:attr:`pysim.bench.verdict.RunAnalysis.amplitude_rpm`),
#: forced or grown.
AMPLITUDE_LABEL = "oscillation at the dither frequencies [rpm]"


#: The legend of a run whose dither frequency, estimated from the
#: pressure, may be an alias (drawn at the frequency found).
ALIASED_LABEL = ("cannot tell: frequency estimated, may be\n"
                 "an alias; not contoured, not on the boundary")


def plot_runs(ax, runs, boundary, levels=None):
    """One panel of a chart from its runs' arrays: amplitude contour, runs
    by mechanism and the experimental boundary.

    A run whose frequency was estimated and may be an alias is drawn
    apart (:data:`ALIASED_LABEL`), out of the contour, as it is out of the
    boundary (:meth:`pysim.bench.charts.Chart.set_points`): where
    it belongs is not known.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    runs : dict
        Arrays ``freq_hz``, ``p_f_bar``, ``amplitude_rpm``, ``judder``,
        ``mechanism`` and, optionally, ``dither_aliased`` (as
        :meth:`pysim.bench.charts.Chart.arrays` and a chart's NPZ
        hold them).
    boundary : list of (float, float or None, float)
        Per set point: Hz, the onset (bar, None: no judder) and the largest
        amplitude tried (:meth:`pysim.bench.charts.Chart.boundary`).
    levels : ndarray, optional
        As :func:`plot_chart`'s.
    """
    from matplotlib.colors import LogNorm
    f = np.asarray(runs["freq_hz"], dtype=float)
    p = np.asarray(runs["p_f_bar"], dtype=float)
    amplitude = np.maximum(np.asarray(runs["amplitude_rpm"], dtype=float),
                           1e-3)
    judder = np.asarray(runs["judder"], dtype=bool)
    mechanism = np.asarray(runs["mechanism"], dtype=str)
    aliased = np.asarray(runs.get("dither_aliased", np.zeros(len(f))),
                         dtype=bool)
    placed = ~aliased
    artists = []
    own = levels is None
    if own:
        levels, ticks = log_levels(amplitude.min(), amplitude.max())
    if len(np.unique(f[placed])) >= 3 and len(np.unique(p[placed])) >= 3:
        contour = ax.tricontourf(f[placed], p[placed],
                                 np.clip(amplitude[placed], levels[0],
                                         levels[-1]),
                                 levels=levels, norm=LogNorm(levels[0],
                                                             levels[-1]),
                                 cmap="Greys", alpha=0.8)
        if own:
            bar = ax.figure.colorbar(contour, ax=ax, ticks=ticks,
                                     label=AMPLITUDE_LABEL)
            bar.ax.set_yticklabels([f"{t:g}" for t in ticks])
        artists.append(contour)
    for name, (marker, colour) in _MECHANISM_MARKERS.items():
        these = placed & judder & (mechanism == name)
        if these.any():
            artists.append(ax.scatter(f[these], p[these], marker=marker,
                                      color=colour, zorder=3, clip_on=False,
                                      label=f"{JUDDER.lower()}, {name}"))
    quiet = placed & ~judder
    artists.append(ax.scatter(f[quiet], p[quiet], marker="o",
                              facecolors="none", edgecolors="black",
                              zorder=3, clip_on=False,
                              label=NO_JUDDER.lower()))
    if aliased.any():
        artists.append(ax.scatter(f[aliased], p[aliased], marker="X", s=70,
                                  color="#e377c2", zorder=3, clip_on=False,
                                  label=ALIASED_LABEL))
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
    return artists


def runs_figure(runs, boundary, title):
    """One chart panel as a figure (:func:`plot_runs`), its legend under
    it: a chart read back from its NPZ file."""
    fig, ax = plt.subplots(figsize=(8, 5.2), layout="constrained")
    plot_runs(ax, runs, boundary)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center",
               ncols=3, fontsize=8)
    ax.set_title(title, fontsize=10)
    return fig


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
    amplitudes = [r.analysis.amplitude_rpm for r in chart.read
                  if not r.analysis.frequency_aliased] or [1.0]
    levels, ticks = log_levels(min(amplitudes), max(amplitudes))
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
                       label=AMPLITUDE_LABEL)
    bar.ax.set_yscale("log")
    bar.ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
    bar.ax.minorticks_off()
    if groups:
        handles = {}
        for ax in panels.values():
            for handle, label in zip(*ax.get_legend_handles_labels()):
                handles.setdefault(label, handle)
        # a row holds as many entries as a panel's width has room for
        fig.legend(handles.values(), handles.keys(), loc="outside lower "
                   "center", ncols=min(len(handles), 2 * columns + 1),
                   fontsize=8)
    if title:
        fig.suptitle(title)
    return fig, panels

"""Plots of stability maps in the manner of Fig. 12 and Fig. 14.

Functions take an ``ax`` (a new figure is made when it is None), return the
artists they drew and never call ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from infra.units import PA_PER_BAR

from .fit_model import fit_curves
from .kinds import KINDS
from .tongues import resonances

__all__ = ["KIND_COLORS", "plot_map", "plot_growth_rate", "map_figure",
           "resonance_lines", "plot_boundaries", "tongues_figure",
           "sensitivity_figure", "plot_threshold", "plot_fit"]

#: Colour of each kind of :data:`~stability.kinds.KINDS`.
KIND_COLORS = ("#ffffff", "#d62728", "#1f77b4", "#2ca02c")


def resonance_lines(natural_frequencies_hz):
    """Frequencies where tongues start, as ``(label, hz, kind code)``."""
    return [(label, hz, kind) for _, label, hz, kind
            in resonances(natural_frequencies_hz)]


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


def plot_boundaries(boundaries, ax=None, tongues=(), style=None, label=None):
    """Boundary of each kind of tongue as lines (Fig. 16), p_f in bar.

    Parameters
    ----------
    boundaries : stability.tongues.Boundaries
    ax : matplotlib.axes.Axes, optional
    tongues : sequence of stability.tongues.Tongue
        Tips to mark and number.
    style : dict, optional
        Line properties shared by the three kinds (colour per kind unless
        ``color`` is given).
    label : str, optional
        Legend label (put on the first line drawn).

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    artists = []
    for column, kind in enumerate((1, 2, 3)):
        props = {"color": KIND_COLORS[kind], "linewidth": 1.2, **(style or {})}
        line, = ax.plot(boundaries.freq_hz,
                        boundaries.amplitude[:, column] / PA_PER_BAR, **props,
                        label=label if column == 0 else None)
        artists.append(line)
    for tongue in tongues:
        if tongue.number is None:
            continue
        artists.append(ax.plot(tongue.tip_freq_hz,
                               tongue.tip_p_f / PA_PER_BAR, "kv",
                               markersize=4)[0])
        artists.append(ax.annotate(str(tongue.number),
                                   (tongue.tip_freq_hz,
                                    tongue.tip_p_f / PA_PER_BAR),
                                   textcoords="offset points", xytext=(0, -11),
                                   ha="center", fontsize=8))
    ax.set_xlim(boundaries.freq_hz.min(), boundaries.freq_hz.max())
    ax.set_ylim(0, boundaries.p_max / PA_PER_BAR)
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    return artists


def tongues_figure(boundaries, tongues, stability_map=None, title=None):
    """Boundaries and numbered tips, over the map when one is given."""
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    if stability_map is not None:
        plot_map(stability_map, ax=ax, mark_resonances=False)
    plot_boundaries(boundaries, ax=ax, tongues=tongues,
                    style={"color": "k"} if stability_map is not None
                    else None)
    if stability_map is None:
        handles = [Patch(facecolor=KIND_COLORS[k], label=KINDS[k])
                   for k in (1, 2, 3)]
        ax.legend(handles=handles, loc="upper left", fontsize=7)
    ax.set_title(title or "tongue boundaries (numbers as in Fig. 14)")
    return fig


def sensitivity_figure(study, title=None):
    """One panel per parameter: nominal boundary and the varied ones
    (Fig. 17, Fig. 18)."""
    names = list(dict.fromkeys(c.parameter for c in study.cases))
    columns = min(3, len(names))
    rows = -(-len(names) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5 * columns, 3.4 * rows),
                             layout="constrained", squeeze=False)
    styles = ("--", ":", "-.", (0, (5, 1)), (0, (1, 3)))
    for ax, name in zip(axes.flat, names):
        _plot_lowest(study.nominal.boundaries, ax, "k", "-", "nominal")
        cases = [c for c in study.cases if c.parameter == name]
        for index, case in enumerate(cases):
            _plot_lowest(case.boundaries, ax, f"C{index}",
                         styles[index % len(styles)],
                         f"{name} = {case.value:.4g} (x{case.factor:.3g})")
        ax.set_title(name)
        ax.legend(fontsize=7, loc="upper right")
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title)
    return fig


def _plot_lowest(boundaries, ax, color, linestyle, label):
    ax.plot(boundaries.freq_hz, boundaries.stability_boundary / PA_PER_BAR,
            color=color, linestyle=linestyle, linewidth=1.1, label=label)
    ax.set_xlim(boundaries.freq_hz.min(), boundaries.freq_hz.max())
    ax.set_ylim(0, boundaries.p_max / PA_PER_BAR)
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("$p_f$ [bar]")


def plot_threshold(study, axes=None):
    """Fig. 19a (largest real part against mu_g) and 19b (threshold in the
    c_i - mu_g plane with regions A and B)."""
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    left, right = axes
    artists = [left.plot(study.mu_g, study.max_real_part, "k-")[0],
               left.axhline(0, color="0.5", linewidth=0.8),
               left.axvline(study.threshold, color="C3", linestyle="--",
                            label=f"threshold {study.threshold:.3g} s/rad")]
    left.set_xlabel(r"friction gradient $\mu_g$ [s/rad]")
    left.set_ylabel("largest real part [1/s]")
    left.set_title("without dither: unstable above the axis")
    left.legend(fontsize=8)
    left.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))
    c, mu = study.external_damping, study.thresholds
    low = min(mu.min(), study.mu_g.min())
    high = max(mu.max(), study.mu_g.max())
    artists += [right.plot(c, mu, "k-", label="threshold (python-control)")[0],
                right.plot(c, study.closed_form, "C1:",
                           label="rigid-chain closed form")[0],
                right.fill_between(c, low, mu, color="C3", alpha=0.25),
                right.fill_between(c, mu, high, color="C2", alpha=0.2)]
    right.text(c.mean(), (low + mu.min()) / 2, "A: unstable", ha="center")
    right.text(c.mean(), (high + mu.max()) / 2,
               "B: stable without dither", ha="center")
    right.set_xlabel("external damping $c_i$ [N m s/rad]")
    right.set_ylabel(r"$\mu_g$ [s/rad]")
    right.set_ylim(low, high)
    right.ticklabel_format(axis="y", style="sci", scilimits=(0, 0))
    right.legend(fontsize=8, loc="lower left")
    return artists


def plot_fit(result, ax=None):
    """Measured, first-attempt and fitted boundaries (Fig. 16a).

    As in Fig. 16a of the paper (section 4.2): the model's lowest boundary
    with the start (first attempt) values is drawn dotted, with the fitted
    values solid, both as continuous curves over a fine frequency grid;
    the measured judder onsets are markers (coloured by the kind of
    tongue each was matched to), and each censored point (no judder up
    to the largest amplitude tried) is an upward arrow at ``p_max``: no
    judder up to here.

    Parameters
    ----------
    result : stability.fitting.FitResult
        Its ``curve_freq_hz``, ``start_curve_bar`` and
        ``fitted_curve_bar`` are drawn; when they are None (a fit run with
        ``curve_points=0``) they are computed here
        (:func:`stability.fit_model.fit_curves`).
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    list of matplotlib artists
        The fitted curve first.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 4.5), layout="constrained")
    freq, start, fitted = _fit_curves(result)
    artists = [
        ax.plot(freq, fitted, "k-", linewidth=1.4,
                label="fitted model")[0],
        ax.plot(freq, start, "k:", linewidth=1.4,
                label="first attempt (start values)")[0]]
    judder = np.isfinite(result.measured_bar)
    kinds = np.array([k or "" for k in result.kinds]) if len(
        result.kinds) == len(judder) else np.full(len(judder), "")
    for kind in dict.fromkeys(kinds[judder]):
        chosen = judder & (kinds == kind)
        color = (KIND_COLORS[KINDS.index(kind)] if kind in KINDS
                 else "k")
        label = "measured judder onset" + (f" ({kind})" if kind else "")
        artists.append(ax.plot(result.freq_hz[chosen],
                               result.measured_bar[chosen], "o",
                               color=color, markeredgecolor="k",
                               label=label)[0])
    p_max = _p_max_bar(result)
    if np.any(~judder):
        artists.append(ax.plot(result.freq_hz[~judder],
                               np.full(np.count_nonzero(~judder), p_max),
                               linestyle="none", marker=r"$\uparrow$",
                               markersize=12, color="k",
                               label=f"no judder up to {p_max:g} bar")[0])
    low = min(freq.min(), result.freq_hz.min())
    high = max(freq.max(), result.freq_hz.max())
    pad = 0.015 * (high - low) if high > low else 1.0
    ax.set_xlim(low - pad, high + pad)
    ax.set_ylim(0, 1.12 * p_max)
    ax.set_xlabel("dither frequency [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    ci = getattr(result, "ci_low", None) is not None
    ax.set_title("fit: " + ", ".join(
        f"{n} = {v:.4g} ± {s:.2g}" + (f" [{lo:.4g}, {hi:.4g}]" if ci else "")
        for n, v, s, lo, hi in zip(
            result.names, result.values, result.std,
            result.ci_low if ci else result.values,
            result.ci_high if ci else result.values))
        + ("" if result.success else "  (problems: see the report)"),
        fontsize=8)
    ax.legend(fontsize=8, loc="lower right")
    return artists


def _p_max_bar(result):
    if getattr(result, "p_max_bar", None) is not None:
        return result.p_max_bar
    values = np.concatenate([result.measured_bar, result.model_bar])
    return float(np.nanmax(values)) if np.isfinite(values).any() else 1.0


def _fit_curves(result):
    """The stored start and fitted curves, or computed ones."""
    if getattr(result, "curve_freq_hz", None) is not None:
        return (result.curve_freq_hz, result.start_curve_bar,
                result.fitted_curve_bar)
    return fit_curves(result)

"""A boundary fit: measured, first-attempt and fitted boundaries
(Fig. 16a)."""

import textwrap

import matplotlib.pyplot as plt
import numpy as np

from infra.numbers import format_interval, format_uncertain
from infra.plotstyle import KIND_COLORS, dither_axes

from ..kinds import KINDS

__all__ = ["plot_fit"]


def plot_fit(result, ax=None):
    """Measured, first-attempt and fitted boundaries (Fig. 16a).

    As in Fig. 16a of the paper (section 4.2): the model's lowest boundary
    with the start (first attempt) values is drawn dotted, with the fitted
    values solid, both as continuous curves over a fine frequency grid;
    the measured judder onsets are markers (coloured by the kind of
    tongue each was matched to; an onset found on a grid of amplitudes is
    a bar between the last amplitude without and the first with judder,
    its marker at the middle, which is fitted), and each censored point
    (no judder up to the largest amplitude tried) is an upward arrow at
    ``p_max``: no judder up to here. A fit that cannot be trusted
    (``success`` False) has no values in its title, only its problems.

    Parameters
    ----------
    result : stability.fit.FitResult
        Its ``curve_freq_hz``, ``start_curve_bar`` and
        ``fitted_curve_bar`` are drawn (a fit run with ``curve_points=0``
        has none: draw ``result.with_curves()``).
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    list of matplotlib artists
        The fitted curve first.

    Raises
    ------
    ValueError
        If the result holds no curves.
    """
    if getattr(result, "curve_freq_hz", None) is None:
        raise ValueError("the fit result holds no model curves (fitted "
                         "with curve_points=0); plot result.with_curves()")
    problems = list(getattr(result, "problems", ()))
    if ax is None:
        lines = _wrapped(problems)
        fig, ax = plt.subplots(figsize=(10, 4.5 + 0.17 * len(lines)),
                               layout="constrained")
        if lines:
            share = (0.17 * len(lines) + 0.15) / (4.5 + 0.17 * len(lines))
            fig.get_layout_engine().set(rect=(0, share, 1, 1 - share))
            fig.text(0.01, share - 0.02, "\n".join(lines), fontsize=7.5,
                     va="top", color="#b00000")
    freq, start, fitted = (result.curve_freq_hz, result.start_curve_bar,
                           result.fitted_curve_bar)
    artists = [
        ax.plot(freq, fitted, "k-", linewidth=1.4,
                label="fitted model")[0],
        ax.plot(freq, start, "k:", linewidth=1.4,
                label="first attempt (start values)")[0]]
    judder = np.isfinite(result.measured_bar)
    onset = getattr(result, "onset_bar", None)
    found = np.zeros(len(judder), dtype=bool) if onset is None else \
        judder & (onset != result.measured_bar)
    if found.any():
        # the onset was found on a grid: the boundary lies between the
        # amplitude tried below it and the onset
        below = 2 * result.measured_bar[found] - onset[found]
        artists.append(ax.vlines(result.freq_hz[found], below, onset[found],
                                 color="0.45", linewidth=2.5, zorder=2,
                                 label="between the last amplitude without "
                                       "and the first with judder"))
    kinds = np.array([k or "" for k in result.kinds]) if len(
        result.kinds) == len(judder) else np.full(len(judder), "")
    for kind in dict.fromkeys(kinds[judder]):
        for on_grid in (False, True):
            chosen = judder & (kinds == kind) & (found == on_grid)
            if not chosen.any():
                continue
            color = (KIND_COLORS[KINDS.index(kind)] if kind in KINDS
                     else "k")
            label = ("middle of that interval, fitted" if on_grid
                     else "measured judder onset") + (
                         f" ({kind})" if kind else "")
            artists.append(ax.plot(result.freq_hz[chosen],
                                   result.measured_bar[chosen], "o",
                                   color=color, markeredgecolor="k",
                                   label=label)[0])
    p_max = _p_max_bar(result)
    if np.any(~judder):
        # the largest amplitude tried as a bench's grid gives it (an
        # estimated amplitude, 0.600448 bar, reads 0.6)
        artists.append(ax.plot(result.freq_hz[~judder],
                               np.full(np.count_nonzero(~judder), p_max),
                               linestyle="none", marker=r"$\uparrow$",
                               markersize=12, color="k",
                               label=f"no judder up to {p_max:.3g} bar")[0])
    low = min(freq.min(), result.freq_hz.min())
    high = max(freq.max(), result.freq_hz.max())
    pad = 0.015 * (high - low) if high > low else 1.0
    ax.set_xlim(low - pad, high + pad)
    ax.set_ylim(0, 1.12 * p_max)
    dither_axes(ax, "dither frequency [Hz]")
    # one line per value: three with their intervals overrun one line; a
    # fit that cannot be trusted shows no numbers to be copied
    if getattr(result, "success", True):
        ax.set_title("fit (Fig. 16a)\n" + "\n".join(
            _fitted_label(result, i) for i in range(len(result.names))),
            fontsize=8)
    else:
        ax.set_title("fit (Fig. 16a) of " + ", ".join(result.names)
                     + " refused: see the problems below", fontsize=8)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return artists


def _fitted_label(result, i):
    """``name = value ± std unit (1 sigma), 95 %: [low, high]`` with the
    interval's digits, or why there is no value."""
    name = result.names[i]
    specs = getattr(result.params, "specs", {})
    unit = specs[name].unit if name in specs else ""
    if name in getattr(result, "held", ()):
        return f"{name} held at {result.values[i]:.4g} (no effect)"
    if name in getattr(result, "undetermined", ()):
        return f"{name} not determined"
    value = format_uncertain(result.values[i], result.std[i], unit)
    interval = format_interval(result.ci_low[i], result.ci_high[i],
                               result.std[i])
    return f"{name} = {value} (1 sigma), 95 %: {interval}"


def _wrapped(problems, width=130):
    """The problems of a fit as lines of at most ``width`` characters."""
    lines = []
    for problem in problems:
        lines += textwrap.wrap("problem: " + problem, width,
                               subsequent_indent="    ")
    return lines


def _p_max_bar(result):
    if getattr(result, "p_max_bar", None) is not None:
        return result.p_max_bar
    values = np.concatenate([result.measured_bar, result.model_bar])
    return float(np.nanmax(values)) if np.isfinite(values).any() else 1.0

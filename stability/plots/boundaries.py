"""Tongue boundaries as lines (Fig. 14, Fig. 16): the exact tips inserted
between the grid points, each tongue closed up to ``p_max``, the tips
numbered as in Fig. 14.
"""

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import (KIND_COLORS, KIND_LINESTYLES, LABEL_GID,
                             dither_axes)
from infra.units import PA_PER_BAR

from ..kinds import KINDS

__all__ = ["boundary_curve", "plot_boundaries", "number_tips"]


def boundary_curve(freq_hz, amplitude_bar, tips=(), p_max_bar=None):
    """One kind's boundary as a drawable curve: the exact tips inserted
    between the grid frequencies, and each tongue closed up to
    ``p_max_bar`` where it leaves the searched range.

    Parameters
    ----------
    freq_hz : ndarray, shape (nf,)
    amplitude_bar : ndarray, shape (nf,)
        Lowest boundary of the kind, bar (NaN: none up to ``p_max``).
    tips : sequence of (float, float)
        ``(tip_freq_hz, tip_p_f_bar)`` of the kind's tongues.
    p_max_bar : float, optional

    Returns
    -------
    x, y : ndarray
        NaN separates the tongues.
    """
    f = np.asarray(freq_hz, dtype=float)
    a = np.asarray(amplitude_bar, dtype=float)
    tips = [(tf, tp) for tf, tp in tips if f[0] <= tf <= f[-1]]
    if tips:
        f = np.concatenate([f, [tf for tf, _ in tips]])
        a = np.concatenate([a, [tp for _, tp in tips]])
        order = np.argsort(f, kind="stable")
        f, a = f[order], a[order]
    if p_max_bar is None:
        return f, a
    xs, ys = [], []
    inside = np.isfinite(a)
    for i in range(len(f)):
        if not inside[i]:
            continue
        if i == 0 or not inside[i - 1]:
            if i > 0:
                xs += [np.nan, f[i]]
                ys += [np.nan, p_max_bar]
            else:
                xs.append(np.nan)
                ys.append(np.nan)
        xs.append(f[i])
        ys.append(a[i])
        if i + 1 < len(f) and not inside[i + 1]:
            xs.append(f[i])
            ys.append(p_max_bar)
    return np.array(xs[1:] if xs and np.isnan(xs[0]) else xs), \
        np.array(ys[1:] if ys and np.isnan(ys[0]) else ys)


def plot_boundaries(boundaries, ax=None, tongues=(), style=None, label=None,
                    numbers=True):
    """Boundary of each kind of tongue as lines (Fig. 16), p_f in bar.

    Each kind has its line style (:data:`KIND_LINESTYLES`) and, unless
    ``style`` sets ``color``, its colour; the tips of ``tongues`` are
    inserted into the curves (they are refined between grid points), and
    each tongue is closed up to ``p_max``.

    Parameters
    ----------
    boundaries : stability.tongues.Boundaries
    ax : matplotlib.axes.Axes, optional
    tongues : sequence of stability.tongues.Tongue
        Tips to insert, mark and number (Fig. 14's numbers).
    style : dict, optional
        Line properties shared by the three kinds.
    label : str, optional
        Legend label (put on the first line drawn).
    numbers : bool
        Mark and number the tips.

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    artists = []
    p_max_bar = boundaries.p_max / PA_PER_BAR
    first = True
    for column, kind in enumerate((1, 2, 3)):
        props = {"color": KIND_COLORS[kind], "linewidth": 1.2,
                 "linestyle": KIND_LINESTYLES[kind], **(style or {})}
        tips = [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR) for t in tongues
                if t.kind == KINDS[kind]]
        x, y = boundary_curve(boundaries.freq_hz,
                              boundaries.amplitude[:, column] / PA_PER_BAR,
                              tips, p_max_bar)
        if not np.isfinite(y).any():
            continue
        line, = ax.plot(x, y, **props, label=label if first else None)
        first = False
        artists.append(line)
    if numbers:
        artists += number_tips(ax, tongues, props.get("color", "k")
                                if style and "color" in style else "k")
    ax.set_xlim(boundaries.freq_hz.min(), boundaries.freq_hz.max())
    ax.set_ylim(0, p_max_bar)
    dither_axes(ax)
    return artists


def number_tips(ax, tongues, color):
    """A marker at each numbered tip and its number beside it (right),
    clear of the frequency axis; :func:`settle_labels` moves a number that
    would overlap another."""
    artists, numbers = [], []
    for tongue in tongues:
        if tongue.number is None:
            continue
        xy = (tongue.tip_freq_hz, tongue.tip_p_f / PA_PER_BAR)
        artists.append(ax.plot(*xy, marker="v", color=color,
                               markeredgecolor="k", markersize=4,
                               linestyle="none")[0])
        numbers.append(ax.annotate(
            str(tongue.number), xy, textcoords="offset points",
            xytext=(4, 1), ha="left", va="bottom", fontsize=8,
            fontweight="bold", color="k", gid=LABEL_GID,
            bbox={"boxstyle": "round,pad=0.1", "fc": "w", "ec": "none",
                  "alpha": 0.7}))
    return artists + numbers

"""Tongue boundaries as lines (Fig. 14, Fig. 16): the exact tips inserted
between the grid points, each tongue closed up to ``p_max``, the tips
numbered as in Fig. 14. A boundary is drawn where it separates stable
from unstable: where it runs inside another kind's tongue (the dither is
unstable on both sides of it there) it is left out, as the shading of
the map is.
"""

import functools

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import (KIND_COLORS, KIND_LINESTYLES, LABEL_GID,
                             UNLISTED, dither_axes)
from infra.units import PA_PER_BAR

from ..kinds import KINDS

__all__ = ["boundary_curve", "boundary_at", "plot_boundaries",
           "number_tips", "BURIED_TIP"]

#: Steps a boundary is cut into, per axis length, to find where it enters
#: another kind's tongue (1/2000 of the frequency range, 1/1000 of the
#: amplitude range: well under a line's width).
_STEPS = (2000, 1000)


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
    f, a = _with_tips(freq_hz, amplitude_bar, tips)
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


def _with_tips(freq_hz, amplitude_bar, tips):
    """The grid's boundary with the exact tips inside its range inserted,
    in order of frequency."""
    f = np.asarray(freq_hz, dtype=float)
    a = np.asarray(amplitude_bar, dtype=float)
    tips = [(tf, tp) for tf, tp in tips if f[0] <= tf <= f[-1]]
    if tips:
        f = np.concatenate([f, [tf for tf, _ in tips]])
        a = np.concatenate([a, [tp for _, tp in tips]])
        order = np.argsort(f, kind="stable")
        f, a = f[order], a[order]
    return f, a


def boundary_at(freq_hz, boundaries, column, tips):
    """One kind's lowest boundary (bar) at ``freq_hz``, as
    :func:`plot_boundaries` draws it: straight between the grid points and
    the inserted tips, NaN where a tongue is absent (its curve closes
    vertically up to ``p_max`` at its last grid point)."""
    f, a = _with_tips(boundaries.freq_hz,
                      boundaries.amplitude[:, column] / PA_PER_BAR, tips)
    i = np.clip(np.searchsorted(f, freq_hz, side="right") - 1, 0,
                len(f) - 2)
    share = (freq_hz - f[i]) / np.where(f[i + 1] > f[i], f[i + 1] - f[i], 1)
    value = a[i] + np.clip(share, 0, 1) * (a[i + 1] - a[i])
    return np.where((freq_hz >= f[0]) & (freq_hz <= f[-1]), value, np.nan)


def separating_part(x, y, others, span):
    """The part of a boundary curve that separates stable from unstable.

    Parameters
    ----------
    x, y : ndarray
        The curve (Hz, bar; NaN separates its pieces), as
        :func:`boundary_curve` gives it.
    others : sequence of callable
        ``low(freq_hz) -> bar``: the lowest boundary of each other kind
        (NaN where it has no tongue); above it that kind is unstable.
    span : (float, float)
        Frequency and amplitude ranges drawn (Hz, bar): the curve is cut
        into steps of :data:`_STEPS` of them.

    Returns
    -------
    x, y : ndarray
        The curve cut finely, NaN where it lies inside another kind's
        tongue (strictly above its lowest boundary).
    """
    xs, ys = [x[:1]], [y[:1]]
    for x0, y0, x1, y1 in zip(x[:-1], y[:-1], x[1:], y[1:]):
        steps = 1
        if np.isfinite([x0, y0, x1, y1]).all():
            steps = int(max(abs(x1 - x0) * _STEPS[0] / span[0],
                            abs(y1 - y0) * _STEPS[1] / span[1], 1))
        t = np.arange(1, steps + 1) / steps
        xs.append(x0 + t * (x1 - x0) if steps > 1 else [x1])
        ys.append(y0 + t * (y1 - y0) if steps > 1 else [y1])
    fx, fy = np.concatenate(xs), np.concatenate(ys)
    inside = np.zeros(fx.shape, dtype=bool)
    tolerance = span[1] / _STEPS[1]
    with np.errstate(invalid="ignore"):
        for low in others:
            inside |= fy > low(fx) + tolerance
    return fx, np.where(inside, np.nan, fy)


def plot_boundaries(boundaries, ax=None, tongues=(), style=None, label=None,
                    numbers=True):
    """Boundary of each kind of tongue as lines (Fig. 16), p_f in bar.

    Each kind has its line style (:data:`KIND_LINESTYLES`) and, unless
    ``style`` sets ``color``, its colour; the tips of ``tongues`` are
    inserted into the curves (they are refined between grid points), and
    each tongue is closed up to ``p_max``. A boundary is drawn only where
    it separates stable from unstable (:func:`separating_part`): inside
    another kind's tongue crossing it changes nothing.

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
    tips = {column: [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR)
                     for t in tongues if t.kind == KINDS[kind]]
            for column, kind in enumerate((1, 2, 3))}
    span = (np.ptp(boundaries.freq_hz) or 1.0, p_max_bar)
    for column, kind in enumerate((1, 2, 3)):
        props = {"color": KIND_COLORS[kind], "linewidth": 1.2,
                 "linestyle": KIND_LINESTYLES[kind], **(style or {})}
        x, y = boundary_curve(boundaries.freq_hz,
                              boundaries.amplitude[:, column] / PA_PER_BAR,
                              tips[column], p_max_bar)
        if not np.isfinite(y).any():
            continue
        x, y = separating_part(x, y, [
            functools.partial(boundary_at, boundaries=boundaries,
                              column=other, tips=tips[other])
            for other in range(3) if other != column], span)
        line, = ax.plot(x, y, **props, label=label if first else None)
        first = False
        artists.append(line)
    if numbers:
        # a tip inside another kind's tongue: that tongue's edge is not
        # drawn there (nothing changes across it), its marker is open
        buried = {id(t) for t in tongues if t.kind in KINDS
                  and any(t.tip_p_f / PA_PER_BAR > boundary_at(
                      t.tip_freq_hz, boundaries, other, tips[other])
                      * (1 + 1e-6)
                      for other in range(3)
                      if other != KINDS.index(t.kind) - 1)}
        artists += number_tips(ax, tongues, props.get("color", "k")
                                if style and "color" in style else "k",
                                buried=buried)
    ax.set_xlim(boundaries.freq_hz.min(), boundaries.freq_hz.max())
    ax.set_ylim(0, p_max_bar)
    dither_axes(ax)
    return artists


#: Legend label of an open tip marker (:func:`number_tips`).
BURIED_TIP = "tip inside another tongue\n(its edge is not drawn there)"


def number_tips(ax, tongues, color, buried=()):
    """A marker at each numbered tip and its number beside it (on the
    side with more room to the next tip), clear of the frequency axis; :func:`settle_labels` moves a number that
    would overlap another. A tongue whose ``id`` is in ``buried`` has its
    tip inside another kind's tongue: its marker is open and labelled
    :data:`BURIED_TIP` (once) for the legend."""
    artists, numbers = [], []
    labelled = False
    tips = sorted(t.tip_freq_hz for t in tongues if t.number is not None)
    for tongue in tongues:
        if tongue.number is None:
            continue
        xy = (tongue.tip_freq_hz, tongue.tip_p_f / PA_PER_BAR)
        # right of the tip, or left where the next tip to the right is
        # close and the left has more room: on the 6-DOF map of the
        # README tip 9 lies 2.5 Hz left of tip 2, and a number right of
        # it sat on tongue 2's edge (issue 46)
        others = [f - xy[0] for f in tips if f != xy[0]]
        right = min([d for d in others if d > 0], default=np.inf)
        left = min([-d for d in others if d < 0], default=np.inf)
        on_left = right < 0.03 * np.ptp(ax.get_xlim()) and left > right
        inside = id(tongue) in buried
        label = UNLISTED        # the number says what it is
        if inside and not labelled:
            label, labelled = BURIED_TIP, True
        artists.append(ax.plot(*xy, marker="v", color=color,
                               markerfacecolor="w" if inside else color,
                               markeredgecolor="k",
                               markersize=6 if inside else 4,
                               linestyle="none", label=label)[0])
        numbers.append(ax.annotate(
            str(tongue.number), xy, textcoords="offset points",
            xytext=(-4 if on_left else 4, 1),
            ha="right" if on_left else "left", va="bottom", fontsize=8,
            fontweight="bold", color="k", gid=LABEL_GID,
            bbox={"boxstyle": "round,pad=0.1", "fc": "w", "ec": "none",
                  "alpha": 0.7},
            # a leader to its tip, seen once settle_labels moves the
            # number up away from a neighbour's
            arrowprops={"arrowstyle": "-", "color": "k", "lw": 0.5,
                        "shrinkA": 0, "shrinkB": 2}))
    return artists + numbers

"""Stability maps (Fig. 12, Fig. 14): the kind of instability and the
growth rate of the leading multiplier over dither frequency and amplitude,
clipped to the exact boundaries when they are given.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from infra.plotstyle import (CONTINUOUS_CMAP, FORCED_LINE, GROWTH_LINE,
                             KIND_COLORS,
                             KIND_LINESTYLES, SLOW_COLOR, dither_axes,
                             figure_title, settle_labels)
from infra.units import PA_PER_BAR

from ..decisions.relevance import is_judder_relevant
from ..kinds import KINDS
from .boundaries import BURIED_TIP, boundary_at, plot_boundaries

__all__ = ["plot_map", "plot_growth_rate", "map_figure", "kind_legend",
           "kind_handles", "drawn_kinds", "draws_instability"]


def _edges(centres):
    centres = np.asarray(centres, dtype=float)
    if len(centres) == 1:
        return centres + np.array([-0.5, 0.5])
    mid = (centres[1:] + centres[:-1]) / 2
    return np.concatenate([[2 * centres[0] - mid[0]], mid,
                           [2 * centres[-1] - mid[-1]]])


def kind_legend(ax, kinds=(1, 2, 3), stable=True, outside=True, lines=False,
                min_growth=None, extra=()):
    """Legend of the kinds, outside the data (right of the axes) by
    default; with ``lines`` the boundary line style of each kind too; with
    ``min_growth`` the grey of the slowly growing (not judder) points;
    ``extra`` handles after them."""
    handles = kind_handles(kinds, stable, lines, min_growth) + list(extra)
    where = ({"loc": "upper left", "bbox_to_anchor": (1.01, 1.0),
              "borderaxespad": 0.0} if outside else {"loc": "best"})
    return ax.legend(handles=handles, fontsize=7, **where)


def kind_handles(kinds=(1, 2, 3), stable=True, lines=False, min_growth=None):
    """Legend handles of :func:`kind_legend`."""
    handles = []
    if stable:
        handles.append(Patch(facecolor=KIND_COLORS[0], edgecolor="k",
                             label=KINDS[0]))
    for k in kinds:
        handles.append(Patch(facecolor=KIND_COLORS[k], edgecolor="k",
                             label=KINDS[k]))
    if min_growth is not None and min_growth > 0:
        handles.append(Patch(facecolor=SLOW_COLOR, edgecolor="k",
                             label=f"unstable, grows < {min_growth:g} 1/s "
                                   "(not judder)"))
        handles.append(Line2D([], [], color="k",
                              linewidth=GROWTH_LINE["linewidths"],
                              linestyle=GROWTH_LINE["linestyles"][0],
                              label=f"judder from here (growth = "
                                    f"{min_growth:g} 1/s)"))
    if lines:
        handles += [Line2D([], [], color="k", linestyle=KIND_LINESTYLES[k],
                           label=f"{KINDS[k]} boundary "
                                 r"($|\lambda| = 1$)")
                    for k in kinds]
    return handles


def plot_map(stability_map, ax=None, mark_resonances=True, tongues=None,
             boundaries=None, legend=True, min_growth=None, forced=None,
             judder=None):
    """Regions of each kind of instability over frequency (Hz) and p_f (bar).

    Parameters
    ----------
    stability_map : stability.maps.StabilityMap
    ax : matplotlib.axes.Axes, optional
    mark_resonances : bool
        Without ``boundaries``: mark the frequencies tongues grow from
        (Fig. 14's numbering) at the top of the axes.
    tongues : sequence of stability.tongues.Tongue, optional
    boundaries : stability.tongues.Boundaries, optional
        The exact boundaries (:func:`stability.tongues.tongue_boundaries`),
        drawn over the grid cells with their tips numbered as in Fig. 14;
        without them the unit-modulus contour of the grid is drawn.
    legend : bool
        Legend of the kinds, outside the axes on the right.
    min_growth : float, optional
        1/s: shade grey the unstable points growing slower than this (not
        judder, :mod:`stability.decisions.relevance`) and outline the
        judder-relevant region.
    forced : (ndarray, ndarray, float), optional
        ``(freq_hz, p_f_bar, limit_rpm)``: where the forced oscillation
        reaches the NVH limit, drawn as a line (forced judder above it).
    judder : (Boundaries, list of Tongue), optional
        With ``boundaries`` and ``min_growth``: the exact boundaries of
        growth at ``min_growth`` and their tongues
        (:func:`stability.tongues.tongue_boundaries` with ``min_growth``),
        drawn as the judder line and shading what lies above them as
        judder, the rest of the unstable region grey; without them, the
        map's growth rate decides, linear between its points.

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    m = stability_map
    bar = m.p_f / PA_PER_BAR
    slow = min_growth is not None and min_growth > 0
    if boundaries is not None and boundaries.min_growth == 0 \
            and len(m.freq_hz) > 1 and len(bar) > 1:
        exact = judder if slow and judder is not None else None
        artists = [_exact_fill(m, boundaries, tongues or (), ax,
                               min_growth if slow else None, exact)]
        if exact is not None:
            # the judder line from the exact boundaries of growth at
            # min_growth, not a contour of the grid (issue 46)
            artists += plot_boundaries(
                exact[0], ax=ax, tongues=exact[1], numbers=False,
                style={"color": "k", "linewidth": GROWTH_LINE["linewidths"],
                       "linestyle": GROWTH_LINE["linestyles"][0]})
        elif slow:
            artists.append(ax.contour(m.freq_hz, bar, m.growth_rate.T,
                                      levels=[min_growth], **GROWTH_LINE))
    else:
        artists = [ax.pcolormesh(_edges(m.freq_hz), _edges(bar), m.kind.T,
                                 cmap=ListedColormap(KIND_COLORS),
                                 vmin=-0.5, vmax=len(KINDS) - 0.5,
                                 shading="flat", rasterized=True)]
        if slow:
            artists += _shade_slow(m, ax, min_growth)
    buried = []
    if boundaries is not None:
        drawn = plot_boundaries(boundaries, ax=ax, tongues=tongues or (),
                                style={"color": "k"})
        artists += drawn
        buried = [a for a in drawn if a.get_label() == BURIED_TIP]
        ax.set_xlim(_edges(m.freq_hz)[0], _edges(m.freq_hz)[-1])
        ax.set_ylim(0, max(bar.max(), boundaries.p_max / PA_PER_BAR))
    else:
        if len(m.freq_hz) > 1 and len(bar) > 1:
            artists.append(ax.contour(m.freq_hz, bar, m.leading_abs.T,
                                      levels=[1.0], colors="k",
                                      linewidths=0.8))
        if mark_resonances:
            artists += _resonance_marks(ax, m.resonances(),
                                        m.freq_hz.min(), m.freq_hz.max())
    if forced is not None:
        top = ax.get_ylim()[1]
        freq, level, limit = forced
        forced_line = ax.plot(freq, np.where(level <= top, level, np.nan),
                              **FORCED_LINE,
                              label=f"forced oscillation = {limit:g} rpm "
                                    "(linear):\nforced judder above")
        artists += forced_line
        ax.set_ylim(top=top)
    dither_axes(ax)
    if legend:
        # the grey of slow growth and the judder line only where
        # something is unstable: else the legend lists what is not there
        artists.append(kind_legend(
            ax, kinds=drawn_kinds(m, boundaries),
            lines=boundaries is not None,
            min_growth=min_growth if draws_instability(m, boundaries)
            else None, extra=[*buried, *(forced_line if forced is not None
                                         else ())]))
    return artists


def drawn_kinds(stability_map, boundaries=None):
    """The kinds (codes 1-3) a map draws: those of its unstable points
    and of the exact boundaries it has; the legend lists only these."""
    drawn = {int(k) for k in np.unique(stability_map.kind) if k > 0}
    if boundaries is not None:
        found = np.isfinite(boundaries.amplitude).any(axis=0)
        drawn |= {column + 1 for column in np.flatnonzero(found)}
    return tuple(sorted(drawn))


def _resonance_marks(ax, resonances, low, high):
    """Tongue numbers (Fig. 14) above the axes at the frequencies the
    tongues grow from, with a short tick."""
    artists = []
    for number, label, hz, kind in resonances:
        if low <= hz <= high:
            artists.append(ax.annotate(
                f"{number}", (hz, 1.0), xycoords=("data", "axes fraction"),
                xytext=(0, 3), textcoords="offset points", ha="center",
                va="bottom", fontsize=8, fontweight="bold"))
            artists.append(ax.axvline(hz, ymin=0.97, color="k",
                                      linewidth=0.8))
    return artists


#: Pixels of the image :func:`_exact_fill` draws (frequency, amplitude).
FILL_PIXELS = (1200, 600)


def _fine_grid(m, boundaries, tongues):
    """Pixels of an image of the map clipped to the exact boundaries.

    Returns
    -------
    extent : tuple
        ``(f0, f1, p0, p1)``, Hz and bar.
    index : tuple of ndarray
        Nearest map point of each pixel, for ``array[index]`` of an
        ``(nf, np)`` map array, giving ``(nP, nF)``.
    inside : ndarray of bool, shape (3, nP, nF)
        The pixel is on or above each kind's exact lowest boundary.
    low : ndarray, shape (3, nF)
        Those boundaries, bar (NaN: none).
    """
    bar = m.p_f / PA_PER_BAR
    f_edges, p_edges = _edges(m.freq_hz), _edges(bar)
    p_top = max(p_edges[-1], boundaries.p_max / PA_PER_BAR)
    freq = np.linspace(f_edges[0], f_edges[-1], FILL_PIXELS[0])
    amp = np.linspace(max(p_edges[0], 0.0), p_top, FILL_PIXELS[1])
    low = np.array([
        boundary_at(freq, boundaries, column,
                     [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR)
                      for t in tongues if t.kind == KINDS[kind]])
        for column, kind in enumerate((1, 2, 3))])
    with np.errstate(invalid="ignore"):
        inside = amp[None, :, None] >= low[:, None, :]
    fi = np.clip(np.searchsorted(f_edges, freq) - 1, 0, len(m.freq_hz) - 1)
    pi = np.clip(np.searchsorted(p_edges, amp) - 1, 0, len(bar) - 1)
    index = (fi[None, :], pi[:, None])
    return (freq[0], freq[-1], amp[0], amp[-1]), index, inside, low


def _pixel_rate(m, extent):
    """The growth rate (1/s) at each pixel of :func:`_fine_grid`'s image,
    shape ``(nP, nF)``: linear between the map's points (as the contour
    of ``min_growth`` is drawn), not the nearest point's, so the edge of
    slow growth follows that contour instead of the grid's staircase."""
    from scipy.interpolate import RegularGridInterpolator
    freq = np.linspace(extent[0], extent[1], FILL_PIXELS[0])
    amp = np.linspace(extent[2], extent[3], FILL_PIXELS[1])
    bar = m.p_f / PA_PER_BAR
    rate = np.nan_to_num(np.asarray(m.growth_rate, dtype=float), nan=0.0)
    interpolate = RegularGridInterpolator((m.freq_hz, bar), rate,
                                          bounds_error=False,
                                          fill_value=None)
    f, p = np.meshgrid(np.clip(freq, m.freq_hz[0], m.freq_hz[-1]),
                       np.clip(amp, bar[0], bar[-1]))
    return interpolate(np.stack([f, p], axis=-1))


def _exact_fill(m, boundaries, tongues, ax, min_growth=None, judder=None):
    """The kinds as an image clipped to the exact boundaries: inside them
    the grid's kind (nearest point), or that of the lowest boundary where
    the grid point is stable; outside them white. With ``min_growth``,
    grey where the growth rate, linear between the map's points
    (:func:`_pixel_rate`), is below it: the edge of the judder-relevant
    region is the contour drawn at ``min_growth``, not the grid's cells
    (issue 46); with ``judder`` (the exact boundaries of growth at
    ``min_growth`` and their tongues), grey below those instead."""
    extent, index, inside, low = _fine_grid(m, boundaries, tongues)
    unstable = inside.any(axis=0)
    lowest = 1 + np.argmin(np.where(inside, low[:, None, :], np.inf), axis=0)
    grid = m.kind[index]
    code = np.where(unstable, np.where(grid > 0, grid, lowest), 0)
    if min_growth is not None and judder is not None:
        above = _fine_grid(m, judder[0], judder[1])[2].any(axis=0)
        code = np.where(unstable & ~above, len(KINDS), code)
    elif min_growth is not None:
        slow = ~is_judder_relevant(_pixel_rate(m, extent), min_growth)
        code = np.where(unstable & slow, len(KINDS), code)
    colours = ListedColormap([*KIND_COLORS, SLOW_COLOR])
    return ax.imshow(code, origin="lower", aspect="auto",
                     interpolation="nearest", cmap=colours, vmin=-0.5,
                     vmax=len(KINDS) + 0.5, extent=extent)


def _shade_slow(m, ax, min_growth):
    """Grey where 0 < growth <= min_growth; a line at growth = min_growth."""
    slow = (m.kind > 0) & ~is_judder_relevant(m.growth_rate, min_growth)
    bar = m.p_f / PA_PER_BAR
    artists = [ax.pcolormesh(_edges(m.freq_hz), _edges(bar),
                             np.ma.masked_where(~slow, slow).T,
                             cmap=ListedColormap([SLOW_COLOR]),
                             shading="flat")]
    if len(m.freq_hz) > 1 and len(bar) > 1:
        artists.append(ax.contour(m.freq_hz, bar, m.growth_rate.T,
                                  levels=[min_growth], **GROWTH_LINE))
    return artists


def plot_growth_rate(stability_map, ax=None, boundaries=None, tongues=()):
    """Growth rate ``ln|lambda|/T`` (1/s) of the leading multiplier.

    Stable points are drawn white; with the exact ``boundaries`` (of the
    stability boundary) the coloured region is clipped to them, as
    :func:`plot_map` clips the kinds. Returns the artists drawn.
    """
    if ax is None:
        _, ax = plt.subplots()
    m = stability_map
    rate = np.where(m.kind > 0, m.growth_rate, np.nan)
    if not draws_instability(m, boundaries):
        # nothing to colour: a colour bar around 0 and an empty panel
        # would say nothing; the note says how stable it is
        dither_axes(ax)
        _set_extent(ax, m, boundaries)
        return [_note(ax, "no unstable point: the leading multiplier's "
                      "growth rate is\n" + _growth_span(m.growth_rate)
                      + " 1/s (decays)")]
    if boundaries is not None and boundaries.min_growth == 0 \
            and len(m.freq_hz) > 1 and len(m.p_f) > 1:
        extent, index, inside, _ = _fine_grid(m, boundaries, tongues)
        # inside the exact boundaries, linear between the map's points
        # (no grid staircase) and at least 0 (it grows there)
        image = np.where(inside.any(axis=0),
                         np.maximum(_pixel_rate(m, extent), 0.0), np.nan)
        mesh = ax.imshow(image, origin="lower", aspect="auto",
                         interpolation="nearest", cmap=CONTINUOUS_CMAP,
                         extent=extent)
    else:
        mesh = ax.pcolormesh(_edges(m.freq_hz), _edges(m.p_f / PA_PER_BAR),
                             rate.T, cmap=CONTINUOUS_CMAP, shading="flat",
                             rasterized=True)
    bar = ax.figure.colorbar(mesh, ax=ax, label="growth rate [1/s]")
    dither_axes(ax)
    return [mesh, bar]


def draws_instability(m, boundaries=None):
    """Whether a map draws an instability: an unstable point, or an
    exact boundary below its top (a tongue); legends list the shading of
    slow growth and the judder line only then."""
    return bool((m.kind > 0).any()) or (
        boundaries is not None and bool(np.isfinite(
            boundaries.amplitude).any()))


def _top_bar(m, boundaries):
    """The largest amplitude of the map or its boundaries, bar."""
    top = float(np.max(m.p_f)) / PA_PER_BAR
    return top if boundaries is None else max(
        top, boundaries.p_max / PA_PER_BAR)


def _set_extent(ax, m, boundaries):
    """The axes over the map's frequencies and 0 to its top amplitude."""
    edges = _edges(m.freq_hz)
    ax.set_xlim(edges[0], edges[-1])
    ax.set_ylim(0, _top_bar(m, boundaries) or 1.0)


def _growth_span(rate):
    """``-0.0625`` or ``-0.4 to -0.0625``: the range of the finite growth
    rates (1/s), to 3 digits."""
    low, high = np.nanmin(rate), np.nanmax(rate)
    return f"{high:.3g}" if f"{low:.3g}" == f"{high:.3g}" else \
        f"{low:.3g} to {high:.3g}"


def _note(ax, text):
    """``text`` in the middle of an axes that has nothing else to show."""
    return ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center",
                   va="center", fontsize=9, color="#333333", wrap=True)


def map_figure(stability_map, title=None, tongues=None, boundaries=None,
               min_growth=None, stacked=False, forced=None, judder=None):
    """Figure with the kinds (left, with the exact boundaries and tongue
    numbers when given, slowly growing points grey with ``min_growth``)
    and the growth rate (right; below with ``stacked``, for a page).
    ``forced``: ``(freq_hz, p_f_bar, limit_rpm)``, the amplitude at which
    the forced oscillation reaches the limit at each frequency, drawn on
    the left (forced judder above it); ``judder``: the exact boundaries of
    growth at ``min_growth`` and their tongues (:func:`plot_map`)."""
    fig, (left, right) = plt.subplots(
        *((2, 1) if stacked else (1, 2)),
        figsize=(9, 8.6) if stacked else (14, 5), layout="constrained")
    plot_map(stability_map, ax=left, tongues=tongues, boundaries=boundaries,
             min_growth=min_growth, forced=forced, judder=judder)
    if not draws_instability(stability_map, boundaries):
        _set_extent(left, stability_map, boundaries)
        _note(left, "stable at every point: every multiplier inside the "
              "unit circle\n(no tongue reaches "
              f"{_top_bar(stability_map, boundaries):g} bar)")
    plot_growth_rate(stability_map, ax=right, boundaries=boundaries,
                     tongues=tongues or ())
    if boundaries is not None:
        plot_boundaries(boundaries, ax=right, tongues=tongues,
                        style={"color": "k", "linewidth": 0.8})
        right.set_xlim(left.get_xlim())
        right.set_ylim(left.get_ylim())
    left.set_title("kind of instability (leading Floquet multiplier)",
                   fontsize=10)
    right.set_title(r"growth rate $\ln|\lambda|/T$ of the leading "
                    "multiplier", fontsize=10)
    if title:
        figure_title(fig, title)
    settle_labels(fig)
    return fig

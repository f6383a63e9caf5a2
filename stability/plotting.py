"""Plots of stability maps in the manner of Fig. 12 and Fig. 14.

Functions take an ``ax`` (a new figure is made when it is None), return the
artists they drew and never call ``plt.show()``.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from infra.numbers import readable_number
from infra.units import PA_PER_BAR

from .fit_model import fit_curves
from .kinds import KINDS
from .tongues import resonances

__all__ = ["KIND_COLORS", "KIND_LINESTYLES", "plot_map", "plot_growth_rate", "map_figure",
           "resonance_lines", "plot_boundaries", "tongues_figure",
           "sensitivity_figure", "plot_threshold", "plot_fit",
           "check_figure", "advice_figure", "plot_multipliers",
           "multipliers_figure", "boundary_curve", "kind_legend",
           "figure_title", "settle_labels"]

#: Colour of each kind of :data:`~stability.kinds.KINDS`: white, then a
#: dark blue, Okabe-Ito vermillion and orange, which colour-blind readers
#: tell apart and which stay apart in greyscale, with the grey of the
#: slowly growing points (:data:`SLOW_COLOR`) between them: greyscale
#: luminance (ITU-R 601) 1.00, 0.28, 0.47, 0.64 and 0.82, every pair at
#: least 0.15 apart (tests/test_figures.py).
KIND_COLORS = ("#ffffff", "#1f4e99", "#d55e00", "#e69f00")

#: Colour of the unstable points that grow too slowly to be judder.
SLOW_COLOR = "#d0d0d0"

#: Line of growth = min_growth (the edge of the judder-relevant region):
#: dash-dot, a style no kind's boundary uses.
GROWTH_LINE = {"colors": "k", "linewidths": 1.3,
               "linestyles": [(0, (7, 2, 1.5, 2))]}

#: Line style of each kind's boundary, so kinds differ without colour.
KIND_LINESTYLES = ("-", "-", "--", (0, (1, 1.5)))

#: Colour map of continuous quantities (growth rates): cividis, made to
#: read the same in colour, greyscale and with colour-vision deficiency,
#: stopped at 80 % so its brightest colour (greyscale luminance 0.71)
#: stays apart from the white of stable points.
CONTINUOUS_CMAP = ListedColormap(
    plt.get_cmap("cividis")(np.linspace(0.0, 0.8, 256)), name="cividis80")


def figure_title(fig, title, fontsize=11):
    """``fig.suptitle(title)``, wrapped onto lines that fit the figure's
    width (a long model description is not clipped)."""
    import textwrap
    # DejaVu Sans averages about 0.55 em a character
    width = max(20, int(fig.get_figwidth() * 72 / (0.58 * fontsize)))
    return fig.suptitle(textwrap.fill(title, width), fontsize=fontsize)


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


def kind_legend(ax, kinds=(1, 2, 3), stable=True, outside=True, lines=False,
                min_growth=None):
    """Legend of the kinds, outside the data (right of the axes) by
    default; with ``lines`` the boundary line style of each kind too; with
    ``min_growth`` the grey of the slowly growing (not judder) points."""
    handles = _kind_handles(kinds, stable, lines, min_growth)
    where = ({"loc": "upper left", "bbox_to_anchor": (1.01, 1.0),
              "borderaxespad": 0.0} if outside else {"loc": "best"})
    return ax.legend(handles=handles, fontsize=7, **where)


def _kind_handles(kinds=(1, 2, 3), stable=True, lines=False, min_growth=None):
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
                             label=f"grows < {min_growth:g} 1/s (not judder)"))
        handles.append(Line2D([], [], color="k",
                              linewidth=GROWTH_LINE["linewidths"],
                              linestyle=GROWTH_LINE["linestyles"][0],
                              label=f"growth = {min_growth:g} 1/s"))
    if lines:
        handles += [Line2D([], [], color="k", linestyle=KIND_LINESTYLES[k],
                           label=f"{KINDS[k]} boundary") for k in kinds]
    return handles


def plot_map(stability_map, ax=None, mark_resonances=True, tongues=None,
             boundaries=None, legend=True, min_growth=None):
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
        judder, :mod:`stability.relevance`) and outline the
        judder-relevant region.

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
        artists = [_exact_fill(m, boundaries, tongues or (), ax,
                               min_growth if slow else None)]
        if slow:
            artists.append(ax.contour(m.freq_hz, bar, m.growth_rate.T,
                                      levels=[min_growth], **GROWTH_LINE))
    else:
        artists = [ax.pcolormesh(_edges(m.freq_hz), _edges(bar), m.kind.T,
                                 cmap=ListedColormap(KIND_COLORS),
                                 vmin=-0.5, vmax=len(KINDS) - 0.5,
                                 shading="flat", rasterized=True)]
        if slow:
            artists += _shade_slow(m, ax, min_growth)
    if boundaries is not None:
        artists += plot_boundaries(boundaries, ax=ax, tongues=tongues or (),
                                   style={"color": "k"})
        ax.set_xlim(_edges(m.freq_hz)[0], _edges(m.freq_hz)[-1])
        ax.set_ylim(0, max(bar.max(), boundaries.p_max / PA_PER_BAR))
    else:
        if len(m.freq_hz) > 1 and len(bar) > 1:
            artists.append(ax.contour(m.freq_hz, bar, m.leading_abs.T,
                                      levels=[1.0], colors="k",
                                      linewidths=0.8))
        if mark_resonances:
            artists += _resonance_marks(ax, m.natural_frequencies_hz,
                                        m.freq_hz.min(), m.freq_hz.max())
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    if legend:
        artists.append(kind_legend(ax, lines=boundaries is not None,
                                   min_growth=min_growth))
    return artists


def _resonance_marks(ax, natural_frequencies_hz, low, high):
    """Tongue numbers (Fig. 14) above the axes at the frequencies the
    tongues grow from, with a short tick."""
    artists = []
    for number, label, hz, kind in resonances(natural_frequencies_hz):
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


def _boundary_at(freq_hz, boundaries, column, tips):
    """One kind's lowest boundary (bar) at ``freq_hz``, as
    :func:`plot_boundaries` draws it: straight between the grid points and
    the inserted tips, NaN where a tongue is absent (its curve closes
    vertically up to ``p_max`` at its last grid point)."""
    f = boundaries.freq_hz
    a = boundaries.amplitude[:, column] / PA_PER_BAR
    if tips:
        f = np.concatenate([f, [tf for tf, _ in tips]])
        a = np.concatenate([a, [tp for _, tp in tips]])
        order = np.argsort(f, kind="stable")
        f, a = f[order], a[order]
    i = np.clip(np.searchsorted(f, freq_hz, side="right") - 1, 0,
                len(f) - 2)
    share = (freq_hz - f[i]) / np.where(f[i + 1] > f[i], f[i + 1] - f[i], 1)
    value = a[i] + np.clip(share, 0, 1) * (a[i + 1] - a[i])
    return np.where((freq_hz >= f[0]) & (freq_hz <= f[-1]), value, np.nan)


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
        _boundary_at(freq, boundaries, column,
                     [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR)
                      for t in tongues if t.kind == KINDS[kind]])
        for column, kind in enumerate((1, 2, 3))])
    with np.errstate(invalid="ignore"):
        inside = amp[None, :, None] >= low[:, None, :]
    fi = np.clip(np.searchsorted(f_edges, freq) - 1, 0, len(m.freq_hz) - 1)
    pi = np.clip(np.searchsorted(p_edges, amp) - 1, 0, len(bar) - 1)
    index = (fi[None, :], pi[:, None])
    return (freq[0], freq[-1], amp[0], amp[-1]), index, inside, low


def _exact_fill(m, boundaries, tongues, ax, min_growth=None):
    """The kinds as an image clipped to the exact boundaries: inside them
    the grid's kind (nearest point), or that of the lowest boundary where
    the grid point is stable; outside them white. With ``min_growth``,
    the slowly growing points grey (a stable grid point inside the exact
    boundaries counts as slow: it grows at about 0 there)."""
    from .relevance import is_judder_relevant
    extent, index, inside, low = _fine_grid(m, boundaries, tongues)
    unstable = inside.any(axis=0)
    lowest = 1 + np.argmin(np.where(inside, low[:, None, :], np.inf), axis=0)
    grid = m.kind[index]
    code = np.where(unstable, np.where(grid > 0, grid, lowest), 0)
    if min_growth is not None:
        slow = ~is_judder_relevant(m.growth_rate, min_growth)
        code = np.where(unstable & (slow[index] | (grid == 0)),
                        len(KINDS), code)
    colours = ListedColormap([*KIND_COLORS, SLOW_COLOR])
    return ax.imshow(code, origin="lower", aspect="auto",
                     interpolation="nearest", cmap=colours, vmin=-0.5,
                     vmax=len(KINDS) + 0.5, extent=extent)


def _shade_slow(m, ax, min_growth):
    """Grey where 0 < growth <= min_growth; a line at growth = min_growth."""
    from .relevance import is_judder_relevant
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


#: Marker and colour of each verdict word
#: (:data:`stability.relevance.VERDICTS`): shape tells them apart without
#: colour; the colours are dark enough to read on every kind's fill.
VERDICT_MARKERS = {"JUDDER": ("X", "#b2182b"),
                   "SLOW GROWTH": ("s", "#404040"),
                   "STABLE": ("o", "#1b7837")}


def check_figure(records, background=None, min_growth=None, title=None):
    """Settings of ``judder check`` marked on the map (or alone).

    Each setting is a marker of its verdict (:data:`VERDICT_MARKERS`, in
    the legend) annotated with both margins to judder (bar, Hz; positive
    = safe).

    Parameters
    ----------
    records : list of dict
        :func:`judder.results.setting_record` fields (Hz, bar).
    background : stability.maps.StabilityMap, optional
    min_growth : float, optional
        Passed to :func:`plot_map`.
    title : str, optional
        The model, after "dither settings: verdict and margins".
    """
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    handles = []
    if background is not None:
        plot_map(background, ax=ax, min_growth=min_growth, legend=False)
        handles = _kind_handles(min_growth=min_growth)
    seen = {}
    for r in records:
        marker, color = VERDICT_MARKERS[r["verdict"]]
        line, = ax.plot(r["freq_hz"], r["p_f_bar"], marker=marker,
                        color=color, markeredgecolor="w", markersize=10,
                        markeredgewidth=1.2, linestyle="none",
                        label=f"setting: {r['verdict']}", clip_on=False)
        seen.setdefault(r["verdict"], line)
        hz, bar = r["margin_hz"], r["margin_bar"]
        text = (("" if bar is None else f"{bar:+.3f} bar\n")
                + ("" if hz is None else f"{hz:+.2f} Hz"))
        if text:
            ax.annotate(text.strip(), (r["freq_hz"], r["p_f_bar"]),
                        xytext=(7, 7), textcoords="offset points", fontsize=7,
                        gid=LABEL_GID, bbox={"boxstyle": "round,pad=0.15",
                                             "fc": "w", "ec": "none",
                                             "alpha": 0.8})
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    ax.legend(handles=handles + list(seen.values()), fontsize=7,
              loc="upper left", bbox_to_anchor=(1.01, 1.0),
              borderaxespad=0.0)
    ax.set_title("dither settings: verdict and margins"
                 + (f", {title}" if title else ""),
                 fontsize=10, pad=16 if background is not None else 6)
    settle_labels(fig)
    return fig


#: ``gid`` of the texts :func:`settle_labels` keeps apart: tongue numbers
#: and the margin notes of ``judder check``.
LABEL_GID = "judder-label"


def settle_labels(fig):
    """Lay the figure out, then move each tongue number or margin note
    (texts with ``gid`` :data:`LABEL_GID`) up until it overlaps none placed
    before it in its axes: nearby tips and settings keep readable labels.
    Figure builders call it last, once the axes have their final size."""
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        notes = sorted((t for t in ax.texts if t.get_gid() == LABEL_GID),
                       key=lambda t: t.xy[0])
        placed = []
        for note in notes:
            for _ in range(20):
                box = note.get_window_extent(renderer)
                if not any(_overlap(box, other) for other in placed):
                    break
                dx, dy = note.xyann
                note.xyann = (dx, dy + box.height * 72.0 / fig.dpi + 2)
            placed.append(note.get_window_extent(renderer))


def _overlap(one, other, slack=1.0):
    """Two boxes (pixels) share more than ``slack`` in both directions."""
    return (min(one.x1, other.x1) - max(one.x0, other.x0) > slack
            and min(one.y1, other.y1) - max(one.y0, other.y0) > slack)


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
    if boundaries is not None and boundaries.min_growth == 0 \
            and len(m.freq_hz) > 1 and len(m.p_f) > 1:
        extent, index, inside, _ = _fine_grid(m, boundaries, tongues)
        # inside the exact boundaries, a stable grid point grows at ~0
        image = np.where(inside.any(axis=0),
                         np.nan_to_num(rate[index], nan=0.0), np.nan)
        mesh = ax.imshow(image, origin="lower", aspect="auto",
                         interpolation="nearest", cmap=CONTINUOUS_CMAP,
                         extent=extent)
    else:
        mesh = ax.pcolormesh(_edges(m.freq_hz), _edges(m.p_f / PA_PER_BAR),
                             rate.T, cmap=CONTINUOUS_CMAP, shading="flat",
                             rasterized=True)
    bar = ax.figure.colorbar(mesh, ax=ax, label="growth rate [1/s]")
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    return [mesh, bar]


def map_figure(stability_map, title=None, tongues=None, boundaries=None,
               min_growth=None, stacked=False):
    """Figure with the kinds (left, with the exact boundaries and tongue
    numbers when given, slowly growing points grey with ``min_growth``)
    and the growth rate (right; below with ``stacked``, for a page)."""
    fig, (left, right) = plt.subplots(
        *((2, 1) if stacked else (1, 2)),
        figsize=(9, 8.6) if stacked else (14, 5), layout="constrained")
    plot_map(stability_map, ax=left, tongues=tongues, boundaries=boundaries,
             min_growth=min_growth)
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
        artists += _number_tips(ax, tongues, props.get("color", "k")
                                if style and "color" in style else "k")
    ax.set_xlim(boundaries.freq_hz.min(), boundaries.freq_hz.max())
    ax.set_ylim(0, p_max_bar)
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("dither amplitude $p_f$ [bar]")
    return artists


def _number_tips(ax, tongues, color):
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


def tongues_figure(boundaries, tongues, stability_map=None, title=None,
                   min_growth=None):
    """Boundaries and numbered tips, over the map when one is given (its
    points growing slower than ``min_growth``, 1/s, grey)."""
    fig, ax = plt.subplots(figsize=(10, 5), layout="constrained")
    if stability_map is not None:
        plot_map(stability_map, ax=ax, tongues=tongues,
                 boundaries=boundaries, min_growth=min_growth)
    else:
        plot_boundaries(boundaries, ax=ax, tongues=tongues)
        handles = [Line2D([], [], color=KIND_COLORS[k],
                          linestyle=KIND_LINESTYLES[k], label=KINDS[k])
                   for k in (1, 2, 3)]
        ax.legend(handles=handles, loc="upper left", fontsize=7,
                  bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax.set_title(title or "tongue boundaries (numbers as in Fig. 14)",
                 fontsize=10)
    settle_labels(fig)
    return fig


#: Line styles of the varied cases of a sensitivity panel, after the
#: nominal solid line: long dashes, then dash-dot, dots, dash-dot-dot.
CASE_STYLES = ((0, (6, 2)), (0, (4, 1.5, 1, 1.5)), (0, (1, 1.2)),
               (0, (5, 1.5, 1, 1.5, 1, 1.5)))


def sensitivity_figure(study, title=None, params=None):
    """One panel per parameter: nominal boundary and the varied ones
    (Fig. 17, Fig. 18).

    Each curve is the lowest boundary with the tongue tips inserted and
    the tongues closed up to ``p_max``; the cases differ in colour
    (cividis) and line style. ``params`` (the nominal set) adds the
    damping factor zeta_12 (Eq. 16) to the labels of c12.
    """
    names = list(dict.fromkeys(c.parameter for c in study.cases))
    columns = min(2 if len(names) in (2, 4, 8) else 3, len(names))
    rows = -(-len(names) // columns)
    fig = plt.figure(figsize=(5.2 * columns, 3.3 * rows + 0.8),
                     layout="constrained")
    axes = fig.subplots(rows, columns, squeeze=False)
    for ax in list(axes.flat)[len(names):]:
        ax.remove()
    for ax, name in zip(axes.flat, names):
        # a case at the nominal value is the nominal line: drawn once
        cases = [c for c in study.cases if c.parameter == name
                 and not np.isclose(c.factor, 1.0, rtol=1e-9, atol=0)]
        colours = plt.get_cmap(CONTINUOUS_CMAP)(
            np.linspace(0.15, 0.8, max(len(cases), 1)))
        _plot_lowest(study.nominal, ax, "k", "-", "nominal", lw=1.6)
        # Fig. 14's numbers, at the tips the nominal curve reaches
        _number_tips(ax, _tips_on_lowest(study.nominal), "k")
        for index, case in enumerate(cases):
            _plot_lowest(case, ax, colours[index],
                         CASE_STYLES[index % len(CASE_STYLES)],
                         _case_label(name, case, params), lw=1.3)
        ax.set_title(_panel_title(name, params), fontsize=9)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                  borderaxespad=0.2, handlelength=3)
    if title:
        figure_title(fig, title)
    settle_labels(fig)
    return fig


def _is_damper(name, params):
    """``name`` is the damping of the clutch damper of a registry
    driveline (Eq. 16 applies; a Modelica class or an FMU has no such
    role)."""
    return (params is not None and params.source_kind.is_chain
            and name == params.driveline.clutch_damper.damping)


def _zeta_percent(params, name, value):
    from .modal import clutch_damper_damping_factor
    return 100 * float(clutch_damper_damping_factor(
        params.replace(**{name: value})))


def _panel_title(name, params):
    unit = params.specs[name].unit if params is not None else ""
    text = f"{name}" + (f" [{unit}]" if unit and unit != "1" else "")
    if params is not None:
        text += f", nominal {readable_number(params[name])}"
        if _is_damper(name, params):
            text += (rf" ($\zeta_{{12}}$ = "
                     f"{_zeta_percent(params, name, params[name]):.2g} %)")
    return text


def _case_label(name, case, params):
    label = f"{name} = {readable_number(case.value)} (x{case.factor:.3g})"
    if _is_damper(name, params):
        label += (rf", $\zeta_{{12}}$ = "
                  f"{_zeta_percent(params, name, case.value):.2g} %")
    return label


def _tips_on_lowest(case):
    """The tongues of a case whose tip is on its lowest boundary: not
    above the lowest boundary around it (another tongue's may be lower
    there, and the tip is then hidden)."""
    b = case.boundaries
    lowest = b.stability_boundary / PA_PER_BAR
    return [t for t in case.tongues
            if not np.interp(t.tip_freq_hz, b.freq_hz, lowest)
            < t.tip_p_f / PA_PER_BAR * (1 - 1e-9)]


def _plot_lowest(case, ax, color, linestyle, label, lw=1.1):
    """A case's lowest boundary with its tips inserted, closed at p_max."""
    b = case.boundaries
    p_max_bar = b.p_max / PA_PER_BAR
    lowest = b.stability_boundary / PA_PER_BAR
    tips = [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR)
            for t in _tips_on_lowest(case)]
    x, y = boundary_curve(b.freq_hz, lowest,
                          tips, p_max_bar)
    ax.plot(x, y, color=color, linestyle=linestyle, linewidth=lw,
            label=label)
    ax.set_xlim(b.freq_hz.min(), b.freq_hz.max())
    ax.set_ylim(0, p_max_bar)
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("$p_f$ [bar]")


def plot_threshold(study, axes=None, own=None):
    """Fig. 19a (largest real part against mu_g) and 19b (threshold in the
    c_i - mu_g plane with regions A and B).

    ``own = (c_i, mu_g)`` marks the driveline's own external damping and
    friction gradient (N m s/rad, s/rad): a point where it lies inside the
    axes, else an arrow at the edge towards it, with its value.
    """
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    left, right = axes
    artists = [left.plot(study.mu_g, study.max_real_part, "k-")[0],
               left.axhline(0, color="0.5", linewidth=0.8),
               left.axvline(study.threshold, color="k", linestyle="--",
                            label=rf"threshold $\mu_g^*$ = "
                                  f"{study.threshold:.3g} s/rad")]
    left.set_xlabel(r"friction gradient $\mu_g$ [s/rad]")
    left.set_ylabel("largest real part [1/s]")
    left.set_title("without dither: unstable above 0", fontsize=10)
    left.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))
    c, mu = study.external_damping, study.thresholds
    low = min(mu.min(), study.mu_g.min())
    high = max(mu.max(), study.mu_g.max())
    artists += [right.fill_between(c, low, mu, color="#d55e00", alpha=0.3,
                                   linewidth=0),
                right.fill_between(c, mu, high, color="#1f4e99", alpha=0.15,
                                   linewidth=0),
                right.plot(c, mu, "k-", label=r"threshold $\mu_g^*$ "
                           "(eigenvalues)")[0],
                right.plot(c, study.closed_form, linestyle="none",
                           marker="o", mfc="w", mec="k", ms=4,
                           markevery=max(1, len(c) // 10),
                           label="rigid-chain closed form")[0]]
    right.text(c.mean(), (low + mu.min()) / 2, "A: unstable", ha="center")
    right.text(c.mean(), (high + mu.max()) / 2,
               "B: stable without dither", ha="center")
    right.set_xlabel("external damping $c_i$ [N m s/rad]")
    right.set_ylabel(r"$\mu_g$ [s/rad]")
    right.set_ylim(low, high)
    right.set_title(r"threshold against the external damping", fontsize=10)
    right.ticklabel_format(axis="y", style="sci", scilimits=(0, 0))
    if own is not None:
        artists += _mark_own(left, right, own, (low, high))
    for ax in (left, right):
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0, -0.2),
                  borderaxespad=0.0, frameon=False)
    return artists


def _mark_own(left, right, own, limits):
    """The driveline's own (c_i, mu_g) on Fig. 19: a point (right) and a
    line (left) where inside the axes, else an arrow at the edge."""
    c_own, mu_own = own
    label = rf"this driveline: $\mu_g$ = {mu_own:.3g} s/rad"
    low, high = limits
    artists = []
    if low <= mu_own <= high:
        artists.append(right.plot(c_own, mu_own, marker="*", ms=12,
                                  color="k", linestyle="none",
                                  label=label)[0])
        artists.append(left.axvline(mu_own, color="k", linestyle=":",
                                    label=label))
        return artists
    up = mu_own > high
    for ax, x in ((right, c_own), (left, high if up else low)):
        y = 0.97 if up else 0.03
        artists.append(ax.annotate(
            label + (" (above)" if up else " (below)"),
            xy=(x, y), xycoords=("data", "axes fraction"),
            xytext=(-8 if ax is left else 8, -22 if up else 22),
            textcoords="offset points", fontsize=8,
            ha="right" if ax is left else "left",
            va="top" if up else "bottom",
            arrowprops={"arrowstyle": "->", "color": "k"}))
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
    freq, start, fitted = _fit_curves(result)
    artists = [
        ax.plot(freq, fitted, "k-", linewidth=1.4,
                label="fitted model")[0],
        ax.plot(freq, start, "k:", linewidth=1.4,
                label="first attempt (start values)")[0]]
    judder = np.isfinite(result.measured_bar)
    onset = getattr(result, "onset_bar", None)
    if onset is not None and np.any(judder & (onset != result.measured_bar)):
        # the onset was found on a grid: the boundary lies between the
        # amplitude tried below it and the onset
        found = judder & (onset != result.measured_bar)
        below = 2 * result.measured_bar[found] - onset[found]
        artists.append(ax.vlines(result.freq_hz[found], below, onset[found],
                                 color="0.45", linewidth=2.5, zorder=2,
                                 label="onset between these amplitudes "
                                       "(fitted to the middle)"))
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
    # one line per value: three with their intervals overrun one line
    ax.set_title("fit (Fig. 16a)\n" + "\n".join(
        _fitted_label(result, i) for i in range(len(result.names))),
        fontsize=8)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return artists


def _fitted_label(result, i):
    """``name = value ± std unit, 95 %: [low, high]`` with the interval's
    digits, or why there is no value."""
    from infra.numbers import format_interval, format_uncertain
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
    return f"{name} = {value}, 95 %: {interval}"


def _wrapped(problems, width=130):
    """The problems of a fit as lines of at most ``width`` characters."""
    import textwrap
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


def _fit_curves(result):
    """The stored start and fitted curves, or computed ones."""
    if getattr(result, "curve_freq_hz", None) is not None:
        return (result.curve_freq_hz, result.start_curve_bar,
                result.fitted_curve_bar)
    return fit_curves(result)


def advice_figure(advice, title=None):
    """Safe amplitude per frequency (left) and the recomputed map of the
    advised design (right, if any).

    Parameters
    ----------
    advice : judder.results.AdviceResult
    """
    if advice.verification is None:
        fig, left = plt.subplots(figsize=(7, 5), layout="constrained")
    else:
        fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5),
                                          layout="constrained")
    op = advice.operating
    inside = ((advice.freq_hz >= op.freq_hz[0])
              & (advice.freq_hz <= op.freq_hz[1]))
    left.fill_between(advice.freq_hz[inside], 0,
                      advice.safe_p_f[inside] / PA_PER_BAR, color="#2ca02c",
                      alpha=0.5, label="safe (with margins)")
    left.axhline(op.p_max / PA_PER_BAR, color="k", linestyle="--",
                 linewidth=0.8, label="operating amplitude")
    for edge in op.freq_hz:
        left.axvline(edge, color="k", linestyle=":", linewidth=0.8)
    left.set_xlabel("dither frequency [Hz]")
    left.set_ylabel("safe dither amplitude $p_f$ [bar]")
    left.set_title("safe dither windows, given design", fontsize=10)
    left.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13),
                ncols=2, frameon=False, borderaxespad=0.0)
    if advice.verification is not None:
        plot_map(advice.verification, ax=right,
                 min_growth=advice.min_growth)
        # above the tongue numbers that head the axes
        right.set_title(f"advised design: {advice.judder_points} "
                        "judder-relevant points", fontsize=10, pad=16)
    figure_title(fig, "judder advise: safe dither windows and the advised "
                 "design" + (f", {title}" if title else ""))
    settle_labels(fig)
    return fig


def plot_multipliers(result, ax=None, zoom=False):
    """Floquet multipliers on the complex plane with the unit circle
    (Fig. 15), the leading one marked in the colour of its kind.

    Parameters
    ----------
    result : stability.floquet.FloquetResult
    ax : matplotlib.axes.Axes, optional
    zoom : bool
        Show only the neighbourhood of the leading multiplier (the paper's
        Fig. 15 is "not to scale" for that reason: the leading multiplier
        is a few per cent outside the circle).

    Returns
    -------
    list of matplotlib artists
    """
    if ax is None:
        _, ax = plt.subplots()
    from .kinds import KINDS as names
    lam = np.asarray(result.multipliers)
    lead = complex(result.leading)
    code = names.index(result.kind)
    theta = np.linspace(0, 2 * np.pi, 721)
    artists = [ax.plot(np.cos(theta), np.sin(theta), color="0.35", lw=0.9,
                       label="unit circle")[0],
               ax.axhline(0, color="0.7", lw=0.6),
               ax.axvline(0, color="0.7", lw=0.6)]
    leading = np.isclose(lam, lead) | np.isclose(lam, np.conj(lead))
    artists.append(ax.plot(lam.real[~leading], lam.imag[~leading], "o",
                           mfc="w", mec="k", ms=5,
                           label="other multipliers")[0])
    artists.append(ax.plot(lam.real[leading], lam.imag[leading], "D",
                           color=KIND_COLORS[code] if code else "0.5",
                           mec="k", ms=7,
                           label=f"leading: {result.kind}, "
                                 rf"$|\lambda|$ = {result.leading_abs:.4f}"
                           )[0])
    if zoom:
        span = max(4 * abs(result.leading_abs - 1), 0.02)
        centre = lead if abs(lead.imag) < 1e-12 else complex(
            lead.real, abs(lead.imag))
        ax.set_xlim(centre.real - span, centre.real + span)
        ax.set_ylim(centre.imag - span, centre.imag + span)
    else:
        reach = max(1.15, 1.05 * np.abs(lam).max())
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.set_xlabel(r"Re $\lambda$ [-]")
    ax.set_ylabel(r"Im $\lambda$ [-]")
    return artists


def multipliers_figure(results, title=None):
    """Fig. 15: one column per Floquet result, the whole plane above and
    the leading multiplier's neighbourhood below.

    Parameters
    ----------
    results : sequence of stability.floquet.FloquetResult
    """
    results = list(results)
    if len(results) == 1:       # one setting: the two views side by side
        fig, pair = plt.subplots(1, 2, figsize=(9.0, 4.8),
                                 layout="constrained")
        axes = np.array(pair).reshape(2, 1)
    else:
        fig, axes = plt.subplots(2, len(results),
                                 figsize=(4.4 * len(results), 9.0),
                                 layout="constrained", squeeze=False)
    for column, result in enumerate(results):
        plot_multipliers(result, ax=axes[0, column])
        plot_multipliers(result, ax=axes[1, column], zoom=True)
        axes[0, column].set_title(
            f"f = {result.freq_hz:g} Hz, $p_f$ = "
            f"{result.p_f / PA_PER_BAR:g} bar: {result.kind}", fontsize=9)
        axes[1, column].set_title("near the leading multiplier",
                                  fontsize=8)
    handles, labels = [], []
    for ax in axes[0]:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="outside lower center", fontsize=8,
               ncols=1 if len(results) == 1 else 2)
    if title:
        figure_title(fig, title)
    return fig

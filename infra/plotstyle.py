"""The look every plot of the project shares: the colours and line styles
of the kinds of instability, the colour map of continuous quantities, the
axis labels of the dither plane, and the titles and labels of a figure.

One module below :mod:`stability.plots`, :mod:`pysim.bench.run_plots`,
:mod:`pysim.bench.plots` and :mod:`studies.figures`, so a colour means the
same in every figure.
Importing it imports matplotlib; nothing imports it but plotting modules.
"""

import textwrap

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap

from .criteria import JUDDER, SLOW_GROWTH, STABLE

__all__ = ["DARK_BLUE", "VERMILLION", "ORANGE", "BLUE", "KIND_COLORS",
           "SLOW_COLOR", "GROWTH_LINE", "KIND_LINESTYLES", "CONTINUOUS_CMAP",
           "FREQUENCY_LABEL", "AMPLITUDE_LABEL", "dither_axes",
           "figure_title", "LABEL_GID", "settle_labels", "log_levels",
           "layout_problems", "significant_digits", "TITLE_DIGITS",
           "setting_text", "VERDICT_MARKERS",
           "UNLISTED"]

#: Dark blue of single-period judder and of "stable" marks.
DARK_BLUE = "#1f4e99"

#: Okabe-Ito vermillion: double-period judder, unstable marks.
VERMILLION = "#d55e00"

#: Okabe-Ito orange: combination judder.
ORANGE = "#e69f00"

#: Okabe-Ito blue: the upstream speed of a run.
BLUE = "#0072b2"

#: Colour of each kind of :data:`stability.kinds.KINDS`, by kind code:
#: white, then a dark blue, Okabe-Ito vermillion and orange, which
#: colour-blind readers tell apart and which stay apart in greyscale,
#: with the grey of the slowly growing points (:data:`SLOW_COLOR`)
#: between them: greyscale
#: luminance (ITU-R 601) 1.00, 0.28, 0.47, 0.64 and 0.82, every pair at
#: least 0.15 apart (tests/test_figures.py).
KIND_COLORS = ("#ffffff", DARK_BLUE, VERMILLION, ORANGE)


#: Colour of the unstable points that grow too slowly to be judder.
SLOW_COLOR = "#d0d0d0"


#: Line of growth = min_growth (the edge of the judder-relevant region):
#: dash-dot, a style no kind's boundary uses.
GROWTH_LINE = {"colors": "k", "linewidths": 1.3,
               "linestyles": [(0, (7, 2, 1.5, 2))]}


#: Line where the forced oscillation reaches the NVH limit: bluish green
#: (Okabe-Ito), thick and dotted, apart from every boundary and the
#: growth line.
FORCED_LINE = {"color": "#009e73", "linewidth": 2.0,
               "linestyle": (0, (1, 1))}


#: Marker and colour of each verdict word
#: (:data:`stability.decisions.relevance.VERDICTS`): shape tells them
#: apart without colour; the colours are dark enough to read on every
#: kind's fill.
VERDICT_MARKERS = {JUDDER: ("X", "#b2182b"),
                   SLOW_GROWTH: ("s", "#404040"),
                   STABLE: ("o", "#1b7837")}


#: Line style of each kind's boundary, so kinds differ without colour.
KIND_LINESTYLES = ("-", "-", "--", (0, (1, 1.5)))


#: Colour map of continuous quantities (growth rates): cividis, made to
#: read the same in colour, greyscale and with colour-vision deficiency,
#: stopped at 80 % so its brightest colour (greyscale luminance 0.71)
#: stays apart from the white of stable points.
CONTINUOUS_CMAP = ListedColormap(
    plt.get_cmap("cividis")(np.linspace(0.0, 0.8, 256)), name="cividis80")


#: Label of the dither-frequency axis.
FREQUENCY_LABEL = "dither frequency $f$ [Hz]"

#: Label of the dither-amplitude axis.
AMPLITUDE_LABEL = "dither amplitude $p_f$ [bar]"


def log_levels(low, high, count=12):
    """Log-spaced contour levels from ``low`` to ``high`` (rpm) and the
    round ticks (1, 3, 10, 30, ...) between them."""
    low, high = max(low, 1e-3), max(high, 1.0001 * max(low, 1e-3))
    levels = np.geomspace(low, high * 1.0001, count)
    decades = np.arange(np.floor(np.log10(low)), np.ceil(np.log10(high)) + 1)
    ticks = [m * 10 ** d for d in decades for m in (1, 3)
             if low <= m * 10 ** d <= high]
    return levels, ticks or [low, high]


def dither_axes(ax, frequency=FREQUENCY_LABEL, amplitude=AMPLITUDE_LABEL):
    """Label ``ax`` as the dither plane: frequency (Hz) across, amplitude
    (bar) up."""
    ax.set_xlabel(frequency)
    ax.set_ylabel(amplitude)


def figure_title(fig, title, fontsize=11):
    """``fig.suptitle(title)``, wrapped onto lines that fit the figure's
    width (a long model description is not clipped)."""
    return fig.suptitle(_wrapped(title, fig.get_figwidth() * 72, fontsize),
                        fontsize=fontsize)


def _wrapped(text, room_pt, fontsize, keep_lines=False):
    """``text`` wrapped onto lines of about ``room_pt`` points at
    ``fontsize``: its line breaks undone, or with ``keep_lines`` each of
    its lines wrapped on its own."""
    # DejaVu Sans averages about 0.55 em a character
    width = max(20, int(room_pt / (0.58 * fontsize)))
    if keep_lines:
        return "\n".join(textwrap.fill(line, width) if line else line
                         for line in text.split("\n"))
    return textwrap.fill(" ".join(text.split("\n")), width)


def redraw_at(fig, width_in, height_in):
    """Give a figure made at another size (its layout constrained) the
    size ``width_in x height_in`` inches: its title (made by
    :func:`figure_title`) wrapped again to the new width, each line of its
    panels' titles to theirs, its labels settled again
    (:func:`settle_labels`), as its builder would have made them at that
    size."""
    fig.set_size_inches(width_in, height_in)
    title = fig._suptitle
    if title is not None and title.get_text():
        title.set_text(_wrapped(title.get_text(), width_in * 72,
                                title.get_fontsize()))
    for ax in fig.axes:
        spec = ax.get_subplotspec()
        share = 1.0 if spec is None else (
            len(spec.colspan) / spec.get_gridspec().ncols)
        for text in (ax.title, ax._left_title, ax._right_title):
            if text.get_text():
                text.set_text(_wrapped(text.get_text(),
                                       0.9 * share * width_in * 72,
                                       text.get_fontsize(), keep_lines=True))
    settle_labels(fig)


#: ``gid`` of the texts :func:`settle_labels` keeps apart: tongue numbers
#: and the margin notes of ``judder check``.
LABEL_GID = "judder-label"

#: Points of white space :func:`settle_labels` keeps between two labels,
#: half a space at 8 pt: numbers that only touch read as one ("1314").
LABEL_GAP_PT = 1.5


def settle_labels(fig):
    """Lay the figure out, then move each tongue number or margin note
    (texts with ``gid`` :data:`LABEL_GID`) up until it lies at least
    :data:`LABEL_GAP_PT` clear of every one placed before it in its axes:
    nearby tips and settings keep readable labels. Figure builders call it
    last, once the axes have their final size."""
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    gap = LABEL_GAP_PT * fig.dpi / 72.0
    for ax in fig.axes:
        notes = sorted((t for t in ax.texts if t.get_gid() == LABEL_GID),
                       key=lambda t: t.xy[0])
        placed = []
        for note in notes:
            for _ in range(20):
                box = _text_box(note, renderer)
                if not any(_overlap(box, other, -gap)
                           for other in placed):
                    break
                dx, dy = note.xyann
                note.xyann = (dx, dy + box.height * 72.0 / fig.dpi + 2)
            placed.append(_text_box(note, renderer))


def _text_box(text, renderer):
    """The box of a text's letters (pixels): of an annotation without its
    leader arrow, which grows as the text moves away."""
    from matplotlib.text import Text
    return Text.get_window_extent(text, renderer)


def _overlap(one, other, slack):
    """Two boxes (pixels) share more than ``slack`` in both directions (a
    negative ``slack``: come closer than ``-slack`` in both)."""
    return (min(one.x1, other.x1) - max(one.x0, other.x0) > slack
            and min(one.y1, other.y1) - max(one.y0, other.y0) > slack)


# --- what a reviewer checks on a drawn figure --------------------------------

#: Most significant digits a number in a title may print ("0.081 bar",
#: not "0.0812726 bar"): engineering precision.
TITLE_DIGITS = 4


def setting_text(freq_hz=None, p_f_bar=None):
    """A dither setting in a title, in engineering precision: frequency
    to 4 significant digits, amplitude to the millibar (``'f = 102.9 Hz,
    $p_f$ = 0.081 bar'``, not 0.0812726 bar)."""
    from infra.numbers import readable_number
    parts = []
    if freq_hz is not None:
        parts.append(f"f = {readable_number(freq_hz)} Hz")
    if p_f_bar is not None:
        amplitude = f"{p_f_bar:.3f}".rstrip("0").rstrip(".")
        parts.append(f"$p_f$ = {amplitude} bar")
    return ", ".join(parts)


def significant_digits(number):
    """Significant digits of a number as printed (``"0.0812726"`` -> 6,
    ``"34860"`` -> 4, ``"1.50"`` -> 3)."""
    digits = number.lstrip("+-").replace("_", "")
    mantissa = digits.split("e")[0].split("E")[0]
    if "." in mantissa:
        whole = mantissa.replace(".", "").lstrip("0")
        return len(whole)
    return len(mantissa.strip("0")) or 1


def layout_problems(fig):
    """What a reviewer would flag in the drawn ``fig``, as sentences
    (empty: none).

    Draws the figure (``fig.canvas.draw()``) and checks, from the window
    extents of what was drawn:

    - no two texts (titles, axis and tick labels, annotations, legend
      texts, colour-bar labels) overlap by more than a pixel;
    - no text leaves the canvas (a clipped title or label);
    - every artist drawn with a label (not starting with ``_``) is listed
      in a legend of the figure, and every legend entry is drawn: its
      handle is an artist of the figure, or a drawn artist has its colour
      (and, for a line, its line style and marker);
    - no title prints a number with more than :data:`TITLE_DIGITS`
      significant digits.
    """
    from matplotlib.text import Text
    drawn, draw = [], Text.draw

    def recording(text, renderer):       # the texts a draw really draws
        draw(text, renderer)
        drawn.append(text)
    Text.draw = recording
    try:
        fig.canvas.draw()
    finally:
        Text.draw = draw
    renderer = fig.canvas.get_renderer()
    problems = _text_problems(drawn, fig.bbox, renderer)
    problems += _legend_problems(fig)
    problems += _title_problems(fig)
    return problems


def _text_problems(drawn, page, renderer):
    boxes = []
    for text in dict.fromkeys(drawn):
        if not text.get_visible() or not text.get_text().strip():
            continue
        box = _text_box(text, renderer)
        if box.width == 0 or box.height == 0:
            continue
        boxes.append((text.get_text(), box))
    problems = [f"text {t!r} leaves the canvas" for t, b in boxes
                if b.x0 < page.x0 - 1 or b.y0 < page.y0 - 1
                or b.x1 > page.x1 + 1 or b.y1 > page.y1 + 1]
    for i, (t1, b1) in enumerate(boxes):
        for t2, b2 in boxes[i + 1:]:
            if _overlap(b1, b2, 1.0):
                problems.append(f"text {t1!r} overlaps {t2!r}")
    return problems


def _artists(fig):
    """Every artist drawn in ``fig``'s axes (lines, collections, patches,
    images), with the axes it is in."""
    for ax in fig.axes:
        if hasattr(ax, "_colorbar"):     # its own scale, not in a legend
            continue
        for artist in (*ax.lines, *ax.collections, *ax.patches, *ax.images):
            if artist.get_visible():
                yield ax, artist


def _has_data(artist):
    from matplotlib.lines import Line2D
    if isinstance(artist, Line2D):
        x, y = (np.asarray(v, dtype=float) for v in artist.get_data())
        finite = np.isfinite(x) & np.isfinite(y)
        if artist.get_marker() in (None, "None", "none", ""):
            # a line without markers shows only between two finite points
            return bool((finite[1:] & finite[:-1]).any())
        return bool(finite.any())
    return True


def _legends(fig):
    legends = [ax.get_legend() for ax in fig.axes] + list(fig.legends)
    return [legend for legend in legends if legend is not None]


def _legend_problems(fig):
    legends = _legends(fig)
    listed = {t.get_text() for legend in legends for t in legend.get_texts()}
    problems = []
    for ax, artist in _artists(fig):
        label = artist.get_label()
        if (label and not label.startswith("_") and _has_data(artist)
                and label not in listed):
            problems.append(f"{label!r} is drawn but not in a legend")
    drawn = [artist for _, artist in _artists(fig) if _has_data(artist)]
    handles = [h for legend in legends for h in legend.legend_handles
               if h is not None]
    if legends:
        for artist in drawn:
            label = artist.get_label() or "_"
            if (label.startswith("_") and not label.startswith(UNLISTED)
                    and _line_like(artist)
                    and not _listed_like(artist, handles)):
                problems.append(f"a {_describe(artist)} is drawn but no "
                                "legend entry looks like it")
    for legend in legends:
        for handle, text in zip(legend.legend_handles, legend.get_texts()):
            if handle is None or not _drawn_like(handle, drawn):
                problems.append(f"legend entry {text.get_text()!r} is "
                                "not drawn")
    return problems


#: Label prefix of an artist left out of the legend on purpose (matplotlib's
#: own ``"_nolegend_"``): tongue tips, which their numbers explain.
UNLISTED = "_nolegend_"


def _line_like(artist):
    """Lines and line contours (not fills, images or patches)."""
    from matplotlib.collections import LineCollection
    from matplotlib.contour import ContourSet
    from matplotlib.lines import Line2D
    if isinstance(artist, Line2D):
        return True
    if isinstance(artist, ContourSet):
        return not artist.filled
    return isinstance(artist, LineCollection)


def _describe(artist):
    from matplotlib.colors import to_hex
    colours = _colours(artist)
    colour = to_hex(colours[0]) if len(colours) else "?"
    style = getattr(artist, "get_linestyle", lambda: "?")()
    marker = getattr(artist, "get_marker", lambda: None)()
    return (f"{type(artist).__name__} ({colour}, line {style!r}"
            + (f", marker {marker!r}" if marker not in (None, "None", "")
               else "") + ")")


def _listed_like(artist, handles):
    """Whether a legend handle has the colour of ``artist`` (a line also
    its dash pattern, or its marker where it has no line)."""
    from matplotlib.lines import Line2D
    colours = _colours(artist)
    for handle in handles:
        if handle is artist:
            return True
        theirs = _colours(handle)
        if not len(colours) or not _same_colour(colours[0], theirs):
            continue
        if isinstance(artist, Line2D) and isinstance(handle, Line2D):
            has_line = artist.get_linestyle() not in ("None", "none", "")
            if has_line and _dashes(artist) != _dashes(handle):
                continue
            if not has_line and artist.get_marker() != handle.get_marker():
                continue
        return True
    return False


def _colours(artist):
    """RGBA colours an artist draws with, as an (n, 4) array."""
    from matplotlib.colors import to_rgba_array
    from matplotlib.image import AxesImage
    from matplotlib.lines import Line2D
    if isinstance(artist, Line2D):
        return to_rgba_array([artist.get_color(),
                              artist.get_markerfacecolor(),
                              artist.get_markeredgecolor()])
    if isinstance(artist, AxesImage):
        cmap, data = artist.get_cmap(), artist.get_array()
        if data is None:
            return np.zeros((0, 4))
        data = np.asarray(data)
        if data.ndim == 3:              # RGB(A) already
            rgba = data.reshape(-1, data.shape[-1]).astype(float)
            if rgba.max() > 1:
                rgba = rgba / 255.0
            if rgba.shape[1] == 3:
                rgba = np.c_[rgba, np.ones(len(rgba))]
            return np.unique(np.round(rgba, 3), axis=0)
        values = np.unique(np.ma.compressed(np.ma.masked_invalid(data)))
        return cmap(artist.norm(values))
    colours = []
    for get in ("get_facecolor", "get_edgecolor"):
        if hasattr(artist, get):
            c = getattr(artist, get)()
            if c is not None and len(np.atleast_1d(c)):
                colours.append(to_rgba_array(c))
    return np.concatenate(colours) if colours else np.zeros((0, 4))


def _same_colour(one, many, tolerance=0.02):
    many = np.asarray(many)
    if not len(many):
        return False
    return bool((np.abs(many[:, :3] - np.asarray(one)[:3]).max(axis=1)
                 <= tolerance).any())


def _dashes(line):
    style = line.get_linestyle()
    return "solid" if style in ("-", "solid") else style


def _drawn_like(handle, drawn):
    """Whether a legend handle stands for something drawn: it is one of
    the drawn artists, or a drawn artist has its colour (a line also its
    marker, and its dash pattern unless it has no line)."""
    from matplotlib.colors import to_rgba
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    if any(handle is artist for artist in drawn):
        return True
    if isinstance(handle, Line2D):
        colour = to_rgba(handle.get_color())
        has_line = handle.get_linestyle() not in ("None", "none", "", " ")
        for artist in drawn:
            if isinstance(artist, Line2D):
                if not _same_colour(colour, _colours(artist)[:1]):
                    if not (not has_line and _same_colour(
                            to_rgba(handle.get_markerfacecolor()),
                            _colours(artist)[1:2])):
                        continue
                if handle.get_marker() not in ("None", "", None, "none") \
                        and artist.get_marker() != handle.get_marker():
                    continue
                if has_line and _dashes(artist) != _dashes(handle):
                    continue
                return True
            elif has_line and _same_colour(colour, _colours(artist)):
                return True
        return False
    if isinstance(handle, Patch):
        colour = handle.get_facecolor()
        if handle.get_fill() is False or colour[3] == 0:
            colour = handle.get_edgecolor()
        return any(_same_colour(colour, _colours(artist))
                   for artist in drawn)
    colours = _colours(handle)
    return any(_same_colour(c, _colours(artist)) for artist in drawn
               for c in colours[:1])


def _title_problems(fig):
    import re
    titles = [fig._suptitle] + [t for ax in fig.axes for t in
                                (ax.title, ax._left_title, ax._right_title)]
    problems = []
    for title in titles:
        if title is None or not title.get_visible():
            continue
        for number in re.findall(
                r"(?<![\w.^{])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?",
                title.get_text()):
            if significant_digits(number) > TITLE_DIGITS:
                problems.append(f"title prints {number} (more than "
                                f"{TITLE_DIGITS} significant digits)")
    return problems

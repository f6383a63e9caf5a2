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

__all__ = ["DARK_BLUE", "VERMILLION", "ORANGE", "BLUE", "KIND_COLORS",
           "SLOW_COLOR", "GROWTH_LINE", "KIND_LINESTYLES", "CONTINUOUS_CMAP",
           "FREQUENCY_LABEL", "AMPLITUDE_LABEL", "dither_axes",
           "figure_title", "LABEL_GID", "settle_labels", "log_levels"]

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
                box = note.get_window_extent(renderer)
                if not any(_overlap(box, other, -gap)
                           for other in placed):
                    break
                dx, dy = note.xyann
                note.xyann = (dx, dy + box.height * 72.0 / fig.dpi + 2)
            placed.append(note.get_window_extent(renderer))


def _overlap(one, other, slack):
    """Two boxes (pixels) share more than ``slack`` in both directions (a
    negative ``slack``: come closer than ``-slack`` in both)."""
    return (min(one.x1, other.x1) - max(one.x0, other.x0) > slack
            and min(one.y1, other.y1) - max(one.y0, other.y0) > slack)

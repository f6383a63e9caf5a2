"""``judder advise``: the safe dither windows of the given design and the
map of the advised one, wide enough to show where its tongues went."""

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
import numpy as np
from matplotlib.patches import Rectangle
from matplotlib.transforms import offset_copy

from infra.plotstyle import figure_title, settle_labels
from infra.units import PA_PER_BAR
from stability.plots import (drawn_kinds, draws_instability, kind_handles,
                             plot_boundaries, plot_map)

__all__ = ["advice_figure"]

#: The given design's stability boundaries over the advised design's map.
GIVEN_STYLE = {"color": "#7f7f7f", "linestyle": (0, (4, 2)),
               "linewidth": 1.0}


def advice_figure(advice, title=None, stacked=False):
    """Safe amplitude per frequency (left) and the map of the advised
    design (right, if any): over the operating range, or, when the result
    holds its wide view (``advise(background=True)``), from half the
    lowest to 1.5 times the highest operating frequency, with the given
    design's stability boundaries dashed and the operating range framed.

    Parameters
    ----------
    advice : studies.advise.AdviceResult
    stacked : bool
        The map below the safe amplitude rather than beside it (a page's
        width, as in the report).
    """
    if advice.verification is None:
        fig, left = plt.subplots(figsize=(7, 5), layout="constrained")
    else:
        fig, (left, right) = plt.subplots(
            *((2, 1) if stacked else (1, 2)),
            figsize=(7.2, 7.6) if stacked else (14, 5.4),
            layout="constrained")
    op = advice.operating
    top = op.p_max / PA_PER_BAR
    inside = ((advice.freq_hz >= op.freq_hz[0])
              & (advice.freq_hz <= op.freq_hz[1]))
    left.fill_between(advice.freq_hz[inside], 0,
                      advice.safe_p_f[inside] / PA_PER_BAR, color="#2ca02c",
                      alpha=0.5, label="safe (with margins)")
    left.axhline(top, color="k", linestyle="--", linewidth=0.8,
                 label="valve's highest amplitude")
    for index, edge in enumerate(op.freq_hz):
        left.axvline(edge, color="k", linestyle=":", linewidth=0.8,
                     label=None if index else "operating range's ends")
    left.set_xlabel("dither frequency [Hz]")
    left.set_ylabel("safe dither amplitude $p_f$ [bar]")
    left.set_title("safe dither windows, given design", fontsize=10)
    # below the tick labels and the axis label, whatever the axes' height
    left.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                bbox_transform=offset_copy(left.transAxes, fig=fig, y=-36,
                                           units="points"),
                ncols=2, frameon=False, borderaxespad=0.0)
    if advice.verification is not None:
        _advised_map(advice, right)
    figure_title(fig, "judder advise: safe dither windows and the advised "
                 "design" + (f", {title}" if title else ""))
    settle_labels(fig)
    return fig


def _advised_map(advice, ax):
    """The advised design's map; with the wide view, its exact tongues,
    the given design's boundaries and the operating range."""
    op = advice.operating
    view = advice.view
    if view is None:
        plot_map(advice.verification, ax=ax, min_growth=advice.min_growth)
    else:
        plot_map(view["map"], ax=ax, tongues=view["tongues"],
                 boundaries=view["boundaries"], legend=False,
                 min_growth=advice.min_growth)
        plot_boundaries(view["given_boundaries"], ax=ax, style=GIVEN_STYLE,
                        numbers=False)
        low, high = op.freq_hz
        ax.add_patch(Rectangle((low, 0), high - low, op.p_max / PA_PER_BAR,
                               fill=False, edgecolor="#2ca02c",
                               linewidth=1.6, zorder=5))
        ax.set_xlim(view["map"].freq_hz[0], view["map"].freq_hz[-1])
        # only the kinds the advised design's map draws, and its slow
        # growth and the given design's boundaries where there are any
        unstable = draws_instability(view["map"], view["boundaries"])
        handles = kind_handles(drawn_kinds(view["map"], view["boundaries"]),
                               lines=True, min_growth=advice.min_growth
                               if unstable else None)
        if np.isfinite(view["given_boundaries"].amplitude).any():
            handles.append(Line2D([], [], label="given design's boundaries",
                                  **GIVEN_STYLE))
        handles.append(Rectangle((0, 0), 1, 1, fill=False,
                                 edgecolor="#2ca02c", linewidth=1.6,
                                 label="operating range"))
        ax.legend(handles=handles, fontsize=7, loc="upper left",
                  bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    # above the tongue numbers that head the axes
    ax.set_title(f"advised design: {advice.judder_points} judder points "
                 f"(>= {advice.min_growth:g} 1/s) in the operating range",
                 fontsize=10, pad=16)

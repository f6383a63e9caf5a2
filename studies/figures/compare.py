"""``judder compare``: the maps of two parameter sets on one figure, each
with the other's stability boundaries dashed and the operating range
framed."""

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle

from infra.plotstyle import VERDICT_MARKERS, figure_title, settle_labels
from infra.units import PA_PER_BAR
from stability.plots import kind_handles, plot_boundaries, plot_map
from stability.plots.boundaries import BURIED_TIP

__all__ = ["compare_figure"]

#: The other set's stability boundaries over a map.
OTHER_STYLE = {"color": "#7f7f7f", "linestyle": (0, (4, 2)),
               "linewidth": 1.0}
#: The operating range of the safe windows.
RANGE_STYLE = {"fill": False, "edgecolor": "#2ca02c", "linewidth": 1.6}


def compare_figure(result, title=None):
    """Two maps side by side (the same axes), each set's tongues and
    judder-relevant region, the other set's boundaries dashed.

    Parameters
    ----------
    result : studies.compare.CompareResult
        Computed with ``maps=True``.
    """
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.4), layout="constrained",
                             sharex=True, sharey=True)
    op = result.operating
    low, high = op.freq_hz
    buried = []
    for index, (ax, side) in enumerate(zip(axes, result.sides)):
        other = result.sides[1 - index]
        shown = side.map
        plot_map(shown.map, ax=ax, tongues=shown.tongues,
                 boundaries=shown.boundaries, legend=False,
                 min_growth=result.min_growth)
        plot_boundaries(other.map.boundaries, ax=ax, style=OTHER_STYLE,
                        numbers=False)
        ax.add_patch(Rectangle((low, 0), high - low, op.p_max / PA_PER_BAR,
                               zorder=5, **RANGE_STYLE))
        buried += [a for a in ax.lines if a.get_label() == BURIED_TIP]
        # the settings compared (--freq, --pf), as judder check marks them
        for record in ([] if side.check is None else side.check.records()):
            marker, colour = VERDICT_MARKERS[record["verdict"]]
            ax.plot(record["freq_hz"], record["p_f_bar"], marker=marker,
                    color=colour, markeredgecolor="k", markersize=10,
                    linestyle="none", zorder=6,
                    label=f"setting: {record['verdict']}")
        ax.set_xlim(shown.map.freq_hz[0], shown.map.freq_hz[-1])
        ax.set_title(f"{'AB'[index]}: {side.label}", fontsize=10, pad=16)
        if index:
            ax.set_ylabel("")
    handles = kind_handles(lines=True, min_growth=result.min_growth)
    handles += [Line2D([], [], label="the other set's boundaries",
                       **OTHER_STYLE),
                Rectangle((0, 0), 1, 1, label="operating range",
                          **RANGE_STYLE)] + buried[:1]
    # one entry per verdict marked on either map
    verdicts = {line.get_label(): line for ax in axes for line in ax.lines
                if line.get_label().startswith("setting: ")}
    handles += list(verdicts.values())
    axes[1].legend(handles=handles, fontsize=7, loc="upper left",
                   bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    figure_title(fig, "judder compare: stability maps" +
                 (f", {title}" if title else ""))
    settle_labels(fig)
    return fig

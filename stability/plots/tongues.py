"""Tongue boundaries with their numbered tips, alone or over the map."""

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D

from infra.plotstyle import KIND_COLORS, KIND_LINESTYLES, settle_labels

from ..kinds import KINDS
from .boundaries import BURIED_TIP, plot_boundaries
from .maps import plot_map

__all__ = ["tongues_figure"]


def tongues_figure(boundaries, tongues, stability_map=None, title=None,
                   min_growth=None, judder=None):
    """Boundaries and numbered tips, over the map when one is given (its
    points growing slower than ``min_growth``, 1/s, grey; below the exact
    boundaries of that growth, ``judder`` = (Boundaries, tongues), where
    given)."""
    fig, ax = plt.subplots(figsize=(10, 5), layout="constrained")
    if stability_map is not None:
        plot_map(stability_map, ax=ax, tongues=tongues,
                 boundaries=boundaries, min_growth=min_growth,
                 judder=judder)
    else:
        drawn = plot_boundaries(boundaries, ax=ax, tongues=tongues)
        handles = [Line2D([], [], color=KIND_COLORS[k],
                          linestyle=KIND_LINESTYLES[k], label=KINDS[k])
                   for k in (1, 2, 3)]
        handles += [a for a in drawn if a.get_label() == BURIED_TIP]
        ax.legend(handles=handles, loc="upper left", fontsize=7,
                  bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax.set_title(title or "tongue boundaries (numbers as in Fig. 14)",
                 fontsize=10)
    settle_labels(fig)
    return fig

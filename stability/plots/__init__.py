"""Plots of the stability results, one module per kind of result, over
the shared look of :mod:`infra.plotstyle` (as python-control's
``timeplot``/``freqplot`` over ``ctrlplot``):

* :mod:`~stability.plots.maps`: stability maps (Fig. 12, Fig. 14);
* :mod:`~stability.plots.boundaries`: tongue boundaries as lines;
* :mod:`~stability.plots.tongues`: boundaries with numbered tips;
* :mod:`~stability.plots.sensitivity`: Fig. 17, Fig. 18;
* :mod:`~stability.plots.threshold`: Fig. 19;
* :mod:`~stability.plots.fit`: a boundary fit (Fig. 16a);
* :mod:`~stability.plots.multipliers`: Floquet multipliers (Fig. 15);
* :mod:`~stability.plots.envelope`: the region over uncertain parameters.

A plot draws what its result holds and computes nothing; functions take
an ``ax`` (a new figure when None), return the artists they drew and never
call ``plt.show()``. Importing this package imports matplotlib;
``import stability`` does not.
"""

from .boundaries import boundary_curve, number_tips, plot_boundaries
from .envelope import envelope_figure, plot_envelope
from .fit import plot_fit
from .maps import (drawn_kinds, draws_instability, kind_handles,
                   kind_legend, map_figure, plot_growth_rate, plot_map)
from .multipliers import multipliers_figure, plot_multipliers
from .sensitivity import sensitivity_figure
from .threshold import plot_threshold
from .tongues import tongues_figure

__all__ = ["plot_map", "plot_growth_rate", "map_figure", "kind_legend",
           "kind_handles", "drawn_kinds", "draws_instability",
           "boundary_curve", "plot_boundaries",
           "number_tips", "tongues_figure", "sensitivity_figure",
           "plot_threshold", "plot_fit", "plot_multipliers",
           "multipliers_figure", "plot_envelope", "envelope_figure"]

"""``judder threshold``: Fig. 19a and 19b of a driveline, with its own
point and the caveat that this study keeps the mean pressure's damping."""

import matplotlib.pyplot as plt

from infra.plotstyle import figure_title
from stability.plots import plot_threshold

__all__ = ["threshold_figure"]


def threshold_figure(result, title=None, stacked=False):
    """Largest real part against mu_g (left) and the threshold against
    the external damping with the driveline's own point (right).

    Parameters
    ----------
    result : studies.threshold.ThresholdResult
    title : str, optional
        The model, after "Fig. 19 without dither" (default: the model's
        name).
    stacked : bool
        Fig. 19b below Fig. 19a rather than beside it (a page's width, as
        in the report: the off-scale notes keep their room).
    """
    fig, axes = plt.subplots(*((2, 1) if stacked else (1, 2)),
                             figsize=(7.2, 5.8) if stacked else (11, 4.4),
                             layout="constrained")
    plot_threshold(result.study, axes=axes, own=result.own)
    figure_title(fig, f"Fig. 19 without dither, "
                 f"{title or result.params.model + ' driveline'}: the "
                 "mean pressure's damping in the slip damping (the maps "
                 "keep only the dither's part)", fontsize=10)
    return fig

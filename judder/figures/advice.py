"""``judder advise``: the safe dither windows of the given design and the
recomputed map of the advised one."""

import matplotlib.pyplot as plt

from infra.plotstyle import figure_title, settle_labels
from infra.units import PA_PER_BAR
from stability.plots import plot_map

__all__ = ["advice_figure"]


def advice_figure(advice, title=None):
    """Safe amplitude per frequency (left) and the recomputed map of the
    advised design (right, if any).

    Parameters
    ----------
    advice : judder.commands.advise.AdviceResult
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

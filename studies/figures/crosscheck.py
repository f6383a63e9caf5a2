"""``judder crosscheck``: growth rates fitted to FMU runs against the
Floquet exponents, and the verdicts of both on the grid."""

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import DARK_BLUE, VERMILLION, dither_axes
from infra.units import PA_PER_BAR

__all__ = ["crosscheck_figure"]


def crosscheck_figure(check, title=None):
    """Fitted against Floquet growth rates, and verdicts on the grid;
    ``title`` (the model) follows the share of agreeing verdicts."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5),
                                      layout="constrained")
    floquet = np.array([p.floquet_rate for p in check.points])
    fitted = np.array([p.fitted_rate for p in check.points])
    agree = np.array([p.agree for p in check.points])
    left.plot(floquet[agree], fitted[agree], "o", ms=4, color=DARK_BLUE,
              label="verdicts agree")
    left.plot(floquet[~agree], fitted[~agree], "x", ms=7, mew=1.5,
              color="k", label="verdicts disagree")
    span = [min(floquet.min(), fitted.min()), max(floquet.max(), fitted.max())]
    left.plot(span, span, "k-", lw=0.6, label="equal")
    left.set_xlabel(r"Floquet exponent $\ln|\lambda|/T$ [1/s]")
    left.set_ylabel("growth rate fitted to the FMU run [1/s]")
    f = np.array([p.freq_hz for p in check.points])
    p = np.array([p.p_f for p in check.points]) / PA_PER_BAR
    unstable = np.array([q.floquet_unstable for q in check.points])
    # shapes tell the verdicts apart without colour (not red against green)
    right.scatter(f[unstable & agree], p[unstable & agree], marker="^",
                  c=VERMILLION, edgecolors="k", linewidths=0.4, s=26,
                  label="unstable in both")
    right.scatter(f[~unstable & agree], p[~unstable & agree], marker="o",
                  facecolors="none", edgecolors=DARK_BLUE, s=22,
                  label="stable in both")
    right.scatter(f[~agree], p[~agree], marker="x", c="k", s=40,
                  linewidths=1.5, label="verdicts disagree")
    dither_axes(right, "dither frequency [Hz]")
    for ax in (left, right):     # legends below the data
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14),
                  ncols=3, borderaxespad=0.0, frameon=False)
    fig.suptitle(f"cross-check: {100 * check.agreement:.1f} % of the verdicts "
                 "agree" + (f", {title}" if title else ""))
    return fig

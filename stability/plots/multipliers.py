"""Floquet multipliers on the complex plane (Fig. 15)."""

import matplotlib.pyplot as plt
import numpy as np

from infra.plotstyle import (UNLISTED, KIND_COLORS, figure_title,
                             setting_text)
from infra.units import PA_PER_BAR

from ..kinds import KINDS

__all__ = ["plot_multipliers", "multipliers_figure"]


def plot_multipliers(result, ax=None, zoom=False):
    """Floquet multipliers on the complex plane with the unit circle
    (Fig. 15), the leading one marked in the colour of its kind.

    Parameters
    ----------
    result : stability.multipliers.FloquetResult
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
    lam = np.asarray(result.multipliers)
    lead = complex(result.leading)
    code = KINDS.index(result.kind)
    theta = np.linspace(0, 2 * np.pi, 721)
    artists = [ax.plot(np.cos(theta), np.sin(theta), color="0.35", lw=0.9,
                       label="unit circle")[0],
               # the axes of the complex plane: no legend entry
               ax.axhline(0, color="0.7", lw=0.6, label=UNLISTED),
               ax.axvline(0, color="0.7", lw=0.6, label=UNLISTED)]
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
    results : sequence of stability.multipliers.FloquetResult
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
            f"{setting_text(result.freq_hz, result.p_f / PA_PER_BAR)}: "
            f"{result.kind}", fontsize=9)
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

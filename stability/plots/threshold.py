"""The friction-gradient threshold without dither (Fig. 19a, 19b)."""

import matplotlib.pyplot as plt

from infra.plotstyle import DARK_BLUE, UNLISTED, VERMILLION

__all__ = ["plot_threshold"]


def plot_threshold(study, axes=None, own=None):
    """Fig. 19a (largest real part against mu_g) and 19b (threshold in the
    c_i - mu_g plane with regions A and B).

    ``own = (c_i, mu_g)`` marks the driveline's own external damping and
    friction gradient (N m s/rad, s/rad): a point where it lies inside the
    axes, else an arrow at the edge towards it, with its value.
    """
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    left, right = axes
    artists = [left.plot(study.mu_g, study.max_real_part, "k-")[0],
               left.axhline(0, color="0.5", linewidth=0.8,
                           label=UNLISTED),   # the axis, not a result
               left.axvline(study.threshold, color="k", linestyle="--",
                            label=rf"threshold $\mu_g^*$ = "
                                  f"{study.threshold:.3g} s/rad")]
    left.set_xlabel(r"friction gradient $\mu_g$ [s/rad]")
    left.set_ylabel("largest real part [1/s]")
    left.set_title("without dither: unstable above 0", fontsize=10)
    left.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))
    c, mu = study.external_damping, study.thresholds
    low = min(mu.min(), study.mu_g.min())
    high = max(mu.max(), study.mu_g.max())
    artists += [right.fill_between(c, low, mu, color=VERMILLION, alpha=0.3,
                                   linewidth=0),
                right.fill_between(c, mu, high, color=DARK_BLUE, alpha=0.15,
                                   linewidth=0),
                right.plot(c, mu, "k-", label=r"threshold $\mu_g^*$ "
                           "(eigenvalues)")[0],
                right.plot(c, study.closed_form, linestyle="none",
                           marker="o", mfc="w", mec="k", ms=4,
                           markevery=max(1, len(c) // 10),
                           label="rigid-chain closed form")[0]]
    right.text(c.mean(), (low + mu.min()) / 2, "A: unstable", ha="center")
    # just above the threshold, clear of the off-scale note that heads the
    # axes (_mark_own) at any panel height
    right.annotate("B: stable without dither", (c.mean(), mu.max()),
                   xytext=(0, 10), textcoords="offset points", ha="center",
                   va="bottom")
    right.set_xlabel("external damping $c_i$ [N m s/rad]")
    right.set_ylabel(r"$\mu_g$ [s/rad]")
    right.set_ylim(low, high)
    right.set_title(r"threshold against the external damping", fontsize=10)
    right.ticklabel_format(axis="y", style="sci", scilimits=(0, 0))
    if own is not None:
        artists += _mark_own(left, right, own, (low, high))
    for ax in (left, right):
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0, -0.2),
                  borderaxespad=0.0, frameon=False)
    return artists


def _mark_own(left, right, own, limits):
    """The driveline's own (c_i, mu_g) on Fig. 19: a point (right) and a
    line (left) where inside the axes, else an arrow at the edge."""
    c_own, mu_own = own
    label = rf"this driveline: $\mu_g$ = {mu_own:.3g} s/rad"
    low, high = limits
    artists = []
    if low <= mu_own <= high:
        artists.append(right.plot(c_own, mu_own, marker="*", ms=12,
                                  color="k", linestyle="none",
                                  label=label)[0])
        artists.append(left.axvline(mu_own, color="k", linestyle=":",
                                    label=label))
        return artists
    # off the scale: the right panel's mu_g axis is vertical, the left
    # panel's horizontal; each arrow points along its own axis, the label
    # saying how far beyond its end the value lies
    up = mu_own > high
    edge = high if up else low
    times = f"{mu_own / edge:.3g} times the axis' end" if edge else ""
    label += f", off the scale ({times})" if times else ", off the scale"
    artists.append(right.annotate(
        label, xy=(c_own, 0.97 if up else 0.03),
        xycoords=("data", "axes fraction"), xytext=(8, -22 if up else 22),
        textcoords="offset points", fontsize=8, ha="left",
        va="top" if up else "bottom",
        arrowprops={"arrowstyle": "->", "color": "k"}))
    artists.append(left.annotate(
        label.replace(": ", ":\n", 1).replace(" (", "\n("),  # off the curve
        xy=(0.99 if up else 0.01, 0.4), xycoords="axes fraction",
        xytext=(-40 if up else 40, 0), textcoords="offset points",
        fontsize=8, ha="right" if up else "left", va="center",
        arrowprops={"arrowstyle": "->", "color": "k"}))
    return artists

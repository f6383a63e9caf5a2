"""``judder check``: the dither settings with their verdicts and margins,
over the map when there is one."""

from matplotlib import patheffects
import matplotlib.pyplot as plt
from matplotlib.lines import Line2D

from infra.criteria import STABLE
from infra.plotstyle import (LABEL_GID, VERDICT_MARKERS, dither_axes,
                             figure_title, settle_labels)
from stability.plots import drawn_kinds, kind_handles, plot_map
from stability.plots.boundaries import BURIED_TIP

__all__ = ["check_figure", "VERDICT_MARKERS"]


# VERDICT_MARKERS lives in infra.plotstyle (compare marks settings too)


def band_text(record):
    """The safe band of a record as a label: ``safe 84.4-100.8 Hz``;
    ``safe from``/``safe up to`` where one side reaches the end of the
    range searched; its Hz margin where the record has no band field."""
    if "safe_band_hz" not in record:
        hz = record["margin_hz"]
        return "" if hz is None else f"{hz:+.2f} Hz"
    band = record["safe_band_hz"]
    if band is None:
        return f"no safe frequency at {record['p_f_bar']:g} bar"
    if None in band:
        return ""
    low, high = band
    open_low = record["safe_band_low_limited_by"] is None
    open_high = record["safe_band_high_limited_by"] is None
    if open_low and open_high:
        return f"safe {low:.3g}-{high:.3g} Hz (all searched)"
    if open_low:
        return f"safe up to {high:.1f} Hz"
    if open_high:
        return f"safe from {low:.1f} Hz"
    return f"safe {low:.1f}-{high:.1f} Hz"


def check_figure(records, background=None, min_growth=None, title=None,
                 boundaries=None, tongues=None, judder=None):
    """Settings of ``judder check`` marked on the map (or alone).

    Each setting is a marker of its verdict (:data:`VERDICT_MARKERS`, in
    the legend) annotated with how far it may go: in bar, the margin to
    parametric judder or the highest safe amplitude where the forced
    oscillation limits it; in Hz, the safe band at its amplitude, also
    drawn as a bar through the setting.

    Parameters
    ----------
    records : list of dict
        :func:`studies.check.setting_record` fields (Hz, bar).
    background : stability.maps.StabilityMap, optional
    min_growth : float, optional
        Passed to :func:`plot_map`.
    boundaries, tongues : optional
        The exact boundaries and tongues of ``background``
        (:func:`stability.tongues.tongue_boundaries`,
        :func:`stability.tongues.find_tongues`): the fills are clipped to
        them and the tongues numbered at their tips, as the map draws
        them; without them the grid's cells and its unit-modulus contour.
    judder : (Boundaries, list), optional
        The exact boundaries of growth at ``min_growth`` and their
        tongues: the judder line and the grey follow them
        (:func:`stability.plots.plot_map`).
    title : str, optional
        The model, after "dither settings: verdict and margins".
    """
    fig, ax = plt.subplots(figsize=(9, 5), layout="constrained")
    handles = []
    if background is not None:
        plot_map(background, ax=ax, min_growth=min_growth, legend=False,
                 boundaries=boundaries, tongues=tongues, judder=judder)
        handles = kind_handles(drawn_kinds(background, boundaries),
                               lines=boundaries is not None,
                               min_growth=min_growth)
        handles += [a for a in ax.lines if a.get_label() == BURIED_TIP]
        if boundaries is None:
            # the map's black line: where the grid's |lambda| reaches 1
            handles.append(Line2D([], [], color="k", linewidth=0.8,
                                  label=r"unstable from here "
                                        r"($|\lambda| = 1$)"))
    seen = {}
    band = None
    for r in records:
        if r.get("safe_band_hz") and None not in r["safe_band_hz"]:
            # the frequencies around the setting, at its amplitude, with
            # neither parametric judder nor a forced oscillation over
            # the limit: a bar with end ticks, white-rimmed over the fills
            low, high = r["safe_band_hz"]
            band, = ax.plot([low, high], [r["p_f_bar"]] * 2,
                            color=VERDICT_MARKERS[STABLE][1], linewidth=2.2,
                            marker="|", markersize=10, markeredgewidth=2.2,
                            zorder=4,
                            solid_capstyle="butt",
                            path_effects=[patheffects.withStroke(
                                linewidth=3.5, foreground="w")],
                            label="safe band at the setting's amplitude")
    for r in records:
        marker, color = VERDICT_MARKERS[r["verdict"]]
        # a large marker with a black rim: apart from every fill and from
        # the small triangles of the tongue tips (issue 46)
        line, = ax.plot(r["freq_hz"], r["p_f_bar"], marker=marker,
                        color=color, markeredgecolor="k", markersize=11,
                        markeredgewidth=1.0, linestyle="none", zorder=5,
                        label=f"setting: {r['verdict']}", clip_on=False)
        seen.setdefault(r["verdict"], line)
        bar = r["margin_bar"]
        if r.get("highest_safe_limited_by") == "forced":
            # the forced oscillation reaches the limit below the tongue:
            # that, not the parametric margin, is how far one can go
            bar_text = (f"safe to {r['highest_safe_p_f_bar']:.3f} bar "
                        "(forced)\n")
        else:
            bar_text = "" if bar is None else f"{bar:+.3f} bar\n"
        text = bar_text + band_text(r)
        if text:
            ax.annotate(text.strip(), (r["freq_hz"], r["p_f_bar"]),
                        xytext=(8, 8), textcoords="offset points", fontsize=7,
                        gid=LABEL_GID, zorder=6,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "w",
                              "ec": color, "lw": 0.6, "alpha": 0.9},
                        # a leader to its setting, also when moved up
                        arrowprops={"arrowstyle": "-", "color": color,
                                    "lw": 0.6, "shrinkA": 0,
                                    "shrinkB": 6})
    dither_axes(ax)
    ax.legend(handles=handles + ([band] if band else [])
              + list(seen.values()), fontsize=7,
              loc="upper left", bbox_to_anchor=(1.01, 1.0),
              borderaxespad=0.0)
    rate = "" if not min_growth else f" (>= {min_growth:g} 1/s)"
    # the figure's title, wrapped to its width: a long model path is not
    # clipped (issue 46)
    figure_title(fig, f"dither settings: verdict and margins to "
                      f"judder{rate}" + (f", {title}" if title else ""),
                 fontsize=10)
    settle_labels(fig)
    return fig

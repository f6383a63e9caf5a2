"""Sensitivity of the boundary to each parameter (Fig. 17, Fig. 18)."""

import matplotlib.pyplot as plt
import numpy as np

from infra.numbers import readable_number
from infra.plotstyle import CONTINUOUS_CMAP, figure_title, settle_labels
from infra.units import PA_PER_BAR

from .boundaries import boundary_curve, number_tips

__all__ = ["sensitivity_figure", "CASE_STYLES"]


#: Line styles of the varied cases of a sensitivity panel, after the
#: nominal solid line: long dashes, then dash-dot, dots, dash-dot-dot.
CASE_STYLES = ((0, (6, 2)), (0, (4, 1.5, 1, 1.5)), (0, (1, 1.2)),
               (0, (5, 1.5, 1, 1.5, 1, 1.5)))


def sensitivity_figure(study, title=None, params=None):
    """One panel per parameter: nominal boundary and the varied ones
    (Fig. 17, Fig. 18).

    Each curve is the lowest boundary with the tongue tips inserted and
    the tongues closed up to ``p_max``; the cases differ in colour
    (cividis) and line style, two panels a row. ``params`` (the nominal
    set) gives the units, and adds the damping factor zeta_12 of each
    case (Eq. 16, ``damper_zeta``) to the labels of c12.
    """
    names = list(dict.fromkeys(c.parameter for c in study.cases))
    # a case at the nominal value is the nominal line: drawn once
    varied = {name: [c for c in study.cases if c.parameter == name
                     and not np.isclose(c.factor, 1.0, rtol=1e-9, atol=0)]
              for name in names}
    factors = {tuple(np.round([c.factor for c in cases], 9))
               for cases in varied.values()}
    # the same factors in every panel (Fig. 17: halved, doubled): one
    # legend above the panels says the line styles, each panel's title its
    # values, and the panels take the whole width (issue 46); otherwise
    # (Fig. 18b's values of c12) each panel its legend on its right
    shared = len(names) > 1 and len(factors) == 1
    columns = min(2, len(names))
    rows = -(-len(names) // columns)
    fig = plt.figure(figsize=((4.6 if shared else 5.2) * columns,
                              (3.6 if shared else 3.3) * rows + 0.9),
                     layout="constrained")
    axes = fig.subplots(rows, columns, squeeze=False)
    for ax in list(axes.flat)[len(names):]:
        ax.remove()
    for ax, name in zip(axes.flat, names):
        cases = varied[name]
        colours = plt.get_cmap(CONTINUOUS_CMAP)(
            np.linspace(0.15, 0.8, max(len(cases), 1)))
        _plot_lowest(study.nominal, ax, "k", "-", "nominal", lw=1.6)
        # Fig. 14's numbers, at the tips the nominal curve reaches
        number_tips(ax, _tips_on_lowest(study.nominal), "k")
        for index, case in enumerate(cases):
            _plot_lowest(case, ax, colours[index],
                         CASE_STYLES[index % len(CASE_STYLES)],
                         _factor_word(case.factor) if shared else
                         _case_label(name, case, params), lw=1.3)
        if shared:
            ax.set_title(_shared_title(name, params, study.nominal, cases),
                         fontsize=9)
        else:
            ax.set_title(_panel_title(name, params, study.nominal),
                         fontsize=9)
            ax.legend(fontsize=7, loc="upper left",
                      bbox_to_anchor=(1.0, 1.0), borderaxespad=0.2,
                      handlelength=3)
    if shared:
        handles, labels = axes.flat[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center",
            ncols=len(handles), fontsize=9, handlelength=3.5,
            frameon=False)
    if title:
        figure_title(fig, title)
    settle_labels(fig)
    return fig


def _factor_word(factor):
    """``'halved'``, ``'doubled'``, or ``'x0.8'``."""
    return {0.5: "halved", 2.0: "doubled"}.get(round(float(factor), 9),
                                               f"x{factor:.3g}")


def _shared_title(name, params, nominal, cases):
    """A panel's title when the legend is shared: the parameter, its unit
    and its values, nominal first (``k24 [N m/rad]: 34 860; x0.5 17 430,
    x2 69 720``)."""
    text = _panel_title(name, params, nominal)
    def zeta(case):
        return (rf" ($\zeta_{{12}}$ = {100 * case.damper_zeta:.2g} %)"
                if _is_damper(name, params) else "")
    values = ", ".join(f"x{c.factor:.3g} {readable_number(c.value)}"
                       f"{zeta(c)}" for c in cases)
    return f"{text};\n{values}" if values else text


def _is_damper(name, params):
    """``name`` is the damping of the clutch damper of a registry
    driveline (Eq. 16 applies; a Modelica class or an FMU has no such
    role)."""
    return (params is not None and params.source_kind.is_chain
            and name == params.driveline.clutch_damper.damping)


def _panel_title(name, params, nominal):
    unit = params.specs[name].unit if params is not None else ""
    text = f"{name}" + (f" [{unit}]" if unit and unit != "1" else "")
    if params is not None:
        text += f", nominal {readable_number(params[name])}"
        if _is_damper(name, params):
            text += (rf" ($\zeta_{{12}}$ = "
                     f"{100 * nominal.damper_zeta:.2g} %)")
    return text


def _case_label(name, case, params):
    label = f"{name} = {readable_number(case.value)} (x{case.factor:.3g})"
    if _is_damper(name, params):
        label += (rf", $\zeta_{{12}}$ = "
                  f"{100 * case.damper_zeta:.2g} %")
    return label


def _tips_on_lowest(case):
    """The tongues of a case whose tip is on its lowest boundary: not
    above the lowest boundary around it (another tongue's may be lower
    there, and the tip is then hidden)."""
    b = case.boundaries
    lowest = b.stability_boundary / PA_PER_BAR
    return [t for t in case.tongues
            if not np.interp(t.tip_freq_hz, b.freq_hz, lowest)
            < t.tip_p_f / PA_PER_BAR * (1 - 1e-9)]


def _plot_lowest(case, ax, color, linestyle, label, lw=1.1):
    """A case's lowest boundary with its tips inserted, closed at p_max."""
    b = case.boundaries
    p_max_bar = b.p_max / PA_PER_BAR
    lowest = b.stability_boundary / PA_PER_BAR
    tips = [(t.tip_freq_hz, t.tip_p_f / PA_PER_BAR)
            for t in _tips_on_lowest(case)]
    x, y = boundary_curve(b.freq_hz, lowest,
                          tips, p_max_bar)
    ax.plot(x, y, color=color, linestyle=linestyle, linewidth=lw,
            label=label)
    ax.set_xlim(b.freq_hz.min(), b.freq_hz.max())
    ax.set_ylim(0, p_max_bar)
    ax.set_xlabel("dither frequency $f$ [Hz]")
    ax.set_ylabel("$p_f$ [bar]")

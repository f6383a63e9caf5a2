"""``judder report``: the paper's figure set and tables for one driveline,
in one self-contained HTML file.

The report runs the studies a user would run one by one
(:func:`studies.eig.eig`, :func:`studies.map.stability_map`,
:func:`studies.tongues.tongues`, :func:`studies.floquet.floquet`,
:func:`studies.sensitivity.sensitivity`, :func:`studies.fit.fit`) and
lays their numbers and figures out for a reader who was not at the
computer: what the driveline is, where it judders, whether the
configured dither is safe and by how much, what moves the tongues most,
and how well the model matches the bench. Figures are embedded as base64
PNG, so the file opens anywhere without its neighbours.

The report is a composer above the other studies: it calls them and
lays their results out.
"""

import dataclasses
from dataclasses import dataclass, field
import html

import numpy as np

from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from sources.dither_modes import linearised_mode, mode_words
from infra.criteria import CHART_THRESHOLD_SPREAD_PER_S

from ._report_sections import (Page, advice_section, chart_figure,
                               driveline_section, engagement_section,
                               fit_section, focus_tongue, kinds_section,
                               map_section, sensitivity_refused,
                               sensitivity_section, setting_section,
                               summary_section, threshold_section, tip_ranking)
from .advise import advise
from .check import check
from .eig import eig
from .fit import fit
from .floquet import floquet
from .map import stability_map
from .params import params
from .rules import refuse_decimal
from .sensitivity import sensitivity
from .simulate import simulate
from .threshold import threshold
from .tongues import tongue_record, tongues

#: Parameters varied in the report's sensitivity study, per model: those
#: of Fig. 17 and 18 where the model has them.
DEFAULT_SENSITIVITY = ("k12", "k24", "k", "J1", "J2", "J24", "J3", "J4",
                       "mu_g", "c12", "c")


#: Kinds of the Fig. 15 panels, in the paper's order (a, b, c); each
#: panel is drawn just inside (1.5 times the tip amplitude) the
#: driveline's lowest tongue of that kind.
_KIND_ORDER = ("single-period", "double-period", "combination")


@dataclass(frozen=True)
class ReportResult:
    """``judder report``: the HTML text and the numbers in it.

    Attributes
    ----------
    html : str
        The self-contained page.
    data : dict
        The numbers of its tables (the ``--json`` output).
    figures : list of str
        Titles of the embedded figures, in order.
    """

    html: str
    data: dict
    figures: list = field(default_factory=list)

    def as_dict(self):
        return {**self.data, "figures": list(self.figures)}

    @keeps_foreign_files
    def save(self, path):
        """Write the HTML file (atomically)."""
        write_text(path, self.html, overwrite=True)

    @keeps_foreign_files
    def save_pdf(self, path, html_path):
        """Print the saved HTML file ``html_path`` to PDF with a headless
        Chromium (Debian's ``chromium``; ``make browser`` installs it)."""
        from infra.pdf import print_pdf
        print_pdf(html_path, path)


def report(parameters=None, changes=None, description=None,
           freq_hz=None, p_f_bar=None, chart=None, boundary=None,
           group=None, decimal=None, fit_names=("c12", "mu_g", "k24"),
           sensitivity_names=None, grid_freq=None, map_freq=None,
           map_pf=None, p_max_bar=1.5, method="dyson", workers=None,
           engagement=False, min_growth=DEFAULT_MIN_GROWTH_PER_S,
           progress=None, driveline=None):
    """``judder report``: the figures and tables of the paper for one
    driveline.

    Parameters
    ----------
    parameters, changes
        The driveline, as for every API function.
    description : str, optional
        How the set was chosen (preset, file, ``--set``), for the title.
    freq_hz, p_f_bar : float, optional
        The configured dither setting (Hz, bar): its verdict, margin and
        multipliers (Fig. 15) head the report.
    chart : path, optional
        An experimental chart (``judder chart --out``): its boundary is
        fitted and drawn (Fig. 16a).
    boundary : path, optional
        A measured boundary CSV instead of ``chart``.
    group : str, optional
        The chart's group, when it has several.
    decimal : {'.', ','}, optional
        The decimal separator of ``boundary``, where its cells cannot
        tell it (:func:`studies.inputs.read_boundary_table`); refused with
        ``chart``.
    fit_names : sequence of str
        Parameters fitted to the bench data.
    sensitivity_names : sequence of str, optional
        Parameters of the sensitivity study (default: those of
        :data:`DEFAULT_SENSITIVITY` the model has).
    grid_freq : array_like, optional
        Frequencies of the tongue and sensitivity boundaries, Hz (default
        10-220 Hz, 300 points).
    map_freq, map_pf : array_like, optional
        Grid of the map, Hz and bar (default 5-250 Hz x 0-``p_max_bar``,
        246 x 121: 1 Hz x 0.0125 bar at 1.5 bar).
    p_max_bar : float
        Largest amplitude searched, bar.
    min_growth : float
        Judder-relevant growth rate, 1/s
        (:mod:`stability.decisions.relevance`):
        the verdict and the map's shading use it, as ``judder check``
        and ``judder map`` do (0: every instability); the tongues and
        tips are the stability boundaries of Fig. 14.
    engagement : bool
        With a dither setting: also run the bench engagement at it and
        without dither through the FMU (Fig. 7, 8; a few seconds); for a
        Modelica class, its own FMU from its steady slip
        (:func:`judder.simulate`). Refused for an FMU of ``--fmu``.
    workers : int, optional
        Local Dask workers of the sensitivity study and the fit. Default
        1 (in this process): the report's studies are small, and starting
        a local cluster costs more (about 6 s of CPU, measured) than it
        saves on a few cores; an existing ``--scheduler`` is used anyway.
    progress : callable, optional
        ``progress(done, total)`` over the report's sections.
    driveline : {'chain', 'bench'}, optional
        The driveline every Floquet section (modes, tongues, map, verdict,
        multipliers, advice, sensitivity) is of
        (:func:`stability.bench.driveline_view`; default the bench where the
        preset has one); Fig. 19 (no dither) and the fit stay the chain's.

    Returns
    -------
    ReportResult
    """
    from stability.bench import driveline_view
    values = params(parameters, changes).params
    driveline = driveline_view(values, driveline)[1]
    names = [n for n in (sensitivity_names or DEFAULT_SENSITIVITY)
             if sensitivity_names or n in values.specs]
    # bench data first: a bad file is refused before any work
    bench = _bench_data(chart, boundary, group, decimal)
    if bench is not None:
        # the fit's time, estimated as judder fit estimates it (one start,
        # three fits with a threshold spread): refused above the limit,
        # announced before the work
        from ._preflight import check_fit
        check_fit(len(bench[0]), 3 if bench[5] > 0 else 1,
                  "`chart`" if chart else "`boundary`", starts=False)
    for option, given in (("`sensitivity_names`", names),
                          ("`fit_names`", fit_names if bench else ())):
        unknown = [n for n in given if n not in values.specs]
        if unknown:
            raise JudderError(f"{option}: unknown parameter "
                              f"{unknown[0]!r} for the {values.model} "
                              "model; allowed names: "
                              f"{', '.join(values.specs)}")
    paper = values.source_kind.is_chain     # a registry driveline
    run_engagement = engagement and freq_hz is not None and (
        not paper or values.driveline.bench_class is not None)
    if run_engagement:
        from .timedomain import class_fmu
        class_fmu(values, "the report's engagement")   # refuses an FMU now
    workers = 1 if workers is None else workers
    grid_freq = np.linspace(10, 220, 300) if grid_freq is None \
        else np.asarray(grid_freq, dtype=float)
    map_freq = np.linspace(5, 250, 246) if map_freq is None else map_freq
    map_pf = np.linspace(0, p_max_bar, 121) if map_pf is None else map_pf
    page = Page(description or values.model)
    data = {"model": values.model, "description": page.description,
            "driveline": driveline}
    mode = linearised_mode(values)
    if mode:
        # as judder map says it: the studies over amplitudes hold the mode
        # at each frequency's largest amplitude
        data.update(mode=mode, mode_checked_at_p_f_bar=float(p_max_bar))
    step = _Steps(7 + bool(bench), progress)

    # the driveline (its table closes the report, as an appendix)
    modes = eig(values, driveline=driveline).as_dict()
    data["natural_frequencies_hz"] = list(modes["natural_frequencies_hz"])
    data["damping_factor_12_percent"] = modes["damping_factor_12_percent"]
    step()

    # tongues, and the map they are drawn over
    found = tongues(grid_freq, p_max_bar, values, method=method,
                    judder_growth=min_growth, driveline=driveline)
    stability = dataclasses.replace(
        stability_map(map_freq, map_pf, values, method=method,
                      min_growth=min_growth, driveline=driveline),
        boundaries=found.boundaries, tongues=found.tongues)
    step()
    data["tongues"] = [
        {key: record[key] for key in ("number", "kind", "resonance",
                                      "tip_freq_hz", "tip_p_f_bar",
                                      "judder_tip_p_f_bar")}
        for record in (tongue_record(t, found.judder_tongues)
                       for t in found.tongues)]

    # the configured dither, and what to do (advise)
    point = verdict = None
    if freq_hz is not None and p_f_bar is not None:
        point, verdict = _setting(values, freq_hz, p_f_bar, min_growth,
                                  p_max_bar, driveline)
        data["verdict"] = verdict
    step()
    advice, advice_error = None, None
    try:
        # the wide view: where the advised design's tongues went, beyond
        # the operating range, as judder advise --plot draws it
        advice = advise(values, min_growth=min_growth, background=True,
                        driveline=driveline)
    except JudderError as error:        # e.g. no design parameter
        advice_error = str(error)
    step()
    if advice is not None:
        data["advice"] = advice.as_dict()
    from stability.bench import driveline_words
    page.sections.append(summary_section(
        verdict, advice, advice_error, min_growth,
        driveline_words(values, driveline)))
    if point is not None:
        page.sections.append(setting_section(page, point, freq_hz, p_f_bar))
    page.sections.append(map_section(
        page, stability, data["tongues"], min_growth, p_max_bar,
        (grid_freq.min(), grid_freq.max()), mode_words(mode, p_max_bar)))
    page.sections.append(kinds_section(page, _inside_each_kind(
        found.tongues, values, p_max_bar, method, driveline)))
    if advice is not None:
        page.sections.append(advice_section(page, advice))

    try:
        sens = sensitivity(names, grid_freq, p_max_bar, parameters=values,
                           method=method, workers=workers,
                           driveline=driveline)
    except JudderError as error:
        # a changed set that leaves a hybrid class's mode: the other
        # sections stand, this one says why it is missing
        sens = None
        data["sensitivity_error"] = str(error)
        page.sections.append(sensitivity_refused(str(error)))
    step()
    if sens is not None:
        focus = focus_tongue(found.tongues, freq_hz)
        ranking = tip_ranking(sens.tip_shifts, focus)
        data["sensitivity_ranking"] = {"tongue": focus, "ranking": ranking}
        page.sections.append(sensitivity_section(
            page, sens, focus, ranking, freq_hz is not None, advice))

    # without dither (Fig. 19): a study of the paper's chains
    if paper:
        study = threshold(np.linspace(-1e-3, 1e-3, 41),
                          np.linspace(0, 2, 21), values)
        data["mu_g_threshold"] = float(study.study.threshold)
        page.sections.append(threshold_section(page, values, study))
    step()

    if run_engagement:
        run = simulate(freq_hz, p_f_bar, compare="none", parameters=values,
                       method=method, min_growth=min_growth)
        data["engagement"] = run.summaries[0]
        page.sections.append(engagement_section(page, run, paper))

    if bench:
        freqs, measured, tried, bench_growth, below_bar, spread = bench
        try:
            fitted, error = fit(freqs, measured / PA_PER_BAR, tried,
                                names=list(fit_names), parameters=values,
                                method=method, workers=workers,
                                min_growth=bench_growth, below_bar=below_bar,
                                threshold_spread=spread), None
        except JudderError as refused:
            fitted, error = None, refused
        text, fit_data, fitted = fit_section(
            bench, fit_names, values, html.escape(str(chart or boundary)),
            fitted, error)
        step()
        data.update(fit_data)
        if chart:
            text += chart_figure(page, chart, group)
        page.sections.append(text + ("" if fitted is None else page.figure(
            "Measured and fitted boundaries (Fig. 16a)", fitted.figure())))
    step()

    page.sections.append(driveline_section(values, modes))
    return ReportResult(html=page.html(), data=data, figures=page.figures)


class _Steps:
    """``progress(done, total)`` called once per finished study."""

    def __init__(self, total, progress):
        self.total, self.done, self.progress = total, 0, progress

    def __call__(self):
        self.done += 1
        if self.progress:
            self.progress(self.done, self.total)


def _bench_data(chart, boundary, group, decimal):
    """The bench data to fit, as :func:`fit_section` takes them: a
    chart's boundary (with its tried points, growth rate, amplitudes
    below and threshold spread) or a measured boundary CSV (censored at
    the amplitudes it says were tried); None without either."""
    from .inputs import (boundary_p_max, read_boundary_min_growth,
                         read_boundary_tested, read_chart_below,
                         read_chart_boundary, read_chart_min_growth)
    if not boundary:
        refuse_decimal(decimal, "a `boundary` file (CSV)",
                       "with `chart` (an NPZ)" if chart else
                       "without a `boundary` file")
    if chart:
        return (*read_chart_boundary(chart, group),
                read_chart_min_growth(chart),
                read_chart_below(chart, group) / PA_PER_BAR,
                CHART_THRESHOLD_SPREAD_PER_S)
    if boundary:
        table = read_boundary_tested(boundary, decimal=decimal)
        stated = read_boundary_min_growth(boundary, decimal=decimal)
        return (table["freq_hz"], table["p_f"],
                boundary_p_max(table, None, boundary, pf_option=None),
                DEFAULT_MIN_GROWTH_PER_S if stated is None else stated,
                np.where(np.isnan(table["p_f"]), np.nan,
                         table["no_judder"]) / PA_PER_BAR, 0.0)
    return None


def _setting(values, freq_hz, p_f_bar, min_growth, p_max_bar,
             driveline=None):
    """``judder check`` at the configured setting, at the growth rate
    that shades the map (the tongues are the stability boundaries of Fig.
    14): its Floquet result and its record with the leading ``|lambda|``."""
    checked = check([freq_hz], [p_f_bar], values, min_growth=min_growth,
                    p_max_bar=max(p_max_bar, 2 * p_f_bar), sensitivity=(),
                    driveline=driveline)
    point = checked.checks[0].floquet
    return point, {**checked.records()[0],
                   "leading_abs": float(point.leading_abs)}


def _inside_each_kind(found, values, p_max_bar, method, driveline=None):
    """Floquet results just inside (1.5 times the tip amplitude) the
    lowest tongue of each kind, in the order of :data:`_KIND_ORDER`
    (Fig. 15)."""
    inside = []
    for kind in _KIND_ORDER:
        same = [t for t in found if t.kind == kind]
        if same:
            t = min(same, key=lambda t: t.tip_p_f)
            inside.append(floquet(t.tip_freq_hz,
                                  min(1.5 * t.tip_p_f / PA_PER_BAR,
                                      p_max_bar), values,
                                  method=method, driveline=driveline).result)
    return inside



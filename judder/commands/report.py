"""``judder report``: the paper's figure set and tables for one driveline,
in one self-contained HTML file.

The report runs the API functions a user would run one by one
(:func:`judder.api.eig`, :func:`~judder.api.stability_map`,
:func:`~judder.api.tongues`, :func:`~judder.api.floquet`,
:func:`~judder.api.sensitivity`, :func:`~judder.api.fit`) and lays their
numbers and figures out for a reader who was not at the computer: what
the driveline is, where it judders, whether the configured dither is
safe and by how much, what moves the tongues most, and how well the model
matches the bench. Figures are embedded as base64 PNG, so the file opens
anywhere without its neighbours.

The report is a composer above the other commands: it calls their API
functions and lays their results out.
"""

import base64
import dataclasses
from dataclasses import dataclass, field
import datetime
import html
import io
from pathlib import Path
import re
import shutil
import subprocess
import tempfile

import numpy as np

from infra.criteria import DEFAULT_MIN_GROWTH_PER_S, ENGAGEMENT_DURATION_S
from infra.errors import JudderError
from infra.files import (MARK, atomic_write, keeps_foreign_files, mark_pdf,
                         write_text)
from infra.numbers import format_interval, format_uncertain
from infra.provenance import current
from infra.units import PA_PER_BAR
from stability.decisions.relevance import (CHART_THRESHOLD_SPREAD_PER_S,
                                           JUDDER, SLOW_GROWTH)

from ._arguments import (force_option, method_option, min_growth_option,
                         model_options, workers_option)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, output_files, written
from ._values import FREQ, PF, Grid, Listed
from .advise import advise
from .check import check, growth_words, margin_words
from .eig import eig
from .fit import fit
from .floquet import floquet
from .map import check_map_grid, stability_map
from .params import params
from .sensitivity import sensitivity
from .simulate import simulate
from .threshold import threshold
from .tongues import tongue_record, tongues

#: The command's --help text.
DESCRIPTION = (
    "Run the studies of the paper for one driveline and write one "
    "self-contained HTML file (figures embedded): the driveline, the "
    "verdict and margin of the configured dither (--freq, --pf) with "
    "its multipliers (Fig. 15), the map with the exact tongues (Fig. "
    "14) and their tips, the sensitivity ranking (Fig. 17, 18), and the "
    "fit to bench data (--chart or --boundary, Fig. 16a). Open it in a "
    "browser; print it to PDF from there.")
OUTPUTS = (("out", "--out", ("html",)), ("pdf", "--pdf", ("pdf",)))


#: Parameters varied in the report's sensitivity study, per model: those
#: of Fig. 17 and 18 where the model has them.
DEFAULT_SENSITIVITY = ("k12", "k24", "k", "J1", "J2", "J24", "J3", "J4",
                       "mu_g", "c12", "c")


#: Kinds of the Fig. 15 panels, in the paper's order (a, b, c); each
#: panel is drawn just inside (1.5 times the tip amplitude) the
#: driveline's lowest tongue of that kind.
_KIND_ORDER = ("single-period", "double-period", "combination")


_CSS = """
@page{size:A4;margin:14mm 13mm}
body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;
color:#111;line-height:1.4}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #999;
margin-top:1.6em}
h2,h3{break-after:avoid;page-break-after:avoid}
table{border-collapse:collapse;margin:0.8em 0}
td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:left;
font-size:0.9em;vertical-align:top}
th{background:#eee}
table.facts th{width:12em}
img{max-width:100%;height:auto;display:block;margin:0.8em auto}
figure{margin:0.5em 0;break-inside:avoid;page-break-inside:avoid}
figcaption{font-size:0.85em;color:#444;text-align:center}
tr,.keep{break-inside:avoid;page-break-inside:avoid}
.verdict{font-size:1.1em;padding:0.6em;border:2px solid #333}
.judder{border-color:#b00;background:#fee}
.slow{border-color:#a60;background:#fff6e0}
.safe{border-color:#070;background:#efe}
.none{border-color:#555;background:#f4f4f4}
.small{font-size:0.85em;color:#444}
@media print{body{margin:0;max-width:none;font-size:10pt}
img{max-height:235mm;width:auto}}
"""


#: Flags of a headless Chromium that reads only the given file.
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu",
                  "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--no-first-run", "--no-pdf-header-footer")


#: The report's map grid: 1 Hz x 0.0125 bar, two thirds of the points of
#: ``judder map``'s (the exact boundaries are drawn over it; the report
#: stays under 20 s, docs/figures.md).
REPORT_MAP_FREQ = "5:250:246"


REPORT_MAP_PF = "0:1.5:121"


def add_arguments(p):
    """The options of ``judder report``."""
    p.add_argument("--out", required=True, metavar="FILE.html",
                   help="the report")
    p.add_argument("--pdf", metavar="FILE.pdf",
                   help="also print it to PDF (needs Debian's chromium)")
    p.add_argument("--engagement", action="store_true",
                   help="with --freq and --pf: also run the bench "
                        "engagement through the FMU (Fig. 7, 8)")
    p.add_argument("--freq", type=FREQ, metavar="HZ",
                   help="dither frequency of the configured setting, Hz")
    p.add_argument("--pf", type=PF, metavar="BAR",
                   help="dither amplitude of the configured setting, bar")
    source = p.add_mutually_exclusive_group()
    source.add_argument("--chart", metavar="FILE.npz",
                        help="bench data: a chart (judder chart --out)")
    source.add_argument("--boundary", metavar="FILE.csv",
                        help="bench data: a measured boundary "
                             "(freq_hz,p_f_bar)")
    p.add_argument("--group", metavar="VALUE",
                   help="group of the chart, when it has several")
    p.add_argument("--fit", type=Listed("--fit", str),
                   default="c12,mu_g,k24", metavar="NAMES",
                   help="parameters fitted to the bench data (default "
                        "c12,mu_g,k24)")
    p.add_argument("--sensitivity", type=Listed("--sensitivity", str),
                   metavar="NAMES",
                   help="parameters of the sensitivity study (default the "
                        "stiffnesses, inertias, mu_g and c12)")
    p.add_argument("--grid", type=Grid("--grid", "Hz"),
                   default="10:220:300", metavar="START:STOP:N",
                   help="frequencies of the boundaries, Hz (default "
                        "10:220:300)")
    p.add_argument("--map-freq", type=Grid("--map-freq", "Hz"),
                   default=REPORT_MAP_FREQ,
                   metavar="START:STOP:N",
                   help=f"map frequencies, Hz (default {REPORT_MAP_FREQ})")
    p.add_argument("--map-pf", type=Grid("--map-pf", "bar"),
                   default=REPORT_MAP_PF, metavar="START:STOP:N",
                   help=f"map amplitudes, bar (default {REPORT_MAP_PF})")
    min_growth_option(p, "; the verdict and the map's shading use it")
    workers_option(p)
    method_option(p)
    model_options(p)
    force_option(p)


def run(args):
    """The paper's figures and tables for one driveline, as one HTML
    file."""
    if (args.freq is None) != (args.pf is None):
        raise JudderError("--freq and --pf go together: give both for a "
                          "dither setting, or neither")
    grid = args.grid
    map_freq = args.map_freq
    map_pf = args.map_pf
    if grid[0] <= 0 or map_freq[0] <= 0:
        raise JudderError("--grid, --map-freq: allowed: frequencies > 0 Hz")
    params, changes = parameters_of(args)
    check_map_grid(params.replace(**changes), map_freq, map_pf,
                    "--map-freq x --map-pf", args.method, True)
    make_parents(args.out)
    with Progress(None, "report") as progress:
        result = report(
            params, changes, description=model_title(args, params),
            freq_hz=args.freq, p_f_bar=args.pf, chart=args.chart,
            boundary=args.boundary, group=args.group,
            fit_names=args.fit, sensitivity_names=args.sensitivity,
            grid_freq=grid, map_freq=map_freq, map_pf=map_pf,
            p_max_bar=float(map_pf[-1]) if map_pf[-1] > 0 else 1.5,
            method=args.method, workers=args.workers,
            engagement=args.engagement, min_growth=args.min_growth,
            progress=progress)
    result.save(args.out, force=args.force)
    if args.pdf:
        make_parents(args.pdf)
        result.save_pdf(args.pdf, args.out, force=args.force)
    verdict = result.data.get("verdict")
    text = (f"{len(result.figures)} figures"
            + (f"; dither {args.freq:g} Hz, {args.pf:g} bar: "
               f"{verdict['verdict']}" if verdict else "")
            + (f"\nbench data: {result.data['fit_status']}"
               if "fit_status" in result.data else "")
            + written(args.out, args.pdf))
    emit(args, {**result.as_dict(),
                **output_files(out=args.out, pdf=args.pdf)},
         text)


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
        print_pdf(html_path, path)


def _png(fig, dpi=100):
    """A figure as a base64 PNG ``<img>``; closes the figure."""
    import matplotlib.pyplot as plt
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return f'<img alt="" src="data:image/png;base64,{data}">'


def _fit_section(bench, names, values, method, workers, source):
    """Section 6: the fit to the bench data, shown only when the data
    determine every fitted value (else one sentence saying why not).

    Returns the section's HTML, its data (``fit``, ``fit_determined``,
    ``fit_status``, ``fit_problems``) and the fit report to draw (None when
    the fit is not shown)."""
    freqs, measured, tried, min_growth, below_bar, spread = bench
    onsets = int(np.sum(np.isfinite(measured)))
    head = _keep("<h2>The bench data and the fit</h2>"
                 f"<p>{len(freqs)} measured points from {source}, {onsets} "
                 f"with judder; fitting {', '.join(names)} to the model's "
                 f"boundary of judder growing at {min_growth:g} 1/s or "
                 "faster.</p>")
    try:
        fitted = fit(freqs, measured / PA_PER_BAR, tried,
                     names=list(names), parameters=values,
                     method=method, starts=1, workers=workers,
                     min_growth=min_growth, below_bar=below_bar,
                     threshold_spread=spread)
    except JudderError as error:
        status = f"no fit: {error}"
        return (head + f"<p><b>No fit is shown</b>: {html.escape(str(error))}"
                ".</p>", {"fit": None, "fit_determined": False,
                          "fit_status": status, "fit_problems": [str(error)]},
                None)
    r = fitted.fit
    problems = list(r.problems)
    if not r.determined:
        missing = list(r.undetermined) + [n for n in r.at_bound
                                          if n not in r.undetermined]
        status = ("no fit: the bench data do not determine "
                  + ", ".join(missing or r.names))
        return (head + f"<p><b>No fit is shown</b>: the bench data do not "
                f"determine {html.escape(', '.join(missing or r.names))}. "
                + " ".join(html.escape(p[0].upper() + p[1:]) + "."
                           for p in problems) + "</p>",
                {"fit": None, "fit_determined": False, "fit_status": status,
                 "fit_problems": problems}, None)
    lines = fitted.text()
    status = "fitted " + "; ".join(line.strip() for line in lines[:len(
        r.names)])
    rows = [(n, f"{s0:.5g}", format_uncertain(v, s, values.specs[n].unit),
             format_interval(lo, hi, s))
            for n, s0, v, s, lo, hi in zip(r.names, r.start, r.values, r.std,
                                           r.ci_low, r.ci_high)]
    text = (head + _table(("parameter", "start", "fitted ± 1 sigma",
                           "95 % interval"),
                          rows)
            + "".join(f"<p>{html.escape(line)}</p>"
                      for line in lines[len(r.names):])
            + "".join(f"<p>problem: {html.escape(p)}</p>" for p in problems))
    return (text, {"fit": {n: {"value": v, "std": s, "ci95": [lo, hi]}
                           for n, v, s, lo, hi in zip(r.names, r.values,
                                                      r.std, r.ci_low,
                                                      r.ci_high)},
                   "fit_determined": True, "fit_status": status,
                   "fit_success": bool(r.success), "fit_problems": problems},
            fitted)


def _table(header, rows):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>"
                                    for c in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _verdict_text(v, engagement_s=ENGAGEMENT_DURATION_S):
    """The configured dither's verdict in words, from a record of
    ``judder check`` (:func:`setting_record`) with the
    leading ``|lambda|`` added: the verdict word, what the multiplier
    does, the growth against an engagement of ``engagement_s`` seconds
    and both margins to judder."""
    tongue = v["tongue"]
    if not v["inside_stability_tongue"]:
        what = "every multiplier inside the unit circle"
    else:
        what = (f"{v['kind']} instability"
                + ("" if tongue is None else
                   f" in tongue {tongue['number'] or '?'}"))
    growth = growth_words(v, engagement_s)
    if v["verdict"] == SLOW_GROWTH:
        growth += (f", slower than the judder-relevant "
                   f"{v['min_growth_per_s']:g} 1/s")
    amplitude, frequency = margin_words(v)
    return (f"{v['verdict']} at {v['freq_hz']:g} Hz, {v['p_f_bar']:g} bar: "
            f"{what} (|\u03bb| = {v['leading_abs']:.4f}); {growth}; "
            f"{amplitude}; {frequency}.")


def _window_text(advice):
    """The safe dither windows of ``judder advise`` in one sentence."""
    op = advice.operating
    top = op.p_max / PA_PER_BAR
    full = [w for w in advice.windows if w.full_range]
    head = (f"Within {op.freq_hz[0]:g}-{op.freq_hz[1]:g} Hz, keeping "
            f"{op.margin_p_f / PA_PER_BAR:g} bar and {op.margin_hz:g} Hz "
            "from every judder-relevant tongue: ")
    if full:
        return head + f"safe up to {top:g} bar at " + ", ".join(
            f"{w.freq_hz[0]:.1f}-{w.freq_hz[1]:.1f} Hz" for w in full) + "."
    best = int(np.argmax(advice.safe_p_f))
    return head + (f"no frequency is safe up to {top:g} bar; the most "
                   f"amplitude is {advice.safe_p_f[best] / PA_PER_BAR:.3f} "
                   f"bar, at {advice.freq_hz[best]:.1f} Hz.")


def _design_text(advice):
    """The smallest design change of ``judder advise`` in one sentence
    (factors within 1 % of 1 left out)."""
    a = advice.advice
    if a is None:
        return "not searched."
    if not a.success:
        return f"none found: {a.message}."
    advised = advice.advised_params()
    from infra.numbers import readable_number
    changes = [f"{n} x{f:.2f} ({readable_number(advice.params[n])} to "
               f"{readable_number(advised[n])} {advice.params.specs[n].unit})"
               for n, f in zip(a.names, a.factors) if abs(f - 1) > 0.01]
    if not changes:
        return "none needed: the window is already clear."
    return (", ".join(changes) + " clears the window; the map recomputed "
            f"with it has {advice.judder_points} judder points of "
            f"{advice.verification.kind.size}.")


def _ranking(tip_shifts, tongue_number):
    """Per parameter, the largest relative move of one tongue's tip (in
    amplitude and frequency) over its variations, largest first."""
    table = {}
    for row in tip_shifts:
        if row["tongue"] != tongue_number:
            continue
        base_p = row["tip_p_f_bar"] - row["d_p_f_bar"] if row["present"] \
            else None
        entry = table.setdefault(row["parameter"],
                                 {"parameter": row["parameter"],
                                  "p_f_percent": 0.0, "freq_percent": 0.0,
                                  "vanishes": False})
        if not row["present"]:
            entry["vanishes"] = True
            continue
        base_f = row["tip_freq_hz"] - row["d_freq_hz"]
        entry["p_f_percent"] = max(entry["p_f_percent"],
                                   abs(100 * row["d_p_f_bar"] / base_p))
        entry["freq_percent"] = max(entry["freq_percent"],
                                    abs(100 * row["d_freq_hz"] / base_f))
    return sorted(table.values(), key=lambda e: (
        not e["vanishes"], -max(e["p_f_percent"], e["freq_percent"])))


def report(parameters=None, changes=None, description=None,
           freq_hz=None, p_f_bar=None, chart=None, boundary=None,
           group=None, fit_names=("c12", "mu_g", "k24"),
           sensitivity_names=None, grid_freq=None, map_freq=None,
           map_pf=None, p_max_bar=1.5, method="dyson", workers=None,
           engagement=False, min_growth=DEFAULT_MIN_GROWTH_PER_S,
           progress=None):
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

    Returns
    -------
    ReportResult
    """
    from stability.plots import multipliers_figure

    from ..inputs import (read_boundary, read_chart_below, read_chart_boundary,
                          read_chart_min_growth)
    values = params(parameters, changes).params
    description = description or values.model
    workers = 1 if workers is None else workers
    grid_freq = np.linspace(10, 220, 300) if grid_freq is None \
        else np.asarray(grid_freq, dtype=float)
    map_freq = np.linspace(5, 250, 246) if map_freq is None else map_freq
    map_pf = np.linspace(0, p_max_bar, 121) if map_pf is None else map_pf
    names = [n for n in (sensitivity_names or DEFAULT_SENSITIVITY)
             if sensitivity_names or n in values.specs]
    # bench data first: a bad file is refused before any work
    bench = None
    if chart:
        bench = (*read_chart_boundary(chart, group),
                 read_chart_min_growth(chart),
                 read_chart_below(chart, group) / PA_PER_BAR,
                 CHART_THRESHOLD_SPREAD_PER_S)
    elif boundary:
        bench = (*read_boundary(boundary, "--boundary"), p_max_bar,
                 DEFAULT_MIN_GROWTH_PER_S, None, 0.0)
    for option, given in (("--sensitivity", names),
                          ("--fit", fit_names if bench else ())):
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
        from ..timedomain import class_fmu
        class_fmu(values, "report --engagement")   # refuses --fmu now
    steps = 7 + bool(bench)
    done = [0]

    def step():
        done[0] += 1
        if progress:
            progress(done[0], steps)

    sections, figures, data = [], [], {"model": values.model,
                                       "description": description}

    def figure(title, fig):
        figures.append(title)
        return f"<figure>{_png(fig)}<figcaption>{html.escape(title)}" \
               f"</figcaption></figure>"

    # the driveline (its table closes the report, as an appendix)
    modes = eig(values).as_dict()
    data["natural_frequencies_hz"] = list(modes["natural_frequencies_hz"])
    data["damping_factor_12_percent"] = modes["damping_factor_12_percent"]
    step()

    # tongues, and the map they are drawn over
    found_tongues = tongues(grid_freq, p_max_bar, values, method=method,
                            judder_growth=min_growth)
    stability = dataclasses.replace(
        stability_map(map_freq, map_pf, values, method=method,
                      min_growth=min_growth),
        boundaries=found_tongues.boundaries, tongues=found_tongues.tongues)
    step()
    data["tongues"] = [
        {"number": t.number, "kind": t.kind, "resonance": t.resonance,
         "tip_freq_hz": t.tip_freq_hz, "tip_p_f_bar": t.tip_p_f / PA_PER_BAR}
        for t in found_tongues.tongues]
    tip_rows = [(t["number"] or "-", t["kind"], t["resonance"] or "-",
                 f"{t['tip_freq_hz']:.2f}", f"{t['tip_p_f_bar']:.4f}",
                 "-" if t["judder_tip_p_f_bar"] is None else
                 f"{t['judder_tip_p_f_bar']:.4f}")
                for t in (tongue_record(t, found_tongues.judder_tongues)
                          for t in found_tongues.tongues)]

    # the configured dither
    verdict = point = None
    if freq_hz is not None and p_f_bar is not None:
        # judder check at the setting, at the growth rate that shades
        # the map (the tongues are the stability boundaries of Fig. 14)
        checked = check([freq_hz], [p_f_bar], values,
                        min_growth=min_growth,
                        p_max_bar=max(p_max_bar, 2 * p_f_bar),
                        sensitivity=())
        point = checked.checks[0].floquet
        verdict = {**checked.records()[0],
                   "leading_abs": float(point.leading_abs)}
        data["verdict"] = verdict
    step()

    # what to do: safe windows and the smallest design change (advise)
    advice, advice_error = None, None
    try:
        advice = advise(values, min_growth=min_growth)
    except JudderError as error:        # e.g. no design parameter
        advice_error = str(error)
    step()
    if advice is not None:
        data["advice"] = advice.as_dict()
    sections.append(_summary_section(verdict, advice, advice_error,
                                     min_growth))

    if point is not None:
        sections.append(_keep(
            "<h2>The configured dither: its multipliers</h2>"
            + figure(f"Floquet multipliers at {freq_hz:g} Hz, {p_f_bar:g} "
                     "bar (Fig. 15)",
                     multipliers_figure([point], title="Floquet multipliers "
                                        f"at {freq_hz:g} Hz, {p_f_bar:g} "
                                        f"bar, {description}"))))

    sections.append(_keep(
        "<h2>Where it judders: the stability map</h2>"
        f'<p class="small">Judder-relevant: growing faster than '
        f"{min_growth:g} 1/s (judder check --min-growth {min_growth:g}); "
        "slower growth is shaded grey; the lines are the exact stability "
        "boundaries (Fig. 14).</p>"
        + figure("Stability map with the exact tongue boundaries and "
                 "numbers (Fig. 14)",
                 stability.figure(title=f"stability map, {description}",
                                  stacked=True)))
        + "<p>Tongue tips, numbers as in Fig. 14: where each tongue becomes "
          "unstable (|lambda| = 1; its tip, refined between grid points) "
          f"and the lowest amplitude where it judders (grows at "
          f"{min_growth:g} 1/s or faster; - : not up to {p_max_bar:g} "
          "bar):</p>"
        + _table(("#", "kind", "resonance", "tip f [Hz]",
                  "unstable from p_f [bar]", "judders from p_f [bar]"),
                 tip_rows))
    # Fig. 15 by kind, at points just inside each kind's lowest tongue
    inside = []
    for kind in _KIND_ORDER:
        found = [t for t in found_tongues.tongues if t.kind == kind]
        if found:
            t = min(found, key=lambda t: t.tip_p_f)
            inside.append(floquet(t.tip_freq_hz,
                                  min(1.5 * t.tip_p_f / PA_PER_BAR,
                                      p_max_bar), values,
                                  method=method).result)
    if inside:
        sections.append(_keep(
            "<h3>How the multipliers leave the unit circle, by kind</h3>"
            + figure("Floquet multipliers just inside the lowest tongue of "
                     "each kind (Fig. 15)",
                     multipliers_figure(inside, title="Floquet multipliers "
                                        "by kind of instability (Fig. 15), "
                                        f"{description}"))))

    if advice is not None:
        sections.append(_keep(
            "<h2>Safe dither windows and the design change</h2>"
            + f"<p>{html.escape(_window_text(advice))}</p>"
            + "<p>Design parameters ranked by how much of the way out of "
              "the window a relative change takes the judder-relevant "
              "tongues (the share of that way a change of the value by a "
              "factor e = 2.72 moves the tongue that needs most; 1 = all "
              "the way): "
            + html.escape(", ".join(f"{n} {share:.2f}"
                          for n, share, _ in advice.ranking))
            + ".</p>"
            + figure("Safe dither amplitude per frequency, and the map of "
                     "the advised design (judder advise)",
                     advice.figure(title=description))))

    # sensitivity
    sens = sensitivity(names, grid_freq, p_max_bar, parameters=values,
                       method=method, workers=workers)
    step()
    focus = _focus_tongue(found_tongues.tongues, freq_hz)
    ranking = _ranking(sens.tip_shifts, focus)
    data["sensitivity_ranking"] = {"tongue": focus, "ranking": ranking}
    sections.append(_keep(
        "<h2>What moves the tongues: sensitivity</h2>"
        f"<p>Each parameter halved and doubled (Fig. 17, 18). Ranking by "
        f"the largest relative move of tongue {focus}'s tip"
        + (" (the tongue nearest the configured dither)"
           if freq_hz is not None else "") + ":</p>"
        + _table(("parameter", "tip p_f moves up to [%]",
                  "tip f moves up to [%]", "tongue vanishes"),
                 [(e["parameter"], f"{e['p_f_percent']:.1f}",
                   f"{e['freq_percent']:.2f}",
                   "yes" if e["vanishes"] else "no") for e in ranking])
        + _rankings_differ(ranking, advice))
        + figure("Sensitivity of the stability boundary (Fig. 17, 18)",
                 sens.figure(title=f"sensitivity, {description}")))

    # without dither (Fig. 19): a study of the paper's chains
    if paper:
        study = threshold(np.linspace(-1e-3, 1e-3, 41),
                                  np.linspace(0, 2, 21), values)
        data["mu_g_threshold"] = float(study.study.threshold)
        sections.append(_threshold_section(values, study, figure))
    step()

    if run_engagement:
        from pysim.simulation.engagement import judder_words
        run = simulate(freq_hz, p_f_bar, compare="none",
                       parameters=values, method=method,
                       min_growth=min_growth)
        first = run.summaries[0]
        data["engagement"] = first
        sections.append(
            "<h2>The engagement "
            + ("on the bench model" if paper else "of the class's FMU")
            + f"</h2><p>Through the {html.escape(run.model_class)} FMU"
            + ("" if paper else " from its start values (a steady slip)")
            + ": upstream speed peak "
            f"{first['speed_peak_amplitude_rpm']:.3g} rpm at "
            f"{first['speed_peak_freq_hz']:.2f} Hz; read as a chart reads "
            "a bench run: " + html.escape(judder_words(first))
            + f"; Floquet exponent of the bench's linearisation (the "
            f"driveline with the damping of the bench's speed control, "
            f"so not section 1's) {first['floquet_exponent_per_s']:+.2f} 1/s"
            + ("" if first.get("orbit_kind") is None else
               f"; the periodic orbit it settles on: "
               f"{first['orbit_settled_rpm']:.3g} rpm, "
               f"{first['orbit_kind']} "
               f"({first['orbit_growth_per_s']:+.2f} 1/s), "
               + (f"judder ({first['orbit_mechanism']})"
                  if first["orbit_mechanism"] else "no judder"))
            + ("" if first.get("linearisation_holds") is not False else
               f". The dither's forced slip swing "
               f"({first['forced_slip_amplitude_rad_s']:.2g} rad/s) exceeds "
               f"the friction curve's linear range "
               f"({first['friction_linear_range_rad_s']:.2g} rad/s): the run "
               "is nonlinear and need not follow the Floquet verdict")
            + ".</p>"
            + figure("Engagement with the configured dither and without "
                     "(Fig. 7, 8)",
                     run.figure(title=f"time-domain run, {description}")))

    # bench data
    if bench:
        text, fit_data, fitted = _fit_section(
            bench, fit_names, values, method, workers,
            html.escape(str(chart or boundary)))
        step()
        data.update(fit_data)
        sections.append(text + ("" if fitted is None else figure(
            "Measured and fitted boundaries (Fig. 16a)", fitted.figure())))
    step()

    rows = [(name, f"{values[name]:.6g}", spec.unit, spec.description)
            for name, spec in values.specs.items()]
    sections.append(_keep(
        "<h2>The driveline and its parameters</h2>"
        "<p>Natural frequencies (Eq. 15): "
        + ", ".join(f"{f:.3f} Hz" for f in modes["natural_frequencies_hz"])
        + ("" if modes["damping_factor_12"] is None else
           "; clutch-damper damping factor zeta_12 (Eq. 16): "
           f"{modes['damping_factor_12_percent']:.2f} %")
        + "; damped modes without dither: " + ", ".join(
            f"{m['frequency_hz']:.3f} Hz ({100 * m['damping_ratio']:.2f} %)"
            for m in modes["damped_modes"]) + ".</p>"
        + _table(("parameter", "value", "unit", "meaning"), rows)))

    stamp = datetime.datetime.now(datetime.timezone.utc).strftime(
        "%Y-%m-%d %H:%M UTC")
    provenance = current()
    page = (
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<meta name=\"generator\" content=\"{MARK} "
        f"{html.escape(provenance.words())}\">"
        f"<title>judder report: {html.escape(description)}</title>"
        f"<style>{_CSS}</style></head><body>"
        f"<h1>Clutch judder from dither: {html.escape(description)}</h1>"
        f'<p class="small">judder report, {stamp}, '
        f"{html.escape(provenance.words())}. Dither frequency in Hz, "
        "amplitude in bar, parameters in SI units. Figures and equations "
        "as numbered in \"Parametric excitation as a cause of clutch "
        "judder: theoretical study and experimental validation\".</p>"
        + _number_sections("".join(sections)) + "</body></html>")
    return ReportResult(html=page, data=data, figures=figures)


def _threshold_section(values, study, figure):
    """Section 4: the friction-gradient threshold without dither (Fig.
    19) of a registry driveline, from :func:`judder.threshold`."""
    return _keep(
        "<h2>Without dither: the friction-gradient threshold</h2>"
        f"<p>This study puts the mean pressure's damping into the slip "
        "damping (Eq. 2-4 taken literally, as Fig. 19 needs), while the "
        "maps above keep only the dither's fluctuating part (see "
        "docs/theory.md). With it, this driveline "
        f"is unstable without any dither for mu_g below "
        f"{study.study.threshold:.3g} s/rad (its mu_g is "
        f"{values['mu_g']:.3g} s/rad"
        + (", so it judders without dither" if values["mu_g"]
           < study.study.threshold else "")
        + ").</p>"
        + figure("Largest real part against mu_g and the threshold "
                 "against the external damping (Fig. 19)",
                 study.figure()))


def _summary_section(verdict, advice, advice_error, min_growth):
    """The first screen: the verdict of the configured dither (or why
    there is none), the safe dither window and the smallest design change
    of ``judder advise``."""
    if verdict is None:
        css, text = "none", (
            "No dither setting given (--freq, --pf): choose one in the safe "
            "window below, or check one with judder check.")
    else:
        css = {JUDDER: "judder", SLOW_GROWTH: "slow"}.get(verdict["verdict"],
                                                          "safe")
        text = _verdict_text(verdict)
    if advice is None:
        window = design = f"not computed: {advice_error}"
    else:
        window, design = _window_text(advice), _design_text(advice)
    rows = "".join(
        f"<tr><th>{html.escape(head)}</th><td>{html.escape(body)}</td></tr>"
        for head, body in (("Safe dither window", window),
                           ("Smallest design change", design)))
    return (
        "<h2>Verdict and advice</h2>"
        f'<p class="verdict {css}">{html.escape(text)}</p>'
        f'<table class="facts">{rows}</table>'
        '<p class="small">JUDDER: an instability growing faster than '
        f"{min_growth:g} 1/s, at least one e-fold within an engagement; "
        "SLOW GROWTH: unstable (inside a stability tongue) but growing "
        "slower, no judder within an engagement; STABLE: no instability. "
        "Sources: judder check and judder advise (valve range 60-200 Hz, "
        "up to 0.7 bar); the evidence follows.</p>")


def _rankings_differ(ranking, advice):
    """Why the sensitivity ranking and ``judder advise``'s differ, when
    their first parameters do."""
    if advice is None or not ranking or not advice.ranking:
        return ""
    first, design = ranking[0]["parameter"], advice.ranking[0][0]
    if first == design:
        return ""
    return (
        f"<p>This ranking puts {html.escape(first)} first, judder advise "
        f"puts {html.escape(design)} first: they answer different "
        "questions. Here each parameter is halved and doubled and the "
        "table gives how far the tip of one tongue moves, mostly in "
        "amplitude (the tip amplitude scales as 1/mu_g). judder advise "
        "asks how far a small relative change of a design parameter "
        "(inertias, stiffnesses, damping; the friction gradient is not "
        "among them by default) moves every judder-relevant tongue out of "
        "the valve's window, mostly in frequency, which the inertias and "
        "stiffnesses set (Eq. 15).</p>")


def _keep(part):
    """``part`` (a heading and what opens its section) kept on one printed
    page."""
    return f'<div class="keep">{part}</div>'


def _number_sections(body):
    """Number the ``<h2>`` headings 1, 2, ... in their order (a number a
    section wrote itself is replaced), so the numbering has no gap
    whichever sections the report has."""
    count = [0]

    def numbered(match):
        count[0] += 1
        return f"<h2>{count[0]}. "
    return re.sub(r"<h2>(?:\d+\. )?", numbered, body)


def _focus_tongue(found, freq_hz):
    """Number of the tongue the ranking follows: the one nearest the
    configured dither frequency, else the lowest tip."""
    numbered = [t for t in found if t.number is not None]
    if not numbered:
        return None
    if freq_hz is None:
        return min(numbered, key=lambda t: t.tip_p_f).number
    return min(numbered, key=lambda t: abs(t.tip_freq_hz - freq_hz)).number


def print_pdf(html_path, pdf_path):
    """Print an HTML file to PDF with headless Chromium, atomically.

    Raises
    ------
    JudderError
        No Chromium on the PATH, or it failed.
    """
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        raise JudderError("--pdf needs Chromium (Debian: apt-get install "
                          "chromium, or make browser); the HTML report "
                          "was written")
    with tempfile.TemporaryDirectory() as scratch:
        target = Path(scratch) / "report.pdf"
        proc = subprocess.run(
            [browser, *CHROMIUM_FLAGS, f"--user-data-dir={scratch}/profile",
             f"--print-to-pdf={target}", Path(html_path).resolve().as_uri()],
            capture_output=True, text=True, timeout=300)
        if not target.exists() or target.stat().st_size == 0:
            raise JudderError(f"--pdf: chromium could not print the report "
                              f"(exit {proc.returncode})")
        # marked, so that the next run may replace it (the overwrite rule)
        data = mark_pdf(target.read_bytes())
    atomic_write(pdf_path, lambda stream: stream.write(data))

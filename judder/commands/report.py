"""``judder report``: the options of the report (:mod:`studies.report`)
and the HTML and PDF files it writes."""

import dataclasses

from infra.errors import JudderError
from studies.map import check_map_grid
from studies.report import report

from ._arguments import (decimal_option, driveline_option, force_option,
                         method_option, min_growth_option, model_options,
                         workers_option)
from ._flags import in_flags
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, output_files, written
from ._values import FREQ, PF, Grid, Listed

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
    p.add_argument("--engagement", nargs="?", const="steady", default=None,
                   choices=("steady",),
                   help="with --freq and --pf: also run the bench's "
                        "engagement through the FMU (Fig. 7, 8), as "
                        "simulate --engagement runs it: steady, the "
                        "held-slip run (the default when given alone)")
    p.add_argument("--freq", type=FREQ, metavar="HZ",
                   help="dither frequency of the configured setting, Hz")
    p.add_argument("--pf", type=PF, metavar="BAR",
                   help="dither amplitude of the configured setting, bar")
    source = p.add_mutually_exclusive_group()
    source.add_argument("--chart", metavar="FILE.npz",
                        help="bench data: a chart (judder chart --out)")
    source.add_argument("--boundary", metavar="FILE.csv",
                        help="bench data: a measured boundary "
                             "(freq_hz,p_f_bar[,no_judder_bar,tried_bar], "
                             "as judder chart --boundary writes it)")
    p.add_argument("--group", metavar="VALUE",
                   help="group of the chart, when it has several")
    decimal_option(p, "the --boundary file")
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
    driveline_option(p)
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
            boundary=args.boundary, group=args.group, decimal=args.decimal,
            fit_names=args.fit, sensitivity_names=args.sensitivity,
            grid_freq=grid, map_freq=map_freq, map_pf=map_pf,
            p_max_bar=float(map_pf[-1]) if map_pf[-1] > 0 else 1.5,
            method=args.method, workers=args.workers,
            engagement=args.engagement is not None,
            min_growth=args.min_growth,
            progress=progress, driveline=args.driveline)
    # the page speaks of the options its reader typed
    result = dataclasses.replace(result, html=in_flags(result.html,
                                                       args.flags))
    result.save(args.out, force=args.force)
    if args.pdf:
        make_parents(args.pdf)
        result.save_pdf(args.pdf, args.out, force=args.force)
    verdict = result.data.get("verdict")
    text = (f"{len(result.figures)} figures"
            + (f"; dither {args.freq:g} Hz, {args.pf:g} bar: "
               f"{verdict['verdict']}" if verdict else "")
            + ("\nbench data: "
               + in_flags(result.data["fit_status"], args.flags)
               if "fit_status" in result.data else "")
            + written(args.out, args.pdf))
    emit(args, {**result.as_dict(),
                **output_files(out=args.out, pdf=args.pdf)},
         text)

"""``judder fit``: fit parameters to a measured boundary (section 4.2)."""

from contextlib import contextmanager

import numpy as np

from infra.errors import JudderError
from infra.files import all_or_none
from infra.units import PA_PER_BAR
from studies._common import resolve
from studies._preflight import check_fit
from studies.fit import fit_checked
from studies.inputs import (boundary_p_max, read_boundary_limit,
                            read_boundary_min_growth, read_boundary_tested,
                            read_chart_below, read_chart_boundary,
                            read_chart_onset_kinds,
                            read_chart_limit, read_chart_min_growth)
from studies.rules import option_value, refuse_decimal

from ._arguments import (decimal_option, driveline_option, force_option,
                         method_option, model_options, renamed_option,
                         workers_option)
from ._model import parameters_of, parse_bench
from ._output import (Progress, emit, make_parents, output_files, save_plot,
                      written)
from ._values import (BOUNDS_FORM, LIMIT, MIN_GROWTH, PF_MAX, SCATTER, SEED,
                      THRESHOLD_SPREAD, Listed, WholeNumber, parse_bounds)

#: The command's --help text.
DESCRIPTION = (
    "Adjust hard-to-know parameters so the model's boundary of judder "
    "growing at --min-growth matches a measured one (CSV: "
    "freq_hz,p_f_bar[,no_judder_bar,tried_bar]; empty p_f_bar = no "
    "judder up to tried_bar or --pf-max), or the "
    "boundary of a chart (judder chart --out). Reports each value with "
    "its standard uncertainty, 95 % interval and unit, their "
    "correlations and the scatter of the onsets; refuses what the data "
    "cannot determine (k parameters need k + 2 onsets, k with "
    "--scatter) and names a parameter that does not move the measured "
    "boundary.")


OUTPUTS = (("save_params", "--save-params", ("toml",)),
           ("plot", "--plot", None))


AMPLITUDE = "pf_max"


def add_arguments(p):
    """The options of ``judder fit``."""
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--boundary", metavar="FILE.csv",
                        help="measured boundary, Hz and bar")
    source.add_argument("--chart", metavar="FILE.npz",
                        help="an experimental chart (judder chart --out); "
                             "--pf-max defaults to its largest amplitude")
    p.add_argument("--group", metavar="VALUE",
                   help="group of the chart to fit, when it has several "
                        "(e.g. 65-70)")
    decimal_option(p, "the --boundary file")
    p.add_argument("--fit", type=Listed("--fit", str),
                   default="c12,mu_g,k24", metavar="NAMES",
                   help="parameters to fit (default c12,mu_g,k24)")
    p.add_argument("--bounds", action="append", default=[],
                   metavar="NAME=LOW:HIGH",
                   help="search range of a fitted parameter: "
                        + BOUNDS_FORM + "; repeatable (default a factor "
                        "100 either way of the start)")
    p.add_argument("--pf-max", type=PF_MAX, default=None, metavar="BAR",
                   help="largest amplitude tried on the bench (and searched "
                        "in the model), bar (default: the chart's, or the "
                        "boundary file's largest tried_bar; needed for a "
                        "file with points without judder and no tried_bar)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="measured and fitted boundaries (Fig. 16a)")
    p.add_argument("--starts", type=WholeNumber("--starts", 1, 1000),
                   default=3, metavar="N",
                   help="starts: the given one plus N-1 sampled within a "
                        "factor 3 of it (default 3)")
    p.add_argument("--uncertainty", default="auto",
                   choices=("auto", "jacobian", "profile", "bootstrap"),
                   help="how the 95 %% intervals are found (default auto: "
                        "the Jacobian, profiled where it is not trusted)")
    p.add_argument("--error-model", default="relative",
                   choices=("relative", "absolute"),
                   help="scatter of the measured onsets: a share of the "
                        "amplitude (default, as a pressure sensor's and a "
                        "valve's errors are) or the same in bar everywhere")
    p.add_argument("--scatter", metavar="SHARE|BAR",
                   help="the bench's known scatter of the onsets (its "
                        "repeatability): a share of the amplitude such as "
                        "3%% (relative error model) or bar such as 20mbar "
                        "(absolute); default: estimated from the residuals, "
                        "which needs two onsets more than the parameters")
    p.add_argument("--seed", type=SEED, default=0,
                   help="seed of the sampled starts and the bootstrap")
    workers_option(p, "one, as starting Dask costs more than the few "
                   "parallel starts gain; all cores for --uncertainty "
                   "bootstrap")
    p.add_argument("--save-params", metavar="FILE.toml",
                   help="write the fitted set, to load with --param-file")
    force_option(p)
    p.add_argument("--limit", type=LIMIT, default=None, metavar="RPM",
                   help="NVH limit the onsets were called judder from, "
                        "rpm (default: the chart's or the boundary file's "
                        "`# judder_limit_rpm`; none for a file without "
                        "it): the model's onset is then also where the "
                        "dither's forced oscillation of the upstream speed "
                        "reaches it, as at tongues 1 and 2")
    p.add_argument("--min-growth", type=MIN_GROWTH,
                   default=None, metavar="1/S",
                   help="compare with the model's boundary of judder "
                        "growing at this rate, 1/s (default: the chart's "
                        "--min-growth with --chart or its --boundary file, "
                        "else check's 1 1/s, so "
                        "fit, check and chart call the same point judder; "
                        "0: the stability boundary)")
    p.add_argument("--threshold-spread",
                   type=THRESHOLD_SPREAD,
                   default=None,
                   metavar="1/S",
                   help="how far the growth rate the onsets were called "
                        "judder at may lie from --min-growth, 1/s: the fit "
                        "is repeated at --min-growth minus and plus it and "
                        "the intervals cover the values found (default: "
                        "0.25 with --chart, as a 3 s run's growth is read "
                        "to about that, docs/fitting.md; 0 with "
                        "--boundary)")
    driveline_option(p, "chain", "default chain; bench compares with the "
                                 "bench's linearisation (c1 + d_control), "
                                 "as for a chart of `judder campaign` runs, "
                                 "and the fitted values stay the "
                                 "driveline's")
    renamed_option(p, "--bench-linearisation", "--driveline bench",
                   "driveline", const="bench")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter for --driveline bench (SI), "
                        "e.g. d_control=2000; repeatable (default: the "
                        "bench model's)")
    method_option(p)
    model_options(p)


def run(args):
    """Fit parameters to a measured boundary (section 4.2, Fig. 16a)."""
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from infra.criteria import CHART_THRESHOLD_SPREAD_PER_S
    params, changes = parameters_of(args)
    names = _fit_names(args.fit, params)
    bounds = parse_bounds(args.bounds, params.replace(**changes), names,
                          "--fit")
    default_growth = DEFAULT_MIN_GROWTH_PER_S
    default_spread = CHART_THRESHOLD_SPREAD_PER_S if args.chart else 0.0
    # where the growth threshold comes from, for a refusal that depends on
    # it (--min-growth, the chart's, the boundary file's comment, default)
    threshold = "the default of --min-growth"
    if args.chart:
        refuse_decimal(args.decimal, "a --boundary file (CSV)",
                       "with --chart (an NPZ)")
        freqs, measured, default_p_max = read_chart_boundary(args.chart,
                                                             args.group)
        default_growth = read_chart_min_growth(args.chart)
        threshold = f"the chart's min_growth_per_s ({args.chart})"
        default_limit = read_chart_limit(args.chart)
        below = read_chart_below(args.chart, args.group)
        kinds = read_chart_onset_kinds(args.chart, args.group)
    else:
        kinds = None
        table = read_boundary_tested(args.boundary, decimal=args.decimal)
        freqs, measured = table["freq_hz"], table["p_f"]
        below = np.where(np.isnan(measured), np.nan, table["no_judder"])
        default_p_max = boundary_p_max(table, args.pf_max, args.boundary)
        stated = read_boundary_min_growth(args.boundary,
                                          decimal=args.decimal)
        default_growth = default_growth if stated is None else stated
        if stated is not None:
            line, text, _ = table["stated"]["min_growth_per_s"]
            threshold = (f"{args.boundary}, line {line}: min_growth_per_s "
                         f"{text}")
        default_limit = read_boundary_limit(args.boundary,
                                            decimal=args.decimal)
    if args.bench and args.driveline != "bench":
        raise JudderError("--bench is for --driveline bench; give both")
    bench = parse_bench(args.bench, resolve(params, changes)) \
        if args.driveline == "bench" else None
    p_max_bar = default_p_max if args.pf_max is None else args.pf_max
    spread = default_spread if args.threshold_spread is None \
        else args.threshold_spread
    check_fit(len(freqs), _local_fits(args.starts, args.uncertainty, spread),
              "--chart" if args.chart else "--boundary")
    min_growth = default_growth if args.min_growth is None \
        else args.min_growth
    compared = _threshold_words(min_growth, f"--min-growth {min_growth:g}"
                                if args.min_growth is not None else threshold)
    make_parents(args.plot, args.save_params)
    # the options were checked by their parsers, the files by their
    # readers: the fit itself, in Pa, without the API's checks
    with Progress(None, "fit") as progress, _naming(compared):
        report = fit_checked(
            params.replace(**changes), freqs, measured,
            p_max_bar * PA_PER_BAR, below, names=names, bounds=bounds,
            method=args.method, starts=args.starts,
            uncertainty=args.uncertainty, error_model=args.error_model,
            seed=args.seed, workers=args.workers, progress=progress,
            min_growth=min_growth, bench=bench, kinds=kinds,
            scatter=_scatter(args.scatter, args.error_model),
            threshold_spread=spread,
            judder_limit_rpm=default_limit if args.limit is None
            else args.limit)
    result = report.fit
    with all_or_none():
        if args.save_params:
            report.save_params(args.save_params, force=args.force)
        if args.plot:
            save_plot(args.plot, report.figure())
    rows = report.text()
    rows.append("compared with: " + _compared_with(result)
                + ("" if report.judder_limit_rpm is None else
                   f", and the dither's forced oscillation reaching "
                   f"{report.judder_limit_rpm:g} rpm"))
    rows += [f"note: {n}" for n in result.notes]
    rows += [f"problem: {p}" for p in result.problems]
    emit(args, {**report.as_dict(),
                **output_files(saved_params=args.save_params, plot=args.plot)},
         "\n".join(rows) + written(args.save_params, args.plot))
    if not result.success:
        raise JudderError("the fit cannot be trusted: "
                          + "; ".join(result.problems or [result.message])
                          + f" ({compared})")


def _threshold_words(min_growth, source):
    """The model boundary a fit compares with, its growth threshold and
    where that came from, in words: what a refusal of the fit depends
    on."""
    what = " (the stability boundary)" if min_growth == 0 else ""
    return (f"compared with the model's boundary of judder growing at "
            f"min_growth_per_s = {min_growth:g} 1/s{what}, from {source}")


@contextmanager
def _naming(compared):
    """A refusal of the fit itself, with the threshold it depends on
    named (``compared``, :func:`_threshold_words`)."""
    try:
        yield
    except JudderError as error:
        raise JudderError(f"{error} ({compared})") from None


def _local_fits(starts, uncertainty, spread):
    """Local fits of a fit: its starts and the bootstrap's refits, at the
    threshold and, with a spread, either side of it."""
    from stability.fit._uncertainty import DEFAULT_BOOTSTRAP
    refits = DEFAULT_BOOTSTRAP if uncertainty == "bootstrap" else 0
    return (starts + refits) * (3 if spread > 0 else 1)


def _fit_names(names, params):
    """The ``--fit`` names, if they are distinct parameters of the set."""
    unknown = [n for n in names if n not in params.specs]
    if unknown or len(set(names)) != len(names):
        raise JudderError(f"--fit {','.join(names)!r} is not allowed; "
                          "allowed: distinct parameter names of the "
                          f"{params.model} model: {', '.join(params.specs)}")
    return names


def _scatter(text, error_model):
    """``--scatter``: a share of the amplitude (relative error model) or
    Pa (absolute), or None."""
    from infra.quantities import parse_quantity
    if text is None:
        return None
    if error_model == "relative":
        share = parse_quantity(text, "1", "--scatter")
        if not 0 < share <= 1:
            raise JudderError(
                f"--scatter {text} is not allowed with the relative error "
                "model; allowed: a share of the amplitude above 0 and up to "
                "100 %, such as 3% or 0.03 (or --error-model absolute and "
                "a scatter in bar, such as 20mbar)")
        return share
    rule = SCATTER["absolute"]
    return option_value(text, rule.option, rule.unit, rule.low,
                        low_open=rule.low_open,
                        amplitude=rule.amplitude) * PA_PER_BAR


def _compared_with(result):
    """Which model boundary the fit compared with, in words."""
    what = ("the stability boundary" if result.min_growth == 0 else
            f"the boundary of judder growing at {result.min_growth:g} 1/s "
            "or faster")
    model = (f"the {result.params.model} driveline" if not result.added else
             "the bench's linearisation (the driveline with "
             + ", ".join(f"{n} + {v:g}" for n, v in result.added) + ")")
    return f"{what} of {model}; fitted: {', '.join(result.names)}"

"""``judder fit``: fit parameters to a measured boundary (section 4.2)."""

from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np

from sources import dumps_toml
from infra.errors import JudderError
from infra.files import all_or_none, keeps_foreign_files, write_text
from infra.numbers import format_interval, format_uncertain
from infra.units import PA_PER_BAR, RAD_S_PER_RPM
from stability.monodromy import DEFAULT_METHOD

from ..bench import bench_damping, check_bench, parse_bench
from ..inputs import (boundary_p_max, read_boundary_limit,
                      read_boundary_min_growth, read_boundary_tested,
                      read_chart_below,
                      read_chart_boundary, read_chart_limit,
                      read_chart_min_growth)
from ._arguments import (decimal_option, force_option, method_option,
                         model_options, refuse_decimal, workers_option)
from ._common import (at_dither_frequency, check_modes_up_to,
                      checked_values, resolve, timed)
from ._model import parameters_of
from ._output import (Progress, emit, make_parents, output_files, save_plot,
                      written)
from ._preflight import check_fit
from ._records import finite_or_none
from ._values import (LIMIT, MIN_GROWTH, PF_MAX, SCATTER, SEED,
                      THRESHOLD_SPREAD, Listed, WholeNumber, option_value)

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
                   help="search range of a fitted parameter, SI; repeatable "
                        "(default a factor 100 either way of the start)")
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
    p.add_argument("--bench-linearisation", action="store_true",
                   help="compare with the bench's linearisation (c1 + "
                        "d_control: its motor speed control damps body 1), "
                        "as for a chart of `judder campaign` runs; the "
                        "fitted values stay the driveline's")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter for --bench-linearisation (SI), "
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
    bounds = _bounds(args.bounds, params, names)
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
    else:
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
    if args.bench and not args.bench_linearisation:
        raise JudderError("--bench is for --bench-linearisation; give both")
    bench = parse_bench(args.bench, resolve(params, changes)) \
        if args.bench_linearisation else None
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
        report = _fitted(
            params.replace(**changes), freqs, measured,
            p_max_bar * PA_PER_BAR, below, names=names, bounds=bounds,
            method=args.method, starts=args.starts,
            uncertainty=args.uncertainty, error_model=args.error_model,
            seed=args.seed, workers=args.workers, progress=progress,
            min_growth=min_growth, bench=bench,
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


def _bounds(items, params, names):
    """``NAME=LOW:HIGH`` strings of --bounds as ``{name: (low, high)}``,
    each a fitted parameter with LOW < HIGH both allowed for it (SI, or
    with units)."""
    from infra.quantities import parse_quantity
    bounds = {}
    for item in items:
        name, _, rng = item.partition("=")
        name = name.strip()
        parts = rng.split(":")
        if name not in names or len(parts) != 2:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              "NAME=LOW:HIGH with NAME one of --fit ("
                              f"{', '.join(names)})")
        spec = params.specs[name]
        low, high = (spec.check(parse_quantity(part, spec.unit,
                                               f"--bounds {name}"))
                     for part in parts)
        if not low < high:
            raise JudderError(f"--bounds {item!r} is not allowed; allowed: "
                              f"LOW < HIGH, each {spec.allowed()} "
                              f"[{spec.unit}]")
        bounds[name] = (low, high)
    return bounds


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


def fit(freq_hz, measured_p_f_bar, p_max_bar=1.5, names=None, bounds=None,
        parameters=None, changes=None, method=DEFAULT_METHOD, kinds=None,
        starts=3, uncertainty="auto", error_model="relative", seed=0,
        workers=None, progress=None, min_growth=None, bench=None,
        scatter=None, below_bar=None, threshold_spread=0.0,
        judder_limit_rpm=None):
    """``judder fit``: fit parameters to a measured boundary (section 4.2,
    Fig. 16a).

    Parameters
    ----------
    freq_hz : array_like
        Frequencies of the measured points, Hz.
    measured_p_f_bar : array_like
        Lowest amplitude with judder, bar; NaN where none was seen up to
        ``p_max_bar`` (see :func:`judder.inputs.read_boundary`).
    names : sequence of str, optional
        Parameters to fit (default
        :data:`stability.fit.DEFAULT_FIT`).
    bounds : dict, optional
        ``{name: (low, high)}``, SI.
    kinds, starts, uncertainty, error_model, seed, workers, scatter
    threshold_spread
        As :func:`stability.fit.fit_boundary` takes them (``scatter``
        in bar with the absolute error model). With ``workers``, the
        rounds of parallel jobs share one Dask cluster.
    min_growth : float, optional
        1/s: the model boundary compared is that of judder growing at
        this rate; default ``judder check``'s
        (:data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`), so fit,
        check and chart call the same point judder.
    below_bar : array_like, optional
        The highest amplitude tried without judder below each onset, bar
        (NaN: none; :func:`judder.inputs.read_chart_below`): the fit
        compares with the middle of each interval (below, onset].
    judder_limit_rpm : float, optional
        The NVH limit (rpm) the onsets were called judder from, as a
        bench reads them (``judder chart --limit``): the model's onset is
        then also where the dither's forced oscillation of the upstream
        speed reaches it (tongues 1 and 2). None: the Floquet boundaries
        alone (a boundary of instabilities).
    bench : dict, optional
        Compare with the bench's linearisation, not the driveline alone:
        the damping its motor control adds
        (:attr:`drivelines.DrivelineModel.bench_damping`, ``c1 +
        d_control``), from these bench parameters (SI) or the bench
        model's defaults (``{}``). None: the driveline.

    Returns
    -------
    FitReport
        ``fit.success`` is False when any of ``fit.problems`` holds (no
        convergence, a parameter on a bound or undetermined, another
        minimum as good).

    Raises
    ------
    JudderError
        For an argument the option carrying it would refuse, naming the
        argument.
    """
    from infra.parallel import cluster
    start = checked_values(parameters, changes, p_max_bar=p_max_bar,
                           min_growth=min_growth,
                           threshold_spread=threshold_spread,
                           judder_limit_rpm=judder_limit_rpm)
    if error_model in SCATTER and scatter is not None:
        SCATTER[error_model].check(scatter, "scatter")
        if error_model == "absolute":
            scatter = scatter * PA_PER_BAR
    if bench is not None:
        bench = check_bench(start, bench)
    with cluster(workers):
        return _fitted(
            start, freq_hz, np.asarray(measured_p_f_bar, dtype=float)
            * PA_PER_BAR, p_max_bar * PA_PER_BAR, None if below_bar is None
            else np.asarray(below_bar, dtype=float) * PA_PER_BAR,
            names=names, bounds=bounds, method=method, kinds=kinds,
            starts=starts, uncertainty=uncertainty, error_model=error_model,
            seed=seed, workers=workers, progress=progress,
            min_growth=min_growth, bench=bench, scatter=scatter,
            threshold_spread=threshold_spread,
            judder_limit_rpm=judder_limit_rpm)


def _fitted(start, freq_hz, measured, p_max, below, names=None,
            bench=None, min_growth=None, judder_limit_rpm=None,
            progress=None, **options):
    """:func:`fit` of the parameter set ``start``, amplitudes in Pa
    (``scatter`` too with the absolute error model), its arguments
    checked where they entered; ``options`` as
    :func:`stability.fit.fit_boundary` takes them."""
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.fit import DEFAULT_FIT, fit_boundary
    from stability.fit._common import SEARCH_FACTOR
    start = at_dither_frequency(start, freq_hz)
    result, seconds = timed(
        fit_boundary, start, freq_hz, measured, p_max,
        names=names or DEFAULT_FIT, callback=progress, below=below,
        min_growth=DEFAULT_MIN_GROWTH_PER_S if min_growth is None
        else min_growth,
        added=None if bench is None else bench_damping(start, bench),
        forced_limit=None if judder_limit_rpm is None
        else judder_limit_rpm * RAD_S_PER_RPM, **options)
    # the fitted set's boundaries are searched at each measured frequency
    # up to SEARCH_FACTOR p_max on its linearisation in one mode
    check_modes_up_to(result.params, freq_hz,
                      SEARCH_FACTOR * p_max / PA_PER_BAR)
    return FitReport(fit=result, seconds=seconds,
                     method=options.get("method", DEFAULT_METHOD),
                     judder_limit_rpm=judder_limit_rpm)


@dataclass(frozen=True)
class FitReport:
    """``judder fit``: a :class:`stability.fit.FitResult` and timing."""

    fit: object
    seconds: float
    method: str
    judder_limit_rpm: float = None

    def as_dict(self):
        r = self.fit
        return {"model": r.params.model, "method": self.method,
                "seconds": self.seconds, "success": r.success,
                "judder_limit_rpm": self.judder_limit_rpm,
                "message": r.message,
                "fitted": {n: {"value": v, "std": finite_or_none(s),
                           "ci95": [finite_or_none(lo),
                                    finite_or_none(hi)], "start": s0}
                           for n, v, s, lo, hi, s0 in zip(
                           r.names, r.values, r.std, r.ci_low,
                           r.ci_high, r.start)},
                "uncertainty": r.uncertainty, "problems": list(r.problems),
                "notes": list(r.notes), "at_bound": list(r.at_bound),
                "undetermined": list(r.undetermined),
                "starts_tried": r.starts_tried,
                "starts_agreeing": r.starts_agreeing,
                "kinds": list(r.kinds),
                "residual_rms_bar": r.residual_rms_bar,
                "evaluations": r.evaluations, "freq_hz": r.freq_hz,
                "measured_bar": [finite_or_none(v) for v in r.measured_bar],
                "model_bar": [finite_or_none(v) for v in r.model_bar],
                "min_growth_per_s": r.min_growth, "added": dict(r.added),
                "determined": r.determined, "held": list(r.held),
                "error_model": r.error_model,
                "scatter": finite_or_none(r.scatter),
                "scatter_unit": ("share of the amplitude"
                                 if r.error_model == "relative" else "bar"),
                "scatter_given": r.scatter_given,
                "threshold_spread_per_s": r.threshold_spread,
                "threshold_shifts": None if r.threshold_shifts is None else {
                    n: {"lower_threshold": float(a),
                        "higher_threshold": float(b)}
                    for n, (a, b) in zip(r.names, r.threshold_shifts)},
                "covariance": None if r.covariance is None else {
                    "names": list(r.names),
                    "matrix": [[finite_or_none(v) for v in row]
                               for row in r.covariance]},
                "correlation": None if r.covariance is None else {
                    "names": list(r.names),
                    "matrix": [[finite_or_none(v) for v in row]
                               for row in r.correlation]}}

    def text(self):
        """The fit as ``judder fit`` prints it: each value with the digits
        its interval supports and its unit, the correlations, the scatter
        of the onsets, the starts, then notes and problems."""
        r = self.fit
        specs = r.params.specs
        rows = []
        for n, v, s, lo, hi, s0 in zip(r.names, r.values, r.std, r.ci_low,
                                       r.ci_high, r.start):
            unit = specs[n].unit if n in specs else ""
            if n in r.held:
                rows.append(f"{n:>8} = {v:.6g} {unit}: held at its start "
                            "value (it does not move the measured boundary)")
            elif n in r.undetermined:
                rows.append(f"{n:>8} = {v:.6g} {unit}: not determined by "
                            "the measured boundary (see the problems)")
            else:
                rows.append(f"{n:>8} = {format_uncertain(v, s, unit)} (1 "
                            f"sigma), 95 % interval "
                            f"{format_interval(lo, hi, s)}  (start {s0:.6g})")
        pairs = [(a, b, r.correlation[i, j])
                 for i, a in enumerate(r.names)
                 for j, b in enumerate(r.names) if j > i]
        pairs = [(a, b, c) for a, b, c in pairs if np.isfinite(c)]
        if pairs:
            rows.append("correlation of the fitted values: " + ", ".join(
                f"{a}-{b} {c:+.2f}" for a, b, c in pairs))
        scatter = (f"{100 * r.scatter:.2g} % of the amplitude"
                   if r.error_model == "relative"
                   else f"{r.scatter:.2g} bar")
        rows.append(f"scatter of the onsets: {scatter} ("
                    + ("given" if r.scatter_given else
                       "estimated from the residuals") + f"; {r.error_model} "
                    f"error model); residual rms {r.residual_rms_bar:.3g} "
                    f"bar over {len(r.freq_hz)} points, "
                    f"{int(np.sum(np.isfinite(r.measured_bar)))} with judder")
        if r.threshold_shifts is not None:
            low = max(r.min_growth - r.threshold_spread, 0.0)
            high = r.min_growth + r.threshold_spread
            rows.append(
                f"growth threshold {low:g} and {high:g} 1/s instead of "
                f"{r.min_growth:g}: " + ", ".join(
                    f"{n} {a:+.2g}/{b:+.2g}" for n, (a, b) in zip(
                        r.names, r.threshold_shifts))
                + " (the intervals cover these shifts)")
        rows.append(f"{_starts_text(r)}; intervals by {r.uncertainty}; "
                    f"{r.evaluations} model boundaries in {self.seconds:.1f} s")
        return rows

    @keeps_foreign_files
    def save_params(self, path):
        """Write the fitted parameter set as TOML, atomically (a file
        judder did not write is replaced only with ``force=True``)."""
        write_text(path, dumps_toml(self.fit.params))

    def figure(self):
        return self.fit.plot()[0].figure


def _starts_text(r):
    """What the starts of a fit did, in words."""
    origins = list(r.start_origins)
    sampled = origins.count("sampled")
    rematched = origins.count("rematched")
    continued = origins.count("continued")
    where = ["the given values"]
    if sampled:
        where.append(f"{sampled} sampled within a factor 3 of them")
    if rematched:
        where.append(f"{rematched} with ambiguous points matched to the "
                     "other kind of tongue")
    if continued:
        where.append("the best one continued after its budget")
    text = (f"{r.starts_tried} local fit{'s' if r.starts_tried > 1 else ''} "
            f"(from {', '.join(where)})")
    if r.starts_tried == 1:
        return text
    others = r.starts_tried - r.starts_agreeing
    return (text + f": {r.starts_agreeing} reached this minimum"
            + (f", {others} stopped at a worse one" if others else ""))

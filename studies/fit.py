"""``judder fit``: fit parameters to a measured boundary (section 4.2)."""

from dataclasses import dataclass

import numpy as np

from infra.files import keeps_foreign_files, write_text
from infra.numbers import format_interval, format_uncertain
from infra.units import PA_PER_BAR, RAD_S_PER_RPM
from sources import dumps_toml
from sources.dither_modes import check_modes_up_to
from stability.monodromy import DEFAULT_METHOD

from ._common import at_dither_frequency, checked_values, timed
from ._records import finite_or_none
from stability.bench import bench_damping, check_bench
from .rules import SCATTER


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
        ``p_max_bar`` (see :func:`studies.inputs.read_boundary`).
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
        (NaN: none; :func:`studies.inputs.read_chart_below`): the fit
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
        return fit_checked(
            start, freq_hz, np.asarray(measured_p_f_bar, dtype=float)
            * PA_PER_BAR, p_max_bar * PA_PER_BAR, None if below_bar is None
            else np.asarray(below_bar, dtype=float) * PA_PER_BAR,
            names=names, bounds=bounds, method=method, kinds=kinds,
            starts=starts, uncertainty=uncertainty, error_model=error_model,
            seed=seed, workers=workers, progress=progress,
            min_growth=min_growth, bench=bench, scatter=scatter,
            threshold_spread=threshold_spread,
            judder_limit_rpm=judder_limit_rpm)


def fit_checked(start, freq_hz, measured, p_max, below, names=None,
                bench=None, min_growth=None, judder_limit_rpm=None,
                progress=None, **options):
    """:func:`fit` of the parameter set ``start`` whose arguments were
    checked where they entered (by :func:`fit`, or by the command line's
    option parsers and file readers: a value is checked once), amplitudes
    in Pa (``scatter`` too with the absolute error model); ``options`` as
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
                "given_start": given_start(r),
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
        why = interval_words(r)
        if why:
            rows.append(why)
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
        wrong = given_start(r)
        if wrong is not None and wrong["worse"]:
            rows.append(_given_start_words(r, wrong))
        return rows

    @keeps_foreign_files
    def save_params(self, path):
        """Write the fitted parameter set as TOML, atomically (a file
        judder did not write is replaced only with ``force=True``)."""
        write_text(path, dumps_toml(self.fit.params))

    def figure(self):
        return self.fit.plot()[0].figure


def given_start(r):
    """Where the local fit from the given values ended, against the
    minimum returned: ``{'start': {name: value}, 'minimum': {name:
    value}, 'sum_of_squares': ..., 'returned_sum_of_squares': ...,
    'worse': bool}`` (SI; the weighted sums of squares), None where no
    start was the given values (or the starts were not kept).

    ``worse``: it stopped at another minimum (farther than a tenth of a
    standard uncertainty from the one returned, or 1e-4 of its value
    where that is not finite, as the fit counts its starts) whose sum of
    squares is larger: the given values lead to a worse answer, which
    the fit did not return."""
    origins = list(r.start_origins)
    if "given" not in origins or r.start_minima is None \
            or r.start_costs is None:
        return None
    i = origins.index("given")
    minimum = np.asarray(r.start_minima[i], dtype=float)
    costs = np.asarray(r.start_costs, dtype=float)
    best = float(np.nanmin(costs)) if np.isfinite(costs).any() else np.nan
    values = np.asarray(r.values, dtype=float)
    std = np.asarray(r.std, dtype=float)
    tolerance = np.where(np.isfinite(std) & (std > 0), 0.1 * std,
                         1e-4 * np.abs(values))
    apart = bool(np.any(np.abs(minimum - values) > np.maximum(
        tolerance, 1e-6 * np.abs(values))))
    cost = float(costs[i])
    return {"start": {n: float(v) for n, v in zip(r.names,
                                                   r.start_points[i])},
            "minimum": {n: float(v) for n, v in zip(r.names, minimum)},
            "sum_of_squares": finite_or_none(2 * cost),
            "returned_sum_of_squares": finite_or_none(2 * best),
            "worse": apart and np.isfinite(cost) and cost > best}


def _given_start_words(r, outcome):
    """The given start that stopped at a worse minimum, in words with
    both minima."""
    def values(point):
        return ", ".join(f"{n} = {v:.4g}" for n, v in point.items())
    ratio = outcome["sum_of_squares"] / outcome["returned_sum_of_squares"] \
        if outcome["returned_sum_of_squares"] else float("inf")
    returned = dict(zip(r.names, r.values))
    return (f"the given start ({values(outcome['start'])}) stopped at a "
            f"worse minimum ({values(outcome['minimum'])}; sum of squares "
            f"{ratio:.3g} times the returned one's) than the one returned "
            f"({values(returned)}), which another start reached: the answer "
            "is that minimum, not the one the given values lead to")


def _starts_text(r):
    """What the starts of a fit did, in words."""
    origins = list(r.start_origins)
    sampled = origins.count("sampled")
    rematched = origins.count("rematched")
    continued = origins.count("continued")
    placed = origins.count("placed")
    where = ["the given values"]
    if sampled:
        where.append(f"{sampled} sampled within a factor 3 of them")
    if rematched:
        where.append(f"{rematched} with ambiguous points matched to the "
                     "other kind of tongue")
    if placed:
        where.append(f"{placed} placed so that a tongue of the kind the "
                     "data saw lies at its onsets")
    if continued:
        where.append("the best one continued after its budget")
    text = (f"{r.starts_tried} local fit{'s' if r.starts_tried > 1 else ''} "
            f"(from {', '.join(where)})")
    if r.starts_tried == 1:
        return text
    others = r.starts_tried - r.starts_agreeing
    return (text + f": {r.starts_agreeing} reached this minimum"
            + (f", {others} stopped at a worse one" if others else ""))


#: Where the 95 % intervals come from, by :attr:`stability.fit.FitResult.
#: uncertainty`, when they are not the value +- 1.96 sigma.
INTERVAL_SOURCES = {
    "profile": "the profile of the residual (the fit refitted with the "
               "parameter held along its range)",
    "jacobian+profile": "the profile of the residual where the linearised "
                        "interval failed its check, the Jacobian elsewhere",
    "bootstrap": "refits to resampled onsets (the bootstrap)"}


def interval_words(result):
    """Why a fit's 95 % intervals are not its value +- 1.96 sigma (they
    follow the residual's shape, or end at a search bound), or ''."""
    fitted = [k for k, n in enumerate(result.names)
              if n not in result.held and n not in result.undetermined]
    lopsided = [result.names[k] for k in fitted
                if np.isfinite(result.std[k]) and result.std[k] > 0
                and abs((result.ci_high[k] - result.values[k])
                        - (result.values[k] - result.ci_low[k]))
                > 0.1 * result.std[k]]
    if not lopsided:
        return ""
    source = INTERVAL_SOURCES.get(result.uncertainty,
                                  "the linearised fit, cut at the search "
                                  "bounds")
    at_bound = [n for n in lopsided if n in result.at_bound]
    return ("the 95 % intervals of " + ", ".join(lopsided) + " are not "
            "value +- 1.96 sigma: they come from " + source
            + ("" if not at_bound else
               "; " + ", ".join(at_bound) + " ends at its search bound"))

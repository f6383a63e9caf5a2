"""The boundary fit put together (section 4.2, Fig. 16a): checks the
input, runs the local fits, the uncertainty and the identifiability
checks, and builds the :class:`~stability.fit.FitResult`; the method is
described in :mod:`stability.fit`.
"""

import dataclasses
import os

import numpy as np
from threadpoolctl import threadpool_limits

from infra.errors import JudderError
from infra.units import PA_PER_BAR

from infra.criteria import DEFAULT_MIN_GROWTH_PER_S

from ..monodromy import DEFAULT_METHOD, get_method
from ..tongues import TONGUE_KINDS
from ._common import _capped, _Problem, _Progress, evaluated
from ._identifiability import (EFFECT_STEP, MIN_EFFECT, check_onsets,
                               flat_pairs, without_effect)
from ._matching import parse_kinds
from ._model import CURVE_POINTS
from ._result import FitResult, problem_sentences, undetermined_names
from ._starts import (ALTERNATIVE_ROUNDS, DEFAULT_STARTS, extra_starts,
                      placed_starts,
                      run_starts)
from ._uncertainty import (DEFAULT_BOOTSTRAP, UNCERTAINTY_METHODS,
                           intervals, threshold_shifts, uncertainty_steps)

__all__ = ["fit_boundary", "DEFAULT_FIT", "BOUND_FACTOR", "ERROR_MODELS"]

#: Parameters fitted by default: those the paper calls hard to estimate.
DEFAULT_FIT = ("c12", "mu_g", "k24")


#: Default search range: this factor either way of the start value (clutch
#: damper damping alone spans 10 to over 1000 N m s/rad in the literature
#: the paper cites), within the parameter's allowed range.
BOUND_FACTOR = 100.0


#: Scatter models of the measured amplitudes.
ERROR_MODELS = ("absolute", "relative")


def fit_boundary(params, freq_hz, measured_p_f, p_max, names=DEFAULT_FIT,
                 bounds=None, start=None, method=DEFAULT_METHOD, *,
                 kinds=None, starts=DEFAULT_STARTS, uncertainty="auto",
                 error_model="relative", n_bootstrap=DEFAULT_BOOTSTRAP,
                 seed=0, workers=None, callback=None,
                 curve_points=CURVE_POINTS,
                 min_growth=DEFAULT_MIN_GROWTH_PER_S, added=None,
                 scatter=None, below=None, threshold_spread=0.0,
                 forced_limit=None):
    """Fit parameters so the model boundary matches a measured one.

    Section 4.2 of the paper, Fig. 16a: the parameters that cannot be
    measured are adjusted until the model's tongue boundary follows the
    judder boundary found on the bench. The module docstring explains the
    matching of points to kinds, the residuals, the starts and the
    uncertainty.

    Parameters
    ----------
    params : drivelines.Parameters
        Starting parameter set.
    freq_hz : array_like, shape (n,)
        Frequencies of the measured points, Hz.
    measured_p_f : array_like, shape (n,)
        Lowest amplitude with judder at each frequency, Pa; NaN where none
        was seen up to ``p_max``.
    p_max : float
        Largest amplitude tried on the bench, Pa.
    names : sequence of str
        Parameters to fit.
    bounds : dict, optional
        ``{name: (low, high)}``; default :data:`BOUND_FACTOR` either way
        of the start value, within the parameter's allowed range.
    start : dict, optional
        Start values overriding ``params``.
    method : str
        Monodromy engine, a key of :data:`stability.monodromy.METHODS`.
    kinds : sequence, optional, shape (n,)
        Kind (or tongue) of judder seen at each point; see
        :func:`parse_kind`. None entries, and the whole argument left
        out, mean "not known": such a point is matched to the kind whose
        boundary is nearest at the start of each local fit, re-matched
        after it. Ignored at censored points.
    starts : int or array_like, shape (m, k)
        Local fits: an ``int`` is the given start plus ``starts - 1``
        screened Latin-hypercube points of the search box; an array
        gives extra start values (SI, columns in the order of ``names``)
        after the given start. The extra starts are skipped when the given
        start already fits the data exactly (to round-off).
    uncertainty : {'auto', 'jacobian', 'profile', 'bootstrap'}
    error_model : {'relative', 'absolute'}
        Scatter of the measured amplitudes: proportional to the amplitude
        (default: a pressure sensor's and a dither valve's errors are a
        share of the reading), or the same in bar everywhere.
    n_bootstrap : int
        Synthetic boundaries refitted when ``uncertainty='bootstrap'``.
    seed : int
        Seed of the Latin hypercube and of the bootstrap noise.
    workers : int, optional
        Processes for the starts, profile sides and bootstrap refits
        (default: one, all cores for the bootstrap: starting Dask's
        workers costs more than the few parallel starts and profile
        sides gain, see docs/benchmarks.md). Call it inside
        :func:`infra.parallel.cluster` (as ``judder fit`` and
        :func:`judder.api.fit` do) for its rounds to share one cluster.
    callback : callable, optional
        ``callback(done, total)`` after each local fit, profile side,
        bootstrap refit and curve; ``total`` is fixed at the first call
        (steps skipped, such as the profile when the Jacobian is trusted,
        are counted done at once).
    curve_points : int
        Frequencies of the start and fitted curves stored for the plot
        (computed with the default engine; 0: none).
    min_growth : float
        1/s, >= 0: compare with the boundaries of judder growing at this
        rate (:func:`stability.tongues.tongue_boundaries`), as a chart
        whose verdict has a growth threshold sees it (``judder chart
        --min-growth``); the default is ``judder check``'s and ``judder
        chart``'s (:data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`),
        so the fit, the verdict and the chart call the same point judder;
        0 is the stability boundary.
    added : dict, optional
        ``{name: value}`` added to the parameters for the model compared,
        SI, not fitted: a bench's linearisation adds its motor control's
        damping to body 1 (``{'c1': d_control}``,
        :attr:`drivelines.DrivelineModel.bench_damping`). The fitted
        values are those of the driveline without it.
    below : array_like, shape (n,), optional
        Pa: the highest amplitude tried without judder below each onset
        (NaN where none is known), as a chart's grid of amplitudes gives
        it (:func:`studies.inputs.read_chart_below`). The boundary lies
        between it and the onset, not at the onset: the fit compares with
        the interval's midpoint (a grid step of 0.2 bar otherwise puts
        every onset 0.1 bar high on average and biases the fit), and the
        intervals count the variance the grid puts in the midpoints
        (:func:`stability.fit._common.grid_variance`): added to a given
        ``scatter``, and the least the estimated one is taken as.
    threshold_spread : float
        1/s, >= 0: how far the growth rate the onsets were called judder
        at may lie from ``min_growth`` (a chart's verdict reads the growth
        from a few seconds of noisy speed). The fit is repeated at
        ``min_growth`` minus and plus it, the shifts are reported
        (``threshold_shifts``) and each interval covers them; 0 (default):
        the threshold is taken as exact.
    forced_limit : float, optional
        rad/s: the onsets are judder as a bench reads it, where the
        oscillation of the upstream speed exceeds this NVH limit or an
        instability grows at ``min_growth`` (:mod:`pysim.bench.verdict`);
        the model's single-period boundary is then the lower of the
        Floquet one and the amplitude at which the dither's forced
        response reaches the limit (:func:`stability.friction.
        forced_onset`; on tongues 1 and 2, the natural frequencies, it is
        the lower). None: the Floquet boundaries alone.
    scatter : float, optional
        The bench's known scatter of the onsets (its repeatability): a
        share of the amplitude (``error_model='relative'``, e.g. 0.03) or
        Pa (``'absolute'``). Intervals then use it (normal quantiles) and
        ``k`` onsets suffice; residuals far larger than it are a problem.
        Default: estimated from the residuals (Student's t), which needs
        ``k +`` :data:`stability.fit._identifiability.MIN_DOF` onsets.

    Returns
    -------
    FitResult
        Check ``success`` and ``problems`` before using the values.

    Raises
    ------
    JudderError
        On inconsistent input (shapes, bounds, kinds, fewer points than
        parameters, no point with judder, an unknown option). The
        numbers (``p_max``, ``min_growth``, ``threshold_spread``,
        ``scatter``) are trusted: :func:`judder.api.fit` and the command
        line check them where they enter.
    """
    names = tuple(names)
    if not names:
        raise JudderError("give at least one parameter to fit")
    get_method(method)
    if uncertainty not in UNCERTAINTY_METHODS:
        raise JudderError(f"uncertainty {uncertainty!r} is not known; "
                          f"allowed: {', '.join(UNCERTAINTY_METHODS)}")
    if error_model not in ERROR_MODELS:
        raise JudderError(f"error model {error_model!r} is not known; "
                          f"allowed: {', '.join(ERROR_MODELS)}")
    freq_hz = np.asarray(freq_hz, dtype=float)
    measured = np.asarray(measured_p_f, dtype=float)
    if freq_hz.shape != measured.shape or freq_hz.ndim != 1:
        raise JudderError("the measured boundary needs one amplitude per "
                          "frequency")
    onsets = measured
    measured = _midpoints(measured, below)
    censored = np.isnan(measured)
    if censored.all():
        raise JudderError("the measured boundary has no point with judder: "
                          "it cannot determine the parameters")
    check_onsets(int(np.sum(~censored)), names, scatter is not None)
    params = params.replace(**(start or {}))
    added = tuple(sorted((added or {}).items()))
    for name, value in added:
        if name not in params.driveline.specs:
            raise JudderError(f"added {name!r} is not a parameter of the "
                              f"{params.model} driveline")
        if not np.isfinite(value):
            raise JudderError(f"added {name} = {value!r} is not allowed; "
                              "allowed: a finite number")
    bounds = {**{n: _default_bounds(params, n) for n in names},
              **(bounds or {})}
    x0 = np.array([params[n] for n in names], dtype=float)
    low, high = _check_bounds(params, names, bounds, x0)
    given = parse_kinds(kinds, evaluated(params, added), len(freq_hz),
                        censored)
    scale = np.maximum(np.abs(x0), 1e-12)
    problem = _Problem(params=params, names=names, freq_hz=freq_hz,
                       measured=measured, p_max=float(p_max),
                       low=low / scale, high=high / scale, scale=scale,
                       method=method, relative=error_model == "relative",
                       x0=x0, min_growth=float(min_growth), added=added,
                       scatter=None if scatter is None else float(
                           scatter if error_model == "relative"
                           else scatter / PA_PER_BAR),
                       threshold_spread=float(threshold_spread),
                       forced_limit=None if forced_limit is None
                       else float(forced_limit)).with_grid(onsets)
    extra = extra_starts(starts, names, low, high)
    if workers is None:
        workers = (os.cpu_count() or 1) if uncertainty == "bootstrap" else 1
    with threadpool_limits(limits=1):
        held = without_effect(problem, given)
        # a parameter without effect at the start may place a tongue at
        # the onsets from elsewhere (placed_starts): held only where it
        # moves nothing from there either
        for z in placed_starts(problem, given) if held else ():
            there = dict(without_effect(dataclasses.replace(
                problem, x0=z * problem.scale), given))
            held = [(j, effect) for j, effect in held if j in there]
        if len(held) == len(names):
            raise JudderError(
                f"none of {', '.join(names)} moves the measured boundary: "
                f"a change of {100 * EFFECT_STEP:g} % moves no measured "
                f"onset by {100 * MIN_EFFECT:g} % of its amplitude; fit "
                "parameters that act where the onsets were measured")
        free = np.array([j not in dict(held) for j in range(len(names))])
        if not isinstance(extra, int):
            extra = extra[:, free]
        result = _fit(_restricted(problem, free), given, extra, uncertainty,
                      n_bootstrap, seed, workers, callback, curve_points)
    if held:
        result = _with_held(result, problem, free, held)
    return dataclasses.replace(result, onset_bar=onsets / PA_PER_BAR)


def _midpoints(onsets, below):
    """The middle of each interval (below, onset] where ``below`` is
    known and lies under the onset; the onset elsewhere."""
    if below is None:
        return onsets
    below = np.asarray(below, dtype=float)
    if below.shape != onsets.shape:
        raise JudderError(f"{below.size} amplitudes below the onsets given "
                          f"for {onsets.size} measured points; give one per "
                          "point (NaN: none)")
    known = np.isfinite(below) & np.isfinite(onsets) & (below >= 0) & (
        below < onsets)
    return np.where(known, 0.5 * (np.where(known, below, 0.0) + onsets),
                    onsets)


def _restricted(problem, free):
    """The problem with only the ``free`` parameters fitted (the others
    stay at their start values in ``problem.params``)."""
    return dataclasses.replace(
        problem, names=tuple(n for n, f in zip(problem.names, free) if f),
        low=problem.low[free], high=problem.high[free],
        scale=problem.scale[free], x0=problem.x0[free])


def _with_held(result, problem, free, held):
    """``result`` of the free parameters, with the held ones put back at
    their start values: undetermined, ``std`` infinite, their search range
    as interval, and a problem saying why."""
    k = len(problem.names)
    x0 = problem.x0
    low, high = problem.low * problem.scale, problem.high * problem.scale

    def full(values, fill):
        out = np.array(np.broadcast_to(fill, (k,) + np.shape(values)[1:]),
                       dtype=float)
        out[free] = values
        return out

    def full_rows(rows):
        out = np.tile(x0, (len(rows), 1))
        out[:, free] = rows
        return out

    covariance = np.full((k, k), np.inf)
    covariance[np.ix_(free, free)] = result.covariance
    names = [problem.names[j] for j, _ in held]
    why = [f"{name} does not move the measured boundary (a "
           f"{100 * EFFECT_STEP:g} % change moves it by "
           f"{100 * effect:.2g} % at most): held at its start value "
           f"{x0[j]:.6g}; measure where it acts, or fix it"
           for (j, effect), name in zip(held, names)]
    return dataclasses.replace(
        result, names=problem.names, values=full(result.values, x0),
        start=x0.copy(), std=full(result.std, np.inf),
        ci_low=full(result.ci_low, low), ci_high=full(result.ci_high, high),
        bounds=np.column_stack([low, high]),
        start_points=full_rows(result.start_points),
        start_minima=full_rows(result.start_minima),
        covariance=covariance,
        threshold_shifts=None if result.threshold_shifts is None else
        full(result.threshold_shifts, 0.0),
        undetermined=tuple(n for n in problem.names
                           if n in names or n in result.undetermined),
        problems=tuple(why) + result.problems, success=False,
        held=tuple(names))


def _default_bounds(params, name):
    value = params[name]
    if value > 0:
        low, high = value / BOUND_FACTOR, value * BOUND_FACTOR
    elif value < 0:
        low, high = value * BOUND_FACTOR, value / BOUND_FACTOR
    else:
        raise JudderError(f"give `bounds` for {name}: its start value is 0")
    spec = params.specs[name]
    return max(low, spec.lower), min(high, spec.upper)


def _check_bounds(params, names, bounds, x0):
    specs = params.specs
    unknown = sorted(set(bounds) - set(names))
    if unknown:
        raise JudderError(f"bounds given for {unknown[0]}, which is not "
                          f"fitted (fitting: {', '.join(names)})")
    low = np.array([bounds[n][0] for n in names], dtype=float)
    high = np.array([bounds[n][1] for n in names], dtype=float)
    if (np.any(~np.isfinite(low)) or np.any(~np.isfinite(high))
            or np.any(low >= high) or np.any(x0 < low) or np.any(x0 > high)):
        raise JudderError("each bound must be LOW < HIGH around the start "
                          "value; got " + ", ".join(
                              f"{n} = {v:g} in [{a:g}, {b:g}]"
                              for n, v, a, b in zip(names, x0, low, high)))
    for name, a, b in zip(names, low, high):
        spec = specs[name]
        spec.check(a)
        spec.check(b)
    return low, high


def _fit(problem, given, extra, uncertainty, n_bootstrap, seed, workers,
         callback, curve_points):
    k = len(problem.names)
    n_extra = extra if isinstance(extra, int) else len(extra)
    progress = _Progress(callback, 1 + n_extra + ALTERNATIVE_ROUNDS + 1
                         + uncertainty_steps(uncertainty, k, n_bootstrap)
                         + (2 if problem.threshold_spread else 0)
                         + (2 if curve_points else 0))
    runs, best, evaluations = run_starts(problem, given, extra, seed,
                                         workers, progress)
    costs = np.array([r["cost"] for r in runs])
    z, columns = best["z"], best["columns"]
    found = intervals(problem, runs, best, given, uncertainty, n_bootstrap,
                      seed, workers, progress)
    evaluations += found.evaluations
    values, std, low, high = found.values, found.std, found.low, found.high
    shifts, count = threshold_shifts(problem, best, given, progress)
    evaluations += count
    ci_low, ci_high = found.ci_low, found.ci_high
    if shifts is not None:
        # the interval covers the values the threshold's spread gives
        ci_low = ci_low + np.minimum(shifts.min(axis=1), 0.0)
        ci_high = ci_high + np.maximum(shifts.max(axis=1), 0.0)
    amplitude, s2 = found.amplitude, found.s2
    used, open_sides = found.used, found.open_sides
    alternatives, same, minima = found.alternatives, found.same, found.minima
    boot_failed, notes, info = found.boot_failed, found.notes, found.info
    n = len(columns)
    width = high - low
    at_bound = tuple(n for n, v, a, b, w in zip(problem.names, values, low,
                                                high, width)
                     if v - a <= 1e-6 * w or b - v <= 1e-6 * w)
    undetermined = undetermined_names(problem.names, values, std, low,
                                      high, at_bound, found.null_names,
                                      open_sides)


    problems = problem_sentences(problem, best, alternatives, s2, at_bound,
                                 undetermined, std, values, low, high,
                                 open_sides, amplitude, columns, boot_failed,
                                 n_bootstrap, used)
    problems = notes + problems + [
        f"{a} and {b} are determined only in combination (correlation "
        f"{r:+.4f}): fix one of them and fit the other"
        for a, b, r in flat_pairs(found.covariance, problem.names)]

    fitted = problem.params_at(z)
    capped = _capped(problem, amplitude) if amplitude is not None else \
        np.full((len(columns), 3), problem.p_search)
    rows = np.arange(n)
    raw_residual = np.where(
        problem.censored,
        -np.maximum(problem.p_max - capped.min(axis=1), 0.0),
        capped[rows, np.maximum(columns, 0)]
        - np.nan_to_num(problem.measured)) / PA_PER_BAR
    lowest = capped.min(axis=1)
    model_bar = np.where(lowest <= problem.p_max, lowest, np.nan) / PA_PER_BAR
    matched = np.where(problem.censored, np.nan,
                       (amplitude if amplitude is not None else capped)[
                           np.arange(len(columns)), np.maximum(columns, 0)]
                       ) / PA_PER_BAR
    result = FitResult(
        names=problem.names, values=values, start=problem.x0.copy(),
        std=std, params=fitted,
        residual_rms_bar=float(np.sqrt(np.mean(raw_residual ** 2))),
        residuals_bar=raw_residual, freq_hz=problem.freq_hz,
        measured_bar=problem.measured / PA_PER_BAR, model_bar=model_bar,
        success=not problems, message=best["message"],
        evaluations=evaluations, ci_low=ci_low, ci_high=ci_high,
        converged=best["success"], at_bound=at_bound,
        undetermined=tuple(undetermined), problems=tuple(problems),
        notes=tuple(info),
        uncertainty=used,
        kinds=tuple(None if c < 0 else TONGUE_KINDS[c].label
                    for c in columns),
        kinds_given=given >= 0, matched_bar=matched,
        p_max_bar=problem.p_max / PA_PER_BAR,
        error_model="relative" if problem.relative else "absolute",
        bounds=np.column_stack([low, high]), starts_tried=len(runs),
        starts_agreeing=int(same.sum()),
        start_points=np.array([r["z0"] for r in runs]) * problem.scale,
        start_minima=minima,
        start_origins=tuple(r["origin"] for r in runs),
        start_costs=costs, min_growth=problem.min_growth,
        added=problem.added, covariance=found.covariance,
        scatter=float(found.scatter),
        scatter_given=problem.scatter is not None,
        threshold_spread=problem.threshold_spread, threshold_shifts=shifts,
        forced_limit=problem.forced_limit)
    if curve_points:
        result = result.with_curves(curve_points)
        progress.step(2)
        result = dataclasses.replace(result,
                                     evaluations=result.evaluations + 2)
    return result

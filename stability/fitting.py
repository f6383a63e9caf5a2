r"""Fitting the model's stability boundary to a measured one (section 4.2).

The paper compares the judder region measured on the bench (Fig. 10) with
the model's tongues and adjusts the parameters that cannot be measured
(the clutch-damper damping ``c12``, the friction gradient ``mu_g`` and the
stiffness ``k24``) until the model boundary follows the measured one: the
dotted (first attempt) and solid (fitted) lines of Fig. 16a. This module
does that adjustment by bounded least squares and says how far the result
can be trusted.

Measured boundary
-----------------
A list of dither frequencies with, for each, the lowest amplitude at
which judder was seen, or none (no judder up to the largest amplitude
tried, ``p_max``: a *censored* point). A point may carry the kind of
judder seen (single-period, double-period, combination), or the tongue it
belongs to (its number as in Fig. 14, or its resonance label such as
``'f2'`` or ``'f1+f2'``).

Matching points to tongues
--------------------------
The model's lowest boundary is the lowest of three curves, one per kind
(:attr:`stability.tongues.Boundaries.amplitude`). Where two curves cross,
the lowest boundary has a kink, and which curve is lowest can change from
one trial parameter set to the next (with the fitted set of section 4.2,
tongue 6's combination flank against the single-period curve near
125 Hz). A least-squares fit on the lowest boundary is then not smooth,
and the finite-difference Jacobian, hence every uncertainty taken from it,
is wrong. Each measured point with judder is therefore matched to one
kind, and its residual uses the boundary of that kind only:

* a point whose kind is given uses that kind;
* otherwise the point is matched to the kind whose boundary is *nearest*
  to it at the start parameters of each local fit, and that assignment is
  kept fixed during the fit, so the residuals are smooth functions of the
  parameters. After the fit converges, the free points are matched again
  at the fitted values; if a match changed, the fit is repeated from
  there with the new assignment (at most :data:`MATCH_ROUNDS` fits).
* Nearest at the start is not always right: from a poor start, tongue 6's
  combination flank may be nearer to a point of tongue 2 than tongue 2
  itself is, and the fit then settles on a wrong, self-consistent
  matching (with ``p_max`` = 1 bar the fit stopped at c12 = 5.9 instead
  of 10 that way). So, from the best minimum, the *ambiguous* free points
  (a second kind nearly as near as the matched one, see
  :data:`AMBIGUITY`) are matched the other way and fitted again
  (:data:`ALTERNATIVE_ROUNDS` times at most); the better fit is kept.

Each kind's boundary is searched up to :data:`SEARCH_FACTOR` times
``p_max``, so a model boundary a little above ``p_max`` still gives a
residual that varies with the parameters (a capped one would not).

Residuals
---------
The measured amplitude is the *lowest* at which judder was seen, so:

* a point with judder: model boundary of its matched kind minus the
  measured amplitude; and, as a second residual, how far the boundary of
  any *other* kind lies below the measured amplitude (zero if none does:
  the model must not predict judder of another kind below the measured
  onset);
* a censored point: how far the *lowest* model boundary (any kind) lies
  below ``p_max`` (zero where the model is stable up to ``p_max`` too).

Both one-sided residuals are zero with zero slope wherever the model
agrees with the data, so near a good fit the sum of squares stays smooth.
The degrees of freedom count the points with judder and the one-sided
residuals that are not zero.

With ``error_model='absolute'`` every residual is in bar (equal scatter
at every amplitude). With ``'relative'`` each residual is divided by its
measured amplitude (censored points by ``p_max``), which suits a scatter
proportional to the amplitude (a noise of a few per cent).

Several starts
--------------
The given start is fitted first. With ``starts = m > 1`` the parameter
box (the bounds, narrowed to :data:`START_SPREAD` either way of the start)
is sampled by a Latin hypercube (log-spaced for a positive range over a
decade or more), each sample is screened by one model boundary, and local
fits (of at most :data:`EXTRA_START_EVALUATIONS` model boundaries each)
are run from the ``m - 1`` samples that match the measured boundary best,
in parallel (skipped when the given start fits the data to round-off:
nothing can fit better). The best minimum is kept (and continued if its
budget stopped it); the result says how many starts reached it, and
warns when another minimum fits almost as well (its sum of squares within
``t^2 s^2`` of the best, its values outside the intervals).

Uncertainty
-----------
The standard uncertainties and 95 % intervals (:data:`CONFIDENCE`) come
from one of:

``'jacobian'``
    ``cov = s^2 (J^T J)^{-1}`` from a central-difference Jacobian at the
    solution, ``s^2`` the residual variance with ``n - k`` degrees of
    freedom, intervals ``value +- t std`` (Student's ``t``).
``'profile'``
    Profile likelihood: each parameter is stepped away from its fitted
    value, the others refitted, until the sum of squares has grown by
    ``t^2 s^2``; the interval may be asymmetric and ends at a bound if
    the data give no limit there. ``std`` is the interval's half-width
    divided by ``t``.
``'bootstrap'``
    Parametric bootstrap: synthetic boundaries (the model boundary at the
    fitted values plus Gaussian noise of the residual scatter, under the
    chosen error model; censored where above ``p_max``) are refitted;
    ``std`` is their standard deviation and the interval their 2.5 and
    97.5 percentiles.
``'auto'`` (default)
    The Jacobian where a check shows it can be trusted, the profile
    elsewhere. The check moves each parameter to each end of its
    linearised 95 % interval (along the direction where the other
    parameters follow it) and compares the growth of the sum of squares
    with the predicted ``t^2 s^2``: an end where the ratio lies outside
    :data:`LINEARITY_RANGE` or beyond a bound is profiled (``uncertainty``
    then reads ``'jacobian+profile'``, or ``'profile'`` if every end was).
    Exact data (residuals at round-off) keep the Jacobian.

A parameter the Jacobian cannot see (rank-deficient) gets ``std = inf``
and its search range as interval; the others' uncertainties are then
those with it held.

What went wrong
---------------
:class:`FitResult` reports ``converged`` (the optimiser's success),
``at_bound`` (parameters on a bound of their search range),
``undetermined`` (parameters the data do not determine: a rank-deficient
Jacobian, a relative uncertainty of 100 % or more, or an interval reaching
a bound without closing) and ``problems``, human-readable sentences for
these and for: a measured point whose kind has no model boundary within
the search limit; a model boundary of another kind clearly below a
measured point, or below ``p_max`` at a censored point (the model
predicts judder where none was seen); another minimum that fits almost as
well. ``success`` is True only when there is no problem.
"""

import dataclasses
from dataclasses import dataclass
import math
import os

import numpy as np
from scipy import stats
from scipy.optimize import least_squares
from scipy.stats import qmc
from threadpoolctl import threadpool_limits

from drivelines import get_model
from infra.errors import JudderError
from infra.parallel import cluster, parallel_map
from infra.units import PA_PER_BAR

from .kinds import Kind
from .modal import natural_frequencies
from .model import build_driveline
from .monodromy import DEFAULT_METHOD, get_method
from .tongues import TONGUE_KINDS, resonances, tongue_boundaries

__all__ = ["FitResult", "model_boundary", "fit_boundary", "DEFAULT_FIT",
           "UNCERTAINTY_METHODS", "ERROR_MODELS", "CONFIDENCE",
           "parse_kind", "fit_curves"]

#: Parameters fitted by default: those the paper calls hard to estimate.
DEFAULT_FIT = ("c12", "mu_g", "k24")
#: Default search range: this factor either way of the start value (clutch
#: damper damping alone spans 10 to over 1000 N m s/rad in the literature
#: the paper cites), within the parameter's allowed range.
BOUND_FACTOR = 100.0
#: Each kind's boundary is searched up to this multiple of ``p_max``.
SEARCH_FACTOR = 2.0
#: Local fits run by default: the given start and the best screened
#: samples of the parameter box.
DEFAULT_STARTS = 3
#: Extra starts are sampled within this factor either way of the start
#: (and within the bounds).
START_SPREAD = 3.0
#: Latin-hypercube samples screened per extra start.
SCREEN_PER_START = 6
#: Model boundaries allowed to the fits of the given start.
START_EVALUATIONS = 400
#: Model boundaries allowed to the fits of each extra start.
EXTRA_START_EVALUATIONS = 60
#: Evaluations allowed to each bootstrap refit and profile refit.
BOOTSTRAP_EVALUATIONS = 60
#: A second kind this many times as near as the matched one (plus 5 % of
#: ``p_max``) makes a point's matching ambiguous.
AMBIGUITY = 3.0
#: Fits from the best minimum with the ambiguous points matched the other
#: way.
ALTERNATIVE_ROUNDS = 2
#: Most fits of one start with re-matched kinds.
MATCH_ROUNDS = 3
#: Ways of computing the uncertainty.
UNCERTAINTY_METHODS = ("auto", "jacobian", "profile", "bootstrap")
#: Scatter models of the measured amplitudes.
ERROR_MODELS = ("absolute", "relative")
#: Synthetic boundaries refitted by the bootstrap.
DEFAULT_BOOTSTRAP = 100
#: Level of the reported intervals.
CONFIDENCE = 0.95
#: Ratio of the actual to the predicted growth of the sum of squares at
#: the ends of the linearised intervals within which the Jacobian is
#: trusted (``uncertainty='auto'``).
LINEARITY_RANGE = (0.7, 1.5)
#: A relative uncertainty at or above this makes a parameter undetermined.
UNDETERMINED_RELATIVE = 1.0
#: Frequencies of the start and fitted curves stored for the plot.
CURVE_POINTS = 100
#: In the relative error model, amplitudes are divided by at least this
#: share of ``p_max``.
_RELATIVE_FLOOR = 0.02
#: Residual rms (weighted, share of the unit) below which the data are
#: taken as exact: the Jacobian is then used without the linearity check.
_EXACT = 1e-7
#: A profile point whose sum of squares lies this many s^2 below the
#: minimum's shows that the minimum is not the best one.
_BETTER = 0.1
#: Profile steps per side of an interval.
_PROFILE_STEPS = 8
#: A profile end is accepted where sqrt(chi^2 growth) is within this share
#: of t (the interval's end to a few per cent of its half-width).
_PROFILE_TOLERANCE = 0.05


def model_boundary(params, freq_hz, p_max, method=DEFAULT_METHOD):
    """Lowest unstable amplitude of the model at each frequency, Pa.

    NaN where the model is stable up to ``p_max``; ``method`` is the
    monodromy engine (:data:`stability.monodromy.METHODS`).
    """
    return tongue_boundaries(build_driveline(params), freq_hz, p_max,
                             method).stability_boundary


@dataclass(frozen=True)
class FitResult:
    """Outcome of :func:`fit_boundary` (section 4.2, Fig. 16a).

    Attributes
    ----------
    names : tuple of str
        Fitted parameters.
    values, start, std : ndarray, shape (k,)
        Fitted values, starting values and standard uncertainties (SI
        units; ``inf`` where the data do not determine a value). How
        ``std`` was obtained is in ``uncertainty``.
    params : drivelines.Parameters
        The parameter set with the fitted values.
    residual_rms_bar : float
        Root mean square of ``residuals_bar``, bar.
    residuals_bar : ndarray, shape (n,)
        Model boundary of the matched kind minus the measured amplitude,
        bar; at censored points, minus how far the lowest model boundary
        lies below ``p_max`` (0 if it does not).
    freq_hz, measured_bar : ndarray, shape (n,)
        The measured boundary (NaN where censored).
    model_bar : ndarray, shape (n,)
        Lowest model boundary (any kind) with the fitted values, bar
        (NaN: stable up to ``p_max``).
    success : bool
        True only when ``problems`` is empty: converged, no parameter at
        a bound or undetermined, no point the model contradicts.
    message : str
        The optimiser's message for the best start.
    evaluations : int
        Model boundaries computed (all starts, checks and refits).
    ci_low, ci_high : ndarray, shape (k,)
        The 95 % interval (:data:`CONFIDENCE`) of each value.
    converged : bool
        The optimiser reported success for the best start.
    at_bound : tuple of str
        Parameters whose fitted value is on a bound of its range.
    undetermined : tuple of str
        Parameters the measured boundary does not determine.
    problems : tuple of str
        What went wrong, one sentence each.
    notes : tuple of str
        What is worth knowing but did not go wrong (points that lie about
        as near two kinds of tongue); they leave ``success`` alone.
    uncertainty : str
        ``'jacobian'``, ``'profile'``, ``'jacobian+profile'`` (the ends
        that failed the linearity check profiled) or ``'bootstrap'``: how
        ``std`` and the intervals were obtained.
    kinds : tuple
        Kind matched to each point (``'single-period'``,
        ``'double-period'``, ``'combination'``; None where censored).
    kinds_given : ndarray of bool, shape (n,)
        Where the kind came with the data (else matched by nearness).
    matched_bar : ndarray, shape (n,)
        Model boundary of the matched kind at the fitted values, bar
        (NaN where censored or none up to the search limit).
    p_max_bar : float
        Largest amplitude tried, bar.
    error_model : str
        ``'absolute'`` or ``'relative'``.
    bounds : ndarray, shape (k, 2)
        Search range of each parameter.
    starts_tried, starts_agreeing : int
        Local fits run, and how many of them reached the kept minimum.
    start_points, start_minima : ndarray, shape (starts_tried, k)
        Where each local fit started and where it ended.
    start_costs : ndarray, shape (starts_tried,)
        Half the weighted sum of squares each local fit ended at.
    start_origins : tuple of str
        Where each start came from: ``'given'``, ``'sampled'`` (Latin
        hypercube or the ``starts`` array), ``'rematched'`` (the best
        minimum with its ambiguous points matched the other way) or
        ``'continued'`` (the best start went on after its budget).
    curve_freq_hz : ndarray or None, shape (m,)
        Fine frequency grid over the measured range.
    start_curve_bar, fitted_curve_bar : ndarray or None, shape (m,)
        Lowest model boundary with the start (first attempt) and fitted
        values, bar (NaN: stable up to ``p_max``): the dotted and solid
        lines of Fig. 16a.
    covariance : ndarray or None, shape (k, k)
        Covariance of ``values`` (SI): the correlations of the linearised
        fit with the standard uncertainties ``std``; ``inf`` in the rows
        and columns of undetermined parameters. ``judder envelope`` takes
        it as a joint normal distribution.
    """

    names: tuple
    values: np.ndarray
    start: np.ndarray
    std: np.ndarray
    params: object
    residual_rms_bar: float
    residuals_bar: np.ndarray
    freq_hz: np.ndarray
    measured_bar: np.ndarray
    model_bar: np.ndarray
    success: bool
    message: str
    evaluations: int
    ci_low: np.ndarray = None
    ci_high: np.ndarray = None
    converged: bool = True
    at_bound: tuple = ()
    undetermined: tuple = ()
    problems: tuple = ()
    notes: tuple = ()
    uncertainty: str = "jacobian"
    kinds: tuple = ()
    kinds_given: np.ndarray = None
    matched_bar: np.ndarray = None
    p_max_bar: float = None
    error_model: str = "absolute"
    bounds: np.ndarray = None
    starts_tried: int = 1
    starts_agreeing: int = 1
    start_points: np.ndarray = None
    start_minima: np.ndarray = None
    start_costs: np.ndarray = None
    start_origins: tuple = ()
    curve_freq_hz: np.ndarray = None
    start_curve_bar: np.ndarray = None
    fitted_curve_bar: np.ndarray = None
    covariance: np.ndarray = None

    @property
    def start_params(self):
        """The parameter set of the first attempt (the start values)."""
        return self.params.replace(**dict(zip(self.names,
                                              map(float, self.start))))

    def plot(self, ax=None):
        """Measured, first-attempt and fitted boundaries (Fig. 16a); see
        :func:`stability.plotting.plot_fit`."""
        from .plotting import plot_fit
        return plot_fit(self, ax=ax)


def fit_curves(result, points=CURVE_POINTS, method=DEFAULT_METHOD):
    """Lowest model boundary with the start and the fitted values.

    Parameters
    ----------
    result : FitResult
    points : int
        Frequencies over the measured range.
    method : str
        Monodromy engine.

    Returns
    -------
    freq_hz, start_bar, fitted_bar : ndarray, shape (points,)
        Hz, and the two boundaries in bar (NaN: stable up to ``p_max``),
        as drawn in Fig. 16a (dotted: first attempt, solid: fitted).
    """
    p_max = result.p_max_bar * PA_PER_BAR
    freq = np.linspace(result.freq_hz.min(), result.freq_hz.max(), points)
    curves = [model_boundary(p, freq, p_max, method) / PA_PER_BAR
              for p in (result.start_params, result.params)]
    return freq, curves[0], curves[1]


# --------------------------------------------------------------------------
# the problem, its residuals and one local fit (module level: the starts,
# profile sides and bootstrap refits run in worker processes)


@dataclass(frozen=True)
class _Problem:
    params: object
    names: tuple
    freq_hz: np.ndarray
    measured: np.ndarray        # Pa, NaN where censored
    p_max: float
    low: np.ndarray             # scaled
    high: np.ndarray
    scale: np.ndarray
    method: str
    relative: bool
    x0: np.ndarray              # start values, SI

    @property
    def p_search(self):
        return SEARCH_FACTOR * self.p_max

    @property
    def censored(self):
        return np.isnan(self.measured)

    @property
    def weights(self):
        """Divisor of each residual, Pa."""
        if not self.relative:
            return np.full(len(self.measured), PA_PER_BAR)
        floor = _RELATIVE_FLOOR * self.p_max
        return np.where(self.censored, self.p_max,
                        np.maximum(np.nan_to_num(self.measured), floor))

    def with_measured(self, measured):
        return _Problem(self.params, self.names, self.freq_hz, measured,
                        self.p_max, self.low, self.high, self.scale,
                        self.method, self.relative, self.x0)


class _Evaluator:
    """Model boundaries of each kind at scaled parameter vectors, counted."""

    def __init__(self, problem):
        self.problem = problem
        self.count = 0

    def params_at(self, z):
        p = self.problem
        return p.params.replace(**dict(zip(p.names, map(float,
                                                         z * p.scale))))

    def amplitudes(self, z, strict=False):
        """Shape (n, 3), Pa, NaN where none up to the search limit; None
        if the model cannot be evaluated there (unless ``strict``)."""
        p = self.problem
        self.count += 1
        try:
            return tongue_boundaries(build_driveline(self.params_at(z)),
                                     p.freq_hz, p.p_search,
                                     p.method).amplitude
        except (ValueError, ArithmeticError, np.linalg.LinAlgError):
            if strict:
                raise
            return None

    def residuals(self, z, columns):
        return _residuals(self.problem, self.amplitudes(z), columns)


def _capped(problem, amplitude):
    return np.where(np.isnan(amplitude), problem.p_search, amplitude)


def _lowest(problem, amplitude):
    return _capped(problem, amplitude).min(axis=1)


def _residuals(problem, amplitude, columns):
    """Weighted residuals, shape (2n,): per point the matched kind's
    boundary minus the measurement (censored points: how far the lowest
    boundary lies below ``p_max``), then per point how far another kind's
    boundary lies below the measurement (zero if none does).

    ``columns`` is the matched kind column of each point (ignored where
    censored).
    """
    n = len(problem.measured)
    if amplitude is None:          # the model failed: a large residual
        amplitude = np.full((n, 3), np.nan)
    capped = _capped(problem, amplitude)
    rows = np.arange(n)
    column = np.maximum(columns, 0)
    matched = capped[rows, column]
    lowest = capped.min(axis=1)
    measured = np.nan_to_num(problem.measured)
    primary = np.where(problem.censored,
                       -np.maximum(problem.p_max - lowest, 0.0),
                       matched - measured)
    others = capped.copy()
    others[rows, column] = np.inf
    below = np.where(problem.censored, 0.0,
                     -np.maximum(measured - others.min(axis=1), 0.0))
    weights = problem.weights
    return np.concatenate([primary / weights, below / weights])


def _nearest(problem, amplitude, given):
    """Column of the kind nearest each measured point (``given`` >= 0
    kept); censored points get -1."""
    capped = _capped(problem, amplitude)
    distance = np.abs(capped - np.nan_to_num(problem.measured)[:, None])
    columns = np.argmin(distance, axis=1)
    columns = np.where(given >= 0, given, columns)
    return np.where(problem.censored, -1, columns)


def _least_squares(evaluator, z0, columns, free=None, loose=False,
                   max_nfev=200):
    """Bounded least squares over the ``free`` scaled parameters."""
    p = evaluator.problem
    free = np.ones(len(z0), bool) if free is None else free
    z_fixed = np.array(z0, dtype=float)

    def fun(y):
        z = z_fixed.copy()
        z[free] = y
        return evaluator.residuals(z, columns)

    y0 = np.clip(z_fixed[free], p.low[free], p.high[free])
    # least_squares does not count the finite-difference evaluations
    max_nfev = max(max_nfev // (int(free.sum()) + 1), 2)
    tol = dict(xtol=1e-7, ftol=1e-8) if loose else dict(xtol=1e-10,
                                                        ftol=1e-12)
    fit = least_squares(fun, y0, bounds=(p.low[free], p.high[free]),
                        x_scale="jac", diff_step=1e-4, max_nfev=max_nfev,
                        **tol)
    z = z_fixed.copy()
    z[free] = fit.x
    return z, fit


def _fit_start(job):
    """One start: fit, re-match the free points, refit if they changed.

    ``job`` is ``(problem, z0, given, index, columns0, max_nfev)``;
    ``columns0`` None matches each free point to the nearest kind at z0;
    ``max_nfev`` bounds the model boundaries computed in all rounds.
    """
    problem, z0, given, index, columns, max_nfev = job
    evaluator = _Evaluator(problem)
    if columns is None:
        amplitude = evaluator.amplitudes(z0)
        columns = _nearest(problem, amplitude if amplitude is not None
                           else np.full((len(given), 3), np.nan), given)
    z = np.array(z0, dtype=float)
    fit = None
    for _ in range(MATCH_ROUNDS):
        left = max_nfev - evaluator.count
        if fit is not None and left < 4 * (len(z) + 1):
            break                       # the budget is spent
        z, fit = _least_squares(evaluator, z, columns, max_nfev=left)
        amplitude = evaluator.amplitudes(z)
        if amplitude is None:
            break
        matched = _nearest(problem, amplitude, given)
        if np.array_equal(matched, columns):
            break
        columns = matched
    cost = 0.5 * float(np.sum(_residuals(problem, amplitude, columns) ** 2))
    return {"index": index, "z0": np.array(z0, dtype=float), "z": z,
            "cost": cost, "columns": columns,
            "success": bool(fit.success) and fit.status > 0,
            "message": fit.message, "evaluations": evaluator.count,
            "failed": amplitude is None}


def _alternative(problem, amplitude, columns, given):
    """The other matching of the ambiguous free points, or None.

    A free point is ambiguous when a second kind's boundary is nearly as
    near as its matched one (distance below :data:`AMBIGUITY` times the
    matched one's plus 5 % of ``p_max``); the alternative flips every
    ambiguous point to that second kind.
    """
    if amplitude is None:
        return None
    capped = _capped(problem, amplitude)
    distance = np.abs(capped - np.nan_to_num(problem.measured)[:, None])
    distance[np.isnan(amplitude)] = np.inf
    rows = np.arange(len(columns))
    own = distance[rows, np.maximum(columns, 0)]
    others = distance.copy()
    others[rows, np.maximum(columns, 0)] = np.inf
    second = np.argmin(others, axis=1)
    near = others[rows, second] < AMBIGUITY * own + 0.05 * problem.p_max
    flip = near & (given < 0) & ~problem.censored
    if not flip.any():
        return None
    return np.where(flip, second, columns)


def _profile_side(job):
    """Where the profile of one parameter crosses the threshold on one
    side: ``(index, sign, end, closed, evaluations, better)`` (end
    scaled; ``better`` lists profile points that fit better than the
    minimum, which then was not the best one)."""
    problem, columns, z_best, cost_best, s2, q, i, sign, step, given = job
    evaluator = _Evaluator(problem)
    free = np.ones(len(z_best), bool)
    free[i] = False
    bound = problem.high[i] if sign > 0 else problem.low[i]
    target = q * q
    warm = {z_best[i]: z_best}

    better = []

    matchings = {z_best[i]: columns}

    def chi(v):
        nearest = min(warm, key=lambda w: abs(w - v))
        start, match = warm[nearest].copy(), matchings[nearest]
        start[i] = v
        z = start
        # refit the others; re-match the free points where that moved
        # them (the profile over every matching)
        for _ in range(MATCH_ROUNDS):
            if free.any():
                z, fit = _least_squares(evaluator, z, match, free,
                                        loose=True,
                                        max_nfev=BOOTSTRAP_EVALUATIONS)
            amplitude = evaluator.amplitudes(z)
            r = _residuals(problem, amplitude, match)
            if amplitude is None:
                break
            rematched = _nearest(problem, amplitude, given)
            if np.array_equal(rematched, match):
                break
            trial = _residuals(problem, amplitude, rematched)
            if not np.sum(trial ** 2) < np.sum(r ** 2):
                break
            match, r = rematched, trial
            if not free.any():
                break
        warm[v], matchings[v] = z, match
        growth = (float(np.sum(r ** 2)) - 2 * cost_best) / s2
        if growth < -_BETTER:
            better.append(z)
        return max(growth, 0.0)

    inner, outer = (z_best[i], 0.0), None
    step = step if np.isfinite(step) and step > 0 else \
        0.1 * (problem.high[i] - problem.low[i])
    v = z_best[i] + sign * step
    for _ in range(_PROFILE_STEPS):
        v = min(v, bound) if sign > 0 else max(v, bound)
        d = chi(v)
        if d < target:
            inner = (v, d)
            if v == bound:
                return (i, sign, bound, False, evaluator.count, better)
        else:
            outer = (v, d)
        # sqrt(chi) is near linear in the parameter: interpolate on it
        gi, gv = math.sqrt(inner[1]) - q, math.sqrt(d) - q
        if abs(gv) < _PROFILE_TOLERANCE * q:
            return (i, sign, v, True, evaluator.count, better)
        if outer is None:
            # extrapolate from the best value and the last inner point
            slope = (math.sqrt(inner[1])) / max(abs(inner[0] - z_best[i]),
                                                1e-300)
            reach = q / slope if slope > 0 else 4 * abs(v - z_best[i])
            reach = min(max(reach, 1.3 * abs(v - z_best[i])),
                        4 * abs(v - z_best[i]))
            v = z_best[i] + sign * reach
        else:
            go = math.sqrt(outer[1]) - q
            v = inner[0] + (outer[0] - inner[0]) * (-gi) / (go - gi)
            if abs(outer[0] - inner[0]) < 1e-9 * max(abs(z_best[i]), 1.0):
                return (i, sign, v, True, evaluator.count, better)
    end = v if outer is None else (
        inner[0] + (outer[0] - inner[0]) * (q - math.sqrt(inner[1]))
        / max(math.sqrt(outer[1]) - math.sqrt(inner[1]), 1e-300))
    return (i, sign, end, outer is not None, evaluator.count, better)


def _bootstrap_refit(job):
    """Refit one synthetic boundary from the fitted values."""
    problem, columns, z_best, index = job
    evaluator = _Evaluator(problem)
    z, fit = _least_squares(evaluator, z_best, columns, loose=True,
                            max_nfev=BOOTSTRAP_EVALUATIONS)
    ok = bool(fit.success) and fit.status > 0
    return index, z, ok, evaluator.count


# --------------------------------------------------------------------------
# input checks


def parse_kind(entry, tongue_table=()):
    """Column of :attr:`stability.tongues.Boundaries.amplitude` a
    measured point's kind or tongue refers to, or -1 if not given.

    Parameters
    ----------
    entry : None, str, int or stability.kinds.Kind
        None, ``''`` or NaN: not given. A :class:`~stability.kinds.Kind`
        or its label (``'single-period'``, ``'double-period'``,
        ``'combination'``; ``'single'``, ``'double'`` too). An ``int``
        (or a string of digits, or ``'tongue 2'``) is a tongue number as
        in Fig. 14, a string like ``'f2'``, ``'2f1'``, ``'f2-f1'``,
        ``'f1+f2'`` a resonance label; both are looked up in
        ``tongue_table``.
    tongue_table : sequence
        :func:`stability.tongues.resonances` of the driveline.

    Examples
    --------
    >>> parse_kind("combination"), parse_kind(None)
    (2, -1)
    >>> parse_kind(2, resonances([18.9, 102.9]))   # tongue 2: single-period
    0
    """
    if entry is None or (isinstance(entry, float) and math.isnan(entry)):
        return -1
    if isinstance(entry, Kind):
        if entry not in TONGUE_KINDS:
            raise JudderError(f"kind {entry.label!r} is not a kind of tongue")
        return TONGUE_KINDS.index(entry)
    if isinstance(entry, (int, np.integer)) and not isinstance(entry, bool):
        return _tongue_column(int(entry), tongue_table, entry)
    text = str(entry).strip().lower()
    if not text:
        return -1
    for column, kind in enumerate(TONGUE_KINDS):
        if text in (kind.label, kind.label.split("-")[0]):
            return column
    number = text.removeprefix("tongue").strip()
    if number.isdigit():
        return _tongue_column(int(number), tongue_table, entry)
    for _, label, _, kind in tongue_table:
        if text == label.lower():
            return TONGUE_KINDS.index(Kind(kind))
    labels = [r[1] for r in tongue_table]
    raise JudderError(
        f"kind {entry!r} is not known; allowed: single-period, "
        f"double-period, combination, a tongue number 1-"
        f"{len(tongue_table)} or a resonance label "
        f"({', '.join(labels)}), or empty")


def _tongue_column(number, tongue_table, entry):
    for n, _, _, kind in tongue_table:
        if n == number:
            return TONGUE_KINDS.index(Kind(kind))
    raise JudderError(f"tongue {entry!r} does not exist; allowed: 1-"
                      f"{len(tongue_table)} (numbered as in Fig. 14)")


def _default_bounds(params, name):
    value = params[name]
    if value > 0:
        low, high = value / BOUND_FACTOR, value * BOUND_FACTOR
    elif value < 0:
        low, high = value * BOUND_FACTOR, value / BOUND_FACTOR
    else:
        raise JudderError(f"give --bounds for {name}: its start value is 0")
    spec = get_model(params.model).specs[name]
    return max(low, spec.lower), min(high, spec.upper)


def _check_bounds(params, names, bounds, x0):
    specs = get_model(params.model).specs
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


def _parse_kinds(kinds, params, n, censored):
    if kinds is None:
        return np.full(n, -1)
    kinds = list(kinds)
    if len(kinds) != n:
        raise JudderError(f"{len(kinds)} kinds given for {n} measured "
                          "points; give one per point (empty: not known)")
    table = resonances(_natural_frequencies(params))
    given = np.array([parse_kind(k, table) for k in kinds])
    return np.where(censored, -1, given)


def _natural_frequencies(params):
    return natural_frequencies(build_driveline(params))


# --------------------------------------------------------------------------
# starts


def _transform(low, high):
    """Per parameter: sample in log space (True) or linearly."""
    return (low > 0) & (high >= 10 * low)


def _sample_starts(problem, count, seed):
    """``count`` Latin-hypercube points of the scaled box: the bounds,
    narrowed to :data:`START_SPREAD` either way of the start."""
    k = len(problem.names)
    unit = qmc.LatinHypercube(d=k, seed=seed).random(count)
    z0 = problem.x0 / problem.scale
    near = np.sort([z0 / START_SPREAD, z0 * START_SPREAD], axis=0)
    low = np.maximum(problem.low, near[0])
    high = np.minimum(problem.high, near[1])
    log = _transform(low, high)
    out = np.empty_like(unit)
    for j in range(k):
        if log[j]:
            out[:, j] = np.exp(np.log(low[j]) + unit[:, j]
                               * (np.log(high[j]) - np.log(low[j])))
        else:
            out[:, j] = low[j] + unit[:, j] * (high[j] - low[j])
    return out


def _screen(problem, candidates, given):
    """Cost of each candidate with the points matched at it."""
    evaluator = _Evaluator(problem)
    costs = []
    for z in candidates:
        amplitude = evaluator.amplitudes(z)
        if amplitude is None:
            costs.append(np.inf)
            continue
        columns = _nearest(problem, amplitude, given)
        costs.append(0.5 * float(np.sum(
            _residuals(problem, amplitude, columns) ** 2)))
    return np.array(costs), evaluator.count


# --------------------------------------------------------------------------
# uncertainty


def _jacobian(evaluator, z, columns):
    """Central-difference Jacobian of the weighted residuals (scaled)."""
    p = evaluator.problem
    k = len(z)
    jac = np.empty((2 * len(p.measured), k))
    for j in range(k):
        h = 1e-4 * max(abs(z[j]), 1e-3)
        up, down = z.copy(), z.copy()
        up[j] = min(z[j] + h, p.high[j])
        down[j] = max(z[j] - h, p.low[j])
        jac[:, j] = (evaluator.residuals(up, columns)
                     - evaluator.residuals(down, columns)) / (up[j] - down[j])
    return jac


def _null_space_names(jac, names):
    """Parameters in the (near) null space of the Jacobian."""
    norms = np.linalg.norm(jac, axis=0)
    if np.any(norms == 0) or not np.all(np.isfinite(jac)):
        return [n for n, c in zip(names, norms) if not c > 0] or list(names)
    _, sv, vt = np.linalg.svd(jac / norms, full_matrices=False)
    small = sv < 1e-8 * sv[0]
    if not small.any():
        return []
    weight = np.abs(vt[small]).max(axis=0)
    return [n for n, w in zip(names, weight) if w > 0.3]


def _ambiguous_points(problem, amplitude, columns, given, s2):
    """Free points with judder whose second-nearest kind lies within
    three standard deviations of the scatter (and within a tenth of
    ``p_max``): ``[(index, column)]``."""
    if amplitude is None:
        return []
    sigma = math.sqrt(max(s2, 0.0)) * problem.weights
    measured = np.nan_to_num(problem.measured)
    out = []
    for i in np.flatnonzero(~problem.censored & (given < 0)):
        distance = np.abs(amplitude[i] - measured[i])
        distance[columns[i]] = np.inf
        distance[np.isnan(distance)] = np.inf
        other = int(np.argmin(distance))
        if distance[other] < min(3 * sigma[i], 0.1 * problem.p_max):
            out.append((i, other))
    return out


def _linearity_ratios(evaluator, z, columns, cov_z, cost, s2, q, kept):
    """Actual over predicted growth of the sum of squares at the ends of
    each linearised interval of the ``kept`` parameters, shape (k, 2)
    (columns: lower, upper end); NaN where that end lies beyond a bound
    or the parameter is not kept."""
    p = evaluator.problem
    ratios = np.full((len(z), 2), np.nan)
    for i in np.flatnonzero(kept):
        step = q * cov_z[:, i] / math.sqrt(cov_z[i, i])
        for side, sign in enumerate((-1, 1)):
            trial = z + sign * step
            if np.any(trial < p.low) or np.any(trial > p.high):
                continue
            r = evaluator.residuals(trial, columns)
            ratios[i, side] = ((float(np.sum(r ** 2)) - 2 * cost) / s2
                               / q ** 2)
    return ratios


# --------------------------------------------------------------------------
# the fit


def fit_boundary(params, freq_hz, measured_p_f, p_max, names=DEFAULT_FIT,
                 bounds=None, start=None, method=DEFAULT_METHOD, *,
                 kinds=None, starts=DEFAULT_STARTS, uncertainty="auto",
                 error_model="absolute", n_bootstrap=DEFAULT_BOOTSTRAP,
                 seed=0, workers=None, callback=None,
                 curve_points=CURVE_POINTS):
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
    error_model : {'absolute', 'relative'}
        Scatter of the measured amplitudes: the same in bar everywhere,
        or proportional to the amplitude.
    n_bootstrap : int
        Synthetic boundaries refitted when ``uncertainty='bootstrap'``.
    seed : int
        Seed of the Latin hypercube and of the bootstrap noise.
    workers : int, optional
        Processes for the starts, profile sides and bootstrap refits
        (default: all cores; 1 runs everything here).
    callback : callable, optional
        ``callback(done, total)`` after each local fit, profile side,
        bootstrap refit and curve; ``total`` is fixed at the first call
        (steps skipped, such as the profile when the Jacobian is trusted,
        are counted done at once).
    curve_points : int
        Frequencies of the start and fitted curves stored for the plot
        (computed with the default engine; 0: none).

    Returns
    -------
    FitResult
        Check ``success`` and ``problems`` before using the values.

    Raises
    ------
    JudderError
        On inconsistent input (shapes, bounds, kinds, fewer points than
        parameters, no point with judder, an unknown option).
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
    if len(freq_hz) < len(names):
        raise JudderError(f"{len(freq_hz)} measured points cannot determine "
                          f"{len(names)} parameters")
    censored = np.isnan(measured)
    if censored.all():
        raise JudderError("the measured boundary has no point with judder: "
                          "it cannot determine the parameters")
    if not (np.isfinite(p_max) and p_max > 0):
        raise JudderError(f"p_max = {p_max!r} Pa is not allowed; allowed: "
                          "> 0")
    params = params.replace(**(start or {}))
    bounds = {**{n: _default_bounds(params, n) for n in names},
              **(bounds or {})}
    x0 = np.array([params[n] for n in names], dtype=float)
    low, high = _check_bounds(params, names, bounds, x0)
    given = _parse_kinds(kinds, params, len(freq_hz), censored)
    scale = np.maximum(np.abs(x0), 1e-12)
    problem = _Problem(params=params, names=names, freq_hz=freq_hz,
                       measured=measured, p_max=float(p_max),
                       low=low / scale, high=high / scale, scale=scale,
                       method=method, relative=error_model == "relative",
                       x0=x0)
    extra = _extra_starts(starts, names, low, high)
    workers = workers or os.cpu_count() or 1
    # one cluster for all the rounds of parallel jobs
    with threadpool_limits(limits=1), cluster(workers):
        return _fit(problem, given, extra, uncertainty, n_bootstrap, seed,
                    workers, callback, curve_points)


def _extra_starts(starts, names, low, high):
    if isinstance(starts, (int, np.integer)) and not isinstance(starts, bool):
        if starts < 1:
            raise JudderError(f"starts = {starts} is not allowed; allowed: "
                              ">= 1")
        return int(starts) - 1
    points = np.atleast_2d(np.asarray(starts, dtype=float))
    if points.shape[1] != len(names):
        raise JudderError(f"each start needs {len(names)} values "
                          f"({', '.join(names)})")
    if np.any(points < low) or np.any(points > high):
        raise JudderError("every start must lie within the bounds")
    return points


def _exact(problem, run):
    """True if a local fit matches the data to round-off."""
    n = max(int(np.sum(~problem.censored)), 1)
    unit = 1.0 if problem.relative else problem.p_max / PA_PER_BAR
    return math.sqrt(2 * run["cost"] / n) < _EXACT * unit


class _Progress:
    def __init__(self, callback, total):
        self.callback, self.total, self.done = callback, total, 0

    def step(self, count=1):
        self.until(self.done + count)

    def until(self, done):
        """Report ``done`` steps (never fewer than before)."""
        self.done = min(max(done, self.done), self.total)
        if self.callback is not None:
            self.callback(self.done, self.total)


def _run(function, jobs, workers, progress):
    out = []
    for item in parallel_map(function, jobs, min(workers, len(jobs)),
                             ordered=False):
        out.append(item)
        progress.step()
    return out


def _fit(problem, given, extra, uncertainty, n_bootstrap, seed, workers,
         callback, curve_points):
    k = len(problem.names)
    n_extra = extra if isinstance(extra, int) else len(extra)
    n_unc = {"jacobian": 1, "bootstrap": n_bootstrap}.get(uncertainty,
                                                          2 * k)
    progress = _Progress(callback, 1 + n_extra + ALTERNATIVE_ROUNDS + 1
                         + n_unc + (2 if curve_points else 0))
    evaluations = 0
    # the start must be computable: raise its error as is
    start_evaluator = _Evaluator(problem)
    z_start = problem.x0 / problem.scale
    start_evaluator.amplitudes(z_start, strict=True)
    evaluations += start_evaluator.count
    first = _fit_start((problem, z_start, given, 0, None, START_EVALUATIONS))
    first["origin"] = "given"
    runs = [first]
    progress.step()
    # an exact fit cannot be bettered: the other starts are skipped
    if n_extra and not _exact(problem, first):
        if isinstance(extra, int):
            candidates = _sample_starts(problem, SCREEN_PER_START * extra,
                                        seed)
            costs, count = _screen(problem, candidates, given)
            evaluations += count
            starts = list(candidates[np.argsort(costs)[:extra]])
        else:
            starts = list(extra / problem.scale)
        sampled = _run(_fit_start, [(problem, z, given, i + 1, None,
                                     EXTRA_START_EVALUATIONS)
                                    for i, z in enumerate(starts)], workers,
                       progress)
        for r in sorted(sampled, key=lambda r: r["index"]):
            r["origin"] = "sampled"
            runs.append(r)
    progress.until(1 + n_extra)
    best = min(runs, key=lambda r: r["cost"])
    # the ambiguous points matched the other way, from the best minimum
    for _ in range(ALTERNATIVE_ROUNDS):
        if _exact(problem, best):
            break
        evaluator = _Evaluator(problem)
        columns = _alternative(problem, evaluator.amplitudes(best["z"]),
                               best["columns"], given)
        evaluations += evaluator.count
        if columns is None:
            break
        run = _fit_start((problem, best["z"], given, len(runs), columns,
                          START_EVALUATIONS))
        run["origin"] = "rematched"
        runs.append(run)
        progress.step()
        if not run["cost"] < best["cost"] * (1 - 1e-9):
            break
        best = run
    if not best["success"] and not best["failed"]:
        # a start stopped by its budget: go on from where it stopped
        run = _fit_start((problem, best["z"], given, len(runs),
                          best["columns"], START_EVALUATIONS))
        run["origin"] = "continued"
        runs.append(run)
        progress.step()
        if run["cost"] <= best["cost"]:
            best = run
    progress.until(1 + n_extra + ALTERNATIVE_ROUNDS + 1)
    evaluations += sum(r["evaluations"] for r in runs)
    costs = np.array([r["cost"] for r in runs])
    z, columns, cost = best["z"], best["columns"], best["cost"]

    evaluator = _Evaluator(problem)
    amplitude = evaluator.amplitudes(z)
    residual = _residuals(problem, amplitude, columns)
    n = len(columns)
    active = int(np.sum(~problem.censored | (residual[:n] != 0))
                 + np.sum(residual[n:] != 0))
    dof = max(active - k, 1)
    s2 = 2 * cost / dof
    q = float(stats.t.ppf(0.5 + CONFIDENCE / 2, dof))
    exact = math.sqrt(s2) < _EXACT * (1.0 if problem.relative
                                      else problem.p_max / PA_PER_BAR)

    # the Jacobian, and on which side of each interval it can be trusted
    jac = _jacobian(evaluator, z, columns)
    null_names = _null_space_names(jac, problem.names)
    notes, info = [], []
    # covariance of the determined parameters, the others held
    cov_z = np.full((k, k), np.inf)
    kept = np.array([n not in null_names for n in problem.names])
    if kept.any():
        part = jac[:, kept]
        cov_z[np.ix_(kept, kept)] = max(s2, 0.0) * np.linalg.inv(part.T
                                                                  @ part)
    std_z = np.sqrt(np.clip(np.diag(cov_z), 0, None))
    trusted = np.repeat(kept[:, None], 2, axis=1)
    ratios = np.ones((k, 2))
    if kept.any() and not exact and s2 > 0 and uncertainty in (
            "auto", "jacobian"):
        ratios = _linearity_ratios(evaluator, z, columns,
                                   np.where(kept[:, None] & kept, cov_z, 0.0),
                                   cost, s2, q, kept)
        trusted = kept[:, None] & (ratios >= LINEARITY_RANGE[0]) & (
            ratios <= LINEARITY_RANGE[1])
        ratios = np.where(kept[:, None], ratios, 1.0)
        if not trusted[kept].all() and uncertainty == "jacobian":
            finite = ratios[np.isfinite(ratios)]
            notes.append(
                "the Jacobian uncertainties are unreliable here (at the ends "
                "of the linearised 95 % intervals the sum of squares grows "
                + (f"{finite.min():.2g} to {finite.max():.2g} times the "
                   "prediction" if len(finite) else "")
                + (" and " if len(finite) and np.isnan(ratios).any() else "")
                + ("some ends lie beyond a bound"
                   if np.isnan(ratios).any() else "")
                + "); use uncertainty='profile' or 'bootstrap'")
    evaluations += evaluator.count

    # a free point about as near to a second kind as to its own: the sum
    # of squares has a kink there (the matching may flip), which the
    # Jacobian cannot see
    ambiguous = _ambiguous_points(problem, amplitude, columns, given, s2)
    if ambiguous:
        info.append(
            "the measured onset lies within the scatter of two kinds of "
            "boundary at " + ", ".join(
                f"{problem.freq_hz[i]:g} Hz "
                f"({problem.measured[i] / PA_PER_BAR:.4g} bar: "
                f"{TONGUE_KINDS[columns[i]].label} "
                f"{amplitude[i, columns[i]] / PA_PER_BAR:.4g}, "
                f"{TONGUE_KINDS[other].label} "
                f"{amplitude[i, other] / PA_PER_BAR:.4g} bar)"
                for i, other in ambiguous)
            + "; matched to the first of each"
            + ("; the intervals are profiled over both matchings"
               if uncertainty in ("auto", "profile") else "")
            + " (give the kinds if they were observed)")
    if ambiguous and not exact:
        trusted[:] = False
    profile = {"jacobian": np.zeros((k, 2), bool),
               "profile": np.ones((k, 2), bool),
               "bootstrap": np.zeros((k, 2), bool)}.get(uncertainty)
    if profile is None:                              # auto
        profile = ~trusted & ~exact
    profile = profile & kept[:, None]   # an undetermined one: its bounds
    used = uncertainty
    if uncertainty == "auto":
        used = ("profile" if profile[kept].all() else "jacobian+profile"
                if profile.any() else "jacobian")
    open_sides = []
    boot_failed = 0
    if uncertainty == "bootstrap":
        ci_low, ci_high, std, boot_failed, count = _bootstrap(
            problem, columns, z, amplitude, s2, n_bootstrap, seed, workers,
            progress)
        evaluations += count
    else:
        ends = np.column_stack([z - q * std_z, z + q * std_z])
        ends = np.clip(ends, problem.low[:, None], problem.high[:, None])
        # first profile step: where the linearised path crossed t^2 s^2
        steps = q * std_z[:, None] / np.sqrt(np.clip(
            np.nan_to_num(ratios, nan=1.0), 0.25, 16.0))
        jobs = [(problem, columns, z, cost, max(s2, 1e-300), q, i, sign,
                 steps[i, side], given) for i in range(k)
                for side, sign in enumerate((-1, 1)) if profile[i, side]]
        progress.step(n_unc - len(jobs))
        if jobs:
            for i, sign, end, closed, count, better in _run(
                    _profile_side, jobs, workers, progress):
                evaluations += count
                ends[i, int(sign > 0)] = end
                if not closed:
                    open_sides.append((i, sign))
                if better:
                    notes.append(
                        f"the profile of {problem.names[i]} found a better "
                        "fit at " + ", ".join(
                            f"{n} = {v:.6g}" for n, v in zip(
                                problem.names, better[0] * problem.scale))
                        + ": the fit did not reach the best minimum; start "
                        "from there")
        ci_low = ends[:, 0] * problem.scale
        ci_high = ends[:, 1] * problem.scale
        std = std_z * problem.scale
        if profile.any():
            # half-width over t: the standard uncertainty the interval
            # corresponds to
            std = np.where(profile.any(axis=1),
                           (ci_high - ci_low) / (2 * q), std)
        std = np.where(kept, std, np.inf)

    values = z * problem.scale
    low, high = problem.low * problem.scale, problem.high * problem.scale
    width = high - low
    at_bound = tuple(n for n, v, a, b, w in zip(problem.names, values, low,
                                                high, width)
                     if v - a <= 1e-6 * w or b - v <= 1e-6 * w)

    # agreement of the starts (same minimum: within a tenth of a standard
    # uncertainty, or 1e-4 relative where that is not finite)
    minima = np.array([r["z"] for r in runs]) * problem.scale
    tolerance = np.where(np.isfinite(std) & (std > 0), 0.1 * std,
                         1e-4 * np.maximum(np.abs(values), 1e-300))
    same = np.all(np.abs(minima - values) <= np.maximum(
        tolerance, 1e-6 * np.abs(values)), axis=1)
    # another minimum inside the confidence set (sum of squares within
    # t^2 s^2): the set has two parts; the intervals are widened to
    # cover both (each with its own linearised interval)
    alternatives = []
    for r, m, agrees in zip(runs, minima, same):
        if agrees or not np.isfinite(r["cost"]) or s2 <= 0 or r["failed"]:
            continue
        growth = 2 * (r["cost"] - cost) / s2
        if growth < q * q and np.any((m < ci_low) | (m > ci_high)):
            alternatives.append((m, growth))
            check = _Evaluator(problem)
            jac_alt = _jacobian(check, r["z"], r["columns"])
            evaluations += check.count
            half = np.full(k, 0.0)
            if kept.any():
                part = jac_alt[:, kept]
                try:
                    cov_alt = s2 * np.linalg.inv(part.T @ part)
                    half[kept] = q * np.sqrt(np.clip(np.diag(cov_alt), 0,
                                                     None))
                except np.linalg.LinAlgError:
                    pass
            half = half * problem.scale
            ci_low = np.maximum(np.minimum(ci_low, m - half), low)
            ci_high = np.minimum(np.maximum(ci_high, m + half), high)
            std = np.maximum(std, (ci_high - ci_low) / (2 * q))

    undetermined = []
    for i, name in enumerate(problem.names):
        relative = std[i] / max(abs(values[i]), 1e-300)
        sides = [s for j, s in open_sides if j == i
                 and not (name in at_bound
                          and abs(values[i] - (high[i] if s > 0 else low[i]))
                          <= 1e-6 * width[i])]
        if (name in null_names or not np.isfinite(std[i])
                or relative >= UNDETERMINED_RELATIVE or sides):
            undetermined.append(name)

    problems = _problems(problem, best, alternatives, s2, at_bound,
                         undetermined, std, values, low, high, open_sides,
                         amplitude, columns, boot_failed, n_bootstrap, used)
    problems = notes + problems

    fitted = evaluator.params_at(z)
    capped = _capped(problem, amplitude) if amplitude is not None else \
        np.full((len(columns), 3), problem.p_search)
    raw_residual = residual[:n] * problem.weights / PA_PER_BAR
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
        start_costs=costs,
        covariance=_covariance(cov_z, std, kept))
    if curve_points:
        freq, start_bar, fitted_bar = fit_curves(result, curve_points)
        progress.step(2)
        result = _replace(result, curve_freq_hz=freq,
                          start_curve_bar=start_bar,
                          fitted_curve_bar=fitted_bar,
                          evaluations=result.evaluations + 2)
    return result


def _covariance(cov_z, std, kept):
    """Covariance of the values (SI): the Jacobian's correlations with the
    reported standard uncertainties; inf in the rows and columns of the
    undetermined parameters."""
    out = np.full(cov_z.shape, np.inf)
    if kept.any():
        part = cov_z[np.ix_(kept, kept)]
        scale = np.sqrt(np.clip(np.diag(part), 1e-300, None))
        out[np.ix_(kept, kept)] = (part / np.outer(scale, scale)
                                   * np.outer(std[kept], std[kept]))
    return out


def _replace(result, **changes):
    return dataclasses.replace(result, **changes)


def _bootstrap(problem, columns, z, amplitude, s2, n_bootstrap, seed,
               workers, progress):
    """Parametric bootstrap: refit synthetic boundaries."""
    if n_bootstrap < 2:
        raise JudderError(f"n_bootstrap = {n_bootstrap} is not allowed; "
                          "allowed: >= 2")
    rng = np.random.default_rng(seed)
    n = len(columns)
    if amplitude is None:
        raise JudderError("the model boundary cannot be computed at the "
                          "fitted values: no bootstrap")
    # the boundary the fitted model would show on the bench: the matched
    # kind at points with judder, the lowest kind elsewhere
    capped = _capped(problem, amplitude)
    lowest_column = np.argmin(capped, axis=1)
    boot_columns = np.where(problem.censored, lowest_column, columns)
    base = amplitude[np.arange(n), boot_columns]
    s = math.sqrt(max(s2, 0.0))
    jobs = []
    for b in range(n_bootstrap):
        noise = rng.standard_normal(n)
        noisy = (base * (1 + s * noise) if problem.relative
                 else base + s * PA_PER_BAR * noise)
        noisy = np.where(np.isnan(base) | (noisy > problem.p_max), np.nan,
                         np.maximum(noisy, 1e-6 * problem.p_max))
        if np.isnan(noisy).all():
            noisy = np.where(problem.censored, np.nan, base)
        jobs.append((problem.with_measured(noisy),
                     np.where(np.isnan(noisy), -1, boot_columns), z, b))
    results = _run(_bootstrap_refit, jobs, workers, progress)
    count = sum(r[3] for r in results)
    good = np.array([r[1] for r in results if r[2]])
    failed = n_bootstrap - len(good)
    if len(good) < 2:
        k = len(z)
        return (np.full(k, -np.inf), np.full(k, np.inf), np.full(k, np.inf),
                failed, count)
    values = good * problem.scale
    lo, hi = np.percentile(values, [50 * (1 - CONFIDENCE),
                                    50 * (1 + CONFIDENCE)], axis=0)
    return lo, hi, values.std(axis=0, ddof=1), failed, count


def _problems(problem, best, alternatives, s2, at_bound, undetermined, std,
              values, low, high, open_sides, amplitude, columns, boot_failed,
              n_bootstrap, used):
    out = []
    names = problem.names
    if not best["success"]:
        out.append(f"the optimiser did not converge: {best['message']}")
    if best["failed"] or amplitude is None:
        out.append("the model boundary could not be computed at the fitted "
                   "values")
        return out
    for name in at_bound:
        i = names.index(name)
        side = "lower" if values[i] - low[i] <= high[i] - values[i] \
            else "upper"
        bound = low[i] if side == "lower" else high[i]
        out.append(f"{name} = {values[i]:.6g} is at the {side} bound "
                   f"{bound:.6g} of its search range: widen its bounds or "
                   "fix it")
    for name in undetermined:
        i = names.index(name)
        sides = [s for j, s in open_sides if j == i]
        if sides:
            which = " and ".join(("upper" if s > 0 else "lower")
                                 for s in sorted(sides))
            why = (f"its 95 % interval reaches the {which} bound of the "
                   "search range without closing")
        elif not np.isfinite(std[i]):
            why = "its uncertainty is infinite (rank-deficient Jacobian)"
        else:
            why = (f"its uncertainty ({std[i]:.3g}) is "
                   f"{std[i] / max(abs(values[i]), 1e-300):.0%} of its value")
        out.append(f"{name} is not determined by the measured boundary: "
                   f"{why}; measure where it acts, or fix it")
    if used == "bootstrap" and boot_failed > 0.1 * n_bootstrap:
        out.append(f"{boot_failed} of {n_bootstrap} bootstrap refits failed")
    # a point whose kind has no boundary within the search limit
    n = len(columns)
    matched = amplitude[np.arange(n), np.maximum(columns, 0)]
    for i in np.flatnonzero(~problem.censored & np.isnan(matched)):
        out.append(
            f"at {problem.freq_hz[i]:g} Hz the model has no "
            f"{TONGUE_KINDS[columns[i]].label} boundary below "
            f"{problem.p_search / PA_PER_BAR:g} bar, where judder was "
            f"measured at {problem.measured[i] / PA_PER_BAR:.4g} bar")
    # the model predicts judder clearly below where it was measured/absent
    sigma = math.sqrt(max(s2, 0.0)) * problem.weights
    if problem.relative:
        sigma = math.sqrt(max(s2, 0.0)) * np.where(
            problem.censored, problem.p_max,
            np.maximum(np.nan_to_num(problem.measured),
                       _RELATIVE_FLOOR * problem.p_max))
    margin = np.maximum(3 * sigma, 0.01 * problem.p_max)
    capped = _capped(problem, amplitude)
    lowest_column = np.argmin(capped, axis=1)
    lowest = capped.min(axis=1)
    for i in range(n):
        if problem.censored[i]:
            if lowest[i] < problem.p_max - margin[i]:
                out.append(
                    f"at {problem.freq_hz[i]:g} Hz the model has "
                    f"{TONGUE_KINDS[lowest_column[i]].label} judder from "
                    f"{lowest[i] / PA_PER_BAR:.4g} bar, where none was "
                    f"measured up to {problem.p_max / PA_PER_BAR:g} bar")
        elif (lowest_column[i] != columns[i]
              and lowest[i] < problem.measured[i] - margin[i]):
            out.append(
                f"at {problem.freq_hz[i]:g} Hz the model's "
                f"{TONGUE_KINDS[lowest_column[i]].label} boundary "
                f"({lowest[i] / PA_PER_BAR:.4g} bar) lies below the "
                f"measured {TONGUE_KINDS[columns[i]].label} judder "
                f"({problem.measured[i] / PA_PER_BAR:.4g} bar)")
    # another minimum that fits nearly as well
    for m, growth in alternatives[:1]:
        out.append(
            "another minimum fits almost as well ("
            + ", ".join(f"{n} = {v:.4g}" for n, v in zip(problem.names, m))
            + f"; sum of squares +{growth:.2g} s^2): the measured boundary "
            "does not single out one parameter set (the intervals cover "
            "both)")
    return out

"""What every step of a boundary fit shares: the fitting problem, the
model's boundaries at scaled trial parameters, the residuals, the matching
of points to the nearest kind, one bounded least-squares run, and the
progress count of the parallel jobs.

Private to :mod:`stability.fit`; the residuals and the matching are
explained in the docstrings of :mod:`stability.fit._model` and
:mod:`stability.fit._matching`.
"""

import dataclasses
from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import least_squares

from infra.parallel import parallel_map
from infra.units import PA_PER_BAR

from ..friction import forced_onset
from ..source import build_driveline
from ..tongues import tongue_boundaries


#: Each kind's boundary is searched up to this multiple of ``p_max``.
SEARCH_FACTOR = 2.0



#: In the relative error model, amplitudes are divided by at least this
#: share of ``p_max``.
_RELATIVE_FLOOR = 0.02



#: Residual rms (weighted, share of the unit) below which the data are
#: taken as exact: the Jacobian is then used without the linearity check.
_EXACT = 1e-7



#: A second kind this many times as near as the matched one (plus 5 % of
#: ``p_max``) makes a point's matching ambiguous.
AMBIGUITY = 3.0



def evaluated(params, added=()):
    """The parameter set the model is evaluated with: ``params`` with each
    ``(name, value)`` of ``added`` added to its parameter.

    A bench's linearisation is the driveline with the damping of its
    motor's speed control added to body 1 (``c1 + d_control``,
    :attr:`drivelines.DrivelineModel.bench_damping`): fitting the driveline
    to a chart of that bench compares the chart with this model, and the
    fitted values stay those of the driveline.

    Examples
    --------
    >>> from sources import get_preset
    >>> evaluated(get_preset("paper-4dof"), (("c1", 2000.0),))["c1"]
    2000.1
    """
    if not added:
        return params
    return params.replace(**{name: params[name] + value
                             for name, value in added})



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
    min_growth: float = 0.0     # 1/s: boundaries of judder growing so
    added: tuple = ()           # (name, value) added for the model
    scatter: float = None       # known scatter, weighted units; None:
                                # estimated from the residuals
    grid_variance: float = 0.0  # weighted units^2: what the amplitude
                                # grid alone puts in the onsets
                                # (:func:`grid_variance`)
    threshold_spread: float = 0.0   # 1/s: uncertainty of min_growth
    forced_limit: float = None  # rad/s: onsets also where the forced
                                # upstream oscillation reaches it

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

    def params_at(self, z):
        """The parameter set at the scaled vector ``z``."""
        return self.params.replace(**dict(zip(self.names,
                                              map(float, z * self.scale))))

    def with_grid(self, onsets):
        """The problem with :attr:`grid_variance` of ``onsets`` (Pa, the
        grid's onsets; :attr:`measured` holds the middles of their
        intervals)."""
        return dataclasses.replace(self, grid_variance=grid_variance(
            onsets, self.measured, self.weights))

    def with_measured(self, measured):
        return dataclasses.replace(self, measured=measured)



def grid_variance(onsets, middles, weights):
    r"""Variance the amplitude grid alone puts in the compared amplitudes,
    in the units of the weighted residuals (share of the amplitude or bar).

    A chart finds an onset on the grid of amplitudes tried: the boundary
    lies anywhere in (below, onset], and the fit compares the model with
    the middle. Were the boundary uniform in that interval of width
    ``w``, the middle misses it by ``w^2 / 12`` in variance (Sheppard's
    correction), whatever the scatter of the onsets. Residuals smaller
    than that are no sign of a precise bench: onsets in the same grid step
    share one middle and their residuals shrink together, so the scatter
    estimated from them can come out far below the truth (six onsets of
    tongue 2 on a 0.1 bar grid: 3.1 % from the residuals where the grid
    alone gives 7 %, and Student's intervals held neither mu_g nor k24).

    Parameters
    ----------
    onsets : ndarray, shape (n,)
        Pa: the lowest amplitude with judder (NaN: censored).
    middles : ndarray, shape (n,)
        Pa: the compared amplitude, the middle of (below, onset] where the
        amplitude below was given, else the onset (NaN: censored).
    weights : ndarray, shape (n,)
        Pa: the divisor of each residual (:attr:`_Problem.weights`).

    Returns
    -------
    float
        The mean over the onsets of ``(w / weight)^2 / 12`` (``w = 0``
        where no amplitude below was given); 0 without onsets.

    Examples
    --------
    >>> grid_variance(np.array([3e4, np.nan]), np.array([2.5e4, np.nan]),
    ...               np.array([2.5e4, 1.5e5])) == (0.4 ** 2 / 12)
    True
    """
    onset = np.isfinite(middles)
    if not onset.any():
        return 0.0
    width = 2 * (onsets[onset] - middles[onset])
    return float(np.mean((width / weights[onset]) ** 2) / 12)


class _Evaluator:
    """Model boundaries of each kind at scaled parameter vectors, counted."""

    def __init__(self, problem):
        self.problem = problem
        self.count = 0

    def params_at(self, z):
        return self.problem.params_at(z)

    def amplitudes(self, z, strict=False):
        """Shape (n, 3), Pa, NaN where none up to the search limit; None
        if the model cannot be evaluated there (unless ``strict``)."""
        p = self.problem
        self.count += 1
        try:
            driveline = build_driveline(evaluated(self.params_at(z),
                                                  p.added))
            # the optimiser reads the amplitudes only: no monodromy check
            amplitude = tongue_boundaries(driveline, p.freq_hz, p.p_search,
                                          p.method, min_growth=p.min_growth,
                                          check=False).amplitude
            if p.forced_limit is not None:
                # the bench's verdict: forced judder at f is single-period
                # judder at its own onset
                amplitude = amplitude.copy()
                amplitude[:, 0] = np.fmin(amplitude[:, 0], forced_onset(
                    driveline, p.freq_hz, p.forced_limit))
            return amplitude
        except (ValueError, ArithmeticError, np.linalg.LinAlgError):
            if strict:
                raise
            return None

    def residuals(self, z, columns):
        return _residuals(self.problem, self.amplitudes(z), columns)



def _capped(problem, amplitude):
    return np.where(np.isnan(amplitude), problem.p_search, amplitude)



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
        if progress is not None:
            progress.step()
    return out

r"""The model side of a boundary fit (section 4.2): the fitting problem,
the model's tongue boundaries at trial parameters, and the residuals.

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
measured amplitude (at least 2 % of ``p_max``; censored points by
``p_max``), which suits a scatter proportional to the amplitude (a noise
of a few per cent). Dividing by the measured amplitude puts the fitted
boundary 2 sigma^2 low (0.2 % with 3 % noise, about a seventh of mu_g's
95 % half-width on the boundaries of ``benchmarks/fit_coverage.py``).
Differences of logarithms would remove that, and were tried: they
compress the residual of a point matched to a kind with no boundary
below the search limit (3 bar against 0.57 bar: 1.7 instead of 4.3), and
on 60 noisy boundaries three fits then stopped at k24 = 41 000-42 000
N m/rad for a truth near 29 000 (reported as problems, but wrong).
"""

import dataclasses
from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import least_squares

from infra.parallel import parallel_map
from infra.units import PA_PER_BAR

from .source import build_driveline
from .monodromy import DEFAULT_METHOD
from .relevance import DEFAULT_MIN_GROWTH_PER_S
from .tongues import tongue_boundaries

__all__ = ["model_boundary", "evaluated", "fit_curves", "SEARCH_FACTOR", "CURVE_POINTS"]

#: Each kind's boundary is searched up to this multiple of ``p_max``.
SEARCH_FACTOR = 2.0


#: Frequencies of the start and fitted curves stored for the plot.
CURVE_POINTS = 100


#: In the relative error model, amplitudes are divided by at least this
#: share of ``p_max``.
_RELATIVE_FLOOR = 0.02
#: Residual rms (weighted, share of the unit) below which the data are
#: taken as exact: the Jacobian is then used without the linearity check.
_EXACT = 1e-7


def model_boundary(params, freq_hz, p_max, method=DEFAULT_METHOD, *,
                   min_growth=DEFAULT_MIN_GROWTH_PER_S, added=()):
    """Lowest amplitude of judder growing at ``min_growth`` (1/s) or
    faster at each frequency, Pa: the model boundary
    :func:`stability.fitting.fit_boundary` compares with.

    NaN where there is none up to ``p_max``; ``method`` is the monodromy
    engine (:data:`stability.monodromy.METHODS`). ``min_growth`` defaults
    to ``judder check``'s judder-relevant rate, as ``fit_boundary``'s
    does; 0 gives the stability boundary
    (:func:`stability.tongues.tongue_boundaries`). ``added`` are ``(name,
    value)`` pairs added to ``params`` for the model evaluated (see
    :func:`evaluated`).
    """
    return tongue_boundaries(build_driveline(evaluated(params, added)),
                             freq_hz, p_max, method,
                             min_growth=min_growth).stability_boundary


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
    >>> from drivelines import get_preset
    >>> evaluated(get_preset("paper-4dof"), (("c1", 2000.0),))["c1"]
    2000.1
    """
    if not added:
        return params
    return params.replace(**{name: params[name] + value
                             for name, value in added})


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
    curves = [model_boundary(p, freq, p_max, method,
                             min_growth=result.min_growth,
                             added=result.added) / PA_PER_BAR
              for p in (result.start_params, result.params)]
    return freq, curves[0], curves[1]


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
    threshold_spread: float = 0.0   # 1/s: uncertainty of min_growth

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

    def with_measured(self, measured):
        return dataclasses.replace(self, measured=measured)


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
            return tongue_boundaries(
                build_driveline(evaluated(self.params_at(z), p.added)),
                p.freq_hz, p.p_search, p.method,
                min_growth=p.min_growth).amplitude
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


def _exact(problem, run):
    """True if a local fit matches the data to round-off."""
    n = max(int(np.sum(~problem.censored)), 1)
    unit = 1.0 if problem.relative else problem.p_max / PA_PER_BAR
    return math.sqrt(2 * run["cost"] / n) < _EXACT * unit

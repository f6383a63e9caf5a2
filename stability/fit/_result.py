r"""The result of a boundary fit (section 4.2, Fig. 16a) and what went
wrong with it.

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

import numpy as np

from infra.units import PA_PER_BAR

from ..monodromy import DEFAULT_METHOD
from ..tongues import TONGUE_KINDS
from ._common import _RELATIVE_FLOOR, _capped
from ._identifiability import correlation
from ._model import CURVE_POINTS, fit_curves

__all__ = ["FitResult", "UNDETERMINED_RELATIVE", "undetermined_names",
           "problem_sentences"]

#: A relative uncertainty at or above this makes a parameter undetermined.
UNDETERMINED_RELATIVE = 1.0


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
        The measured boundary compared with the model (NaN where
        censored): the onsets, or the middle of (below, onset] where the
        amplitude tried below each onset was given.
    onset_bar : ndarray, shape (n,)
        The onsets as given, bar (NaN where censored).
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
    min_growth : float
        1/s: the model boundaries compared are those of judder growing at
        this rate (0: the stability boundary).
    forced_limit : float or None
        rad/s: the model's single-period onset is also where the forced
        oscillation of the upstream speed reaches it (a bench's verdict,
        :func:`stability.friction.forced_onset`); None: Floquet alone.
    added : tuple of (str, float)
        Added to the parameters for the model compared (a bench's
        linearisation: ``(('c1', d_control),)``); ``values`` and
        ``params`` are without them.
    covariance : ndarray or None, shape (k, k)
        Covariance of ``values`` (SI): the correlations of the linearised
        fit with the standard uncertainties ``std``; ``inf`` in the rows
        and columns of undetermined parameters. ``judder envelope`` takes
        it as a joint normal distribution.
    scatter : float
        Scatter of the measured onsets: a share of the amplitude
        (``error_model='relative'``) or bar (``'absolute'``); estimated
        from the residuals, or the one given (``scatter_given``).
    scatter_given : bool
        The scatter was given (the bench's known repeatability).
    threshold_spread : float
        1/s: the spread of the growth threshold the fit was repeated at.
    threshold_shifts : ndarray or None, shape (k, 2)
        SI: each value refitted at ``min_growth`` minus and plus
        ``threshold_spread``, minus the fitted value; the intervals cover
        them. None without a spread.
    held : tuple of str
        Parameters that do not move the measured boundary, held at their
        start values (:func:`stability.fit._identifiability.without_effect`);
        also in ``undetermined`` and ``problems``.
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
    min_growth: float = 0.0
    added: tuple = ()
    covariance: np.ndarray = None
    scatter: float = None
    scatter_given: bool = False
    threshold_spread: float = 0.0
    threshold_shifts: np.ndarray = None
    held: tuple = ()
    onset_bar: np.ndarray = None
    forced_limit: float = None

    @property
    def determined(self):
        """True when the data determine every fitted value: the optimiser
        converged and no parameter is undetermined, held or on a bound of
        its search range (the report shows only such a fit)."""
        return (self.converged and not self.undetermined
                and not self.at_bound and not self.held)

    @property
    def correlation(self):
        """Correlation matrix of the fitted values, shape (k, k) (NaN in
        the rows and columns of undetermined parameters)."""
        return correlation(self.covariance)

    @property
    def start_params(self):
        """The parameter set of the first attempt (the start values)."""
        return self.params.replace(**dict(zip(self.names,
                                              map(float, self.start))))

    def with_curves(self, points=CURVE_POINTS, method=DEFAULT_METHOD):
        """A copy holding the start and fitted curves :meth:`plot` draws,
        computed by :func:`~stability.fit.fit_curves` (which takes
        ``points`` and ``method``); ``fit_boundary`` stores them unless run
        with ``curve_points=0``."""
        freq, start_bar, fitted_bar = fit_curves(self, points, method)
        return dataclasses.replace(self, curve_freq_hz=freq,
                                   start_curve_bar=start_bar,
                                   fitted_curve_bar=fitted_bar)

    def plot(self, ax=None):
        """Measured, first-attempt and fitted boundaries (Fig. 16a); see
        :func:`stability.plots.plot_fit`."""
        from ..plots import plot_fit
        return plot_fit(self, ax=ax)


def undetermined_names(names, values, std, low, high, at_bound,
                       null_names, open_sides):
    """Parameters the measured boundary does not determine."""
    width = high - low
    out = []
    for i, name in enumerate(names):
        relative = std[i] / max(abs(values[i]), 1e-300)
        sides = [s for j, s in open_sides if j == i
                 and not (name in at_bound
                          and abs(values[i] - (high[i] if s > 0 else low[i]))
                          <= 1e-6 * width[i])]
        if (name in null_names or not np.isfinite(std[i])
                or relative >= UNDETERMINED_RELATIVE or sides):
            out.append(name)
    return out


def problem_sentences(problem, best, alternatives, s2, at_bound,
                      undetermined, std, values, low, high, open_sides,
                      amplitude, columns, boot_failed, n_bootstrap, used):
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

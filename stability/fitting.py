"""Fitting the model's stability boundary to a measured one (section 4.2).

The measured boundary is a list of dither frequencies with, for each, the
lowest amplitude at which judder was seen, or none (no judder up to the
largest amplitude tried: a censored point). The model boundary at a
frequency is the lowest amplitude at which any tongue starts
(:attr:`~stability.tongues.Boundaries.stability_boundary`). The fit
adjusts the chosen parameters by bounded least squares
(:func:`scipy.optimize.least_squares`) on the residuals in bar:

* a point with judder: model boundary minus measured boundary (a model
  boundary above the search limit counts as the limit);
* a censored point: how far the model boundary lies below the largest
  amplitude tried (zero if the model is stable there too).

The standard uncertainty of each fitted value comes from the Jacobian at
the solution, ``cov = s^2 (J^T J)^-1`` with ``s^2`` the residual variance.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from infra.errors import JudderError
from infra.units import PA_PER_BAR

from .model import build_driveline
from .monodromy import DEFAULT_METHOD, get_method
from .tongues import tongue_boundaries

__all__ = ["FitResult", "model_boundary", "fit_boundary", "DEFAULT_FIT"]

#: Parameters fitted by default: those the paper calls hard to estimate.
DEFAULT_FIT = ("c12", "mu_g", "k24")


def model_boundary(params, freq_hz, p_max, method=DEFAULT_METHOD):
    """Lowest unstable amplitude of the model at each frequency, Pa.

    NaN where the model is stable up to ``p_max``; ``method`` is the
    monodromy engine (:data:`stability.monodromy.METHODS`).
    """
    return tongue_boundaries(build_driveline(params), freq_hz, p_max,
                             method).stability_boundary


@dataclass(frozen=True)
class FitResult:
    """Outcome of :func:`fit_boundary`.

    Attributes
    ----------
    names : tuple of str
        Fitted parameters.
    values, start, std : ndarray, shape (k,)
        Fitted values, starting values and standard uncertainties (SI
        units; ``inf`` where the data do not determine a value).
    params : drivelines.Parameters
        The parameter set with the fitted values.
    residual_rms_bar : float
        Root mean square of the residuals, bar.
    residuals_bar : ndarray, shape (n,)
    freq_hz, measured_bar : ndarray, shape (n,)
        The measured boundary (NaN where censored).
    model_bar : ndarray, shape (n,)
        Model boundary with the fitted values, bar (NaN: stable up to the
        search limit).
    success : bool
    message : str
    evaluations : int
        Model boundaries computed.
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

    def plot(self, ax=None):
        """Measured and fitted boundaries; see
        :func:`stability.plotting.plot_fit`."""
        from .plotting import plot_fit
        return plot_fit(self, ax=ax)


#: Default search range: this factor either way of the start value (clutch
#: damper damping alone spans 10 to over 1000 N m s/rad in the literature
#: the paper cites).
BOUND_FACTOR = 100.0


def _default_bounds(params, name):
    value = params[name]
    if value > 0:
        return value / BOUND_FACTOR, value * BOUND_FACTOR
    if value < 0:
        return value * BOUND_FACTOR, value / BOUND_FACTOR
    raise JudderError(f"give --bounds for {name}: its start value is 0")


def fit_boundary(params, freq_hz, measured_p_f, p_max, names=DEFAULT_FIT,
                 bounds=None, start=None, method=DEFAULT_METHOD):
    """Fit parameters so the model boundary matches a measured one.

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
        Largest amplitude tried on the bench (and searched in the model),
        Pa.
    names : sequence of str
        Parameters to fit.
    bounds : dict, optional
        ``{name: (low, high)}``; default :data:`BOUND_FACTOR` either way
        of the start value.
    start : dict, optional
        Start values overriding ``params``.
    method : str
        Monodromy engine, a key of :data:`stability.monodromy.METHODS`.

    Returns
    -------
    FitResult
    """
    names = tuple(names)
    if not names:
        raise JudderError("give at least one parameter to fit")
    get_method(method)
    freq_hz = np.asarray(freq_hz, dtype=float)
    measured = np.asarray(measured_p_f, dtype=float)
    if freq_hz.shape != measured.shape or freq_hz.ndim != 1:
        raise JudderError("the measured boundary needs one amplitude per "
                          "frequency")
    if len(freq_hz) < len(names):
        raise JudderError(f"{len(freq_hz)} measured points cannot determine "
                          f"{len(names)} parameters")
    params = params.replace(**(start or {}))
    bounds = {**{n: _default_bounds(params, n) for n in names},
              **(bounds or {})}
    unknown = sorted(set(bounds) - set(names))
    if unknown:
        raise JudderError(f"bounds given for {unknown[0]}, which is not "
                          f"fitted (fitting: {', '.join(names)})")
    low = np.array([bounds[n][0] for n in names], dtype=float)
    high = np.array([bounds[n][1] for n in names], dtype=float)
    x0 = np.array([params[n] for n in names], dtype=float)
    if np.any(low >= high) or np.any(x0 < low) or np.any(x0 > high):
        raise JudderError("each bound must be LOW < HIGH around the start "
                          "value; got " + ", ".join(
                              f"{n} = {v:g} in [{a:g}, {b:g}]"
                              for n, v, a, b in zip(names, x0, low, high)))
    scale = np.maximum(np.abs(x0), 1e-12)
    censored = np.isnan(measured)
    if censored.all():
        raise JudderError("the measured boundary has no point with judder: "
                          "it cannot determine the parameters")
    count = [0]

    def boundary(x):
        count[0] += 1
        trial = params.replace(**dict(zip(names, map(float, x * scale))))
        return model_boundary(trial, freq_hz, p_max, method)

    def residuals(x):
        model = boundary(x)
        capped = np.where(np.isnan(model), p_max, model)
        return np.where(censored, -np.maximum(p_max - capped, 0.0),
                        capped - measured) / PA_PER_BAR

    fit = least_squares(residuals, x0 / scale, bounds=(low / scale,
                                                       high / scale),
                        x_scale="jac", diff_step=1e-4, xtol=1e-10,
                        ftol=1e-12)
    values = fit.x * scale
    dof = max(len(freq_hz) - len(names), 1)
    variance = 2 * fit.cost / dof
    jac = fit.jac / scale[None, :]
    # a parameter the data do not determine has an infinite uncertainty
    if np.linalg.matrix_rank(jac) < len(names):
        std = np.full(len(names), np.inf)
    else:
        cov = variance * np.linalg.inv(jac.T @ jac)
        std = np.sqrt(np.clip(np.diag(cov), 0, None))
    fitted = params.replace(**dict(zip(names, map(float, values))))
    return FitResult(
        names=names, values=values, start=x0, std=std, params=fitted,
        residual_rms_bar=float(np.sqrt(np.mean(fit.fun ** 2))),
        residuals_bar=fit.fun, freq_hz=freq_hz,
        measured_bar=measured / PA_PER_BAR,
        model_bar=boundary(fit.x) / PA_PER_BAR, success=bool(fit.success),
        message=fit.message, evaluations=count[0])

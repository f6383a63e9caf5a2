r"""Stability without dither: the friction-gradient threshold (Fig. 19).

With ``p_f = 0`` Eq. (6) is time-invariant; the mean pressure in the
slip damping (option ``mean_pressure_damping``, 1 for this study) makes
``mu_g N_c R_m S p_m`` a damping between the clutch discs, negative for a
falling friction curve. The driveline is unstable everywhere (region A of
Fig. 19b) when an eigenvalue has a positive real part, and otherwise stable
unless parametrically excited (region B).

The linear analysis uses python-control. The rigid-body angles are not in
the state (see :meth:`~stability.model.Driveline.periodic_system`); if all
external damping is zero, the common rotation of all bodies is an
undamped free mode with eigenvalue exactly 0, and it is deflated so that
it cannot decide the verdict.

Closed form: treating the chain as rigid, the slip mode is two bodies
(chain with external damping ``C_a``, output body with ``C_b``) joined by
the damping ``d = mu_g N_c R_m S p_m``; its determinant changes sign at

.. math:: d^* = -\frac{C_a C_b}{C_a + C_b},

the two external dampings in series. With every ``c_i = c`` in the 4-DOF
model this is ``mu_g* = -0.75 c / (N_c R_m S p_m)``.
"""

from dataclasses import dataclass

import control
import numpy as np
import scipy.linalg
from scipy.optimize import brentq

from drivelines.specs import MEAN_PRESSURE_DAMPING
from infra.errors import JudderError

from .source import build_driveline

__all__ = ["constant_system", "max_real_part", "friction_threshold",
           "closed_form_threshold", "ThresholdStudy", "threshold_study"]


#: 1/s: a common rotation decaying slower than this (its external
#: damping over its inertia) is free: below round-off of the eigenvalues,
#: it is deflated as with no external damping at all (c_i = 1e-300 would
#: otherwise decide the verdict by the sign of a round-off).
FREE_RATE_PER_S = 1e-9


def constant_system(driveline):
    """The driveline without dither as a python-control state-space model.

    Input: a torque between the clutch discs (N m, positive drives the
    input disc backwards like the friction torque); output: the slip speed
    (rad/s). States as in :meth:`~stability.model.Driveline.periodic_system`,
    with the free common rotation deflated when no external damping holds
    it.

    Returns
    -------
    control.StateSpace
    """
    system = driveline.periodic_system()
    gain = driveline.mu_g * driveline.clutch_factor
    B = (system.u / gain if gain != 0 else
         _unit_torque_input(driveline))[:, None]
    A, B, C = system.A0, B, system.v[None, :]
    if (np.sum(driveline.external_damping) / np.sum(driveline.inertia)
            < FREE_RATE_PER_S):
        ns = len(driveline.springs)
        rigid = np.concatenate([np.zeros(ns), np.sqrt(driveline.inertia)])
        basis = scipy.linalg.null_space(rigid[None, :])
        A, B, C = basis.T @ A @ basis, basis.T @ B, C @ basis
    return control.ss(A, B, C, 0)


def _unit_torque_input(driveline):
    ns = len(driveline.springs)
    return np.concatenate([np.zeros(ns), -driveline.clutch_vector()
                           / np.sqrt(driveline.inertia)])


def max_real_part(params):
    """Largest real part of the eigenvalues without dither, 1/s (Fig. 19a).

    Positive: unstable whatever the dither (region A).
    """
    return float(np.max(constant_system(build_driveline(params)).poles().real))


def closed_form_threshold(params):
    """``mu_g*`` of the rigid-chain slip mode (module docstring), s/rad."""
    driveline = build_driveline(params)
    output = driveline.external_damping[driveline.clutch[1]]
    chain = driveline.external_damping.sum() - output
    series = 0.0 if chain + output == 0 else chain * output / (chain + output)
    return -series / (params.clutch_factor * params["p_m"]
                      * params[MEAN_PRESSURE_DAMPING])


def friction_threshold(params, bracket=(-1.0, 1.0)):
    """Friction gradient ``mu_g*`` where the largest real part crosses 0.

    Parameters
    ----------
    params : drivelines.Parameters
        ``mu_g`` is ignored (it is the unknown); ``mean_pressure_damping``
        must be > 0, or ``mu_g`` does not enter without dither.
    bracket : (float, float)
        Search interval for ``mu_g``, s/rad.

    Returns
    -------
    float
        ``mu_g*``: stable above it, unstable below it, s/rad.

    Raises
    ------
    JudderError
        If no crossing lies in ``bracket``.
    """
    if params[MEAN_PRESSURE_DAMPING] <= 0 or params["p_m"] <= 0:
        raise JudderError("the friction-gradient threshold needs the mean "
                          "pressure in the slip damping: set "
                          "mean_pressure_damping > 0 and p_m > 0")

    def rate(mu_g):
        return max_real_part(params.replace(mu_g=mu_g))

    low, high = bracket
    at_low, at_high = rate(low), rate(high)
    if not (at_low > 0 >= at_high):
        raise JudderError(
            f"no stability threshold for mu_g in [{low:g}, {high:g}] s/rad: "
            f"the largest real part is {at_low:+.3g} 1/s at mu_g = {low:g} "
            f"and {at_high:+.3g} 1/s at {high:g} (unstable above 0); "
            "allowed: a driveline stable for a large mu_g and unstable for "
            "a very negative one (a `bracket` wider than the threshold)")
    return brentq(rate, low, high, xtol=1e-14, rtol=1e-12)


@dataclass(frozen=True)
class ThresholdStudy:
    """Fig. 19: largest real part against mu_g, threshold against c_i.

    Attributes
    ----------
    mu_g : ndarray, shape (n,)
        Friction gradients, s/rad.
    max_real_part : ndarray, shape (n,)
        Largest real part of the eigenvalues at each mu_g, 1/s (Fig. 19a).
    threshold : float
        ``mu_g*`` of the parameter set, s/rad.
    external_damping : ndarray, shape (k,)
        Values of c_i (every external damping set to it), N m s/rad.
    thresholds : ndarray, shape (k,)
        ``mu_g*`` at each c_i (Fig. 19b): region A below, B above.
    closed_form : ndarray, shape (k,)
        The rigid-chain formula at each c_i.
    """

    mu_g: np.ndarray
    max_real_part: np.ndarray
    threshold: float
    external_damping: np.ndarray
    thresholds: np.ndarray
    closed_form: np.ndarray

    def plot(self, axes=None):
        """Draw Fig. 19a and 19b; see :func:`stability.plots.plot_threshold`."""
        from .plots import plot_threshold
        return plot_threshold(self, axes=axes)


def threshold_study(params, mu_g, external_damping, callback=None):
    """Fig. 19 for a parameter set.

    Parameters
    ----------
    params : drivelines.Parameters
    mu_g : array_like
        Friction gradients for Fig. 19a, s/rad.
    external_damping : array_like
        Values for every external damping c_i, N m s/rad (Fig. 19b).
    callback : callable, optional
        ``callback(done, total)`` after each c_i.

    Returns
    -------
    ThresholdStudy
    """
    mu_g = np.atleast_1d(np.asarray(mu_g, dtype=float))
    damping = np.atleast_1d(np.asarray(external_damping, dtype=float))
    if not np.all(np.isfinite(mu_g)):
        raise JudderError("mu_g values must be finite")
    if not np.all(np.isfinite(damping)) or np.any(damping < 0):
        raise JudderError("external damping values must be finite and >= 0")
    rates = np.array([max_real_part(params.replace(mu_g=m)) for m in mu_g])
    span = max(1.0, 10 * np.abs(mu_g).max())
    thresholds, closed = [], []
    for index, c in enumerate(damping):
        case = params.replace(**{
            n: c for n in params.driveline.external_damping_names()})
        thresholds.append(friction_threshold(case, (-span, span)))
        closed.append(closed_form_threshold(case))
        if callback is not None:
            callback(index + 1, len(damping))
    return ThresholdStudy(mu_g=mu_g, max_real_part=rates,
                          threshold=friction_threshold(params, (-span, span)),
                          external_damping=damping,
                          thresholds=np.array(thresholds),
                          closed_form=np.array(closed))

"""The bounded friction curve of the engagement models and its linearisation.

The bench's EVEN clutch (``Judder.Components.CurveWetClutch``) has a
friction coefficient that is a bounded, rising curve of the slip speed
``w`` (the kind Fig. 9 shows), with the value ``mu0`` and the slope
``mu_g`` at the slip ``w_op``:

.. math:: \\mu(w) = \\mu_0 + \\Delta\\mu \\tanh\\left(
          \\frac{\\mu_g (|w| - w_{op})}{\\Delta\\mu}\\right)

Linearised about a steady slip ``w_s``, the engagement model is the
stability model of Eq. (2)-(6) with ``mu0`` and ``mu_g`` replaced by the
curve's value and slope at ``w_s`` (:func:`curve_at`): the two views of
one model. :func:`curve_from_table` turns a measured curve into the
three parameters.
"""

from dataclasses import dataclass

import numpy as np

from infra.errors import JudderError

__all__ = ["FrictionPoint", "curve", "curve_value", "curve_at", "curve_from_table",
           "linear_range", "forced_slip_amplitude", "forced_speed_per_pa", "forced_onset",
           "SLOPE_LOSS"]


@dataclass(frozen=True)
class FrictionPoint:
    """Value and slope of the friction curve at one slip.

    Attributes
    ----------
    mu : float
        Friction coefficient, 1 (the stability model's ``mu0``).
    slope : float
        d mu / d w, s/rad (the stability model's ``mu_g``).
    """

    mu: float
    slope: float


def curve(slip, mu0, mu_g, delta_mu, w_op):
    """Value and slope of the friction curve at many slips (the kernel
    :func:`curve_at` and :meth:`stability.orbit.EngagementModel.friction`
    share).

    Parameters
    ----------
    slip : array_like
        Slip speeds ``w``, rad/s, any shape.
    mu0, mu_g, delta_mu, w_op : float
        As for :func:`curve_at`.

    Returns
    -------
    mu : ndarray, shape of ``slip``
        Friction coefficient, 1.
    slope : ndarray, shape of ``slip``
        ``d mu / d|w|``, s/rad (times ``sign(w)`` for ``d mu / d w``).

    Examples
    --------
    >>> mu, slope = curve([84.7, -84.7], 0.09, 0.022, 0.09, 84.7)
    >>> mu.round(3).tolist(), slope.round(4).tolist()
    ([0.09, 0.09], [0.022, 0.022])
    """
    # 1/cosh^2, not 1 - tanh^2: on the flat tails (slope 1e-10) the
    # difference would lose every digit; cosh overflows to inf only where
    # the slope is 0 anyway
    with np.errstate(over="ignore"):
        return (curve_value(slip, mu0, mu_g, delta_mu, w_op),
                mu_g / np.cosh(_rise(slip, mu_g, delta_mu, w_op)) ** 2)


def curve_value(slip, mu0, mu_g, delta_mu, w_op):
    """The friction coefficient alone, 1, shape of ``slip`` (:func:`curve`
    without the slope, for a right-hand side that needs no Jacobian)."""
    return mu0 + delta_mu * np.tanh(_rise(slip, mu_g, delta_mu, w_op))


def _rise(slip, mu_g, delta_mu, w_op):
    """The argument of the curve's tanh."""
    return mu_g * (np.abs(slip) - w_op) / delta_mu


def curve_at(slip, mu0, mu_g, delta_mu, w_op):
    """Value and slope of the friction curve at the slip ``slip``.

    Parameters
    ----------
    slip : float
        Slip speed, rad/s.
    mu0, mu_g : float
        Value (1) and slope (s/rad) of the curve at ``w_op``.
    delta_mu : float
        Half the rise of the curve, 1 (> 0).
    w_op : float
        Slip of ``mu0`` and ``mu_g``, rad/s.

    Returns
    -------
    FrictionPoint

    Examples
    --------
    >>> p = curve_at(84.7, 0.09, 0.022, 0.09, 84.7)
    >>> round(p.mu, 3), round(p.slope, 4)
    (0.09, 0.022)
    """
    mu, slope = curve(slip, mu0, mu_g, delta_mu, w_op)
    return FrictionPoint(mu=float(mu), slope=float(slope))


def curve_from_table(slip, mu, w_op):
    """Curve parameters from a measured friction curve.

    The value and slope at the operating slip come from a cubic
    smoothing of the table (SciPy ``make_smoothing_spline``), half the
    rise from the table's range.

    Parameters
    ----------
    slip : array_like, shape (n,)
        Slip speeds, rad/s, increasing (n >= 5).
    mu : array_like, shape (n,)
        Friction coefficients, 1.
    w_op : float
        Operating slip, rad/s, inside the table.

    Returns
    -------
    dict
        ``mu0``, ``mu_g`` (s/rad) and ``delta_mu``, the parameters of
        ``CurveWetClutch`` and of the bench model.
    """
    from scipy.interpolate import make_smoothing_spline
    slip = np.asarray(slip, dtype=float)
    mu = np.asarray(mu, dtype=float)
    if slip.shape != mu.shape or slip.ndim != 1 or len(slip) < 5:
        raise JudderError("a friction table needs two columns of the same "
                          f"length, at least 5 rows (got {slip.shape} and "
                          f"{mu.shape})")
    if not (np.all(np.isfinite(slip)) and np.all(np.isfinite(mu))):
        raise JudderError("a friction table must hold finite numbers only")
    if np.any(np.diff(slip) <= 0):
        raise JudderError("the slip column of a friction table must be "
                          "increasing")
    if not slip[0] <= w_op <= slip[-1]:
        raise JudderError(f"w_op = {w_op:g} rad/s is outside the friction "
                          f"table; allowed: {slip[0]:g} to {slip[-1]:g} rad/s")
    spline = make_smoothing_spline(slip, mu)
    rise = 0.5 * float(mu.max() - mu.min())
    return {"mu0": float(spline(w_op)), "mu_g": float(spline(w_op, 1)),
            "delta_mu": max(rise, 1e-6)}


#: Loss of slope (share) at the edge of :func:`linear_range`.
SLOPE_LOSS = 0.2


def linear_range(slip, mu_g, delta_mu, w_op, loss=SLOPE_LOSS):
    """Slip offset from ``slip`` over which the curve keeps its slope there
    to within ``loss`` (either way), rad/s.

    With ``x = mu_g (|w| - w_op)/delta_mu`` the slope is ``mu_g
    sech^2 x``; from ``x0`` at ``slip`` the offset is the smallest ``dx``
    with ``sech^2(x0 +- dx) = (1 +- loss) sech^2 x0``, in slip units. At
    the steep middle (``x0 = 0``) this is ``arctanh(sqrt(loss)) delta_mu
    / mu_g``; on a flat tail the slope still changes by ``loss`` within
    about ``loss delta_mu / (2 mu_g)``, however small it is there (the
    tail of the curve is not linear over a wide range because its slope
    is small).

    A slip that swings wider samples another slope: the engagement then
    need not follow the linearisation's Floquet exponent.

    Examples
    --------
    >>> round(linear_range(84.7, 0.022, 0.09, 84.7), 2)
    1.97
    >>> round(linear_range(137.0, 0.017, 0.09, 84.7), 2)
    0.48
    """
    if mu_g == 0:
        return float("inf")
    scale = delta_mu / abs(mu_g)
    x0 = (abs(slip) - w_op) / scale
    sech2 = 1.0 / np.cosh(x0) ** 2
    # |x| where the slope has fallen, or risen (towards the middle), by
    # the share ``loss``; a rise beyond the middle's slope never comes
    targets = [(1 - loss) * sech2] + ([(1 + loss) * sech2]
                                      if (1 + loss) * sech2 < 1 else [])
    return float(min(abs(abs(x0) - np.arccosh(1.0 / np.sqrt(target)))
                     for target in targets) * scale)


def forced_slip_amplitude(driveline, freq_hz, p_f):
    """Amplitude of the slip's forced response to the dither, rad/s.

    The steady response of Eq. (6) to the dither part of the friction
    torque, ``mu0 N_c R_m S p_f cos(omega t)`` (the column ``D`` of Eq. 9),
    without the parametric term (which does not move the forced response
    to first order in ``p_f``):
    ``(K - omega^2 M + i omega C_0) Theta = -mu0 N_c R_m S p_f e``.

    Parameters
    ----------
    driveline : stability.model.Driveline
    freq_hz : float
        Dither frequency, Hz (> 0).
    p_f : float
        Dither amplitude, Pa.

    Returns
    -------
    float
        ``|i omega e . Theta|``, rad/s.
    """
    theta = _forced_angles(driveline, freq_hz)[0] * p_f
    omega = 2 * np.pi * freq_hz
    return float(abs(1j * omega * (driveline.clutch_vector() @ theta)))


def forced_upstream_amplitude(driveline, freq_hz, p_f):
    """Amplitude of the upstream disc's forced speed at the dither
    frequency, rad/s: :func:`forced_slip_amplitude`'s response read at
    the clutch's engine-side body (the speed the bench records), the
    linear harmonic response of Eq. (6) driven by the column ``D`` of
    Eq. (9)."""
    theta = _forced_angles(driveline, freq_hz)[0] * p_f
    omega = 2 * np.pi * freq_hz
    return float(abs(1j * omega * theta[driveline.clutch[0]]))


def _forced_angles(driveline, freq_hz):
    """Complex angle amplitudes per Pa of ``p_f`` forced by the dither,
    shape (len, n): ``(K - omega^2 M + i omega C_0) Theta = -mu0 N_c R_m S
    e`` at each frequency (Eq. 6 driven by the column D of Eq. 9)."""
    e = driveline.clutch_vector()
    damping = driveline.structural_damping() + (
        driveline.mu_g * driveline.clutch_factor
        * driveline.mean_pressure_damping * driveline.p_m) * np.outer(e, e)
    omega = 2 * np.pi * np.atleast_1d(np.asarray(freq_hz, dtype=float))
    dynamic = (driveline.stiffness_matrix()[None]
               - omega[:, None, None] ** 2 * driveline.mass_matrix()[None]
               + 1j * omega[:, None, None] * damping[None])
    force = -driveline.mu0 * driveline.clutch_factor * e.astype(complex)
    return np.linalg.solve(dynamic, np.broadcast_to(
        force, (len(omega), len(e)))[..., None])[..., 0]


def forced_speed_per_pa(driveline, freq_hz, body=None):
    """Speed amplitude of one body forced by the dither, per Pa of
    ``p_f``, rad/(s Pa).

    The steady response of Eq. (6) to the column ``D`` of Eq. (9), as in
    :func:`forced_slip_amplitude`, read at ``body`` (default the clutch's
    engine-side disc, whose speed the bench records upstream of the
    clutch). It is the fundamental of the periodic orbit at any amplitude
    the friction curve allows: an odd curve about the operating slip
    adds harmonics and a rectified torque, not a fundamental
    (:mod:`stability.orbit`; 257 rpm against 263 rpm on the bench at 103
    Hz and 0.3 bar, where the slip swings over 40 times the curve's
    linear range).

    Parameters
    ----------
    driveline : stability.model.Driveline
    freq_hz : array_like
        Dither frequencies, Hz (> 0).
    body : int, optional

    Returns
    -------
    ndarray
        Same shape as ``freq_hz``.
    """
    body = driveline.clutch[0] if body is None else body
    omega = 2 * np.pi * np.atleast_1d(np.asarray(freq_hz, dtype=float))
    speed = np.abs(omega * _forced_angles(driveline, freq_hz)[:, body])
    return speed.reshape(np.shape(freq_hz))


def forced_onset(driveline, freq_hz, limit):
    """Dither amplitude at which the forced oscillation of the upstream
    speed reaches ``limit`` (rad/s), Pa: the boundary of forced judder,
    ``limit`` over :func:`forced_speed_per_pa` (no threshold: the
    amplitude is proportional to ``p_f``)."""
    return limit / forced_speed_per_pa(driveline, freq_hz)

r"""Monodromy matrices over one dither period (Eq. 10-11).

Two engines compute :math:`X(T)` of :math:`\dot z = (A_0 + p_f\cos(\omega t)
U V^T) z` for a whole column of dither amplitudes at one frequency:

``'dyson'`` (default)
    Splits the period into ``m`` equal sub-intervals. On each, the
    propagator is written in the interaction picture of :math:`A_0` as a
    power series in :math:`p_f` (Dyson series),

    .. math:: X_j(p_f) = e^{A_0 h} \sum_{n=0}^{D} p_f^n Y_n(h), \qquad
              Y_n(s) = \int_0^s \cos(\omega (t_j+\sigma))\,
              e^{-A_0\sigma} U V^T e^{A_0\sigma}\, Y_{n-1}(\sigma)\,d\sigma,

    with :math:`Y_0 = I`. The integrals are evaluated by Chebyshev
    spectral integration on Gauss-Lobatto nodes; a modulation of rank
    ``r`` (``U, V`` of shape ``(m, r)``; the paper's models have
    ``r = 1``, ``u v^T``) makes each term cost O(r m^2) per node. The
    coefficients do not depend
    on :math:`p_f`, so a whole column of amplitudes costs one Horner
    evaluation and ``m`` products per amplitude. Sub-interval length,
    node count and series degree are chosen so the series tail and the
    quadrature error stay near machine precision.
``'solve_ivp'``
    Integrates the matrix ODE for each amplitude with
    :func:`scipy.integrate.solve_ivp` (DOP853): the simple baseline and the
    independent reference.

Each engine is a propagator class, built once per frequency for
amplitudes up to ``p_max`` and asked for ``monodromy(p_f)`` (shape
``(n_amplitudes, m, m)``); :data:`METHODS` maps the names to the classes,
and every study (maps, tongues, sensitivity, fitting, cross-check) takes
a ``method`` from it.
"""

import math

import numpy as np
import scipy.linalg
from numpy.polynomial import chebyshev
from scipy.integrate import solve_ivp

from infra.errors import JudderError

from .waveforms import waveform_of

__all__ = ["METHODS", "DEFAULT_METHOD", "DysonPropagator",
           "IntegratedPropagator", "monodromy", "monodromy_dyson",
           "monodromy_solve_ivp", "get_method", "least_subintervals"]

#: Chebyshev-Lobatto nodes per sub-interval.
_NODES = 32
#: Largest phase (rad) the interaction-picture integrand may turn through
#: on one sub-interval; 32 nodes resolve it to machine precision.
_MAX_PHASE = 8.0
#: Largest norm bound of the modulation over one sub-interval, so that the
#: series converges fast.
_MAX_STRENGTH = 1.5
#: Relative size of the first neglected series term.
_SERIES_TOLERANCE = 1e-17
#: Most sub-intervals one period may need (memory grows with it: about
#: 0.5 GB at this limit); below about 0.01 Hz use 'solve_ivp'.
MAX_SUBINTERVALS = 20_000


def _lobatto_integration():
    """Nodes on [-1, 1] and the matrix of the integral from -1 to each node."""
    x = np.cos(np.pi * np.arange(_NODES)[::-1] / (_NODES - 1))
    vander = chebyshev.chebvander(x, _NODES - 1)
    integral = np.empty((_NODES, _NODES))
    for k in range(_NODES):
        coef = np.zeros(_NODES)
        coef[k] = 1.0
        integral[:, k] = chebyshev.chebval(x, chebyshev.chebint(coef, lbnd=-1))
    return x, integral @ np.linalg.inv(vander)


_X, _INTEGRATION = _lobatto_integration()


def _series_degree(strength):
    """Smallest D with strength^(D+1)/(D+1)! below the tolerance."""
    degree, term = 0, strength
    while term > _SERIES_TOLERANCE:
        degree += 1
        term *= strength / (degree + 1)
    return max(degree, 1)


def least_subintervals(A0, freq_hz):
    """Sub-intervals per period the Dyson engine takes at least.

    The integrand of one sub-interval turns through at most
    :data:`_MAX_PHASE` rad, and it turns at twice the spectral radius of
    ``A0`` plus the dither's angular frequency; a strong modulation asks
    for more (:class:`DysonPropagator`). Time estimates use the same rule.

    Parameters
    ----------
    A0 : ndarray, shape (m, m)
        Constant part of the system, 1/s.
    freq_hz : float or array_like
        Dither frequencies, Hz (> 0).

    Returns
    -------
    ndarray of float, shape (k,)
        Sub-intervals per period, one per frequency.
    """
    radius = np.abs(np.linalg.eigvals(A0)).max()
    f = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    return np.maximum(1, np.ceil((1.0 / f) * (2 * radius + 2 * np.pi * f)
                                 / _MAX_PHASE))


class DysonPropagator:
    """Monodromy matrix as a function of ``p_f`` at one dither frequency.

    The series coefficients are computed once (for amplitudes up to
    ``p_max``); :meth:`monodromy` then evaluates any amplitudes in that
    range cheaply, which root finders on ``p_f`` use.

    Parameters
    ----------
    system : stability.model.PeriodicSystem
    freq_hz : float
        Dither frequency, Hz (> 0).
    p_max : float
        Largest amplitude that will be evaluated, Pa.
    """

    def __init__(self, system, freq_hz, p_max):
        A0, U, V = system.A0, system.U, system.V
        size = len(A0)
        omega, period = 2 * np.pi * freq_hz, 1.0 / freq_hz
        waveform = waveform_of(system)
        # the shape is smooth between its breakpoints: sub-intervals end
        # on them, so the spectral integration stays exact
        group = waveform.breakpoints
        peak = np.abs(waveform.values(np.linspace(0, 2 * np.pi, 257),
                                      freq_hz)).max()
        steps = int(least_subintervals(A0, freq_hz)[0])
        steps = group * math.ceil(steps / group)
        while True:
            if steps > MAX_SUBINTERVALS:
                raise JudderError(
                    f"freq = {freq_hz:g} Hz with p_f up to {p_max / 1e5:g} bar "
                    f"needs {steps} sub-intervals per period with method "
                    f"'dyson' (at most {MAX_SUBINTERVALS}); use a higher "
                    "frequency or method 'solve_ivp'")
            h = period / steps
            s = (_X + 1.0) * (h / 2)
            forward = scipy.linalg.expm(A0[None] * s[:, None, None])
            backward = scipy.linalg.expm(-A0[None] * s[:, None, None])
            left = backward @ U                          # (Q, m, r)
            right = np.einsum("ir,qij->qrj", V, forward)  # (Q, r, m)
            strength = (p_max * peak * h * np.linalg.norm(left, axis=(1, 2))
                        * np.linalg.norm(right, axis=(1, 2))).max()
            if strength <= _MAX_STRENGTH:
                break
            steps = group * math.ceil(steps * strength / _MAX_STRENGTH
                                      / group)

        weights = _INTEGRATION * (h / 2)
        # the end nodes take the shape's one-sided limits (a square wave
        # jumps there): evaluate a hair inside the sub-interval
        inside = s if group == 1 else np.clip(s, 1e-12 * h, (1 - 1e-12) * h)
        phase = waveform.values(
            omega * (h * np.arange(steps)[:, None] + inside[None, :]),
            freq_hz)
        Y = np.broadcast_to(np.eye(size), (steps, _NODES, size, size))
        coefficients = [np.broadcast_to(np.eye(size), (steps, size, size))]
        for _ in range(_series_degree(strength)):
            row = np.einsum("qri,jqik->jqrk", right, Y)   # V^T e^{A0 s} Y
            integrand = phase[:, :, None, None] * (left[None] @ row)
            Y = np.matmul(weights, integrand.reshape(steps, _NODES, -1))
            Y = Y.reshape(steps, _NODES, size, size)
            coefficients.append(Y[:, -1])
        self.p_max = p_max
        self._step = scipy.linalg.expm(A0 * h)
        self._coefficients = coefficients

    def monodromy(self, p_f):
        """Monodromy matrices ``X(T)``, shape (k, m, m), for ``p_f`` (Pa)."""
        p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
        steps, size = self._coefficients[0].shape[:2]
        sub = np.zeros((len(p_f), steps, size, size))
        for coefficient in reversed(self._coefficients):
            sub = sub * p_f[:, None, None, None] + coefficient[None]
        sub = self._step @ sub
        result = sub[:, 0]
        for j in range(1, steps):
            result = sub[:, j] @ result
        return result


def monodromy_dyson(system, freq_hz, p_f):
    """Monodromy matrices by the sub-interval Dyson series.

    Parameters
    ----------
    system : stability.model.PeriodicSystem
    freq_hz : float
        Dither frequency, Hz (> 0).
    p_f : array_like, shape (k,)
        Dither amplitudes, Pa.

    Returns
    -------
    ndarray, shape (k, m, m)
        ``X(T)`` for each amplitude, ``T = 1/freq_hz``.
    """
    p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
    return DysonPropagator(system, freq_hz,
                           np.abs(p_f).max()).monodromy(p_f)


def monodromy_solve_ivp(system, freq_hz, p_f, rtol=1e-10, atol=1e-12):
    """Monodromy matrices by direct integration with ``solve_ivp``.

    Parameters
    ----------
    system : object with ``matrix(t, omega, p_f)``
        A :class:`~stability.model.PeriodicSystem`, or any object whose
        ``matrix`` gives the system matrix (for example the full Eq. (6)
        or the augmented Eq. (9), see :func:`stability.multipliers.system_of`).
    freq_hz : float
        Dither frequency, Hz.
    p_f : array_like, shape (k,)
        Dither amplitudes, Pa.
    rtol, atol : float
        Tolerances of DOP853.

    Returns
    -------
    ndarray, shape (k, m, m)
    """
    p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
    omega, period = 2 * np.pi * freq_hz, 1.0 / freq_hz
    size = system.matrix(0.0, omega, 0.0).shape[0]
    out = np.empty((len(p_f), size, size))
    for index, amplitude in enumerate(p_f):
        def rhs(t, y, amplitude=amplitude):
            return (system.matrix(t, omega, amplitude)
                    @ y.reshape(size, size)).ravel()
        sol = solve_ivp(rhs, (0.0, period), np.eye(size).ravel(),
                        method="DOP853", rtol=rtol, atol=atol)
        if not sol.success:
            raise JudderError(f"solve_ivp failed at f = {freq_hz} Hz, "
                               f"p_f = {amplitude} Pa: {sol.message}")
        out[index] = sol.y[:, -1].reshape(size, size)
    return out


class IntegratedPropagator:
    """Monodromy matrices by ``solve_ivp``, one integration per amplitude.

    The reference engine, with the interface of :class:`DysonPropagator`.

    Parameters
    ----------
    system : object with ``matrix(t, omega, p_f)``
    freq_hz : float
        Dither frequency, Hz.
    p_max : float, optional
        Unused (nothing is precomputed); kept for the common interface.
    """

    def __init__(self, system, freq_hz, p_max=None):
        self._system, self._freq_hz = system, freq_hz

    def monodromy(self, p_f):
        """``X(T)`` for each amplitude of ``p_f`` (Pa), shape (k, m, m)."""
        return monodromy_solve_ivp(self._system, self._freq_hz, p_f)


#: Monodromy engines by name: propagator classes.
METHODS = {"dyson": DysonPropagator, "solve_ivp": IntegratedPropagator}
#: The engine used when none is named.
DEFAULT_METHOD = "dyson"


def get_method(name):
    """The propagator class called ``name``; JudderError lists the options."""
    try:
        return METHODS[name]
    except (KeyError, TypeError):
        raise JudderError(f"method = {name!r} is unknown; allowed: "
                          f"{', '.join(METHODS)}") from None


def monodromy(system, freq_hz, p_f, method=DEFAULT_METHOD):
    """Monodromy matrices for a column of amplitudes by the named engine.

    Parameters
    ----------
    system : stability.model.PeriodicSystem
        (``'solve_ivp'`` also takes any object with ``matrix``.)
    freq_hz : float
        Dither frequency, Hz.
    p_f : array_like, shape (k,)
        Dither amplitudes, Pa.
    method : str
        A key of :data:`METHODS`.

    Returns
    -------
    ndarray, shape (k, m, m)
    """
    p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
    engine = get_method(method)
    return engine(system, freq_hz, np.abs(p_f).max()).monodromy(p_f)

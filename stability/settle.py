r"""The motion an engagement settles on where no periodic orbit attracts.

In a combination tongue (5, 6) the T-periodic orbit of the dithered
engagement (:mod:`stability.orbit`) loses stability through a complex
pair of multipliers: what grows out of it is a quasi-periodic motion, a
torus with the dither frequency ``f`` and a second frequency ``f_c``
(the combination's partner, ``f = f_2 - f_1`` or ``f_1 + f_2``), which no
harmonic balance of ``f`` gives. Its amplitude is found here the way a
bench finds it: the orbit's equations of motion,

.. math::
   M\ddot x + C\dot x + K x = -e\,\bigl(\tau(w_s + e^T\dot x, t)
   - \tau_s\bigr) + b\,\Delta\tau_m(b^T\dot x),

(the clutch torque of ``Judder.Components.CurveWetClutch`` and the part
of the bench motor's torque its limit cuts off, ``b`` its body:
:class:`stability.orbit.EngagementModel`) are integrated from the steady
slip with the dither on, by the classical fourth-order Runge-Kutta
method with :data:`STEPS_PER_PERIOD` steps per dither period, for all
settings of a batch at once (each in its own time). Unlike the orbit,
the slip's mean is free here, as on the bench.

Settled, stated: the largest dither-related component of the upstream
speed (at ``f``, at ``f/2``, and the largest spectral peak below ``f/2``,
where every combination response has a frequency: the components
:mod:`pysim.bench.verdict` reads off a run), over the last
:data:`WINDOW_S` of the run, differs from the same over the window before
by less than :data:`TOLERANCE` of it. A setting that has not settled after
``duration`` is integrated on, up to ``max_duration``, and reported with
``settled`` False if it still has not.
"""

from dataclasses import dataclass

import numpy as np

from infra.spectrum import hann_amplitude, hann_spectrum


__all__ = ["SettledMotion", "settle", "settle_orbits", "STEPS_PER_PERIOD",
           "WINDOW_S", "TOLERANCE"]

#: Runge-Kutta steps per dither period: the stiffest rate of the bench
#: (its speed control, d_control / J1 = 1786 1/s) times the step stays
#: below 0.7 from 60 Hz up, and the phase error of the 103 Hz mode below
#: 1e-5 rad a step.
STEPS_PER_PERIOD = 32
#: Length of the windows the settled components are read over, s.
WINDOW_S = 0.5
#: Largest relative change of the largest component between the last two
#: windows of a settled motion.
TOLERANCE = 0.1
#: Lowest frequency of the "other" spectral peak, Hz: below it lies the
#: slow drift of the slip, not judder.
_LOWEST_PEAK_HZ = 2.0


@dataclass(frozen=True)
class SettledMotion:
    """Integrated motions of a batch of dither settings.

    Attributes
    ----------
    freq_hz, p_f : ndarray, shape (b,)
        Dither frequency (Hz) and amplitude (Pa).
    duration : ndarray, shape (b,)
        Time each setting was integrated over, s.
    at_dither, at_half, other : ndarray, shape (b,)
        Amplitudes of the upstream speed's components over the last
        window at ``f``, at ``f/2`` and at the largest peak below ``f/2``
        (``other_hz``), rad/s.
    other_hz : ndarray, shape (b,)
    settled : ndarray of bool, shape (b,)
        The largest component changed by less than :data:`TOLERANCE`
        between the last two windows.
    time : list of ndarray
        Each setting's sample times, s (every Runge-Kutta step).
    upstream : list of ndarray
        The upstream speed's deviation from the steady motion at those
        times, rad/s.
    """

    freq_hz: np.ndarray
    p_f: np.ndarray
    duration: np.ndarray
    at_dither: np.ndarray
    at_half: np.ndarray
    other: np.ndarray
    other_hz: np.ndarray
    settled: np.ndarray
    time: list
    upstream: list

    @property
    def amplitude(self):
        """The largest of the three components, rad/s."""
        return np.maximum(np.maximum(self.at_dither, self.at_half),
                          self.other)


class _Equations:
    """The right-hand side of the engagement's equations for a batch:
    :meth:`stability.orbit.EngagementModel.torque` (its friction
    :meth:`~stability.orbit.EngagementModel.friction_value`) and
    :meth:`~stability.orbit.EngagementModel.drive_excess` written out for
    speed (the integration calls it four times a step)."""

    def __init__(self, model, omega, p_f):
        self.model = model
        n = self.n = len(model.clutch)
        self.omega, self.p_f = omega, p_f
        minv = np.linalg.inv(model.mass)
        # d/dt (x, v) = (x, v) @ A^T + clutch and drive forces
        self.transposed = np.zeros((2 * n, 2 * n))
        self.transposed[n:, :n] = np.eye(n)
        self.transposed[:n, n:] = -(minv @ model.stiffness).T
        self.transposed[n:, n:] = -(minv @ model.damping).T
        self.e = np.concatenate([np.zeros(n), model.clutch.astype(float)])
        self.clutch = np.concatenate([np.zeros(n), -minv @ model.clutch])
        self.drive = (np.concatenate([np.zeros(n), minv[:, model.drive]])
                      if model.limited_drive else None)
        self.steady = model.steady_torque()
        m = model.mean_pressure_damping
        self.mean_load = m * model.p_m
        self.fixed = (1.0 - m) * model.mu0 * model.p_m

    def __call__(self, dither, state):
        """``dither``: ``p_f cos(omega t)`` of each setting, Pa."""
        model = self.model
        w = model.slip + state @ self.e
        mu = model.friction_value(w)
        tau = model.clutch_factor * np.tanh(w / model.w_small) * (
            mu * (self.mean_load + dither) + self.fixed)
        rate = state @ self.transposed
        rate += np.multiply.outer(tau - self.steady, self.clutch)
        if self.drive is not None:
            rate += np.multiply.outer(
                model.drive_excess(state[:, self.n + model.drive])[0],
                self.drive)
        return rate


def _components(time, speed, freq_hz, window):
    """The upstream speed's components at ``f``, ``f/2`` and the largest
    peak below ``f/2`` over the last ``window`` seconds (Hann window):
    amplitudes (rad/s) and the peak's frequency (Hz)."""
    late = time >= time[-1] - window
    t, y = time[late], speed[late]
    y = y - y.mean()
    bins, spectrum = hann_spectrum(y, t[1] - t[0])
    at_dither, at_half = hann_amplitude(t, y, [freq_hz, freq_hz / 2])
    resolution = bins[1]
    below = (bins >= _LOWEST_PEAK_HZ) & (bins < freq_hz / 2 - 2 * resolution)
    if not below.any():
        return at_dither, at_half, 0.0, np.nan
    k = np.flatnonzero(below)[np.argmax(spectrum[below])]
    # the peak between the bins (the Hann window's scalloping is up to
    # 15 % at a bin's edge)
    near = bins[k] + np.linspace(-1, 1, 41) * resolution
    amplitudes = hann_amplitude(t, y, near)
    best = int(np.argmax(amplitudes))
    return at_dither, at_half, float(amplitudes[best]), float(near[best])


def settle(model, freq_hz, p_f, duration=4.0, max_duration=8.0,
           steps_per_period=STEPS_PER_PERIOD, window=WINDOW_S,
           tolerance=TOLERANCE):
    """Integrate the dithered engagement at each setting until its
    motion settles (module docstring).

    Parameters
    ----------
    model : stability.orbit.EngagementModel
    freq_hz, p_f : array_like, shape (b,)
        Dither frequencies (Hz) and amplitudes (Pa), paired.
    duration : float
        Time integrated before the first test, s (the bench's run is 4 s).
    max_duration : float
        Longest time integrated, s.
    steps_per_period : int
    window : float
        Length of each of the two windows compared, s.
    tolerance : float
        Largest relative change of a settled motion's largest component.

    Returns
    -------
    SettledMotion
    """
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    p_f = np.atleast_1d(np.asarray(p_f, dtype=float))
    omega = 2 * np.pi * freq_hz
    equations = _Equations(model, omega, p_f)
    step = 1.0 / (freq_hz * steps_per_period)
    count = len(freq_hz)
    state = np.zeros((count, 2 * equations.n))
    t = np.zeros(count)
    samples, stepped = [np.zeros(count)], [np.ones(count, dtype=bool)]
    active = np.ones(count, dtype=bool)
    results = [None] * count
    target = duration
    while active.any():
        steps = int(np.ceil((target - t[active].min()) / step[active].min()))
        h = np.where(active, step, 0.0)[:, None]
        for _ in range(max(steps, 1)):
            start = p_f * np.cos(omega * t)
            middle = p_f * np.cos(omega * (t + h[:, 0] / 2))
            end = p_f * np.cos(omega * (t + h[:, 0]))
            k1 = equations(start, state)
            k2 = equations(middle, state + h / 2 * k1)
            k3 = equations(middle, state + h / 2 * k2)
            k4 = equations(end, state + h * k3)
            state = state + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t = t + h[:, 0]
            samples.append(state[:, equations.n + model.upstream].copy())
            stepped.append(h[:, 0] > 0)
            # a setting stops once it passes the target
            done = active & (t >= target - 1e-12)
            h[done] = 0.0
        trace, taken = np.array(samples), np.array(stepped)
        for i in np.flatnonzero(active):
            speed = trace[taken[:, i], i]
            time = np.arange(len(speed)) * step[i]
            last = _components(time, speed, freq_hz[i], window)
            before = _components(time[time <= time[-1] - window],
                                 speed[time <= time[-1] - window],
                                 freq_hz[i], window)
            largest, previous = max(last[:3]), max(before[:3])
            settled = abs(largest - previous) <= tolerance * max(largest,
                                                                 1e-12)
            if settled or target >= max_duration:
                results[i] = (time[-1], *last, settled, time, speed)
                active[i] = False
        target = min(target + 2 * window, max_duration)
    columns = list(zip(*results))
    return SettledMotion(
        freq_hz=freq_hz, p_f=p_f, duration=np.array(columns[0]),
        at_dither=np.array(columns[1]), at_half=np.array(columns[2]),
        other=np.array(columns[3]), other_hz=np.array(columns[4]),
        settled=np.array(columns[5], dtype=bool), time=list(columns[6]),
        upstream=list(columns[7]))


def settle_orbits(model, orbits, duration=4.0):
    """The settled motion of each of ``orbits``
    (:class:`stability.orbit.Orbit`) unstable through a complex pair, all
    in one batch of :func:`settle`; None for the others.

    Returns
    -------
    list of (dict or None)
        ``combination`` (the component at the combination frequency,
        rad/s), ``combination_hz``, ``at_dither`` (rad/s), ``duration``
        (s) and ``settled``.
    """
    quasi = [k for k, o in enumerate(orbits)
             if o.success and o.kind == "combination"]
    motions = [None] * len(orbits)
    if quasi:
        motion = settle(model, [orbits[k].freq_hz for k in quasi],
                        [orbits[k].p_f for k in quasi], duration=duration)
        for position, k in enumerate(quasi):
            motions[k] = {"combination": float(motion.other[position]),
                          "combination_hz": float(motion.other_hz[position]),
                          "at_dither": float(motion.at_dither[position]),
                          "duration": float(motion.duration[position]),
                          "settled": bool(motion.settled[position])}
    return motions

"""The predicted judder chart: the periodic orbit over a dither grid.

For each dither frequency the T-periodic orbit of the engagement
(:mod:`stability.orbit`) is continued in ``p_f`` over the grid; where it
loses stability through -1, the 2T orbit that grows out of it is
computed. Each point then gets the verdict a bench engineer reads off an
engagement (:mod:`pysim.bench.verdict`) and its mechanism:

* judder: the settled oscillation of the upstream speed at ``f`` or
  ``f/2`` exceeds the NVH limit, or the T-orbit is unstable and grows at
  ``min_growth`` or faster (the engagement leaves it that fast);
* forced: the T-orbit's oscillation at ``f`` exceeds the limit (the
  dither drives it: the forced response, made nonlinear by the friction
  curve);
* parametric: the T-orbit grows at ``min_growth`` or faster, or the 2T
  orbit's oscillation at ``f/2`` exceeds the limit;
* both, where both hold.

Where the T-orbit loses stability through a complex pair (a combination
tongue), the motion is quasi-periodic and no periodic orbit gives its
amplitude: the point is marked (:attr:`OrbitChart.quasi_periodic`), the
motion integrated until it settles (:mod:`stability.settle`), and its
component at the combination frequency is the settled amplitude, judged
with the T-orbit's growth.
"""

from dataclasses import dataclass

import numpy as np

from infra.criteria import MECHANISMS, mechanism_code

from .orbit import (DEFAULT_HARMONICS, continue_orbit, double_period_orbit,
                    drifted_orbit, periodic_orbit)

__all__ = ["OrbitChart", "orbit_chart", "OrbitVerdict", "orbit_verdict",
           "held_slip_motion", "forced_limit_amplitude",
           "forced_limit_frequencies", "held_slip_forced_amplitude"]


def held_slip_motion(model, orbit, harmonics=DEFAULT_HARMONICS):
    """The motion a held-slip run shows at the end: the T-orbit ``orbit``
    carried along the slip's drift (:func:`stability.orbit.drifted_orbit`)
    and the 2T orbit grown out of it where it doubles (None)."""
    orbit, at = drifted_orbit(model, orbit, harmonics=harmonics)
    doubled = (double_period_orbit(at, orbit, harmonics=harmonics)
               if orbit.success and orbit.kind == "double-period" else None)
    return orbit, doubled


def forced_limit_amplitude(model, freq_hz, p_f, forced, limit, p_max,
                           tolerance=0.001, steps=8):
    """The dither amplitude (Pa) at which the held slip's forced
    oscillation at ``freq_hz`` reaches ``limit`` (rad/s), from the
    setting ``p_f`` whose forced oscillation is ``forced`` (rad/s).

    The secant method on the drifted T-orbit's amplitude
    (:func:`held_slip_motion`), which grows nearly in proportion to the
    dither amplitude, to ``tolerance`` times the limit.

    Returns
    -------
    float
        Pa; ``inf`` where the oscillation stays below the limit up to
        ``p_max`` (Pa), NaN where the orbit is lost on the way (the
        harmonic balance does not converge).
    """
    def excess(p):
        orbit = held_slip_motion(model, periodic_orbit(model, freq_hz,
                                                       p))[0]
        return orbit.dither_amplitude - limit if orbit.success else np.nan
    points = [(0.0, -limit), (float(p_f), forced - limit)]
    for _ in range(steps):
        (p0, e0), (p1, e1) = points[-2:]
        if abs(e1) <= tolerance * limit:
            return p1
        guess = p1 - e1 * (p1 - p0) / (e1 - e0) if e1 != e0 else p_max
        if guess >= p_max:
            at_top = excess(p_max)
            if not at_top >= 0:        # below the limit, or lost (NaN)
                return np.inf if at_top < 0 else np.nan
            guess = p_max
        value = excess(max(guess, 0.0))
        if np.isnan(value):
            return np.nan
        points.append((max(guess, 0.0), value))
    return points[-1][0]


def held_slip_forced_amplitude(model, p_f, harmonics=DEFAULT_HARMONICS):
    """``amplitude(freq_hz)``: the held slip's forced oscillation at the
    dither frequency at the dither amplitude ``p_f`` (Pa), rad/s (the
    drifted T-orbit's, :func:`held_slip_motion`; NaN where the harmonic
    balance does not converge), for :func:`forced_limit_frequencies`."""
    def amplitude(freq_hz):
        orbit = held_slip_motion(model, periodic_orbit(
            model, freq_hz, p_f, harmonics=harmonics), harmonics)[0]
        return orbit.dither_amplitude if orbit.success else np.nan
    return amplitude


def forced_limit_frequencies(amplitude, freq_hz, limit, low, high,
                             step=0.005, widest=6, xtol=1e-3):
    """The nearest frequencies below and above ``freq_hz`` at which the
    forced oscillation at one dither amplitude reaches ``limit``.

    Walks from ``freq_hz`` outwards to ``low`` and to ``high`` (Hz) in
    relative steps between a tenth of ``step`` and ``widest`` times it,
    then refines the first step that crosses the limit by Brent's method.
    Where the amplitude rises, it is read as a resonance's ``C /
    detuning`` (the last two amplitudes give the detuning), and a step
    goes half of the way to where that reaches the limit; where it falls,
    the step is ``step`` times the ratio of the limit to the amplitude. A
    peak that stays above the limit over less than a tenth of ``step``
    can be stepped over; the bench's are far wider (at 105 Hz and 0.3
    bar the forced oscillation goes from 17.5 to 45 rpm over 5 %).

    Parameters
    ----------
    amplitude : callable
        ``amplitude(freq_hz)``, rad/s, NaN where it is not known
        (:func:`held_slip_forced_amplitude`, or a linear response).
    freq_hz : float
        The setting, Hz, with ``amplitude(freq_hz) <= limit``.
    limit : float
        rad/s.
    low, high : float
        Hz, ``low <= freq_hz <= high``: how far each side is searched.
    xtol : float
        Absolute tolerance of the crossings, Hz.

    Returns
    -------
    list of (float, str)
        Below and above: ``(frequency, reason)``, reason ``'forced'``
        (the limit reached there), ``'end'`` (not up to ``low`` or
        ``high``, returned) or ``'unknown'`` (the amplitude was lost at
        the frequency returned, the last one below the limit before it).
    """
    from scipy.optimize import brentq

    def excess(f):
        return amplitude(f) - limit
    start = amplitude(freq_hz)
    if not start <= limit:
        reason = "unknown" if np.isnan(start) else "forced"
        return [(float(freq_hz), reason)] * 2
    out = []
    for end in (low, high):
        previous, f, value = freq_hz, freq_hz, start - limit
        distance = None     # to the pole the last rise points at, log Hz
        found = (end, "end")
        while f != end:
            now = max(value + limit, 1e-12 * limit)
            if distance is not None:
                wide = 0.5 * distance * (1.0 - now / limit)
            else:
                wide = step * limit / now
            grow = np.exp(min(max(wide, step / 10), widest * step))
            f = min(f * grow, end) if end > freq_hz else max(f / grow, end)
            value = excess(f)
            if not np.isnan(value) and value + limit > now:
                # a rise from a to b over d (log Hz), read as a pole's
                # C / distance: distance = d a / (b - a)
                distance = np.log(grow) * now / (value + limit - now)
            else:
                distance = None
            if np.isnan(value):
                found = (previous, "unknown")
                break
            if value >= 0:
                found = (brentq(lambda x: np.nan_to_num(excess(x), nan=1.0),
                                min(previous, f), max(previous, f),
                                xtol=xtol), "forced")
                break
            previous = f
        out.append((float(found[0]), found[1]))
    return out


@dataclass(frozen=True)
class OrbitVerdict:
    """What the bench sees at one setting, from its orbits.

    Attributes
    ----------
    forced : float
        The T-orbit's upstream speed at ``f``, rad/s.
    half : float
        The 2T orbit's at ``f/2``, rad/s (0 without one).
    settled : float
        The larger of the settled motion's components at ``f`` and ``f/2``
        (the 2T orbit where one exists) and, in a combination tongue, at
        the combination frequency (the integrated motion,
        :mod:`stability.settle`), rad/s.
    growth_rate : float
        Of the T-orbit, 1/s.
    quasi_periodic : bool
        The T-orbit is unstable through a complex pair: no periodic orbit
        settles; ``settled`` is the integrated motion's where it was
        given, else the unstable T-orbit's.
    judder : bool
    mechanism : int
        Index into :data:`infra.criteria.MECHANISMS`.
    """

    forced: float
    half: float
    settled: float
    growth_rate: float
    quasi_periodic: bool
    judder: bool
    mechanism: int


def orbit_verdict(orbit, doubled, limit, min_growth, combination=0.0):
    """The verdict of one setting from its T-orbit ``orbit`` and the 2T
    orbit ``doubled`` grown out of it (None), as a bench engineer reads
    an engagement (module docstring): judder where the settled
    oscillation exceeds ``limit`` (rad/s) or the T-orbit grows at
    ``min_growth`` (1/s) or faster. ``combination``: in a combination
    tongue, the settled motion's component at the combination frequency
    (:attr:`stability.settle.SettledMotion.other`), rad/s; the dither
    cannot force it, so above the limit it is parametric judder."""
    forced = orbit.dither_amplitude
    half = 0.0 if doubled is None else abs(doubled.upstream_harmonics[0])
    settled = forced if doubled is None else max(
        half, abs(doubled.upstream_harmonics[1]))
    settled = max(settled, combination)
    is_forced = forced > limit
    parametric = orbit.growth_rate >= min_growth or half > limit or \
        combination > limit or (settled > limit and not is_forced)
    judder = settled > limit or parametric
    mechanism = mechanism_code(is_forced, parametric)
    return OrbitVerdict(forced=float(forced), half=float(half),
                        settled=float(settled),
                        growth_rate=float(orbit.growth_rate),
                        quasi_periodic=orbit.kind == "combination",
                        judder=bool(judder), mechanism=int(mechanism))

@dataclass(frozen=True)
class OrbitChart:
    """Periodic orbits and verdicts over a dither grid.

    Attributes
    ----------
    freq_hz : ndarray, shape (nf,)
    p_f : ndarray, shape (np,)
        Dither amplitudes, Pa.
    forced_amplitude : ndarray, shape (nf, np)
        Upstream speed of the T-orbit at ``f``, rad/s (NaN where the
        balance did not converge).
    half_amplitude : ndarray, shape (nf, np)
        Upstream speed of the 2T orbit at ``f/2``, rad/s (0 where there is
        none).
    settled_amplitude : ndarray, shape (nf, np)
        The larger of the settled orbit's components at ``f`` and
        ``f/2`` (the 2T orbit where one exists), rad/s.
    growth_rate : ndarray, shape (nf, np)
        Of the T-orbit, 1/s.
    kind : ndarray of str, shape (nf, np)
        How the T-orbit loses stability (:data:`stability.kinds.KINDS`).
    quasi_periodic : ndarray of bool, shape (nf, np)
        Unstable through a complex pair: no periodic orbit settles.
    drift_torque : ndarray, shape (nf, np)
        Mean torque the dither rectifies on the T-orbit, N m.
    judder : ndarray of bool, shape (nf, np)
        False where the balance did not converge (no verdict there: see
        ``converged``).
    mechanism : ndarray of int8, shape (nf, np)
        Index into :data:`infra.criteria.MECHANISMS`.
    converged : ndarray of bool, shape (nf, np)
        The harmonic balance converged: only there are ``kind``,
        ``judder`` and ``mechanism`` a verdict (elsewhere ``kind`` is
        ``''``).
    limit : float
        NVH limit, rad/s.
    min_growth : float
        1/s.
    """

    freq_hz: np.ndarray
    p_f: np.ndarray
    forced_amplitude: np.ndarray
    half_amplitude: np.ndarray
    settled_amplitude: np.ndarray
    growth_rate: np.ndarray
    kind: np.ndarray
    quasi_periodic: np.ndarray
    drift_torque: np.ndarray
    judder: np.ndarray
    mechanism: np.ndarray
    limit: float
    min_growth: float
    converged: np.ndarray = None

    def _converged(self):
        return (np.ones(self.judder.shape, dtype=bool)
                if self.converged is None else self.converged)

    def counts(self):
        """Converged points per mechanism, ``{name: count}`` (``none``:
        no judder); the others are :meth:`not_converged`, no verdict."""
        converged = self._converged()
        return {name: int(np.count_nonzero(converged
                                           & (self.mechanism == code)))
                for code, name in enumerate(MECHANISMS)}

    def not_converged(self):
        """Points where the balance did not converge: no verdict."""
        return int(np.count_nonzero(~self._converged()))

    def onsets(self):
        """Per frequency the lowest amplitude of the grid with judder, Pa
        (NaN where none): the predicted experimental boundary."""
        out = np.full(len(self.freq_hz), np.nan)
        for i, row in enumerate(self.judder):
            if row.any():
                out[i] = self.p_f[np.argmax(row)]
        return out


def settled_combinations(model, found, duration=4.0):
    """The combination component of the settled motion
    (:func:`stability.settle.settle_orbits`, one batch) at each grid
    point ``(i, j)`` of ``found`` (``{(i, j): (T-orbit, 2T orbit)}``)
    whose T-orbit is unstable through a complex pair, rad/s; ``duration``
    None: none integrated."""
    if duration is None:
        return {}
    from .settle import settle_orbits
    keys = list(found)
    motions = settle_orbits(model, [found[key][0] for key in keys],
                            duration=duration)
    return {key: motion["combination"]
            for key, motion in zip(keys, motions) if motion is not None}


def orbit_chart(model, freq_hz, p_f, limit, min_growth,
                harmonics=DEFAULT_HARMONICS, callback=None,
                settle_duration=4.0):
    """Periodic orbits and verdicts over a dither grid.

    Parameters
    ----------
    model : stability.orbit.EngagementModel
    freq_hz : array_like, shape (nf,)
        Dither frequencies, Hz.
    p_f : array_like, shape (np,)
        Dither amplitudes, Pa, increasing.
    limit : float
        NVH limit of the upstream speed's oscillation, rad/s.
    min_growth : float
        Growth rate from which an instability is judder, 1/s.
    callback : callable, optional
        ``callback(done, total)`` after each frequency.
    settle_duration : float or None
        Time the points of combination tongues are integrated over before
        their settled amplitude is read (:mod:`stability.settle`), s;
        None: judged by the unstable T-orbit's amplitude and growth.

    Returns
    -------
    OrbitChart
    """
    freq_hz = np.asarray(freq_hz, dtype=float)
    p_f = np.asarray(p_f, dtype=float)
    shape = (len(freq_hz), len(p_f))
    forced = np.full(shape, np.nan)
    half = np.zeros(shape)
    settled = np.full(shape, np.nan)
    growth = np.full(shape, np.nan)
    kind = np.full(shape, "stable", dtype=object)
    drift = np.full(shape, np.nan)
    amplitudes = np.concatenate([[0.0], p_f]) if p_f[0] > 0 else p_f
    offset = len(amplitudes) - len(p_f)
    judder = np.zeros(shape, dtype=bool)
    mechanism = np.zeros(shape, dtype=np.int8)
    found = {}
    for i, f in enumerate(freq_hz):
        branch = continue_orbit(model, f, amplitudes, harmonics=harmonics)
        on_grid = [o for k, o in enumerate(branch.orbits)
                   if k not in branch.folds]
        for j, orbit in enumerate(on_grid[offset:]):
            if orbit.success:
                found[i, j] = held_slip_motion(model, orbit, harmonics)
        if callback is not None:
            callback(i + 1, len(freq_hz))
    combination = settled_combinations(model, found, settle_duration)
    for (i, j), (orbit, doubled) in found.items():
        verdict = orbit_verdict(orbit, doubled, limit, min_growth,
                                combination.get((i, j), 0.0))
        forced[i, j] = verdict.forced
        half[i, j] = verdict.half
        settled[i, j] = verdict.settled
        growth[i, j] = orbit.growth_rate
        kind[i, j] = orbit.kind
        drift[i, j] = orbit.drift_torque
        judder[i, j] = verdict.judder
        mechanism[i, j] = verdict.mechanism
    quasi = kind == "combination"
    converged = np.zeros(shape, dtype=bool)
    for key in found:
        converged[key] = True
    kind[~converged] = ""
    return OrbitChart(freq_hz=freq_hz, p_f=p_f, forced_amplitude=forced,
                      half_amplitude=half, settled_amplitude=settled,
                      growth_rate=growth, kind=kind.astype(str),
                      quasi_periodic=quasi, drift_torque=drift,
                      judder=judder, mechanism=mechanism,
                      limit=float(limit), min_growth=float(min_growth),
                      converged=converged)

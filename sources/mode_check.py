"""Where a hybrid class leaves its mode within a dither period, for many
dither settings at once.

The equations of a class fixed in one mode (:func:`sources.modes.fixed_mode`)
are integrated over one dither period from the start values, for each
setting (a parameter vector with its dither frequency and amplitude);
the discrete variables' equations (:func:`sources.modes.mode_values`)
are then evaluated at :data:`SAMPLES` times of the period and just past
each zero crossing of the relations in them
(:func:`sources.modes.mode_indicators`). The settings are integrated
together, in time normalised by each one's period (``s = f t`` in
``[0, 1]``), so that one call of the compiled equations serves them all:
a call costs about 0.1 ms, nearly all of it CasADi's and numpy's
overhead, whichever the number of settings.
"""

import casadi
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .modes import arguments, mode_indicators, mode_values

__all__ = ["SAMPLES", "BATCH", "first_changes"]

#: Samples per dither period at which the mode is checked, besides just
#: after each zero crossing of its relations.
SAMPLES = 64
#: Settings integrated together: sorted by frequency, so that their
#: steps are alike (a batch takes the steps its most demanding setting
#: needs).
BATCH = 32
#: Tolerances of one setting's integration (scipy's ``solve_ivp``, RK45).
RTOL, ATOL = 1e-9, 1e-12
#: Fraction of the period past a crossing at which the mode is read (on
#: the crossing's other side).
AFTER = 1e-9


class _Batch:
    """Settings (columns of ``P``, frequencies ``f``) of one integration:
    the state ``y`` holds their states one after the other."""

    def __init__(self, ode, derivatives, P, f):
        self.P, self.f, self.size = P, f, len(f)
        self.states = len(ode.states)
        symbols = arguments(ode)
        self.rhs = casadi.Function("ode", symbols,
                                   [derivatives]).map(self.size)
        self.values = mode_values(ode)
        self.indicators = mode_indicators(ode)
        self.start = casadi.Function("start", symbols[2:], [
            casadi.vertcat(casadi.SX(0, 1),
                           *[s.start for s in ode.states])]).map(self.size)

    def columns(self, y):
        return y.reshape(self.size, self.states).T

    def derivative(self, s, y):
        """``dy/ds``: each setting's ``der(x) / f`` at ``t = s / f``."""
        out = np.asarray(self.rhs(s / self.f, self.columns(y), self.P))
        return (out / self.f).T.ravel()

    def y0(self):
        return np.asarray(self.start(self.P)).T.ravel()



def _at(batch, members, s, states):
    """``(nx, len(s))``: the state of setting ``members[j]`` at ``s[j]``
    from the batch's ``states`` (``(ny, len(s))``)."""
    stacked = states.reshape(batch.size, batch.states, len(s))
    return stacked[members, :, np.arange(len(s))].T


def _evaluate(batch, function, members, s, states):
    """``function(t, x, p)`` of setting ``members[j]`` at ``s[j]``, one
    column each, in one call."""
    return np.asarray(function.map(len(s))(
        s / batch.f[members], _at(batch, members, s, states),
        batch.P[:, members]))


def _crossings(batch, path):
    """``(member, s)`` of each zero crossing of a relation between two
    steps of ``path`` (scipy's events: a sign change, zero counting as
    either sign), located on the dense output by Brent's method."""
    steps = len(path.t)
    members = np.tile(np.arange(batch.size), steps)
    s = np.repeat(path.t, batch.size)
    values = _evaluate(batch, batch.indicators, members, s,
                       np.repeat(path.y, batch.size, axis=1))
    values = values.reshape(-1, steps, batch.size)   # relation, step, member
    before, after = values[:, :-1], values[:, 1:]
    crossed = ((before <= 0) & (after >= 0)) | ((before >= 0) & (after <= 0))
    found = []
    for k, step, member in zip(*np.nonzero(crossed)):
        def value(point, k=k, member=member):
            return _evaluate(batch, batch.indicators, np.array([member]),
                             np.array([point]), path.sol(point)[:, None])[k, 0]
        found.append((member, brentq(value, path.t[step], path.t[step + 1],
                                     xtol=4 * np.finfo(float).eps,
                                     rtol=4 * np.finfo(float).eps)))
    return found


def _first_change(batch, path, mode, rank):
    """``(member, s, values)`` of the setting first by ``rank`` whose
    mode's values differ from ``mode`` at a sample or just past a
    crossing, the earliest such time of it; None if none does."""
    times = [[k / SAMPLES for k in range(1, SAMPLES + 1)]
             for _ in range(batch.size)]
    for member, s in _crossings(batch, path):
        times[member].append(min(s + AFTER, 1.0))
    members = np.concatenate([np.full(len(t), m)
                              for m, t in enumerate(times)])
    s = np.concatenate([np.asarray(t) for t in times])
    now = _evaluate(batch, batch.values, members, s, path.sol(s)).T
    changed = np.flatnonzero(np.any(now != np.asarray(mode), axis=1))
    if not len(changed):
        return None
    first = min(changed, key=lambda i: (rank[members[i]], s[i]))
    return int(members[first]), float(s[first]), tuple(now[first])


def first_changes(ode, derivatives, mode, vectors, frequencies):
    """The first dither setting whose mode changes within its period.

    Parameters
    ----------
    ode : fmu.backend.Ode
        The class in one mode (:func:`sources.modes.fixed_mode` compiled).
    derivatives : casadi.SX
        ``der(x)`` of ``ode`` as a formula in ``t, x, p`` (its relations
        evaluated as it goes).
    mode : tuple of float
        The mode's values of the discrete variables.
    vectors : numpy.ndarray
        One parameter vector per setting (rows), dither included.
    frequencies : numpy.ndarray
        The dither frequency of each setting, Hz.

    Returns
    -------
    None or (int, float, tuple, str)
        The setting's index, the time (s) and the values there, or the
        solver's message (time NaN) where its equations could not be
        integrated; the setting first in ``vectors``' order.
    """
    vectors = np.atleast_2d(np.asarray(vectors, dtype=float))
    frequencies = np.asarray(frequencies, dtype=float)
    order = np.argsort(frequencies, kind="stable")
    found = []
    for start in range(0, len(order), BATCH):
        members = order[start:start + BATCH]
        batch = _Batch(ode, derivatives, vectors[members].T,
                       frequencies[members])
        scale = 1.0 / np.sqrt(len(members))   # scipy's norm is a mean
        path = solve_ivp(batch.derivative, (0.0, 1.0), batch.y0(),
                         dense_output=True, rtol=RTOL * scale,
                         atol=ATOL * scale)
        if not path.success:
            found.append((int(members.min()), np.nan, (), path.message))
            continue
        change = _first_change(batch, path, mode, members)
        if change is not None:
            member, s, values = change
            found.append((int(members[member]), s / frequencies[
                members[member]], values, ""))
    return min(found, default=None)

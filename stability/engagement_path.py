"""An engagement's path through the stability map: the quasi-static
Floquet exponent along a slip that changes.

The paper's judder happens during engagements, whose slip falls from the
engine's speed to zero (Fig. 1, 7). The stability model (Eq. 6-13) is
the engagement linearised at one slip: ``mu0`` and ``mu_g`` are the
friction characteristic's value and slope there. Where the slip changes
slowly against the dither period and against the time a disturbance
needs to grow (quasi-static), the disturbance's amplitude follows the
local Floquet exponent ``sigma(w)`` (the growth rate of Eq. 13 at the
slip ``w``):

.. math:: A(t) = A(t_0) \\exp \\int_{t_0}^{t} \\sigma(w(s))\\, ds

:func:`engagement_path` evaluates ``sigma`` on a grid of slips spanning
the run, interpolates it along the run's mean slip and integrates it:
the accumulated growth, the predicted amplitude gain and the spans in
which the engagement is inside a tongue (growing faster than a rate).
"""

from dataclasses import dataclass

import numpy as np

from .multipliers import floquet

__all__ = ["EngagementPath", "engagement_path", "mean_slip"]

#: Finest spacing of the slips the exponent is computed at, rad/s: well
#: inside the bounded curve's linear range (+-1.1 rad/s at the paper's
#: slope), so a tongue's edge is not stepped over.
GRID_STEP_RAD_S = 0.25


@dataclass(frozen=True)
class EngagementPath:
    """The quasi-static Floquet view of one engagement.

    Attributes
    ----------
    time : ndarray
        s, from the start of the path.
    slip : ndarray
        The mean slip at those times, rad/s.
    growth_per_s : ndarray
        The Floquet exponent (growth rate, Eq. 13) of the linearisation
        at that slip, 1/s.
    kind : ndarray of str
        Its kind (single-period, double-period, combination, stable).
    accumulated : ndarray
        ``int sigma dt`` from the first time, 1 (e-folds).
    """

    time: np.ndarray
    slip: np.ndarray
    growth_per_s: np.ndarray
    kind: np.ndarray
    accumulated: np.ndarray

    def gain(self, start=None, stop=None):
        """Predicted amplitude gain ``A(stop)/A(start)`` (the whole path
        by default): ``exp`` of the accumulated growth between them."""
        at = np.interp([self.time[0] if start is None else start,
                        self.time[-1] if stop is None else stop],
                       self.time, self.accumulated)
        return float(np.exp(at[1] - at[0]))

    def spans(self, min_growth, gap_s=0.05):
        """The intervals in which the exponent exceeds ``min_growth``
        (1/s), those closer than ``gap_s`` joined: ``[(t_start, t_stop,
        slip_start, slip_stop, kind, e-folds)]``, the kind the one at the
        interval's largest exponent."""
        above = self.growth_per_s > min_growth
        # a dip shorter than gap_s (the mean slip's ripple at a tongue's
        # edge) does not end a span
        below = np.flatnonzero(~above)
        if len(below):
            runs = np.split(below, np.flatnonzero(np.diff(below) > 1) + 1)
            for run in runs:
                inside = run[0] > 0 and run[-1] < len(above) - 1
                if inside and (self.time[run[-1] + 1]
                               - self.time[run[0] - 1]) < gap_s:
                    above[run] = True
        edges = np.flatnonzero(np.diff(above.astype(int)))
        starts = ([0] if above[0] else []) + [e + 1 for e in edges
                                              if not above[e]]
        stops = [e for e in edges if above[e]] + (
            [len(above) - 1] if above[-1] else [])
        found = []
        for first, last in zip(starts, stops):
            peak = first + int(np.argmax(self.growth_per_s[first:last + 1]))
            found.append((float(self.time[first]), float(self.time[last]),
                          float(self.slip[first]), float(self.slip[last]),
                          str(self.kind[peak]),
                          float(self.accumulated[last]
                                - self.accumulated[first])))
        return found

    def as_dict(self):
        return {"time_s": self.time.tolist(), "slip_rad_s": self.slip.tolist(),
                "growth_per_s": self.growth_per_s.tolist(),
                "kind": self.kind.tolist(),
                "accumulated_efolds": self.accumulated.tolist()}


def mean_slip(time, slip, freq_hz):
    """The slip averaged over one dither period about each sample (the
    path's slow motion, without the dither's forced swing), rad/s."""
    time = np.asarray(time, dtype=float)
    slip = np.asarray(slip, dtype=float)
    dt = float(np.median(np.diff(time)))
    width = max(int(round(1.0 / (freq_hz * dt))), 1)
    kernel = np.ones(width) / width
    padded = np.pad(slip, (width // 2, width - 1 - width // 2), mode="edge")
    return np.convolve(padded, kernel, mode="valid")


def engagement_path(linearisation_at, freq_hz, p_f, time, slip,
                    grid_points=48, method=None):
    """The quasi-static Floquet exponent along a slip history.

    Parameters
    ----------
    linearisation_at : callable
        ``slip -> stability.model.Driveline``: the engagement linearised
        at a steady slip (rad/s), ``mu0`` and ``mu_g`` its friction
        characteristic's value and slope there.
    freq_hz, p_f : float
        Dither frequency (Hz) and amplitude (Pa).
    time, slip : array_like, shape (n,)
        The run's times (s) and mean slip (rad/s; :func:`mean_slip`).
    grid_points : int
        At most this many slips at which the exponent is computed, spread
        over the range the run covers (one every
        :data:`GRID_STEP_RAD_S` where fewer suffice); interpolated
        linearly between them.
    method : str, optional
        Monodromy engine (:func:`stability.multipliers.floquet`).

    Returns
    -------
    EngagementPath
    """
    time = np.asarray(time, dtype=float)
    slip = np.asarray(slip, dtype=float)
    low, high = float(slip.min()), float(slip.max())
    # a grid slip every GRID_STEP_RAD_S at the finest, at most
    # grid_points: a held slip needs two, not 48
    count = int(np.clip(np.ceil((high - low) / GRID_STEP_RAD_S) + 1, 2,
                        grid_points))
    grid = (np.array([low]) if high - low < 1e-9 else
            np.linspace(low, high, count))
    results = [floquet(linearisation_at(w), freq_hz, p_f, method=method)
               for w in grid]
    rates = np.array([r.growth_rate for r in results])
    kinds = np.array([r.kind for r in results])
    growth = (np.full(len(slip), rates[0]) if len(grid) == 1 else
              np.interp(slip, grid, rates))
    # the kind of the bracketing grid slip with the larger exponent: the
    # motion that grows fastest there
    right = np.clip(np.searchsorted(grid, slip), 1, len(grid) - 1) \
        if len(grid) > 1 else np.zeros(len(slip), dtype=int)
    left = np.maximum(right - 1, 0)
    nearest = np.where(rates[left] >= rates[right], left, right)
    accumulated = np.concatenate([[0.0], np.cumsum(
        0.5 * (growth[1:] + growth[:-1]) * np.diff(time))])
    return EngagementPath(time=time, slip=slip, growth_per_s=growth,
                          kind=kinds[nearest], accumulated=accumulated)

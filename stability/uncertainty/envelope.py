r"""The broadest unstable region over uncertain parameters (section 4.2).

The paper takes as the predicted unstable region "the broadest region
obtained by considering all the variation ranges of parameters due to
uncertainties in their estimation". Here each uncertain parameter is an
interval or a distribution (:mod:`stability.uncertainty.ranges`). Every
sampled parameter set gets its exact tongue boundaries
(:func:`stability.tongues.tongue_boundaries`, Hill's method and the
monodromy, without the monodromy check of each boundary point); at a
dither frequency ``f`` its unstable region is the amplitudes from its
lowest boundary :math:`b_s(f)` (any kind, growth rate ``min_growth``) up
to ``p_max``. Then

* the broadest region is the union :math:`p_f \ge \min_s b_s(f)`;
* the probability of instability at :math:`(f, p_f)` is the share of the
  random samples with :math:`b_s(f) \le p_f`.

The samples are the vertices of the box of ranges (every parameter at an
end of its range, where a monotonic dependence puts the extremes) and a
space-filling sample of the box (scrambled Sobol or Latin hypercube,
:mod:`scipy.stats.qmc`, mapped through each distribution's quantile
function), which catches extremes inside the box, such as a tip moving
along the frequency axis. A distribution without bounds is truncated to
its central ``coverage`` interval (for a covariance, along each principal
axis): that is the range the union is taken over, and held-back samples
from the same ranges fall inside it. How converged the union is is the
area the last 10 % of the samples added (:attr:`Envelope.convergence`).

Between samples the true lowest boundary at a frequency can lie below
every sample (the tip of a tongue whose frequency moves with the
parameters passes it). So the union is then refined: at every frequency
where some sample is unstable, the lowest boundary over the box is
searched from the best sample (Powell's method, bounded to the box,
:func:`refine_at`). The broadest region is the union of the samples and
these refined points; the area the refinement added is reported too.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from infra.parallel import TaskFailure, parallel_map

from ..source import build_driveline
from ..monodromy import DEFAULT_METHOD
from ..tongues import lowest_of_kinds, tongue_boundaries
from .ranges import DEFAULT_COVERAGE

__all__ = ["Envelope", "sample_boundary", "compute_samples", "refine_at",
           "refine_union", "refinement_starts", "build_envelope",
           "CONVERGENCE_SHARE", "REFINE_EVALUATIONS"]

#: Share of the samples (the last ones drawn) whose added area measures
#: the convergence of the union.
CONVERGENCE_SHARE = 0.1
#: Boundary evaluations per uncertain parameter allowed to the refinement
#: at one frequency (default).
REFINE_EVALUATIONS = 20


def sample_boundary(job):
    """Lowest boundary of each kind for one parameter set.

    Parameters
    ----------
    job : tuple
        ``(params, names, values, freq_hz, p_max, method, min_growth)``:
        the nominal :class:`drivelines.Parameters`, the uncertain names
        and their values (SI), the dither frequencies (Hz), the largest
        amplitude (Pa), the monodromy engine and the growth rate (1/s) of
        the boundary.

    Returns
    -------
    ndarray, shape (nf, 3)
        :attr:`stability.tongues.Boundaries.amplitude`, Pa.
    """
    params, names, values, freq_hz, p_max, method, min_growth = job
    changed = params.replace(**dict(zip(names, map(float, values))))
    # Only the amplitudes are used: the monodromy check of every boundary
    # point (tongue_boundaries' default) would be most of the cost.
    return tongue_boundaries(build_driveline(changed), freq_hz, p_max,
                             method, min_growth=min_growth,
                             check=False).amplitude


def _area(lowest, freq_hz, p_max):
    """Area of the region above ``lowest`` up to p_max, Pa Hz."""
    height = np.where(np.isfinite(lowest), p_max - lowest, 0.0)
    if len(freq_hz) < 2:
        return float(height.sum())
    return float(np.trapezoid(height, freq_hz))


@dataclass(frozen=True)
class Envelope:
    """Broadest unstable region and probability of instability.

    Attributes
    ----------
    freq_hz : ndarray, shape (nf,)
        Dither frequencies, Hz.
    p_f : ndarray, shape (np,)
        Amplitudes of :attr:`probability`, Pa (0 to ``p_max``).
    p_max : float
        Largest amplitude searched, Pa.
    names : tuple of str
        Uncertain parameters.
    values : ndarray, shape (ns, d)
        Every sampled parameter set (SI): the vertices first, then the
        space-filling sample in the order drawn.
    is_vertex : ndarray of bool, shape (ns,)
    amplitude : ndarray, shape (ns, nf, 3)
        Lowest boundary of each kind per sample, Pa (NaN: none up to
        ``p_max``, or the sample failed).
    ok : ndarray of bool, shape (ns,)
        The sample's boundaries were computed (False: it failed; it is
        left out of everything below).
    nominal : ndarray, shape (nf, 3)
        Boundaries of the nominal parameter set, Pa.
    min_growth : float
        Growth rate (1/s) of the boundaries (0: stability).
    method : str
    coverage : float
    refined : ndarray, shape (nf,)
        Lowest boundary found by :func:`refine_at` at each frequency, Pa
        (+inf where not searched or none found below the samples).
    refined_values : ndarray, shape (nf, d)
        The parameter set (SI) of each refined point (NaN where none).
    """

    freq_hz: np.ndarray
    p_f: np.ndarray
    p_max: float
    names: tuple
    values: np.ndarray
    is_vertex: np.ndarray
    amplitude: np.ndarray
    ok: np.ndarray
    nominal: np.ndarray
    min_growth: float = 0.0
    method: str = DEFAULT_METHOD
    coverage: float = DEFAULT_COVERAGE
    refined: np.ndarray = None
    refined_values: np.ndarray = None

    @property
    def lowest(self):
        """Lowest boundary of every sample over the kinds, Pa, shape (ns,
        nf); +inf where none (or the sample failed)."""
        return np.where(self.ok[:, None], lowest_of_kinds(self.amplitude), np.inf)

    @property
    def nominal_boundary(self):
        """Lowest nominal boundary, Pa, shape (nf,); NaN where none."""
        low = lowest_of_kinds(self.nominal)
        return np.where(np.isfinite(low), low, np.nan)

    @property
    def sampled(self):
        """Lower edge of the union of the computed samples, Pa, shape
        (nf,); +inf where none is unstable up to ``p_max``."""
        return self.lowest.min(axis=0, initial=np.inf)

    @property
    def edge(self):
        """:attr:`sampled` lowered to the refined points, Pa; +inf where
        none."""
        if self.refined is None:
            return self.sampled
        return np.minimum(self.sampled, self.refined)

    @property
    def broadest(self):
        """Lower edge of the broadest region (the samples and the refined
        points), Pa, shape (nf,); NaN where nothing is unstable up to
        ``p_max``."""
        return np.where(np.isfinite(self.edge), self.edge, np.nan)

    @property
    def random(self):
        """Rows of the space-filling sample that were computed."""
        return self.ok & ~self.is_vertex

    @property
    def probability(self):
        """Share of the random samples unstable at each (f, p_f), shape
        (nf, np); NaN without random samples."""
        low = self.lowest[self.random]
        if len(low) == 0:
            return np.full((len(self.freq_hz), len(self.p_f)), np.nan)
        return (low[:, :, None] <= self.p_f[None, None, :]).mean(axis=0)

    def lowest_at(self, freq_hz):
        """Each random sample's lowest boundary at ``freq_hz`` (Hz, shape
        (n,)), Pa, shape (n_random, n): linear between the study's
        frequencies, as its outline is drawn; next to a frequency where
        the sample has none, it rises to ``p_max`` there (the outline
        closes on the top), and ``inf`` where it reaches ``p_max``."""
        low = self.lowest[self.random]
        closed = np.where(np.isfinite(low), low, self.p_max)
        freq_hz = np.asarray(freq_hz, dtype=float)
        out = np.array([np.interp(freq_hz, self.freq_hz, row)
                        for row in closed]).reshape(len(low), len(freq_hz))
        return np.where(out < self.p_max, out, np.inf)

    def probability_at(self, freq_hz, p_f):
        """Share of the random samples unstable at each (f, p_f) of the
        given frequencies (Hz, shape (n,)) and amplitudes (Pa, shape
        (m,)), shape (n, m), each sample's boundary linear between the
        study's frequencies (:meth:`lowest_at`): the bands of a figure
        follow the samples' boundaries, not the cells of
        :attr:`probability`'s grid; NaN without random samples."""
        freq_hz = np.asarray(freq_hz, dtype=float)
        p_f = np.asarray(p_f, dtype=float)
        if not self.random.any():
            return np.full((len(freq_hz), len(p_f)), np.nan)
        low = self.lowest_at(freq_hz)
        return (low[:, :, None] <= p_f[None, None, :]).mean(axis=0)

    def quantile_at(self, freq_hz, probability):
        """:meth:`quantile_boundary` at the given frequencies (Hz), from
        :meth:`lowest_at`, Pa; NaN where fewer are unstable up to
        ``p_max``."""
        freq_hz = np.asarray(freq_hz, dtype=float)
        if not self.random.any():
            return np.full(len(freq_hz), np.nan)
        q = np.quantile(self.lowest_at(freq_hz), probability, axis=0,
                        method="inverted_cdf")
        return np.where(np.isfinite(q), q, np.nan)

    def quantile_boundary(self, probability):
        """Amplitude (Pa, shape (nf,)) from which at least ``probability``
        of the random samples are unstable; NaN where fewer are up to
        ``p_max``."""
        low = self.lowest[self.random]
        if len(low) == 0:
            return np.full(len(self.freq_hz), np.nan)
        q = np.quantile(low, probability, axis=0, method="inverted_cdf")
        return np.where(np.isfinite(q), q, np.nan)

    @property
    def area_history(self):
        """Area of the union after each computed sample (in order), Pa Hz,
        shape (n_ok,)."""
        running = np.minimum.accumulate(self.lowest[self.ok], axis=0)
        return np.array([_area(row, self.freq_hz, self.p_max)
                         for row in running])

    @property
    def convergence(self):
        """How much the last samples changed the union.

        Returns
        -------
        dict
            ``samples`` (computed, vertices included), ``last`` (how many
            of the last random ones are measured, :data:`CONVERGENCE_SHARE`),
            ``area_bar_hz`` (of the union), ``added_area_bar_hz`` and
            ``added_share`` (area the last ones added, absolute and as a
            share of the whole), ``max_drop_bar`` (largest lowering of the
            union's edge they caused); ``refined_area_bar_hz`` (of the
            broadest region) and ``refinement_added_share`` (the share of
            it the refinement added).
        """
        lowest = self.lowest[self.ok]
        random = self.random[self.ok]
        last = int(np.ceil(CONVERGENCE_SHARE * random.sum()))
        order = np.flatnonzero(random)
        earlier = np.ones(len(lowest), bool)
        earlier[order[len(order) - last:]] = False
        before = lowest[earlier].min(axis=0, initial=np.inf)
        after = lowest.min(axis=0, initial=np.inf)
        area = _area(after, self.freq_hz, self.p_max)
        added = area - _area(before, self.freq_hz, self.p_max)
        with np.errstate(invalid="ignore"):
            drop = np.where(np.isfinite(after),
                            np.minimum(before, self.p_max) - after, 0.0)
        refined = _area(self.edge, self.freq_hz, self.p_max)
        return {"samples": int(len(lowest)), "last": last,
                "area_bar_hz": area / 1e5, "added_area_bar_hz": added / 1e5,
                "added_share": added / area if area > 0 else 0.0,
                "max_drop_bar": float(drop.max(initial=0.0)) / 1e5,
                "refined_area_bar_hz": refined / 1e5,
                "refinement_added_share":
                    (refined - area) / refined if refined > 0 else 0.0}

    def contains(self, amplitude, tolerance=0.0):
        """True if boundaries ``amplitude`` (Pa, shape (nf, 3)) lie inside
        the broadest region: at each frequency, not below its edge by more
        than ``tolerance`` (Pa)."""
        low = lowest_of_kinds(amplitude)
        return bool(np.all(low >= self.edge - tolerance))


def build_envelope(freq_hz, p_max, names, values, is_vertex, amplitude, ok,
                   nominal, amplitudes=150, min_growth=0.0,
                   method=DEFAULT_METHOD, coverage=DEFAULT_COVERAGE,
                   refined=None, refined_values=None):
    """Assemble an :class:`Envelope` from per-sample boundaries.

    Parameters
    ----------
    amplitudes : int
        Points of the amplitude grid of the probability, 0 to ``p_max``.

    Other parameters are the attributes of :class:`Envelope`.
    """
    return Envelope(
        freq_hz=np.asarray(freq_hz, dtype=float),
        p_f=np.linspace(0.0, p_max, amplitudes), p_max=float(p_max),
        names=tuple(names), values=np.asarray(values, dtype=float),
        is_vertex=np.asarray(is_vertex, bool),
        amplitude=np.asarray(amplitude, dtype=float),
        ok=np.asarray(ok, bool), nominal=np.asarray(nominal, dtype=float),
        min_growth=float(min_growth), method=method, coverage=coverage,
        refined=None if refined is None else np.asarray(refined, float),
        refined_values=None if refined_values is None
        else np.asarray(refined_values, float))


def _indexed(job):
    index, rest = job
    return index, sample_boundary(rest)


def compute_samples(params, names, values, freq_hz, p_max,
                    method=DEFAULT_METHOD, min_growth=0.0, skip=(),
                    workers=None):
    """Boundaries of many parameter sets, on the executor.

    Parameters
    ----------
    params : drivelines.Parameters
        The nominal set the ``values`` change.
    names : sequence of str
    values : ndarray, shape (n, d)
        One parameter set per row (SI).
    freq_hz, p_max, method, min_growth
        As :func:`stability.tongues.tongue_boundaries` takes them.
    skip : collection of int
        Rows already known (not computed again).
    workers : int, optional
        As :func:`infra.parallel.parallel_map` takes it.

    Yields
    ------
    index : int
        The row.
    outcome : ndarray, shape (nf, 3), or infra.parallel.TaskFailure
        Its boundaries (:func:`sample_boundary`), or why it failed; in
        the order they complete.
    """
    todo = [i for i in range(len(values)) if i not in set(skip)]
    freq_hz = np.asarray(freq_hz, dtype=float)
    jobs = [(i, (params, tuple(names), np.asarray(values[i], dtype=float),
                 freq_hz, float(p_max), method, float(min_growth)))
            for i in todo]

    def describe(job):
        _, (_, names_, row, *_rest) = job
        return ", ".join(f"{n} = {v:.6g}" for n, v in zip(names_, row))
    yield from _indexed_map(_indexed, jobs, workers, describe)


def _indexed_map(function, jobs, workers, describe):
    """``(index, outcome)`` of jobs ``(index, job)`` as they complete; a
    failure comes as its :class:`~infra.parallel.TaskFailure`."""
    for item in parallel_map(function, jobs, workers, ordered=False,
                             describe=describe, failures="yield"):
        yield (jobs[item.index][0], item) if isinstance(item, TaskFailure) \
            else item


def refine_at(job):
    """Lowest boundary at one frequency over the box of ranges.

    Parameters
    ----------
    job : tuple
        ``(params, ranges, freq_hz, p_max, method, min_growth, start,
        evaluations)``: as :func:`sample_boundary`, one frequency (Hz),
        the point of the unit cube to start from (the best sample there)
        and the boundary evaluations allowed per parameter.

    Returns
    -------
    lowest : float
        Lowest boundary found, Pa (that of ``start`` if nothing lower;
        +inf if no boundary up to ``p_max``).
    unit : ndarray, shape (d,)
        Where (unit cube).

    Bounded Powell search; a point with no boundary up to ``p_max``
    counts as ``2 p_max``.
    """
    (params, ranges, freq_hz, p_max, method, min_growth, start,
     evaluations) = job

    def boundary(unit):
        row = ranges.values(np.clip(unit, 0.0, 1.0)[None])[0]
        low = lowest_of_kinds(sample_boundary((params, ranges.names, row, [freq_hz],
                                       p_max, method, min_growth)))[0]
        return float(low) if np.isfinite(low) else 2.0 * p_max

    start = np.asarray(start, dtype=float)
    first = boundary(start)
    best = minimize(boundary, start, method="Powell",
                    bounds=[(0.0, 1.0)] * len(start),
                    options={"xtol": 1e-4, "ftol": 1e-10,
                             "maxfev": evaluations * len(start)})
    value, point = ((float(best.fun), np.clip(best.x, 0.0, 1.0))
                    if best.fun < first else (first, start))
    return (value if value <= p_max else np.inf), point


def refine_union(params, ranges, unit, lowest, freq_hz, p_max,
                 method=DEFAULT_METHOD, min_growth=0.0, skip=(),
                 evaluations=REFINE_EVALUATIONS, workers=None):
    """:func:`refine_at` at every frequency where a sample is unstable,
    and next to them.

    Parameters
    ----------
    unit : ndarray, shape (ns, d)
        The samples' points of the unit cube.
    lowest : ndarray, shape (ns, nf)
        Their lowest boundaries, Pa (+inf: none, or not computed).
    skip : collection of int
        Frequencies already refined.
    evaluations : int
        Boundary evaluations per parameter at each frequency.

    Yields
    ------
    index : int
        The frequency.
    outcome : tuple (float, ndarray) or infra.parallel.TaskFailure
        As :func:`refine_at` returns; in the order they complete.
    """
    freq_hz = np.asarray(freq_hz, dtype=float)
    starts = refinement_starts(lowest)
    todo = [j for j in range(len(freq_hz))
            if j not in set(skip) and starts[j] >= 0]
    jobs = [(j, (params, ranges, float(freq_hz[j]), float(p_max), method,
                 float(min_growth), unit[starts[j]], int(evaluations)))
            for j in todo]

    def describe(job):
        return f"refinement at {job[1][2]:g} Hz"
    yield from _indexed_map(_refined, jobs, workers, describe)


def refinement_starts(lowest):
    """Per frequency, the sample to refine from (-1: none): the lowest
    there, or where no sample is unstable next to a frequency where one
    is, the lowest at that neighbour (the region may reach past it)."""
    best = np.argmin(lowest, axis=0)
    unstable = np.isfinite(lowest.min(axis=0, initial=np.inf))
    starts = np.where(unstable, best, -1)
    for j in np.flatnonzero(~unstable):
        for k in (j - 1, j + 1):
            if 0 <= k < len(best) and unstable[k]:
                starts[j] = best[k]
                break
    return starts


def _refined(job):
    index, rest = job
    return index, refine_at(rest)

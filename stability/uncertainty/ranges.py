r"""Uncertain parameters of an envelope (section 4.2): intervals and
distributions, and the points of the unit cube that sample them.

Each uncertain parameter is an interval or a distribution
(:class:`Uniform`, :class:`Normal`, or several jointly as the normal
approximation of a fit, :class:`Correlated`). A point of the unit cube
``[0, 1]^d`` maps to parameter values through each distribution's quantile
function, 0 and 1 being the ends of each range; a normal distribution is
kept to its central ``coverage`` interval (for a covariance, along each
principal axis). :func:`design_points` gives the vertices of the cube and
a space-filling sample of it (:mod:`scipy.stats.qmc`).
"""

from dataclasses import dataclass
import itertools

import numpy as np
from scipy.special import ndtri
from scipy.stats import qmc

from infra.errors import JudderError, ParameterError

__all__ = ["Uniform", "Normal", "Correlated", "Ranges", "SAMPLERS",
           "DEFAULT_COVERAGE", "MAX_VERTEX_DIMENSION", "design_points",
           "check_values"]

#: Central probability of a normal distribution kept as its range.
DEFAULT_COVERAGE = 0.95
#: Most uncertain parameters whose 2**d vertices are all computed.
MAX_VERTEX_DIMENSION = 12
#: Space-filling samplers of :func:`design_points`.
SAMPLERS = ("sobol", "lhs")


@dataclass(frozen=True)
class Uniform:
    """A parameter anywhere in ``[low, high]`` (SI): an interval (``kind
    'interval'``, sampled uniformly) or a uniform distribution."""

    name: str
    low: float
    high: float
    kind: str = "interval"

    @property
    def names(self):
        return (self.name,)

    def unit_ends(self, coverage):
        return np.zeros(1), np.ones(1)

    def values(self, unit):
        return self.low + unit * (self.high - self.low)

    def describe(self):
        return {"name": self.name, "kind": self.kind, "low": self.low,
                "high": self.high}


@dataclass(frozen=True)
class Normal:
    """A normally distributed parameter (SI), kept to its central
    ``coverage`` interval."""

    name: str
    mean: float
    std: float

    @property
    def names(self):
        return (self.name,)

    def unit_ends(self, coverage):
        return (np.full(1, (1 - coverage) / 2),
                np.full(1, (1 + coverage) / 2))

    def values(self, unit):
        return self.mean + self.std * ndtri(unit)

    def describe(self):
        return {"name": self.name, "kind": "normal", "mean": self.mean,
                "std": self.std}


@dataclass(frozen=True)
class Correlated:
    """Parameters jointly normal with ``mean`` and ``covariance`` (SI), as
    a fit estimates them; kept to the central ``coverage`` interval along
    each principal axis of the covariance."""

    names: tuple
    mean: np.ndarray
    covariance: np.ndarray
    source: str = "covariance"

    def unit_ends(self, coverage):
        k = len(self.names)
        return (np.full(k, (1 - coverage) / 2),
                np.full(k, (1 + coverage) / 2))

    def values(self, unit):
        scale, axes = np.linalg.eigh(self.covariance)
        return self.mean + (ndtri(unit) * np.sqrt(np.clip(scale, 0, None))) \
            @ axes.T

    def describe(self):
        return {"names": list(self.names), "kind": "normal (covariance)",
                "source": self.source, "mean": self.mean.tolist(),
                "covariance": self.covariance.tolist()}


@dataclass(frozen=True)
class Ranges:
    """The uncertain parameters: a tuple of :class:`Uniform`,
    :class:`Normal` and :class:`Correlated`, and the ``coverage`` that
    bounds the normal ones.

    Raises
    ------
    JudderError
        A parameter given twice, a coverage outside (0, 1), or a range
        that is empty or not finite.
    """

    items: tuple
    coverage: float = DEFAULT_COVERAGE

    def __post_init__(self):
        if not 0 < self.coverage < 1:
            raise JudderError(f"coverage = {self.coverage!r} is not allowed;"
                              " allowed: 0 < coverage < 1")
        names = self.names
        repeated = sorted({n for n in names if names.count(n) > 1})
        if repeated:
            raise JudderError(f"ranges: {repeated[0]} is given twice; allowed:"
                              " each parameter once")
        if not names:
            raise JudderError("ranges: no uncertain parameter; give at least"
                              " one")
        for item in self.items:
            _check_item(item)

    @property
    def names(self):
        return tuple(n for item in self.items for n in item.names)

    @property
    def dimension(self):
        return len(self.names)

    def values(self, unit):
        """Parameter values (SI) of points of the unit cube.

        Parameters
        ----------
        unit : ndarray, shape (n, d)
            Points in ``[0, 1]^d``; 0 and 1 are the ends of each range.

        Returns
        -------
        ndarray, shape (n, d)
            Columns in the order of :attr:`names`.
        """
        unit = np.atleast_2d(np.asarray(unit, dtype=float))
        out, column = [], 0
        for item in self.items:
            k = len(item.names)
            low, high = item.unit_ends(self.coverage)
            out.append(item.values(low + unit[:, column:column + k]
                                   * (high - low)))
            column += k
        return np.column_stack(out)

    def describe(self):
        return {"coverage": self.coverage,
                "parameters": [item.describe() for item in self.items]}


def _check_item(item):
    if isinstance(item, Uniform):
        if not (np.isfinite(item.low) and np.isfinite(item.high)
                and item.low < item.high):
            raise JudderError(f"ranges: {item.name} = [{item.low!r}, "
                              f"{item.high!r}] is not allowed; allowed: "
                              "finite low < high")
    elif isinstance(item, Normal):
        if not (np.isfinite(item.mean) and np.isfinite(item.std)
                and item.std > 0):
            raise JudderError(f"ranges: {item.name} normal with mean "
                              f"{item.mean!r}, std {item.std!r} is not "
                              "allowed; allowed: finite mean, std > 0")
    else:
        cov = np.asarray(item.covariance, dtype=float)
        k = len(item.names)
        if cov.shape != (k, k) or not np.all(np.isfinite(cov)) \
                or not np.all(np.isfinite(item.mean)) \
                or not np.allclose(cov, cov.T, rtol=1e-9, atol=0) \
                or np.linalg.eigvalsh(cov).min() < -1e-9 * np.abs(cov).max():
            raise JudderError(f"ranges: the covariance of {', '.join(item.names)}"
                              f" ({item.source}) is not allowed; allowed: a "
                              "finite symmetric positive semi-definite "
                              f"{k} x {k} matrix")


def design_points(ranges, samples, seed=0, sampler="sobol", vertices=True):
    """Points of the unit cube: the vertices, then a space-filling sample.

    Parameters
    ----------
    ranges : Ranges
    samples : int
        Space-filling points (>= 0).
    seed : int
        Seed of the scrambling (Sobol) or permutation (LHS).
    sampler : {'sobol', 'lhs'}
        Scrambled Sobol sequence (its first ``samples`` points) or Latin
        hypercube.
    vertices : bool
        Start with the ``2**d`` vertices.

    Returns
    -------
    unit : ndarray, shape (n, d)
    is_vertex : ndarray of bool, shape (n,)

    Raises
    ------
    JudderError
        An unknown sampler, a negative count, or vertices asked for more
        than :data:`MAX_VERTEX_DIMENSION` parameters.
    """
    d = ranges.dimension
    if sampler not in SAMPLERS:
        raise JudderError(f"sampler {sampler!r} is unknown; allowed: "
                          f"{', '.join(SAMPLERS)}")
    if int(samples) != samples or samples < 0:
        raise JudderError(f"samples = {samples!r} is not allowed; allowed: a "
                          "whole number >= 0")
    if vertices and d > MAX_VERTEX_DIMENSION:
        raise JudderError(f"{d} uncertain parameters have 2**{d} vertices; "
                          f"allowed: at most {MAX_VERTEX_DIMENSION} (or leave "
                          "the vertices out)")
    corners = (np.array(list(itertools.product((0.0, 1.0), repeat=d)))
               if vertices else np.empty((0, d)))
    samples = int(samples)
    if samples == 0:
        sample = np.empty((0, d))
    elif sampler == "sobol":
        m = max(int(np.ceil(np.log2(samples))), 0)
        sample = qmc.Sobol(d, scramble=True, rng=seed).random_base2(m)[
            :samples]
    else:
        sample = qmc.LatinHypercube(d=d, rng=seed).random(samples)
    unit = np.vstack([corners, sample])
    return unit, np.arange(len(unit)) < len(corners)


def check_values(params, names, values):
    """Refuse a range that reaches values the model does not allow.

    Parameters
    ----------
    params : drivelines.Parameters
        The nominal set.
    names : sequence of str
    values : ndarray, shape (n, d)
        Typically the vertices: the ends of every range.

    Raises
    ------
    ParameterError
        Naming the parameter, the value its range reaches and the model's
        allowed range.
    """
    for name in names:
        if name not in params.specs:
            raise ParameterError(f"ranges: unknown parameter {name!r} for the"
                                 f" {params.model} model; allowed names: "
                                 f"{', '.join(params.specs)}")
    for row in values:
        try:
            params.replace(**dict(zip(names, map(float, row))))
        except JudderError as exc:
            raise ParameterError(f"ranges: an end of the ranges is not "
                                 f"allowed: {exc}") from None

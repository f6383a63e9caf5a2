r"""Tongue boundaries, labels and tips (Fig. 14, Fig. 16).

Boundaries
----------
A single-period boundary is the lowest amplitude where a Floquet
multiplier passes +1, a double-period one where it passes -1, a
combination boundary where a complex pair reaches the unit circle. Hill's
method (:mod:`stability.hill`) gives the first two for every system and
waveform: ``1/p_f`` is a real eigenvalue of Hill's matrix, projected on
the modulated channels. Two solvers (:data:`SOLVERS`) add the combination
boundaries:

``'hill'`` (default)
    :func:`stability.hill.combination_boundaries`: the same projected Hill
    problem with the exponent ``i nu`` as a second unknown, solved by
    Newton's method, every kind for all frequencies at once (about 45x
    faster, `make bench`). It needs the paper's rank-one cosine
    modulation (:func:`stability.hill.applies`); other systems go to
    ``'scan'``.
``'scan'``
    Brent's method, per frequency, on the monodromy of the chosen engine
    (:data:`~stability.monodromy.METHODS`) for the combination boundary.

With ``check=True`` every boundary point is checked against the monodromy
multiplier of the chosen engine (an independent computation).

Tongues
-------
Each dip of a boundary curve (a local minimum of the lowest boundary
amplitude over frequency, with a prominence of at least
:data:`TIP_PROMINENCE` of ``p_max``) is the tip of a tongue. Neighbouring
tongues of one kind can merge above their tips (with a stiff clutch damper
the single-period boundary is one curve dipping at ``f1`` and ``f2``); they
are separated at the highest point between their tips. A tongue is
labelled after the resonance it grows from (section 4.2): single-period at the
natural frequencies ``f_i``, double-period at ``2 f_i``, combination at
``f_j - f_i`` and ``f_i + f_j``. Numbers follow Fig. 14: 1..n single,
n+1..2n double, then the combination pairs (difference, then sum).
"""

from dataclasses import dataclass
import itertools

import numpy as np
from scipy.optimize import brentq, minimize_scalar
from scipy.signal import find_peaks

from infra.errors import JudderError

from .hill import (applies as hill_applies, combination_boundaries,
                   modal_transfer, real_boundaries)
from .kinds import Kind, is_real
from .modal import natural_frequencies
from .monodromy import DEFAULT_METHOD, get_method

__all__ = ["Boundaries", "Tongue", "TONGUE_KINDS", "SOLVERS",
           "DEFAULT_SOLVER", "get_solver", "lowest_boundaries",
           "tongue_boundaries", "kind_boundary",
           "kind_boundaries", "lowest_of_kinds", "find_tongues", "resonances",
           "higher_order_resonances", "resonance_of"]

#: Amplitudes scanned per frequency before refining a combination boundary.
_SCAN_POINTS = 48
#: A tongue tip farther than this share from every resonance of its kind
#: is reported without a number.
_LABEL_TOLERANCE = 0.15
#: Smallest dip (share of p_max) of a boundary curve counted as a tongue.
TIP_PROMINENCE = 0.02


def _combination_excess(propagator, p_f):
    """Largest |multiplier| - 1 among the non-real multipliers."""
    lam = np.linalg.eigvals(propagator.monodromy(p_f))
    return np.where(is_real(lam), 0.0, np.abs(lam)).max(axis=-1) - 1.0


def _combination_boundary(propagator, p_max):
    """Lowest amplitude where a complex pair leaves the unit circle, or NaN."""
    grid = np.linspace(0.0, p_max, _SCAN_POINTS)
    excess = _combination_excess(propagator, grid)
    above = np.flatnonzero(excess > 0)
    if len(above) == 0 or above[0] == 0:
        return np.nan
    i = above[0]
    return brentq(lambda p: _combination_excess(propagator, [p])[0],
                  grid[i - 1], grid[i], xtol=1e-9 * p_max, rtol=1e-13)


def _multiplier_error(propagator, p_f, kind):
    """Distance of the crossing multiplier from the unit circle at p_f."""
    lam = np.linalg.eigvals(propagator.monodromy([p_f])[0])
    if kind == Kind.SINGLE_PERIOD:
        return float(np.abs(lam - 1.0).min())
    if kind == Kind.DOUBLE_PERIOD:
        return float(np.abs(lam + 1.0).min())
    pair = lam[~is_real(lam)]
    if len(pair) == 0:
        return np.nan
    return float(np.abs(np.abs(pair) - 1.0).min())


#: The kinds of tongue, in the order of the columns of
#: :attr:`Boundaries.amplitude`.
TONGUE_KINDS = (Kind.SINGLE_PERIOD, Kind.DOUBLE_PERIOD, Kind.COMBINATION)


def _real_lowest(transfer, freq_hz, p_max):
    """Lowest single- and double-period boundary up to ``p_max`` (Pa, NaN
    where none), shape (2, nf)."""
    real = real_boundaries(transfer, freq_hz, [1, -1])[..., 0]
    return np.where(real <= p_max, real, np.nan)


def _scan_lowest(system, freq_hz, p_max, method):
    """``'scan'`` solver: Hill's method for +-1, Brent's method on the
    monodromy, per frequency, for pairs."""
    engine = get_method(method)
    combination = [_combination_boundary(engine(system, freq, p_max), p_max)
                   for freq in freq_hz]
    return np.column_stack([*_real_lowest(modal_transfer(system), freq_hz,
                                          p_max), combination])


def _hill_lowest(system, freq_hz, p_max, method):
    """``'hill'`` solver: every kind and frequency at once.

    It assumes the paper's rank-one cosine modulation; a modulation of
    higher rank or another waveform goes to the ``'scan'`` solver."""
    if not hill_applies(system):
        return _scan_lowest(system, freq_hz, p_max, method)
    transfer = modal_transfer(system)
    combination, _ = combination_boundaries(transfer, freq_hz, p_max)
    return np.column_stack([*_real_lowest(transfer, freq_hz, p_max),
                            combination])


#: Boundary solvers by name: ``f(system, freq_hz, p_max, method)`` gives the
#: lowest amplitude of each kind, shape (nf, 3), NaN where none.
SOLVERS = {"hill": _hill_lowest, "scan": _scan_lowest}
DEFAULT_SOLVER = "hill"


def lowest_of_kinds(amplitude):
    """Lowest boundary over the kinds (last axis), Pa; ``inf`` where no
    kind has one (NaN in ``amplitude``)."""
    amplitude = np.asarray(amplitude, dtype=float)
    return np.min(np.where(np.isfinite(amplitude), amplitude, np.inf),
                  axis=-1)


def get_solver(name):
    """The boundary solver ``name``; ValueError listing the options."""
    if name not in SOLVERS:
        raise JudderError(f"solver = {name!r} is unknown; allowed: "
                          f"{', '.join(SOLVERS)}")
    return SOLVERS[name]


def lowest_boundaries(system, freq_hz, p_max, solver=DEFAULT_SOLVER,
                      method=DEFAULT_METHOD):
    """Lowest boundary amplitude of each kind, no checks (for optimisers).

    Parameters
    ----------
    system : stability.model.PeriodicSystem
        Shift it (:meth:`~stability.model.PeriodicSystem.shifted`) for the
        boundary of a growth rate.
    freq_hz : ndarray, shape (nf,)
        Hz.
    p_max : float
        Pa.
    solver : str
        A key of :data:`SOLVERS`.
    method : str
        Monodromy engine of the ``'scan'`` solver.

    Returns
    -------
    ndarray, shape (nf, 3)
        Pa, columns in the order of :data:`TONGUE_KINDS`; NaN where none
        up to ``p_max``.
    """
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    return get_solver(solver)(system, freq_hz, p_max, method)


@dataclass(frozen=True)
class Boundaries:
    """Lowest boundary amplitude of each kind of tongue, per frequency.

    Attributes
    ----------
    freq_hz : ndarray, shape (nf,)
        Dither frequencies, Hz.
    p_max : float
        Largest amplitude searched, Pa.
    amplitude : ndarray, shape (nf, 3)
        Lowest ``p_f`` (Pa) at which a multiplier leaves the unit circle
        through +1 (column 0, single-period), -1 (column 1,
        double-period) or as a complex pair (column 2, combination); NaN
        where none does up to ``p_max``.
    multiplier_error : ndarray, shape (nf, 3)
        At each boundary point, the distance of the crossing multiplier
        from +1, -1 or the unit circle, by the monodromy (NaN where no
        point).
    natural_frequencies_hz : ndarray
    method : str
        Monodromy engine of the combination boundaries and the checks.
    min_growth : float
        1/s: the boundaries are where the response grows at this rate (0:
        the stability boundary, a multiplier on the unit circle).
    solver : str
        Boundary solver, a key of :data:`SOLVERS`.
    checked : bool
        False if the points were not checked against the monodromy
        (``multiplier_error`` is then NaN).
    """

    freq_hz: np.ndarray
    p_max: float
    amplitude: np.ndarray
    multiplier_error: np.ndarray
    natural_frequencies_hz: np.ndarray
    method: str = DEFAULT_METHOD
    min_growth: float = 0.0
    solver: str = DEFAULT_SOLVER
    checked: bool = True

    @property
    def stability_boundary(self):
        """Lowest unstable amplitude of any kind, Pa, shape (nf,)."""
        lowest = lowest_of_kinds(self.amplitude)
        return np.where(np.isfinite(lowest), lowest, np.nan)

    @property
    def max_multiplier_error(self):
        """Largest ``multiplier_error`` over all points (0 if none, NaN
        if unchecked)."""
        if not self.checked:
            return float("nan")
        finite = self.multiplier_error[np.isfinite(self.multiplier_error)]
        return float(finite.max()) if len(finite) else 0.0


def tongue_boundaries(driveline, freq_hz, p_max, method=DEFAULT_METHOD,
                      callback=None, min_growth=0.0, solver=DEFAULT_SOLVER,
                      check=True):
    """Boundaries of the single-, double-period and combination tongues.

    Parameters
    ----------
    driveline : stability.source.ModelSource
    freq_hz : array_like, shape (nf,)
        Dither frequencies, Hz.
    p_max : float
        Largest amplitude searched, Pa.
    method : str
        Monodromy engine (a key of :data:`stability.monodromy.METHODS`)
        for the combination boundaries and the checks of every point.
    callback : callable, optional
        ``callback(done, total)`` after each frequency.
    min_growth : float
        Draw the boundary of growth at this rate (1/s) instead of the
        stability boundary: the stability boundary of
        :meth:`~stability.model.PeriodicSystem.shifted`. Judder that grows
        slower than about 1/s does not build up within an engagement.

    Returns
    -------
    Boundaries

    Examples
    --------
    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> b = tongue_boundaries(build_driveline(get_preset("paper-4dof")),
    ...                       [100.0], 1e5)
    >>> round(float(b.amplitude[0, 0]) / 1e5, 4)   # single-period, bar
    0.3642
    """
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    system = driveline.periodic_system().shifted(min_growth)
    amplitude = lowest_boundaries(system, freq_hz, p_max, solver, method)
    errors = np.full((len(freq_hz), 3), np.nan)
    engine = get_method(method)
    for index, freq in enumerate(freq_hz):
        if check and np.isfinite(amplitude[index]).any():
            propagator = engine(system, freq, p_max)
            errors[index] = [np.nan if np.isnan(p) else
                             _multiplier_error(propagator, p, kind)
                             for kind, p in zip(TONGUE_KINDS,
                                                amplitude[index])]
        if callback is not None:
            callback(index + 1, len(freq_hz))
    return Boundaries(freq_hz=freq_hz, p_max=float(p_max),
                      amplitude=amplitude, multiplier_error=errors,
                      natural_frequencies_hz=natural_frequencies(driveline),
                      method=method, min_growth=float(min_growth),
                      solver=solver, checked=bool(check))


def resonances(natural_frequencies_hz):
    """Frequencies tongues grow from: ``(number, label, hz, kind code)``.

    Single-period at ``f_i``, double-period at ``2 f_i``, combination at
    ``f_j - f_i`` and ``f_i + f_j``, numbered as in Fig. 14.
    """
    f = np.sort(np.asarray(natural_frequencies_hz, dtype=float))
    n = len(f)
    out = [(i + 1, f"f{i + 1}", fi, Kind.SINGLE_PERIOD)
           for i, fi in enumerate(f)]
    out += [(n + i + 1, f"2f{i + 1}", 2 * fi, Kind.DOUBLE_PERIOD)
            for i, fi in enumerate(f)]
    number = 2 * n
    for (i, fi), (j, fj) in itertools.combinations(enumerate(f), 2):
        out += [(number + 1, f"f{j + 1}-f{i + 1}", fj - fi,
                 Kind.COMBINATION),
                (number + 2, f"f{i + 1}+f{j + 1}", fi + fj,
                 Kind.COMBINATION)]
        number += 2
    return out


def higher_order_resonances(natural_frequencies_hz):
    """Resonances of higher order: ``(None, label, hz, kind code)``.

    A mode of frequency ``f_i`` is excited parametrically at ``2 f_i /
    k`` with the multiplier ``(-1)^k`` (Mathieu's tongues; k = 1, 2 are
    Fig. 14's ``2f_i`` and ``f_i``): here k = 3 (double-period,
    ``2f1/3``) and k = 4 (single-period, ``f1/2``). Two modes are excited
    at ``(f_j -+ f_i) / k``, complex multipliers (combination): here k =
    2 and 3. They carry no number of Fig. 14.
    """
    f = np.sort(np.asarray(natural_frequencies_hz, dtype=float))
    out = [(None, f"2f{i + 1}/3", 2 * fi / 3, Kind.DOUBLE_PERIOD)
           for i, fi in enumerate(f)]
    out += [(None, f"f{i + 1}/2", fi / 2, Kind.SINGLE_PERIOD)
            for i, fi in enumerate(f)]
    for k in (2, 3):
        for (i, fi), (j, fj) in itertools.combinations(enumerate(f), 2):
            out += [(None, f"(f{j + 1}-f{i + 1})/{k}", (fj - fi) / k,
                     Kind.COMBINATION),
                    (None, f"(f{i + 1}+f{j + 1})/{k}", (fi + fj) / k,
                     Kind.COMBINATION)]
    return out


def resonance_of(tip_hz, kind, natural_frequencies_hz):
    """The resonance a tongue of ``kind`` tipped at ``tip_hz`` grows from.

    The nearest of its kind among :func:`resonances` and
    :func:`higher_order_resonances`, within :data:`_LABEL_TOLERANCE`
    relative (the first order where two are as near).

    Returns
    -------
    tuple
        ``(number, label, hz, kind)``; ``(None, None, None, kind)`` when
        none is near.

    Examples
    --------
    >>> resonance_of(65.2, Kind.COMBINATION, [30.0, 100.0])[1]
    '(f1+f2)/2'
    >>> resonance_of(68.0, Kind.DOUBLE_PERIOD, [18.9, 102.9])[1]
    '2f2/3'
    """
    candidates = [r for r in resonances(natural_frequencies_hz)
                  + higher_order_resonances(natural_frequencies_hz)
                  if r[3] == kind and r[2] > 0]
    best = min(candidates, key=lambda r: abs(r[2] - tip_hz) / r[2],
               default=None)
    if best is None or abs(best[2] - tip_hz) > _LABEL_TOLERANCE * best[2]:
        return (None, None, None, kind)
    return best


@dataclass(frozen=True)
class Tongue:
    """One instability tongue and its tip.

    Attributes
    ----------
    number : int or None
        Number as in Fig. 14; None when it grows from a resonance of
        higher order (:func:`higher_order_resonances`) or from none.
    kind : str
        ``'single-period'``, ``'double-period'`` or ``'combination'``.
    resonance : str or None
        ``'f2'``, ``'2f1'``, ``'f2-f1'``, ``'2f2/3'``, ``'(f1+f2)/2'``,
        ... the resonance it grows from (:func:`resonance_of`); None when
        none of its kind is near.
    resonance_hz : float or None
    tip_freq_hz : float
        Frequency of the lowest boundary point, Hz (refined by Brent's
        method between grid points).
    tip_p_f : float
        Lowest boundary amplitude, Pa.
    tip_multiplier_error : float
        Monodromy check at the tip (distance from the unit circle).
    freq_range_hz : tuple of float
        Grid frequencies where the tongue is below ``p_max``.
    tip_at_edge : bool
        True if the lowest point is at the end of the frequency grid (the
        true tip may lie outside).
    """

    number: object
    kind: str
    resonance: object
    resonance_hz: object
    tip_freq_hz: float
    tip_p_f: float
    tip_multiplier_error: float
    freq_range_hz: tuple
    tip_at_edge: bool


def _runs(mask):
    """Start and stop indices of the runs of True in ``mask``."""
    edges = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1))


def _tips(amplitude, p_max):
    """Index ranges and tip index of each tongue along one boundary curve.

    Yields ``(start, stop, tip)`` over the grid indices.
    """
    for start, stop in _runs(np.isfinite(amplitude)):
        # beyond the run (or the grid) the boundary is above p_max
        curve = np.concatenate([[2 * p_max], amplitude[start:stop],
                                [2 * p_max]])
        tips, _ = find_peaks(-curve, prominence=TIP_PROMINENCE * p_max)
        if len(tips) == 0:
            tips = [1 + int(np.argmin(curve[1:-1]))]
        cuts = [0] + [a + int(np.argmax(curve[a:b + 1]))
                      for a, b in zip(tips[:-1], tips[1:])] + [len(curve) - 1]
        # curve index i is grid index start + i - 1 (one pad in front)
        for tip, low, high in zip(tips, cuts[:-1], cuts[1:]):
            yield (start + max(low, 1) - 1,
                   start + min(high, len(curve) - 2) - 1,
                   start + tip - 1)


def find_tongues(driveline, boundaries):
    """Label the tongues of ``boundaries`` and refine their tips.

    Parameters
    ----------
    driveline : stability.source.ModelSource
        The driveline the boundaries were computed for.
    boundaries : Boundaries

    Returns
    -------
    list of Tongue
        Ordered by number (unnumbered ones last). The tips are checked
        against the monodromy when ``boundaries.checked`` (otherwise
        ``tip_multiplier_error`` is NaN).
    """
    system = driveline.periodic_system().shifted(boundaries.min_growth)
    f = boundaries.freq_hz
    found = []
    engine = get_method(boundaries.method)
    curves = kind_boundaries(system, boundaries.p_max, boundaries.solver,
                             boundaries.method)
    for column, kind in enumerate(TONGUE_KINDS):
        amplitude = boundaries.amplitude[:, column]
        boundary = curves[column]
        for start, stop, i in _tips(amplitude, boundaries.p_max):
            tip_f, tip_p = f[i], amplitude[i]
            at_edge = i in (0, len(f) - 1)
            if not at_edge:
                tip_f, tip_p = _refine_tip(boundary, f[i - 1], f[i + 1],
                                           boundaries.p_max, tip_f, tip_p)
            error = (_multiplier_error(engine(system, tip_f, boundaries.p_max),
                                       tip_p, kind)
                     if boundaries.checked else float("nan"))
            best = resonance_of(tip_f, kind,
                                boundaries.natural_frequencies_hz)
            found.append(Tongue(
                number=best[0], kind=kind.label, resonance=best[1],
                resonance_hz=best[2], tip_freq_hz=float(tip_f),
                tip_p_f=float(tip_p), tip_multiplier_error=error,
                freq_range_hz=(float(f[start]), float(f[stop])),
                tip_at_edge=bool(at_edge)))
    return _deduplicate(found)


def _deduplicate(tongues):
    """Keep the lowest tip per number; extra runs lose their number."""
    tongues = sorted(tongues, key=lambda t: t.tip_p_f)
    seen, out = set(), []
    for t in tongues:
        if t.number is not None and t.number in seen:
            t = Tongue(None, t.kind, None, None, t.tip_freq_hz, t.tip_p_f,
                       t.tip_multiplier_error, t.freq_range_hz, t.tip_at_edge)
        seen.add(t.number)
        out.append(t)
    return sorted(out, key=lambda t: (t.number is None, t.number or 0,
                                      t.tip_freq_hz))


def kind_boundaries(system, p_max, solver=DEFAULT_SOLVER,
                    method=DEFAULT_METHOD):
    """:func:`kind_boundary` of each of :data:`TONGUE_KINDS`, in that
    order, sharing one modal transfer."""
    transfer = modal_transfer(system)
    return [kind_boundary(system, column, p_max, solver, method, transfer)
            for column in range(len(TONGUE_KINDS))]


def kind_boundary(system, column, p_max, solver=DEFAULT_SOLVER,
                  method=DEFAULT_METHOD, transfer=None):
    """``B_k(f)``: the lowest boundary amplitude of one kind, Pa.

    Parameters
    ----------
    system : stability.model.PeriodicSystem
        Shifted to the growth rate whose boundary is wanted.
    column : int
        Index into :data:`TONGUE_KINDS`.
    p_max : float
        Pa; amplitudes above it count as no boundary.
    solver, method : str
        As for :func:`lowest_boundaries`.
    transfer : stability.hill.ModalTransfer, optional
        :func:`stability.hill.modal_transfer` of ``system``, if known.

    Returns
    -------
    callable
        ``f(freq_hz)`` for a float: Pa, or ``inf`` where there is no
        boundary up to ``p_max``.
    """
    transfer = modal_transfer(system) if transfer is None else transfer
    if TONGUE_KINDS[column] is not Kind.COMBINATION:
        multiplier = 1 if TONGUE_KINDS[column] is Kind.SINGLE_PERIOD else -1

        def lowest(freq):
            return real_boundaries(transfer, [freq], multiplier)[0, 0]
    elif solver == "hill" and hill_applies(system):
        def lowest(freq):
            return combination_boundaries(transfer, [freq], p_max)[0][0]
    else:
        def lowest(freq):
            return lowest_boundaries(system, [freq], p_max, solver,
                                     method)[0, column]

    def amplitude(freq):
        p = lowest(freq)
        return p if np.isfinite(p) and p <= p_max else np.inf
    return amplitude


def _refine_tip(boundary, low, high, p_max, grid_f, grid_p):
    """Minimise ``boundary`` (:func:`kind_boundary`) over [low, high]."""
    def amplitude(freq):
        return min(boundary(freq), 2 * p_max)

    best = minimize_scalar(amplitude, bounds=(low, high), method="bounded",
                           options={"xatol": 1e-7 * grid_f})
    if best.fun < grid_p:
        return float(best.x), float(best.fun)
    return float(grid_f), float(grid_p)

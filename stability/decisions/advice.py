r"""Design advice: safe dither windows and the smallest design change that
clears the dither window of judder (section 4.3, section 5 of the paper).

Everything is read from the exact judder-relevant boundary :math:`B(f)`:
the lowest amplitude at which the response grows at ``min_growth``
(:mod:`stability.decisions.relevance`), by Hill's method
(:mod:`stability.hill`), taken as the lowest over a list of parameter sets when the parameters are
uncertain (the broadest region of section 4.2).

Safe windows
    The operating range is :math:`[f_{lo}, f_{hi}] \times [0, p_{hi}]`
    (the paper's valve: 60-200 Hz, 0.7 bar). The safe amplitude at ``f``
    is :math:`\min(p_{hi}, \min_{|f' - f| \le m_f} B(f') - m_p)`, with a
    margin :math:`m_p` in bar and :math:`m_f` in Hz; a safe window is an
    interval where it is positive.

Clearing the window
    A tongue is in the way when its boundary lies below
    :math:`p_{req} = p_{hi} + m_p` somewhere in
    :math:`[f_{lo} - m_f, f_{hi} + m_f]`. It leaves by moving up (its left
    edge at :math:`p_{req}` above :math:`f_{hi} + m_f`), down (its right
    edge below :math:`f_{lo} - m_f`) or by rising (its tip above
    :math:`p_{req}`). With :math:`x = \ln(\theta/\theta_0)` the log-changes
    of the design parameters and weights :math:`w`, the advice minimises
    :math:`\lVert w \odot x \rVert` subject to every tongue leaving:
    sequential linear programming, each step the smallest weighted step
    that satisfies the linearised exits (elasticities of the edges and tips
    by central differences on the exact boundaries), then a line search and
    a per-parameter shrink with the exact boundaries. Whether a design
    clears the window is read on the grid of its safe windows
    (:func:`window_grid`), with :data:`CLEARANCE` to spare, so that the
    design the advice gives always has the whole operating range as its
    safe window at :math:`p_{hi}`. Each parameter stays
    inside its bounds (factors of the nominal value, default
    :data:`DEFAULT_BOUNDS`). The result is checked by a recomputed Floquet
    map of the advised design.

Clear of judder, not always stable
    The design keeps the judder-relevant tongues (growth at ``min_growth``
    or faster) out of the window; a tongue may still be unstable there,
    growing slower. :func:`unstable_regions` says where.
"""

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize

from infra.errors import JudderError

from ..kinds import KINDS
from ..source import build_driveline
from ..tongues import (TONGUE_KINDS, find_tongues, lowest_boundaries,
                      lowest_of_kinds, tongue_boundaries)
from .relevance import is_judder_relevant

__all__ = ["OperatingRange", "window_boundary", "safe_windows", "SafeWindow",
           "ranking", "Advice", "advise_design", "verify_design",
           "unstable_regions", "UnstableRegion", "DEFAULT_DESIGN_PARAMETERS",
           "DEFAULT_BOUNDS", "check_bounds", "PRUNE_BELOW", "CLEARANCE",
           "window_grid"]

#: Design parameters the advice may change by default (section 4.3).
DEFAULT_DESIGN_PARAMETERS = ("J2", "J4", "k12", "k24", "c12")
#: Relative step of the elasticities (central differences in ln theta).
_STEP = 0.02
#: Factors of the nominal value each design parameter may take by default:
#: halved to doubled, the range of the paper's sensitivity study (Fig. 17,
#: 18), over which the tongue shifts it reports were computed; a change
#: beyond it is a new component rather than a revision of the given one.
DEFAULT_BOUNDS = (0.5, 2.0)
#: Relative change below which an advised change is dropped when the
#: window stays clear without it: 3 %, below the tolerance of a stiffness
#: or an inertia as built, so not a change a design review could act on.
PRUNE_BELOW = 0.03
#: Frequency points of the grid of the tongues (edges, tips) per design
#: evaluation.
_GRID_POINTS = 600
#: Frequency step of the safe windows' grid, Hz.
WINDOW_STEP_HZ = 0.5
#: Relative amount by which a design's judder boundary must clear the
#: required amplitude on the safe windows' grid (:func:`window_grid`) for
#: the design to count as clear: 0.1 %, 0.8 mbar at 0.7 + 0.1 bar. The
#: shrink towards nominal stops on the edge of this criterion; the
#: clearance keeps the exact boundary between the grid's points above the
#: required amplitude too (on the README's two advised designs it dips
#: there by 0.013 and 0.23 mbar below its lowest grid value, on a 0.05 Hz
#: grid: under a third of the clearance).
CLEARANCE = 1e-3


@dataclass(frozen=True)
class OperatingRange:
    """Dither operating range and the margins a setting must keep.

    Attributes
    ----------
    freq_hz : (float, float)
        Lowest and highest dither frequency, Hz.
    p_max : float
        Highest dither amplitude, Pa.
    margin_p_f : float
        Amplitude margin below the boundary, Pa.
    margin_hz : float
        Frequency margin from a tongue edge, Hz.
    """

    freq_hz: tuple = (60.0, 200.0)
    p_max: float = 0.7e5
    margin_p_f: float = 0.1e5
    margin_hz: float = 5.0

    @property
    def required_p_f(self):
        """Lowest boundary amplitude allowed inside the window, Pa."""
        return self.p_max + self.margin_p_f

    @property
    def guarded(self):
        """The frequency window widened by the margin, Hz."""
        return (self.freq_hz[0] - self.margin_hz,
                self.freq_hz[1] + self.margin_hz)

    def grid(self, points=_GRID_POINTS):
        """Frequencies that hold the window and the tongues beside it."""
        low, high = self.guarded
        return np.linspace(max(0.5 * low, 1.0), 1.5 * high, points)


def window_grid(operating, step=WINDOW_STEP_HZ):
    """Frequencies of the safe windows: the operating range widened by the
    frequency margin (so that tongues just outside count), every ``step``
    Hz (:data:`WINDOW_STEP_HZ`), Hz."""
    low, high = operating.guarded
    return np.linspace(low, high, int(round((high - low) / step)) + 1)


def window_boundary(param_sets, freq_hz, min_growth, p_search):
    """Lowest judder-relevant boundary over all kinds and parameter sets.

    Parameters
    ----------
    param_sets : sequence of drivelines.Parameters
    freq_hz : ndarray, shape (nf,)
    min_growth : float
        1/s.
    p_search : float
        Largest amplitude searched, Pa.

    Returns
    -------
    ndarray, shape (nf,)
        Pa; ``inf`` where no boundary up to ``p_search``.
    """
    lowest = np.full(len(freq_hz), np.inf)
    for params in param_sets:
        system = build_driveline(params).periodic_system().shifted(min_growth)
        amplitude = lowest_boundaries(system, freq_hz, p_search)
        lowest = np.minimum(lowest, lowest_of_kinds(amplitude))
    return lowest


@dataclass(frozen=True)
class SafeWindow:
    """An interval of dither frequencies with a safe amplitude.

    Attributes
    ----------
    freq_hz : (float, float)
        Hz.
    max_p_f : float
        Pa: every setting of the interval up to this amplitude keeps both
        margins.
    full_range : bool
        True if the whole operating amplitude is safe there.
    """

    freq_hz: tuple
    max_p_f: float
    full_range: bool


#: Amplitudes (shares of the operating amplitude) at which safe windows
#: are listed.
WINDOW_LEVELS = (1.0, 0.5, 0.25, 0.125)


def safe_windows(freq_hz, boundary, operating, levels=WINDOW_LEVELS):
    """Safe amplitude per frequency and the safe windows at a few levels.

    Parameters
    ----------
    freq_hz : ndarray, shape (nf,)
        Evenly spaced, Hz.
    boundary : ndarray, shape (nf,)
        :func:`window_boundary`, Pa.
    operating : OperatingRange
    levels : sequence of float
        Shares of ``operating.p_max``.

    Returns
    -------
    safe_p_f : ndarray, shape (nf,)
        Pa (0 where nothing is safe; only inside the operating range).
    windows : list of SafeWindow
        For each level, the maximal intervals where every amplitude up to
        it is safe (``max_p_f`` the level, ``full_range`` for level 1).
    """
    step = freq_hz[1] - freq_hz[0] if len(freq_hz) > 1 else 1.0
    reach = int(np.ceil(operating.margin_hz / step - 1e-9))
    padded = np.concatenate([np.full(reach, np.inf), boundary,
                             np.full(reach, np.inf)])
    near = np.min(np.stack([padded[i:i + len(boundary)]
                            for i in range(2 * reach + 1)]), axis=0)
    safe = np.clip(np.minimum(operating.p_max, near - operating.margin_p_f),
                   0.0, None)
    inside = (freq_hz >= operating.freq_hz[0]) & (freq_hz <= operating.freq_hz[1])
    safe = np.where(inside, safe, 0.0)
    windows = []
    for share in levels:
        level = share * operating.p_max
        edges = np.diff(np.concatenate([[0], (safe >= level * (1 - 1e-12))
                                        .astype(int), [0]]))
        for start, stop in zip(np.flatnonzero(edges == 1),
                               np.flatnonzero(edges == -1)):
            windows.append(SafeWindow(
                freq_hz=(float(freq_hz[start]), float(freq_hz[stop - 1])),
                max_p_f=float(level), full_range=bool(share >= 1.0)))
    return safe, windows


def _tongues(params, operating, min_growth, p_search):
    """Judder-relevant tongues of one design over the window's grid."""
    driveline = build_driveline(params)
    boundaries = tongue_boundaries(driveline, operating.grid(), p_search,
                                   min_growth=min_growth, check=False)
    return boundaries, find_tongues(driveline, boundaries)


def _edges(boundaries, tongue, level):
    """Left and right frequency where ``tongue`` crosses ``level`` (Pa),
    by linear interpolation of the exact boundary on the grid; the grid
    ends when it does not cross there."""
    column = [KINDS[k] for k in TONGUE_KINDS].index(tongue.kind)
    f = boundaries.freq_hz
    a = np.where(np.isfinite(boundaries.amplitude[:, column]),
                 boundaries.amplitude[:, column], np.inf)
    tip = int(np.argmin(np.abs(f - tongue.tip_freq_hz)))
    left = tip
    while left > 0 and a[left - 1] <= level:
        left -= 1
    right = tip
    while right < len(f) - 1 and a[right + 1] <= level:
        right += 1

    def cross(i, j):   # a[i] <= level < a[j]
        if not np.isfinite(a[j]):
            return float(f[j])
        return float(f[i] + (level - a[i]) / (a[j] - a[i]) * (f[j] - f[i]))
    low = cross(left, left - 1) if left > 0 else float(f[0])
    high = cross(right, right + 1) if right < len(f) - 1 else float(f[-1])
    return low, high


def _in_the_way(boundaries, tongues, operating):
    """``{number: (left edge, right edge, tip p_f)}`` of tongues that reach
    below the required amplitude inside the guarded window."""
    level = operating.required_p_f
    low, high = operating.guarded
    out = {}
    for t in tongues:
        if t.tip_p_f > level or t.number is None:
            continue
        left, right = _edges(boundaries, t, level)
        if right >= low and left <= high:
            out[t.number] = (left, right, t.tip_p_f)
    return out


def _features(params, numbers, operating, min_growth, p_search):
    """Edges and tip amplitude of the numbered tongues (NaN if absent)."""
    boundaries, tongues = _tongues(params, operating, min_growth, p_search)
    level = operating.required_p_f
    out = {}
    for number in numbers:
        t = next((t for t in tongues if t.number == number), None)
        if t is None:
            out[number] = (np.nan, np.nan, np.nan)
        elif t.tip_p_f > level:
            out[number] = (t.tip_freq_hz, t.tip_freq_hz, t.tip_p_f)
        else:
            out[number] = (*_edges(boundaries, t, level), t.tip_p_f)
    return out


def _changed(param_sets, names, x):
    factors = dict(zip(names, np.exp(x)))
    return [p.replace(**{n: p[n] * factors[n] for n in names})
            for p in param_sets]


def _elasticities(param_sets, names, x, numbers, operating, min_growth,
                  p_search, step=_STEP):
    """d(ln edge, ln edge, ln tip p_f)/d(x_i), per tongue: (n_names, 3)."""
    out = {n: np.full((len(names), 3), np.nan) for n in numbers}
    for i in range(len(names)):
        values = []
        for sign in (1, -1):
            xi = np.array(x, dtype=float)
            xi[i] += sign * step
            values.append(_features(_changed(param_sets, names, xi)[0],
                                    numbers, operating, min_growth, p_search))
        for n in numbers:
            up, down = np.array(values[0][n]), np.array(values[1][n])
            with np.errstate(all="ignore"):
                out[n][i] = (np.log(up) - np.log(down)) / (2 * step)
    return out


def ranking(params, names, operating, min_growth, p_search):
    """Effect of each parameter per relative change on the tongues in the
    way: the share of the way out of the window one unit of ``ln theta``
    takes the worst of them (the one that needs most), by its best exit.

    Returns
    -------
    list of (name, share, detail)
        Sorted by decreasing share; ``detail`` maps each tongue number to
        ``(d ln left edge, d ln right edge, d ln tip p_f)`` per unit
        ``ln theta``.
    """
    boundaries, tongues = _tongues(params, operating, min_growth, p_search)
    way = _in_the_way(boundaries, tongues, operating)
    if not way:
        return []
    slopes = _elasticities([params], names, np.zeros(len(names)), list(way),
                           operating, min_growth, p_search)
    low, high = operating.guarded
    out = []
    for i, name in enumerate(names):
        shares = []
        for number, (left, right, tip) in way.items():
            d_left, d_right, d_tip = slopes[number][i]
            need = [np.log(high / left), np.log(right / low),
                    np.log(operating.required_p_f / tip)]
            gain = [d_left, -d_right, d_tip]
            shares.append(max((g / n for g, n in zip(gain, need)
                               if np.isfinite(g) and n > 0), default=0.0))
        out.append((name, float(min(shares)),
                    {n: tuple(slopes[n][i]) for n in way}))
    return sorted(out, key=lambda r: -r[1])


@dataclass(frozen=True)
class Advice:
    """Smallest weighted relative design change that clears the window.

    Attributes
    ----------
    names : tuple of str
    factors : ndarray, shape (n,)
        New value / nominal value of each parameter.
    weighted_change : float
        ``||w * ln(factors)||``.
    success : bool
    message : str
    iterations : int
    history : list
        Tongues in the way at each iteration (their numbers).
    bounds : ndarray, shape (n, 2)
        Lowest and highest factor each parameter was allowed.
    dropped : dict
        ``{name: factor}``: changes below :data:`PRUNE_BELOW` the search
        found and that were dropped (the parameter is back at nominal),
        as the window stays clear without them.
    """

    names: tuple
    factors: np.ndarray
    weighted_change: float
    success: bool
    message: str
    iterations: int
    history: list = field(default_factory=list)
    bounds: np.ndarray = None
    dropped: dict = field(default_factory=dict)


def _clear(param_sets, names, x, operating, min_growth, p_search):
    """True if no judder-relevant tongue of any set is in the window: the
    judder boundary of every set lies at least :data:`CLEARANCE` above
    the required amplitude on the grid of the safe windows
    (:func:`window_grid`, the same boundaries :func:`safe_windows` reads),
    so a clear design's safe window at the valve's highest amplitude is
    the whole operating range."""
    boundary = window_boundary(_changed(param_sets, names, x),
                               window_grid(operating), min_growth, p_search)
    return bool(np.all(boundary >= (1 + CLEARANCE) * operating.required_p_f))


def _smallest_step(x, weights, rows, targets, limit):
    """min ||w (x + d)|| subject to rows @ d >= targets and
    limit[:, 0] <= x + d <= limit[:, 1]."""
    def objective(d):
        return float(np.sum((weights * (x + d)) ** 2))

    def gradient(d):
        return 2 * weights ** 2 * (x + d)
    constraints = [{"type": "ineq", "fun": lambda d: rows @ d - targets,
                    "jac": lambda d: rows}]
    bounds = [(low - xi, high - xi) for xi, (low, high) in zip(x, limit)]
    start = np.zeros_like(x)
    result = minimize(objective, start, jac=gradient, bounds=bounds,
                      constraints=constraints, method="SLSQP",
                      options={"maxiter": 200, "ftol": 1e-12})
    return result.x if result.success else None


def _combined_step(x, weights, way, slopes, operating, limit):
    """Smallest weighted step that moves every tongue in the way out by
    one of its exits (up, down, rise), over every choice of exits."""
    import itertools
    low, high = operating.guarded
    per_tongue = []
    for number, (left, right, tip) in way.items():
        options = [(slopes[number][:, 0], np.log(high / left)),
                   (-slopes[number][:, 1], np.log(right / low)),
                   (slopes[number][:, 2], np.log(operating.required_p_f / tip))]
        # overshoot the linearisation a little
        per_tongue.append([(row, 1.15 * need + 0.01) for row, need in options
                           if np.all(np.isfinite(row)) and np.any(row)])
    best = None
    for choice in itertools.product(*per_tongue):
        rows = np.array([row for row, _ in choice])
        targets = np.array([need for _, need in choice])
        step = _smallest_step(x, weights, rows, targets, limit)
        if step is None or np.any(rows @ step < targets - 1e-6):
            continue
        cost = np.linalg.norm(weights * (x + step))
        if best is None or cost < best[0]:
            best = (cost, step)
    return None if best is None else best[1]


def check_bounds(names, bounds):
    """The bounds of the design parameters as an ``(n, 2)`` array of
    factors; JudderError unless each is ``0 < low <= 1 <= high <
    inf`` (the nominal design lies inside)."""
    bounds = np.asarray(bounds, dtype=float)
    if bounds.shape != (len(names), 2):
        raise JudderError(f"{len(bounds)} bounds for {len(names)} "
                          "parameters; allowed: one (low, high) each")
    for name, (low, high) in zip(names, bounds):
        if not (np.isfinite(low) and np.isfinite(high) and 0 < low <= 1
                <= high and low < high):
            raise JudderError(f"bounds of {name} = {low:g}:{high:g} are not "
                              "allowed; allowed: factors 0 < LOW <= 1 <= "
                              "HIGH, LOW < HIGH, finite")
    return bounds


def bounds_words(names, bounds):
    """``J2 x0.5-2, J4 x0.8-1.25``."""
    return ", ".join(f"{n} x{low:g}-{high:g}"
                     for n, (low, high) in zip(names, bounds))


def advise_design(param_sets, names, weights, operating, min_growth,
                  p_search, max_iterations=8, callback=None, bounds=None):
    """:class:`Advice`: the smallest weighted change that clears the window.

    Parameters
    ----------
    param_sets : sequence of drivelines.Parameters
        The nominal set first; the others (an envelope) get the same
        relative change and must be clear too.
    names : sequence of str
        Design parameters.
    weights : ndarray, shape (n,)
        Cost of a unit change of ``ln theta`` of each.
    operating : OperatingRange
    min_growth : float
        1/s.
    p_search : float
        Largest boundary amplitude searched, Pa (> required amplitude).
    callback : callable, optional
        ``callback(done, total)`` after each iteration.
    bounds : array_like, shape (n, 2), optional
        Lowest and highest factor of each parameter (default
        :data:`DEFAULT_BOUNDS` for each).
    """
    names = tuple(names)
    weights = np.asarray(weights, dtype=float)
    bounds = check_bounds(names, [DEFAULT_BOUNDS] * len(names)
                          if bounds is None else bounds)
    limit = np.log(bounds)
    x = np.zeros(len(names))
    history = []
    message = "no design found within the iteration limit"
    success = False
    iterations = 0
    for iterations in range(1, max_iterations + 1):
        boundaries, tongues = _tongues(_changed(param_sets, names, x)[0],
                                       operating, min_growth, p_search)
        way = _in_the_way(boundaries, tongues, operating)
        history.append(sorted(way))
        if not way and _clear(param_sets, names, x, operating, min_growth,
                              p_search):
            success, message = True, "the window is clear"
            break
        if not way:   # only an uncertain set or an unnumbered tongue left
            x = np.clip(x * 1.1 + 0.02 * np.sign(x), limit[:, 0], limit[:, 1])
            continue
        slopes = _elasticities(param_sets, names, x, list(way), operating,
                               min_growth, p_search)
        step = _combined_step(x, weights, way, slopes, operating, limit)
        if step is None:
            message = (f"no design inside the bounds ({bounds_words(names, bounds)}) "
                       f"moves tongue{'s' if len(way) > 1 else ''} "
                       f"{', '.join(map(str, sorted(way)))} out of the "
                       "window by the linearised exits (up, down or up in "
                       "amplitude) from this design")
            break
        x = np.clip(x + step, limit[:, 0], limit[:, 1])
        if callback is not None:
            callback(iterations, max_iterations)
    dropped = {}
    if success:
        shrunk = _shrink(param_sets, names, x, operating, min_growth,
                         p_search)
        x, dropped = _prune(param_sets, names, x, shrunk, operating,
                            min_growth, p_search)
    elif message.startswith("no design found within"):
        message = (f"no design inside the bounds ({bounds_words(names, bounds)}) "
                   f"found in {max_iterations} iterations; tongues "
                   f"{', '.join(map(str, history[-1]))} still in the window")
    return Advice(names=names, factors=np.exp(x),
                  weighted_change=float(np.linalg.norm(weights * x)),
                  success=success, message=message, iterations=iterations,
                  history=history, bounds=bounds, dropped=dropped)


def _shrink(param_sets, names, x, operating, min_growth, p_search,
            steps=6):
    """Bring a clear design back towards the nominal one: the whole change
    by bisection on its scale, then each parameter alone."""
    def clear(z):
        return _clear(param_sets, names, z, operating, min_growth, p_search)
    low, high = 0.0, 1.0
    for _ in range(steps):
        mid = 0.5 * (low + high)
        low, high = (low, mid) if clear(mid * x) else (mid, high)
    x = high * x
    for i in range(len(x)):
        low, high = 0.0, 1.0
        for _ in range(steps):
            mid = 0.5 * (low + high)
            trial = x.copy()
            trial[i] *= mid
            low, high = (low, mid) if clear(trial) else (mid, high)
        x[i] *= high
    return x


def _prune(param_sets, names, found, shrunk, operating, min_growth,
           p_search, below=PRUNE_BELOW):
    """Drop the small changes of a clear design that it does not need.

    The shrunk design (:func:`_shrink`) sits on the edge of clearing the
    window in every parameter, so no change of it can be dropped alone;
    the drop is tried on the design the search found instead (clear, with
    room to spare), and the shrink then repeated without the dropped
    parameters. Each change with ``|factor - 1| < below`` in the shrunk
    design is reset to nominal, the smallest first, and the reset is kept
    when the design still clears the window (:func:`_clear`, the criterion
    of the search).

    Parameters
    ----------
    found, shrunk : ndarray, shape (n,)
        Log-changes of the design the search found, and of it shrunk.

    Returns
    -------
    x : ndarray
        The log-changes, the dropped ones zero (``shrunk`` if none is
        dropped).
    dropped : dict
        ``{name: factor}`` of the changes dropped, as in ``shrunk``.
    """
    kept = found.copy()
    dropped = {}
    for i in np.argsort(np.abs(shrunk)):
        if shrunk[i] == 0 or abs(np.expm1(shrunk[i])) >= below:
            continue
        trial = kept.copy()
        trial[i] = 0.0
        if _clear(param_sets, names, trial, operating, min_growth, p_search):
            dropped[names[i]] = float(np.exp(shrunk[i]))
            kept = trial
    if not dropped:
        return shrunk, dropped
    return _shrink(param_sets, names, kept, operating, min_growth,
                   p_search), dropped


def verify_design(params, operating, min_growth, freq_points=141,
                  p_points=36, method=None):
    """Recompute the Floquet map of a design over the operating range.

    Returns
    -------
    map : stability.maps.StabilityMap
    judder_points : int
        Grid points growing faster than ``min_growth``.
    """
    from ..maps import stability_map
    from ..monodromy import DEFAULT_METHOD
    low, high = operating.freq_hz
    result = stability_map(build_driveline(params),
                           np.linspace(low, high, freq_points),
                           np.linspace(0.0, operating.p_max, p_points),
                           method=method or DEFAULT_METHOD)
    judder = (result.kind > 0) & is_judder_relevant(result.growth_rate,
                                                     min_growth)
    return result, int(np.count_nonzero(judder))


@dataclass(frozen=True)
class UnstableRegion:
    """Frequencies of the operating range where a design is unstable
    (``|lambda| > 1``) below the operating amplitude.

    Attributes
    ----------
    freq_hz : (float, float)
        Hz.
    lowest_p_f : float
        Lowest unstable amplitude there, Pa.
    lowest_at_hz : float
        Its frequency, Hz.
    """

    freq_hz: tuple
    lowest_p_f: float
    lowest_at_hz: float


def unstable_regions(param_sets, operating, freq_points=561):
    """Where a design is unstable in the operating range, at any growth.

    The stability boundary (growth 0) of every set, lowest over the sets,
    exact from Hill's method on ``freq_points`` frequencies of the range.

    Returns
    -------
    list of UnstableRegion
        Intervals where it lies at or below ``operating.p_max``.
    """
    low, high = operating.freq_hz
    grid = np.linspace(low, high, freq_points)
    boundary = window_boundary(param_sets, grid, 0.0,
                               max(1.5e5, 2 * operating.required_p_f))
    below = boundary <= operating.p_max
    out = []
    edges = np.diff(np.concatenate([[0], below.astype(int), [0]]))
    for start, stop in zip(np.flatnonzero(edges == 1),
                           np.flatnonzero(edges == -1)):
        at = start + int(np.argmin(boundary[start:stop]))
        out.append(UnstableRegion(
            freq_hz=(float(grid[start]), float(grid[stop - 1])),
            lowest_p_f=float(boundary[at]), lowest_at_hz=float(grid[at])))
    return out


def check_weights(names, weights):
    """Raise JudderError unless every weight is finite and > 0."""
    for name, w in zip(names, weights):
        if not np.isfinite(w) or w <= 0:
            raise JudderError(f"weight of {name} = {float(w)!r} is not "
                              "allowed; "
                              "allowed: a finite value > 0")

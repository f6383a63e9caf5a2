r"""Margins of a dither setting to the nearest judder-relevant tongue.

For a setting :math:`(f_0, p_0)` the judder-relevant boundary is the
lowest amplitude :math:`B(f)` at which the response grows at
``min_growth`` (:mod:`stability.decisions.relevance`), the stability
boundary of the shifted system (:meth:`~stability.model.PeriodicSystem.shifted`),
computed exactly by :mod:`stability.hill` for each kind of tongue:

* margin in bar: :math:`B(f_0) - p_0` (negative inside a tongue);
* margin in Hz: the distance from :math:`f_0` to the nearest frequency
  where :math:`B(f) = p_0` (a root of the exact boundary of one kind,
  found by Brent's method between the points of a fine grid), positive
  outside a tongue, negative inside.

The sensitivities are finite differences of those margins (on the exact
boundaries, the root followed from its nominal place) for a relative
change of each parameter.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from infra.errors import JudderError

from ..multipliers import floquet
from ..kinds import KINDS
from ..source import build_driveline
from ..tongues import (TONGUE_KINDS, find_tongues, kind_boundaries,
                      kind_boundary, lowest_boundaries, tongue_boundaries)
from .relevance import is_judder_relevant

__all__ = ["Margin", "setting_margin", "margin_sensitivity", "search_grid",
           "GRID_POINTS", "SettingCheck", "check_settings"]

#: Points of the log-spaced frequency grid on which boundary crossings are
#: bracketed before Brent's method refines them.
GRID_POINTS = 1200
#: Relative step of the finite differences of the sensitivities.
STEP = 1e-3


def search_grid(freq_hz, low=None, high=None, points=GRID_POINTS):
    """Log-spaced frequencies around the settings, Hz.

    Default range: a quarter of the lowest to four times the highest
    setting frequency.
    """
    freq_hz = np.asarray(freq_hz, dtype=float)
    low = freq_hz.min() / 4 if low is None else low
    high = freq_hz.max() * 4 if high is None else high
    return np.geomspace(low, high, points)


@dataclass(frozen=True)
class Margin:
    """Distance of one setting from the judder-relevant boundary.

    Attributes
    ----------
    freq_hz, p_f : float
        The setting, Hz and Pa.
    boundary_p_f : float
        ``B(f0)``, Pa (``inf`` if none up to ``p_max``).
    bar_kind : str or None
        Kind of the boundary right at ``f0``.
    margin_p_f : float
        ``B(f0) - p0``, Pa (``inf``: none up to ``p_max``).
    crossing_hz : float or None
        Nearest frequency where ``B(f) = p0``, Hz (None: none in the
        search range).
    hz_kind : str or None
        Kind of tongue whose boundary that is.
    margin_hz : float
        Signed distance to ``crossing_hz``, Hz: > 0 outside a tongue (the
        frequency may move that far), < 0 inside; ``inf`` if none.
    crossing_tolerance_hz : float
        0 when ``crossing_hz`` is the root of the boundary curve; else half
        the grid step that holds it (:func:`_crossing`), Hz.
    inside : bool
        ``p0 >= B(f0)``: the setting lies in a judder-relevant tongue.
    band_low_hz, band_high_hz : float or None
        The nearest frequencies below and above ``f0`` where ``B(f) =
        p0``, Hz (None: none in the search range): outside a tongue, the
        band of frequencies around ``f0`` free of parametric judder at
        ``p0``.
    band_low_kind, band_high_kind : str or None
        Kind of tongue whose boundary ends the band there.
    """

    freq_hz: float
    p_f: float
    boundary_p_f: float
    bar_kind: object
    margin_p_f: float
    crossing_hz: object
    hz_kind: object
    margin_hz: float
    crossing_tolerance_hz: float
    inside: bool
    band_low_hz: object = None
    band_low_kind: object = None
    band_high_hz: object = None
    band_high_kind: object = None


def _crossing(curves, column, p0, low, high):
    """Root of ``B_k(f) = p0`` in [low, high], a grid step where the
    batched boundaries cross ``p0``.

    A boundary evaluated at one frequency can miss a branch that the
    batched solver followed along the grid (its continuation in frequency,
    :func:`stability.hill.combination_boundaries`); then the ends do not
    bracket a root of ``B_k`` and the crossing is known to the grid step
    only: its middle.

    Returns
    -------
    root, tolerance : float
        Hz; ``tolerance`` is 0 for Brent's root, half the step otherwise.
    """
    def excess(freq):
        p = curves[column](freq)
        return (p if np.isfinite(p) else 2 * p0 + 1.0) - p0
    if np.sign(excess(low)) == np.sign(excess(high)):
        return 0.5 * (low + high), 0.5 * (high - low)
    return brentq(excess, low, high, xtol=1e-10 * high, rtol=1e-12), 0.0


def setting_margin(system, freq_hz, p_f, p_max, grid, amplitude=None):
    """:class:`Margin` of the setting ``(freq_hz, p_f)``.

    Parameters
    ----------
    system : stability.model.PeriodicSystem
        Shifted by the judder-relevant growth rate.
    freq_hz, p_f : float
        Hz, Pa.
    p_max : float
        Largest boundary amplitude searched, Pa (> ``p_f``).
    grid : ndarray
        Frequencies that bracket the crossings, Hz (:func:`search_grid`).
    amplitude : ndarray, shape (len(grid), 3), optional
        :func:`stability.tongues.lowest_boundaries` on ``grid``, if known.

    Returns
    -------
    Margin
    """
    if amplitude is None:
        amplitude = lowest_boundaries(system, grid, p_max)
    curves = kind_boundaries(system, p_max)
    at = np.array([curve(freq_hz) for curve in curves])
    column = int(np.argmin(at))
    boundary = float(at[column])
    inside = p_f >= boundary
    # unstable at p0 on the grid: some kind below p0
    low_curve = np.where(np.isfinite(amplitude), amplitude, np.inf)
    best = (np.inf, None, None, 0.0)
    # the nearest crossing on each side: the band free of parametric
    # judder at p0 (of any kind) around f0
    sides = {-1: (np.inf, None, None), 1: (np.inf, None, None)}
    for kind_col in range(3):
        below = low_curve[:, kind_col] <= p_f
        flips = np.flatnonzero(below[1:] != below[:-1])
        for i in flips:
            root, tolerance = _crossing(curves, kind_col, p_f, grid[i],
                                        grid[i + 1])
            distance = abs(root - freq_hz)
            if distance < best[0]:
                best = (distance, root, kind_col, tolerance)
            side = 1 if root > freq_hz else -1
            if distance < sides[side][0]:
                sides[side] = (distance, float(root),
                               KINDS[TONGUE_KINDS[kind_col]])
    if inside and best[1] is None:
        raise JudderError(f"freq = {freq_hz:g} Hz, p_f = {p_f / 1e5:g} bar "
                          "lies in a tongue wider than the search range; "
                          "widen it")
    distance, root, hz_col, tolerance = best
    return Margin(
        freq_hz=float(freq_hz), p_f=float(p_f), boundary_p_f=boundary,
        bar_kind=None if not np.isfinite(boundary) else
        KINDS[TONGUE_KINDS[column]],
        margin_p_f=boundary - p_f,
        crossing_hz=None if root is None else float(root),
        hz_kind=None if hz_col is None else KINDS[TONGUE_KINDS[hz_col]],
        margin_hz=(-distance if inside else distance),
        crossing_tolerance_hz=float(tolerance), inside=bool(inside),
        band_low_hz=sides[-1][1], band_low_kind=sides[-1][2],
        band_high_hz=sides[1][1], band_high_kind=sides[1][2])


def margin_sensitivity(params, names, freq_hz, p_f, margin, min_growth,
                       p_max, step=STEP):
    """Change of both margins per relative change of each parameter.

    The bar margin follows the boundary of ``margin.bar_kind`` at ``f0``;
    the Hz margin follows the crossing root of ``margin.hz_kind`` from
    its nominal place (Brent's method in a bracket grown around it).

    Parameters
    ----------
    params : drivelines.Parameters
    names : sequence of str
        Parameters to vary.
    freq_hz, p_f : float
        The setting, Hz and Pa.
    margin : Margin
        Its nominal margin.
    min_growth : float
        1/s, the judder-relevant rate.
    p_max : float
        Pa.
    step : float
        Relative step (central differences).

    Returns
    -------
    dict
        ``{name: (d margin_p_f / d ln(name) in Pa, d margin_hz / d
        ln(name) in Hz)}``; NaN where that margin is not defined.
    """
    kinds = [KINDS[k] for k in TONGUE_KINDS]
    out = {}
    for name in names:
        values = []
        for sign in (1, -1):
            changed = params.replace(**{name: params[name] * (1 + sign * step)})
            system = build_driveline(changed).periodic_system().shifted(
                min_growth)
            bar = hz = np.nan
            if margin.bar_kind is not None:
                curve = kind_boundary(system, kinds.index(margin.bar_kind),
                                         p_max)
                bar = curve(freq_hz) - p_f
            if margin.hz_kind is not None:
                hz = _followed_crossing(system, kinds.index(margin.hz_kind),
                                        p_f, margin.crossing_hz, p_max)
                hz = np.sign(margin.margin_hz) * abs(hz - freq_hz)
            values.append((bar, hz))
        (bar_up, hz_up), (bar_down, hz_down) = values
        scale = np.log((1 + step) / (1 - step))
        out[name] = ((bar_up - bar_down) / scale, (hz_up - hz_down) / scale)
    return out


def _followed_crossing(system, column, p_f, nominal, p_max):
    """The root of ``B_k(f) = p_f`` nearest ``nominal``, Hz (NaN if lost)."""
    curve = kind_boundary(system, column, p_max)

    def excess(freq):
        return min(curve(freq), 2 * p_f + 1.0) - p_f
    for width in (1e-3, 1e-2, 5e-2):
        low, high = nominal * (1 - width), nominal * (1 + width)
        if np.sign(excess(low)) != np.sign(excess(high)):
            return brentq(excess, low, high, xtol=1e-10 * nominal,
                          rtol=1e-12)
    return np.nan


@dataclass(frozen=True)
class SettingCheck:
    """Verdict and margins of one dither setting (``judder check``).

    Attributes
    ----------
    margin : Margin
    floquet : stability.multipliers.FloquetResult
        At the setting, without the growth shift.
    judder : bool
        The leading growth rate exceeds ``min_growth``
        (:func:`stability.decisions.relevance.is_judder_relevant`).
    bar_tongue, hz_tongue : stability.tongues.Tongue or None
        The judder-relevant tongue whose boundary gives each margin.
    tongue : stability.tongues.Tongue or None
        The tongue the setting lies in, when it is unstable: the tongue of
        the leading multiplier's kind whose frequency range holds the
        setting (else the one with the nearest tip), numbered by its
        resonance as in Fig. 14.
    sensitivity : dict
        :func:`margin_sensitivity` (empty if not asked for).
    band_low_tongue, band_high_tongue : stability.tongues.Tongue or None
        The judder-relevant tongues whose boundaries end the band free of
        parametric judder at the setting's amplitude
        (``margin.band_low_hz``, ``margin.band_high_hz``).
    unstable_p_f : float
        The stability boundary at the setting's frequency: the lowest
        amplitude at which a multiplier leaves the unit circle
        (``|lambda| = 1``, growth 0), Pa (``inf``: none up to ``p_max``).
        Below the judder-relevant ``margin.boundary_p_f`` unless
        ``min_growth`` is 0.
    """

    margin: Margin
    floquet: object
    judder: bool
    bar_tongue: object
    hz_tongue: object
    sensitivity: dict
    tongue: object = None
    unstable_p_f: float = np.inf
    band_low_tongue: object = None
    band_high_tongue: object = None


def _tongue_at(tongues, kind, freq_hz):
    """The tongue of ``kind`` whose range holds ``freq_hz``, else the one
    with the nearest tip (None if there is none of that kind)."""
    same = [t for t in tongues if t.kind == kind]
    if not same or freq_hz is None:
        return None
    holding = [t for t in same
               if t.freq_range_hz[0] <= freq_hz <= t.freq_range_hz[1]]
    pool = holding or same
    return min(pool, key=lambda t: abs(t.tip_freq_hz - freq_hz))


def check_settings(params, freq_hz, p_f, min_growth, p_max, names=(),
                   callback=None):
    """:class:`SettingCheck` of each setting ``(freq_hz[i], p_f[i])``.

    Parameters
    ----------
    params : drivelines.Parameters
    freq_hz, p_f : array_like, shape (n,)
        Settings, Hz and Pa.
    min_growth : float
        Judder-relevant growth rate, 1/s.
    p_max : float
        Largest boundary amplitude searched, Pa.
    names : sequence of str
        Parameters of the sensitivities.
    callback : callable, optional
        ``callback(done, total)`` after each setting.

    Returns
    -------
    list of SettingCheck
    """
    driveline = build_driveline(params)
    system = driveline.periodic_system().shifted(min_growth)
    grid = search_grid(freq_hz)
    boundaries = tongue_boundaries(driveline, grid, p_max,
                                   min_growth=min_growth, check=False)
    amplitude = boundaries.amplitude
    tongues = find_tongues(driveline, boundaries)
    # where the setting's frequency becomes unstable (growth 0)
    unstable_curves = kind_boundaries(driveline.periodic_system(), p_max)
    out = []
    for index, (f0, p0) in enumerate(zip(freq_hz, p_f)):
        margin = setting_margin(system, f0, p0, p_max, grid, amplitude)
        unstable = min(float(curve(f0)) for curve in unstable_curves)
        point = floquet(driveline, f0, p0)
        sens = (margin_sensitivity(params, names, f0, p0, margin, min_growth,
                                   p_max) if names else {})
        out.append(SettingCheck(
            margin=margin, floquet=point,
            judder=bool(is_judder_relevant(point.growth_rate, min_growth)),
            bar_tongue=_tongue_at(tongues, margin.bar_kind, f0),
            hz_tongue=_tongue_at(tongues, margin.hz_kind, margin.crossing_hz),
            sensitivity=sens,
            tongue=(None if point.kind == KINDS[0] else
                    _tongue_at(tongues, point.kind, f0)),
            unstable_p_f=unstable,
            band_low_tongue=_tongue_at(tongues, margin.band_low_kind,
                                       margin.band_low_hz),
            band_high_tongue=_tongue_at(tongues, margin.band_high_kind,
                                        margin.band_high_hz)))
        if callback is not None:
            callback(index + 1, len(freq_hz))
    return out

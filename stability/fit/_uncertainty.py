r"""Uncertainty of a boundary fit (section 4.2): standard uncertainties
and 95 % intervals that hold.

Uncertainty
-----------
The standard uncertainties and 95 % intervals (:data:`CONFIDENCE`) come
from one of:

``'jacobian'``
    ``cov = s^2 (J^T J)^{-1}`` from a central-difference Jacobian at the
    solution, ``s^2`` the residual variance with ``n - k`` degrees of
    freedom, intervals ``value +- t std`` (Student's ``t``). Onsets found
    on a grid of amplitudes are compared at the middle of their step,
    which misses the boundary by the step's own variance ``w^2 / 12``
    (:func:`stability.fit._common.grid_variance`): where ``s^2`` comes
    out smaller (onsets in one step share a middle, and their residuals
    shrink together), that variance replaces it (with the same Student's
    ``t``: the scatter of the onsets may be larger still, and an interval
    is never narrower than the residuals' estimate makes it); a given
    scatter has it added.
``'profile'``
    Profile likelihood: each parameter is stepped away from its fitted
    value, the others refitted, until the sum of squares has grown by
    ``t^2 s^2``; the interval may be asymmetric and ends at a bound if
    the data give no limit there. ``std`` is the interval's half-width
    divided by ``t``.
``'bootstrap'``
    Parametric bootstrap: synthetic boundaries (the model boundary at the
    fitted values plus Gaussian noise of the residual scatter, under the
    chosen error model; censored where above ``p_max``) are refitted;
    ``std`` is their standard deviation and the interval their 2.5 and
    97.5 percentiles.
``'auto'`` (default)
    The Jacobian where a check shows it can be trusted, the profile
    elsewhere. The check moves each parameter to each end of its
    linearised 95 % interval (along the direction where the other
    parameters follow it) and compares the growth of the sum of squares
    with the predicted ``t^2 s^2``: an end where the ratio lies outside
    :data:`LINEARITY_RANGE` or beyond a bound is profiled (``uncertainty``
    then reads ``'jacobian+profile'``, or ``'profile'`` if every end was).
    Exact data (residuals at round-off) keep the Jacobian.

A parameter the Jacobian cannot see (rank-deficient) gets ``std = inf``
and its search range as interval; the others' uncertainties are then
those with it held.

The growth threshold
--------------------
A chart calls a run judder when it grows at ``min_growth`` or faster, but
a run's growth is read from a few seconds of noisy speed: on the tongue-4
round trip (docs/roundtrip.md) runs whose Floquet exponent lay within
0.25 1/s of the threshold were called either way. With
``threshold_spread`` the fit is repeated from its minimum at
``min_growth`` minus and plus the spread (:func:`threshold_shifts`); each
interval is widened to cover the values those thresholds give. A damping
shifts every exponent alike, so it is the parameter the threshold moves:
on that round trip c12 = 1.10 N m s/rad at 1 1/s moved to 1.41 at 0.75
and to 0.78 at 1.25 1/s, while mu_g and k24 moved by less than a tenth of
their standard uncertainties.
"""

import dataclasses
from dataclasses import dataclass
import math

import numpy as np
from scipy import stats

from infra.errors import JudderError
from infra.units import PA_PER_BAR

from ..tongues import TONGUE_KINDS
from ._common import (_EXACT, _ambiguous_points, _capped, _Evaluator,
                      _least_squares, _nearest, _residuals, _run)
from ._matching import MATCH_ROUNDS
from ._starts import fit_start

__all__ = ["UNCERTAINTY_METHODS", "CONFIDENCE", "DEFAULT_BOOTSTRAP",
           "uncertainty_steps", "intervals", "threshold_shifts"]

#: Evaluations allowed to each bootstrap refit and profile refit.
BOOTSTRAP_EVALUATIONS = 60


#: Ways of computing the uncertainty.
UNCERTAINTY_METHODS = ("auto", "jacobian", "profile", "bootstrap")


#: Synthetic boundaries refitted by the bootstrap.
DEFAULT_BOOTSTRAP = 100


#: Level of the reported intervals.
CONFIDENCE = 0.95


#: Ratio of the actual to the predicted growth of the sum of squares at
#: the ends of the linearised intervals within which the Jacobian is
#: trusted (``uncertainty='auto'``).
LINEARITY_RANGE = (0.7, 1.5)


#: A profile point whose sum of squares lies this many s^2 below the
#: minimum's shows that the minimum is not the best one.
_BETTER = 0.1


#: Profile steps per side of an interval.
_PROFILE_STEPS = 8


#: A profile end is accepted where sqrt(chi^2 growth) is within this share
#: of t (the interval's end to a few per cent of its half-width).
_PROFILE_TOLERANCE = 0.05


def uncertainty_steps(uncertainty, k, n_bootstrap):
    """Progress steps :func:`intervals` takes for ``k`` parameters."""
    return {"jacobian": 1, "bootstrap": n_bootstrap}.get(uncertainty, 2 * k)


@dataclass(frozen=True)
class Intervals:
    """What :func:`intervals` found at the best minimum.

    ``values``, ``std``, ``ci_low``, ``ci_high``, ``low``, ``high`` are
    SI, shape (k,); ``amplitude`` the model boundaries of each kind at
    the minimum (Pa, shape (n, 3), None if they cannot be computed);
    ``residual`` the weighted residuals there; ``scatter`` the onsets'
    scatter, given or estimated from the residuals; ``s2`` the variance
    the intervals use (``scatter^2``, plus the amplitude grid's
    :func:`stability.fit._common.grid_variance` if given, at least that
    if estimated) and ``q`` the quantile of the interval level; ``used`` the
    method (``'jacobian'``, ``'profile'``, ``'jacobian+profile'``,
    ``'bootstrap'``); ``null_names`` the parameters of the Jacobian's null
    space; ``open_sides`` ``[(index, sign)]`` profiles that reached a
    bound without closing; ``alternatives`` ``[(values, growth)]`` other
    minima inside the confidence set; ``same`` which runs reached this
    minimum and ``minima`` where each ended (SI); ``notes`` sentences that
    are problems, ``info`` sentences that are not; ``covariance`` (SI,
    shape (k, k)) the Jacobian's correlations scaled to ``std``, ``inf``
    in the rows and columns of undetermined parameters.
    """

    values: np.ndarray
    std: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    low: np.ndarray
    high: np.ndarray
    amplitude: object
    residual: np.ndarray
    scatter: float
    s2: float
    q: float
    used: str
    null_names: list
    open_sides: list
    boot_failed: int
    alternatives: list
    same: np.ndarray
    minima: np.ndarray
    notes: list
    info: list
    evaluations: int
    covariance: np.ndarray


def intervals(problem, runs, best, given, uncertainty, n_bootstrap, seed,
              workers, progress):
    """Standard uncertainties and 95 % intervals at the best minimum.

    Parameters
    ----------
    problem : _Problem
    runs : list of dict
        Every local fit (:func:`stability.fit._starts.run_starts`).
    best : dict
        The one kept.
    given : ndarray of int, shape (n,)
        Kinds given with the data (-1: matched by nearness).
    uncertainty : {'auto', 'jacobian', 'profile', 'bootstrap'}
    n_bootstrap, seed, workers
        As :func:`stability.fit.fit_boundary` takes them.
    progress : _Progress
        Advanced by :func:`uncertainty_steps` steps.

    Returns
    -------
    Intervals
    """
    k = len(problem.names)
    n_unc = uncertainty_steps(uncertainty, k, n_bootstrap)
    evaluations = 0
    z, columns, cost = best["z"], best["columns"], best["cost"]

    evaluator = _Evaluator(problem)
    amplitude = evaluator.amplitudes(z)
    residual = _residuals(problem, amplitude, columns)
    # the scatter is sampled by the onsets alone: a one-sided residual
    # (a bound the fit presses against) is no sample of it (counted, it
    # made the intervals of 60 noisy boundaries too narrow)
    dof = max(int(np.sum(~problem.censored)) - k, 1)
    notes, info = [], []
    grid = problem.grid_variance
    unit = "%" if problem.relative else " bar"
    scale_unit = 100.0 if problem.relative else 1.0
    if problem.scatter is None:
        s2 = 2 * cost / dof
        scatter = math.sqrt(max(s2, 0.0))
        q = float(stats.t.ppf(0.5 + CONFIDENCE / 2, dof))
        if s2 < grid:
            # the middles of a grid's steps miss the boundary by at least
            # the grid's own variance: residuals below it came out small
            # together (onsets in one step share a middle), not precise;
            # Student's t stays (the onsets' scatter adds to the grid's)
            info.append(
                f"the residuals' scatter "
                f"({scale_unit * math.sqrt(s2):.2g}{unit}) is smaller than "
                "the amplitude grid alone puts in the onsets "
                f"({scale_unit * math.sqrt(grid):.2g}{unit}: a step's "
                "width over the square root of 12): the intervals use "
                "the grid's")
            s2 = grid
    else:
        # the bench's known scatter and the grid's, with normal
        # quantiles, and a check that the residuals are not far larger
        scatter = problem.scatter
        s2 = scatter ** 2 + grid
        q = float(stats.norm.ppf(0.5 + CONFIDENCE / 2))
        ratio = math.sqrt(2 * cost / dof / s2)
        if 2 * cost / s2 > stats.chi2.ppf(0.999, dof):
            notes.append(
                f"the residuals are {ratio:.2g} times the given scatter "
                + ("and the amplitude grid's " if grid else "")
                + "(chi-square test, 0.1 % level): the model does not "
                "follow the measured boundary, or the scatter is larger "
                "than given")
        elif grid:
            info.append(
                "the amplitude grid adds "
                f"{scale_unit * math.sqrt(grid):.2g}{unit} (a step's width "
                "over the square root of 12) to the given scatter in the "
                "intervals")
    exact = math.sqrt(s2) < _EXACT * (1.0 if problem.relative
                                      else problem.p_max / PA_PER_BAR)

    # the Jacobian, and on which side of each interval it can be trusted
    jac = _jacobian(evaluator, z, columns)
    null_names = _null_space_names(jac, problem.names)
    # covariance of the determined parameters, the others held
    cov_z = np.full((k, k), np.inf)
    kept = np.array([n not in null_names for n in problem.names])
    if kept.any():
        part = jac[:, kept]
        cov_z[np.ix_(kept, kept)] = max(s2, 0.0) * np.linalg.inv(part.T
                                                                  @ part)
    std_z = np.sqrt(np.clip(np.diag(cov_z), 0, None))
    trusted = np.repeat(kept[:, None], 2, axis=1)
    ratios = np.ones((k, 2))
    if kept.any() and not exact and s2 > 0 and uncertainty in (
            "auto", "jacobian"):
        ratios = _linearity_ratios(evaluator, z, columns,
                                   np.where(kept[:, None] & kept, cov_z, 0.0),
                                   cost, s2, q, kept)
        trusted = kept[:, None] & (ratios >= LINEARITY_RANGE[0]) & (
            ratios <= LINEARITY_RANGE[1])
        ratios = np.where(kept[:, None], ratios, 1.0)
        if not trusted[kept].all() and uncertainty == "jacobian":
            finite = ratios[np.isfinite(ratios)]
            notes.append(
                "the Jacobian uncertainties are unreliable here (at the ends "
                "of the linearised 95 % intervals the sum of squares grows "
                + (f"{finite.min():.2g} to {finite.max():.2g} times the "
                   "prediction" if len(finite) else "")
                + (" and " if len(finite) and np.isnan(ratios).any() else "")
                + ("some ends lie beyond a bound"
                   if np.isnan(ratios).any() else "")
                + "); use uncertainty='profile' or 'bootstrap'")
    evaluations += evaluator.count

    # a free point about as near to a second kind as to its own: the sum
    # of squares has a kink there (the matching may flip), which the
    # Jacobian cannot see
    ambiguous = _ambiguous_points(problem, amplitude, columns, given, s2)
    if ambiguous:
        info.append(
            "the measured onset lies within the scatter of two kinds of "
            "boundary at " + ", ".join(
                f"{problem.freq_hz[i]:g} Hz "
                f"({problem.measured[i] / PA_PER_BAR:.4g} bar: "
                f"{TONGUE_KINDS[columns[i]].label} "
                f"{amplitude[i, columns[i]] / PA_PER_BAR:.4g}, "
                f"{TONGUE_KINDS[other].label} "
                f"{amplitude[i, other] / PA_PER_BAR:.4g} bar)"
                for i, other in ambiguous)
            + "; matched to the first of each"
            + ("; the intervals are profiled over both matchings"
               if uncertainty in ("auto", "profile") else "")
            + " (give the kinds if they were observed)")
    if ambiguous and not exact:
        trusted[:] = False
    profile = {"jacobian": np.zeros((k, 2), bool),
               "profile": np.ones((k, 2), bool),
               "bootstrap": np.zeros((k, 2), bool)}.get(uncertainty)
    if profile is None:                              # auto
        profile = ~trusted & ~exact
    profile = profile & kept[:, None]   # an undetermined one: its bounds
    used = uncertainty
    if uncertainty == "auto":
        used = ("profile" if profile[kept].all() else "jacobian+profile"
                if profile.any() else "jacobian")
    open_sides = []
    boot_failed = 0
    if uncertainty == "bootstrap":
        ci_low, ci_high, std, boot_failed, count = _bootstrap(
            problem, columns, z, amplitude, s2, n_bootstrap, seed, workers,
            progress)
        evaluations += count
    else:
        ends = np.column_stack([z - q * std_z, z + q * std_z])
        ends = np.clip(ends, problem.low[:, None], problem.high[:, None])
        # first profile step: where the linearised path crossed t^2 s^2
        steps = q * std_z[:, None] / np.sqrt(np.clip(
            np.nan_to_num(ratios, nan=1.0), 0.25, 16.0))
        jobs = [(problem, columns, z, cost, max(s2, 1e-300), q, i, sign,
                 steps[i, side], given) for i in range(k)
                for side, sign in enumerate((-1, 1)) if profile[i, side]]
        progress.step(n_unc - len(jobs))
        if jobs:
            for i, sign, end, closed, count, better in _run(
                    _profile_side, jobs, workers, progress):
                evaluations += count
                ends[i, int(sign > 0)] = end
                if not closed:
                    open_sides.append((i, sign))
                if better:
                    notes.append(
                        f"the profile of {problem.names[i]} found a better "
                        "fit at " + ", ".join(
                            f"{n} = {v:.6g}" for n, v in zip(
                                problem.names, better[0] * problem.scale))
                        + ": the fit did not reach the best minimum; start "
                        "from there")
        ci_low = ends[:, 0] * problem.scale
        ci_high = ends[:, 1] * problem.scale
        std = std_z * problem.scale
        if profile.any():
            # half-width over t: the standard uncertainty the interval
            # corresponds to
            std = np.where(profile.any(axis=1),
                           (ci_high - ci_low) / (2 * q), std)
        std = np.where(kept, std, np.inf)


    values = z * problem.scale
    low, high = problem.low * problem.scale, problem.high * problem.scale


    # agreement of the starts (same minimum: within a tenth of a standard
    # uncertainty, or 1e-4 relative where that is not finite)
    minima = np.array([r["z"] for r in runs]) * problem.scale
    tolerance = np.where(np.isfinite(std) & (std > 0), 0.1 * std,
                         1e-4 * np.maximum(np.abs(values), 1e-300))
    same = np.all(np.abs(minima - values) <= np.maximum(
        tolerance, 1e-6 * np.abs(values)), axis=1)
    # another minimum inside the confidence set (sum of squares within
    # t^2 s^2): the set has two parts; the intervals are widened to
    # cover both (each with its own linearised interval)
    alternatives = []
    for r, m, agrees in zip(runs, minima, same):
        if agrees or not np.isfinite(r["cost"]) or s2 <= 0 or r["failed"]:
            continue
        growth = 2 * (r["cost"] - cost) / s2
        if growth < q * q and np.any((m < ci_low) | (m > ci_high)):
            alternatives.append((m, growth))
            check = _Evaluator(problem)
            jac_alt = _jacobian(check, r["z"], r["columns"])
            evaluations += check.count
            half = np.full(k, 0.0)
            if kept.any():
                part = jac_alt[:, kept]
                try:
                    cov_alt = s2 * np.linalg.inv(part.T @ part)
                    half[kept] = q * np.sqrt(np.clip(np.diag(cov_alt), 0,
                                                     None))
                except np.linalg.LinAlgError:
                    pass
            half = half * problem.scale
            ci_low = np.maximum(np.minimum(ci_low, m - half), low)
            ci_high = np.minimum(np.maximum(ci_high, m + half), high)
            std = np.maximum(std, (ci_high - ci_low) / (2 * q))
    return Intervals(values=values, std=std, ci_low=ci_low, ci_high=ci_high,
                     low=low, high=high, amplitude=amplitude,
                     residual=residual, scatter=scatter, s2=s2, q=q,
                     used=used,
                     null_names=null_names, open_sides=open_sides,
                     boot_failed=boot_failed, alternatives=alternatives,
                     same=same, minima=minima, notes=notes, info=info,
                     evaluations=evaluations,
                     covariance=_covariance(cov_z, std, kept))


#: Model boundaries allowed to each refit at a shifted growth threshold.
THRESHOLD_EVALUATIONS = 60


def threshold_shifts(problem, best, given, progress):
    """How far each fitted value moves when the growth threshold moves
    by ``problem.threshold_spread`` either way (see the module
    docstring).

    Returns
    -------
    shifts : ndarray, shape (k, 2), or None
        SI: the refitted value minus the fitted one at ``min_growth -
        spread`` (at least 0) and at ``min_growth + spread``; None without
        a spread.
    evaluations : int
        Model boundaries computed.
    """
    spread = problem.threshold_spread
    if not spread:
        return None, 0
    out = np.zeros((len(best["z"]), 2))
    evaluations = 0
    for side, sign in enumerate((-1, 1)):
        shifted = dataclasses.replace(
            problem, min_growth=max(problem.min_growth + sign * spread, 0.0))
        run = fit_start((shifted, best["z"], given, 0, best["columns"],
                         THRESHOLD_EVALUATIONS))
        out[:, side] = (run["z"] - best["z"]) * problem.scale
        evaluations += run["evaluations"]
        progress.step()
    return out, evaluations


def _covariance(cov_z, std, kept):
    """Covariance of the values (SI): the Jacobian's correlations with the
    reported standard uncertainties; inf in the rows and columns of the
    undetermined parameters (``judder envelope`` samples a fit's values
    jointly normal with it)."""
    out = np.full(cov_z.shape, np.inf)
    if kept.any():
        part = cov_z[np.ix_(kept, kept)]
        scale = np.sqrt(np.clip(np.diag(part), 1e-300, None))
        out[np.ix_(kept, kept)] = (part / np.outer(scale, scale)
                                   * np.outer(std[kept], std[kept]))
    return out


def _jacobian(evaluator, z, columns):
    """Central-difference Jacobian of the weighted residuals (scaled)."""
    p = evaluator.problem
    k = len(z)
    jac = np.empty((2 * len(p.measured), k))
    for j in range(k):
        h = 1e-4 * max(abs(z[j]), 1e-3)
        up, down = z.copy(), z.copy()
        up[j] = min(z[j] + h, p.high[j])
        down[j] = max(z[j] - h, p.low[j])
        jac[:, j] = (evaluator.residuals(up, columns)
                     - evaluator.residuals(down, columns)) / (up[j] - down[j])
    return jac


def _null_space_names(jac, names):
    """Parameters in the (near) null space of the Jacobian."""
    norms = np.linalg.norm(jac, axis=0)
    if np.any(norms == 0) or not np.all(np.isfinite(jac)):
        return [n for n, c in zip(names, norms) if not c > 0] or list(names)
    _, sv, vt = np.linalg.svd(jac / norms, full_matrices=False)
    small = sv < 1e-8 * sv[0]
    if not small.any():
        return []
    weight = np.abs(vt[small]).max(axis=0)
    return [n for n, w in zip(names, weight) if w > 0.3]


def _linearity_ratios(evaluator, z, columns, cov_z, cost, s2, q, kept):
    """Actual over predicted growth of the sum of squares at the ends of
    each linearised interval of the ``kept`` parameters, shape (k, 2)
    (columns: lower, upper end); NaN where that end lies beyond a bound
    or the parameter is not kept."""
    p = evaluator.problem
    ratios = np.full((len(z), 2), np.nan)
    for i in np.flatnonzero(kept):
        step = q * cov_z[:, i] / math.sqrt(cov_z[i, i])
        for side, sign in enumerate((-1, 1)):
            trial = z + sign * step
            if np.any(trial < p.low) or np.any(trial > p.high):
                continue
            r = evaluator.residuals(trial, columns)
            ratios[i, side] = ((float(np.sum(r ** 2)) - 2 * cost) / s2
                               / q ** 2)
    return ratios


def _profile_side(job):
    """Where the profile of one parameter crosses the threshold on one
    side: ``(index, sign, end, closed, evaluations, better)`` (end
    scaled; ``better`` lists profile points that fit better than the
    minimum, which then was not the best one)."""
    problem, columns, z_best, cost_best, s2, q, i, sign, step, given = job
    evaluator = _Evaluator(problem)
    free = np.ones(len(z_best), bool)
    free[i] = False
    bound = problem.high[i] if sign > 0 else problem.low[i]
    target = q * q
    warm = {z_best[i]: z_best}

    better = []

    matchings = {z_best[i]: columns}

    def chi(v):
        nearest = min(warm, key=lambda w: abs(w - v))
        start, match = warm[nearest].copy(), matchings[nearest]
        start[i] = v
        z = start
        # refit the others; re-match the free points where that moved
        # them (the profile over every matching)
        for _ in range(MATCH_ROUNDS):
            if free.any():
                z, fit = _least_squares(evaluator, z, match, free,
                                        loose=True,
                                        max_nfev=BOOTSTRAP_EVALUATIONS)
            amplitude = evaluator.amplitudes(z)
            r = _residuals(problem, amplitude, match)
            if amplitude is None:
                break
            rematched = _nearest(problem, amplitude, given)
            if np.array_equal(rematched, match):
                break
            trial = _residuals(problem, amplitude, rematched)
            if not np.sum(trial ** 2) < np.sum(r ** 2):
                break
            match, r = rematched, trial
            if not free.any():
                break
        warm[v], matchings[v] = z, match
        growth = (float(np.sum(r ** 2)) - 2 * cost_best) / s2
        if growth < -_BETTER:
            better.append(z)
        return max(growth, 0.0)

    inner, outer = (z_best[i], 0.0), None
    step = step if np.isfinite(step) and step > 0 else \
        0.1 * (problem.high[i] - problem.low[i])
    v = z_best[i] + sign * step
    for _ in range(_PROFILE_STEPS):
        v = min(v, bound) if sign > 0 else max(v, bound)
        d = chi(v)
        if d < target:
            inner = (v, d)
            if v == bound:
                return (i, sign, bound, False, evaluator.count, better)
        else:
            outer = (v, d)
        # sqrt(chi) is near linear in the parameter: interpolate on it
        gi, gv = math.sqrt(inner[1]) - q, math.sqrt(d) - q
        if abs(gv) < _PROFILE_TOLERANCE * q:
            return (i, sign, v, True, evaluator.count, better)
        if outer is None:
            # extrapolate from the best value and the last inner point
            slope = (math.sqrt(inner[1])) / max(abs(inner[0] - z_best[i]),
                                                1e-300)
            reach = q / slope if slope > 0 else 4 * abs(v - z_best[i])
            reach = min(max(reach, 1.3 * abs(v - z_best[i])),
                        4 * abs(v - z_best[i]))
            v = z_best[i] + sign * reach
        else:
            go = math.sqrt(outer[1]) - q
            v = inner[0] + (outer[0] - inner[0]) * (-gi) / (go - gi)
            if abs(outer[0] - inner[0]) < 1e-9 * max(abs(z_best[i]), 1.0):
                return (i, sign, v, True, evaluator.count, better)
    end = v if outer is None else (
        inner[0] + (outer[0] - inner[0]) * (q - math.sqrt(inner[1]))
        / max(math.sqrt(outer[1]) - math.sqrt(inner[1]), 1e-300))
    return (i, sign, end, outer is not None, evaluator.count, better)


def _bootstrap_refit(job):
    """Refit one synthetic boundary from the fitted values."""
    problem, columns, z_best, index = job
    evaluator = _Evaluator(problem)
    z, fit = _least_squares(evaluator, z_best, columns, loose=True,
                            max_nfev=BOOTSTRAP_EVALUATIONS)
    ok = bool(fit.success) and fit.status > 0
    return index, z, ok, evaluator.count


def _bootstrap(problem, columns, z, amplitude, s2, n_bootstrap, seed,
               workers, progress):
    """Parametric bootstrap: refit synthetic boundaries."""
    if n_bootstrap < 2:
        raise JudderError(f"n_bootstrap = {n_bootstrap} is not allowed; "
                          "allowed: >= 2")
    rng = np.random.default_rng(seed)
    n = len(columns)
    if amplitude is None:
        raise JudderError("the model boundary cannot be computed at the "
                          "fitted values: no bootstrap")
    # the boundary the fitted model would show on the bench: the matched
    # kind at points with judder, the lowest kind elsewhere
    capped = _capped(problem, amplitude)
    lowest_column = np.argmin(capped, axis=1)
    boot_columns = np.where(problem.censored, lowest_column, columns)
    base = amplitude[np.arange(n), boot_columns]
    s = math.sqrt(max(s2, 0.0))
    jobs = []
    for b in range(n_bootstrap):
        noise = rng.standard_normal(n)
        noisy = (base * (1 + s * noise) if problem.relative
                 else base + s * PA_PER_BAR * noise)
        noisy = np.where(np.isnan(base) | (noisy > problem.p_max), np.nan,
                         np.maximum(noisy, 1e-6 * problem.p_max))
        if np.isnan(noisy).all():
            noisy = np.where(problem.censored, np.nan, base)
        jobs.append((problem.with_measured(noisy),
                     np.where(np.isnan(noisy), -1, boot_columns), z, b))
    results = _run(_bootstrap_refit, jobs, workers, progress)
    count = sum(r[3] for r in results)
    good = np.array([r[1] for r in results if r[2]])
    failed = n_bootstrap - len(good)
    if len(good) < 2:
        k = len(z)
        return (np.full(k, -np.inf), np.full(k, np.inf), np.full(k, np.inf),
                failed, count)
    values = good * problem.scale
    lo, hi = np.percentile(values, [50 * (1 - CONFIDENCE),
                                    50 * (1 + CONFIDENCE)], axis=0)
    return lo, hi, values.std(axis=0, ddof=1), failed, count

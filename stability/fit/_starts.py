r"""The multi-start driver of a boundary fit (section 4.2).

Several starts
--------------
The given start is fitted first. With ``starts = m > 1`` the parameter
box (the bounds, narrowed to :data:`START_SPREAD` either way of the start)
is sampled by a Latin hypercube (log-spaced for a positive range over a
decade or more), each sample is screened by one model boundary, and local
fits (of at most :data:`EXTRA_START_EVALUATIONS` model boundaries each)
are run from the ``m - 1`` samples that match the measured boundary best,
in parallel (skipped when the given start fits the data to round-off:
nothing can fit better). Where the data give the kind of their onsets,
starts are also placed so that a tongue of that kind lies at them
(:func:`placed_starts`): a start whose tongues lie elsewhere compares
with nothing the parameters move. The best minimum is kept (and
continued if its budget stopped it); the result says how many starts
reached it, and
warns when another minimum fits almost as well (its sum of squares within
``t^2 s^2`` of the best, its values outside the intervals).
"""

import numpy as np
from scipy.stats import qmc

from infra.errors import JudderError

from ..source import build_driveline
from ._common import (_alternative, _Evaluator, _exact, _least_squares,
                      _nearest, _residuals, _run)
from ._matching import MATCH_ROUNDS

__all__ = ["DEFAULT_STARTS", "ALTERNATIVE_ROUNDS", "run_starts",
           "fit_start", "extra_starts"]

#: Local fits run by default: the given start and the best screened
#: samples of the parameter box.
DEFAULT_STARTS = 3


#: Extra starts are sampled within this factor either way of the start
#: (and within the bounds).
START_SPREAD = 3.0


#: Latin-hypercube samples screened per extra start.
SCREEN_PER_START = 30


#: Model boundaries allowed to the fits of the given start.
START_EVALUATIONS = 400


#: Model boundaries allowed to the fits of each extra start.
EXTRA_START_EVALUATIONS = 40


#: Fits from the best minimum with the ambiguous points matched the other
#: way.
ALTERNATIVE_ROUNDS = 2


def run_starts(problem, given, extra, seed, workers, progress):
    """Every local fit: the given start, the extra ones, the ambiguous
    points matched the other way, and the best one continued if its
    budget stopped it.

    Parameters
    ----------
    problem : _Problem
    given : ndarray of int, shape (n,)
        Kind column given for each point (-1: match by nearness).
    extra : int or ndarray, shape (m, k)
        Latin-hypercube starts to screen for, or extra start values (SI).
    seed : int
    workers : int
    progress : _Progress
        Advanced by one step per start (``1 + n_extra +
        ALTERNATIVE_ROUNDS + 1`` steps in all).

    Returns
    -------
    runs : list of dict
        Each local fit (see :func:`fit_start`), with its ``origin``.
    best : dict
        The run kept.
    evaluations : int
        Model boundaries computed.
    """
    n_extra = extra if isinstance(extra, int) else len(extra)
    evaluations = 0
    # the start must be computable: raise its error as is
    start_evaluator = _Evaluator(problem)
    z_start = problem.x0 / problem.scale
    start_evaluator.amplitudes(z_start, strict=True)
    evaluations += start_evaluator.count
    first = fit_start((problem, z_start, given, 0, None, START_EVALUATIONS))
    first["origin"] = "given"
    runs = [first]
    progress.step()
    # an exact fit cannot be bettered: the other starts are skipped
    if n_extra and not _exact(problem, first):
        if isinstance(extra, int):
            candidates = _sample_starts(problem, SCREEN_PER_START * extra,
                                        seed)
            costs, count = _screen(problem, candidates, given)
            evaluations += count
            starts = list(candidates[np.argsort(costs)[:extra]])
        else:
            starts = list(extra / problem.scale)
        runs += _fitted_from(problem, given, starts, len(runs), workers,
                             progress, "sampled")
    placed = [] if _exact(problem, first) else \
        placed_starts(problem, given)
    if placed:
        runs += _fitted_from(problem, given, placed, len(runs), workers, None,
                             "placed")
    progress.until(1 + n_extra)
    best = min(runs, key=lambda r: r["cost"])
    # the ambiguous points matched the other way, from the best minimum
    for _ in range(ALTERNATIVE_ROUNDS):
        if _exact(problem, best):
            break
        evaluator = _Evaluator(problem)
        columns = _alternative(problem, evaluator.amplitudes(best["z"]),
                               best["columns"], given)
        evaluations += evaluator.count
        if columns is None:
            break
        run = fit_start((problem, best["z"], given, len(runs), columns,
                         START_EVALUATIONS))
        run["origin"] = "rematched"
        runs.append(run)
        progress.step()
        if not run["cost"] < best["cost"] * (1 - 1e-9):
            break
        best = run
    if not best["success"] and not best["failed"]:
        # a start stopped by its budget: go on from where it stopped
        run = fit_start((problem, best["z"], given, len(runs),
                         best["columns"], START_EVALUATIONS))
        run["origin"] = "continued"
        runs.append(run)
        progress.step()
        if run["cost"] <= best["cost"]:
            best = run
    progress.until(1 + n_extra + ALTERNATIVE_ROUNDS + 1)
    evaluations += sum(r["evaluations"] for r in runs)
    return runs, best, evaluations


def fit_start(job):
    """One start: fit, re-match the free points, refit if they changed.

    ``job`` is ``(problem, z0, given, index, columns0, max_nfev)``;
    ``columns0`` None matches each free point to the nearest kind at z0;
    ``max_nfev`` bounds the model boundaries computed in all rounds.
    """
    problem, z0, given, index, columns, max_nfev = job
    evaluator = _Evaluator(problem)
    if columns is None:
        amplitude = evaluator.amplitudes(z0)
        columns = _nearest(problem, amplitude if amplitude is not None
                           else np.full((len(given), 3), np.nan), given)
    z = np.array(z0, dtype=float)
    fit = None
    for _ in range(MATCH_ROUNDS):
        left = max_nfev - evaluator.count
        if fit is not None and left < 4 * (len(z) + 1):
            break                       # the budget is spent
        z, fit = _least_squares(evaluator, z, columns, max_nfev=left)
        amplitude = evaluator.amplitudes(z)
        if amplitude is None:
            break
        matched = _nearest(problem, amplitude, given)
        if np.array_equal(matched, columns):
            break
        columns = matched
    cost = 0.5 * float(np.sum(_residuals(problem, amplitude, columns) ** 2))
    return {"index": index, "z0": np.array(z0, dtype=float), "z": z,
            "cost": cost, "columns": columns,
            "success": bool(fit.success) and fit.status > 0,
            "message": fit.message, "evaluations": evaluator.count,
            "failed": amplitude is None}


#: Values of a fitted parameter scanned (log-spaced over its bounds) for
#: the one that puts a tongue's resonance at the measured onsets.
PLACING_SCAN = 41

#: Resonance of a tongue kind (column of
#: :data:`stability.tongues.TONGUE_KINDS`) as a multiple of the
#: natural frequency it grows from: single-period at ``f_i``,
#: double-period at ``2 f_i``; a combination (``f_i +- f_j``) is placed
#: by no one frequency.
_RESONANCE_MULTIPLE = {0: 1.0, 1: 2.0}


def _fitted_from(problem, given, starts, first_index, workers, progress,
                 origin):
    """Local fits from ``starts`` (scaled), numbered from
    ``first_index``, in that order, each marked with its ``origin``
    (``'sampled'``, ``'placed'``)."""
    found = _run(fit_start, [(problem, z, given, first_index + i, None,
                              EXTRA_START_EVALUATIONS)
                             for i, z in enumerate(starts)], workers,
                 progress)
    found = sorted(found, key=lambda r: r["index"])
    for r in found:
        r["origin"] = origin
    return found


def placed_starts(problem, given):
    """Starts that put a tongue of the kind the data saw onto its onsets.

    A start whose tongues lie away from the measured onsets (a preset's
    tongue 4 at 209 Hz, onsets at 187-199 Hz) compares with no boundary
    there: no parameter moves the residual, and the local fits, given or
    sampled, stay where nothing fits (issue 44's held-out round trips).
    For each kind the data give (``given``, columns of
    :data:`stability.tongues.TONGUE_KINDS`; single- and double-period),
    the tongue's resonance belongs at the lowest onset of that kind
    (the tip); for each fitted parameter, the others at the start, the
    value within its bounds at which a damped natural frequency of the
    model (:func:`stability.modal.damped_modes`) times the kind's
    multiple crosses that frequency is a start (linear between the
    :data:`PLACING_SCAN` values scanned). Parameters that move no
    natural frequency give none.

    Returns
    -------
    list of ndarray, shape (k,)
        Scaled starts, none within 1e-3 of the given one.
    """
    from ..modal import damped_modes
    from ._common import evaluated
    given = np.asarray(given)
    z0 = problem.x0 / problem.scale
    targets = []
    for column, multiple in _RESONANCE_MULTIPLE.items():
        onsets = (given == column) & ~problem.censored
        if onsets.any():
            lowest = np.argmin(np.where(onsets, problem.measured, np.inf))
            targets.append(problem.freq_hz[lowest] / multiple)
    out = []
    for j in range(len(z0)):
        low, high = problem.low[j], problem.high[j]
        if not (low > 0 and high > low):
            continue
        values = np.geomspace(low, high, PLACING_SCAN)
        modes = []
        for value in values:
            z = z0.copy()
            z[j] = value
            try:
                frequency, _ = damped_modes(build_driveline(evaluated(
                    problem.params_at(z), problem.added)))
            except (JudderError, ValueError, np.linalg.LinAlgError):
                frequency = np.array([])    # a value the model refuses
            modes.append(frequency)
        count = min(len(m) for m in modes)
        if count == 0:
            continue
        modes = np.array([m[:count] for m in modes])
        for target in targets:
            for mode in range(count):
                gap = modes[:, mode] - target
                cross = np.flatnonzero(np.sign(gap[:-1]) * np.sign(gap[1:])
                                       < 0)
                for i in cross:
                    share = gap[i] / (gap[i] - gap[i + 1])
                    z = z0.copy()
                    z[j] = np.exp(np.log(values[i]) + share * (
                        np.log(values[i + 1]) - np.log(values[i])))
                    if all(np.max(np.abs(z / other - 1)) > 1e-3
                           for other in [z0, *out]):
                        out.append(z)
    return out


def _transform(low, high):
    """Per parameter: sample in log space (True) or linearly."""
    return (low > 0) & (high >= 10 * low)


def _sample_starts(problem, count, seed):
    """``count`` Latin-hypercube points of the scaled box: the bounds,
    narrowed to :data:`START_SPREAD` either way of the start."""
    k = len(problem.names)
    unit = qmc.LatinHypercube(d=k, seed=seed).random(count)
    z0 = problem.x0 / problem.scale
    near = np.sort([z0 / START_SPREAD, z0 * START_SPREAD], axis=0)
    low = np.maximum(problem.low, near[0])
    high = np.minimum(problem.high, near[1])
    log = _transform(low, high)
    out = np.empty_like(unit)
    for j in range(k):
        if log[j]:
            out[:, j] = np.exp(np.log(low[j]) + unit[:, j]
                               * (np.log(high[j]) - np.log(low[j])))
        else:
            out[:, j] = low[j] + unit[:, j] * (high[j] - low[j])
    return out


def _screen(problem, candidates, given):
    """Cost of each candidate with the points matched at it."""
    evaluator = _Evaluator(problem)
    costs = []
    for z in candidates:
        amplitude = evaluator.amplitudes(z)
        if amplitude is None:
            costs.append(np.inf)
            continue
        columns = _nearest(problem, amplitude, given)
        costs.append(0.5 * float(np.sum(
            _residuals(problem, amplitude, columns) ** 2)))
    return np.array(costs), evaluator.count


def extra_starts(starts, names, low, high):
    if isinstance(starts, (int, np.integer)) and not isinstance(starts, bool):
        if starts < 1:
            raise JudderError(f"starts = {starts} is not allowed; allowed: "
                              ">= 1")
        return int(starts) - 1
    points = np.atleast_2d(np.asarray(starts, dtype=float))
    if points.shape[1] != len(names):
        raise JudderError(f"each start needs {len(names)} values "
                          f"({', '.join(names)})")
    if np.any(points < low) or np.any(points > high):
        raise JudderError("every start must lie within the bounds")
    return points

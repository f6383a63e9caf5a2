r"""What a measured boundary can determine (section 4.2): the checks
before and after a boundary fit.

A fit reports a value with an interval only for what the data determine.
Three things make a parameter undeterminable, and each is found before
the optimiser could hide it behind a number:

* **Too few onsets.** The scatter of the measured onsets is estimated
  from the residuals, so ``k`` parameters need ``k`` points with judder
  and :data:`MIN_DOF` more (censored points bound the model but say
  nothing about the scatter): with one degree of freedom the scatter is
  one residual, and on noisy boundaries made from known parameters
  (``benchmarks/fit_coverage.py``) such intervals missed the truth by up
  to 17 standard uncertainties. With the scatter given (a bench's known
  repeatability), ``k`` onsets suffice. Fewer are refused
  (:func:`check_onsets`).
* **No effect on the measured part.** A parameter whose change of
  :data:`EFFECT_STEP` (10 %) moves no measured onset, and no model
  boundary below ``p_max`` at a censored point, by :data:`MIN_EFFECT` of
  the amplitude cannot be fitted from these points (the mean pressure
  when the mean-pressure damping is off, a stiffness that acts only
  outside the measured range). It is held at its start value and named
  (:func:`without_effect`).
* **A flat direction.** Two parameters whose estimates are correlated
  beyond :data:`FLAT_CORRELATION` are fixed by the data only in a
  combination (:func:`flat_pairs`); a parameter whose standard
  uncertainty reaches its value, or whose interval reaches its search
  bound unclosed, is undetermined as well
  (:func:`stability.fit._result.undetermined_names`).
"""

import numpy as np

from infra.errors import JudderError

from ._common import _capped, _Evaluator, _nearest

__all__ = ["MIN_DOF", "EFFECT_STEP", "MIN_EFFECT", "FLAT_CORRELATION",
           "check_onsets", "without_effect", "flat_pairs", "correlation"]

#: Degrees of freedom the scatter of the onsets is estimated with, at
#: least (when it is not given).
MIN_DOF = 2


#: Relative change of a parameter by which its effect is tried.
EFFECT_STEP = 0.1


#: Smallest change of the measured part of the boundary, as a share of
#: the amplitude, that counts as an effect of :data:`EFFECT_STEP`.
MIN_EFFECT = 1e-4


#: Correlation of two fitted values beyond which the data determine only
#: a combination of them.
FLAT_CORRELATION = 0.999


def check_onsets(n_onsets, names, scatter_given=False):
    """Refuse a fit of ``names`` from ``n_onsets`` points with judder.

    Raises
    ------
    JudderError
        With fewer than ``len(names) +`` :data:`MIN_DOF` onsets
        (``len(names)`` with the scatter given), saying why and what to do.

    Examples
    --------
    >>> check_onsets(4, ("mu_g", "k24"))
    >>> check_onsets(2, ("mu_g", "k24"), scatter_given=True)
    >>> check_onsets(1, ("mu_g",))
    Traceback (most recent call last):
    ...
    infra.errors.JudderError: the measured boundary has 1 point with judder: fitting 1 parameter (mu_g) needs at least 3, 2 more than the parameters to estimate the scatter of the onsets; fit fewer parameters (`names`), measure the onset at more frequencies, or give the bench's known scatter (`scatter`)
    """
    k = len(names)
    needed = k if scatter_given else k + MIN_DOF
    if n_onsets >= needed:
        return
    why = ("one per parameter" if scatter_given else
           f"{MIN_DOF} more than the parameters to estimate the scatter of "
           "the onsets")
    raise JudderError(
        f"the measured boundary has {n_onsets} point"
        f"{'' if n_onsets == 1 else 's'} with judder: fitting {k} "
        f"parameter{'s' if k > 1 else ''} ({', '.join(names)}) needs at "
        f"least {needed}, {why}; fit fewer parameters (`names`), measure the "
        "onset at more frequencies"
        + ("" if scatter_given else
           ", or give the bench's known scatter (`scatter`)"))


def without_effect(problem, given):
    """Fitted parameters that do not move the measured part of the
    boundary.

    Each parameter is changed by :data:`EFFECT_STEP` of its start value
    (downwards where the upper bound is nearer) and the model boundaries
    recomputed. The measured part is each onset's boundary of its nearest
    kind at the start (or its given kind) and, at censored points, the
    lowest boundary where it lies below ``p_max`` before or after.

    Parameters
    ----------
    problem : stability.fit._common._Problem
    given : ndarray of int, shape (n,)
        Kind column given for each point (-1: nearest).

    Returns
    -------
    list of (int, float)
        Index of each parameter without effect and its largest relative
        change of the measured part; empty when the start's boundary
        cannot be computed (the fit then says so itself).
    """
    evaluator = _Evaluator(problem)
    z0 = problem.x0 / problem.scale
    base = evaluator.amplitudes(z0)
    if base is None:
        return []
    columns = _nearest(problem, base, given)
    out = []
    for j in range(len(z0)):
        z = z0.copy()
        up = z0[j] * (1 + EFFECT_STEP)
        z[j] = up if up <= problem.high[j] else z0[j] * (1 - EFFECT_STEP)
        moved = evaluator.amplitudes(z)
        if moved is None:
            continue                # the model changed enough to fail
        effect = _measured_change(problem, base, moved, columns)
        if effect < MIN_EFFECT:
            out.append((j, effect))
    return out


def _measured_change(problem, base, moved, columns):
    """Largest change of the measured part, share of the amplitude."""
    rows = np.arange(len(columns))
    onset = ~problem.censored
    column = np.maximum(columns, 0)
    before, after = base[rows, column], moved[rows, column]
    # a boundary that appears or leaves within the search limit moved
    if np.any(onset & (np.isnan(before) != np.isnan(after))):
        return np.inf
    scale = np.where(onset, np.nan_to_num(problem.measured), problem.p_max)
    change = np.where(onset, np.abs(np.nan_to_num(after - before)), 0.0)
    low_before = _capped(problem, base).min(axis=1)
    low_after = _capped(problem, moved).min(axis=1)
    below = problem.censored & (np.minimum(low_before, low_after)
                                < problem.p_max)
    change = np.where(below, np.abs(low_after - low_before), change)
    return float(np.max(change / np.maximum(scale, 1e-300)))


def correlation(covariance):
    """Correlation matrix of a covariance (NaN where a variance is not
    finite and positive).

    Examples
    --------
    >>> float(correlation(np.array([[4.0, 1.0], [1.0, 1.0]]))[0, 1])
    0.5
    """
    covariance = np.asarray(covariance, dtype=float)
    std = np.sqrt(np.diag(covariance))
    good = np.isfinite(std) & (std > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = covariance / np.outer(std, std)
    out[~good, :] = np.nan
    out[:, ~good] = np.nan
    return out


def flat_pairs(covariance, names):
    """Pairs of fitted values the data determine only in combination.

    Returns
    -------
    list of (str, str, float)
        Both names and their correlation, where ``|r| >``
        :data:`FLAT_CORRELATION`.
    """
    r = correlation(covariance)
    return [(names[i], names[j], float(r[i, j]))
            for i in range(len(names)) for j in range(i + 1, len(names))
            if abs(r[i, j]) > FLAT_CORRELATION]

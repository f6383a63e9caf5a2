r"""Matching measured judder onsets to the model's tongues (section 4.2).

Matching points to tongues
--------------------------
The model's lowest boundary is the lowest of three curves, one per kind
(:attr:`stability.tongues.Boundaries.amplitude`). Where two curves cross,
the lowest boundary has a kink, and which curve is lowest can change from
one trial parameter set to the next (with the fitted set of section 4.2,
tongue 6's combination flank against the single-period curve near
125 Hz). A least-squares fit on the lowest boundary is then not smooth,
and the finite-difference Jacobian, hence every uncertainty taken from it,
is wrong. Each measured point with judder is therefore matched to one
kind, and its residual uses the boundary of that kind only:

* a point whose kind is given uses that kind;
* otherwise the point is matched to the kind whose boundary is *nearest*
  to it at the start parameters of each local fit, and that assignment is
  kept fixed during the fit, so the residuals are smooth functions of the
  parameters. After the fit converges, the free points are matched again
  at the fitted values; if a match changed, the fit is repeated from
  there with the new assignment (at most :data:`MATCH_ROUNDS` fits).
* Nearest at the start is not always right: from a poor start, tongue 6's
  combination flank may be nearer to a point of tongue 2 than tongue 2
  itself is, and the fit then settles on a wrong, self-consistent
  matching (with ``p_max`` = 1 bar the fit stopped at c12 = 5.9 instead
  of 10 that way). So, from the best minimum, the *ambiguous* free points
  (a second kind nearly as near as the matched one, see
  :data:`~stability.fit._common.AMBIGUITY`) are matched the other way
  and fitted again (:data:`~stability.fit._starts.ALTERNATIVE_ROUNDS`
  times at most); the better fit is kept.

Each kind's boundary is searched up to
:data:`~stability.fit._common.SEARCH_FACTOR` times ``p_max``, so a model boundary a little above ``p_max`` still gives a
residual that varies with the parameters (a capped one would not).
"""

import math

import numpy as np

from infra.errors import JudderError

from ..kinds import Kind
from ..modal import natural_frequencies
from ..source import build_driveline
from ..tongues import TONGUE_KINDS, resonances

__all__ = ["parse_kind", "parse_kinds", "MATCH_ROUNDS"]


#: Most fits of one start with re-matched kinds.
MATCH_ROUNDS = 3


def parse_kind(entry, tongue_table=()):
    """Column of :attr:`stability.tongues.Boundaries.amplitude` a
    measured point's kind or tongue refers to, or -1 if not given.

    Parameters
    ----------
    entry : None, str, int or stability.kinds.Kind
        None, ``''`` or NaN: not given. A :class:`~stability.kinds.Kind`
        or its label (``'single-period'``, ``'double-period'``,
        ``'combination'``; ``'single'``, ``'double'`` too). An ``int``
        (or a string of digits, or ``'tongue 2'``) is a tongue number as
        in Fig. 14, a string like ``'f2'``, ``'2f1'``, ``'f2-f1'``,
        ``'f1+f2'`` a resonance label; both are looked up in
        ``tongue_table``.
    tongue_table : sequence
        :func:`stability.tongues.resonances` of the driveline.

    Examples
    --------
    >>> parse_kind("combination"), parse_kind(None)
    (2, -1)
    >>> parse_kind(2, resonances([18.9, 102.9]))   # tongue 2: single-period
    0
    """
    if entry is None or (isinstance(entry, float) and math.isnan(entry)):
        return -1
    if isinstance(entry, Kind):
        if entry not in TONGUE_KINDS:
            raise JudderError(f"kind {entry.label!r} is not a kind of tongue")
        return TONGUE_KINDS.index(entry)
    if isinstance(entry, (int, np.integer)) and not isinstance(entry, bool):
        return _tongue_column(int(entry), tongue_table, entry)
    text = str(entry).strip().lower()
    if not text:
        return -1
    for column, kind in enumerate(TONGUE_KINDS):
        if text in (kind.label, kind.label.split("-")[0]):
            return column
    number = text.removeprefix("tongue").strip()
    if number.isdigit():
        return _tongue_column(int(number), tongue_table, entry)
    for _, label, _, kind in tongue_table:
        if text == label.lower():
            return TONGUE_KINDS.index(Kind(kind))
    labels = [r[1] for r in tongue_table]
    raise JudderError(
        f"kind {entry!r} is not known; allowed: single-period, "
        f"double-period, combination, a tongue number 1-"
        f"{len(tongue_table)} or a resonance label "
        f"({', '.join(labels)}), or empty")


def _tongue_column(number, tongue_table, entry):
    for n, _, _, kind in tongue_table:
        if n == number:
            return TONGUE_KINDS.index(Kind(kind))
    raise JudderError(f"tongue {entry!r} does not exist; allowed: 1-"
                      f"{len(tongue_table)} (numbered as in Fig. 14)")


def parse_kinds(kinds, params, n, censored):
    if kinds is None:
        return np.full(n, -1)
    kinds = list(kinds)
    if len(kinds) != n:
        raise JudderError(f"{len(kinds)} kinds given for {n} measured "
                          "points; give one per point (empty: not known)")
    table = resonances(_natural_frequencies(params))
    given = np.array([parse_kind(k, table) for k in kinds])
    return np.where(censored, -1, given)


def _natural_frequencies(params):
    return natural_frequencies(build_driveline(params))



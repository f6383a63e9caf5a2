"""The kinds of instability and how a leading multiplier is sorted into one.

How the leading Floquet multiplier leaves the unit circle names the
instability, as in Fig. 15 of the paper: through +1 the response has the
dither period (single-period), through -1 twice the dither period
(double-period), as a complex pair a period unrelated to the dither
(combination). This module is the one encoding of those kinds (maps store
the integer codes) and the one test of "real multiplier".
"""

from enum import IntEnum

import numpy as np

__all__ = ["Kind", "KINDS", "REAL_TOLERANCE", "is_real", "classify"]


class Kind(IntEnum):
    """Integer code of each verdict, as stored in maps."""

    STABLE = 0
    SINGLE_PERIOD = 1
    DOUBLE_PERIOD = 2
    COMBINATION = 3

    @property
    def label(self):
        """Name used in output: 'single-period', ..."""
        return KINDS[self]


#: Names of the verdicts, indexed by :class:`Kind`.
KINDS = ("stable", "single-period", "double-period", "combination")

#: A multiplier whose imaginary part is below this share of its modulus is
#: real. LAPACK returns exactly zero for the real eigenvalues of a real
#: matrix; the margin covers a complex pair just before it meets the real
#: axis at a tongue boundary.
REAL_TOLERANCE = 1e-9


def is_real(multiplier):
    """True where a multiplier is real (within :data:`REAL_TOLERANCE`).

    Examples
    --------
    >>> is_real([1.5, -1.2 + 1e-12j, 0.5 + 0.5j]).tolist()
    [True, True, False]
    """
    lam = np.asarray(multiplier, dtype=complex)
    return np.abs(lam.imag) <= REAL_TOLERANCE * np.abs(lam)


def classify(multiplier):
    """:class:`Kind` code of each leading multiplier.

    Parameters
    ----------
    multiplier : array_like of complex
        Leading multipliers (any shape).

    Returns
    -------
    ndarray of int8, same shape
        0 stable (modulus <= 1), 1 single-period (real, > 1),
        2 double-period (real, < -1), 3 combination (complex).

    Examples
    --------
    >>> [Kind(k).label for k in classify([1.02, -1.05, 0.16 + 1.02j, 0.99])]
    ['single-period', 'double-period', 'combination', 'stable']
    """
    lam = np.asarray(multiplier, dtype=complex)
    code = np.where(is_real(lam),
                    np.where(lam.real > 0, Kind.SINGLE_PERIOD,
                             Kind.DOUBLE_PERIOD),
                    Kind.COMBINATION)
    return np.where(np.abs(lam) > 1.0, code, Kind.STABLE).astype(np.int8)

r"""Rigid-body reduction of a linear time-periodic system, Eq. (6)-(7).

A driveline whose bodies turn freely as a group has constant angles: each
is a Floquet multiplier at exactly 1 that hides the vibration modes. For
:math:`\dot x = (A_0 + p_f c(\omega t) B) x` those directions are the
common null space of :math:`A_0` and :math:`B`; found from the matrices
(not from a topology), after a diagonal balancing of the states (angles
in rad, speeds in rad/s), and removed by projecting on its orthogonal
complement. The reduced system keeps every other multiplier of the full
one, and its modulation is factored as :math:`U V^T` of rank ``r``.
"""

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from infra.errors import JudderError

__all__ = ["Reduction", "reduce_rigid_body", "low_rank_factors"]

#: Relative size below which a singular value counts as zero (round-off
#: of a compiled model's Jacobian is near 1e-16).
_ZERO = 1e-10


@dataclass(frozen=True)
class Reduction:
    r"""A system without its rigid-body directions.

    .. math:: x = Q_s z, \qquad
              \dot z = (A_{0,r} + p_f c(\omega t)\, U V^T) z

    Attributes
    ----------
    basis : ndarray, shape (n, m)
        ``Q_s``: maps the reduced state ``z`` to ``x`` (balancing included).
    rigid : ndarray, shape (n, n - m)
        Rigid-body directions removed (columns, in ``x``).
    A0 : ndarray, shape (m, m)
        Reduced constant part, 1/s.
    U, V : ndarray, shape (m, r)
        Reduced modulation per Pa, ``U V^T``, 1/(s Pa).
    """

    basis: np.ndarray
    rigid: np.ndarray
    A0: np.ndarray
    U: np.ndarray
    V: np.ndarray

    @property
    def rank(self):
        """Rank ``r`` of the modulation."""
        return self.U.shape[1]


def _balance(A0, B):
    """Diagonal ``D`` with ``D^-1 (|A0| + |B| p) D`` balanced (angles vs
    speeds), as powers of 2 (exact)."""
    magnitude = np.abs(A0) + np.abs(B) * 1e5
    _, (scale, _) = scipy.linalg.matrix_balance(magnitude, permute=False,
                                                separate=True)
    return scale


def _rigid_directions(A0, B):
    """Orthonormal common null space of ``A0`` and ``B`` and its complement."""
    stacked = np.vstack([A0, B * (np.linalg.norm(A0) / max(
        np.linalg.norm(B), np.finfo(float).tiny))])
    _, sigma, vt = np.linalg.svd(stacked)
    rank = int(np.count_nonzero(sigma > _ZERO * sigma[0]))
    return vt[rank:].T, vt[:rank].T


def low_rank_factors(B):
    """``U, V`` with ``U V^T = B`` and as few columns as its rank.

    Parameters
    ----------
    B : ndarray, shape (m, m)

    Returns
    -------
    U, V : ndarray, shape (m, r)
        From the singular values above ``1e-10`` of the largest; ``r`` may
        be 0.
    """
    u, sigma, vt = np.linalg.svd(B)
    rank = int(np.count_nonzero(sigma > _ZERO * max(sigma[0], 1e-300)))
    return u[:, :rank] * sigma[:rank], vt[:rank].T


def reduce_rigid_body(A0, B, name="the driveline"):
    """The :class:`Reduction` of ``A0 + p_f c(w t) B``.

    Parameters
    ----------
    A0, B : ndarray, shape (n, n)
        Constant part (1/s) and modulation per Pa of the full system.
    name : str
        The model, for the message of an error.

    Returns
    -------
    Reduction

    Raises
    ------
    JudderError
        If the modulation vanishes in the reduced coordinates (the dither
        moves the rigid body only).

    Examples
    --------
    A free body and an oscillator with a modulated damping:

    >>> A0 = np.array([[0.0, 0, 0], [0, 0, 1], [0, -100, -1]])
    >>> B = np.diag([0.0, 0, -1])
    >>> r = reduce_rigid_body(A0, B)
    >>> r.A0.shape, r.rank, r.rigid.shape
    ((2, 2), 1, (3, 1))
    """
    D = _balance(A0, B)
    A_bal = A0 / D[:, None] * D[None, :]
    B_bal = B / D[:, None] * D[None, :]
    rigid, complement = _rigid_directions(A_bal, B_bal)
    U, V = low_rank_factors(complement.T @ B_bal @ complement)
    if U.shape[1] == 0:
        raise JudderError(f"{name}: the dither does not enter the "
                          "linearised equations (no clutch damping is "
                          "modulated)")
    return Reduction(basis=D[:, None] * complement, rigid=D[:, None] * rigid,
                     A0=complement.T @ A_bal @ complement, U=U, V=V)

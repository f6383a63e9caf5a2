r"""Tongue boundaries of all kinds by Hill's method, vectorised over frequency.

Eq. (7) is :math:`\dot z = (A_0 + p_f\, c(\omega t)\, U V^T) z`, with the
dither's waveform :math:`c` (:mod:`stability.waveforms`; the paper's
cosine has :math:`c_{\pm1} = 1/2`) and a modulation :math:`U V^T` of rank
``r`` (one for the paper's chains, more for a driveline compiled from
Modelica, :class:`~stability.model.ModulatedSystem`). A Floquet solution
:math:`z = e^{st}\sum_k c_k e^{ik\omega t}` projected on the modulated
channels :math:`w_k = V^T c_k` obeys

.. math:: w_k = p_f\, G(s + ik\omega) \sum_n c_n w_{k-n},
          \qquad G(s) = V^T (sI - A_0)^{-1} U,

so the Floquet exponents at amplitude :math:`p_f` are the zeros of
:math:`F(p_f, s) = \det(I - p_f H(s))`, with the Hill matrix :math:`H(s)`
of blocks :math:`G(s + ik\omega)\, c_{k-l}`. Projecting on :math:`w_k`
removes exactly the infinite eigenvalues that the singular (rank ``r``)
modulation gives the unprojected block problem. A boundary is a
multiplier :math:`e^{sT}` on the unit circle, :math:`s = i\nu`:

* single-period (multiplier +1): :math:`\nu = 0`, and :math:`1/p_f` is a
  real eigenvalue of :math:`H(0)` (:func:`real_boundaries`);
* double-period (-1): :math:`\nu = \omega/2`, the same with half-integer
  harmonics;
* combination (a complex pair :math:`e^{\pm i\nu T}`), for the rank-one
  cosine (:func:`applies`): :math:`\nu` is a second unknown.
  :math:`H` is then :math:`\tfrac12 \operatorname{diag}(G(s + ik\omega))
  S` (``S`` has ones next to the diagonal), and :math:`F(p_f, i\nu) = 0`
  is two real equations in the two real unknowns :math:`(p_f, \nu)`,
  solved by Newton's method (:func:`combination_boundaries`) from seeds at
  the first-order combination resonances :math:`\omega \approx \omega_i
  \pm \omega_j` (where the exponents :math:`i\omega_i` and :math:`\pm
  i\omega_j - i\omega` meet). A lightly damped pole of :math:`G` close to
  the axis makes :math:`F` steep in :math:`\nu`, so Newton runs on
  :math:`F` times a factor that moves every pole of :math:`G` away from
  the axis (same zeros on the axis), and points of narrow tongues where it
  still fails from the seed are found by continuation in frequency from a
  converged neighbour. With the tridiagonal :math:`H` the determinant is
  a three-term recurrence in :math:`p_f^2`.

:math:`G` is a sum of poles, :math:`G(s) = \sum_i R_i / (s - \lambda_i)`
with the eigenvalues :math:`\lambda_i` of :math:`A_0`
(:class:`ModalTransfer`), so all of it is evaluated for every frequency
at once, with no per-frequency propagator. The monodromy
(:mod:`stability.monodromy`) stays the independent check.
"""

from dataclasses import dataclass

import numpy as np

from infra.errors import JudderError

from .model import PeriodicSystem
from .waveforms import Cosine, waveform_of

__all__ = ["ModalTransfer", "applies", "modal_transfer", "real_boundaries",
           "combination_boundaries", "HARMONICS", "COMBINATION_HARMONICS"]

#: Harmonics kept on each side for the single- and double-period
#: boundaries of a waveform without its own ``hill_harmonics``: 10 to 220
#: Hz on the paper's model, the lowest boundary up to 1.5 bar differs from
#: 14 harmonics by 1e-9 relative with 6, 1e-14 with 8; with 7 it is
#: within 6e-13 of the exact boundary of the monodromy up to 1.5 bar, and
#: 6e-11 at 11 bar (200 Hz; tests/test_tongues.py).
HARMONICS = 7
#: Harmonics kept on each side for the combination boundaries (same
#: test: 1e-10 with 4, 1e-14 with 6).
COMBINATION_HARMONICS = 6
#: An eigenvalue ``1/p_f`` of Hill's (complex) matrix is real when its
#: imaginary part is below this share of its modulus. Not a multiplier
#: test: Hill's eigenvalues carry round-off from the complex transfer
#: function, so the margin is wider than
#: :data:`stability.kinds.REAL_TOLERANCE`.
_REAL_TOLERANCE = 1e-8
#: Two boundary amplitudes closer than this share are one (``+p`` and
#: ``-p`` are the same solution shifted by half a period).
_DISTINCT = 1e-9
#: Newton iterations for the combination boundaries, and their tolerance
#: (relative step in p_f and in nu / omega).
_NEWTON_ITERATIONS = 30
_NEWTON_TOLERANCE = 1e-12
#: Amplitude seeds of the continuation, as multiples of the neighbour's
#: root: past a tongue's tip the boundary may double in one frequency step
#: (geared 5-DOF, 0.36 bar at 11.5 Hz, 1.37 at 12.5), and Newton from
#: the neighbour's own amplitude then drifts to p_f = 0.
_CONTINUATION_SCALES = np.array([1.0, 2.0, 4.0])
#: A combination root whose nu lies within this share of omega/2 of 0 or
#: omega/2 is a real multiplier (+1 or -1), not a complex pair.
_REAL_MULTIPLIER_GAP = 1e-4


@dataclass(frozen=True)
class ModalTransfer:
    r"""``G(s) = V^T (sI - A0)^-1 U`` as a sum of poles, and the waveform
    of the dither that modulates it: the system as Hill's method sees it.

    Attributes
    ----------
    poles : ndarray of complex, shape (m,)
        Eigenvalues of ``A0``, 1/s.
    residues : ndarray of complex, shape (m, r, r)
        ``R_i`` with ``G(s) = sum R_i / (s - poles_i)``, in 1/Pa.
    waveform : object
        Shape of the dither (:mod:`stability.waveforms`).
    """

    poles: np.ndarray
    residues: np.ndarray
    waveform: object

    def __call__(self, s):
        """``G`` at the complex points ``s`` (any shape), shape
        ``s.shape + (r, r)``."""
        s = np.asarray(s, dtype=complex)[..., None, None, None]
        return (self.residues / (s - self.poles[:, None, None])).sum(axis=-3)

    def oscillating_poles(self):
        """Poles with positive imaginary part (the vibration modes), by
        increasing frequency."""
        upper = self.poles[self.poles.imag > 0]
        return upper[np.argsort(upper.imag)]


def applies(system):
    """Whether :func:`combination_boundaries` fits ``system``: the
    rank-one cosine modulation of :class:`stability.model.PeriodicSystem`.
    Other systems (a modulation of higher rank, another waveform) have
    their combination boundaries found on the monodromy (solver
    ``'scan'`` of :mod:`stability.tongues`); :func:`real_boundaries` takes
    every system."""
    return (isinstance(system, PeriodicSystem)
            and isinstance(waveform_of(system), Cosine))


def modal_transfer(system):
    """The :class:`ModalTransfer` of a periodic system.

    Parameters
    ----------
    system : stability.model.PeriodicSystem or ModulatedSystem

    Raises
    ------
    JudderError
        If the system without dither turns freely (all external damping
        zero): a pole at 0 puts a multiplier at 1 for every amplitude and
        the boundaries are undefined.
    """
    poles, vectors = np.linalg.eig(system.A0)
    scale = np.abs(poles).max()
    if np.abs(poles).min() <= 1e-12 * scale:
        raise JudderError("the driveline without dither turns freely "
                          "(external damping c_i all zero): the tongue "
                          "boundaries need some c_i > 0")
    left = system.V.T @ vectors                              # (r, m)
    right = np.linalg.solve(vectors, system.U.astype(complex))  # (m, r)
    return ModalTransfer(poles=poles,
                         residues=left.T[:, :, None] * right[:, None, :],
                         waveform=waveform_of(system))


def _harmonics(multiplier, harmonics):
    """Integer (``multiplier = 1``) or half-integer (-1) harmonics, a
    set symmetric about 0 so that ``det(I - p H)`` is real for real p."""
    if multiplier == 1:
        return np.arange(-harmonics, harmonics + 1, dtype=float)
    return np.arange(-harmonics - 1, harmonics + 1) + 0.5


def _hill_matrices(transfer, freq_hz, k):
    """Hill's matrices at ``s = 0``, shape (nf, len(k) r, len(k) r): block
    ``(k, l)`` is ``G(ik omega) c_(k-l)`` with the waveform's harmonics
    ``c_n`` (``c_-n`` their conjugates)."""
    size = len(k)
    gains = transfer(1j * 2 * np.pi * freq_hz[:, None] * k[None, :])
    lag = np.subtract.outer(np.arange(size), np.arange(size))
    c = np.stack([transfer.waveform.coefficients(size - 1, f)
                  for f in freq_hz])                         # (nf, size)
    toeplitz = np.where(lag >= 0, c[:, np.abs(lag)],
                        np.conj(c[:, np.abs(lag)]))
    rank = gains.shape[-1]
    return np.einsum("fkab,fkl->fkalb", gains, toeplitz).reshape(
        len(freq_hz), size * rank, size * rank)


def _half_spectrum(gains):
    """``mu^2`` of ``H = diag(gains) S / 2``, shape (..., ceil(n/2)).

    ``H`` maps even harmonics to odd ones and back, so ``H^2`` restricted
    to the even ones holds every ``mu^2``; it is tridiagonal, with
    ``h_{2r} (h_{2r-1} + h_{2r+1})`` on the diagonal and ``h_{2r}
    h_{2r+-1}`` beside it (``h = gains / 2``).
    """
    half = 0.5 * gains
    n = half.shape[-1]
    m = (n + 1) // 2
    padded = np.zeros(half.shape[:-1] + (2 * m + 1,), dtype=complex)
    padded[..., 1:n + 1] = half               # padded[i + 1] = h_i
    even, before, after = (padded[..., 1:2 * m:2], padded[..., 0:2 * m - 1:2],
                           padded[..., 2:2 * m + 1:2])
    square = np.zeros(half.shape[:-1] + (m, m), dtype=complex)
    rows = np.arange(m)
    square[..., rows, rows] = even * (before + after)
    square[..., rows[:-1], rows[1:]] = (even * after)[..., :-1]
    square[..., rows[1:], rows[:-1]] = (even * before)[..., 1:]
    return np.linalg.eigvals(square)


def _tridiagonal_boundaries(transfer, freq_hz, multiplier, harmonics):
    """:func:`real_boundaries` of the rank-one cosine, shape (nf, h + 1).

    Its Hill matrix ``diag(G(ik omega)) S / 2`` is tridiagonal with a zero
    diagonal: the eigenvalues come in pairs ``+-mu``, one ``mu^2`` per
    pair from :func:`_half_spectrum`, a problem half the size.
    """
    omega = 2 * np.pi * freq_hz
    k = _harmonics(multiplier, harmonics)
    # a harmonic with zero gain decouples exactly: both kinds one size
    gains = np.zeros((len(omega), 2 * harmonics + 2), dtype=complex)
    gains[:, :len(k)] = transfer(1j * omega[:, None] * k[None, :])[..., 0, 0]
    mu2 = _half_spectrum(gains)
    real = ((np.abs(mu2.imag) <= _REAL_TOLERANCE * np.abs(mu2))
            & (mu2.real > 0))
    with np.errstate(divide="ignore"):
        amplitude = np.where(real, 1.0 / np.sqrt(np.abs(mu2.real)), np.nan)
    return np.sort(amplitude, axis=-1)


def real_boundaries(transfer, freq_hz, multiplier=1, harmonics=None):
    """Amplitudes where a multiplier equals +1 or -1, every frequency at once.

    Parameters
    ----------
    transfer : ModalTransfer
    freq_hz : array_like, shape (nf,)
        Dither frequencies, Hz.
    multiplier : {1, -1} or sequence of them
        +1: single-period boundary (integer harmonics); -1: double-period
        (half-integer harmonics). A sequence stacks its results on a new
        first axis.
    harmonics : int, optional
        Harmonics kept on each side; default the waveform's
        ``hill_harmonics`` (a square wave's harmonics decay slowly and
        need more), else :data:`HARMONICS`.

    Notes
    -----
    The eigenvalues of Hill's matrix of every frequency are found in one
    batched call; for the rank-one cosine (the paper's chains) that
    matrix is tridiagonal and the eigenproblem is halved
    (:func:`_tridiagonal_boundaries`).

    Returns
    -------
    ndarray, shape (nf, n) (or (len(multiplier), nf, n))
        Distinct boundary amplitudes (Pa), ascending along each row,
        NaN-padded.

    Examples
    --------
    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> g = modal_transfer(build_driveline(get_preset("paper-4dof"))
    ...                    .periodic_system())
    >>> round(float(real_boundaries(g, [100.0], 1)[0, 0]) / 1e5, 4)
    0.3642
    """
    if harmonics is None:
        harmonics = getattr(transfer.waveform, "hill_harmonics", HARMONICS)
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    kinds = np.atleast_1d(multiplier)
    # the double-period set has one harmonic more: pad with NaN
    width = (2 * harmonics + 2) * transfer.residues.shape[-1]
    amplitude = np.full((len(kinds), len(freq_hz), width), np.nan)
    tridiagonal = (transfer.residues.shape[-1] == 1
                   and isinstance(transfer.waveform, Cosine))
    for row, m in enumerate(kinds):
        if tridiagonal:
            found = _tridiagonal_boundaries(transfer, freq_hz, m, harmonics)
            amplitude[row, :, :found.shape[-1]] = found
            continue
        lam = np.linalg.eigvals(
            _hill_matrices(transfer, freq_hz, _harmonics(m, harmonics)))
        real = ((np.abs(lam.imag) <= _REAL_TOLERANCE * np.abs(lam))
                & (lam.real != 0))
        with np.errstate(divide="ignore"):
            found = np.sort(np.where(real, 1 / np.abs(lam.real), np.nan),
                            axis=-1)
        # +p and -p are the same solution shifted by half a period
        repeated = np.diff(found, axis=-1) <= _DISTINCT * found[..., 1:]
        found[..., 1:][repeated] = np.nan
        amplitude[row, :, :found.shape[-1]] = np.sort(found, axis=-1)
    return amplitude if np.ndim(multiplier) else amplitude[0]


def _determinant(transfer, omega, p, nu, harmonics):
    """``F = det(I - p H(i nu))`` and its derivatives in ``p`` and ``nu``.

    The continuant recurrence ``D_k = D_{k-1} - p^2 g_k g_{k-1} / 4
    D_{k-2}``, carried with its two derivatives (forward mode), times
    ``Phi(nu) = prod_{k,i} (s_k - lambda_i) / (s_k - lambda_i + |lambda_i|)``
    (``s_k = i(nu + k omega)``), which is nonzero on the axis and cancels
    the poles of ``G`` there, so the function Newton sees is smooth near
    a lightly damped mode. All arguments have shape (e,).

    Newton calls this thousands of times in a fit, for a few dozen points
    each, so numpy's cost per call rules: the arrays run over (pole,
    harmonic, point), the points last and contiguous; ``G`` and
    ``dG/ds`` share the terms ``1 / (s_k - lambda_i)``; and the three
    recurrences run as one on the rows ``(D, dD/dp, dD/dnu)``.
    """
    k = np.arange(-harmonics, harmonics + 1)
    s = 1j * (k[:, None] * omega + nu)             # (2h + 1, e)
    poles = transfer.poles[:, None, None]
    near_s = s - poles                             # (m, 2h + 1, e)
    inverse = 1 / near_s
    residues = transfer.residues[:, 0, 0]          # rank one: scalar G
    flat = inverse.reshape(len(residues), -1)
    g = (residues @ flat).reshape(s.shape)
    dg = (-1j * residues @ (flat * flat)).reshape(s.shape)   # dG/dnu
    a = g[1:] * g[:-1]
    da = dg[1:] * g[:-1] + g[1:] * dg[:-1]
    q = 0.25 * p * p
    # per step, the coefficient of D_{k-2} and its derivatives in p, nu
    c = q * a
    dc = np.empty((len(a), 2, len(p)), dtype=complex)
    np.multiply(0.5 * p, a, out=dc[:, 0])
    np.multiply(q, da, out=dc[:, 1])
    prev = np.zeros((3, len(p)), dtype=complex)
    prev[0] = 1.0
    cur = prev.copy()
    for ck, dck in zip(c, dc):
        new = cur - ck * prev
        new[1:] -= dck * prev[0]
        prev, cur = cur, new
    D, Dp, Dn = cur
    # remove the poles of G near the axis (light damping makes F steep):
    # Phi = prod (s - lambda) / (s - mu), mu = lambda moved left by |lambda|
    far_s = s - (poles - np.abs(poles))
    phi = np.multiply.reduce((near_s / far_s).reshape(-1, len(p)))
    dlog = 1j * np.add.reduce((inverse - 1 / far_s).reshape(-1, len(p)))
    return D * phi, Dp * phi, (Dn + D * dlog) * phi


def _combination_seeds(transfer, omega):
    """Starting points ``(nu, p_f)`` of each first-order combination resonance.

    Modes ``i < j`` (damped frequencies ``w_i < w_j``) meet near ``omega =
    w_i + w_j`` at ``nu = (omega + w_i - w_j)/2``, coupling harmonics 0 and
    -1, and near ``omega = w_j - w_i`` at ``nu = (w_i + w_j - omega)/2``,
    coupling harmonics 0 and +1. Kept to those two harmonics, ``F = 1 -
    p^2 g_0 g_{+-1} / 4``, which gives the amplitude seed. Shapes (nf, ns).
    """
    w = transfer.oscillating_poles().imag
    nus, amps = [], []
    for i in range(len(w)):
        for j in range(i + 1, len(w)):
            for nu, side in ((0.5 * (omega + w[i] - w[j]), -1),
                             (0.5 * (w[i] + w[j] - omega), 1)):
                pair = (transfer(1j * nu)
                        * transfer(1j * (nu + side * omega)))[..., 0, 0]
                nus.append(nu)
                # no slip damping (a flat friction characteristic): no
                # tongue, an infinite seed
                with np.errstate(divide="ignore"):
                    amps.append(2.0 / np.sqrt(np.abs(pair)))
    if not nus:
        return np.empty((len(omega), 0)), np.empty((len(omega), 0))
    return np.stack(nus, axis=1), np.stack(amps, axis=1)


def _newton(transfer, om, nu, p, p_max, harmonics):
    """Newton's method on ``F(p_f, i nu) = 0`` from each seed at once.

    All arguments have shape (e,) (``p_max`` and ``harmonics`` scalars);
    returns the final ``(p, nu)`` and whether each converged.
    """
    nu, p = nu.copy(), p.copy()
    done = np.zeros(len(p), dtype=bool)
    # the seeds still iterated: their indices and values
    active, pa, na, oa = np.arange(len(p)), p, nu, om
    with np.errstate(all="ignore"):
        for _ in range(_NEWTON_ITERATIONS):
            F, Fp, Fn = _determinant(transfer, oa, pa, na, harmonics)
            det = Fp.real * Fn.imag - Fn.real * Fp.imag
            dp = -(F.real * Fn.imag - Fn.real * F.imag) / det
            dn = -(Fp.real * F.imag - F.real * Fp.imag) / det
            step_p, step_n, size = np.abs(dp), np.abs(dn), np.abs(pa)
            # damp steps that would leave the physical range
            limit = np.maximum(step_p / (0.5 * size), step_n / (0.1 * oa))
            scale = np.where(limit > 1, 1 / limit, 1.0)
            pa, na = pa + scale * dp, na + scale * dn
            p[active], nu[active] = pa, na
            converged = ((step_p <= _NEWTON_TOLERANCE * size)
                         & (step_n <= _NEWTON_TOLERANCE * oa))
            done[active] = converged
            # drop converged seeds and those that left for good (NaN too)
            keep = ~converged & (np.abs(pa) <= 4 * p_max)
            active, pa, na, oa = active[keep], pa[keep], na[keep], oa[keep]
            if len(active) == 0:
                break
    return p, nu, done


def _accepted(p, nu, om, done, p_max):
    """Converged roots that are a complex pair on the circle within
    ``(0, p_max]``: their amplitude ``|p|``, else inf; and ``nu`` folded
    into ``[0, omega/2]`` (exponents are defined modulo omega and up to
    sign)."""
    folded = np.abs((nu + 0.5 * om) % om - 0.5 * om)
    complex_pair = ((folded > _REAL_MULTIPLIER_GAP * om)
                    & (folded < (0.5 - _REAL_MULTIPLIER_GAP) * om))
    good = done & complex_pair & (np.abs(p) > 0) & (np.abs(p) <= p_max)
    return np.where(good, np.abs(p), np.inf), folded


def _continue(transfer, omega, nu0, p, nu, amplitude, p_max, harmonics):
    """Continuation in frequency of the combination roots, in place.

    On a steep flank of a narrow tongue Newton from the first-order seed
    ``nu0`` may not converge. Each seed column (one resonance) is swept
    along the sorted frequencies: a point without an accepted root is
    seeded from an accepted neighbour of the same column, with the
    neighbour's ``p_f`` (times each of ``_CONTINUATION_SCALES``) and its
    ``nu`` shifted by the change of ``nu0`` between the two frequencies,
    until no new point is accepted. All
    arrays have shape (nf, ns); ``omega`` must be ascending.
    """
    shape = amplitude.shape
    fresh = np.isfinite(amplitude)
    for _ in range(len(omega)):
        # each point without a root, from its lower and its upper neighbour
        missing = ~np.isfinite(amplitude)
        below, above = missing.copy(), missing.copy()
        below[0], below[1:] = False, below[1:] & fresh[:-1]
        above[-1], above[:-1] = False, above[:-1] & fresh[1:]
        (rb, cb), (ra, ca) = np.nonzero(below), np.nonzero(above)
        if len(rb) + len(ra) == 0:
            return
        rows = np.tile(np.concatenate([rb, ra]), len(_CONTINUATION_SCALES))
        cols = np.tile(np.concatenate([cb, ca]), len(_CONTINUATION_SCALES))
        near = np.tile(np.concatenate([rb - 1, ra + 1]),
                       len(_CONTINUATION_SCALES))
        scale = np.repeat(_CONTINUATION_SCALES, len(rb) + len(ra))
        om = omega[rows]
        p_new, nu_new, done = _newton(
            transfer, om, nu[near, cols] + nu0[rows, cols] - nu0[near, cols],
            scale * p[near, cols], p_max, harmonics)
        found, _ = _accepted(p_new, nu_new, om, done, p_max)
        # per point, the lowest accepted root of its trials
        order = np.argsort(found, kind="stable")
        order = order[np.isfinite(found[order])]
        _, first = np.unique(rows[order] * shape[1] + cols[order],
                             return_index=True)
        take = order[first]
        r, c = rows[take], cols[take]
        amplitude[r, c], p[r, c], nu[r, c] = found[take], p_new[take], \
            nu_new[take]
        fresh = np.zeros(shape, dtype=bool)
        fresh[r, c] = True


def combination_boundaries(transfer, freq_hz, p_max,
                           harmonics=COMBINATION_HARMONICS):
    """Lowest amplitude where a complex pair of multipliers reaches the
    unit circle, every frequency at once.

    Newton's method from the first-order seeds, then continuation in
    frequency (:func:`_continue`) for the points where it did not converge.

    Parameters
    ----------
    transfer : ModalTransfer
    freq_hz : ndarray, shape (nf,)
        Dither frequencies, Hz.
    p_max : float
        Largest amplitude searched, Pa.
    harmonics : int
        Harmonics kept on each side.

    Returns
    -------
    amplitude : ndarray, shape (nf,)
        Pa; NaN where no combination boundary lies in ``(0, p_max]``.
    nu : ndarray, shape (nf,)
        Imaginary part of the exponent on the circle (rad/s, in
        ``(0, omega/2)``): the multipliers are ``exp(+-i nu T)``.

    Notes
    -----
    Only the first-order combination resonances of two modes are seeded.
    A complex pair of one mode that leaves the circle close to +1 beside
    its second-order single-period tongue (``omega ~ w_i``) is not: the
    geared 5-DOF at 7 and 7.5 Hz has such points (0.91 and 0.99 bar,
    ``nu / omega ~ 0.03``) that the solver ``'scan'`` finds and this one
    misses.
    """
    omega = 2 * np.pi * np.atleast_1d(np.asarray(freq_hz, dtype=float))
    order = np.argsort(omega, kind="stable")
    omega = omega[order]
    nu0, p0 = _combination_seeds(transfer, omega)            # (nf, ns)
    if nu0.shape[1] == 0:
        nan = np.full(len(omega), np.nan)
        return nan, nan.copy()
    shape = nu0.shape
    om = np.broadcast_to(omega[:, None], shape).ravel()
    p, nu, done = _newton(transfer, om, nu0.ravel(), p0.ravel(), p_max,
                          harmonics)
    amplitude, _ = _accepted(p, nu, om, done, p_max)
    p, nu, amplitude = (a.reshape(shape) for a in (p, nu, amplitude))
    _continue(transfer, omega, nu0, p, nu, amplitude, p_max, harmonics)
    _, folded = _accepted(p, nu, omega[:, None], True, p_max)
    best = np.argmin(amplitude, axis=1)
    rows = np.arange(len(omega))
    lowest = amplitude[rows, best]
    found = np.isfinite(lowest)
    result = np.empty((2, len(omega)))
    result[0, order] = np.where(found, lowest, np.nan)
    result[1, order] = np.where(found, folded[rows, best], np.nan)
    return result[0], result[1]

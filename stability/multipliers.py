"""Floquet multipliers and characteristic exponents, Eq. (10)-(13).

The multipliers are the eigenvalues of the monodromy matrix; the leading
one (largest modulus) decides stability, and how it leaves the unit circle
names the instability (:mod:`stability.kinds`, Fig. 15).
"""

from dataclasses import dataclass

import numpy as np

from infra.errors import JudderError

from .kinds import KINDS, classify
from .monodromy import monodromy

__all__ = ["FloquetResult", "FORMS", "floquet", "system_of",
           "leading_multipliers"]


def leading_multipliers(monodromies):
    """Eigenvalues and leading eigenvalue of a stack of monodromy matrices.

    Parameters
    ----------
    monodromies : ndarray, shape (k, m, m)

    Returns
    -------
    multipliers : ndarray of complex, shape (k, m)
        Sorted by decreasing modulus.
    leading : ndarray of complex, shape (k,)
    """
    if not np.isfinite(monodromies).all():
        raise JudderError("the response grows beyond the floating-point "
                          "range over one dither period (the monodromy "
                          "overflows); allowed: a smaller dither amplitude "
                          "or friction gradient")
    lam = np.linalg.eigvals(monodromies)
    order = np.argsort(-np.abs(lam), axis=-1, kind="stable")
    lam = np.take_along_axis(lam, order, axis=-1)
    return lam, lam[:, 0]


@dataclass(frozen=True)
class FloquetResult:
    """Floquet analysis at one dither frequency and amplitude.

    Attributes
    ----------
    freq_hz : float
        Dither frequency, Hz.
    p_f : float
        Dither amplitude, Pa.
    period : float
        Dither period ``T``, s.
    monodromy : ndarray, shape (m, m)
        Monodromy matrix ``X(T)`` of the system analysed.
    multipliers : ndarray of complex, shape (m,)
        Floquet multipliers, decreasing modulus (Eq. 12).
    exponents : ndarray of complex, shape (m,)
        Characteristic exponents ``log(lambda)/T``, 1/s, principal branch
        (Eq. 12-13: the imaginary part is defined modulo ``2 pi/T``).
    leading : complex
        Multiplier of largest modulus.
    leading_abs : float
    growth_rate : float
        ``ln|leading| / T``, 1/s: the envelope of the response grows as
        ``exp(growth_rate * t)``.
    kind : str
        One of :data:`KINDS`.
    """

    freq_hz: float
    p_f: float
    period: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    exponents: np.ndarray
    leading: complex
    leading_abs: float
    growth_rate: float
    kind: str


#: The forms of a model source's system, by name: ``f(source)`` gives the
#: system whose monodromy is analysed.
FORMS = {"reduced": lambda source: source.periodic_system(),
         "full": lambda source: source.full_system(),
         "augmented": lambda source: source.augmented_system()}


def system_of(driveline, form="reduced"):
    """The system whose monodromy is analysed.

    Parameters
    ----------
    driveline : stability.source.ModelSource
    form : {'reduced', 'full', 'augmented'}
        ``'reduced'``: Eq. (6) without the rigid-body angles (default, see
        :meth:`~stability.model.Driveline.periodic_system`); ``'full'``:
        Eq. (6) as printed, with two multipliers at exactly 1;
        ``'augmented'``: Eq. (9), which adds two more at 1. Each carries
        the source's waveform (:class:`stability.waveforms.Dithered`), so
        all three give that waveform's multipliers.

    Raises
    ------
    JudderError
        An unknown form, or ``'augmented'`` of a source without a forcing
        term (a linearised model).
    """
    if form not in FORMS:
        raise JudderError(f"form = {form!r} is unknown; allowed: "
                          f"{', '.join(FORMS)}")
    return FORMS[form](driveline)


def floquet(driveline, freq_hz, p_f, method=None, form="reduced"):
    """Floquet multipliers of the driveline at one dither setting.

    Parameters
    ----------
    driveline : stability.source.ModelSource
    freq_hz : float
        Dither frequency, Hz.
    p_f : float
        Dither amplitude, Pa.
    method : str, optional
        Monodromy engine, a key of :data:`stability.monodromy.METHODS`. Default
        ``'dyson'`` for the reduced form, ``'solve_ivp'`` otherwise.
    form : {'reduced', 'full', 'augmented'}
        See :func:`system_of`. With ``'full'`` and ``'augmented'`` the
        trivial multipliers at 1 are part of the result.

    Returns
    -------
    FloquetResult

    Examples
    --------
    Inside tongue 2 of Fig. 14, near its tip at f2 = 102.9 Hz:

    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> r = floquet(build_driveline(get_preset("paper-4dof")), 102.9, 0.3e5)
    >>> r.kind, round(r.leading_abs, 4)
    ('single-period', 1.0261)
    """
    if method is None:
        method = "dyson" if form == "reduced" else "solve_ivp"
    if method == "dyson" and form == "augmented":
        raise JudderError("form = 'augmented' needs method = 'solve_ivp'; "
                          "the 'dyson' engine takes A0 + p_f c(w t) U V^T, "
                          "which Eq. (9)'s forcing column p_f D is not")
    system = system_of(driveline, form)
    matrices = monodromy(system, freq_hz, [p_f], method)
    lam, leading = leading_multipliers(matrices)
    period = 1.0 / freq_hz
    lead = complex(leading[0])
    # a mode damped by more than about 37 e-folds in a period (the
    # bench's speed control: 116 over a 15 Hz period) has a multiplier
    # below the eigenvalue solver's rounding, which may come out as 0:
    # its exponent is -inf, not a warning
    with np.errstate(divide="ignore", invalid="ignore"):
        exponents = np.log(lam[0].astype(complex)) / period
    return FloquetResult(
        freq_hz=float(freq_hz), p_f=float(p_f), period=period,
        monodromy=matrices[0], multipliers=lam[0],
        exponents=exponents,
        leading=lead, leading_abs=abs(lead),
        growth_rate=float(np.log(abs(lead)) / period),
        kind=KINDS[int(classify(lead))])

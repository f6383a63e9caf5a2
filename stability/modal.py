"""Natural frequencies and damping factor of the driveline, Eq. (14)-(16)."""

import numpy as np

__all__ = ["natural_frequencies", "closed_form_frequencies",
           "clutch_damper_damping_factor", "damped_modes"]

#: Eigenvalues of ``M^-1 K`` below this share of the largest are rigid-body.
_RIGID_TOLERANCE = 1e-9


def natural_frequencies(driveline):
    """Non-zero undamped natural frequencies of Eq. (14), Hz, ascending.

    Solves the generalised eigenproblem ``K phi = w^2 M phi``; the
    rigid-body zeros (one per freely turning group of bodies) are dropped.

    Parameters
    ----------
    driveline : stability.source.ModelSource
        Anything with ``undamped_omega2()``.

    Returns
    -------
    ndarray, shape (n_springs,)
        Frequencies in Hz.

    Examples
    --------
    >>> from sources import get_preset
    >>> from stability import build_driveline
    >>> natural_frequencies(build_driveline(get_preset("paper-4dof"))).round(3)
    array([ 18.939, 102.884])
    """
    omega2 = driveline.undamped_omega2()
    elastic = omega2[omega2 > _RIGID_TOLERANCE * omega2.max()]
    return np.sqrt(elastic) / (2 * np.pi)


def closed_form_frequencies(params):
    """Natural frequencies from the closed forms, Hz, ascending.

    4-DOF: Eq. (15) of the paper. 3-DOF: the two-inertia oscillator
    ``w^2 = k (J1 + J24) / (J1 J24)``. The formula of each driveline is
    in its registry entry.

    Parameters
    ----------
    params : drivelines.Parameters
    """
    return np.sqrt(params.driveline.closed_form_omega2(params)) / (2 * np.pi)


def clutch_damper_damping_factor(params):
    """Damping factor of the clutch damper, Eq. (16), as a fraction.

    ``zeta_12 = c12 / (2 sqrt(k12 J2))``, the damper taken as an isolated
    one-degree-of-freedom system on the inertia behind it (3-DOF:
    ``c / (2 sqrt(k J24))``). Multiply by 100 for the paper's percent.
    """
    model = params.driveline
    damper = model.clutch_damper
    inertia = model.bodies[model.body_index(damper.body_b)].inertia
    return params[damper.damping] / (2 * np.sqrt(params[damper.stiffness]
                                                 * params[inertia]))


def damped_modes(driveline):
    """Damped frequencies and damping ratios of the system without dither.

    Eigenvalues ``s`` of the constant part ``A0`` of Eq. (6) (``p_f = 0``,
    mean pressure in the damping as the ``mean_pressure_damping`` option
    says), rigid-body angles removed. One entry per oscillatory pair
    (``Im s > 0``), ascending in frequency.

    Returns
    -------
    frequency_hz : ndarray
        Damped natural frequencies ``Im(s) / 2 pi``, Hz.
    damping_ratio : ndarray
        ``-Re(s) / |s|``.
    """
    s = np.linalg.eigvals(driveline.periodic_system().A0)
    s = s[s.imag > 0]
    s = s[np.argsort(s.imag)]
    return s.imag / (2 * np.pi), -s.real / np.abs(s)

"""Natural frequencies and damping factor of the driveline, Eq. (14)-(16)."""

import numpy as np
import scipy.linalg

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
    driveline : stability.model.Driveline

    Returns
    -------
    ndarray, shape (n_springs,)
        Frequencies in Hz.

    Examples
    --------
    >>> from stability import get_preset, build_driveline
    >>> natural_frequencies(build_driveline(get_preset("paper-4dof"))).round(3)
    array([ 18.939, 102.884])
    """
    omega2 = scipy.linalg.eigh(driveline.stiffness_matrix(),
                               driveline.mass_matrix(), eigvals_only=True)
    elastic = omega2[omega2 > _RIGID_TOLERANCE * omega2.max()]
    return np.sqrt(elastic) / (2 * np.pi)


def closed_form_frequencies(params):
    """Natural frequencies from the closed forms, Hz, ascending.

    4-DOF: Eq. (15) of the paper. 3-DOF: the two-inertia oscillator
    ``w^2 = k (J1 + J24) / (J1 J24)``.

    Parameters
    ----------
    params : stability.parameters.Parameters
    """
    p = params
    if p.model == "3dof":
        omega2 = np.array([p["k"] * (p["J1"] + p["J24"])
                           / (p["J1"] * p["J24"])])
    else:
        J1, J2, J4 = p["J1"], p["J2"], p["J4"]
        k12, k24 = p["k12"], p["k24"]
        a = J4 * k12 * (J1 + J2)
        b = J1 * k24 * (J2 + J4)
        delta = (a ** 2 + b ** 2
                 + 2 * J1 * J4 * k12 * k24 * (J4 * (J1 - J2)
                                              - J2 * (J1 + J2)))
        omega2 = (a + b + np.array([-1.0, 1.0]) * np.sqrt(delta)) \
            / (2 * J1 * J2 * J4)
    return np.sqrt(omega2) / (2 * np.pi)


def clutch_damper_damping_factor(params):
    """Damping factor of the clutch damper, Eq. (16), as a fraction.

    ``zeta_12 = c12 / (2 sqrt(k12 J2))``, the damper taken as an isolated
    one-degree-of-freedom system (3-DOF: ``c / (2 sqrt(k J24))``).
    Multiply by 100 for the paper's percent.
    """
    p = params
    if p.model == "3dof":
        return p["c"] / (2 * np.sqrt(p["k"] * p["J24"]))
    return p["c12"] / (2 * np.sqrt(p["k12"] * p["J2"]))


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

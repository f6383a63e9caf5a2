"""Equations of motion of the driveline, Eq. (1)-(9) of the paper.

Every registered driveline (:mod:`drivelines.registry`) is a chain of
inertias joined by spring-dampers (engine side, clutch damper, shafts) and
a wet clutch between the last body of the chain and the gearbox-side body.
:func:`stability.source.build_driveline` turns a
:class:`~drivelines.Parameters` set into a :class:`Driveline`, which
writes the paper's matrices. Its :meth:`Driveline.periodic_system` gives
the form the Floquet layer integrates, with the rigid-body angles
removed; :meth:`Driveline.full_system` and
:meth:`Driveline.augmented_system` give Eq. (6) and Eq. (9).

Coordinates follow Eq. (6): for the 4-DOF model ``theta = [theta1, theta2,
theta4, theta3]``, for the 3-DOF model ``[theta1, theta24, theta3]``.
"""

from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar

import numpy as np
import scipy.linalg

from sources.kinds import SourceKind

from .waveforms import Cosine

__all__ = ["Driveline", "PeriodicSystem", "ModulatedSystem",
           "AugmentedSystem"]


def _shape(system, theta, omega):
    """The dither's shape at the phase ``theta``: cosine unless the system
    carries a waveform."""
    if system.waveform is None:
        return np.cos(theta)
    return system.waveform.values(theta, omega / (2 * np.pi))


@dataclass(frozen=True)
class PeriodicSystem:
    r"""Linear system with a rank-one cosine modulation.

    .. math:: \dot z = \bigl(A_0 + p_f \cos(\omega t)\, u v^T\bigr) z

    This is Eq. (7) for the homogeneous part of Eq. (6), written in the
    non-trivial coordinates ``z`` (see :meth:`Driveline.periodic_system`).

    Attributes
    ----------
    A0 : ndarray, shape (m, m)
        Constant part, 1/s.
    u, v : ndarray, shape (m,)
        Factors of the modulation per unit dither amplitude;
        ``u v^T`` is in 1/(s Pa).
    state_names : tuple of str
        Meaning of each entry of ``z``.
    waveform : object or None
        Shape of the dither (:mod:`stability.waveforms`); None is the
        paper's cosine.
    """

    A0: np.ndarray
    u: np.ndarray
    v: np.ndarray
    state_names: tuple
    waveform: object = None

    @property
    def U(self):
        """``u`` as the one column of a rank-``r`` factor, shape (m, 1)."""
        return self.u[:, None]

    @property
    def V(self):
        """``v`` as the one column of a rank-``r`` factor, shape (m, 1)."""
        return self.v[:, None]

    def matrix(self, t, omega, p_f):
        """System matrix at time ``t`` (s) for angular frequency ``omega``
        (rad/s) and amplitude ``p_f`` (Pa)."""
        return self.A0 + (p_f * _shape(self, omega * t, omega)) \
            * np.outer(self.u, self.v)

    def shifted(self, rate):
        """The system of ``w = exp(-rate t) z``, 1/s.

        Its multipliers are those of this system times ``exp(-rate T)``,
        so its stability boundary is where this system's response grows
        at ``rate``: the boundary of judder that grows at least that fast.

        Examples
        --------
        >>> from sources import get_preset
        >>> from stability import build_driveline
        >>> s = build_driveline(get_preset("paper-4dof")).periodic_system()
        >>> bool(np.allclose(s.shifted(2.0).A0, s.A0 - 2 * np.eye(6)))
        True
        """
        return PeriodicSystem(self.A0 - rate * np.eye(len(self.u)), self.u,
                              self.v, self.state_names, self.waveform)


@dataclass(frozen=True)
class ModulatedSystem:
    r"""Linear system with a cosine modulation of any rank ``r``.

    .. math:: \dot z = \bigl(A_0 + p_f \cos(\omega t)\, U V^T\bigr) z

    The form a driveline compiled from Modelica takes (a second clutch
    with dither, a gear between the bodies the clutch joins, ...); with
    ``r = 1`` it is :class:`PeriodicSystem`. Both engines of
    :mod:`stability.monodromy` and Hill's method take it.

    Attributes
    ----------
    A0 : ndarray, shape (m, m)
        Constant part, 1/s.
    U, V : ndarray, shape (m, r)
        Factors of the modulation per unit dither amplitude, 1/(s Pa).
    state_names : tuple of str
    waveform : object or None
        Shape of the dither (:mod:`stability.waveforms`); None: cosine.
    """

    A0: np.ndarray
    U: np.ndarray
    V: np.ndarray
    state_names: tuple
    waveform: object = None

    def matrix(self, t, omega, p_f):
        """System matrix at time ``t`` (s) for angular frequency ``omega``
        (rad/s) and amplitude ``p_f`` (Pa)."""
        return self.A0 + (p_f * _shape(self, omega * t, omega)) \
            * (self.U @ self.V.T)

    def shifted(self, rate):
        """The system of ``w = exp(-rate t) z``, see
        :meth:`PeriodicSystem.shifted`."""
        return ModulatedSystem(self.A0 - rate * np.eye(len(self.A0)), self.U,
                               self.V, self.state_names, self.waveform)


@dataclass(frozen=True)
class AugmentedSystem:
    r"""The homogeneous augmented form of Eq. (8)-(9).

    .. math:: \frac{d}{dt}\begin{bmatrix} x \\ y \\ \dot y
              \end{bmatrix} = \begin{bmatrix} A(t) & p_f d & 0 \\
              0 & 0 & 1 \\ 0 & -\omega^2 & 0 \end{bmatrix}
              \begin{bmatrix} x \\ y \\ \dot y \end{bmatrix}

    ``A(t)`` is the full system ``state`` (Eq. 6, with its waveform); the
    two added states are the dither's fundamental ``y = cos(w t)`` and its
    derivative, which drive the forcing column ``p_f d``. The form is
    block-triangular, so its multipliers are those of ``state`` plus two
    at 1, whatever the waveform.

    Attributes
    ----------
    state : PeriodicSystem
        The full system, shape (m, m).
    forcing : ndarray, shape (m,)
        ``d``: the dither part of the friction torque per Pa,
        ``[0; -M^-1 e mu0 N_c R_m S]``, 1/(s^2 Pa).
    """

    state: PeriodicSystem
    forcing: np.ndarray

    @property
    def waveform(self):
        """The waveform of ``state``."""
        return self.state.waveform

    def matrix(self, t, omega, p_f):
        """System matrix at time ``t`` (s), shape (m + 2, m + 2)."""
        size = len(self.forcing)
        A = np.zeros((size + 2, size + 2))
        A[:size, :size] = self.state.matrix(t, omega, p_f)
        A[:size, size] = p_f * self.forcing
        A[size, size + 1] = 1.0
        A[size + 1, size] = -omega ** 2
        return A


@dataclass(frozen=True)
class Driveline:
    """A chain of inertias joined by spring-dampers, plus a wet clutch.

    Attributes
    ----------
    names : tuple of str
        Name of each body, in the order of the coordinates.
    inertia : ndarray, shape (n,)
        Moments of inertia, kg m^2.
    springs : tuple of (int, int, float, float)
        ``(i, j, k, c)``: stiffness ``k`` (N m/rad) and damping ``c``
        (N m s/rad) between bodies ``i`` and ``j``.
    external_damping : ndarray, shape (n,)
        Damping to ground of each body, N m s/rad.
    clutch : (int, int)
        Indices of the input (engine-side) and output discs of the clutch.
    clutch_factor : float
        ``N_c R_m S`` of Eq. (3), m^3.
    mu0, mu_g : float
        Friction law of Eq. (5): ``mu = mu0 + mu_g * slip``; mu_g in s/rad.
    p_m : float
        Mean actuation pressure, Pa.
    mean_pressure_damping : float
        Share of ``p_m`` in the slip damping ``mu_g N_c R_m S p(t)``.
    name : str
        The registry model the chain is built from.
    kind : sources.kinds.SourceKind
        ``CHAIN``, for every instance.
    """

    names: tuple
    inertia: np.ndarray
    springs: tuple
    external_damping: np.ndarray
    clutch: tuple
    clutch_factor: float
    mu0: float
    mu_g: float
    p_m: float
    mean_pressure_damping: float
    name: str
    kind: ClassVar[SourceKind] = SourceKind.CHAIN

    @property
    def waveform(self):
        """The paper's cosine (Eq. 4)."""
        return Cosine()

    @property
    def dof(self):
        """Number of degrees of freedom ``n``."""
        return len(self.names)

    def mass_matrix(self):
        """``M`` of Eq. (2), kg m^2, shape (n, n)."""
        return np.diag(self.inertia)

    def undamped_omega2(self):
        """Eigenvalues of ``K phi = w^2 M phi`` (Eq. 14), (rad/s)^2,
        ascending, rigid-body zeros included."""
        return scipy.linalg.eigh(self.stiffness_matrix(), self.mass_matrix(),
                                 eigvals_only=True)

    def incidence(self):
        """Spring deflections ``E theta``, shape (n_springs, n)."""
        E = np.zeros((len(self.springs), self.dof))
        for row, (i, j, _, _) in enumerate(self.springs):
            E[row, i], E[row, j] = 1.0, -1.0
        return E

    def stiffness_matrix(self):
        """``K`` of Eq. (2), N m/rad, shape (n, n)."""
        E = self.incidence()
        return E.T @ np.diag([s[2] for s in self.springs]) @ E

    def clutch_vector(self):
        """``e`` with ``e @ theta_dot`` the slip speed, shape (n,)."""
        e = np.zeros(self.dof)
        e[self.clutch[0]], e[self.clutch[1]] = 1.0, -1.0
        return e

    def structural_damping(self):
        """Constant part of ``C(t)`` without the clutch, N m s/rad."""
        E = self.incidence()
        return (E.T @ np.diag([s[3] for s in self.springs]) @ E
                + np.diag(self.external_damping))

    def slip_damping(self, t, freq_hz, p_f):
        """Clutch term ``mu_g f(t)`` of ``C(t)``, N m s/rad (Eq. 2-4).

        Only ``mean_pressure_damping`` times ``p_m`` enters, see
        :mod:`drivelines.registry`.
        """
        pressure = (self.mean_pressure_damping * self.p_m
                    + p_f * np.cos(2 * np.pi * freq_hz * t))
        return self.mu_g * self.clutch_factor * pressure

    def damping_matrix(self, t, freq_hz, p_f):
        """``C(t)`` of Eq. (2), N m s/rad, shape (n, n)."""
        e = self.clutch_vector()
        return (self.structural_damping()
                + self.slip_damping(t, freq_hz, p_f) * np.outer(e, e))

    def forcing(self, t, freq_hz, p_f, engine_torque=0.0,
                resistant_torque=0.0):
        """``g(t)`` of Eq. (2)-(3), N m, shape (n,).

        The first body is driven by the engine torque (the paper prints
        ``T_c`` there; its nomenclature and Fig. 13 put ``T_e`` on body 1),
        the output body is loaded by ``resistant_torque``.
        """
        pressure = self.p_m + p_f * np.cos(2 * np.pi * freq_hz * t)
        clutch_torque = self.mu0 * self.clutch_factor * pressure
        g = -clutch_torque * self.clutch_vector()
        g[0] += engine_torque
        g[self.clutch[1]] -= resistant_torque
        return g

    def state_matrix(self, t, freq_hz, p_f):
        """Matrix of the state-space form, Eq. (6), shape (2n, 2n).

        ``x = [theta, theta_dot]``.
        """
        n = self.dof
        Minv = np.diag(1.0 / self.inertia)
        return np.block([
            [np.zeros((n, n)), np.eye(n)],
            [-Minv @ self.stiffness_matrix(),
             -Minv @ self.damping_matrix(t, freq_hz, p_f)]])

    def state_forcing(self, t, freq_hz, p_f, **torques):
        """Non-homogeneous term of Eq. (6), ``[0; M^-1 g(t)]``.

        The paper prints a minus sign before ``M^-1 g``; moving ``g`` of
        Eq. (1) to the right-hand side gives a plus, which is also the sign
        of ``D`` in Eq. (9).
        """
        g = self.forcing(t, freq_hz, p_f, **torques)
        return np.concatenate([np.zeros(self.dof), g / self.inertia])

    def full_system(self):
        """Eq. (6) as a :class:`PeriodicSystem` in ``x = [theta,
        theta_dot]``: its ``matrix`` is :meth:`state_matrix`, the
        rank-one modulation ``u v^T`` the slip damping's dither part."""
        n = self.dof
        Minv = np.diag(1.0 / self.inertia)
        e = self.clutch_vector()
        mean_damping = (self.mu_g * self.clutch_factor
                        * self.mean_pressure_damping * self.p_m)
        C0 = self.structural_damping() + mean_damping * np.outer(e, e)
        A0 = np.block([[np.zeros((n, n)), np.eye(n)],
                       [-Minv @ self.stiffness_matrix(), -Minv @ C0]])
        gain = self.mu_g * self.clutch_factor
        u = np.concatenate([np.zeros(n), -gain * e / self.inertia])
        v = np.concatenate([np.zeros(n), e])
        names = (tuple(f"angle {name}" for name in self.names)
                 + tuple(f"speed {name}" for name in self.names))
        return PeriodicSystem(A0, u, v, names)

    def augmented_system(self):
        """Eq. (8)-(9) as an :class:`AugmentedSystem`, shape (2n+2, 2n+2).

        The two added states are ``cos(w t)`` and its derivative; the
        column ``D`` carries the dither part of the friction torque
        ``mu0 N_c R_m S p_f``.
        """
        e = self.clutch_vector()
        forcing = np.concatenate([
            np.zeros(self.dof),
            -self.mu0 * self.clutch_factor * e / self.inertia])
        return AugmentedSystem(self.full_system(), forcing)

    def periodic_system(self):
        """Eq. (6) without its rigid-body angles, as a :class:`PeriodicSystem`
        (computed once per driveline, see :attr:`reduced`)."""
        return self.reduced

    @cached_property
    def reduced(self):
        """Eq. (6) without its rigid-body angles, as a :class:`PeriodicSystem`.

        The chain and the output body each turn freely: the constant angle
        of each leaves two Floquet multipliers at exactly 1 that hide the
        vibration modes. The forces depend on the angles only through the
        spring deflections ``q = E theta``, so ``[q, theta_dot]`` is closed:

        .. math:: \\dot q = E \\dot\\theta, \\quad
                  M \\ddot\\theta = -E^T K_s q - C(t) \\dot\\theta

        and its multipliers are those of Eq. (6) less the two at 1. The
        state is scaled to energy units (``sqrt(k) q``, ``sqrt(J)
        theta_dot``), which makes the undamped part skew-symmetric and keeps
        the integrators well conditioned. The velocities stay: their
        slowly decaying rigid-body modes are genuine multipliers.
        """
        E = self.incidence()
        k = np.array([s[2] for s in self.springs])
        sq_k, sq_J = np.sqrt(k), np.sqrt(self.inertia)
        e = self.clutch_vector()
        mean_damping = (self.mu_g * self.clutch_factor
                        * self.mean_pressure_damping * self.p_m)
        C0 = self.structural_damping() + mean_damping * np.outer(e, e)
        ns = len(k)
        A0 = np.block([
            [np.zeros((ns, ns)), sq_k[:, None] * E / sq_J[None, :]],
            [-(E.T * sq_k[None, :]) / sq_J[:, None],
             -C0 / np.outer(sq_J, sq_J)]])
        gain = self.mu_g * self.clutch_factor
        u = np.concatenate([np.zeros(ns), -gain * e / sq_J])
        v = np.concatenate([np.zeros(ns), e / sq_J])
        names = tuple(f"deflection {self.names[i]}-{self.names[j]}"
                      for i, j, _, _ in self.springs)
        names += tuple(f"speed {name}" for name in self.names)
        return PeriodicSystem(A0, u, v, names)

"""A driveline given by its linear time-periodic system, Eq. (6)-(7).

:class:`LinearDriveline` is what the studies (maps, tongues, Floquet
points, sensitivity) need of a driveline when its matrices come from
somewhere other than the paper's chain of Eq. (2): in practice from a
Modelica class compiled and linearised by :func:`drivelines.modelica.linearize`.
It offers the same calls as :class:`~stability.model.Driveline` that the
studies use: :meth:`periodic_system` (rigid-body directions removed),
:meth:`state_matrix` (the full system) and :meth:`undamped_omega2`.
"""

from dataclasses import dataclass

import numpy as np

from .model import ModulatedSystem, PeriodicSystem

__all__ = ["LinearDriveline"]


@dataclass(frozen=True)
class LinearDriveline:
    r"""A driveline as :math:`\dot x = (A_0 + p_f\cos(\omega t) B) x`.

    Attributes
    ----------
    A0, B : ndarray, shape (n, n)
        Full system: constant part (1/s), modulation per Pa.
    A0_reduced : ndarray, shape (m, m)
        Without the rigid-body directions.
    U, V : ndarray, shape (m, r)
        Reduced modulation ``U V^T``.
    omega2 : ndarray
        Undamped ``w^2`` of the elastic and rigid-body modes, (rad/s)^2.
    state_names : tuple of str
        Names of the full state.
    name : str
        Where the system comes from (a Modelica class name).
    """

    A0: np.ndarray
    B: np.ndarray
    A0_reduced: np.ndarray
    U: np.ndarray
    V: np.ndarray
    omega2: np.ndarray
    state_names: tuple
    name: str

    @classmethod
    def from_model(cls, model):
        """From a :class:`drivelines.modelica.LinearPeriodicModel`."""
        return cls(A0=model.A0, B=model.B, A0_reduced=model.A0_reduced,
                   U=model.U, V=model.V, omega2=model.omega2,
                   state_names=model.state_names, name=model.class_name)

    def periodic_system(self):
        """The reduced system: a :class:`~stability.model.PeriodicSystem`
        when the modulation has rank one (the fast rank-one paths stay),
        else a :class:`~stability.model.ModulatedSystem`."""
        names = tuple(f"z{i}" for i in range(len(self.A0_reduced)))
        if self.U.shape[1] == 1:
            return PeriodicSystem(self.A0_reduced, self.U[:, 0],
                                  self.V[:, 0], names)
        return ModulatedSystem(self.A0_reduced, self.U, self.V, names)

    def state_matrix(self, t, freq_hz, p_f):
        """The full Jacobian at time ``t`` (s), shape (n, n)."""
        return self.A0 + p_f * np.cos(2 * np.pi * freq_hz * t) * self.B

    def undamped_omega2(self):
        """``w^2`` of the undamped modes, (rad/s)^2 (Eq. 14)."""
        return self.omega2

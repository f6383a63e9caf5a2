"""A driveline given by its linear time-periodic system, Eq. (6)-(7).

:class:`LinearDriveline` is the model source
(:class:`stability.source.ModelSource`) of a driveline whose matrices
come from somewhere other than the paper's chain of Eq. (2): a Modelica
class compiled and linearised by :func:`sources.modelica.linearize`,
or an FMU's Jacobian (:func:`sources.fmus.linearize_fmu`). Its
rigid-body reduction (:mod:`stability.reduction`) is computed once, on
first use.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sources.kinds import SourceKind
from infra.errors import JudderError

from .model import ModulatedSystem, PeriodicSystem
from .reduction import low_rank_factors, reduce_rigid_body
from .waveforms import Cosine

__all__ = ["LinearDriveline"]


def _system(A0, U, V, names):
    """:class:`PeriodicSystem` when the modulation has rank one (the fast
    rank-one paths stay), else :class:`ModulatedSystem`."""
    if U.shape[1] == 1:
        return PeriodicSystem(A0, U[:, 0], V[:, 0], names)
    return ModulatedSystem(A0, U, V, names)


@dataclass(frozen=True)
class LinearDriveline:
    r"""A driveline as :math:`\dot x = (A_0 + p_f\cos(\omega t) B) x`.

    Attributes
    ----------
    A0, B : ndarray, shape (n, n)
        Full system: constant part (1/s), modulation per Pa.
    omega2 : ndarray
        Undamped ``w^2`` of the elastic and rigid-body modes, (rad/s)^2.
    state_names : tuple of str
        Names of the full state.
    name : str
        Where the system comes from (a Modelica class name, an FMU's
        model name).
    kind : sources.kinds.SourceKind
        ``MODELICA`` or ``FMU``.
    """

    A0: np.ndarray
    B: np.ndarray
    omega2: np.ndarray
    state_names: tuple
    name: str
    kind: SourceKind

    @classmethod
    def from_model(cls, model):
        """From a :class:`sources.modelica.LinearPeriodicModel`."""
        return cls(A0=model.A0, B=model.B, omega2=model.omega2,
                   state_names=model.state_names, name=model.class_name,
                   kind=model.source_kind)

    @property
    def waveform(self):
        """The paper's cosine (:class:`stability.waveforms.Cosine`)."""
        return Cosine()

    @cached_property
    def reduction(self):
        """The :class:`~stability.reduction.Reduction` of ``A0`` and
        ``B``, computed on first use."""
        return reduce_rigid_body(self.A0, self.B, self.name)

    def periodic_system(self):
        """The reduced system (rigid-body directions removed)."""
        r = self.reduction
        return _system(r.A0, r.U, r.V,
                       tuple(f"z{i}" for i in range(len(r.A0))))

    def full_system(self):
        """The full system, rigid-body directions included."""
        U, V = low_rank_factors(self.B)
        return _system(self.A0, U, V, self.state_names)

    def augmented_system(self):
        """Refused: Eq. (9) needs the clutch's friction torque, which a
        linearised model does not give.

        Raises
        ------
        JudderError
            Always.
        """
        raise JudderError(f"form = 'augmented' of {self.name} is not "
                          "possible: Eq. (9) adds the dither's forcing, "
                          "which a linearised model does not give; "
                          "allowed: form = 'reduced' or 'full'")

    def state_matrix(self, t, freq_hz, p_f):
        """The full Jacobian at time ``t`` (s), shape (n, n)."""
        return self.A0 + p_f * np.cos(2 * np.pi * freq_hz * t) * self.B

    def undamped_omega2(self):
        """``w^2`` of the undamped modes, (rad/s)^2 (Eq. 14)."""
        return self.omega2

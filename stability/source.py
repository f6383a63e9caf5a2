"""What every study needs of a driveline: the model-source interface.

A linear time-periodic model source is anything the studies (Floquet
points, maps, tongues, sensitivity, modal analysis, margins, fitting)
analyse: the paper's chain (:class:`stability.model.Driveline`), a
Modelica class or an FMU linearised to its Jacobian
(:class:`stability.linear.LinearDriveline`), or either dithered by
another waveform (:class:`stability.waveforms.Dithered`). Each declares
:class:`ModelSource`; none is told apart by its type.

:func:`build_driveline` makes the source of a parameter set, by the kind
the set declares (``params.source_kind``, a
:class:`sources.kinds.SourceKind`) through :data:`SOURCES`; the
linearised sources are built once per model.
"""

from functools import lru_cache
from typing import Protocol, runtime_checkable

import numpy as np

from sources.kinds import SourceKind
from drivelines.specs import MEAN_PRESSURE_DAMPING

from .linear import LinearDriveline
from .model import Driveline

__all__ = ["ModelSource", "SOURCES", "build_driveline"]


@runtime_checkable
class ModelSource(Protocol):
    r"""A linear time-periodic model of a driveline, Eq. (6)-(7).

    .. math:: \dot x = \bigl(A_0 + p_f\, c(\omega t)\, U V^T\bigr) x

    with ``c`` the dither's waveform (the paper's cosine, Eq. 4, unless
    dithered by another). The systems carry the waveform, so every
    engine of :mod:`stability.monodromy` and Hill's method
    (:mod:`stability.tongues`) take them as they are.

    Attributes
    ----------
    name : str
        The model (a registry model, a Modelica class, an FMU).
    kind : sources.kinds.SourceKind
        Where the equations come from; says what the time-domain side
        may do with the model (``kind.is_chain``,
        ``kind.runs_in_time_domain``).
    waveform : object
        The dither's shape, a waveform of :mod:`stability.waveforms`.

    Examples
    --------
    >>> from sources import get_preset
    >>> d = build_driveline(get_preset("paper-4dof"))
    >>> isinstance(d, ModelSource), d.kind.is_chain
    (True, True)
    """

    @property
    def name(self):
        """The model's name."""

    @property
    def kind(self):
        """The :class:`~sources.kinds.SourceKind`."""

    @property
    def waveform(self):
        """The dither's waveform."""

    def periodic_system(self):
        """The reduced system, rigid-body directions removed.

        Returns
        -------
        stability.model.PeriodicSystem or stability.model.ModulatedSystem
            Shape (m, m); its multipliers are those of the full system
            less the rigid-body ones at exactly 1.
        """

    def full_system(self):
        """Eq. (6): the full system, rigid-body directions included.

        Returns
        -------
        stability.model.PeriodicSystem or stability.model.ModulatedSystem
            Shape (n, n).
        """

    def augmented_system(self):
        """Eq. (9): the full system plus the dither's forcing states.

        Returns
        -------
        stability.model.AugmentedSystem
            Shape (n + 2, n + 2).

        Raises
        ------
        JudderError
            If the source has no forcing term (a linearised model).
        """

    def undamped_omega2(self):
        """``w^2`` of the undamped modes (Eq. 14), (rad/s)^2, ascending,
        rigid-body zeros included."""


def _chain(params):
    """The :class:`Driveline` of a registry parameter set (Fig. 12, 13)."""
    p, model = params, params.driveline
    index = model.body_index
    return Driveline(
        names=tuple(b.label for b in model.bodies),
        inertia=np.array([p[b.inertia] for b in model.bodies]),
        springs=tuple((index(c.body_a), index(c.body_b), p[c.stiffness],
                       p[c.damping]) for c in model.couplings),
        external_damping=np.array([p[b.external_damping]
                                   for b in model.bodies]),
        clutch=(index(model.clutch[0]), index(model.clutch[1])),
        clutch_factor=p.clutch_factor, mu0=p["mu0"], mu_g=p["mu_g"],
        p_m=p["p_m"], mean_pressure_damping=p[MEAN_PRESSURE_DAMPING],
        name=p.model)


@lru_cache(maxsize=16)
def _linear_of(model):
    """The :class:`LinearDriveline` of one linearised model (by identity),
    so its rigid-body reduction is computed once."""
    return LinearDriveline.from_model(model)


def _linearised(params):
    """The :class:`LinearDriveline` of a Modelica class or an FMU."""
    return _linear_of(params.linear_model())


#: Model sources by the kind a parameter set declares: ``f(params)``
#: gives its :class:`ModelSource`.
SOURCES = {SourceKind.CHAIN: _chain, SourceKind.MODELICA: _linearised,
           SourceKind.FMU: _linearised}


def build_driveline(params):
    """The model source of a parameter set.

    The bodies, couplings and clutch of a registry chain come from
    :class:`drivelines.registry.DrivelineModel` (Fig. 12 for the 3-DOF
    model, Fig. 13 for the 4-DOF model), the values from ``params``; a
    Modelica class or an FMU gives its linearised system
    (``params.linear_model()``), once per model and values.

    Parameters
    ----------
    params : drivelines.Parameters, sources.modelica.ModelicaParameters or sources.fmus.FmuParameters
        Any parameter set that declares its ``source_kind``.

    Returns
    -------
    ModelSource
        A :class:`~stability.model.Driveline` or a
        :class:`~stability.linear.LinearDriveline`.

    Examples
    --------
    >>> from sources import get_preset
    >>> build_driveline(get_preset("paper-4dof")).names
    ('1', '2', '4', '3')
    """
    return SOURCES[params.source_kind](params)

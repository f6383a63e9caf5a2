"""The kind of model a parameter set describes, declared by the set.

Every parameter set (:class:`drivelines.Parameters`,
:class:`sources.modelica.ModelicaParameters`,
:class:`sources.fmus.FmuParameters`) names its
:class:`SourceKind` in ``source_kind``; the layers above ask it what the
model offers instead of testing for a registry entry or a class.
"""

from enum import Enum

__all__ = ["SourceKind"]


class SourceKind(Enum):
    """Where a driveline's equations come from, and what that allows.

    ``CHAIN``
        A driveline of the registry (:mod:`drivelines.registry`): the
        paper's chain of Eq. (2), whose bodies and couplings have roles
        (the clutch damper, the bench's engagement model, closed forms).
    ``MODELICA``
        A Modelica class, linearised from its equations; its FMU can be
        built and run in the time domain.
    ``FMU``
        A third-party FMU, linearised from its Jacobian only; it has no
        time-domain run.

    Examples
    --------
    >>> SourceKind.CHAIN.is_chain, SourceKind.FMU.runs_in_time_domain
    (True, False)
    """

    CHAIN = "chain"
    MODELICA = "modelica"
    FMU = "fmu"

    @property
    def is_chain(self):
        """A registry chain: its parameters have roles (Eq. 16's damper,
        the bench, Fig. 19's dampings) and its entry names its FMU."""
        return self is SourceKind.CHAIN

    @property
    def runs_in_time_domain(self):
        """An FMU of the model can be built and run (:mod:`pysim`)."""
        return self is not SourceKind.FMU

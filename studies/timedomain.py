"""The time-domain model of a parameter set: the FMU that runs it and
the values a run sets.

``crosscheck`` and ``simulate`` run a driveline in the time domain. A
registry driveline runs through the FMU of its Modelica class
(:attr:`drivelines.DrivelineModel.modelica_class`), its parameters set by
the same names; a Modelica class (``--modelica``) through the FMU the
project's compiler builds of it (:func:`fmu.store.ensure_fmu`), every
tunable value set as an FMU parameter. An FMU given by ``--fmu`` is only
linearised through its directional derivatives (docs/fmu-path.md): there
is no time-domain model of it here, and these functions refuse it.
"""

from infra.errors import JudderError
from fmu.store import ensure_fmu

__all__ = ["class_fmu", "fmu_refusal", "run_values"]


def fmu_refusal(command, path):
    """The error for ``command --fmu path``: a command that runs the
    driveline in the time domain has no model of a third-party FMU."""
    return JudderError(
        f"{command} of `path` {path} is not possible: {command} runs the "
        "driveline in the time domain, and an FMU is read only for its "
        "Jacobian at its start values; allowed: `class_name` CLASS (a "
        "Modelica class: its FMU is built and run) or a preset")


def class_fmu(params, command):
    """The FMU that runs ``params`` in the time domain (built if needed).

    Parameters
    ----------
    params : drivelines.Parameters, ModelicaParameters or FmuParameters
    command : str
        The command that runs it, for the message of a refusal.

    Raises
    ------
    JudderError
        For an FMU of ``--fmu``, or a Modelica class whose dither is not
        in the parameters ``p_f`` and ``f_dither`` (which a run sets).
    """
    if params.source_kind.is_chain:
        return ensure_fmu(params.driveline.modelica_class)
    if not params.source_kind.runs_in_time_domain:
        raise fmu_refusal(command, params.path)
    if (params.amplitude, params.frequency) != ("p_f", "f_dither"):
        raise JudderError(f"{command} runs the FMU with the dither in p_f "
                          "and f_dither; allowed: `amplitude` p_f "
                          "`frequency` f_dither")
    return ensure_fmu(params.class_name, library=params.library)


def run_values(params):
    """``(params, extra)`` for :func:`pysim.simulation.runs.run_fmu` of the FMU of
    :func:`class_fmu`: a registry set maps onto the FMU parameters of the
    same names; a Modelica class's values are all given as ``extra``,
    without the dither (each run sets its own)."""
    if params.source_kind.is_chain:
        return params, {}
    return None, {name: value for name, value in params.values.items()
                  if name not in (params.amplitude, params.frequency)}

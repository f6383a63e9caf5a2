"""Time-domain runs of the FMUs with fmpy.

A run maps a :class:`~drivelines.Parameters` set (the names are the same
in the FMUs, see :mod:`drivelines.registry`) plus the dither setting onto
the FMU's start values, simulates it with fmpy (through
:func:`fmu.store.simulate`, which unpacks the FMU and reads its model
description once) and returns the time histories in SI units.
"""

from dataclasses import dataclass

import numpy as np

from drivelines.registry import SIGNALS
from fmu.store import model_description, simulate
from infra.errors import JudderError
from infra.units import PA_PER_BAR

__all__ = ["Run", "run_fmu"]


@dataclass(frozen=True)
class Run:
    """Time histories of one FMU run.

    Attributes
    ----------
    time : ndarray, shape (n,)
        s.
    signals : dict of str -> ndarray, shape (n,)
        Outputs in SI units (:data:`drivelines.registry.SIGNALS`) and any
        extra variables.
    start_values : dict
        FMU parameters set for the run (SI).
    freq_hz, p_f : float
        Dither frequency (Hz) and amplitude (Pa).
    """

    time: np.ndarray
    signals: dict
    start_values: dict
    freq_hz: float
    p_f: float

    def __getitem__(self, name):
        return self.signals[name]


def run_fmu(fmu_path, freq_hz, p_f, params=None, extra=None, duration=None,
            output_interval=None, fmi_type="CoSimulation", variables=()):
    """Simulate an FMU at one dither setting.

    Parameters
    ----------
    fmu_path : path
    freq_hz, p_f : float
        Dither frequency (Hz) and amplitude (Pa).
    params : drivelines.Parameters, optional
        Values for the FMU parameters of the same names; every one must
        be a parameter of the FMU.
    extra : dict, optional
        Further FMU parameters by name (e.g. ``w_motor``, ``t_engage``).
    duration : float, optional
        s (default: the FMU's StopTime).
    output_interval : float, optional
        s (default: the FMU's Interval).
    fmi_type : {'CoSimulation', 'ModelExchange'}
    variables : sequence of str
        Variables recorded besides :data:`drivelines.registry.SIGNALS`.

    Raises
    ------
    JudderError
        On a parameter (of ``params`` or ``extra``) or a recorded variable
        the FMU does not have, or a failed run.
    """
    description = model_description(fmu_path)
    tunable = {v.name for v in description.modelVariables
               if v.causality == "parameter"}
    values = {**(params.as_dict() if params is not None else {}),
              **(extra or {})}
    start = {"f_dither": float(freq_hz), "p_f": float(p_f)}
    for name, value in values.items():
        if name not in tunable:
            raise JudderError(f"{name!r} is not a parameter of "
                              f"{description.modelName}; allowed: "
                              f"{', '.join(sorted(tunable))}")
        start[name] = float(value)
    experiment = description.defaultExperiment
    outputs = list(SIGNALS) + [v for v in variables if v not in SIGNALS]
    known = {v.name for v in description.modelVariables}
    missing = [name for name in outputs if name not in known]
    if missing:
        raise JudderError(f"{description.modelName} has no variable "
                          f"{missing[0]!r}; allowed: a model with the "
                          f"outputs {', '.join(SIGNALS)} (a run records "
                          "them)")
    try:
        result = simulate(
            fmu_path, fmi_type=fmi_type,
            start_values=start,
            stop_time=duration or experiment.stopTime,
            output_interval=output_interval or experiment.stepSize,
            output=outputs)
    except Exception as exc:   # fmpy raises plain Exceptions on FMU errors
        raise JudderError(f"the FMU run failed at f = {freq_hz:g} Hz, "
                          f"p_f = {p_f / PA_PER_BAR:g} bar: {exc}") from None
    return Run(time=np.asarray(result["time"]),
               signals={n: np.asarray(result[n]) for n in outputs},
               start_values=start, freq_hz=float(freq_hz), p_f=float(p_f))
